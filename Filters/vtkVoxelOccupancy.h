/**
 * @file   vtkVoxelOccupancy.h
 * @brief  Which bricks of the irradiance grid may hold a non-empty voxel,
 *         so that the shadow passes draw only the box around them.
 *
 * No pass reads an empty voxel's transmittance except where the piecewise
 * sweep interpolates a read slice (PlanSweepBoxes adds those voxels): the
 * fill pass averages non-empty neighbours only and the diffusion exchanges
 * through voxels with s > 0. Drawing an empty voxel still costs a software
 * rasterizer about as much as a cheap voxel (on a generated chest CT, 72 %
 * of the voxels are empty and a shadow draw that computes nothing takes
 * half the time of one that marches), so the draws shrink to the box of the
 * bricks that may be non-empty.
 *
 * Conservative by construction: each brick keeps the range of its values
 * (once per volume), and an opacity table marks it occupied when any entry
 * that a value in that range reads with a positive weight is positive or
 * not finite. The GPU's classification (mmvClassifyFS.glsl) decides per
 * voxel with the same float arithmetic; a brick this calls empty holds no
 * voxel it calls non-empty.
 */
#ifndef vtkVoxelOccupancy_h
#define vtkVoxelOccupancy_h

#include "vtkIrradianceRegion.h" // IndexBox

#include <vector>

namespace mmv
{

class VoxelOccupancy
{
public:
  /// Voxels per brick edge: boxes come out at most BrickSize - 1 voxels
  /// larger than the non-empty voxels' on each side.
  static constexpr int BrickSize = 4;

  /// The value range of every brick of `values` (normalised, x fastest) on a
  /// grid of `dims`; every brick counts as occupied until Classify().
  void SetValues(const std::vector<float>& values, const int dims[3]);
  /// Marks the bricks where `opacity` (the estimator's table over [0, 1],
  /// read with linear interpolation) may be positive.
  void Classify(const std::vector<float>& opacity);
  /// The part of `box` that may hold non-empty voxels: the voxels of its
  /// occupied bricks, bounded, within `box`; empty when none is. Without
  /// values (SetValues not called, or another grid), `box` itself.
  IndexBox Shrink(const IndexBox& box) const;
  /// Occupied bricks, of GetNumberOfBricks().
  long long GetNumberOfOccupiedBricks() const;
  long long GetNumberOfBricks() const { return static_cast<long long>(this->Occupied.size()); }

private:
  int Dimensions[3] = { 0, 0, 0 };
  int Bricks[3] = { 0, 0, 0 };
  std::vector<float> Low; // per brick; NaN where a value is NaN
  std::vector<float> High;
  std::vector<unsigned char> Occupied;
};

} // namespace mmv

#endif
