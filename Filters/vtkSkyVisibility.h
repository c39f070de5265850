/**
 * @file   vtkSkyVisibility.h
 * @brief  How much of the sky every voxel sees: the transmittance toward K
 *         directions, kept as two moments so that any sky whose radiance is
 *         linear in the direction shades without estimating again.
 *
 * The environment light is the renderer's background seen as an infinitely
 * distant sky: L(w) = a + (w . up) c, a vertical gradient (a uniform
 * background has c = 0). Integrated over the sphere with the volume's
 * transmittance T(x, w) toward the sky,
 *
 *   F0(x) = int L T dw = a S0 + c (up . S1),
 *   S0 = int T dw ~ sum_k W T_k,   S1 = int T w dw ~ sum_k W T_k w_k,
 *
 * with K directions w_k of equal weight W = 4 pi / K. S0 and S1 depend on
 * the data and the opacity only, so a change of background colour, or of
 * the gradient's up axis (the camera's view-up), reshades without
 * re-estimation. The directions come in antipodal pairs, so an unoccluded
 * voxel has S1 = 0 exactly and S0 = 4 pi.
 *
 * T_k is swept slice to slice along direction k's dominant index axis (the
 * light-volume propagation of Ropinski et al.): a voxel takes the
 * transmittance one slice toward the sky, interpolated bilinearly in that
 * slice, times exp(-depth) of the step between them (trapezoid rule on the
 * extinction). The slice nearest the sky has T = 1: the volume is the box of
 * its voxel centres, as for the lights. A ray that leaves the box through
 * a side within a few steps is marched to its exit instead: interpolated
 * against the boundary's rays (T = 1), it would take in sky it cannot see.
 * The interpolation's numerical diffusion is what remains: against full
 * rays in a smooth medium, a mean error of about 0.005 in T.
 *
 * The sky is smooth where it matters (ambient occlusion), so it is
 * estimated on a grid coarser than the irradiance grid, from the extinction
 * averaged over each coarse voxel (AverageOntoGrid), which keeps the
 * occlusion of structures thinner than a coarse voxel.
 */
#ifndef vtkSkyVisibility_h
#define vtkSkyVisibility_h

#include "vtkIrradianceDiffusion.h"              // DiffusionSettings
#include "vtkIrradianceGrid.h"                   // IrradianceGrid
#include "vtkMultiMaterialVolumeFiltersModule.h" // export macro

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace mmv
{

/// Floats per voxel of the sky's visibility: S0, then S1's x, y, z.
constexpr int SkyMomentsPerVoxel = 4;

/// The ray cast's sky grid has at most this many voxels along an axis:
/// occlusion by the environment is smooth, and its cost grows with the grid.
constexpr int SkyVoxelsPerAxis = 40;
/// Directions the sky's visibility is swept along (SkyDirections): 64 keep
/// the second moment within 2 % of isotropic.
constexpr int SkyDirectionCount = 64;

/// The largest EnvironmentLighting used: a brighter sky only saturates.
constexpr double MaxEnvironmentLighting = 100.0;

/// Checks an EnvironmentLighting strength: NaN, negative or infinite returns
/// 0 (off), above MaxEnvironmentLighting returns that maximum, and `why`
/// (if given) says so; valid values come back unchanged.
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT double ValidEnvironmentLighting(
  double strength, std::string* why);

/**
 * `count` unit directions (an odd count is rounded up) in antipodal pairs:
 * the first half a spherical Fibonacci set on the hemisphere z > 0, the
 * second half their negations in the same order. Each weighs 4 pi / count.
 */
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT std::vector<glm::dvec3> SkyDirections(int count);

/**
 * A grid spanning the same box as `fine` (the same first and last voxel
 * centres, the same direction) with every `stride`-th voxel, rounded up:
 * (n - 1) / stride + 1 voxels per axis (n = 1 stays 1).
 */
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT IrradianceGrid CoarsenIrradianceGrid(
  const IrradianceGrid& fine, int stride);

/**
 * The mean of `values` (on `fine`, x fastest) over each voxel of `coarse`
 * (a CoarsenIrradianceGrid of `fine`): the fine voxels whose centres lie
 * nearest to that coarse voxel's centre, along each axis. With `table`,
 * the mean of the table's entries at the values (mmv::LookupTable: a
 * normalised value's extinction), without a fine array of them.
 */
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT void AverageOntoGrid(const IrradianceGrid& fine,
  const float* values, const IrradianceGrid& coarse, std::vector<float>& out,
  const std::vector<float>* table = nullptr);

/**
 * The transmittance from every voxel centre of `grid` toward the sky along
 * unit physical `direction`, through `extinction` (per physical unit, one per
 * voxel, x fastest; negative and NaN count as 0), into `transmittance` (one
 * per voxel).
 */
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT void SweepSkyTransmittance(const IrradianceGrid& grid,
  const float* extinction, const glm::dvec3& direction, std::vector<float>& transmittance);

/**
 * S0 and S1 (SkyMomentsPerVoxel floats per voxel) of every voxel of `grid`
 * over `directions` (SkyDirections), each weighing 4 pi / directions.size().
 * The moments are summed in the directions' order, whatever the threads.
 */
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT void ComputeSkyVisibility(const IrradianceGrid& grid,
  const float* extinction, const std::vector<glm::dvec3>& directions, std::vector<float>& moments);

/**
 * Multiple scattering of the sky: each moment of `moments` (on a grid of
 * `dims`, SkyMomentsPerVoxel floats per voxel) diffused by
 * mmv::DiffuseIrradiance with the per-voxel `strength` (s, in data voxels^2;
 * `spacing` in data voxels). The diffusion is linear, so the diffused
 * moments still shade any sky colour.
 */
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT void DiffuseSkyMoments(const int dims[3],
  const double spacing[3], const float* strength, std::vector<float>& moments,
  const DiffusionSettings& settings);

} // namespace mmv

#endif
