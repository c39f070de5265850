/**
 * @file   vtkIrradianceRegion.h
 * @brief  The part of the irradiance grid a piece of the volume needs, and
 *         what must be estimated so that it comes out exactly as the whole
 *         grid's would.
 *
 * Under MPI every rank lights its piece from the global grid
 * (vtkGlobalPrefilteredVolume), but its ray cast only samples the grid
 * around its own piece. The irradiance there depends on more than that box:
 * the fill pass reads the neighbours of each voxel, the diffusion's passes
 * reach one diffusion-grid block further each, and the restriction reads
 * every voxel of a block. A rank therefore estimates its region grown by
 * those reaches (a halo it computes itself rather than exchanges: no
 * collective call in a render, and no GPU read-back per pass), and the
 * region's values equal the whole grid's bit for bit (the default
 * exponential diffusion has a fixed number of passes). Directional lights
 * add the slices the piecewise sweep reads on its way from the light
 * (PlanSweepBoxes in vtkShadowSweep.h).
 */
#ifndef vtkIrradianceRegion_h
#define vtkIrradianceRegion_h

#include "vtkIrradianceDiffusion.h" // DiffusionGrid
#include "vtkIrradianceGrid.h"      // IrradianceGrid
#include "vtkType.h"                // vtkIdType

#include <algorithm>
#include <cmath>

namespace mmv
{

/// Voxels [Bounds[2a], Bounds[2a + 1]] along each axis a (inclusive), the
/// box layout of vtkIrradianceEstimator's draws; empty when a minimum
/// exceeds its maximum.
struct IndexBox
{
  int Bounds[6] = { 0, -1, 0, -1, 0, -1 };

  /// Every voxel of any grid (Intersected with a grid's Whole: that).
  static IndexBox Everything()
  {
    return IndexBox{ { 0, VTK_INT_MAX, 0, VTK_INT_MAX, 0, VTK_INT_MAX } };
  }
  static IndexBox Whole(const int dims[3])
  {
    IndexBox box;
    for (int a = 0; a < 3; ++a)
    {
      box.Bounds[2 * a] = 0;
      box.Bounds[2 * a + 1] = dims[a] - 1;
    }
    return box;
  }
  bool IsEmpty() const
  {
    return this->Bounds[0] > this->Bounds[1] || this->Bounds[2] > this->Bounds[3] ||
      this->Bounds[4] > this->Bounds[5];
  }
  vtkIdType GetNumberOfVoxels() const
  {
    return this->IsEmpty() ? 0
                           : static_cast<vtkIdType>(this->Bounds[1] - this->Bounds[0] + 1) *
        (this->Bounds[3] - this->Bounds[2] + 1) * (this->Bounds[5] - this->Bounds[4] + 1);
  }
  bool Contains(const int index[3]) const
  {
    for (int a = 0; a < 3; ++a)
    {
      if (index[a] < this->Bounds[2 * a] || index[a] > this->Bounds[2 * a + 1])
      {
        return false;
      }
    }
    return true;
  }
  bool operator==(const IndexBox& other) const
  {
    return (this->IsEmpty() && other.IsEmpty()) ||
      std::equal(this->Bounds, this->Bounds + 6, other.Bounds);
  }
  bool operator!=(const IndexBox& other) const { return !(*this == other); }
  /// This box grown by `by` voxels on every side, within a grid of `dims`.
  IndexBox Grown(int by, const int dims[3]) const
  {
    IndexBox box = *this;
    for (int a = 0; a < 3 && !this->IsEmpty(); ++a)
    {
      box.Bounds[2 * a] = std::max(0, this->Bounds[2 * a] - by);
      box.Bounds[2 * a + 1] = std::min(dims[a] - 1, this->Bounds[2 * a + 1] + by);
    }
    return box;
  }
  /// The smallest box holding both.
  IndexBox United(const IndexBox& other) const
  {
    if (this->IsEmpty())
    {
      return other;
    }
    if (other.IsEmpty())
    {
      return *this;
    }
    IndexBox box;
    for (int a = 0; a < 3; ++a)
    {
      box.Bounds[2 * a] = std::min(this->Bounds[2 * a], other.Bounds[2 * a]);
      box.Bounds[2 * a + 1] = std::max(this->Bounds[2 * a + 1], other.Bounds[2 * a + 1]);
    }
    return box;
  }
  IndexBox Intersected(const IndexBox& other) const
  {
    IndexBox box;
    for (int a = 0; a < 3; ++a)
    {
      box.Bounds[2 * a] = std::max(this->Bounds[2 * a], other.Bounds[2 * a]);
      box.Bounds[2 * a + 1] = std::min(this->Bounds[2 * a + 1], other.Bounds[2 * a + 1]);
    }
    return box;
  }
};

/**
 * The irradiance voxels a piece's ray cast reads: the piece spans data
 * points [offset, offset + pieceDims - 1] of the whole volume, irradiance
 * index (offset + i) / r (r = grid.DataVoxelsPerVoxel), and trilinear
 * fetches read the voxels on both sides (the index that
 * mmv::PieceToGlobalIrradianceMap maps the piece's texture coordinates to).
 * One voxel more on each side covers VTK's sampling just past a block face
 * and float rounding.
 */
inline IndexBox PieceIrradianceBox(
  const IrradianceGrid& grid, const double offset[3], const int pieceDims[3])
{
  IndexBox box;
  const int* gridDims = grid.Dimensions;
  for (int a = 0; a < 3; ++a)
  {
    const double r = grid.DataVoxelsPerVoxel[a] > 0.0 ? grid.DataVoxelsPerVoxel[a] : 1.0;
    const double first = offset[a] / r;
    const double last = (offset[a] + std::max(pieceDims[a], 1) - 1) / r;
    box.Bounds[2 * a] = std::max(0, static_cast<int>(std::floor(first)) - 1);
    box.Bounds[2 * a + 1] = std::min(gridDims[a] - 1, static_cast<int>(std::ceil(last)) + 1);
  }
  return box;
}

/**
 * The voxels of a grid of `otherDims` spanning the same points as a grid of
 * `dims` (voxel t at index t (n - 1) / (m - 1)) that trilinear fetches at
 * the points of `box` read: the tint grid of the irradiance grid's region.
 */
inline IndexBox ResampledBox(const IndexBox& box, const int dims[3], const int otherDims[3])
{
  IndexBox other;
  for (int a = 0; a < 3; ++a)
  {
    const double ratio = dims[a] > 1 ? static_cast<double>(otherDims[a] - 1) / (dims[a] - 1) : 0.0;
    other.Bounds[2 * a] = std::max(0, static_cast<int>(std::floor(box.Bounds[2 * a] * ratio)) - 1);
    other.Bounds[2 * a + 1] =
      std::min(otherDims[a] - 1, static_cast<int>(std::floor(box.Bounds[2 * a + 1] * ratio)) + 2);
  }
  return box.IsEmpty() ? IndexBox() : other;
}

/// What the passes of one light update draw for a region (see the file).
struct IrradianceRegionPlan
{
  IndexBox Region;    // the voxels the ray cast reads: the final write
  IndexBox Source;    // what the fill pass reads: Region and its neighbours
  IndexBox Coarse;    // diffusion-grid blocks the restriction and sweeps draw (empty: none)
  IndexBox Estimated; // shadow rays: Source and the restriction's footprint of Coarse
};

/**
 * The plan for `region` of a grid of `dims`; `diffusion` null, or the
 * diffusion grid and the number of passes each reading their neighbours
 * (the series' terms, or every Jacobi sweep of every sub-step).
 */
inline IrradianceRegionPlan PlanIrradianceRegion(
  const IndexBox& region, const int dims[3], const DiffusionGrid* diffusion, int passes)
{
  IrradianceRegionPlan plan;
  plan.Region = region.Intersected(IndexBox::Whole(dims));
  plan.Source = plan.Region.Grown(1, dims);
  plan.Estimated = plan.Source;
  if (!diffusion || plan.Source.IsEmpty())
  {
    return plan;
  }
  // Prolongation: fine voxel i interpolates the blocks floor(u) and
  // floor(u) + 1 of its coarse coordinate u = (i - (f - 1) / 2) / f.
  IndexBox read;
  for (int a = 0; a < 3; ++a)
  {
    const double f = diffusion->Factor[a];
    read.Bounds[2 * a] =
      static_cast<int>(std::floor((plan.Source.Bounds[2 * a] - 0.5 * (f - 1.0)) / f));
    read.Bounds[2 * a + 1] =
      static_cast<int>(std::floor((plan.Source.Bounds[2 * a + 1] - 0.5 * (f - 1.0)) / f)) + 1;
  }
  // Each pass reads its input's neighbours; one more block for the first
  // pass's reads of the restricted input, and one for rounding.
  plan.Coarse = read.Grown(std::max(passes, 0) + 2, diffusion->Dimensions);
  // Restriction: block c is the mean of fine voxels [c f, c f + f - 1].
  IndexBox footprint;
  for (int a = 0; a < 3; ++a)
  {
    footprint.Bounds[2 * a] = plan.Coarse.Bounds[2 * a] * diffusion->Factor[a];
    footprint.Bounds[2 * a + 1] =
      std::min(dims[a] - 1, (plan.Coarse.Bounds[2 * a + 1] + 1) * diffusion->Factor[a] - 1);
  }
  plan.Estimated = plan.Source.United(footprint);
  return plan;
}

} // namespace mmv

#endif
