/**
 * @file   vtkIrradianceResolutionError.h
 * @brief  How far irradiance computed on a coarser grid is from the same
 *         irradiance on a finer grid, where the image can show it.
 *
 * The ray caster reads the irradiance trilinearly at every sample, so the
 * coarse grid's error at a fine voxel is its trilinear value there minus
 * the fine grid's. Only voxels that hold material contribute to the image:
 * each fine voxel's squared error is weighted by its opacity. The result is
 * a PSNR with a unit peak (the irradiance of a unit light through empty
 * space), the measure vtkIrradianceResolutionProbe bounds to choose the
 * coarsest grid a volume needs.
 */
#ifndef vtkIrradianceResolutionError_h
#define vtkIrradianceResolutionError_h

#include "vtkIrradianceGrid.h"                   // IrradianceGrid
#include "vtkMultiMaterialVolumeFiltersModule.h" // export macro

#include <vector>

namespace mmv
{

/**
 * Opacity-weighted PSNR (dB, peak 1) of `coarse` against `fine`, both one
 * vector of values per light on their grids (x fastest), the same number of
 * lights, grids spanning the same physical bounds. `weights` holds one
 * non-negative weight per fine voxel (NaN or negative: 0). +inf when the
 * fields agree or no voxel has weight; NaN when the inputs do not fit
 * together (sizes).
 */
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT double VisibleIrradiancePSNR(const IrradianceGrid& fine,
  const std::vector<std::vector<float>>& fineValues, const std::vector<float>& weights,
  const IrradianceGrid& coarse, const std::vector<std::vector<float>>& coarseValues);

/// Per-voxel weights for VisibleIrradiancePSNR: the opacity table (`n`
/// entries over the normalised range [0, 1]) at each normalised pre-filtered
/// value, linearly interpolated; NaN values weigh 0.
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT std::vector<float> OpacityWeights(
  const std::vector<float>& normalizedValues, const std::vector<float>& opacityTable);

} // namespace mmv

#endif
