// mmv::VisibleIrradiancePSNR and mmv::OpacityWeights (the error probe's
// measure) against closed forms.
#include "vtkIrradianceResolutionError.h"
#include "vtkMultiMaterialParameters.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

namespace
{
/// An axis-aligned grid of `n` voxels per axis spanning [0, 1]^3.
mmv::IrradianceGrid UnitGrid(int n)
{
  mmv::IrradianceGrid grid;
  for (int a = 0; a < 3; ++a)
  {
    grid.Dimensions[a] = n;
    grid.Spacing[a] = 1.0 / (n - 1);
  }
  return grid;
}

std::vector<float> Sample(
  const mmv::IrradianceGrid& grid, const std::function<double(glm::dvec3)>& f)
{
  std::vector<float> values(grid.GetNumberOfVoxels());
  for (vtkIdType v = 0; v < grid.GetNumberOfVoxels(); ++v)
  {
    values[v] = static_cast<float>(f(grid.IndexToPhysical(grid.IndexOfVoxel(v))));
  }
  return values;
}
}

TEST(IrradianceResolutionError, TrilinearFieldsLoseNothingOnACoarserGrid)
{
  // The ray caster reads the coarse grid trilinearly: a trilinear field is
  // exact there, so the PSNR is limited by float rounding alone.
  const auto field = [](glm::dvec3 p) { return 0.2 + 0.3 * p.x + 0.2 * p.y * p.z + 0.1 * p.z; };
  const mmv::IrradianceGrid fine = UnitGrid(17);
  const mmv::IrradianceGrid coarse = UnitGrid(5);
  const std::vector<float> weights(fine.GetNumberOfVoxels(), 1.0f);
  const double psnr = mmv::VisibleIrradiancePSNR(
    fine, { Sample(fine, field) }, weights, coarse, { Sample(coarse, field) });
  EXPECT_GT(psnr, 120.0);
}

TEST(IrradianceResolutionError, UniformOffsetGivesItsClosedForm)
{
  const mmv::IrradianceGrid fine = UnitGrid(9);
  const mmv::IrradianceGrid coarse = UnitGrid(4);
  const std::vector<float> weights(fine.GetNumberOfVoxels(), 0.5f);
  const auto a = [](glm::dvec3) { return 0.5; };
  const auto b = [](glm::dvec3) { return 0.5 + 0.01; };
  // Two lights, both off by 0.01: PSNR = -20 log10(0.01) = 40 dB.
  const double psnr = mmv::VisibleIrradiancePSNR(fine, { Sample(fine, a), Sample(fine, a) },
    weights, coarse, { Sample(coarse, b), Sample(coarse, b) });
  EXPECT_NEAR(psnr, 40.0, 1e-3);
}

TEST(IrradianceResolutionError, OnlyVoxelsWithWeightCount)
{
  // A shadow edge the coarse grid cannot hold, where nothing is visible
  // (weight 0), and an offset of 0.1 where the material is (weight 1).
  const mmv::IrradianceGrid fine = UnitGrid(9);
  const mmv::IrradianceGrid coarse = UnitGrid(9);
  std::vector<float> weights(fine.GetNumberOfVoxels(), 0.0f);
  std::vector<float> f(fine.GetNumberOfVoxels(), 0.5f);
  std::vector<float> c = f;
  for (vtkIdType v = 0; v < fine.GetNumberOfVoxels(); ++v)
  {
    if (fine.IndexOfVoxel(v).x < 4)
    {
      c[v] = 1.0f; // invisible error
    }
    else
    {
      weights[v] = 1.0f;
      c[v] = 0.6f;
    }
  }
  EXPECT_NEAR(mmv::VisibleIrradiancePSNR(fine, { f }, weights, coarse, { c }), 20.0, 1e-3);
  // Nothing visible: nothing to lose.
  const std::vector<float> none(fine.GetNumberOfVoxels(), 0.0f);
  EXPECT_TRUE(std::isinf(mmv::VisibleIrradiancePSNR(fine, { f }, none, coarse, { c })));
}

TEST(IrradianceResolutionError, MismatchedInputsAreNaN)
{
  const mmv::IrradianceGrid fine = UnitGrid(5);
  const mmv::IrradianceGrid coarse = UnitGrid(3);
  const std::vector<float> f(fine.GetNumberOfVoxels(), 0.5f);
  const std::vector<float> c(coarse.GetNumberOfVoxels(), 0.5f);
  const std::vector<float> weights(fine.GetNumberOfVoxels(), 1.0f);
  EXPECT_TRUE(std::isnan(mmv::VisibleIrradiancePSNR(fine, { f }, weights, coarse, { c, c })));
  EXPECT_TRUE(std::isnan(mmv::VisibleIrradiancePSNR(fine, { c }, weights, coarse, { c })));
  EXPECT_TRUE(std::isnan(mmv::VisibleIrradiancePSNR(fine, {}, weights, coarse, {})));
  EXPECT_TRUE(std::isnan(
    mmv::VisibleIrradiancePSNR(fine, { f }, std::vector<float>(3, 1.0f), coarse, { c })));
}

TEST(IrradianceResolutionError, OpacityWeightsInterpolateTheTable)
{
  const std::vector<float> table = { 0.0f, 0.2f, 1.0f };
  const std::vector<float> w =
    mmv::OpacityWeights({ 0.0f, 0.25f, 0.5f, 0.75f, 1.0f, 2.0f, -1.0f, NAN }, table);
  ASSERT_EQ(w.size(), 8u);
  EXPECT_FLOAT_EQ(w[0], 0.0f);
  EXPECT_FLOAT_EQ(w[1], 0.1f);
  EXPECT_FLOAT_EQ(w[2], 0.2f);
  EXPECT_FLOAT_EQ(w[3], 0.6f);
  EXPECT_FLOAT_EQ(w[4], 1.0f);
  EXPECT_FLOAT_EQ(w[5], 1.0f); // clamped to the range
  EXPECT_FLOAT_EQ(w[6], 0.0f);
  EXPECT_FLOAT_EQ(w[7], 0.0f); // NaN: lit as empty, never visible
}

TEST(IrradianceResolutionError, ErrorBoundsOutOfRangeAreReported)
{
  std::string why;
  EXPECT_EQ(mmv::ValidIrradianceErrorBound(34.0, &why), 34.0);
  EXPECT_TRUE(why.empty());
  EXPECT_EQ(mmv::ValidIrradianceErrorBound(0.0, &why), 0.0);
  EXPECT_TRUE(why.empty());
  EXPECT_EQ(mmv::ValidIrradianceErrorBound(-3.0, &why), 0.0);
  EXPECT_NE(why.find("using 0"), std::string::npos) << why;
  why.clear();
  EXPECT_EQ(mmv::ValidIrradianceErrorBound(NAN, &why), 0.0);
  EXPECT_FALSE(why.empty());
  why.clear();
  EXPECT_EQ(mmv::ValidIrradianceErrorBound(1e9, &why), mmv::MaxIrradianceErrorBoundDB);
  EXPECT_FALSE(why.empty());
}
