// Tests of vtkPreIntegrationTable against direct numerical integration of the
// segment integrals and against closed forms for simple transfer functions.
#include "vtkPreIntegrationTable.h"

#include "mmvTestUtilities.h"
#include "vtkColorTransferFunction.h"
#include "vtkCommand.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMultiMaterialParameters.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <limits>
#include <random>
#include <utility>
#include <vector>

namespace
{

struct Segment
{
  double Alpha = 0.0;
  double RGB[3] = { 0.0, 0.0, 0.0 };
  double Sigma = 0.0;
};

// Direct integration of the segment model along x with `steps` midpoint
// samples, each treated as a homogeneous slab (exact compositing per slab).
Segment BruteForce(vtkPiecewiseFunction* otf, vtkColorTransferFunction* ctf,
  vtkMaterialTransferFunction* mtf, double length, double unitDistance, double t1, double t2,
  int steps = 4000)
{
  Segment s;
  double transmittance = 1.0;
  double tauSigma = 0.0;
  const double dx = length / steps;
  for (int k = 0; k < steps; ++k)
  {
    const double t = t1 + (t2 - t1) * (k + 0.5) / steps;
    const double mu = mmv::ExtinctionFromOpacity(otf->GetValue(t), unitDistance);
    double rgb[3] = { 1.0, 1.0, 1.0 };
    if (ctf)
    {
      ctf->GetColor(t, rgb);
    }
    const double a = -std::expm1(-mu * dx);
    for (int c = 0; c < 3; ++c)
    {
      s.RGB[c] += rgb[c] * a * transmittance;
    }
    transmittance *= 1.0 - a;
    tauSigma += (mtf ? mtf->EvaluateParameter(t, mmv::Attenuation) : 1.0) * mu * dx;
  }
  s.Alpha = 1.0 - transmittance;
  s.Sigma = -std::expm1(-tauSigma);
  return s;
}

// Random piecewise-linear TFs on [0, 1] with a fixed seed: interior nodes at
// random positions, opacities up to 0.9 with some exact zeros.
void MakeRandomFunctions(vtkPiecewiseFunction* otf, vtkColorTransferFunction* ctf,
  vtkMaterialTransferFunction* mtf, unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  otf->AddPoint(0.0, 0.0);
  otf->AddPoint(1.0, 0.5);
  for (int k = 0; k < 10; ++k)
  {
    const double opacity = unit(rng) < 0.25 ? 0.0 : 0.9 * unit(rng);
    otf->AddPoint(unit(rng), opacity);
  }
  if (ctf)
  {
    for (int k = 0; k < 8; ++k)
    {
      const double x = k == 0 ? 0.0 : (k == 7 ? 1.0 : unit(rng));
      const double r = unit(rng), g = unit(rng), b = unit(rng);
      ctf->AddRGBPoint(x, r, g, b);
    }
  }
  if (mtf)
  {
    for (int k = 0; k < 6; ++k)
    {
      mtf->AddNode(unit(rng), 0.2, 0.7, 0.2, 20.0, 2.0 * unit(rng), 0.0, 0.0);
    }
  }
}

std::size_t Index(int i, int j, int n)
{
  return static_cast<std::size_t>(j) * n + i;
}

double NodeValue(int i, int n)
{
  return static_cast<double>(i) / (n - 1);
}

// The table settings the accuracy tests share: range [0, 1].
void Configure(vtkPreIntegrationTable* table, vtkPiecewiseFunction* otf,
  vtkColorTransferFunction* ctf, vtkMaterialTransferFunction* mtf, double length, int n,
  double unitDistance = 1.0)
{
  table->SetScalarOpacity(otf);
  table->SetColorTransferFunction(ctf);
  table->SetMaterialTransferFunction(mtf);
  table->SetStepLength(length);
  table->SetScalarOpacityUnitDistance(unitDistance);
  table->SetTableSize(n);
  table->SetScalarRange(0.0, 1.0);
}

} // namespace

TEST(PreIntegrationTable, BruteForceOpacityAndColor)
{
  vtkNew<vtkPiecewiseFunction> otf;
  vtkNew<vtkColorTransferFunction> ctf;
  MakeRandomFunctions(otf, ctf, nullptr, 12345u);

  const int n = 128;
  const double length = 1.5;
  vtkNew<vtkPreIntegrationTable> table;
  Configure(table, otf, ctf, nullptr, length, n);
  ASSERT_TRUE(table->Update());
  const float* rgba = table->GetColorOpacityTable();
  ASSERT_NE(rgba, nullptr);

  // A coarse grid of entries plus every entry near the diagonal, where a
  // segment spans one or two cells and sub-cell TF detail matters most.
  double maxAlphaError = 0.0, maxColorError = 0.0, maxAlpha = 0.0;
  for (int j = 0; j < n; ++j)
  {
    for (int i = 0; i < n; ++i)
    {
      if (std::abs(i - j) > 2 && (i % 3 != 0 || j % 3 != 0))
      {
        continue;
      }
      const Segment ref =
        BruteForce(otf, ctf, nullptr, length, 1.0, NodeValue(i, n), NodeValue(j, n));
      const float* entry = rgba + 4 * Index(i, j, n);
      maxAlphaError = std::max(maxAlphaError, std::abs(entry[3] - ref.Alpha));
      maxAlpha = std::max(maxAlpha, ref.Alpha);
      for (int c = 0; c < 3; ++c)
      {
        maxColorError = std::max(maxColorError, std::abs(entry[c] - ref.RGB[c]));
      }
    }
  }
  std::cout << "n = " << n << ": max |I_alpha - brute force| = " << maxAlphaError
            << ", max |I_c - brute force| = " << maxColorError << " (max I_alpha " << maxAlpha
            << ")\n";
  // The TFs must be demanding enough for the comparison to mean something.
  EXPECT_GT(maxAlpha, 0.8);
  // Measured: 3.9e-7 (opacity: closed-form extinction integrals, float
  // storage) and 1.0e-4 (colour: largest for one-cell segments, from fitting
  // the colour as linear in optical depth within each piece of a cell).
  EXPECT_LT(maxAlphaError, 1e-6);
  EXPECT_LT(maxColorError, 2e-4);

  // Opacity does not depend on the direction of traversal.
  for (int j = 0; j < n; ++j)
  {
    for (int i = 0; i < j; ++i)
    {
      ASSERT_FLOAT_EQ(rgba[4 * Index(i, j, n) + 3], rgba[4 * Index(j, i, n) + 3]);
    }
  }
}

TEST(PreIntegrationTable, BruteForceShadowOpacity)
{
  vtkNew<vtkPiecewiseFunction> otf;
  vtkNew<vtkMaterialTransferFunction> mtf;
  MakeRandomFunctions(otf, nullptr, mtf, 777u);
  ASSERT_EQ(mtf->GetSize(), 6);

  const int n = 96;
  const double length = 1.6;
  const double unitDistance = 0.5;
  vtkNew<vtkPreIntegrationTable> table;
  Configure(table, otf, nullptr, mtf, length, n, unitDistance);
  ASSERT_TRUE(table->Update());
  const float* shadow = table->GetShadowOpacityTable();
  ASSERT_NE(shadow, nullptr);

  double maxError = 0.0, maxSigma = 0.0;
  for (int j = 0; j < n; j += 3)
  {
    for (int i = 0; i < n; i += 3)
    {
      const Segment ref =
        BruteForce(otf, nullptr, mtf, length, unitDistance, NodeValue(i, n), NodeValue(j, n));
      maxError = std::max(maxError, std::abs(shadow[Index(i, j, n)] - ref.Sigma));
      maxSigma = std::max(maxSigma, ref.Sigma);
    }
  }
  std::cout << "n = " << n << ": max |I_sigma - brute force| = " << maxError << " (max I_sigma "
            << maxSigma << ")\n";
  EXPECT_GT(maxSigma, 0.8);
  // Measured: 9.6e-7.
  EXPECT_LT(maxError, 2e-6);
}

TEST(PreIntegrationTable, DiagonalLimitAndConstantColor)
{
  vtkNew<vtkPiecewiseFunction> otf;
  MakeRandomFunctions(otf, nullptr, nullptr, 4242u);
  vtkNew<vtkColorTransferFunction> ctf;
  const double color[3] = { 0.3, 0.6, 0.9 };
  ctf->AddRGBPoint(0.5, color[0], color[1], color[2]);

  const int n = 64;
  const double length = 2.0;
  vtkNew<vtkPreIntegrationTable> table;
  Configure(table, otf, ctf, nullptr, length, n);
  ASSERT_TRUE(table->Update());
  const float* rgba = table->GetColorOpacityTable();

  for (int i = 0; i < n; ++i)
  {
    const double mu = mmv::ExtinctionFromOpacity(otf->GetValue(NodeValue(i, n)), 1.0);
    EXPECT_NEAR(rgba[4 * Index(i, i, n) + 3], 1.0 - std::exp(-length * mu), 1e-6) << "i = " << i;
  }
  for (int j = 0; j < n; ++j)
  {
    for (int i = 0; i < n; ++i)
    {
      const float* entry = rgba + 4 * Index(i, j, n);
      for (int c = 0; c < 3; ++c)
      {
        ASSERT_NEAR(entry[c], color[c] * entry[3], 1e-6) << "i = " << i << ", j = " << j;
      }
    }
  }
}

TEST(PreIntegrationTable, SharpStep)
{
  // Opacity 0 below 0.4 and 0.8 above; the step lies inside a table cell.
  const double step = 0.4037;
  const double high = 0.8;
  vtkNew<vtkPiecewiseFunction> otf;
  otf->AddPoint(0.0, 0.0);
  otf->AddPoint(step, 0.0);
  otf->AddPoint(step + 1e-9, high);
  otf->AddPoint(1.0, high);

  const int n = 101;
  const double length = 1.3;
  const double cell = 1.0 / (n - 1);
  vtkNew<vtkPreIntegrationTable> table;
  Configure(table, otf, nullptr, nullptr, length, n);
  ASSERT_TRUE(table->Update());

  const double muHigh = mmv::ExtinctionFromOpacity(high, 1.0);
  const double segments[][2] = { { 0.1, 0.9 }, { 0.3, 0.5 }, { 0.123, 0.877 }, { 0.40, 0.41 } };
  for (const auto& seg : segments)
  {
    const double t1 = seg[0], t2 = seg[1];
    const double above = (t2 - step) / (t2 - t1);
    const double expected = 1.0 - std::exp(-muHigh * length * above);
    // On table nodes only quadrature and float rounding remain; between nodes
    // the bilinear lookup adds its interpolation error.
    const bool onNodes = std::abs(t1 * (n - 1) - std::round(t1 * (n - 1))) < 1e-9 &&
      std::abs(t2 * (n - 1) - std::round(t2 * (n - 1))) < 1e-9;
    EXPECT_NEAR(table->LookupOpacity(t1, t2), expected, onNodes ? 1e-6 : 2e-3)
      << t1 << " -> " << t2;
    EXPECT_NEAR(table->LookupShadingPosition(t1, t2), 1.0 - above, 0.5 * cell / (t2 - t1))
      << t1 << " -> " << t2;
    // Back to front: the front is already opaque.
    EXPECT_NEAR(table->LookupOpacity(t2, t1), expected, onNodes ? 1e-6 : 2e-3);
    EXPECT_FLOAT_EQ(table->LookupShadingPosition(t2, t1), 0.0f);
  }
}

TEST(PreIntegrationTable, ThinSpikeBetweenNodes)
{
  // A triangular spike of half-width 0.002 between table nodes 1/63 apart:
  // sampling the OTF at the nodes alone would miss it completely.
  const double centre = 0.5, halfWidth = 0.002, peak = 0.9;
  vtkNew<vtkPiecewiseFunction> otf;
  otf->AddPoint(0.0, 0.0);
  otf->AddPoint(centre - halfWidth, 0.0);
  otf->AddPoint(centre, peak);
  otf->AddPoint(centre + halfWidth, 0.0);
  otf->AddPoint(1.0, 0.0);

  const int n = 64;
  const double length = 1.0;
  vtkNew<vtkPreIntegrationTable> table;
  Configure(table, otf, nullptr, nullptr, length, n);
  ASSERT_TRUE(table->Update());

  // int mu dt over the spike: 2 (w/p) (p + (1-p) ln(1-p)).
  const double spike = 2.0 * halfWidth / peak * (peak + (1.0 - peak) * std::log(1.0 - peak));
  const int pairs[][2] = { { 31, 32 }, { 30, 33 }, { 20, 40 }, { 0, 63 }, { 45, 10 } };
  for (const auto& p : pairs)
  {
    const double t1 = NodeValue(p[0], n), t2 = NodeValue(p[1], n);
    const double expected = 1.0 - std::exp(-length * spike / std::abs(t2 - t1));
    EXPECT_NEAR(table->LookupOpacity(t1, t2), expected, 1e-6) << t1 << " -> " << t2;
    const double before = std::abs((t1 < t2 ? centre - halfWidth : centre + halfWidth) - t1);
    EXPECT_NEAR(table->LookupShadingPosition(t1, t2), before / std::abs(t2 - t1), 1e-6);
  }
  EXPECT_GT(table->LookupOpacity(NodeValue(31, n), NodeValue(32, n)), 0.1);
}

TEST(PreIntegrationTable, ShadingPositionLimits)
{
  vtkNew<vtkPiecewiseFunction> otf;
  otf->AddPoint(0.0, 0.0);
  otf->AddPoint(0.3, 0.0);
  otf->AddPoint(0.5, 0.6);
  otf->AddPoint(0.7, 0.6);
  otf->AddPoint(0.8, 0.0);
  otf->AddPoint(1.0, 0.0);

  vtkNew<vtkPreIntegrationTable> table;
  Configure(table, otf, nullptr, nullptr, 1.0, 101);
  ASSERT_TRUE(table->Update());

  // Front value opaque.
  EXPECT_DOUBLE_EQ(table->LookupShadingPosition(0.6, 0.9), 0.0);
  EXPECT_DOUBLE_EQ(table->LookupShadingPosition(0.6, 0.1), 0.0);
  EXPECT_DOUBLE_EQ(table->LookupShadingPosition(0.6, 0.6), 0.0);
  // All transparent.
  EXPECT_DOUBLE_EQ(table->LookupShadingPosition(0.05, 0.25), 1.0);
  EXPECT_DOUBLE_EQ(table->LookupShadingPosition(0.95, 0.85), 1.0);
  EXPECT_DOUBLE_EQ(table->LookupShadingPosition(0.1, 0.1), 1.0);
  EXPECT_DOUBLE_EQ(table->LookupOpacity(0.05, 0.25), 0.0);
  // Up to and including the node where opacity starts to rise is transparent.
  EXPECT_DOUBLE_EQ(table->LookupShadingPosition(0.1, 0.3), 1.0);
  EXPECT_NEAR(table->LookupShadingPosition(0.1, 0.5), 0.5, 1e-6);
  EXPECT_NEAR(table->LookupShadingPosition(0.9, 0.0), 0.1 / 0.9, 1e-6);
  EXPECT_NEAR(table->LookupShadingPosition(0.3, 0.9), 0.0, 1e-6);
}

TEST(PreIntegrationTable, ShadowAttenuation)
{
  vtkNew<vtkPiecewiseFunction> otf;
  MakeRandomFunctions(otf, nullptr, nullptr, 99u);
  const int n = 48;
  vtkNew<vtkPreIntegrationTable> table;
  Configure(table, otf, nullptr, nullptr, 1.7, n);

  // No material function: attenuation 1, shadow opacity == opacity.
  ASSERT_TRUE(table->Update());
  const std::size_t entries = static_cast<std::size_t>(n) * n;
  for (std::size_t k = 0; k < entries; ++k)
  {
    ASSERT_FLOAT_EQ(table->GetShadowOpacityTable()[k], table->GetColorOpacityTable()[4 * k + 3]);
  }

  vtkNew<vtkMaterialTransferFunction> mtf;
  ASSERT_GE(mtf->AddNode(0.5, 0.2, 0.7, 0.2, 20.0, 0.0, 0.0, 0.0), 0);
  table->SetMaterialTransferFunction(mtf);
  ASSERT_TRUE(table->Update());
  double maxShadow = 0.0;
  for (std::size_t k = 0; k < entries; ++k)
  {
    maxShadow = std::max(maxShadow, static_cast<double>(table->GetShadowOpacityTable()[k]));
  }
  EXPECT_EQ(maxShadow, 0.0);

  ASSERT_GE(mtf->AddNode(0.5, 0.2, 0.7, 0.2, 20.0, 2.0, 0.0, 0.0), 0);
  ASSERT_TRUE(table->Update());
  double maxAlpha = 0.0;
  for (std::size_t k = 0; k < entries; ++k)
  {
    const double alpha = table->GetColorOpacityTable()[4 * k + 3];
    maxAlpha = std::max(maxAlpha, alpha);
    ASSERT_NEAR(table->GetShadowOpacityTable()[k], 1.0 - (1.0 - alpha) * (1.0 - alpha), 1e-6)
      << "entry " << k;
  }
  EXPECT_GT(maxAlpha, 0.5);
}

TEST(PreIntegrationTable, RebuildsOnlyWhenInputsChange)
{
  vtkNew<vtkPiecewiseFunction> otf;
  otf->AddPoint(0.0, 0.0);
  otf->AddPoint(1.0, 0.5);
  vtkNew<vtkColorTransferFunction> ctf;
  ctf->AddRGBPoint(0.0, 1.0, 0.0, 0.0);
  vtkNew<vtkMaterialTransferFunction> mtf;
  vtkNew<vtkPreIntegrationTable> table;
  table->SetScalarOpacity(otf);
  table->SetColorTransferFunction(ctf);
  table->SetMaterialTransferFunction(mtf);
  table->SetTableSize(32);

  EXPECT_EQ(table->GetBuildCount(), 0);
  ASSERT_TRUE(table->Update());
  ASSERT_TRUE(table->Update());
  EXPECT_EQ(table->GetBuildCount(), 1);

  const double before = table->LookupOpacity(0.5, 0.5);
  otf->AddPoint(0.5, 0.9);
  ASSERT_TRUE(table->Update());
  EXPECT_EQ(table->GetBuildCount(), 2);
  EXPECT_GT(table->LookupOpacity(0.5, 0.5), before);

  table->SetStepLength(2.0);
  ASSERT_TRUE(table->Update());
  ASSERT_TRUE(table->Update());
  EXPECT_EQ(table->GetBuildCount(), 3);

  table->SetStepLength(2.0); // same value: not a change
  ASSERT_TRUE(table->Update());
  EXPECT_EQ(table->GetBuildCount(), 3);

  ctf->AddRGBPoint(1.0, 0.0, 0.0, 1.0);
  ASSERT_TRUE(table->Update());
  EXPECT_EQ(table->GetBuildCount(), 4);

  mtf->AddNode(0.5, 0.2, 0.7, 0.2, 20.0, 0.5, 0.0, 0.0);
  ASSERT_TRUE(table->Update());
  EXPECT_EQ(table->GetBuildCount(), 5);

  table->SetTableSize(16);
  ASSERT_TRUE(table->Update());
  EXPECT_EQ(table->GetBuildCount(), 6);
  EXPECT_GE(table->GetLastBuildSeconds(), 0.0);
}

// A fresh table of the same inputs: what every rebuild must equal, bit for bit.
void ExpectSameTables(vtkPreIntegrationTable* built, vtkPiecewiseFunction* otf,
  vtkColorTransferFunction* ctf, vtkMaterialTransferFunction* mtf, int n, const char* what)
{
  vtkNew<vtkPreIntegrationTable> fresh;
  fresh->SetScalarOpacity(otf);
  fresh->SetColorTransferFunction(ctf);
  fresh->SetMaterialTransferFunction(mtf);
  fresh->SetScalarRange(0.0, 100.0);
  fresh->SetStepLength(0.7);
  fresh->SetScalarOpacityUnitDistance(2.0);
  fresh->SetTableSize(n);
  ASSERT_TRUE(fresh->Update());
  const size_t entries = static_cast<size_t>(n) * n;
  const auto same = [&](const float* a, const float* b, size_t count)
  { return a && b && std::equal(a, a + count, b); };
  EXPECT_TRUE(same(built->GetColorOpacityTable(), fresh->GetColorOpacityTable(), 4 * entries))
    << what;
  EXPECT_TRUE(same(built->GetShadingPositionTable(), fresh->GetShadingPositionTable(), entries))
    << what;
  EXPECT_TRUE(same(built->GetShadowOpacityTable(), fresh->GetShadowOpacityTable(), entries))
    << what;
  EXPECT_TRUE(same(built->GetShadowTintTable(), fresh->GetShadowTintTable(), 4 * entries)) << what;
}

// A colour edit recomputes the colour channels alone, from the opacity parts
// the last full build kept, and gives the bits a full build gives; a moved
// colour node, an opacity or a material edit, and tables too large to keep
// those parts rebuild whole.
TEST(PreIntegrationTable, ColourEditsRebuildTheColoursAloneToTheSameBits)
{
  for (const int n : { 64, 520 })
  {
    vtkNew<vtkPiecewiseFunction> otf;
    otf->AddPoint(0.0, 0.0);
    otf->AddPoint(20.0, 0.0);
    otf->AddPoint(35.0, 0.3, 0.3, 0.7); // curved: the Gauss rule's pieces
    otf->AddPoint(60.0, 0.9);
    otf->AddPoint(100.0, 0.95);
    vtkNew<vtkColorTransferFunction> ctf;
    ctf->AddRGBPoint(0.0, 0.1, 0.1, 0.1);
    ctf->AddRGBPoint(40.0, 0.8, 0.3, 0.2);
    ctf->AddRGBPoint(100.0, 1.0, 1.0, 0.9);
    vtkNew<vtkMaterialTransferFunction> mtf; // tinted shadows: every table
    mtf->AddNode(30.0, 0.2, 0.7, 0.2, 20.0, 1.5, 0.0, 0.0, 0.0, 0.0, 0.9, 0.5, 0.3);
    vtkNew<vtkPreIntegrationTable> table;
    table->SetScalarOpacity(otf);
    table->SetColorTransferFunction(ctf);
    table->SetMaterialTransferFunction(mtf);
    table->SetScalarRange(0.0, 100.0);
    table->SetStepLength(0.7);
    table->SetScalarOpacityUnitDistance(2.0);
    table->SetTableSize(n);
    ASSERT_TRUE(table->Update());
    ASSERT_NE(table->GetShadowTintTable(), nullptr);
    const bool kept = n <= 512;

    ctf->AddRGBPoint(40.0, 0.2, 0.9, 0.4); // the same node, a new colour
    ASSERT_TRUE(table->Update());
    EXPECT_EQ(table->GetBuildCount(), 2);
    EXPECT_EQ(table->GetColorOnlyBuildCount(), kept ? 1 : 0) << n;
    ExpectSameTables(table, otf, ctf, mtf, n, "after a colour edit");

    ctf->AddRGBPoint(70.0, 0.5, 0.5, 1.0); // a new node splits cells
    ASSERT_TRUE(table->Update());
    EXPECT_EQ(table->GetColorOnlyBuildCount(), kept ? 1 : 0) << n;
    ExpectSameTables(table, otf, ctf, mtf, n, "after a new colour node");

    otf->AddPoint(60.0, 0.7);
    ASSERT_TRUE(table->Update());
    EXPECT_EQ(table->GetColorOnlyBuildCount(), kept ? 1 : 0) << n;
    ExpectSameTables(table, otf, ctf, mtf, n, "after an opacity edit");

    ctf->AddRGBPoint(70.0, 0.9, 0.1, 0.1);
    ASSERT_TRUE(table->Update());
    EXPECT_EQ(table->GetColorOnlyBuildCount(), kept ? 2 : 0) << n;
    ExpectSameTables(table, otf, ctf, mtf, n, "after a second colour edit");

    mtf->AddNode(30.0, 0.2, 0.7, 0.2, 20.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.4, 0.8, 0.9);
    ASSERT_TRUE(table->Update());
    EXPECT_EQ(table->GetColorOnlyBuildCount(), kept ? 2 : 0) << n;
    ExpectSameTables(table, otf, ctf, mtf, n, "after a material edit");
    EXPECT_EQ(table->GetBuildCount(), 6);
  }
}

TEST(PreIntegrationTable, InvalidSettingsKeepPreviousTable)
{
  vtkNew<vtkPiecewiseFunction> otf;
  otf->AddPoint(0.0, 0.1);
  otf->AddPoint(1.0, 0.7);
  vtkNew<vtkPreIntegrationTable> table;
  mmvtest::ErrorCounter errors(table);

  // Nothing built yet: lookups give 0.
  EXPECT_FALSE(table->Update());
  EXPECT_EQ(errors.Errors(), 1);
  EXPECT_EQ(table->GetBuildCount(), 0);
  EXPECT_EQ(table->LookupOpacity(0.2, 0.8), 0.0);
  EXPECT_EQ(table->LookupShadowOpacity(0.2, 0.8), 0.0);
  EXPECT_EQ(table->LookupShadingPosition(0.2, 0.8), 0.0);
  double rgba[4] = { -1.0, -1.0, -1.0, -1.0 };
  table->LookupColor(0.2, 0.8, rgba);
  for (double v : rgba)
  {
    EXPECT_EQ(v, 0.0);
  }

  table->SetScalarOpacity(otf);
  table->SetTableSize(16);
  ASSERT_TRUE(table->Update());
  ASSERT_EQ(table->GetBuildCount(), 1);
  const std::vector<float> good(
    table->GetColorOpacityTable(), table->GetColorOpacityTable() + 4 * 16 * 16);
  const double goodOpacity = table->LookupOpacity(0.2, 0.8);
  ASSERT_GT(goodOpacity, 0.0);

  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  using Table = vtkPreIntegrationTable;
  const std::vector<std::pair<const char*, std::function<void(Table*)>>> cases = {
    { "no opacity", [](Table* t) { t->SetScalarOpacity(nullptr); } },
    { "step 0", [](Table* t) { t->SetStepLength(0.0); } },
    { "step < 0", [](Table* t) { t->SetStepLength(-1.0); } },
    { "step NaN", [&](Table* t) { t->SetStepLength(nan); } },
    { "step inf", [&](Table* t) { t->SetStepLength(inf); } },
    { "unit 0", [](Table* t) { t->SetScalarOpacityUnitDistance(0.0); } },
    { "unit NaN", [&](Table* t) { t->SetScalarOpacityUnitDistance(nan); } },
    { "size 1", [](Table* t) { t->SetTableSize(1); } },
    { "size 4097", [](Table* t) { t->SetTableSize(4097); } },
  };
  for (const auto& c : cases)
  {
    const int builds = table->GetBuildCount();
    errors.Reset();
    c.second(table);
    EXPECT_FALSE(table->Update()) << c.first;
    EXPECT_EQ(errors.Errors(), 1) << c.first;
    EXPECT_EQ(table->GetBuildCount(), builds) << c.first;
    EXPECT_EQ(table->LookupOpacity(0.2, 0.8), goodOpacity) << c.first;
    ASSERT_NE(table->GetColorOpacityTable(), nullptr);
    EXPECT_TRUE(std::equal(good.begin(), good.end(), table->GetColorOpacityTable())) << c.first;

    // Restoring valid settings rebuilds (the settings changed) the same table.
    table->SetScalarOpacity(otf);
    table->SetStepLength(1.0);
    table->SetScalarOpacityUnitDistance(1.0);
    table->SetTableSize(16);
    errors.Reset();
    EXPECT_TRUE(table->Update()) << c.first;
    EXPECT_EQ(errors.Errors(), 0) << c.first;
    EXPECT_EQ(table->GetBuildCount(), builds + 1) << c.first;
    EXPECT_TRUE(std::equal(good.begin(), good.end(), table->GetColorOpacityTable())) << c.first;
  }
}

TEST(PreIntegrationTable, TableRangeIsTheRangeActuallyUsed)
{
  vtkNew<vtkPreIntegrationTable> table;
  table->SetTableSize(8);
  double range[2] = { -1.0, -1.0 };
  table->GetTableRange(range);
  EXPECT_EQ(range[0], 0.0); // nothing built yet
  EXPECT_EQ(range[1], 1.0);

  vtkNew<vtkPiecewiseFunction> otf;
  otf->AddPoint(-1.0, 0.1);
  otf->AddPoint(3.0, 0.7);
  table->SetScalarOpacity(otf);
  table->SetScalarRange(2.0, 5.0); // an explicit range wins
  ASSERT_TRUE(table->Update());
  table->GetTableRange(range);
  EXPECT_EQ(range[0], 2.0);
  EXPECT_EQ(range[1], 5.0);

  table->SetScalarRange(0.0, 0.0); // empty: the opacity TF's range
  ASSERT_TRUE(table->Update());
  table->GetTableRange(range);
  EXPECT_EQ(range[0], -1.0);
  EXPECT_EQ(range[1], 3.0);

  vtkNew<vtkPiecewiseFunction> single; // empty TF range too: [t, t + 1]
  single->AddPoint(4.0, 0.5);
  table->SetScalarOpacity(single);
  ASSERT_TRUE(table->Update());
  table->GetTableRange(range);
  EXPECT_EQ(range[0], 4.0);
  EXPECT_EQ(range[1], 5.0);

  // A failed build keeps the previous tables, and so their range.
  mmvtest::ErrorCounter errors(table);
  table->SetScalarRange(7.0, 9.0);
  table->SetStepLength(0.0);
  EXPECT_FALSE(table->Update());
  EXPECT_EQ(errors.Errors(), 1);
  table->GetTableRange(range);
  EXPECT_EQ(range[0], 4.0);
  EXPECT_EQ(range[1], 5.0);
}

TEST(PreIntegrationTable, LookupInterpolatesAndClamps)
{
  vtkNew<vtkPiecewiseFunction> otf;
  otf->AddPoint(10.0, 0.0);
  otf->AddPoint(14.0, 0.6);
  otf->AddPoint(20.0, 0.2);
  vtkNew<vtkColorTransferFunction> ctf;
  ctf->AddRGBPoint(10.0, 0.0, 0.5, 1.0);
  ctf->AddRGBPoint(20.0, 1.0, 0.5, 0.0);

  const int n = 11;
  vtkNew<vtkPreIntegrationTable> table;
  table->SetScalarOpacity(otf);
  table->SetColorTransferFunction(ctf);
  table->SetTableSize(n); // ScalarRange unset: the OTF's range [10, 20], d = 1
  ASSERT_TRUE(table->Update());
  const float* rgba = table->GetColorOpacityTable();

  EXPECT_FLOAT_EQ(table->LookupOpacity(13.0, 17.0), rgba[4 * Index(3, 7, n) + 3]);
  const double mid = 0.25 *
    (rgba[4 * Index(3, 7, n) + 3] + rgba[4 * Index(4, 7, n) + 3] + rgba[4 * Index(3, 8, n) + 3] +
      rgba[4 * Index(4, 8, n) + 3]);
  EXPECT_NEAR(table->LookupOpacity(13.5, 17.5), mid, 1e-6);
  double c[4];
  table->LookupColor(13.0, 17.0, c);
  for (int k = 0; k < 4; ++k)
  {
    EXPECT_FLOAT_EQ(c[k], rgba[4 * Index(3, 7, n) + k]);
  }
  // Outside the range values clamp to the edge of the table.
  EXPECT_DOUBLE_EQ(table->LookupOpacity(-100.0, 100.0), table->LookupOpacity(10.0, 20.0));
  EXPECT_DOUBLE_EQ(table->LookupOpacity(25.0, 14.0), table->LookupOpacity(20.0, 14.0));
  EXPECT_NEAR(table->LookupOpacity(20.0, 14.0), rgba[4 * Index(10, 4, n) + 3], 1e-7);

  // A degenerate range (single node) still builds finite tables.
  vtkNew<vtkPiecewiseFunction> single;
  single->AddPoint(5.0, 0.5);
  table->SetScalarOpacity(single);
  ASSERT_TRUE(table->Update());
  const double alpha = table->LookupOpacity(5.0, 5.0);
  EXPECT_TRUE(std::isfinite(alpha));
  EXPECT_NEAR(alpha, 0.5, 1e-6); // alpha per unit distance over L = u = 1
}

TEST(PreIntegrationTable, FullSizeTableStaysInBounds)
{
  vtkNew<vtkPiecewiseFunction> otf;
  vtkNew<vtkColorTransferFunction> ctf;
  vtkNew<vtkMaterialTransferFunction> mtf;
  MakeRandomFunctions(otf, ctf, mtf, 2024u);
  vtkNew<vtkPreIntegrationTable> table;
  table->SetScalarOpacity(otf);
  table->SetColorTransferFunction(ctf);
  table->SetMaterialTransferFunction(mtf);
  table->SetTableSize(256);
  table->SetScalarRange(0.0, 1.0);
  ASSERT_TRUE(table->Update());
  std::cout << "n = 256 build: " << table->GetLastBuildSeconds() << " s\n";
  const std::size_t entries = 256 * 256;
  for (std::size_t k = 0; k < entries; ++k)
  {
    const float* entry = table->GetColorOpacityTable() + 4 * k;
    for (int c = 0; c < 3; ++c)
    {
      // Opacity-weighted colour never exceeds the opacity (colours <= 1).
      ASSERT_LE(entry[c], entry[3] + 1e-6f) << "entry " << k;
      ASSERT_GE(entry[c], 0.0f);
    }
    ASSERT_GE(table->GetShadingPositionTable()[k], 0.0f);
    ASSERT_LE(table->GetShadingPositionTable()[k], 1.0f);
  }
}

TEST(PreIntegrationTable, FullyOpaqueNodesAreClampedNotRecursedOn)
{
  // ParaView's default opacity ramp reaches 1.0, above mmv::MaxOpacity: the
  // build must clamp (it once recursed without end there).
  vtkNew<vtkPiecewiseFunction> otf;
  otf->AddPoint(0.0, 0.0);
  otf->AddPoint(1.0, 1.0);
  vtkNew<vtkPreIntegrationTable> table;
  table->SetScalarOpacity(otf);
  table->SetTableSize(64);
  table->SetStepLength(0.5);
  ASSERT_TRUE(table->Update());
  const double clampedDepth = -std::log1p(-mmv::MaxOpacity);
  // A homogeneous segment at the opaque end: the clamped extinction.
  EXPECT_NEAR(table->LookupOpacity(1.0, 1.0), 1.0 - std::exp(-0.5 * clampedDepth), 1e-6);
  // Segments crossing into the clamp stay finite and inside [0, 1].
  for (double t1 : { 0.0, 0.5, 0.99 })
  {
    const double a = table->LookupOpacity(t1, 1.0);
    EXPECT_TRUE(std::isfinite(a));
    EXPECT_GE(a, 0.0);
    EXPECT_LE(a, 1.0);
  }
  EXPECT_GT(table->LookupOpacity(0.99, 1.0), table->LookupOpacity(0.5, 1.0));
}
