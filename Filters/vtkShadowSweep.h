/**
 * @file   vtkShadowSweep.h
 * @brief  The order in which piecewise shadow rays fill the irradiance grid
 *         for one directional light; the CPU filter and the GPU estimator share it.
 *
 * A full shadow ray crosses the whole grid, so estimating a directional
 * light costs O(n^4) for an n^3 grid. Piecewise shadow rays (as in Hernell,
 * Ljung and Ynnerman's local piecewise integration) cost O(n^3 K): the grid
 * is swept slice by slice along the light's dominant index axis, nearest
 * slices first, in chunks of K slices. A voxel's ray runs toward the light
 * only up to the last slice of the previous chunk (at most K slices away),
 * where it takes the transmittance already computed there, interpolated
 * bilinearly in that slice. Every voxel of a chunk reads only earlier chunks,
 * so a chunk is one parallel pass (one draw on the GPU). Empty voxels cost
 * nothing unless they lie on a slice the next chunk reads.
 *
 * The price is the in-slice interpolation: once per chunk along a ray, so a
 * shadow edge blurs by at most about sqrt(n / K) / 2 voxels (compared with
 * full rays in docs/performance.md, "Piecewise shadow rays").
 */
#ifndef vtkShadowSweep_h
#define vtkShadowSweep_h

#include "vtkIrradianceRegion.h"        // IndexBox
#include "vtkMultiMaterialLightModel.h" // LightSource
#include "vtkMultiMaterialParameters.h" // ShadowEstimation

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

namespace mmv
{

/// Whether `light` is estimated by piecewise rays under `estimation`:
/// directional lights only (point and spot lights take full rays).
inline bool UsesPiecewiseShadowRays(int estimation, const LightSource& light)
{
  return estimation == PiecewiseShadowRays && light.Kind == DirectionalLight;
}

struct ShadowSweep
{
  int Axis = 2;               // the dominant index axis of the direction toward the light
  bool TowardPositive = true; // the light lies toward +Axis: the sweep starts at the last slice
  int Slices = 1;             // grid dimension along Axis
  int SlicesPerChunk = 1;     // K

  int GetNumberOfChunks() const
  {
    return (this->Slices + this->SlicesPerChunk - 1) / this->SlicesPerChunk;
  }

  /// The slice at `depth` slices from the light's side.
  int SliceAtDepth(int depth) const
  {
    return this->TowardPositive ? this->Slices - 1 - depth : depth;
  }

  /**
   * Chunk `c`: its slices [first, last] (index order) and the slice whose
   * transmittance its rays end on, or -1 for the first chunk, whose rays run
   * to the boundary.
   */
  void GetChunk(int c, int& first, int& last, int& plane) const
  {
    const int nearest = c * this->SlicesPerChunk;
    const int farthest = std::min(this->Slices, nearest + this->SlicesPerChunk) - 1;
    first = std::min(this->SliceAtDepth(nearest), this->SliceAtDepth(farthest));
    last = std::max(this->SliceAtDepth(nearest), this->SliceAtDepth(farthest));
    plane = c == 0 ? -1 : this->SliceAtDepth(nearest - 1);
  }

  /// The slice of chunk `c` that the next chunk reads (-1 for the last):
  /// its empty voxels are computed too, the chunk's other empty voxels not.
  int GetReadSlice(int c) const
  {
    return c + 1 < this->GetNumberOfChunks()
      ? this->SliceAtDepth((c + 1) * this->SlicesPerChunk - 1)
      : -1;
  }
};

/// The sweep for index-space direction `toLight` (need not be unit length).
inline ShadowSweep PlanShadowSweep(const int dims[3], const glm::dvec3& toLight, int slicesPerChunk)
{
  ShadowSweep sweep;
  for (int a = 0; a < 3; ++a)
  {
    if (std::abs(toLight[a]) > std::abs(toLight[sweep.Axis]))
    {
      sweep.Axis = a;
    }
  }
  sweep.TowardPositive = toLight[sweep.Axis] > 0.0;
  sweep.Slices = dims[sweep.Axis];
  sweep.SlicesPerChunk = std::max(1, slicesPerChunk);
  return sweep;
}

/**
 * What each chunk of `sweep` must draw so that the voxels of `region` come
 * out exactly as a sweep of the whole grid computes them (vtkIrradianceRegion.h):
 * the region's voxels in the chunk, and the voxels of its read slice that
 * the next chunk's draw interpolates. `toLight` is the index-space direction
 * the sweep was planned with. Walks from the farthest chunk toward the
 * light; a chunk upstream of the region draws a patch of one slice. An
 * empty box: nothing to draw. `nonEmpty`, when given, shrinks the region's
 * part of each chunk to the voxels whose own values matter (the non-empty
 * ones, VoxelOccupancy::Shrink); the read slices are added after it.
 */
inline std::vector<IndexBox> PlanSweepBoxes(const ShadowSweep& sweep, const int dims[3],
  const glm::dvec3& toLight, const IndexBox& region,
  const std::function<IndexBox(const IndexBox&)>& nonEmpty = nullptr)
{
  const int axis = sweep.Axis;
  std::vector<IndexBox> boxes(sweep.GetNumberOfChunks());
  IndexBox read; // of the chunk being planned's read slice, for the chunk after it
  for (int chunk = sweep.GetNumberOfChunks() - 1; chunk >= 0; --chunk)
  {
    int first, last, plane;
    sweep.GetChunk(chunk, first, last, plane);
    IndexBox slab = IndexBox::Whole(dims);
    slab.Bounds[2 * axis] = first;
    slab.Bounds[2 * axis + 1] = last;
    const IndexBox own = region.Intersected(slab);
    const IndexBox needed = (nonEmpty ? nonEmpty(own) : own).United(read);
    boxes[chunk] = needed;
    read = IndexBox();
    if (needed.IsEmpty() || plane < 0)
    {
      continue;
    }
    // A ray from voxel v reaches `plane` at in-slice coordinate
    // v_e + (plane - v_axis) toLight_e / toLight_axis (linear in v: the
    // box's corners bound it), where the shader reads the bilinear pair
    // min(floor(clamped), n - 2) and one more (Shaders/mmvPiecewiseShadowFS.glsl);
    // one voxel more on each side covers float rounding.
    read.Bounds[2 * axis] = plane;
    read.Bounds[2 * axis + 1] = plane;
    for (int e = 0; e < 3; ++e)
    {
      if (e == axis)
      {
        continue;
      }
      const double slope = toLight[axis] != 0.0 ? toLight[e] / toLight[axis] : 0.0;
      double lo = std::numeric_limits<double>::infinity();
      double hi = -lo;
      for (int s = 0; s < 2; ++s)
      {
        for (int t = 0; t < 2; ++t)
        {
          const double q = needed.Bounds[2 * e + t] + (plane - needed.Bounds[2 * axis + s]) * slope;
          lo = std::min(lo, q);
          hi = std::max(hi, q);
        }
      }
      const double top = dims[e] - 1;
      lo = std::min(std::max(lo, 0.0), top);
      hi = std::min(std::max(hi, 0.0), top);
      read.Bounds[2 * e] = std::max(0, static_cast<int>(std::floor(lo)) - 1);
      read.Bounds[2 * e + 1] = std::min(dims[e] - 1, static_cast<int>(std::floor(hi)) + 2);
    }
  }
  return boxes;
}

/**
 * A ray from index coordinate `start` (along the sweep axis) with
 * `direction` index units per world unit reaches slice `plane` at
 * `distance` (world units); it ends there if that is no farther than its
 * exit distance `exit`, within the tolerances of vtkMultiMaterialParameters.h.
 * GLSL: mmvReachesSweepPlane (Shaders/mmvPiecewiseShadowFS.glsl).
 */
inline bool ReachesSweepPlane(
  double start, double direction, int plane, double exit, double& distance)
{
  distance = 0.0;
  if (plane < 0 || direction == 0.0)
  {
    return false;
  }
  distance = (static_cast<double>(plane) - start) / direction;
  return distance >= 0.0 &&
    distance <= exit * (1.0 + SweepPlaneRelativeTolerance) + SweepPlaneAbsoluteTolerance;
}

} // namespace mmv

#endif
