// Selective absorption: a transmission colour T tints the
// shadows a material casts, sigma_lambda = c_t mu (1 - ln T_lambda)
// (vtkMultiMaterialParameters.h). Closed forms on a homogeneous slab for the
// CPU irradiance filter and the GPU pass, grey materials unchanged, and
// shaders without RGB code unless a material is tinted.
#include "mmvTestUtilities.h"

#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkIrradianceVolumeFilter.h"
#include "vtkLight.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMultiMaterialParameters.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPreIntegrationTable.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

namespace
{
// The slab: value 1 everywhere, opacity Alpha per unit distance U,
// attenuation Ct, transmission colour T; light along +x.
constexpr double Alpha = 0.3, U = 2.0, Ct = 1.5, Spacing = 0.5;
constexpr int SlabDims[3] = { 21, 9, 7 };
const double T[3] = { 0.9, 0.5, 0.2 };

vtkSmartPointer<vtkImageData> Slab()
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(SlabDims[0], SlabDims[1], SlabDims[2]);
  image->SetSpacing(Spacing, Spacing, Spacing);
  vtkNew<vtkFloatArray> scalars;
  scalars->SetName("density");
  scalars->SetNumberOfTuples(image->GetNumberOfPoints());
  scalars->Fill(1.0);
  image->GetPointData()->SetScalars(scalars);
  return image;
}

vtkSmartPointer<vtkPiecewiseFunction> Opacity()
{
  auto otf = vtkSmartPointer<vtkPiecewiseFunction>::New();
  otf->AddPoint(0.0, Alpha);
  otf->AddPoint(2.0, Alpha);
  return otf;
}

vtkSmartPointer<vtkLight> LightAlongX()
{
  auto light = vtkSmartPointer<vtkLight>::New();
  light->SetPositional(false);
  light->SetFocalPoint(0.0, 0.0, 0.0);
  light->SetPosition(1.0, 0.0, 0.0); // toward +x
  return light;
}

vtkSmartPointer<vtkIrradianceVolumeFilter> SlabFilter(
  vtkMaterialTransferFunction* material, int divisor, int estimation)
{
  auto filter = vtkSmartPointer<vtkIrradianceVolumeFilter>::New();
  filter->SetInputData(Slab());
  filter->SetScalarOpacity(Opacity());
  filter->SetScalarOpacityUnitDistance(U);
  filter->SetMaterialTransferFunction(material);
  filter->SetIrradianceScale(1.0);
  filter->SetShadowEstimation(estimation);
  filter->SetTintResolutionDivisor(divisor);
  filter->MultipleScatteringOff();
  filter->AddLight(LightAlongX());
  filter->Update();
  return filter;
}

vtkFloatArray* Array(vtkIrradianceVolumeFilter* filter, const std::string& name)
{
  return vtkFloatArray::SafeDownCast(filter->GetOutput()->GetPointData()->GetArray(name.c_str()));
}

/// The closed form: grey depth tau = c_t mu d to the slab's +x face, channel
/// lambda arrives as exp(-tau (1 - ln T_lambda)) = exp(-tau) T_lambda^tau.
double Expected(int i, int channel)
{
  const double mu = -std::log(1.0 - Alpha) / U;
  const double depth = (SlabDims[0] - 1 - i) * Spacing;
  const double tau = Ct * mu * depth;
  return std::exp(-tau * mmv::TransmissionWeight(T[channel]));
}
} // namespace

// CPU model: grey irradiance times tint equals the closed form per channel,
// at full tint resolution everywhere and, compressed (tint on every second
// point), exactly on the tint grid's points; between them the linear
// interpolation of an exponential stays within its bound.
TEST(OpticalModel, RGBShadowOfATintedSlabIsTheClosedFormOnTheCPU)
{
  vtkNew<vtkMaterialTransferFunction> material;
  material->AddNode(0.0, 0.2, 0.7, 0.2, 20.0, Ct, 0.0, 0.0, 0.0, 0.0, T[0], T[1], T[2]);
  for (int estimation : { mmv::FullShadowRays, mmv::PiecewiseShadowRays })
  {
    for (int divisor : { 1, 2 })
    {
      SCOPED_TRACE(
        "estimation " + std::to_string(estimation) + " divisor " + std::to_string(divisor));
      auto filter = SlabFilter(material, divisor, estimation);
      vtkFloatArray* grey = Array(filter, "Irradiance_0");
      vtkFloatArray* tint = Array(filter, "IrradianceTint_0");
      ASSERT_NE(grey, nullptr);
      ASSERT_NE(tint, nullptr);
      ASSERT_EQ(tint->GetNumberOfComponents(), 3);
      double onGrid = 0.0, between = 0.0;
      const int nx = SlabDims[0], nxy = SlabDims[0] * SlabDims[1];
      for (vtkIdType v = 0; v < grey->GetNumberOfTuples(); ++v)
      {
        const int i = static_cast<int>(v % nx);
        const int j = static_cast<int>((v / nx) % SlabDims[1]);
        const int k = static_cast<int>(v / nxy);
        const bool tintPoint = divisor == 1 || (i % 2 == 0 && j % 2 == 0 && k % 2 == 0);
        for (int c = 0; c < 3; ++c)
        {
          const double rgb = grey->GetValue(v) * tint->GetComponent(v, c);
          const double error = std::abs(rgb - Expected(i, c)) / Expected(i, c);
          (tintPoint ? onGrid : between) = std::max(tintPoint ? onGrid : between, error);
        }
      }
      // Float rounding (the table is exact for a constant value).
      EXPECT_LT(onGrid, 1.0e-4);
      if (divisor == 2)
      {
        // Linear interpolation of K = exp(-k x) over two voxels, at the
        // midpoint: relative error cosh(k h) - 1 with k h the selective depth
        // of one voxel (blue: c_t mu 0.5 (-ln 0.2) = 0.216), 0.023.
        const double kh = Ct * (-std::log(1.0 - Alpha) / U) * Spacing * -std::log(T[2]);
        EXPECT_LT(between, std::cosh(kh) - 1.0 + 1.0e-4);
        EXPECT_GT(between, 0.5 * (std::cosh(kh) - 1.0)); // the compression is measured
      }
    }
  }
}

// A white transmission colour is grey: no tint table, no tint arrays, and
// the grey irradiance is bitwise what the 10-number node (before the colour
// existed) gives; so is a JSON node without the keys.
TEST(OpticalModel, GreyTransmissionIsTodaysScalarAttenuation)
{
  vtkNew<vtkMaterialTransferFunction> old;
  const double ten[10] = { 0.0, 0.2, 0.7, 0.2, 20.0, Ct, 0.0, 0.0, 0.0, 0.0 };
  ASSERT_TRUE(old->SetNodes(10, ten));
  vtkNew<vtkMaterialTransferFunction> white;
  white->AddNode(0.0, 0.2, 0.7, 0.2, 20.0, Ct, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0);
  vtkNew<vtkMaterialTransferFunction> json;
  ASSERT_TRUE(json->FromJSON(R"({"nodes": [{"value": 0, "ambient": 0.2, "diffuse": 0.7,
    "specular": 0.2, "shininess": 20, "attenuation": 1.5}]})"));
  vtkNew<vtkMaterialTransferFunction> added;
  added->AddNode(0.0, 0.2, 0.7, 0.2, 20.0, Ct, 0.0, 0.0);
  EXPECT_FALSE(white->HasChromaticTransmission());
  EXPECT_EQ(white->ToJSON(), old->ToJSON());
  EXPECT_EQ(json->ToJSON(), old->ToJSON());
  EXPECT_EQ(added->ToJSON(), old->ToJSON());
  EXPECT_EQ(old->ToJSON().find("transmission"), std::string::npos);

  auto reference = SlabFilter(old, 2, mmv::PiecewiseShadowRays);
  vtkFloatArray* expected = Array(reference, "Irradiance_0");
  ASSERT_NE(expected, nullptr);
  for (vtkMaterialTransferFunction* m : { white.Get(), json.Get(), added.Get() })
  {
    auto filter = SlabFilter(m, 2, mmv::PiecewiseShadowRays);
    EXPECT_EQ(Array(filter, "IrradianceTint_0"), nullptr);
    EXPECT_EQ(filter->GetOutput()->GetPointData()->GetNumberOfArrays(), 1);
    vtkFloatArray* got = Array(filter, "Irradiance_0");
    ASSERT_NE(got, nullptr);
    EXPECT_EQ(std::memcmp(got->GetPointer(0), expected->GetPointer(0),
                sizeof(float) * expected->GetNumberOfTuples()),
      0);
  }
  vtkNew<vtkPreIntegrationTable> table;
  table->SetScalarOpacity(Opacity());
  table->SetMaterialTransferFunction(white);
  ASSERT_TRUE(table->Update());
  EXPECT_EQ(table->GetShadowTintTable(), nullptr);
}

// Out-of-range colours are input errors, as for every table parameter.
TEST(OpticalModel, TransmissionOutsideZeroToOneIsRejected)
{
  vtkNew<vtkMaterialTransferFunction> f;
  mmvtest::ErrorCounter errors(f);
  EXPECT_EQ(f->AddNode(0.0, 0.2, 0.7, 0.2, 20.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.5, 1.0, 1.0), -1);
  EXPECT_EQ(f->AddNode(0.0, 0.2, 0.7, 0.2, 20.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, -0.1, 1.0), -1);
  EXPECT_EQ(
    f->AddNode(0.0, 0.2, 0.7, 0.2, 20.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, std::nan("")), -1);
  EXPECT_FALSE(f->FromJSON(R"({"nodes": [{"value": 0, "transmission_g": 2}]})"));
  EXPECT_EQ(errors.Errors(), 4);
  EXPECT_NE(errors.LastMessage().find("transmission_g"), std::string::npos) << errors.LastMessage();
  EXPECT_EQ(f->GetSize(), 0);
  // The ends themselves are valid: T = 0 is clamped to MinTransmission.
  EXPECT_EQ(f->AddNode(0.0, 0.2, 0.7, 0.2, 20.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0), 0);
  EXPECT_EQ(mmv::TransmissionWeight(0.0), 1.0 - std::log(mmv::MinTransmission));
  EXPECT_EQ(mmv::TransmissionWeight(1.0), 1.0);
}
