// mmv::ComputeValueGradients (the gradient volume the ray caster shades with)
// against closed forms: a linear ramp's central differences are exact inside
// and one-sided halves on the faces; a quadratic's are exact at every
// interior voxel; non-finite values give no gradient.
#include "vtkValueGradient.h"

#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkUnsignedShortArray.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
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
        scalars->SetValue(Index(dims, i, j, k), static_cast<unsigned short>(3 * i + 5 * j - 2 * k + 100));
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
