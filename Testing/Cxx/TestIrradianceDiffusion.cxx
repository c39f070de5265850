// Properties of mmv::DiffuseIrradiance (Zhang & Ma eq. 15): conservation,
// the discrete maximum principle, insulation by s = 0 and closed-form spread.
#include "vtkBlockDiffusionSeries.h"
#include "vtkDiffusionGridTransfer.h"
#include "vtkIrradianceDiffusion.h"
#include "vtkIrradianceGrid.h"
#include "vtkMultiMaterialParameters.h"
#include "vtkMultiMaterialThreads.h"

#include "vtkSMPTools.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>
#include <random>
#include <vector>

namespace
{

struct Field
{
  int Dims[3];
  double Spacing[3] = { 1.0, 1.0, 1.0 };
  std::vector<float> Strength;
  std::vector<float> Irradiance;

  Field(int nx, int ny, int nz)
    : Dims{ nx, ny, nz }
    , Strength(static_cast<size_t>(nx) * ny * nz, 0.0f)
    , Irradiance(static_cast<size_t>(nx) * ny * nz, 0.0f)
  {
  }
  size_t Index(int i, int j, int k) const
  {
    return static_cast<size_t>(i) +
      static_cast<size_t>(Dims[0]) * (j + static_cast<size_t>(Dims[1]) * k);
  }
  mmv::DiffusionReport Diffuse(const mmv::DiffusionSettings& settings = mmv::DiffusionSettings())
  {
    return mmv::DiffuseIrradiance(Dims, Spacing, Strength.data(), Irradiance.data(), settings);
  }
};

double Sum(const std::vector<float>& v)
{
  return std::accumulate(v.begin(), v.end(), 0.0);
}

/// Random field in [0, 1] and a strength that is `s` on ~80% of the voxels and
/// 0 elsewhere (empty space inside the material).
Field RandomField(double s, int nx = 18, int ny = 14, int nz = 11)
{
  Field f(nx, ny, nz);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (size_t v = 0; v < f.Irradiance.size(); ++v)
  {
    f.Irradiance[v] = unit(rng);
    f.Strength[v] = unit(rng) < 0.8f ? static_cast<float>(s) : 0.0f;
  }
  return f;
}

/// Variance (in index units) of a 1-D profile along x.
double VarianceAlongX(const Field& f)
{
  double m0 = 0.0, m1 = 0.0, m2 = 0.0;
  for (int i = 0; i < f.Dims[0]; ++i)
  {
    const double w = f.Irradiance[f.Index(i, 0, 0)];
    m0 += w;
    m1 += w * i;
    m2 += w * i * i;
  }
  const double mean = m1 / m0;
  return m2 / m0 - mean * mean;
}

class DiffusionStrength : public ::testing::TestWithParam<double>
{
};

} // namespace

TEST_P(DiffusionStrength, ConservesSumAndHonoursMaximumPrinciple)
{
  // Both integrators: backward Euler (CG) and the exponential's series.
  const double s = GetParam();
  for (const bool exponential : { false, true })
  {
    SCOPED_TRACE(exponential ? "exponential" : "backward Euler");
    Field f = RandomField(s);
    const std::vector<float> before = f.Irradiance;
    const double sum0 = Sum(before);
    const float max0 = *std::max_element(before.begin(), before.end());
    const float min0 = *std::min_element(before.begin(), before.end());

    mmv::DiffusionSettings settings;
    settings.Exponential = exponential;
    const mmv::DiffusionReport report = f.Diffuse(settings);

    EXPECT_EQ(report.Skipped, s == 0.0);
    EXPECT_LE(report.FinalResidual, 1.0e-7);
    const double sum1 = Sum(f.Irradiance);
    EXPECT_NEAR(sum1, sum0, 1.0e-6 * sum0);
    for (size_t v = 0; v < f.Irradiance.size(); ++v)
    {
      const float x = f.Irradiance[v];
      ASSERT_TRUE(std::isfinite(x)) << "voxel " << v;
      ASSERT_LE(x, max0 * (1.0 + 1.0e-6)) << "voxel " << v;
      ASSERT_GE(x, min0 - 1.0e-6 * max0) << "voxel " << v;
      if (f.Strength[v] == 0.0f)
      {
        // Harmonic-mean faces: a voxel with s = 0 exchanges nothing.
        ASSERT_EQ(x, before[v]) << "voxel " << v;
      }
    }
    if (s > 0.0)
    {
      // Something must actually have diffused.
      double change = 0.0;
      for (size_t v = 0; v < before.size(); ++v)
      {
        change = std::max(change, std::abs(static_cast<double>(f.Irradiance[v]) - before[v]));
      }
      EXPECT_GT(change, 0.05);
      EXPECT_GT(report.Iterations, 0);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Strengths, DiffusionStrength, ::testing::Values(0.0, 1.0, 20.0, 1000.0));

TEST(IrradianceDiffusion, ZeroStrengthWallInsulates)
{
  // Two halves separated by a plane of s = 0: each half keeps its own total
  // and, for huge s, becomes uniform.
  Field f(20, 6, 5);
  for (int k = 0; k < 5; ++k)
  {
    for (int j = 0; j < 6; ++j)
    {
      for (int i = 0; i < 20; ++i)
      {
        const size_t v = f.Index(i, j, k);
        f.Strength[v] = i == 10 ? 0.0f : 1000.0f;
        f.Irradiance[v] = i < 10 ? static_cast<float>(j + k) : (i == 3 * j ? 5.0f : 0.0f);
      }
    }
  }
  auto halfSum = [&](int begin, int end)
  {
    double sum = 0.0;
    for (int k = 0; k < 5; ++k)
      for (int j = 0; j < 6; ++j)
        for (int i = begin; i < end; ++i)
          sum += f.Irradiance[f.Index(i, j, k)];
    return sum;
  };
  const double left0 = halfSum(0, 10), right0 = halfSum(11, 20);
  mmv::DiffusionSettings settings;
  settings.Time = 10.0;
  f.Diffuse(settings);
  EXPECT_NEAR(halfSum(0, 10), left0, 1.0e-6 * left0);
  EXPECT_NEAR(halfSum(11, 20), right0, 1.0e-6 * right0);
  const double leftMean = left0 / 300.0;
  EXPECT_NEAR(f.Irradiance[f.Index(0, 0, 0)], leftMean, 1.0e-3 * leftMean);
  EXPECT_NEAR(f.Irradiance[f.Index(9, 5, 4)], leftMean, 1.0e-3 * leftMean);
}

TEST(IrradianceDiffusion, DeltaSpreadsWithVarianceTwoST)
{
  // Backward Euler with a conservative symmetric stencil adds exactly
  // 2*s*dt/h^2 to the variance per step (summation by parts), whatever the
  // number of sub-steps, as long as the tails stay off the boundaries.
  for (const double h : { 1.0, 0.5 })
  {
    for (const int maxSubSteps : { 1, 8 })
    {
      Field f(161, 1, 1);
      f.Spacing[0] = h;
      const double s = 2.0;
      std::fill(f.Strength.begin(), f.Strength.end(), static_cast<float>(s));
      f.Irradiance[80] = 1.0f;
      mmv::DiffusionSettings settings;
      settings.Time = 1.5;
      settings.MaxSubSteps = maxSubSteps;
      settings.Tolerance = 1.0e-10;
      const mmv::DiffusionReport report = f.Diffuse(settings);
      const double expected = 2.0 * s * settings.Time / (h * h);
      EXPECT_NEAR(VarianceAlongX(f), expected, 1.0e-5 * expected)
        << "h = " << h << ", sub-steps " << report.SubSteps;
      EXPECT_NEAR(Sum(f.Irradiance), 1.0, 1.0e-6);
    }
  }
}

TEST(IrradianceDiffusion, StepMatchesErfProfile)
{
  // A step on a bar (zero flux at both ends, far away) against the
  // continuous solution 0.5*erfc(x / (2*sqrt(s*T))). s = 25 voxel^2 spreads
  // the front over ~10 voxels. Sub-steps: min(MaxSubSteps, ceil(T * 2s)) =
  // 8 or 50. Measured max error: 8 steps 0.0092 (time error dominates),
  // 50 steps 0.0020 (mostly the grid's).
  const double s = 25.0;
  for (const int maxSubSteps : { 8, 64 })
  {
    Field f(200, 1, 1);
    std::fill(f.Strength.begin(), f.Strength.end(), static_cast<float>(s));
    for (int i = 0; i < 100; ++i)
    {
      f.Irradiance[i] = 1.0f;
    }
    mmv::DiffusionSettings settings;
    settings.Exponential = false;
    settings.MaxSubSteps = maxSubSteps;
    settings.Tolerance = 1.0e-10;
    const mmv::DiffusionReport report = f.Diffuse(settings);
    EXPECT_EQ(report.SubSteps, std::min(maxSubSteps, 50));
    double maxError = 0.0;
    for (int i = 0; i < 200; ++i)
    {
      const double x = i - 99.5; // the step sits between voxels 99 and 100
      const double exact = 0.5 * std::erfc(x / (2.0 * std::sqrt(s * settings.Time)));
      maxError = std::max(maxError, std::abs(f.Irradiance[i] - exact));
    }
    EXPECT_LT(maxError, maxSubSteps == 8 ? 0.012 : 0.003) << report.SubSteps << " sub-steps";
  }
}

TEST(IrradianceDiffusion, ExponentialMatchesErfProfileWithoutTimeError)
{
  // The same step as above with the exponential integrator:
  // exact in time, so only the grid's error is left, below backward Euler's
  // 8 steps (0.0092) and as small as its 50 steps (0.0020).
  const double s = 25.0;
  Field f(200, 1, 1);
  std::fill(f.Strength.begin(), f.Strength.end(), static_cast<float>(s));
  for (int i = 0; i < 100; ++i)
  {
    f.Irradiance[i] = 1.0f;
  }
  mmv::DiffusionSettings settings;
  settings.Exponential = true;
  settings.Tolerance = 1.0e-10;
  const mmv::DiffusionReport report = f.Diffuse(settings);
  double maxError = 0.0;
  for (int i = 0; i < 200; ++i)
  {
    const double x = i - 99.5;
    const double exact = 0.5 * std::erfc(x / (2.0 * std::sqrt(s * settings.Time)));
    maxError = std::max(maxError, std::abs(f.Irradiance[i] - exact));
  }
  std::printf(
    "exponential: max error %.4f against erfc, %d Chebyshev terms\n", maxError, report.Iterations);
  EXPECT_LT(maxError, 0.0025);
  EXPECT_EQ(report.SubSteps, 1);
}

TEST(IrradianceDiffusion, ExponentialSeriesIsShortAndBounded)
{
  // exp(-a (1 - y)) on [-1, 1]: the series' degree grows as sqrt(a), and
  // truncated it stays within the tolerance of the function everywhere.
  for (const double a : { 0.5, 5.0, 21.0, 100.0, 1000.0 })
  {
    const std::vector<double> c = mmv::ExponentialChebyshevCoefficients(a, 1.0e-3);
    ASSERT_FALSE(c.empty());
    double worst = 0.0;
    for (int j = 0; j <= 400; ++j)
    {
      const double y = -1.0 + j / 200.0;
      const double theta = std::acos(std::min(1.0, std::max(-1.0, y)));
      double sum = 0.0;
      for (size_t k = 0; k < c.size(); ++k)
      {
        sum += c[k] * std::cos(k * theta);
      }
      worst = std::max(worst, std::abs(sum - std::exp(-a * (1.0 - y))));
    }
    std::printf("a = %g: degree %zu, max error %.2e\n", a, c.size() - 1, worst);
    EXPECT_LE(worst, 1.0e-3) << a;
    EXPECT_LE(static_cast<double>(c.size()), 4.0 * std::sqrt(a) + 8.0) << a;
  }
  EXPECT_TRUE(mmv::ExponentialChebyshevCoefficients(0.0, 1e-3).empty());
  EXPECT_TRUE(mmv::ExponentialChebyshevCoefficients(std::nan(""), 1e-3).empty());
}

TEST(IrradianceDiffusion, MatchesFineExplicitReference)
{
  // Heterogeneous s in 3-D against many small explicit (forward Euler) steps
  // of the same flux-form operator; MaxSubSteps is not the limit here.
  Field f = RandomField(3.0);
  Field reference = f;
  const int dims[3] = { f.Dims[0], f.Dims[1], f.Dims[2] };
  const double time = 1.0;
  const int steps = 400; // dt * max row sum = 18/400, far below 1
  const double dt = time / steps;
  std::vector<float>& u = reference.Irradiance;
  std::vector<double> next(u.size());
  auto coeff = [&](size_t a, size_t b)
  {
    const double sa = reference.Strength[a], sb = reference.Strength[b];
    return sa > 0.0 && sb > 0.0 ? 2.0 * sa * sb / (sa + sb) : 0.0;
  };
  for (int step = 0; step < steps; ++step)
  {
    for (int k = 0; k < dims[2]; ++k)
      for (int j = 0; j < dims[1]; ++j)
        for (int i = 0; i < dims[0]; ++i)
        {
          const size_t v = f.Index(i, j, k);
          double flux = 0.0;
          const int ijk[3] = { i, j, k };
          const size_t stride[3] = { 1, static_cast<size_t>(dims[0]),
            static_cast<size_t>(dims[0]) * dims[1] };
          for (int a = 0; a < 3; ++a)
          {
            if (ijk[a] > 0)
              flux += coeff(v, v - stride[a]) * (u[v - stride[a]] - u[v]);
            if (ijk[a] + 1 < dims[a])
              flux += coeff(v, v + stride[a]) * (u[v + stride[a]] - u[v]);
          }
          next[v] = u[v] + dt * flux;
        }
    std::copy(next.begin(), next.end(), u.begin());
  }
  mmv::DiffusionSettings settings;
  settings.MaxSubSteps = 64;
  settings.Tolerance = 1.0e-9;
  f.Diffuse(settings);
  double maxError = 0.0;
  for (size_t v = 0; v < u.size(); ++v)
  {
    maxError = std::max(maxError, std::abs(static_cast<double>(f.Irradiance[v]) - u[v]));
  }
  // 18 implicit sub-steps (ceil(T * 6s)); measured 0.0066, the first-order
  // time error on a field with unit-sized jumps.
  EXPECT_LT(maxError, 0.01);
}

TEST(IrradianceDiffusion, InvalidInputIsSkipped)
{
  Field f(4, 4, 4);
  std::fill(f.Strength.begin(), f.Strength.end(), 1.0f);
  mmv::DiffusionSettings settings;
  settings.Time = 0.0;
  EXPECT_TRUE(f.Diffuse(settings).Skipped);
  const int badDims[3] = { 0, 4, 4 };
  EXPECT_TRUE(
    mmv::DiffuseIrradiance(badDims, f.Spacing, f.Strength.data(), f.Irradiance.data()).Skipped);
  // s > 0 only on isolated voxels: no face couples two of them.
  std::fill(f.Strength.begin(), f.Strength.end(), 0.0f);
  f.Strength[f.Index(1, 1, 1)] = 5.0f;
  f.Irradiance[f.Index(1, 1, 1)] = 2.0f;
  EXPECT_TRUE(f.Diffuse().Skipped);
  EXPECT_EQ(f.Irradiance[f.Index(1, 1, 1)], 2.0f);
}

TEST(IrradianceDiffusion, ResultDoesNotDependOnThreadCount)
{
  // Reductions are summed per fixed block in block order, so the bits match.
  // 40^3 voxels make 4 blocks of ~16k.
  Field one = RandomField(20.0, 40, 40, 40);
  Field many = one;
  vtkSMPTools::Initialize(1);
  const mmv::DiffusionReport a = one.Diffuse();
  vtkSMPTools::Initialize(4);
  const mmv::DiffusionReport b = many.Diffuse();
  vtkSMPTools::Initialize(0);
  EXPECT_EQ(a.Iterations, b.Iterations);
  EXPECT_EQ(one.Irradiance, many.Irradiance);
}

TEST(DiffusionGrid, CoarsensToTheDiffusionLength)
{
  const int dims[3] = { 64, 64, 32 };
  const double unit[3] = { 1.0, 1.0, 1.0 };
  // s = 32, T = 1: L = sqrt(2 s T) = 8 data voxels, two diffusion-grid
  // voxels per L (DiffusionSettings::VoxelsPerDiffusionLength).
  ASSERT_EQ(mmv::DiffusionSettings().VoxelsPerDiffusionLength, 2.0);
  mmv::DiffusionGrid grid = mmv::PlanDiffusionGrid(dims, unit, 32.0);
  EXPECT_DOUBLE_EQ(grid.DiffusionLength, 8.0);
  EXPECT_EQ(grid.Factor[0], 4);
  EXPECT_EQ(grid.Dimensions[0], 16);
  EXPECT_DOUBLE_EQ(grid.Spacing[1], 4.0);
  // The short axis keeps MinimumVoxelsPerAxis voxels: factor 32 / 12 = 2.
  EXPECT_EQ(grid.Factor[2], 2);
  EXPECT_EQ(grid.Dimensions[2], 16);
  // An irradiance grid of 2 data voxels per voxel needs half the factor.
  const double two[3] = { 2.0, 2.0, 2.0 };
  EXPECT_EQ(mmv::PlanDiffusionGrid(dims, two, 32.0).Factor[0], 2);
  // The factor nearest in ratio: 2 / 1.335 = 1.498 > sqrt(2) rounds up, 2 / 1.45
  // = 1.38 down (s = 8: L / 2 = 2 data voxels).
  const double scale75[3] = { 1.335, 1.335, 1.335 };
  EXPECT_EQ(mmv::PlanDiffusionGrid(dims, scale75, 8.0).Factor[0], 2);
  const double coarser[3] = { 1.45, 1.45, 1.45 };
  EXPECT_EQ(mmv::PlanDiffusionGrid(dims, coarser, 8.0).Factor[0], 1);
  // Weak scattering (L / 2 < 1 voxel) and no scattering keep the grid.
  EXPECT_TRUE(mmv::PlanDiffusionGrid(dims, unit, 1.0).IsIdentity());
  EXPECT_TRUE(mmv::PlanDiffusionGrid(dims, unit, 0.0).IsIdentity());
  // Very strong scattering keeps about MinimumVoxelsPerAxis voxels per axis.
  ASSERT_EQ(mmv::DiffusionSettings().MinimumVoxelsPerAxis, 12);
  grid = mmv::PlanDiffusionGrid(dims, unit, 1.0e6);
  EXPECT_EQ(grid.Factor[0], 5);      // 64 / 12
  EXPECT_EQ(grid.Dimensions[0], 13); // ceil(64 / 5)
  EXPECT_EQ(grid.Dimensions[2], 16); // 32 / 12 = 2
  // Coarse voxel J sits at the centre of fine voxels [J f, J f + f).
  grid = mmv::PlanDiffusionGrid(dims, unit, 32.0);
  EXPECT_DOUBLE_EQ(grid.CoarseCoordinate(0, 5), (5 - 1.5) / 4.0);
  EXPECT_DOUBLE_EQ(grid.CoarseCoordinate(0, 0), 0.0);   // clamped
  EXPECT_DOUBLE_EQ(grid.CoarseCoordinate(0, 63), 15.0); // clamped
}

TEST(DiffusionGrid, SweepsFollowTheErrorBounds)
{
  mmv::DiffusionSettings settings;
  settings.SweepTolerance = 1.0e-3;
  // r = 1: one sweep halves the error; 2^-10 < 1e-3 < 2^-9.
  EXPECT_EQ(mmv::JacobiSweeps(1.0, settings), 10);
  // r = 3: contraction 3/4; ln(1e-3)/ln(0.75) = 24.01.
  EXPECT_EQ(mmv::JacobiSweeps(3.0, settings), 25);
  EXPECT_EQ(mmv::JacobiSweeps(0.0, settings), 1);
  // Chebyshev, r = 3: rho = 3/4, c = 0.75 / (1 + sqrt(1 - 0.5625)) = 0.4534;
  // ln(5e-4) / ln(c) = 9.6.
  EXPECT_EQ(mmv::ChebyshevSweeps(3.0, settings), 10);
  // Stiff, r = 100: about the square root of Jacobi's count.
  EXPECT_LT(mmv::ChebyshevSweeps(100.0, settings), mmv::JacobiSweeps(100.0, settings) / 10);
  EXPECT_DOUBLE_EQ(mmv::ChebyshevWeight(1, 0.75), 1.0);
  EXPECT_DOUBLE_EQ(mmv::ChebyshevWeight(2, 0.75), 1.0 / (1.0 - 0.5 * 0.5625));
  // Sub-steps: ceil(T * rate), capped.
  EXPECT_EQ(mmv::DiffusionSubSteps(2.5, settings), 3);
  EXPECT_EQ(mmv::DiffusionSubSteps(1.0e6, settings), settings.MaxSubSteps);
}

TEST(DiffusionGrid, IdentityGridEqualsTheFullSolve)
{
  const int dims[3] = { 12, 10, 9 };
  const double unit[3] = { 1.0, 1.0, 1.0 };
  const vtkIdType n = 12 * 10 * 9;
  std::vector<float> strength(n, 0.4f);
  std::vector<float> field(n);
  std::mt19937 random(7);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  for (float& v : field)
  {
    v = uniform(random);
  }
  std::vector<float> full = field;
  std::vector<float> viaGrid = field;
  mmv::DiffuseIrradiance(dims, unit, strength.data(), full.data());
  mmv::DiffusionGrid used;
  mmv::DiffuseIrradianceOnDiffusionGrid(
    dims, unit, strength.data(), viaGrid.data(), mmv::DiffusionSettings(), &used);
  ASSERT_TRUE(used.IsIdentity()); // L = 0.9 voxel
  for (vtkIdType v = 0; v < n; ++v)
  {
    ASSERT_NEAR(viaGrid[v], full[v], 1.0e-5) << "voxel " << v;
  }
}

TEST(DiffusionGrid, CoarseChangeApproachesTheFullSolve)
{
  // Light entering a homogeneous medium at x = 0 (s = 8, L = 4 voxels): the
  // change computed on the diffusion grid (2-voxel blocks) against the full
  // solve. The boundary layer at the zero-flux face is where it differs most.
  const int dims[3] = { 32, 32, 32 };
  const double unit[3] = { 1.0, 1.0, 1.0 };
  const vtkIdType n = 32 * 32 * 32;
  std::vector<float> strength(n, 8.0f);
  std::vector<float> field(n);
  for (vtkIdType v = 0; v < n; ++v)
  {
    field[v] = static_cast<float>(std::exp(-3.0 * static_cast<double>(v % 32) / 31.0));
  }
  std::vector<float> full = field;
  mmv::DiffuseIrradiance(dims, unit, strength.data(), full.data());
  std::vector<float> viaGrid = field;
  mmv::DiffusionGrid used;
  mmv::DiffuseIrradianceOnDiffusionGrid(
    dims, unit, strength.data(), viaGrid.data(), mmv::DiffusionSettings(), &used);
  EXPECT_EQ(used.Factor[0], 2);
  double change = 0.0;
  double worst = 0.0;
  double interior = 0.0;
  for (vtkIdType v = 0; v < n; ++v)
  {
    const double error = std::abs(static_cast<double>(viaGrid[v]) - full[v]);
    change = std::max(change, std::abs(static_cast<double>(full[v]) - field[v]));
    worst = std::max(worst, error);
    if (v % 32 >= 4 && v % 32 < 28)
    {
      interior = std::max(interior, error);
    }
  }
  std::cout << "full-solve change " << change << ", coarse-grid error " << worst
            << " (away from the faces " << interior << ")" << std::endl;
  EXPECT_GT(change, 0.1);
  // Measured: 20 % of the change at the lit face, where the change varies
  // most inside a block (vtkIrradianceDiffusion.h says why the change is
  // added all the same), 3 % away from it.
  EXPECT_LT(worst, 0.25 * change);
  EXPECT_LT(interior, 0.05 * change);
}

TEST(IrradianceResolution, ScreenRuleUsesQuarterOctaves)
{
  const int data[3] = { 256, 256, 128 };
  // Budget large enough for full resolution.
  mmv::IrradianceResolution r = mmv::ChooseIrradianceResolution(data, 1, 1.0e4, 0.0, 0.0);
  EXPECT_EQ(r.Dimensions[0], 256);
  EXPECT_NE(r.Reason.find("budget"), std::string::npos);
  // p pixels per data voxel: scale p / PixelsPerIrradianceVoxel rounded up to 2^(k/4).
  const double p = 0.5 * mmv::PixelsPerIrradianceVoxel; // exactly 2^-1
  r = mmv::ChooseIrradianceResolution(data, 1, 1.0e4, 0.0, p);
  EXPECT_DOUBLE_EQ(r.Scale, 0.5);
  EXPECT_EQ(r.Dimensions[0], 128);
  EXPECT_EQ(r.Dimensions[2], 64);
  EXPECT_NE(r.Reason.find("screen"), std::string::npos);
  r = mmv::ChooseIrradianceResolution(data, 1, 1.0e4, 0.0, 0.55 * mmv::PixelsPerIrradianceVoxel);
  EXPECT_DOUBLE_EQ(r.Scale, std::exp2(-0.75)); // log2(0.55) = -0.86 -> -0.75
  // Zoomed in: never finer than the data.
  r = mmv::ChooseIrradianceResolution(data, 1, 1.0e4, 0.0, 50.0);
  EXPECT_EQ(r.Dimensions[0], 256);
  // A small budget wins over the screen.
  r = mmv::ChooseIrradianceResolution(data, 5, 4.0, 0.0, 50.0);
  EXPECT_LT(r.Dimensions[0], 128);
  EXPECT_NE(r.Reason.find("budget"), std::string::npos);
  // The user's scale wins over both.
  r = mmv::ChooseIrradianceResolution(data, 1, 4.0, 0.25, 50.0);
  EXPECT_EQ(r.Dimensions[0], 64);
  EXPECT_NE(r.Reason.find("user"), std::string::npos);
}

// A diffusion grid of one-voxel blocks (a diffusion length of a few voxels)
// restricts to each voxel's own values: its strength where it scatters, its
// irradiance there, capacity 1; zero where the strength is zero, negative or
// not a number.
TEST(IrradianceDiffusion, RestrictionOntoOneVoxelBlocksKeepsEachVoxel)
{
  const int dims[3] = { 7, 5, 4 };
  mmv::DiffusionGrid blocks;
  for (int a = 0; a < 3; ++a)
  {
    blocks.Factor[a] = 1;
    blocks.Dimensions[a] = dims[a];
    blocks.Spacing[a] = 1.5;
  }
  const vtkIdType n = 7 * 5 * 4;
  std::mt19937 random(5);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  std::vector<float> strength(n), fine(n);
  for (vtkIdType v = 0; v < n; ++v)
  {
    const float u = uniform(random);
    strength[v] = u < 0.2f ? 0.0f
      : u < 0.3f           ? -1.0f
      : u < 0.35f          ? std::numeric_limits<float>::quiet_NaN()
                           : 10.0f * uniform(random);
    fine[v] = uniform(random);
  }
  const float* const irradiances[2] = { fine.data(), nullptr };
  for (const float* irradiance : irradiances)
  {
    std::vector<float> coarseStrength, coarseIrradiance, capacity;
    mmv::RestrictToDiffusionGrid(
      dims, blocks, strength.data(), irradiance, &coarseStrength, &coarseIrradiance, &capacity);
    ASSERT_EQ(coarseStrength.size(), static_cast<size_t>(n));
    int scattering = 0;
    for (vtkIdType v = 0; v < n; ++v)
    {
      const bool scatters = strength[v] > 0.0f;
      scattering += scatters ? 1 : 0;
      EXPECT_EQ(coarseStrength[v], scatters ? strength[v] : 0.0f) << "voxel " << v;
      EXPECT_EQ(coarseIrradiance[v], scatters && irradiance ? fine[v] : 0.0f) << "voxel " << v;
      EXPECT_EQ(capacity[v], scatters ? 1.0f : 0.0f) << "voxel " << v;
    }
    EXPECT_GT(scattering, 70);
    EXPECT_LT(scattering, 120);
  }
}

// Layers of scattering on blocks of 2: a layer that fills whole blocks counts
// in full, a layer thinner than a block, or one that straddles two, not at
// all; a mixture counts each voxel where it lies.
TEST(IrradianceDiffusion, FilledBlockShareTellsThinLayersFromThickOnes)
{
  const int dims[3] = { 8, 8, 8 };
  mmv::DiffusionGrid blocks;
  for (int a = 0; a < 3; ++a)
  {
    blocks.Factor[a] = 2;
    blocks.Dimensions[a] = 4;
    blocks.Spacing[a] = 2.0;
  }
  auto share = [&](const std::function<bool(int)>& scatters)
  {
    std::vector<float> strength(512, 0.0f);
    for (int v = 0; v < 512; ++v)
    {
      strength[v] = scatters(v / 64) ? 1.0f : 0.0f; // by the voxel's z
    }
    std::vector<float> capacity;
    mmv::RestrictToDiffusionGrid(
      dims, blocks, strength.data(), nullptr, nullptr, nullptr, &capacity);
    return mmv::FilledBlockShare(capacity.data(), static_cast<vtkIdType>(capacity.size()));
  };
  EXPECT_EQ(share([](int) { return true; }), 1.0);
  EXPECT_EQ(share([](int) { return false; }), 0.0);
  EXPECT_EQ(share([](int z) { return z == 3; }), 0.0);           // one voxel thick
  EXPECT_EQ(share([](int z) { return z == 2 || z == 3; }), 1.0); // one block thick
  EXPECT_EQ(share([](int z) { return z == 3 || z == 4; }), 0.0); // across two blocks
  // 4 layers that fill two block layers and 1 that half fills one: 4 of 5.
  EXPECT_NEAR(share([](int z) { return z <= 3 || z == 6; }), 0.8, 1e-12);
  EXPECT_EQ(mmv::FilledBlockShare(nullptr, 4), 0.0);
}

TEST(IrradianceDiffusion, BlockTexelsHoldEachFaceFromBothSides)
{
  // What the GPU's sweeps read per block instead of computing it: the
  // coefficient of each face, the harmonic mean of s over h^2 of its axis
  // (anisotropic here), equal from both sides, 0 at the boundary and where
  // either side does not scatter; the capacity (1 where none) and whether
  // the block scatters. Their largest row sum over the capacity is
  // MaxDiffusionRate, the rate the GPU's series is scaled by.
  const int dims[3] = { 5, 4, 3 };
  const double spacing[3] = { 1.0, 2.0, 0.5 };
  const vtkIdType n = 5 * 4 * 3;
  std::mt19937 random(11);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  std::vector<float> strength(n), capacity(n);
  for (vtkIdType v = 0; v < n; ++v)
  {
    capacity[v] = uniform(random) < 0.25f ? 0.0f : 0.125f + 0.875f * uniform(random);
    strength[v] = capacity[v] > 0.0f ? 20.0f * uniform(random) * capacity[v] : 0.0f;
  }
  std::vector<float> xy, z, exchanges;
  const double texelsRate =
    mmv::DiffusionBlockTexels(dims, spacing, strength.data(), capacity.data(), xy, z, exchanges);
  ASSERT_EQ(xy.size(), static_cast<size_t>(4 * n));
  ASSERT_EQ(z.size(), static_cast<size_t>(4 * n));
  ASSERT_EQ(exchanges.size(), static_cast<size_t>(n));
  // Face `f` (-x, +x, -y, +y, -z, +z) of block v.
  auto face = [&](vtkIdType v, int f) { return f < 4 ? xy[4 * v + f] : z[4 * v + f - 4]; };
  const vtkIdType stride[3] = { 1, 5, 20 };
  int open = 0;
  int blocked = 0;
  double maxRate = 0.0;
  for (vtkIdType v = 0; v < n; ++v)
  {
    const int index[3] = { static_cast<int>(v % 5), static_cast<int>((v / 5) % 4),
      static_cast<int>(v / 20) };
    double total = 0.0;
    for (int a = 0; a < 3; ++a)
    {
      for (int side = 0; side < 2; ++side)
      {
        const int f = 2 * a + side;
        const int neighbor = index[a] + (side == 0 ? -1 : 1);
        const bool inside = neighbor >= 0 && neighbor < dims[a];
        const vtkIdType u = v + (side == 0 ? -stride[a] : stride[a]);
        const double expected = inside
          ? mmv::DiffusionFaceStrength(strength[v], strength[u]) / (spacing[a] * spacing[a])
          : 0.0;
        ASSERT_NEAR(face(v, f), expected, 1e-6 * expected) << "block " << v << " face " << f;
        if (inside)
        {
          ASSERT_EQ(face(v, f), face(u, f ^ 1)) << "block " << v << " face " << f;
        }
        (face(v, f) > 0.0f ? open : blocked) += 1;
        total += face(v, f);
      }
    }
    EXPECT_EQ(z[4 * v + 2], capacity[v] > 0.0f ? capacity[v] : 1.0f);
    EXPECT_EQ(z[4 * v + 3], strength[v] > 0.0f ? 1.0f : 0.0f);
    EXPECT_EQ(exchanges[v], total > 0.0 ? 1.0f : 0.0f) << "block " << v;
    maxRate = std::max(maxRate, total / z[4 * v + 2]);
  }
  EXPECT_GT(open, 50);
  EXPECT_GT(blocked, 50);
  EXPECT_NEAR(mmv::MaxDiffusionRate(dims, spacing, strength.data(), capacity.data()), maxRate,
    1e-6 * maxRate);
  // The rate the texels return is the operator's, bit for bit.
  EXPECT_EQ(texelsRate, mmv::MaxDiffusionRate(dims, spacing, strength.data(), capacity.data()));
  std::vector<float> none(n, 0.0f);
  EXPECT_EQ(mmv::DiffusionBlockTexels(dims, spacing, none.data(), nullptr, xy, z, exchanges), 0.0);
  // Capacity 1 where a block scatters and 0 elsewhere (one-voxel blocks) is
  // no capacity at all.
  std::vector<float> scattering(n);
  std::transform(strength.begin(), strength.end(), scattering.begin(),
    [](float s) { return s > 0.0f ? 1.0f : 0.0f; });
  std::vector<float> xyOnes, zOnes, exchangesOnes;
  const double onesRate = mmv::DiffusionBlockTexels(
    dims, spacing, strength.data(), scattering.data(), xyOnes, zOnes, exchangesOnes);
  EXPECT_EQ(
    onesRate, mmv::DiffusionBlockTexels(dims, spacing, strength.data(), nullptr, xy, z, exchanges));
  EXPECT_EQ(xyOnes, xy);
  EXPECT_EQ(zOnes, z);
  EXPECT_EQ(exchangesOnes, exchanges);
  // On a grid of many chunks, on every core: the chunks' maxima combine to it.
  const int large[3] = { 61, 47, 33 };
  const vtkIdType m = 61 * 47 * 33;
  std::vector<float> largeStrength(m), largeCapacity(m);
  for (vtkIdType v = 0; v < m; ++v)
  {
    largeCapacity[v] = uniform(random) < 0.25f ? 0.0f : 0.125f + 0.875f * uniform(random);
    largeStrength[v] = largeCapacity[v] > 0.0f ? 20.0f * uniform(random) * largeCapacity[v] : 0.0f;
  }
  double largeRate = 0.0;
  mmv::RunOnAllCores(
    [&]()
    {
      largeRate = mmv::DiffusionBlockTexels(
        large, spacing, largeStrength.data(), largeCapacity.data(), xy, z, exchanges);
    });
  EXPECT_GT(largeRate, 0.0);
  EXPECT_EQ(
    largeRate, mmv::MaxDiffusionRate(large, spacing, largeStrength.data(), largeCapacity.data()));
}

TEST(IrradianceDiffusion, CapacityConservesWeightedSumAndMatchesJacobi)
{
  // (C + dt A) x = C b: the sum of C x is conserved, and plain Jacobi sweeps
  // of the same system (what the GPU runs) converge to the CG solution.
  const int dims[3] = { 6, 5, 4 };
  const double unit[3] = { 2.0, 2.0, 2.0 };
  const vtkIdType n = 6 * 5 * 4;
  std::mt19937 random(3);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  std::vector<float> strength(n), capacity(n), field(n);
  for (vtkIdType v = 0; v < n; ++v)
  {
    capacity[v] = uniform(random) < 0.2f ? 0.0f : 0.25f + 0.75f * uniform(random);
    strength[v] = capacity[v] > 0.0f ? 8.0f * capacity[v] : 0.0f;
    field[v] = uniform(random);
  }
  mmv::DiffusionSettings settings;
  settings.Exponential = false; // one backward-Euler step, solved by CG
  settings.MaxSubSteps = 1;
  std::vector<float> cg = field;
  mmv::DiffuseIrradiance(dims, unit, strength.data(), cg.data(), settings, capacity.data());
  double before = 0.0, after = 0.0;
  for (vtkIdType v = 0; v < n; ++v)
  {
    const double c = capacity[v] > 0.0f ? capacity[v] : 1.0;
    before += c * field[v];
    after += c * cg[v];
  }
  EXPECT_NEAR(after, before, 1.0e-5 * before);
  // Jacobi: x = (C b + dt sum c_f x_f) / (C + dt sum c_f), dt = T = 1.
  std::vector<double> x(field.begin(), field.end()), next(n);
  auto at = [&](int i, int j, int k) { return i + 6 * (j + 5 * k); };
  for (int sweep = 0; sweep < 2000; ++sweep)
  {
    for (int k = 0; k < 4; ++k)
      for (int j = 0; j < 5; ++j)
        for (int i = 0; i < 6; ++i)
        {
          const int v = at(i, j, k);
          const double s = strength[v];
          const double c = s > 0.0 ? capacity[v] : 1.0;
          double num = c * field[v], den = c;
          const int idx[3] = { i, j, k };
          for (int a = 0; a < 3; ++a)
            for (int side = -1; side <= 1; side += 2)
            {
              int m[3] = { i, j, k };
              m[a] += side;
              if (s > 0.0 && m[a] >= 0 && m[a] < dims[a])
              {
                const int u = at(m[0], m[1], m[2]);
                const double f = mmv::DiffusionFaceStrength(s, strength[u]) / (unit[a] * unit[a]);
                num += f * x[u];
                den += f;
              }
              (void)idx;
            }
          next[v] = num / den;
        }
    x.swap(next);
  }
  for (vtkIdType v = 0; v < n; ++v)
  {
    ASSERT_NEAR(x[v], cg[v], 1.0e-4) << "voxel " << v;
  }
}

// The estimator's diffusion on the CPU (restriction, the exponential's
// series on the block texels in float, prolongation; what a CPU rasterizer
// runs) against the double-precision model of the same diffusion
// (DiffuseIrradianceOnDiffusionGrid with the exponential integrator): a
// field of random strengths with empty voxels, on two diffusion grids
// coarser than the irradiance grid, four channels at once.
TEST(IrradianceDiffusion, BlockPipelineOnTheCPUMatchesTheModel)
{
  const int dims[3] = { 48, 40, 36 };
  const vtkIdType n = static_cast<vtkIdType>(dims[0]) * dims[1] * dims[2];
  const double spacing[3] = { 1.0, 1.0, 1.0 };
  std::mt19937 random(7);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<float> classes(n);
  std::vector<float> fine(4 * n);
  for (vtkIdType v = 0; v < n; ++v)
  {
    // A third empty (class < 0), the rest s in [0.5, 4]; and a gap of
    // empty voxels wider than a block, where the prolongation renormalises
    // over the corner blocks that scatter.
    const bool gap = v % dims[0] >= 16 && v % dims[0] < 28;
    classes[v] = gap || unit(random) < 0.33f ? -1.0f : 0.5f + 3.5f * unit(random);
    for (int c = 0; c < 4; ++c)
    {
      fine[4 * v + c] = unit(random);
    }
  }
  std::vector<float> strength(n);
  std::transform(
    classes.begin(), classes.end(), strength.begin(), [](float s) { return std::max(0.0f, s); });
  for (const double voxelsPerLength : { 1.0, 2.0 })
  {
    mmv::DiffusionSettings settings;
    settings.Exponential = true;
    settings.Time = 4.0; // a diffusion length of 5.7 voxels
    settings.VoxelsPerDiffusionLength = voxelsPerLength;
    // The plan, as the estimator makes it (PlanDiffusionBlocks).
    const float maxStrength = *std::max_element(strength.begin(), strength.end());
    const mmv::DiffusionGrid coarse = mmv::PlanDiffusionGrid(dims, spacing, maxStrength, settings);
    std::vector<float> coarseStrength;
    std::vector<float> capacity;
    mmv::RestrictToDiffusionGrid(
      dims, coarse, strength.data(), nullptr, &coarseStrength, nullptr, &capacity);
    const double rate = mmv::MaxDiffusionRate(
      coarse.Dimensions, coarse.Spacing, coarseStrength.data(), capacity.data());
    ASSERT_GT(rate, 0.0);
    std::vector<float> xy;
    std::vector<float> z;
    std::vector<float> exchanges;
    mmv::DiffusionBlockTexels(
      coarse.Dimensions, coarse.Spacing, coarseStrength.data(), capacity.data(), xy, z, exchanges);
    const std::vector<double> series =
      mmv::ExponentialChebyshevCoefficients(rate * settings.Time, 1.0e-7);
    const int* cd = coarse.Dimensions;
    const int blocks[6] = { 0, cd[0] - 1, 0, cd[1] - 1, 0, cd[2] - 1 };
    const int whole[6] = { 0, dims[0] - 1, 0, dims[1] - 1, 0, dims[2] - 1 };
    std::vector<float> restricted(4 * coarse.GetNumberOfVoxels());
    std::vector<float> change(restricted.size());
    mmv::RestrictToDiffusionBlocks(
      dims, fine.data(), classes.data(), coarse, 4, blocks, restricted.data());
    mmv::BlockDiffusionSeries cpu;
    ASSERT_TRUE(cpu.Change(
      cd, 4, xy.data(), z.data(), blocks, series, 1.0 / rate, restricted.data(), change.data()));
    std::vector<float> diffused = fine;
    mmv::ProlongDiffusionChange(dims, fine.data(), classes.data(), coarse, 4, change.data(),
      z.data(), 0xF, whole, diffused.data());
    double worst = 0.0;
    double moved = 0.0;
    for (int c = 0; c < 4; ++c)
    {
      std::vector<float> model(n);
      for (vtkIdType v = 0; v < n; ++v)
      {
        model[v] = fine[4 * v + c];
      }
      mmv::DiffuseIrradianceOnDiffusionGrid(dims, spacing, strength.data(), model.data(), settings);
      for (vtkIdType v = 0; v < n; ++v)
      {
        worst = std::max(worst, std::abs(static_cast<double>(diffused[4 * v + c]) - model[v]));
        moved = std::max(moved, std::abs(static_cast<double>(model[v]) - fine[4 * v + c]));
      }
    }
    std::cout << "diffusion grid " << cd[0] << "x" << cd[1] << "x" << cd[2]
              << ": CPU blocks vs model max |difference| " << worst << ", the diffusion moved "
              << moved << std::endl;
    for (int a = 0; a < 3; ++a)
    {
      EXPECT_GT(coarse.Factor[a], 1) << "axis " << a;
    }
    EXPECT_GT(moved, 0.1); // the diffusion does something here
    EXPECT_LT(worst, 1e-5);
  }
}
