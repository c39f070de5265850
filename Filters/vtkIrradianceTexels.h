/**
 * @file   vtkIrradianceTexels.h
 * @brief  The GPU estimator's final write (the light grid's upsampling,
 *         Shaders/mmvLightGridUpsampleFS.glsl, then the fill pass,
 *         Shaders/mmvDiffusionFS.glsl with MMV_FILL_PASS) on the CPU, into
 *         the irradiance texture's 16-bit texels.
 *
 * Where the CPU swept every light of an irradiance texture
 * (mmv::SweepTransmittanceOnCPU), uploading its floats for two fragment
 * passes to read back costs a software rasterizer more than the CPU takes to
 * make the texels: the passes shade every voxel of the box as a fragment
 * (llvmpipe: about 0.14 s for the light kit on a 237 x 237 x 119 grid).
 *
 * The classes of empty voxels name their non-empty face neighbours
 * (EmptyVoxelClass); an empty voxel takes their mean, a non-empty one its
 * own value: the light grid's trilinear interpolation for a strided light,
 * else the sweep's. Texels are unsigned normalised, rounded to nearest.
 */
#ifndef vtkIrradianceTexels_h
#define vtkIrradianceTexels_h

#include "vtkIrradianceRegion.h" // IndexBox
#include "vtkMultiMaterialVolumeFiltersModule.h"

#include <glm/glm.hpp>

namespace mmv
{

/// The class of an empty voxel (Shaders/mmvClassifyFS.glsl writes the same):
/// -1 - m, m the bits of its non-empty face neighbours (bit 2 a: the one
/// below on axis a, 2 a + 1: above). Negative, so every pass that asks
/// "empty?" reads them alike; the final write averages the neighbours m names.
inline float EmptyVoxelClass(int neighbors)
{
  return -1.0f - static_cast<float>(neighbors);
}

/// The neighbour bits of an empty voxel's class (EmptyVoxelClass).
inline int EmptyVoxelNeighbors(float voxelClass)
{
  return static_cast<int>(-voxelClass) - 1;
}

/// What the final write reads: the sweeps' results, as the passes' targets.
struct IrradianceTexelInputs
{
  int Dimensions[3] = { 0, 0, 0 }; // the irradiance grid's points
  const float* Classes = nullptr;  // per voxel: s, or EmptyVoxelClass where empty
  int Lights = 0;                  // channels with a light; the others get 0
  int StridedMask = 0;             // bit l: light l's values are on the light grid
  // The lights on the irradiance grid: FineChannels floats per voxel, light
  // l's in channel l.
  const float* Fine = nullptr;
  int FineChannels = 0;
  // The strided lights: LightGridChannels floats per light grid point.
  const float* LightGrid = nullptr;
  int LightGridChannels = 0;
  int LightGridDimensions[3] = { 0, 0, 0 };
  glm::vec3 IndexToLightGrid{ 1.0f }; // irradiance index -> light grid coordinate
};

/**
 * The texels of box `box` of `texels` (`channels` unsigned shorts per
 * voxel, the whole grid, x fastest): the values of the final write of every
 * light of `inputs`, on all cores. Voxels outside the box keep theirs.
 */
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT void WriteIrradianceTexels(
  const IrradianceTexelInputs& inputs, const IndexBox& box, int channels, unsigned short* texels);

/**
 * What the final write reads at the non-empty voxels of box `box`: each
 * light's value (the light grid's interpolation for a strided light, else
 * the sweep's) into channels [0, inputs.Lights) of `values` (`channels`
 * floats per voxel, the whole grid, x fastest), as the multiple scattering
 * on the CPU takes them; other voxels and channels keep theirs.
 */
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT void GatherIrradianceValues(
  const IrradianceTexelInputs& inputs, const IndexBox& box, int channels, float* values);

} // namespace mmv

#endif
