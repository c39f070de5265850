// The bricks that may hold non-empty voxels (Filters/vtkVoxelOccupancy.h):
// the box Shrink returns holds every voxel of the query box whose value the
// estimator's lookup maps to a positive opacity and lies inside the query
// box; checked voxel by voxel against that lookup on random volumes and
// tables, and in closed form for one voxel.
#include "vtkVoxelOccupancy.h"

#include "vtkTableLookup.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace
{

/// The smallest box of the non-empty voxels inside `box`, voxel by voxel.
mmv::IndexBox NonEmptyVoxels(const std::vector<float>& values, const int dims[3],
  const std::vector<float>& table, const mmv::IndexBox& box)
{
  mmv::IndexBox found;
  for (int z = box.Bounds[4]; z <= box.Bounds[5]; ++z)
  {
    for (int y = box.Bounds[2]; y <= box.Bounds[3]; ++y)
    {
      for (int x = box.Bounds[0]; x <= box.Bounds[1]; ++x)
      {
        if (mmv::LookupTable(table, values[(static_cast<size_t>(z) * dims[1] + y) * dims[0] + x]) >
          0.0f)
        {
          found = found.United(mmv::IndexBox{ { x, x, y, y, z, z } });
        }
      }
    }
  }
  return found;
}

bool Contains(const mmv::IndexBox& outer, const mmv::IndexBox& inner)
{
  return inner.IsEmpty() || outer.United(inner) == outer;
}

} // namespace

TEST(VoxelOccupancy, ShrunkBoxesHoldEveryNonEmptyVoxelOfTheQueryBox)
{
  std::mt19937 random(7);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const int dims[3] = { 37, 22, 19 };
  const size_t voxels = static_cast<size_t>(dims[0]) * dims[1] * dims[2];
  int shrunk = 0;
  for (int trial = 0; trial < 20; ++trial)
  {
    // Sparse thin structures: most voxels low, a few sheets and rods high.
    std::vector<float> values(voxels);
    const int sheet = static_cast<int>(unit(random) * dims[2]);
    const int rod = static_cast<int>(unit(random) * dims[1]);
    for (size_t v = 0; v < voxels; ++v)
    {
      const int x = static_cast<int>(v % dims[0]);
      const int y = static_cast<int>((v / dims[0]) % dims[1]);
      const int z = static_cast<int>(v / (static_cast<size_t>(dims[0]) * dims[1]));
      const bool high = z == sheet || (y == rod && x > 20) || unit(random) < 0.002f;
      values[v] = high ? 0.5f + 0.5f * unit(random) : 0.3f * unit(random);
    }
    // Tables of 64 entries, zero below a random threshold, and some
    // isolated positive entries.
    std::vector<float> table(64, 0.0f);
    const int threshold = 20 + static_cast<int>(unit(random) * 40);
    for (int i = threshold; i < 64; ++i)
    {
      table[i] = unit(random);
    }
    if (trial % 3 == 0)
    {
      table[static_cast<int>(unit(random) * 19)] = 0.5f;
    }
    mmv::VoxelOccupancy occupancy;
    occupancy.SetValues(values, dims);
    occupancy.Classify(table);
    for (int query = 0; query < 10; ++query)
    {
      mmv::IndexBox box;
      for (int a = 0; a < 3; ++a)
      {
        int lo = static_cast<int>(unit(random) * dims[a]);
        int hi = static_cast<int>(unit(random) * dims[a]);
        box.Bounds[2 * a] = std::min(lo, hi);
        box.Bounds[2 * a + 1] = std::max(lo, hi);
      }
      if (query == 0)
      {
        box = mmv::IndexBox::Whole(dims);
      }
      const mmv::IndexBox exact = NonEmptyVoxels(values, dims, table, box);
      const mmv::IndexBox kept = occupancy.Shrink(box);
      ASSERT_TRUE(Contains(box, kept)) << "trial " << trial;
      ASSERT_TRUE(Contains(kept, exact)) << "trial " << trial << ": a non-empty voxel was cut";
      // Conservative (value ranges of whole bricks, one table entry more on
      // each side): the kept box may reach past the non-empty voxels.
      shrunk += kept.GetNumberOfVoxels() < box.GetNumberOfVoxels() ? 1 : 0;
    }
  }
  EXPECT_GT(shrunk, 50) << "the boxes hardly ever shrank";
}

TEST(VoxelOccupancy, OneNonEmptyVoxelKeepsItsBrick)
{
  const int dims[3] = { 21, 10, 30 };
  std::vector<float> values(static_cast<size_t>(dims[0]) * dims[1] * dims[2], 0.1f);
  values[(static_cast<size_t>(22) * dims[1] + 5) * dims[0] + 13] = 0.9f;
  std::vector<float> table(32, 0.0f);
  std::fill(table.begin() + 24, table.end(), 0.4f);
  mmv::VoxelOccupancy occupancy;
  occupancy.SetValues(values, dims);
  occupancy.Classify(table);
  EXPECT_EQ(occupancy.GetNumberOfOccupiedBricks(), 1);
  EXPECT_EQ(occupancy.GetNumberOfBricks(), 6 * 3 * 8);
  // Voxel (13, 5, 22) lies in brick (3, 1, 5): voxels 12-15, 4-7, 20-23.
  EXPECT_EQ(
    occupancy.Shrink(mmv::IndexBox::Whole(dims)), (mmv::IndexBox{ { 12, 15, 4, 7, 20, 23 } }));
  // Within a query box the brick is cut to it; a box beside it keeps nothing.
  EXPECT_EQ(occupancy.Shrink(mmv::IndexBox{ { 13, 20, 0, 9, 21, 21 } }),
    (mmv::IndexBox{ { 13, 15, 4, 7, 21, 21 } }));
  EXPECT_TRUE(occupancy.Shrink(mmv::IndexBox{ { 0, 11, 0, 9, 0, 29 } }).IsEmpty());
  // A table positive everywhere keeps every voxel; one that is zero
  // everywhere keeps none.
  occupancy.Classify(std::vector<float>(32, 0.1f));
  EXPECT_EQ(occupancy.Shrink(mmv::IndexBox::Whole(dims)), mmv::IndexBox::Whole(dims));
  occupancy.Classify(std::vector<float>(32, 0.0f));
  EXPECT_TRUE(occupancy.Shrink(mmv::IndexBox::Whole(dims)).IsEmpty());
}

TEST(VoxelOccupancy, NaNValuesAndTablesKeepTheirBricks)
{
  const int dims[3] = { 8, 8, 8 };
  std::vector<float> values(512, 0.0f);
  values[0] = std::numeric_limits<float>::quiet_NaN();
  std::vector<float> table(16, 0.0f);
  table[15] = 1.0f;
  mmv::VoxelOccupancy occupancy;
  occupancy.SetValues(values, dims);
  occupancy.Classify(table);
  EXPECT_EQ(occupancy.Shrink(mmv::IndexBox::Whole(dims)), (mmv::IndexBox{ { 0, 3, 0, 3, 0, 3 } }));
  // A NaN entry may be positive for all this knows: every brick reading it
  // (every value 0 reads entry 0) stays.
  table.assign(16, 0.0f);
  table[0] = std::numeric_limits<float>::quiet_NaN();
  occupancy.Classify(table);
  EXPECT_EQ(occupancy.Shrink(mmv::IndexBox::Whole(dims)), mmv::IndexBox::Whole(dims));
}

TEST(VoxelOccupancy, WithoutValuesBoxesStayWhole)
{
  mmv::VoxelOccupancy occupancy;
  const mmv::IndexBox box{ { 1, 5, 2, 6, 3, 7 } };
  EXPECT_EQ(occupancy.Shrink(box), box);
  const int dims[3] = { 4, 4, 4 };
  occupancy.SetValues(std::vector<float>(10, 0.0f), dims); // not 4^3 values
  occupancy.Classify(std::vector<float>(8, 0.0f));
  EXPECT_EQ(occupancy.Shrink(box), box);
}
