/**
 * @file   vtkSceneTransmittance.h
 * @brief  The transmittance toward each light through the other volumes of a
 *         scene, on a grid of one volume (the receiver), on the CPU.
 *
 * Several volumes in one renderer shadow each other: a point of the
 * receiver is lit by light k through its own volume (its irradiance) and
 * through every other volume on the way (this transmittance). For volumes
 * that do not overlap the product is exact for single scattering, since the
 * transmittance along a ray is the product of its segments' transmittances.
 *
 * Each other volume (an Occluder) is its extinction on a coarse grid of its
 * own object space (mmv::CoarseExtinction) and the map from the receiver's
 * object space into that space (the two vtkProp3D matrices). A ray from a
 * receiver point toward the light is clipped to each occluder's box of
 * voxel centres and marched in half-voxel steps of that grid (midpoint rule,
 * trilinear extinction); its length is measured in the occluder's object
 * units, as its own shadows measure it. A point light's ray ends at the
 * light. The light's distance falloff and spot cone are not here: the
 * irradiance the transmittance multiplies has them.
 *
 * A receiver point inside an occluder's box counts the occluder's extinction
 * between the point and the light: overlapping volumes shadow each other,
 * but the ray cast does not composite them within one ray.
 */
#ifndef vtkSceneTransmittance_h
#define vtkSceneTransmittance_h

#include "vtkIrradianceGrid.h"                   // IrradianceGrid
#include "vtkMultiMaterialLightModel.h"          // LightSource
#include "vtkMultiMaterialVolumeFiltersModule.h" // export macro

#include <glm/glm.hpp>

#include <vector>

namespace mmv
{

/// An occluding volume's extinction grid has at most this many voxels along
/// an axis, and so has the grid a receiver's transmittance is computed on
/// (linearly interpolated to its irradiance grid): shadows cast from one
/// volume onto another are as sharp as the coarser of the two.
constexpr int SceneShadowVoxelsPerAxis = 64;

/// Another volume, as the receiver's lights see it.
struct Occluder
{
  const IrradianceGrid* Grid = nullptr;           // in the occluder's object space
  const std::vector<float>* Extinction = nullptr; // per its object unit, one per voxel
  glm::dmat4 ReceiverToOccluder{ 1.0 };           // receiver object -> occluder object
};

/// The transmittance through `occluder` from receiver point `x` along unit
/// receiver direction `direction`, up to `distance` (< 0: unbounded).
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT double OccluderTransmittance(
  const Occluder& occluder, const glm::dvec3& x, const glm::dvec3& direction, double distance);

/**
 * For every voxel of `grid` (the receiver's object space) and every light of
 * `lights` (its object space), the product of OccluderTransmittance over
 * `occluders` toward that light. Out: one vector per group of
 * mmv::IrradianceLightsPerTexture lights, 4 floats per voxel (light 4g + c
 * in channel c; channels without a light hold 1), x fastest, as the
 * irradiance textures group the lights.
 */
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT void ComputeSceneTransmittance(const IrradianceGrid& grid,
  const std::vector<LightSource>& lights, const std::vector<Occluder>& occluders,
  std::vector<std::vector<float>>& groups);

} // namespace mmv

#endif
