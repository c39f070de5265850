#include "vtkVoxelOccupancy.h"

#include "vtkTableLookup.h"

#include "vtkMultiMaterialThreads.h" // mmv::For
#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mmv
{

void VoxelOccupancy::SetValues(const std::vector<float>& values, const int dims[3])
{
  const size_t voxels = static_cast<size_t>(dims[0]) * dims[1] * dims[2];
  if (dims[0] < 1 || dims[1] < 1 || dims[2] < 1 || values.size() != voxels)
  {
    *this = VoxelOccupancy();
    return;
  }
  for (int a = 0; a < 3; ++a)
  {
    this->Dimensions[a] = dims[a];
    this->Bricks[a] = (dims[a] + BrickSize - 1) / BrickSize;
  }
  const int* b = this->Bricks;
  const size_t bricks = static_cast<size_t>(b[0]) * b[1] * b[2];
  this->Low.assign(bricks, std::numeric_limits<float>::infinity());
  this->High.assign(bricks, -std::numeric_limits<float>::infinity());
  this->Occupied.assign(bricks, 1);
  // In parallel over brick layers: each writes only its own bricks.
  mmv::For(0, b[2],
    [&](vtkIdType first, vtkIdType last)
    {
      for (int bz = static_cast<int>(first); bz < last; ++bz)
      {
        for (int z = bz * BrickSize; z < std::min(dims[2], (bz + 1) * BrickSize); ++z)
        {
          for (int y = 0; y < dims[1]; ++y)
          {
            const float* row = values.data() + (static_cast<size_t>(z) * dims[1] + y) * dims[0];
            const size_t brickRow = (static_cast<size_t>(bz) * b[1] + y / BrickSize) * b[0];
            for (int x = 0; x < dims[0]; ++x)
            {
              const size_t brick = brickRow + x / BrickSize;
              const float v = row[x];
              if (std::isnan(v))
              {
                this->Low[brick] = std::numeric_limits<float>::quiet_NaN();
              }
              else if (!std::isnan(this->Low[brick]))
              {
                this->Low[brick] = std::min(this->Low[brick], v);
                this->High[brick] = std::max(this->High[brick], v);
              }
            }
          }
        }
      }
    });
}

void VoxelOccupancy::Classify(const std::vector<float>& opacity)
{
  const int n = static_cast<int>(opacity.size());
  if (this->Occupied.empty())
  {
    return;
  }
  if (n < 2)
  {
    std::fill(this->Occupied.begin(), this->Occupied.end(), 1);
    return;
  }
  // positives[i]: entries before i that are positive or not finite.
  std::vector<int> positives(static_cast<size_t>(n) + 1, 0);
  for (int i = 0; i < n; ++i)
  {
    const float a = opacity[i];
    positives[i + 1] = positives[i] + ((a > 0.0f || !std::isfinite(a)) ? 1 : 0);
  }
  // Values in [low, high] read entries Entry(low) .. Entry(high) with a
  // positive weight, Entry(high) + 1 only where Weight(high) > 0, and skip
  // Entry(low) where Weight(low) = 1 (t = 1, the last entry): LookupTable's
  // (1 - f) table[i0] + f table[i0 + 1] (vtkTableLookup.h).
  for (size_t brick = 0; brick < this->Occupied.size(); ++brick)
  {
    const float low = this->Low[brick];
    if (std::isnan(low))
    {
      this->Occupied[brick] = 1;
      continue;
    }
    if (low > this->High[brick])
    {
      this->Occupied[brick] = 0; // no voxel (cannot happen on a full grid)
      continue;
    }
    const TablePosition from = LocateInTable(n, low);
    const TablePosition to = LocateInTable(n, this->High[brick]);
    const int first = from.Weight < 1.0f ? from.Entry : from.Entry + 1;
    const int last = to.Weight > 0.0f ? to.Entry + 1 : to.Entry;
    this->Occupied[brick] = positives[last + 1] > positives[first] ? 1 : 0;
  }
}

IndexBox VoxelOccupancy::Shrink(const IndexBox& box) const
{
  if (this->Occupied.empty() || box.IsEmpty())
  {
    return box;
  }
  const IndexBox within = box.Intersected(IndexBox::Whole(this->Dimensions));
  if (within.IsEmpty())
  {
    return within;
  }
  int first[3];
  int last[3];
  for (int a = 0; a < 3; ++a)
  {
    first[a] = within.Bounds[2 * a] / BrickSize;
    last[a] = within.Bounds[2 * a + 1] / BrickSize;
  }
  const int* b = this->Bricks;
  IndexBox occupied;
  for (int bz = first[2]; bz <= last[2]; ++bz)
  {
    for (int by = first[1]; by <= last[1]; ++by)
    {
      const size_t row = (static_cast<size_t>(bz) * b[1] + by) * b[0];
      for (int bx = first[0]; bx <= last[0]; ++bx)
      {
        if (!this->Occupied[row + bx])
        {
          continue;
        }
        const int brick[3] = { bx, by, bz };
        IndexBox voxels;
        for (int a = 0; a < 3; ++a)
        {
          voxels.Bounds[2 * a] = brick[a] * BrickSize;
          voxels.Bounds[2 * a + 1] = brick[a] * BrickSize + BrickSize - 1;
        }
        occupied = occupied.United(voxels);
      }
    }
  }
  return occupied.Intersected(within);
}

long long VoxelOccupancy::GetNumberOfOccupiedBricks() const
{
  return std::count(this->Occupied.begin(), this->Occupied.end(), 1);
}

} // namespace mmv
