// mmv::ComputeValueGradients (the gradient volume the ray caster shades with)
// against closed forms: a linear ramp's central differences are exact inside
// and one-sided halves on the faces; a quadratic's are exact at every
// interior voxel; non-finite values give no gradient.
#include "vtkValueGradient.h"

#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkUnsignedShortArray.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace
{
vtkIdType Index(const int dims[3], int i, int j, int k)
{
  return i + dims[0] * (j + static_cast<vtkIdType>(dims[1]) * k);
}
}

TEST(ValueGradient, LinearRampIsExactInsideAndHalfOnTheFaces)
{
  // value = 3i + 5j - 2k + 100 in uint16, normalised over [0, 1000].
  const int dims[3] = { 6, 5, 4 };
  vtkNew<vtkUnsignedShortArray> scalars;
  scalars->SetNumberOfTuples(dims[0] * dims[1] * dims[2]);
  for (int k = 0; k < dims[2]; ++k)
    for (int j = 0; j < dims[1]; ++j)
      for (int i = 0; i < dims[0]; ++i)
      {
        scalars->SetValue(
          Index(dims, i, j, k), static_cast<unsigned short>(3 * i + 5 * j - 2 * k + 100));
      }
  const double range[2] = { 0.0, 1000.0 };
  std::vector<float> g;
  mmv::ComputeValueGradients(scalars, 0, dims, range, g);
  ASSERT_EQ(g.size(), 3u * dims[0] * dims[1] * dims[2]);
  const double slope[3] = { 3.0 / 1000.0, 5.0 / 1000.0, -2.0 / 1000.0 };
  for (int k = 0; k < dims[2]; ++k)
    for (int j = 0; j < dims[1]; ++j)
      for (int i = 0; i < dims[0]; ++i)
      {
        const int ijk[3] = { i, j, k };
        for (int a = 0; a < 3; ++a)
        {
          const bool face = ijk[a] == 0 || ijk[a] == dims[a] - 1;
          EXPECT_NEAR(g[3 * Index(dims, i, j, k) + a], face ? slope[a] / 2.0 : slope[a], 1e-7)
            << i << " " << j << " " << k << " axis " << a;
        }
      }
}

TEST(ValueGradient, QuadraticIsExactAtInteriorVoxels)
{
  // Central differences of x^2 are exact: (x+1)^2 - (x-1)^2 = 4x.
  const int dims[3] = { 9, 3, 3 };
  vtkNew<vtkFloatArray> scalars;
  scalars->SetNumberOfTuples(dims[0] * dims[1] * dims[2]);
  for (vtkIdType v = 0; v < scalars->GetNumberOfTuples(); ++v)
  {
    const double x = static_cast<double>(v % dims[0]);
    scalars->SetValue(v, static_cast<float>(x * x));
  }
  const double range[2] = { 0.0, 64.0 };
  std::vector<float> g;
  mmv::ComputeValueGradients(scalars, 0, dims, range, g);
  for (int i = 1; i + 1 < dims[0]; ++i)
  {
    EXPECT_NEAR(g[3 * Index(dims, i, 1, 1)], 2.0 * i / 64.0, 1e-7);
    EXPECT_EQ(g[3 * Index(dims, i, 1, 1) + 1], 0.0f);
  }
}

TEST(ValueGradient, NonFiniteValuesGiveNoGradient)
{
  const int dims[3] = { 4, 4, 4 };
  vtkNew<vtkFloatArray> scalars;
  scalars->SetNumberOfTuples(64);
  for (vtkIdType v = 0; v < 64; ++v)
  {
    scalars->SetValue(v, static_cast<float>(v % 4));
  }
  scalars->SetValue(Index(dims, 1, 1, 1), std::numeric_limits<float>::quiet_NaN());
  scalars->SetValue(Index(dims, 2, 2, 2), std::numeric_limits<float>::infinity());
  const double range[2] = { 0.0, 3.0 };
  std::vector<float> g;
  mmv::ComputeValueGradients(scalars, 0, dims, range, g);
  for (const float value : g)
  {
    ASSERT_TRUE(std::isfinite(value));
  }
  // Beside the NaN along x: no gradient; elsewhere the ramp's 1/3.
  EXPECT_EQ(g[3 * Index(dims, 0, 1, 1)], 0.0f);
  EXPECT_EQ(g[3 * Index(dims, 2, 1, 1)], 0.0f);
  EXPECT_NEAR(g[3 * Index(dims, 1, 0, 0)], 1.0 / 3.0, 1e-7);
}

TEST(ValueGradient, SmoothingKeepsALinearRampsGradientInside)
{
  // A Gaussian of a linear field is the same linear field: away from the
  // faces (3 sigma + 1 voxels) the smoothed gradient is the ramp's exactly.
  const int dims[3] = { 20, 18, 16 };
  vtkNew<vtkFloatArray> scalars;
  scalars->SetNumberOfTuples(dims[0] * dims[1] * dims[2]);
  for (int k = 0; k < dims[2]; ++k)
    for (int j = 0; j < dims[1]; ++j)
      for (int i = 0; i < dims[0]; ++i)
      {
        scalars->SetValue(Index(dims, i, j, k), static_cast<float>(2.0 * i - 1.0 * j + 0.5 * k));
      }
  const double range[2] = { 0.0, 10.0 };
  std::vector<float> g;
  mmv::ComputeValueGradients(scalars, 0, dims, range, g);
  const double sigma[3] = { 1.0, 1.5, 0.7 };
  mmv::SmoothVectors(g, 3, dims, sigma);
  const double expected[3] = { 0.2, -0.1, 0.05 };
  for (int k = 4; k < dims[2] - 4; ++k)
    for (int j = 6; j < dims[1] - 6; ++j)
      for (int i = 4; i < dims[0] - 4; ++i)
        for (int a = 0; a < 3; ++a)
        {
          ASSERT_NEAR(g[3 * Index(dims, i, j, k) + a], expected[a], 1e-6)
            << i << " " << j << " " << k << " axis " << a;
        }
}

TEST(ValueGradient, SmoothingAnImpulseGivesTheGaussiansVariance)
{
  // One component, a unit impulse in the middle of a line: the blur keeps
  // the sum (normalised weights) and its variance is sigma^2 (truncation at
  // 3 sigma and sampling take 1 % of it at most from sigma = 1 up).
  const int dims[3] = { 41, 1, 1 };
  for (const double s : { 1.0, 1.5, 2.5 })
  {
    std::vector<float> v(41, 0.0f);
    v[20] = 1.0f;
    const double sigma[3] = { s, 0.0, 0.0 };
    mmv::SmoothVectors(v, 1, dims, sigma);
    double sum = 0.0;
    double variance = 0.0;
    for (int i = 0; i < 41; ++i)
    {
      sum += v[i];
      variance += v[i] * (i - 20.0) * (i - 20.0);
    }
    EXPECT_NEAR(sum, 1.0, 1e-6) << "sigma " << s;
    EXPECT_NEAR(variance, s * s, 0.01 * s * s) << "sigma " << s;
    EXPECT_EQ(v[20 + static_cast<int>(std::ceil(3.0 * s)) + 1], 0.0f) << "truncated at 3 sigma";
  }
}

TEST(ValueGradient, SmoothingIsRoundInWorldSpace)
{
  // The MR head's spacing: sigma 1 is 3.2 mm, one voxel in x and y, 2.13 in z.
  const double spacing[3] = { 3.2, 3.2, 1.5 };
  double voxels[3];
  mmv::GradientSmoothingVoxels(1.0, spacing, voxels);
  EXPECT_DOUBLE_EQ(voxels[0], 1.0);
  EXPECT_DOUBLE_EQ(voxels[1], 1.0);
  EXPECT_NEAR(voxels[2], 3.2 / 1.5, 1e-12);
  mmv::GradientSmoothingVoxels(0.0, spacing, voxels);
  EXPECT_EQ(voxels[0] + voxels[1] + voxels[2], 0.0);
}

TEST(ValueGradient, BadSmoothingValuesAreReported)
{
  std::string why;
  EXPECT_EQ(mmv::ValidGradientSmoothing(1.5, &why), 1.5);
  EXPECT_TRUE(why.empty());
  EXPECT_EQ(mmv::ValidGradientSmoothing(std::nan(""), &why), 0.0);
  EXPECT_NE(why.find("GradientSmoothing"), std::string::npos) << why;
  why.clear();
  EXPECT_EQ(mmv::ValidGradientSmoothing(-2.0, &why), 0.0);
  EXPECT_FALSE(why.empty());
  why.clear();
  EXPECT_EQ(mmv::ValidGradientSmoothing(100.0, &why), mmv::MaxGradientSmoothing);
  EXPECT_FALSE(why.empty());
  why.clear();
  EXPECT_EQ(mmv::ValidGradientSmoothing(std::numeric_limits<double>::infinity(), &why),
    mmv::MaxGradientSmoothing);
  EXPECT_FALSE(why.empty());
}

TEST(ValueGradient, HalfFloatsArePackedAsIEEEBinary16)
{
  // Exact halves: sign, exponent and mantissa bits of binary16.
  const std::vector<float> exact = { 0.0f, 1.0f, -2.0f, 0.5f, 65504.0f, 0.099975586f };
  const std::vector<unsigned short> bits = { 0x0000, 0x3C00, 0xC000, 0x3800, 0x7BFF, 0x2E66 };
  EXPECT_EQ(mmv::PackHalfFloats(exact), bits);
  // Any other value is within half a unit in the last place: 2^-11 relative.
  std::vector<float> values;
  for (int i = 1; i <= 100000; ++i)
  {
    values.push_back(std::ldexp(1.0f + i * 1e-5f, (i % 20) - 10) * (i % 2 ? 1.0f : -1.0f));
  }
  const std::vector<unsigned short> halves = mmv::PackHalfFloats(values);
  ASSERT_EQ(halves.size(), values.size());
  double worst = 0.0;
  for (size_t i = 0; i < values.size(); ++i)
  {
    const unsigned short h = halves[i];
    const int exponent = (h >> 10) & 0x1F;
    const double mantissa = 1.0 + (h & 0x3FF) / 1024.0;
    const double value = (h & 0x8000 ? -1.0 : 1.0) * std::ldexp(mantissa, exponent - 15);
    worst = std::max(worst, std::abs(value - values[i]) / std::abs(values[i]));
  }
  EXPECT_LE(worst, std::ldexp(1.0, -11));
}

// The gradient texture is uploaded a slab at a time: every slab partition
// gives PackHalfFloats(ComputeValueGradients(...)) bit for bit, on the
// volume's faces, at NaN and infinite values, and on a one-voxel-thick axis.
TEST(ValueGradient, HalfFloatSlabsEqualTheWholeVolumePacked)
{
  for (const int thickness : { 1, 7 })
  {
    const int dims[3] = { 9, thickness, 11 };
    vtkNew<vtkFloatArray> scalars;
    scalars->SetNumberOfTuples(dims[0] * dims[1] * dims[2]);
    for (vtkIdType v = 0; v < scalars->GetNumberOfTuples(); ++v)
    {
      // Irregular values, with a NaN and an infinity among them.
      scalars->SetValue(v, static_cast<float>(std::sin(0.7 * v) * 300.0 + (v % 13) * 11.0));
    }
    scalars->SetValue(40, std::numeric_limits<float>::quiet_NaN());
    scalars->SetValue(77, std::numeric_limits<float>::infinity());
    const double range[2] = { -300.0, 450.0 };
    std::vector<float> g;
    mmv::ComputeValueGradients(scalars, 0, dims, range, g);
    const std::vector<unsigned short> whole = mmv::PackHalfFloats(g);
    for (const int slab : { 1, 2, 4, 11 })
    {
      std::vector<unsigned short> assembled;
      std::vector<float> values;
      std::vector<unsigned short> halves;
      for (int first = 0; first < dims[2]; first += slab)
      {
        const int last = std::min(dims[2] - 1, first + slab - 1);
        mmv::ComputeHalfValueGradients(scalars, 0, dims, range, first, last, values, halves);
        ASSERT_EQ(halves.size(), 3u * dims[0] * dims[1] * (last - first + 1));
        assembled.insert(assembled.end(), halves.begin(), halves.end());
      }
      EXPECT_EQ(assembled, whole) << "thickness " << thickness << ", slabs of " << slab;
    }
  }
}
