// The sky's visibility (Filters/vtkSkyVisibility.h) against closed forms: a
// furnace, a slab under a uniform sky (exponential integrals), a closed
// cavity, full shadow rays through a random medium, and the coarse grid's
// extinction.
#include "vtkSkyVisibility.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <limits>
#include <random>
#include <vector>

namespace
{

mmv::IrradianceGrid Grid(int nx, int ny, int nz, double spacing = 1.0)
{
  mmv::IrradianceGrid grid;
  grid.Dimensions[0] = nx;
  grid.Dimensions[1] = ny;
  grid.Dimensions[2] = nz;
  grid.Spacing = glm::dvec3(spacing);
  return grid;
}

size_t At(const mmv::IrradianceGrid& g, int x, int y, int z)
{
  return (static_cast<size_t>(z) * g.Dimensions[1] + y) * g.Dimensions[0] + x;
}

// E_n(t) = int_1^inf exp(-t u) / u^n du, by recurrence from E_1.
double E1(double t)
{
  return -std::expint(-t);
}
double E2(double t)
{
  return std::exp(-t) - t * E1(t);
}
double E3(double t)
{
  return 0.5 * (std::exp(-t) - t * E2(t));
}

} // namespace

TEST(EnvironmentLight, DirectionsComeInAntipodalPairsOfEqualWeight)
{
  for (int count : { 1, 2, 7, 16, 32, 64 })
  {
    const std::vector<glm::dvec3> d = mmv::SkyDirections(count);
    ASSERT_EQ(d.size() % 2, 0u);
    ASSERT_GE(static_cast<int>(d.size()), count);
    const size_t half = d.size() / 2;
    glm::dvec3 sum(0.0);
    glm::dmat3 second(0.0);
    for (size_t i = 0; i < d.size(); ++i)
    {
      EXPECT_NEAR(glm::length(d[i]), 1.0, 1e-12);
      if (i < half)
      {
        EXPECT_GT(d[i].z, 0.0);
        EXPECT_EQ(d[half + i], -d[i]);
      }
      sum += d[i];
      second += glm::outerProduct(d[i], d[i]);
    }
    EXPECT_NEAR(glm::length(sum), 0.0, 1e-12);
    // The second moment that the shading of surfaces takes as isotropic
    // (S0 / 3 per axis): within 2 % from 64 directions on (32: 6 %).
    if (count >= 64)
    {
      for (int a = 0; a < 3; ++a)
      {
        EXPECT_NEAR(second[a][a] / d.size(), 1.0 / 3.0, 0.02 / 3.0) << count << " axis " << a;
      }
    }
  }
}

TEST(EnvironmentLight, FurnaceGivesEveryVoxelTheWholeSky)
{
  // No extinction anywhere: S0 = 4 pi and S1 = 0 at every voxel, on a grid
  // with a non-axis direction matrix and unequal spacing.
  mmv::IrradianceGrid grid = Grid(9, 7, 5);
  grid.Spacing = glm::dvec3(1.0, 2.0, 0.5);
  const double c = std::cos(0.4), s = std::sin(0.4);
  grid.Direction = glm::dmat3(glm::dvec3(c, s, 0.0), glm::dvec3(-s, c, 0.0), glm::dvec3(0, 0, 1));
  const std::vector<float> extinction(grid.GetNumberOfVoxels(), 0.0f);
  std::vector<float> moments;
  mmv::ComputeSkyVisibility(grid, extinction.data(), mmv::SkyDirections(32), moments);
  ASSERT_EQ(moments.size(), extinction.size() * mmv::SkyMomentsPerVoxel);
  for (size_t v = 0; v < extinction.size(); ++v)
  {
    EXPECT_NEAR(moments[4 * v], 4.0 * M_PI, 1e-5);
    for (int a = 1; a < 4; ++a)
    {
      EXPECT_NEAR(moments[4 * v + a], 0.0, 1e-5);
    }
  }
}

TEST(EnvironmentLight, SlabUnderUniformSkyMatchesExponentialIntegrals)
{
  // A voxel on the floor of a wide homogeneous slab of optical depth tau:
  // the upper hemisphere sees the sky through tau / mu, the lower one
  // unoccluded. Closed form: S0 = 2 pi (1 + E2(tau)), S1.z = 2 pi E3(tau) - pi.
  // The sweep is checked against the same directions' exact transmittance,
  // and the directions' quadrature against the closed form.
  const int height = 8;
  const mmv::IrradianceGrid grid = Grid(121, 121, height + 1);
  for (double tau : { 0.5, 1.0, 3.0 })
  {
    const double s0 = 2.0 * M_PI * (1.0 + E2(tau));
    const double s1 = 2.0 * M_PI * E3(tau) - M_PI;
    for (int count : { 64, 1024 })
    {
      const std::vector<glm::dvec3> directions = mmv::SkyDirections(count);
      const double weight = 4.0 * M_PI / directions.size();
      glm::dvec4 exact(0.0);
      for (const glm::dvec3& w : directions)
      {
        const double t = w.z > 0.0 ? std::exp(-tau / w.z) : 1.0;
        exact += weight * t * glm::dvec4(1.0, w);
      }
      // The quadrature: 1 % of the whole sky at 64 directions, 0.2 % at 1024.
      const double quadrature = (count == 64 ? 0.01 : 0.002) * 4.0 * M_PI;
      EXPECT_NEAR(exact[0], s0, quadrature) << "tau " << tau << ", " << count;
      EXPECT_NEAR(exact[3], s1, quadrature) << "tau " << tau << ", " << count;
      if (count != 64)
      {
        continue; // the sweep's cost grows with the directions
      }
      const std::vector<float> extinction(
        grid.GetNumberOfVoxels(), static_cast<float>(tau / height));
      std::vector<float> moments;
      mmv::ComputeSkyVisibility(grid, extinction.data(), directions, moments);
      // Rays that leave through a side (grazing ones, 60 voxels away) see
      // slightly more sky than the infinite slab: within 0.5 % of the sky.
      const size_t floor = At(grid, 60, 60, 0);
      for (int m = 0; m < 4; ++m)
      {
        EXPECT_NEAR(moments[4 * floor + m], exact[m], 0.005 * 4.0 * M_PI)
          << "tau " << tau << " moment " << m;
      }
      // The slab's top: the mirror image.
      const size_t top = At(grid, 60, 60, height);
      EXPECT_NEAR(moments[4 * top], exact[0], 0.005 * 4.0 * M_PI);
      EXPECT_NEAR(moments[4 * top + 3], -exact[3], 0.005 * 4.0 * M_PI);
    }
  }
}

TEST(EnvironmentLight, CavityInsideAnOpaqueShellSeesNoSky)
{
  // A hollow cube inside a shell 3 voxels thick of optical depth 30 across
  // it: the cavity is occluded, the outside is not.
  mmv::IrradianceGrid grid = Grid(24, 24, 24);
  std::vector<float> extinction(grid.GetNumberOfVoxels(), 0.0f);
  for (int z = 0; z < 24; ++z)
  {
    for (int y = 0; y < 24; ++y)
    {
      for (int x = 0; x < 24; ++x)
      {
        const int inset = std::min({ x, y, z, 23 - x, 23 - y, 23 - z });
        extinction[At(grid, x, y, z)] = inset >= 5 && inset < 8 ? 10.0f : 0.0f;
      }
    }
  }
  std::vector<float> moments;
  mmv::ComputeSkyVisibility(grid, extinction.data(), mmv::SkyDirections(32), moments);
  EXPECT_LT(moments[4 * At(grid, 12, 12, 12)], 1e-3 * 4.0 * M_PI);
  EXPECT_LT(moments[4 * At(grid, 9, 14, 10)], 1e-3 * 4.0 * M_PI);
  // A corner outside the shell sees at least the octant facing away.
  EXPECT_GT(moments[4 * At(grid, 0, 0, 0)], 0.5 * 4.0 * M_PI);
  // Beside the shell's face, the half-space away from it is open: S1
  // points away from the shell (-x).
  const size_t beside = At(grid, 2, 12, 12);
  EXPECT_GT(moments[4 * beside], 0.5 * 4.0 * M_PI);
  EXPECT_LT(moments[4 * beside + 1], -0.5);
}

TEST(EnvironmentLight, SweepMatchesFullShadowRaysInASmoothMedium)
{
  // A smooth random medium of optical depth about 2 across: the slice sweep
  // against rays marched at 1/32 voxel with trilinear extinction, for
  // oblique directions. The sweep's error is its in-slice interpolation.
  mmv::IrradianceGrid grid = Grid(20, 18, 16);
  std::vector<float> extinction(grid.GetNumberOfVoxels());
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> phase(0.0, 6.28);
  const double p1 = phase(rng), p2 = phase(rng), p3 = phase(rng);
  for (int z = 0; z < 16; ++z)
  {
    for (int y = 0; y < 18; ++y)
    {
      for (int x = 0; x < 20; ++x)
      {
        extinction[At(grid, x, y, z)] = static_cast<float>(0.1 *
          (1.0 + 0.9 * std::sin(0.4 * x + p1) * std::cos(0.3 * y + p2) * std::sin(0.5 * z + p3)));
      }
    }
  }
  auto sample = [&](glm::dvec3 p)
  {
    int i[3];
    double f[3];
    for (int a = 0; a < 3; ++a)
    {
      i[a] = std::min(static_cast<int>(p[a]), grid.Dimensions[a] - 2);
      f[a] = p[a] - i[a];
    }
    double s = 0.0;
    for (int c = 0; c < 8; ++c)
    {
      const int dx = c & 1, dy = (c >> 1) & 1, dz = c >> 2;
      s += (dx ? f[0] : 1 - f[0]) * (dy ? f[1] : 1 - f[1]) * (dz ? f[2] : 1 - f[2]) *
        extinction[At(grid, i[0] + dx, i[1] + dy, i[2] + dz)];
    }
    return s;
  };
  for (const glm::dvec3& w : { glm::normalize(glm::dvec3(0.3, -0.2, 1.0)),
         glm::normalize(glm::dvec3(-1.0, 0.6, 0.4)), glm::normalize(glm::dvec3(0.5, 1.0, -0.7)) })
  {
    std::vector<float> t;
    mmv::SweepSkyTransmittance(grid, extinction.data(), w, t);
    double worst = 0.0;
    double sum = 0.0;
    int count = 0;
    for (int z = 0; z < 16; ++z)
    {
      for (int y = 0; y < 18; ++y)
      {
        for (int x = 0; x < 20; ++x)
        {
          glm::dvec3 p(x, y, z);
          double depth = 0.0;
          const double h = 1.0 / 16.0;
          auto inside = [&](const glm::dvec3& q)
          { return q.x >= 0 && q.y >= 0 && q.z >= 0 && q.x <= 19 && q.y <= 17 && q.z <= 15; };
          while (inside(p + h * w))
          {
            depth += h * 0.5 * (sample(p) + sample(p + h * w));
            p += h * w;
          }
          const double error = std::abs(t[At(grid, x, y, z)] - std::exp(-depth));
          worst = std::max(worst, error);
          sum += error;
          ++count;
        }
      }
    }
    // Measured: mean 0.004-0.006, worst 0.05-0.11 (rays that leave through
    // a side within 8 steps are marched; the rest interpolate, and the
    // worst voxels are those whose neighbours' rays leave soon after: the
    // scheme's numerical diffusion).
    EXPECT_LT(sum / count, 0.008) << w.x << " " << w.y << " " << w.z;
    EXPECT_LT(worst, 0.12) << w.x << " " << w.y << " " << w.z;
  }
}

TEST(EnvironmentLight, CoarseGridAveragesTheExtinctionOfThinStructures)
{
  // A plane one voxel thick keeps its mean extinction on a grid 4x coarser,
  // and the coarse grid spans the fine grid's box.
  mmv::IrradianceGrid fine = Grid(33, 17, 9, 0.5);
  fine.Origin = glm::dvec3(1.0, -2.0, 3.0);
  const mmv::IrradianceGrid coarse = mmv::CoarsenIrradianceGrid(fine, 4);
  EXPECT_EQ(coarse.Dimensions[0], 9);
  EXPECT_EQ(coarse.Dimensions[1], 5);
  EXPECT_EQ(coarse.Dimensions[2], 3);
  const glm::dvec3 last(32, 16, 8);
  const glm::dvec3 coarseLast(8, 4, 2);
  EXPECT_NEAR(
    glm::length(fine.IndexToPhysical(last) - coarse.IndexToPhysical(coarseLast)), 0.0, 1e-12);
  std::vector<float> values(fine.GetNumberOfVoxels(), 0.0f);
  for (int z = 0; z < 9; ++z)
  {
    for (int y = 0; y < 17; ++y)
    {
      values[At(fine, 16, y, z)] = 0.5f; // the plane x = 16
    }
  }
  // Through a table: value v reads extinction 8 v.
  const std::vector<float> table = { 0.0f, 8.0f };
  std::vector<float> mean;
  mmv::AverageOntoGrid(fine, values.data(), coarse, mean, &table);
  ASSERT_EQ(mean.size(), static_cast<size_t>(coarse.GetNumberOfVoxels()));
  // Coarse x = 4 gathers fine x 14..17 (the nearest, halves rounded up:
  // 18 * 8 / 32 = 4.5 goes to 5): extinction 4 on one of four columns.
  EXPECT_NEAR(mean[At(coarse, 4, 2, 1)], 1.0, 1e-6);
  EXPECT_EQ(mean[At(coarse, 3, 2, 1)], 0.0f);
  double total = 0.0;
  for (float m : mean)
  {
    total += m;
  }
  EXPECT_GT(total, 0.0);
}

TEST(EnvironmentLight, NonFiniteAndNegativeExtinctionAbsorbNothing)
{
  mmv::IrradianceGrid grid = Grid(6, 6, 6);
  std::vector<float> extinction(grid.GetNumberOfVoxels(), 0.0f);
  extinction[At(grid, 2, 3, 3)] = std::nanf("");
  extinction[At(grid, 3, 3, 3)] = -5.0f;
  std::vector<float> moments;
  mmv::ComputeSkyVisibility(grid, extinction.data(), mmv::SkyDirections(16), moments);
  for (size_t v = 0; v < extinction.size(); ++v)
  {
    ASSERT_NEAR(moments[4 * v], 4.0 * M_PI, 1e-5);
  }
}

TEST(EnvironmentLight, SixtyFourDirectionsAreEnoughForAHomogeneousCube)
{
  // S0 along the central line of a cube of optical depth 1 (17^3 points):
  // the sweep with K directions against exact exit distances over 20 000
  // directions. The error falls with K; 64 (mmv::SkyDirectionCount) is
  // within 1 % of the whole sky everywhere on the line.
  const mmv::IrradianceGrid grid = Grid(17, 17, 17);
  const std::vector<float> extinction(grid.GetNumberOfVoxels(), 1.0f / 16.0f);
  const std::vector<glm::dvec3> many = mmv::SkyDirections(20000);
  std::vector<double> exact(17);
  for (int z = 0; z < 17; ++z)
  {
    const glm::dvec3 p(8.0, 8.0, z);
    double sum = 0.0;
    for (const glm::dvec3& w : many)
    {
      double t = std::numeric_limits<double>::infinity();
      for (int a = 0; a < 3; ++a)
      {
        if (w[a] != 0.0)
        {
          t = std::min(t, ((w[a] > 0.0 ? 16.0 : 0.0) - p[a]) / w[a]);
        }
      }
      sum += std::exp(-t / 16.0);
    }
    exact[z] = 4.0 * M_PI * sum / many.size();
  }
  double previous = 1.0;
  for (int count : { 8, 16, 32, mmv::SkyDirectionCount, 128 })
  {
    std::vector<float> moments;
    mmv::ComputeSkyVisibility(grid, extinction.data(), mmv::SkyDirections(count), moments);
    double worst = 0.0;
    for (int z = 0; z < 17; ++z)
    {
      worst = std::max(worst, std::abs(moments[4 * At(grid, 8, 8, z)] - exact[z]) / (4.0 * M_PI));
    }
    std::cout << count << " directions: largest S0 error " << worst << " of the sky\n";
    if (count >= mmv::SkyDirectionCount)
    {
      EXPECT_LT(worst, 0.01) << count;
    }
    if (count == 8)
    {
      EXPECT_GT(worst, 0.01); // too few: the quadrature shows
    }
    previous = worst;
  }
  EXPECT_LT(previous, 0.01);
}

TEST(EnvironmentLight, StrengthsAreCheckedWithAReason)
{
  std::string why;
  EXPECT_EQ(mmv::ValidEnvironmentLighting(0.0, &why), 0.0);
  EXPECT_EQ(mmv::ValidEnvironmentLighting(2.5, &why), 2.5);
  EXPECT_TRUE(why.empty());
  for (double bad : { -1.0, std::nan(""), std::numeric_limits<double>::infinity(),
         -std::numeric_limits<double>::infinity() })
  {
    why.clear();
    EXPECT_EQ(mmv::ValidEnvironmentLighting(bad, &why), 0.0) << bad;
    EXPECT_NE(why.find("EnvironmentLighting"), std::string::npos) << bad;
  }
  why.clear();
  EXPECT_EQ(mmv::ValidEnvironmentLighting(1e30, &why), mmv::MaxEnvironmentLighting);
  EXPECT_NE(why.find("largest"), std::string::npos);
}
