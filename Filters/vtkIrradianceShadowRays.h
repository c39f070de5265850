/**
 * @file   vtkIrradianceShadowRays.h
 * @brief  The CPU shadow rays of vtkIrradianceVolumeFilter: full rays per
 *         voxel, piecewise rays swept along a directional light or a point
 *         light outside the grid (vtkShadowSweep.h), and the per-channel
 *         tint of selective
 *         absorption. The GLSL twins: Shaders/mmvShadowRay.glsl and
 *         mmvPiecewiseShadowFS.glsl.
 */
#ifndef vtkIrradianceShadowRays_h
#define vtkIrradianceShadowRays_h

#include "vtkIrradianceGrid.h"          // IrradianceGrid
#include "vtkMultiMaterialCutaway.h"    // IndexCutaway
#include "vtkMultiMaterialLightModel.h" // LightSource
#include "vtkShadowSweep.h"             // ShadowSweep
#include "vtkType.h"                    // vtkIdType

#include <vector>

class vtkAlgorithm;
class vtkPreIntegrationTable;

namespace mmv
{
namespace shadowrays
{
/// Everything the shadow rays read; shared by all threads, read-only.
struct RayContext
{
  const mmv::IrradianceGrid* Irradiance;
  const float* Prefiltered;
  const vtkPreIntegrationTable* Table;
  double Step;
  glm::dmat3 PhysicalToIndex; // of *Irradiance, inverted once
  mmv::IndexCutaway Cut;      // removed by cropping and clipping: empty
};

/**
 * The tint of one light at every voxel of the tint grid (full shadow rays
 * through the irradiance grid's pre-filtered values), interpolated
 * trilinearly to the irradiance grid: 3 components per irradiance voxel,
 * what the ray cast reads from its tint texture. Adds the rays cast to `rays`.
 */
void ComputeTint(
  const RayContext& ctx, const mmv::LightSource& light, int divisor, float* out, vtkIdType& rays);

/**
 * Piecewise shadow rays of `light` in `sweep` (one of mmv::PlanLightSweeps,
 * vtkShadowSweep.h) into `transmittance`, one value per voxel of the grid,
 * without a point light's falloff: the non-empty voxels of the sweep (of a
 * pyramid sweep, of its pyramid; of a spot light, those inside its cone),
 * and every such voxel of the slices a later chunk reads; the others keep
 * their values. Progress (from `progress` over `progressSpan`) and
 * AbortExecute of `self` are handled between chunks; returns false when
 * aborted. Adds the rays cast to `rays`.
 */
bool SweepPiecewiseShadowRays(vtkAlgorithm* self, const RayContext& ctx,
  const mmv::LightSource& light, const mmv::ShadowSweep& sweep,
  const std::vector<unsigned char>& nonEmpty, double progress, double progressSpan,
  std::vector<float>& transmittance, vtkIdType& rays);

/**
 * Shadow rays of one light for every computed voxel into `irradiance`, in
 * chunks so progress and AbortExecute are handled on the calling thread.
 * Returns false when aborted.
 */
bool CastShadowRays(vtkAlgorithm* self, const RayContext& ctx, const mmv::LightSource& light,
  const std::vector<vtkIdType>& computed, float* irradiance, double progress, double progressSpan,
  vtkIdType& rays);
}
}

#endif
