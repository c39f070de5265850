/**
 * @file   vtkSweptTransmittance.h
 * @brief  The GPU estimator's piecewise shadow rays of a directional light
 *         (Shaders/mmvPiecewiseShadowFS.glsl), in float on the CPU, for
 *         software rasterizers.
 *
 * A rasterizer shades every voxel of a chunk as a fragment that locates and
 * weights each sample of its ray anew. Toward a directional light the rays
 * are parallel: along a row of voxels (an axis other than the sweep's) the
 * samples of step n lie at the same offset from each voxel, so the row
 * shares the weights across it and along the sweep, and along it as well
 * where the light grid's points fall on irradiance points; each step is
 * then a fixed stencil over the row, vectorised, and the rows run in
 * parallel. Voxels whose rays leave the grid sideways take the shader's
 * arithmetic point by point. On llvmpipe the light kit's key light takes
 * about a quarter of its fragment passes' time (docs/performance.md,
 * "Shadow rays on the CPU").
 *
 * The arithmetic is the shader's step for step (start, exit, plane, march,
 * rest, the bilinear read of the previous chunk's slice, early
 * termination); a shared weight is the step offset's, where the pass rounds
 * the voxel's position plus it, a difference of a float's rounding of the
 * grid's size. The mirror test holds the two within one 16-bit step.
 */
#ifndef vtkSweptTransmittance_h
#define vtkSweptTransmittance_h

#include "vtkIrradianceRegion.h" // IndexBox
#include "vtkMultiMaterialVolumeFiltersModule.h"
#include "vtkShadowSweep.h" // ShadowSweep
#include "vtkType.h"        // vtkIdType

#include <glm/glm.hpp>

#include <vector>

namespace mmv
{

/// What the sweep reads: the pass's textures and uniforms, as CPU arrays.
struct SweptTransmittanceInputs
{
  const float* Scalars = nullptr;     // normalised pre-filtered values, irradiance grid
  int Dimensions[3] = { 0, 0, 0 };    // the irradiance grid's points
  const float* ShadowTable = nullptr; // I_sigma(t1 along x, t2 along y), TableSize^2
  int TableSize = 0;
  float StepLength = 1.0f;               // world units
  glm::mat3 WorldToIndex{ 1.0f };        // irradiance index per world unit
  int TargetDimensions[3] = { 0, 0, 0 }; // the light grid's points
  glm::vec3 TargetToIndex{ 1.0f };       // light grid point -> irradiance index
  bool Strided = false;                  // off: the light grid is the irradiance grid
  const float* Classes = nullptr;        // irradiance grid, < 0 empty (unstrided)
  const unsigned char* Needed = nullptr; // light grid, 0 where no voxel needs it (strided)
  bool SkipEmpty = true;                 // off: every voxel is computed (computeEmptyVoxels)
};

/**
 * The piecewise shadow rays of the directional light toward `toLight`
 * (world, unit) in `sweep` (a directional light's: not a pyramid), into
 * channel `channel` of `target` (`channels` floats per light grid point, x
 * fastest): every point of each chunk's box (`boxes`, mmv::PlanSweepBoxes
 * of the sweep), chunk after chunk as the pass draws them; empty points off
 * the slice the next chunk reads get 0, as in the pass. Points outside the
 * boxes keep their values. Returns the points computed.
 */
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT vtkIdType SweepTransmittanceOnCPU(
  const SweptTransmittanceInputs& inputs, const glm::vec3& toLight, const ShadowSweep& sweep,
  const std::vector<IndexBox>& boxes, float* target, int channels, int channel);

} // namespace mmv

#endif
