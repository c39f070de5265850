// What a region of the irradiance grid depends on (vtkIrradianceRegion.h,
// mmv::PlanSweepBoxes of vtkShadowSweep.h): every voxel the piecewise
// shadow sweep reads on the way to a region, found by following the
// shader's reads one voxel at a time, lies in the box its chunk draws (for
// a directional light and for a point light beyond the grid); and
// the boxes stay small where the region allows. The GPU pass's region
// equals its whole grid bit for bit (TestIrradianceEstimator.cxx).
#include "vtkIrradianceRegion.h"
#include "vtkShadowSweep.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <set>
#include <string>
#include <vector>

namespace
{

using Voxel = std::array<int, 3>;

/// The slice voxels Shaders/mmvPiecewiseShadowFS.glsl's mmvSampleSlice
/// fetches for a ray from `v` toward `toLight` that reaches slice `plane`
/// (rays that leave the grid first read nothing: a superset is checked).
/// With `pointLight`, the ray runs toward that index-space position instead.
void SliceReads(const int dims[3], int axis, int plane, const Voxel& v, glm::dvec3 toLight,
  std::set<Voxel>& reads, const glm::dvec3* pointLight)
{
  if (pointLight)
  {
    toLight = *pointLight - glm::dvec3(v[0], v[1], v[2]);
  }
  const double distance = (plane - v[axis]) / toLight[axis];
  int low[3];
  int count[3] = { 1, 1, 1 };
  low[axis] = plane;
  for (int e = 0; e < 3; ++e)
  {
    if (e == axis)
    {
      continue;
    }
    const double q = v[e] + distance * toLight[e];
    const double x = std::min(std::max(q, 0.0), dims[e] - 1.0);
    low[e] = std::min(static_cast<int>(x), std::max(dims[e] - 2, 0));
    count[e] = dims[e] > 1 ? 2 : 1;
  }
  for (int i = 0; i < count[0]; ++i)
  {
    for (int j = 0; j < count[1]; ++j)
    {
      for (int k = 0; k < count[2]; ++k)
      {
        reads.insert({ low[0] + i, low[1] + j, low[2] + k });
      }
    }
  }
}

/// Follows the reads from `region` chunk by chunk toward the light and
/// checks that each needed voxel lies in its chunk's box. Returns the
/// number of voxels the boxes draw.
long long CheckSweepBoxes(const int dims[3], const glm::dvec3& toLight, int slicesPerChunk,
  const mmv::IndexBox& region, const glm::dvec3* pointLight = nullptr)
{
  const mmv::ShadowSweep sweep = mmv::PlanShadowSweep(dims, toLight, slicesPerChunk);
  const std::vector<mmv::IndexBox> boxes =
    mmv::PlanSweepBoxes(sweep, dims, toLight, region, nullptr, pointLight);
  EXPECT_EQ(static_cast<int>(boxes.size()), sweep.GetNumberOfChunks());
  std::set<Voxel> needed;
  for (int k = region.Bounds[4]; k <= region.Bounds[5]; ++k)
  {
    for (int j = region.Bounds[2]; j <= region.Bounds[3]; ++j)
    {
      for (int i = region.Bounds[0]; i <= region.Bounds[1]; ++i)
      {
        needed.insert({ i, j, k });
      }
    }
  }
  long long drawn = 0;
  for (int chunk = sweep.GetNumberOfChunks() - 1; chunk >= 0; --chunk)
  {
    int first, last, plane;
    sweep.GetChunk(chunk, first, last, plane);
    drawn += boxes[chunk].GetNumberOfVoxels();
    std::set<Voxel> reads;
    for (const Voxel& v : needed)
    {
      if (v[sweep.Axis] < first || v[sweep.Axis] > last)
      {
        continue;
      }
      EXPECT_TRUE(boxes[chunk].Contains(v.data()))
        << "chunk " << chunk << " misses voxel " << v[0] << " " << v[1] << " " << v[2];
      if (plane >= 0)
      {
        SliceReads(dims, sweep.Axis, plane, v, toLight, reads, pointLight);
      }
    }
    needed.insert(reads.begin(), reads.end());
  }
  return drawn;
}

/// A box between two random points of a `dims` grid.
mmv::IndexBox RandomBox(std::mt19937& random, const int dims[3])
{
  mmv::IndexBox box;
  for (int a = 0; a < 3; ++a)
  {
    std::uniform_int_distribution<int> index(0, dims[a] - 1);
    const int p = index(random);
    const int q = index(random);
    box.Bounds[2 * a] = std::min(p, q);
    box.Bounds[2 * a + 1] = std::max(p, q);
  }
  return box;
}

} // namespace

TEST(IrradianceRegion, SweepBoxesHoldEveryVoxelTheRegionReadsOnTheWayToTheLight)
{
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const std::vector<std::array<int, 3>> grids = { { 17, 13, 11 }, { 9, 1, 12 }, { 24, 24, 24 } };
  for (const auto& grid : grids)
  {
    for (int trial = 0; trial < 12; ++trial)
    {
      glm::dvec3 toLight(unit(random), unit(random), unit(random));
      if (trial < 3)
      {
        toLight = glm::dvec3(0.0);
        toLight[trial] = trial == 1 ? -1.0 : 1.0; // along an axis: no in-slice shift
      }
      const mmv::IndexBox region = RandomBox(random, grid.data());
      for (const int k : { 1, 3, 16 })
      {
        SCOPED_TRACE(::testing::Message() << "grid " << grid[0] << "x" << grid[1] << "x" << grid[2]
                                          << ", trial " << trial << ", K " << k);
        CheckSweepBoxes(grid.data(), toLight, k, region);
      }
    }
  }
}

// A point or spot light beyond the grid: the rays converge on it, and the
// boxes still hold every slice voxel they read.
TEST(IrradianceRegion, SweepBoxesHoldEveryVoxelTheRegionReadsTowardAPointLight)
{
  std::mt19937 random(11);
  const std::vector<std::array<int, 3>> grids = { { 17, 13, 11 }, { 9, 1, 12 }, { 24, 24, 24 } };
  for (const auto& grid : grids)
  {
    int swept = 0;
    for (int trial = 0; trial < 12; ++trial)
    {
      // Anywhere within three grid widths, most of it outside the grid.
      glm::dvec3 light;
      for (int a = 0; a < 3; ++a)
      {
        std::uniform_real_distribution<double> at(-3.0 * grid[a], 4.0 * grid[a]);
        light[a] = at(random);
      }
      const glm::dvec3 toLight = mmv::PointLightSweepDirection(grid.data(), light);
      if (toLight == glm::dvec3(0.0))
      {
        continue;
      }
      ++swept;
      const mmv::IndexBox region = RandomBox(random, grid.data());
      for (const int k : { 1, 3, 16 })
      {
        SCOPED_TRACE(::testing::Message()
          << "grid " << grid[0] << "x" << grid[1] << "x" << grid[2] << ", light " << light[0] << " "
          << light[1] << " " << light[2] << ", K " << k);
        CheckSweepBoxes(grid.data(), toLight, k, region, &light);
        CheckSweepBoxes(grid.data(), toLight, k, mmv::IndexBox::Whole(grid.data()), &light);
      }
    }
    EXPECT_GE(swept, 8);
  }
}

namespace
{
// A point light inside the grid: its pyramid sweeps (InsideLightSweeps),
// run over the boxes PlanSweepBoxes gives for `region` as the GPU runs them
// (a chunk computes its pyramid's voxels in its box). Every voxel lies in a
// pyramid, within its sweep's slices; every region voxel is computed; and
// every computed voxel's ray that reaches its plane inside the grid reads
// only texels an earlier chunk of the same sweep computed (its bilinear pair
// in the previous slice, clamped to SliceReadRange, as
// Shaders/mmvPiecewiseShadowFS.glsl reads them).
void CheckInsideLightSweeps(
  const int dims[3], const glm::dvec3& light, int slicesPerChunk, const mmv::IndexBox& region)
{
  const std::vector<mmv::ShadowSweep> sweeps = mmv::InsideLightSweeps(dims, light, slicesPerChunk);
  const vtkIdType n = static_cast<vtkIdType>(dims[0]) * dims[1] * dims[2];
  std::vector<int> pyramids(n, 0);
  auto id = [&](int i, int j, int k)
  { return i + dims[0] * (j + static_cast<vtkIdType>(dims[1]) * k); };
  for (const mmv::ShadowSweep& sweep : sweeps)
  {
    ASSERT_TRUE(sweep.Pyramid);
    std::vector<char> computed(n, 0);
    const int a = sweep.Axis;
    const std::vector<mmv::IndexBox> boxes =
      mmv::PlanSweepBoxes(sweep, dims, glm::dvec3(0.0), region, nullptr, &light);
    for (int chunk = 0; chunk < sweep.GetNumberOfChunks(); ++chunk)
    {
      int first, last, plane;
      sweep.GetChunk(chunk, first, last, plane);
      std::vector<vtkIdType> made;
      int v[3];
      for (v[2] = 0; v[2] < dims[2]; ++v[2])
      {
        for (v[1] = 0; v[1] < dims[1]; ++v[1])
        {
          for (v[0] = 0; v[0] < dims[0]; ++v[0])
          {
            const glm::vec3 voxel(v[0], v[1], v[2]);
            if (v[a] < first || v[a] > last || !mmv::InSweptPyramid(sweep, voxel))
            {
              continue;
            }
            ++pyramids[id(v[0], v[1], v[2])];
            if (!boxes[chunk].Contains(v))
            {
              ASSERT_FALSE(region.Contains(v))
                << "a region voxel left out, chunk " << chunk << " voxel " << v[0] << " " << v[1]
                << " " << v[2] << " axis " << a << " tp " << sweep.TowardPositive << " box "
                << boxes[chunk].Bounds[0] << "-" << boxes[chunk].Bounds[1] << " "
                << boxes[chunk].Bounds[2] << "-" << boxes[chunk].Bounds[3] << " "
                << boxes[chunk].Bounds[4] << "-" << boxes[chunk].Bounds[5] << " region "
                << region.Bounds[0] << "-" << region.Bounds[1] << " " << region.Bounds[2] << "-"
                << region.Bounds[3] << " " << region.Bounds[4] << "-" << region.Bounds[5];
              continue;
            }
            made.push_back(id(v[0], v[1], v[2]));
            if (plane < 0)
            {
              continue;
            }
            // Where the ray toward the light crosses the plane, and the
            // texels the read interpolates.
            const glm::dvec3 start(v[0], v[1], v[2]);
            const double t = (plane - start[a]) / (light[a] - start[a]);
            ASSERT_GT(t, 0.0);
            ASSERT_LE(t, 1.0);
            const glm::dvec3 q = start + t * (light - start);
            bool inside = true;
            for (int e = 0; e < 3; ++e)
            {
              inside = inside && q[e] >= -1e-9 && q[e] <= dims[e] - 1 + 1e-9;
            }
            int range[4];
            if (!inside || !mmv::SliceReadRange(sweep, plane, dims, range))
            {
              continue; // the ray leaves the grid first, or runs on to the light
            }
            int i0[3], i1[3];
            for (int k = 0; k < 3; ++k)
            {
              const int e = (a + k) % 3;
              if (k == 0)
              {
                i0[e] = i1[e] = plane;
                continue;
              }
              const int lo = range[2 * (k - 1)];
              const int hi = range[2 * (k - 1) + 1];
              const double x = std::min(std::max(q[e], double(lo)), double(hi));
              i0[e] = std::min(static_cast<int>(x), std::max(hi - 1, lo));
              i1[e] = hi > lo ? i0[e] + 1 : i0[e];
            }
            for (int k = i0[2]; k <= i1[2]; ++k)
            {
              for (int j = i0[1]; j <= i1[1]; ++j)
              {
                for (int i = i0[0]; i <= i1[0]; ++i)
                {
                  ASSERT_TRUE(computed[id(i, j, k)])
                    << "chunk " << chunk << " of the sweep along " << a << " reads " << i << " "
                    << j << " " << k << " before it is computed";
                }
              }
            }
          }
        }
      }
      for (const vtkIdType m : made)
      {
        computed[m] = 1;
      }
    }
  }
  EXPECT_EQ(std::count(pyramids.begin(), pyramids.end(), 0), 0) << "a voxel in no pyramid";
}
} // namespace

// A point light inside the grid sweeps six pyramids: on any grid, from any
// position inside it (on voxels, halfway between them, anywhere), for the
// whole grid and a region, every voxel, and every read already made.
TEST(IrradianceRegion, InsideLightPyramidsSweepEveryVoxelAndReadOnlyWhatIsMade)
{
  std::mt19937 random(5);
  const std::vector<std::array<int, 3>> grids = { { 17, 13, 11 }, { 24, 24, 24 }, { 9, 2, 12 } };
  for (const auto& grid : grids)
  {
    std::vector<glm::dvec3> lights = { glm::dvec3(4.0, 1.0, 5.0), glm::dvec3(4.5, 0.5, 5.5),
      glm::dvec3(0.0, 0.0, 0.0), glm::dvec3(grid[0] - 1.0, grid[1] - 1.0, 3.0),
      glm::dvec3(-0.4, 0.7, grid[2] - 0.6) };
    for (int trial = 0; trial < 6; ++trial)
    {
      glm::dvec3 light;
      for (int a = 0; a < 3; ++a)
      {
        std::uniform_real_distribution<double> at(-0.5, grid[a] - 0.5);
        light[a] = at(random);
      }
      lights.push_back(light);
    }
    for (const glm::dvec3& light : lights)
    {
      ASSERT_EQ(mmv::PointLightSweepDirection(grid.data(), light), glm::dvec3(0.0));
      const mmv::IndexBox region = RandomBox(random, grid.data());
      for (const int k : { 1, 3, 16 })
      {
        SCOPED_TRACE(::testing::Message()
          << "grid " << grid[0] << "x" << grid[1] << "x" << grid[2] << ", light " << light[0] << " "
          << light[1] << " " << light[2] << ", K " << k);
        CheckInsideLightSweeps(grid.data(), light, k, mmv::IndexBox::Whole(grid.data()));
        CheckInsideLightSweeps(grid.data(), light, k, region);
      }
    }
  }
}

// The axis a point light sweeps along: one it lies beyond (by more than half
// a voxel), the steepest for the grid's rays; none from within the grid.
TEST(IrradianceRegion, PointLightSweepsAlongTheSteepestAxisItLiesBeyond)
{
  const int dims[3] = { 10, 10, 10 };
  EXPECT_EQ(mmv::PointLightSweepDirection(dims, glm::dvec3(30.0, 4.0, 5.0)), glm::dvec3(1, 0, 0));
  EXPECT_EQ(mmv::PointLightSweepDirection(dims, glm::dvec3(4.0, -20.0, 5.0)), glm::dvec3(0, -1, 0));
  EXPECT_EQ(mmv::PointLightSweepDirection(dims, glm::dvec3(4.0, 4.0, 4.0)), glm::dvec3(0.0));
  EXPECT_EQ(mmv::PointLightSweepDirection(dims, glm::dvec3(4.0, 4.0, 9.4)), glm::dvec3(0.0));
  EXPECT_EQ(mmv::PointLightSweepDirection(dims, glm::dvec3(4.0, 4.0, 9.6)), glm::dvec3(0, 0, 1));
  // Beyond x by 6 and beyond z by 31: the rays cross z's slices at cos >= 0.89, x's at 0.15.
  EXPECT_EQ(mmv::PointLightSweepDirection(dims, glm::dvec3(15.0, 4.0, 40.0)), glm::dvec3(0, 0, 1));
  // Directional lights sweep toward themselves; full rays sweep nothing.
  mmv::LightSource point;
  point.Kind = mmv::PointLight;
  point.Position = glm::dvec3(3.0, 30.0, 4.0);
  const glm::dmat3 half(0.5); // index = (p - origin) / 2
  const glm::dvec3 origin(-2.0, 0.0, 0.0);
  // (3, 30, 4) is index (2.5, 15, 2): beyond y.
  EXPECT_EQ(mmv::ShadowSweepDirection(mmv::PiecewiseShadowRays, point, dims, half, origin),
    glm::dvec3(0, 1, 0));
  EXPECT_EQ(
    mmv::ShadowSweepDirection(mmv::FullShadowRays, point, dims, half, origin), glm::dvec3(0.0));
  mmv::LightSource directional;
  directional.ToLight = glm::dvec3(0.0, 0.6, 0.8);
  EXPECT_EQ(mmv::ShadowSweepDirection(mmv::PiecewiseShadowRays, directional, dims, half, origin),
    glm::dvec3(0.0, 0.3, 0.4));
}

TEST(IrradianceRegion, SweepBoxesOfAWholeGridAreItsSlabs)
{
  const int dims[3] = { 10, 12, 14 };
  const mmv::ShadowSweep sweep = mmv::PlanShadowSweep(dims, glm::dvec3(0.3, -0.2, 0.9), 4);
  const auto boxes =
    mmv::PlanSweepBoxes(sweep, dims, glm::dvec3(0.3, -0.2, 0.9), mmv::IndexBox::Whole(dims));
  ASSERT_EQ(boxes.size(), 4u);
  for (int chunk = 0; chunk < 4; ++chunk)
  {
    int first, last, plane;
    sweep.GetChunk(chunk, first, last, plane);
    const int slab[6] = { 0, 9, 0, 11, first, last };
    EXPECT_TRUE(std::equal(slab, slab + 6, boxes[chunk].Bounds)) << "chunk " << chunk;
  }
}

// The chunks tile the swept slices once, nearest the light first, each
// reading the slice just before it; every chunk but the first starts at a
// multiple of K in index order (the rasterizer's blocks), in both
// directions, from any first slice (a pyramid's) and for any K.
TEST(IrradianceRegion, SweepChunksTileTheSlicesAndStartAtMultiplesOfK)
{
  for (const bool towardPositive : { true, false })
  {
    for (const int first : { 0, 3, 17 })
    {
      for (const int slices : { 1, 5, 16, 37, 119 })
      {
        for (const int k : { 1, 3, 4, 16 })
        {
          mmv::ShadowSweep sweep;
          sweep.TowardPositive = towardPositive;
          sweep.First = first;
          sweep.Slices = slices;
          sweep.SlicesPerChunk = k;
          const std::string what = "toward +: " + std::to_string(towardPositive) + ", first " +
            std::to_string(first) + ", " + std::to_string(slices) + " slices, K " +
            std::to_string(k);
          std::vector<int> covered(slices, 0);
          int nearestPrevious = -1;
          for (int chunk = 0; chunk < sweep.GetNumberOfChunks(); ++chunk)
          {
            int lo, hi, plane;
            sweep.GetChunk(chunk, lo, hi, plane);
            ASSERT_LE(lo, hi) << what;
            EXPECT_LE(hi - lo + 1, k) << what;
            for (int slice = lo; slice <= hi; ++slice)
            {
              ASSERT_GE(slice - first, 0) << what;
              ASSERT_LT(slice - first, slices) << what;
              ++covered[slice - first];
            }
            // The slice nearest the light, and the one its rays end on.
            const int nearest = towardPositive ? hi : lo;
            EXPECT_EQ(plane, chunk == 0 ? -1 : nearestPrevious) << what << ", chunk " << chunk;
            EXPECT_EQ(plane, chunk == 0 ? -1 : nearest + (towardPositive ? 1 : -1)) << what;
            if (chunk > 0)
            {
              // Its side toward the light's end of the grid lies on a multiple of K.
              EXPECT_EQ((towardPositive ? hi + 1 : lo) % k, 0) << what << ", chunk " << chunk;
            }
            nearestPrevious = towardPositive ? lo : hi;
            EXPECT_EQ(sweep.GetReadSlice(chunk),
              chunk + 1 < sweep.GetNumberOfChunks() ? nearestPrevious : -1)
              << what;
          }
          EXPECT_TRUE(std::all_of(covered.begin(), covered.end(), [](int c) { return c == 1; }))
            << what;
        }
      }
    }
  }
}

// A quarter slab of a 64^3 grid: across the light, its chunks draw the slab
// and a margin; along it, the chunks upstream draw one slice each.
TEST(IrradianceRegion, ASlabAcrossOrAlongTheLightDrawsLittleMoreThanItself)
{
  const int dims[3] = { 64, 64, 64 };
  const mmv::IndexBox slab{ { 0, 63, 0, 63, 32, 47 } };
  const long long slabVoxels = slab.GetNumberOfVoxels();
  const long long whole = 64LL * 64 * 64;
  // Across: the light mostly along x, a little toward z.
  const long long across = CheckSweepBoxes(dims, glm::dvec3(1.0, 0.2, 0.1), 16, slab);
  EXPECT_LT(across, slabVoxels * 3 / 2);
  // Along: the light along +z, the slab two chunks from it.
  const long long along = CheckSweepBoxes(dims, glm::dvec3(0.1, 0.15, 1.0), 16, slab);
  EXPECT_LE(along, slabVoxels + 64LL * 64);
  EXPECT_LT(along, whole / 3);
}

TEST(IrradianceRegion, PieceBoxCoversItsPointsAndOneVoxelMore)
{
  mmv::IrradianceGrid grid;
  const int dims[3] = { 33, 17, 9 };
  std::copy(dims, dims + 3, grid.Dimensions);
  grid.DataVoxelsPerVoxel = glm::dvec3(2.0, 4.0, 1.0);
  // Points 20..41 of x, 0..63 of y, 3..5 of z.
  const double offset[3] = { 20.0, 0.0, 3.0 };
  const int piece[3] = { 22, 65, 3 };
  const mmv::IndexBox box = mmv::PieceIrradianceBox(grid, offset, piece);
  const int expected[6] = { 9, 22, 0, 16, 2, 6 };
  EXPECT_TRUE(std::equal(expected, expected + 6, box.Bounds))
    << box.Bounds[0] << " " << box.Bounds[1] << " " << box.Bounds[2] << " " << box.Bounds[3] << " "
    << box.Bounds[4] << " " << box.Bounds[5];
}

TEST(IrradianceRegion, DiffusionPlanReachesOneBlockFurtherPerPass)
{
  const int dims[3] = { 40, 40, 40 };
  mmv::DiffusionGrid coarse;
  for (int a = 0; a < 3; ++a)
  {
    coarse.Factor[a] = 4;
    coarse.Dimensions[a] = 10;
  }
  const mmv::IndexBox region{ { 16, 23, 0, 39, 0, 39 } };
  const mmv::IrradianceRegionPlan none = mmv::PlanIrradianceRegion(region, dims, nullptr, 0);
  const int source[6] = { 15, 24, 0, 39, 0, 39 };
  EXPECT_TRUE(std::equal(source, source + 6, none.Source.Bounds));
  EXPECT_TRUE(none.Estimated == none.Source);
  EXPECT_TRUE(none.Coarse.IsEmpty());
  // Source x 15..24: coarse coordinates (15 - 1.5) / 4 = 3.375 .. 5.625,
  // blocks 3..6 (floor and floor + 1), grown by the passes + 2.
  const mmv::IrradianceRegionPlan one = mmv::PlanIrradianceRegion(region, dims, &coarse, 1);
  EXPECT_EQ(one.Coarse.Bounds[0], 0);
  EXPECT_EQ(one.Coarse.Bounds[1], 9);
  const mmv::IrradianceRegionPlan zero = mmv::PlanIrradianceRegion(region, dims, &coarse, 0);
  EXPECT_EQ(zero.Coarse.Bounds[0], 1);
  EXPECT_EQ(zero.Coarse.Bounds[1], 8);
  EXPECT_EQ(zero.Estimated.Bounds[0], 4);  // block 1 starts at voxel 4
  EXPECT_EQ(zero.Estimated.Bounds[1], 35); // block 8 ends at voxel 35
  // A long solve reaches the whole grid: the halo is then everything.
  const mmv::IrradianceRegionPlan many = mmv::PlanIrradianceRegion(region, dims, &coarse, 40);
  EXPECT_TRUE(many.Estimated == mmv::IndexBox::Whole(dims));
}
