/**
 * @file   vtkBlockDiffusionSeries.h
 * @brief  The diffusion's exponential series on the diffusion grid's block
 *         texels, on the CPU, as the GPU's passes compute it.
 *
 * On a CPU rasterizer (llvmpipe) each of the series' passes is a fragment
 * draw over the diffusion grid with eight texel fetches and a framebuffer
 * write per block: a time step of `smoke` on a 237 x 237 x 119 grid spent
 * 1.4-1.6 s in its 13 passes, and 0.2 s more in the pass that takes the
 * change. The same arithmetic in plain loops over the block texels
 * (mmv::DiffusionBlockTexels) costs a fraction of that, so the estimator
 * reads the restricted irradiance back, runs the series here and uploads the
 * change for the prolongation (vtkIrradianceEstimator::DiffusionPlace).
 *
 * The operations mirror Shaders/mmvDiffusionFS.glsl (MMV_EXPONENTIAL, then
 * MMV_CHANGE) in float and in the same order, so the two agree to rounding
 * (IrradianceEstimator.CPUDiffusionMatchesTheGPU):
 *   out = alpha u0 + beta (b + invRate (sum_f c_f b_f - total b) / C)
 *         + gamma b_previous
 * over the blocks of `box` that exchange light (total = sum_f c_f > 0), from
 * k = n down to 0 with alpha = c_k, beta = 0 for k = n, 1 for k = 0, else 2,
 * gamma = -1 for k < n - 1, else 0; then change = result - u0 there, 0
 * elsewhere.
 */
#ifndef vtkBlockDiffusionSeries_h
#define vtkBlockDiffusionSeries_h

#include "vtkMultiMaterialVolumeFiltersModule.h" // export macro

#include <array>   // scratch
#include <cstddef> // size_t
#include <vector>  // coefficients, scratch

namespace mmv
{

class VTKMULTIMATERIALVOLUMEFILTERS_EXPORT BlockDiffusionSeries
{
public:
  /**
   * The change the series `coefficients` (ExponentialChebyshevCoefficients,
   * rate bound 1 / invRate) makes to `u0`, `channels` (1, 2 or 4) floats per
   * block of a grid of `dims`, x fastest, into `change` (same layout, every
   * block written). `facesXY` and `facesZ` are DiffusionBlockTexels' texels;
   * `box` (inclusive block index bounds, x0 x1 y0 y1 z0 z1) the blocks the
   * series computes. False (nothing written) for other channel counts.
   */
  bool Change(const int dims[3], int channels, const float* facesXY, const float* facesZ,
    const int box[6], const std::vector<double>& coefficients, double invRate, const float* u0,
    float* change);

  /// Frees the iterates kept between calls.
  void ReleaseScratch();
  /// Bytes of the iterates kept between calls.
  size_t GetBytes() const
  {
    return 4 * (this->Iterates[0].size() + this->Iterates[1].size() + this->Iterates[2].size());
  }

private:
  std::array<std::vector<float>, 3> Iterates;
};

} // namespace mmv

#endif
