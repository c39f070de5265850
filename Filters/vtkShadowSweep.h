/**
 * @file   vtkShadowSweep.h
 * @brief  The order in which piecewise shadow rays fill the irradiance grid
 *         for one directional light (the CPU filter and the GPU estimator
 *         share it), or on the GPU for a point or spot light outside the grid.
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

struct ShadowSweep
{
  int Axis = 2;               // the dominant index axis of the direction toward the light
  bool TowardPositive = true; // the light lies toward +Axis: the sweep starts at the last slice
  int Slices = 1;             // slices swept along Axis
  int SlicesPerChunk = 1;     // K
  int First = 0;              // the first of them (index order)
  // A point light inside the grid (InsideLightSweeps): this sweep computes
  // only the voxels of the light's pyramid on its side of the light along
  // Axis (InSweptPyramid), and its rays read only that pyramid's slices.
  bool Pyramid = false;
  glm::vec3 Light{ 0.0f }; // the light's index-space position, in float as the GPU has it

  /**
   * Slices of the first chunk: the chunks after it start at multiples of
   * SlicesPerChunk in index order, wherever the sweep starts. A rasterizer
   * shades a chunk along x or y as a strip of that many texels in every
   * layer, in blocks aligned to the texture (llvmpipe: 4 x 4 texels); a strip
   * that starts inside a block shades one block more.
   */
  int GetFirstChunkSlices() const
  {
    const int k = this->SlicesPerChunk;
    const int lead =
      this->TowardPositive ? (this->First + this->Slices - 1) % k + 1 : k - this->First % k;
    return std::min(this->Slices, lead);
  }

  int GetNumberOfChunks() const
  {
    const int rest = this->Slices - this->GetFirstChunkSlices();
    return 1 + (rest + this->SlicesPerChunk - 1) / this->SlicesPerChunk;
  }

  /// Depth (slices from the light's side) of chunk `c`'s first slice.
  int GetChunkDepth(int c) const
  {
    return c == 0 ? 0 : this->GetFirstChunkSlices() + (c - 1) * this->SlicesPerChunk;
  }

  /// The slice at `depth` slices from the light's side.
  int SliceAtDepth(int depth) const
  {
    return this->First + (this->TowardPositive ? this->Slices - 1 - depth : depth);
  }

  /**
   * Chunk `c`: its slices [first, last] (index order) and the slice whose
   * transmittance its rays end on, or -1 for the first chunk, whose rays run
   * to the boundary.
   */
  void GetChunk(int c, int& first, int& last, int& plane) const
  {
    const int nearest = this->GetChunkDepth(c);
    const int farthest = std::min(this->Slices, this->GetChunkDepth(c + 1)) - 1;
    first = std::min(this->SliceAtDepth(nearest), this->SliceAtDepth(farthest));
    last = std::max(this->SliceAtDepth(nearest), this->SliceAtDepth(farthest));
    plane = c == 0 ? -1 : this->SliceAtDepth(nearest - 1);
  }

  /// The slice of chunk `c` that the next chunk reads (-1 for the last):
  /// its empty voxels are computed too, the chunk's other empty voxels not.
  int GetReadSlice(int c) const
  {
    return c + 1 < this->GetNumberOfChunks() ? this->SliceAtDepth(this->GetChunkDepth(c + 1) - 1)
                                             : -1;
  }
};

/**
 * Whether voxel `voxel` (index) belongs to `sweep`'s pyramid: its offset
 * from the light is largest along the sweep's axis (ties included), on the
 * sweep's side of the light (offset >= 0 where the light lies toward -Axis).
 * Every voxel belongs to one of InsideLightSweeps' pyramids; one on an edge
 * between pyramids (a tie) to each of them, and each computes it from its
 * own slices for its own later chunks. In float, as the GPU decides it.
 * GLSL: mmvInSweptPyramid.
 */
inline bool InSweptPyramid(const ShadowSweep& sweep, const glm::vec3& voxel)
{
  const glm::vec3 d = voxel - sweep.Light;
  const float along = std::abs(d[sweep.Axis]);
  return along >= std::abs(d[(sweep.Axis + 1) % 3]) && along >= std::abs(d[(sweep.Axis + 2) % 3]) &&
    (d[sweep.Axis] >= 0.0f) == !sweep.TowardPositive;
}

/**
 * The in-slice indices along axis `e` that a ray of a pyramid sweep may read
 * in slice `plane`: those whose offset from the light along `e` is at most
 * the plane's along the sweep axis, [lo, hi] within [0, n - 1] (lo > hi:
 * none), compared in float as InSweptPyramid compares them: the pyramid's
 * own. A ray of the pyramid reaches the plane within them; its bilinear read
 * is clamped to them (SliceReadRange).
 */
inline void PyramidSliceRange(const ShadowSweep& sweep, int plane, int e, int n, int& lo, int& hi)
{
  const float reach = std::abs(static_cast<float>(plane) - sweep.Light[sweep.Axis]);
  const float at = sweep.Light[e];
  auto within = [&](int i) { return std::abs(static_cast<float>(i) - at) <= reach; };
  lo = std::max(0, static_cast<int>(std::ceil(at - reach)));
  hi = std::min(n - 1, static_cast<int>(std::floor(at + reach)));
  // Rounding of at -/+ reach may put either end one index off.
  lo = lo > 0 && within(lo - 1) ? lo - 1 : (lo < n && !within(lo) ? lo + 1 : lo);
  hi = hi < n - 1 && within(hi + 1) ? hi + 1 : (hi >= 0 && !within(hi) ? hi - 1 : hi);
}

/**
 * The part of slice `plane` that `sweep`'s rays may read, as
 * {lo, hi} of in-slice axis (Axis + 1) % 3 and then of (Axis + 2) % 3 in
 * `range`: the whole slice, or a pyramid's part of it (PyramidSliceRange).
 * Returns whether it holds a voxel; where it does not (a pyramid's part of a
 * slice near a light close to a face), the rays that would end on the slice
 * run on to the light. It is the same for every ray of a chunk: the GPU
 * takes it as the uniform sliceRange (Shaders/mmvPiecewiseShadowFS.glsl).
 */
inline bool SliceReadRange(const ShadowSweep& sweep, int plane, const int dims[3], int range[4])
{
  bool holds = true;
  for (int k = 0; k < 2; ++k)
  {
    const int e = (sweep.Axis + 1 + k) % 3;
    range[2 * k] = 0;
    range[2 * k + 1] = dims[e] - 1;
    if (sweep.Pyramid)
    {
      PyramidSliceRange(sweep, plane, e, dims[e], range[2 * k], range[2 * k + 1]);
    }
    holds = holds && range[2 * k] <= range[2 * k + 1];
  }
  return holds;
}

/**
 * A point or spot light inside the grid (PointLightSweepDirection gives
 * (0, 0, 0)) sweeps six pyramids with their apex at the light, one per side
 * of it along each axis (InSweptPyramid): in its pyramid a voxel's ray
 * toward the light keeps the pyramid's axis dominant, so it crosses that
 * axis's slices in order, nearest the light first, and reaches the previous
 * chunk's slice within the pyramid's part of it (PyramidSliceRange). Each
 * sweep reads only its own pyramid, so the sweeps are independent; the
 * slices of each run from the light's (float, as the GPU has it) outward.
 * Sides without slices are left out.
 */
inline std::vector<ShadowSweep> InsideLightSweeps(
  const int dims[3], const glm::dvec3& light, int slicesPerChunk)
{
  const glm::vec3 apex(light);
  std::vector<ShadowSweep> sweeps;
  for (int a = 0; a < 3; ++a)
  {
    // The voxels with an offset >= 0 along a: from ceil(light) on.
    const int split = std::min(std::max(static_cast<int>(std::ceil(apex[a])), 0), dims[a]);
    for (const bool beyond : { true, false })
    {
      ShadowSweep sweep;
      sweep.Axis = a;
      sweep.TowardPositive = !beyond;
      sweep.First = beyond ? split : 0;
      sweep.Slices = beyond ? dims[a] - split : split;
      sweep.SlicesPerChunk = std::max(1, slicesPerChunk);
      sweep.Pyramid = true;
      sweep.Light = apex;
      if (sweep.Slices > 0)
      {
        sweeps.push_back(sweep);
      }
    }
  }
  return sweeps;
}

/**
 * Point and spot lights outside the grid sweep as well. Along an index axis
 * on which the light lies beyond the grid, every voxel's ray toward the
 * light crosses that axis's slices in order, nearest the light first, and
 * the rest of the ray from where it crosses a slice is that point's own ray:
 * so a ray may end on a slice computed before, as a directional light's
 * does. Returns the index-space direction to plan the sweep with (a unit
 * vector along that axis, toward the light), or (0, 0, 0) where the light at
 * index-space position `light` lies within half a voxel of the grid's extent
 * on every axis (full rays). Of the axes it lies beyond, the one whose rays
 * cross its slices most steeply (the largest smallest cosine over the
 * grid's corners), so that rays march the least between slices.
 */
inline glm::dvec3 PointLightSweepDirection(const int dims[3], const glm::dvec3& light)
{
  glm::dvec3 best(0.0);
  double bestCosine = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    const double high = dims[a] - 1.0;
    if (light[a] >= -0.5 && light[a] <= high + 0.5)
    {
      continue;
    }
    double cosine = 1.0;
    for (int corner = 0; corner < 8; ++corner)
    {
      glm::dvec3 c;
      for (int b = 0; b < 3; ++b)
      {
        c[b] = (corner >> b) & 1 ? dims[b] - 1.0 : 0.0;
      }
      const glm::dvec3 d = light - c;
      cosine = std::min(cosine, std::abs(d[a]) / glm::length(d));
    }
    if (cosine > bestCosine)
    {
      bestCosine = cosine;
      best = glm::dvec3(0.0);
      best[a] = light[a] > high ? 1.0 : -1.0;
    }
  }
  return best;
}

/**
 * The index-space direction `light`'s piecewise rays are swept with on a
 * grid of `dims` points where physical point p has index toIndex (p -
 * origin), or (0, 0, 0) where the light takes full rays: under
 * PiecewiseShadowRays a directional light sweeps toward itself, a point or
 * spot light along PointLightSweepDirection.
 */
inline glm::dvec3 ShadowSweepDirection(int estimation, const LightSource& light, const int dims[3],
  const glm::dmat3& toIndex, const glm::dvec3& origin)
{
  if (estimation != PiecewiseShadowRays)
  {
    return glm::dvec3(0.0);
  }
  if (light.Kind == DirectionalLight)
  {
    return toIndex * light.ToLight;
  }
  return PointLightSweepDirection(dims, toIndex * (light.Position - origin));
}

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
 * The sweeps of `light`'s piecewise rays on a grid of `dims` points (physical
 * point p at index toIndex (p - origin)), in order: one toward a directional
 * light or a point or spot light beyond the grid (ShadowSweepDirection), the
 * pyramids of one inside it (InsideLightSweeps); none under full rays.
 */
inline std::vector<ShadowSweep> PlanLightSweeps(int estimation, const LightSource& light,
  const int dims[3], const glm::dmat3& toIndex, const glm::dvec3& origin, int slicesPerChunk)
{
  const glm::dvec3 direction = ShadowSweepDirection(estimation, light, dims, toIndex, origin);
  if (direction != glm::dvec3(0.0))
  {
    return { PlanShadowSweep(dims, direction, slicesPerChunk) };
  }
  if (estimation != PiecewiseShadowRays || light.Kind == DirectionalLight)
  {
    return {};
  }
  return InsideLightSweeps(dims, toIndex * (light.Position - origin), slicesPerChunk);
}

/**
 * The box around what chunk `chunk` of a pyramid sweep (InsideLightSweeps)
 * may compute on a grid of `dims`: its pyramid's part of the chunk's slices
 * (the pyramid widens away from the light: its part of the farthest slice)
 * and of its read slice. The shader leaves the box's voxels outside the
 * pyramid alone.
 */
inline IndexBox PyramidChunkBox(const ShadowSweep& sweep, const int dims[3], int chunk)
{
  const int axis = sweep.Axis;
  int first, last, plane;
  sweep.GetChunk(chunk, first, last, plane);
  const int read = sweep.GetReadSlice(chunk);
  if (read >= 0)
  {
    first = std::min(first, read);
    last = std::max(last, read);
  }
  IndexBox box = IndexBox::Whole(dims);
  box.Bounds[2 * axis] = first;
  box.Bounds[2 * axis + 1] = last;
  const int far = std::abs(static_cast<float>(first) - sweep.Light[axis]) >
      std::abs(static_cast<float>(last) - sweep.Light[axis])
    ? first
    : last;
  for (int e = 0; e < 3; ++e)
  {
    if (e != axis)
    {
      PyramidSliceRange(sweep, far, e, dims[e], box.Bounds[2 * e], box.Bounds[2 * e + 1]);
    }
  }
  return box;
}

/**
 * What each chunk of `sweep` must draw so that the voxels of `region` come
 * out exactly as a sweep of the whole grid computes them (vtkIrradianceRegion.h):
 * the region's voxels in the chunk, and the voxels of its read slice that
 * the next chunk's draw interpolates. `toLight` is the index-space direction
 * the sweep was planned with; for a point or spot light, `pointLight` is the
 * light's index-space position, toward which the rays converge (for a
 * pyramid sweep, each box is cut to its pyramid's, PyramidChunkBox). Walks from the farthest chunk
 * toward the light; a chunk upstream of the region draws a patch of one slice. An empty box:
 * nothing to draw. `nonEmpty`, when given, shrinks the region's part of each chunk to the voxels
 * whose own values matter (the non-empty ones, VoxelOccupancy::Shrink); the read slices are added
 * after it.
 */
inline std::vector<IndexBox> PlanSweepBoxes(const ShadowSweep& sweep, const int dims[3],
  const glm::dvec3& toLight, const IndexBox& region,
  const std::function<IndexBox(const IndexBox&)>& nonEmpty = nullptr,
  const glm::dvec3* pointLight = nullptr)
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
    IndexBox needed = (nonEmpty ? nonEmpty(own) : own).United(read);
    if (sweep.Pyramid)
    {
      needed = needed.Intersected(PyramidChunkBox(sweep, dims, chunk));
    }
    boxes[chunk] = needed;
    read = IndexBox();
    if (needed.IsEmpty() || plane < 0)
    {
      continue;
    }
    // A ray from voxel v reaches `plane` at in-slice coordinate
    // v_e + (plane - v_axis) toLight_e / toLight_axis (linear in v: the
    // box's corners bound it), toward a point light L at
    // L_e + (v_e - L_e) (plane - L_axis) / (v_axis - L_axis) (a central
    // projection from L, which lies beyond the grid along the axis: the
    // corners bound it too), where the shader reads the bilinear pair
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
          const double ve = needed.Bounds[2 * e + t];
          const double va = needed.Bounds[2 * axis + s];
          const double q = pointLight ? (*pointLight)[e] +
              (ve - (*pointLight)[e]) * (plane - (*pointLight)[axis]) / (va - (*pointLight)[axis])
                                      : ve + (plane - va) * slope;
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
