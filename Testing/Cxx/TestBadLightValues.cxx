// Bad light values (docs/stability.md, "Bad input"): negative, NaN or all-zero
// attenuation, cone angles of 0, NaN or 180 and above, NaN spot exponents,
// a negative or NaN PointLightRadius and an IrradianceScale outside [0, 1]. Each must give one
// clear warning and render exactly what its documented fallback renders: never NaN, never a
// silently black image.
#include "mmvTestScenes.h"
#include "mmvTestUtilities.h"

#include "vtkFloatArray.h"
#include "vtkIrradianceVolumeFilter.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMultiMaterialVolumeMapper.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>

namespace
{
const double NaN = std::numeric_limits<double>::quiet_NaN();
const double Center[3] = { 16.0, 16.0, 16.0 };

using LightSetup = std::function<void(vtkLight*)>;
using MapperSetup = std::function<void(vtkMultiMaterialVolumeMapper*)>;

struct Outcome
{
  std::vector<unsigned char> Pixels;
  int Warnings = 0;
  int Errors = 0;
  std::string Message;
  double Luminance = 0.0; // mean over the image, 0-255
};

/// A spot light 44 units above a ball, aimed at its centre, cone 30.
vtkSmartPointer<vtkLight> Spot()
{
  auto light = vtkSmartPointer<vtkLight>::New();
  light->SetLightTypeToSceneLight();
  light->PositionalOn();
  light->SetPosition(22.0, 20.0, 60.0);
  light->SetFocalPoint(Center[0], Center[1], Center[2]);
  light->SetConeAngle(30.0);
  return light;
}

vtkSmartPointer<vtkImageData> Ball()
{
  return mmvtest::MakeVolume(33,
    [](int i, int j, int k)
    {
      const double r =
        std::sqrt((i - 16.0) * (i - 16.0) + (j - 16.0) * (j - 16.0) + (k - 16.0) * (k - 16.0));
      return static_cast<float>(std::max(0.0, 12.0 - r) * 10.0);
    });
}

/// Renders the lit ball twice (the warning must not repeat) and returns the
/// second image and the warnings of both renders.
Outcome Render(const LightSetup& setLight, const MapperSetup& setMapper = nullptr)
{
  mmvtest::Scene scene;
  scene.Color->AddRGBPoint(0.0, 1.0, 0.8, 0.6);
  scene.Color->AddRGBPoint(120.0, 1.0, 0.8, 0.6);
  scene.Opacity->AddPoint(0.0, 0.0);
  scene.Opacity->AddPoint(120.0, 0.5);
  vtkNew<vtkMaterialTransferFunction> materials;
  materials->AddNode(60.0, 0.3, 0.6, 0.3, 20.0, 1.0, 0.0, 0.0);
  vtkNew<vtkMultiMaterialVolumeMapper> mapper;
  mmvtest::ErrorCounter counter(mapper);
  auto image = Ball();
  mapper->SetInputData(image);
  mapper->SetMaterialTransferFunction(materials);
  scene.Volume->SetMapper(mapper);
  scene.FrameBounds(image->GetBounds());
  auto light = Spot();
  setLight(light);
  scene.Renderer->AddLight(light);
  if (setMapper)
  {
    setMapper(mapper);
  }
  scene.Window->Render();
  scene.Renderer->GetActiveCamera()->Azimuth(1.0);
  scene.Window->Render();
  EXPECT_TRUE(mapper->GetMultiMaterialActive());
  Outcome out;
  out.Pixels = scene.Pixels();
  out.Warnings = counter.Warnings();
  out.Errors = counter.Errors();
  out.Message = counter.LastMessage();
  for (unsigned char v : out.Pixels)
  {
    out.Luminance += v;
  }
  out.Luminance /= out.Pixels.size();
  return out;
}

int MaxDifference(const std::vector<unsigned char>& a, const std::vector<unsigned char>& b)
{
  if (a.size() != b.size())
  {
    return 255;
  }
  int worst = 0;
  for (size_t i = 0; i < a.size(); ++i)
  {
    worst = std::max(worst, std::abs(int(a[i]) - int(b[i])));
  }
  return worst;
}

/// `bad` warns once, naming `keyword`, and renders exactly as `fallback`,
/// which warns about nothing and is not black.
void ExpectFallback(const char* what, const LightSetup& bad, const LightSetup& fallback,
  const char* keyword, const MapperSetup& badMapper = nullptr,
  const MapperSetup& fallbackMapper = nullptr)
{
  const Outcome b = Render(bad, badMapper);
  const Outcome f = Render(fallback, fallbackMapper);
  std::printf("%-28s warnings %d (\"%s\"), max |bad - fallback| %d, mean level %.2f\n", what,
    b.Warnings, b.Message.c_str(), MaxDifference(b.Pixels, f.Pixels), b.Luminance);
  EXPECT_EQ(b.Warnings, 1) << what;
  EXPECT_EQ(b.Errors, 0) << what;
  EXPECT_NE(b.Message.find(keyword), std::string::npos) << what << ": " << b.Message;
  EXPECT_EQ(f.Warnings, 0) << what << ": " << f.Message;
  EXPECT_EQ(MaxDifference(b.Pixels, f.Pixels), 0) << what;
  EXPECT_GT(f.Luminance, 5.0) << what << ": the fallback must light the ball";
}

void Attenuation(vtkLight* l, double c, double q, double r)
{
  l->SetAttenuationValues(c, q, r);
}
} // namespace

TEST(BadLightValues, AttenuationFallsBackToNoFalloff)
{
  const LightSetup none = [](vtkLight*) {};
  ExpectFallback(
    "attenuation (-1, 0, 0)", [](vtkLight* l) { Attenuation(l, -1.0, 0.0, 0.0); }, none,
    "AttenuationValues");
  ExpectFallback(
    "attenuation (1, -0.1, 0)", [](vtkLight* l) { Attenuation(l, 1.0, -0.1, 0.0); }, none,
    "AttenuationValues");
  ExpectFallback(
    "attenuation (NaN, 0.1, 0)", [](vtkLight* l) { Attenuation(l, NaN, 0.1, 0.0); }, none,
    "AttenuationValues");
  ExpectFallback(
    "attenuation (0, 0, 0)", [](vtkLight* l) { Attenuation(l, 0.0, 0.0, 0.0); }, none,
    "AttenuationValues");
}

TEST(BadLightValues, ConeAngleOutsideZeroTo180IsAPointLight)
{
  const LightSetup point = [](vtkLight* l) { l->SetConeAngle(120.0); };
  ExpectFallback(
    "cone 0", [](vtkLight* l) { l->SetConeAngle(0.0); }, point, "ConeAngle");
  ExpectFallback(
    "cone -10", [](vtkLight* l) { l->SetConeAngle(-10.0); }, point, "ConeAngle");
  ExpectFallback(
    "cone 180", [](vtkLight* l) { l->SetConeAngle(180.0); }, point, "ConeAngle");
  ExpectFallback(
    "cone 270", [](vtkLight* l) { l->SetConeAngle(270.0); }, point, "ConeAngle");
  ExpectFallback(
    "cone NaN", [](vtkLight* l) { l->SetConeAngle(NaN); }, point, "ConeAngle");
}

TEST(BadLightValues, NaNExponentIsOne)
{
  // vtkLight::SetExponent clamps to [0, 128] itself; NaN gets through.
  const LightSetup one = [](vtkLight* l) { l->SetExponent(1.0); };
  ExpectFallback(
    "exponent NaN", [](vtkLight* l) { l->SetExponent(NaN); }, one, "Exponent");
}

TEST(BadLightValues, NegativeOrNaNPointLightRadiusIsZero)
{
  const LightSetup none = [](vtkLight*) {};
  const MapperSetup zero = [](vtkMultiMaterialVolumeMapper* m) { m->SetPointLightRadius(0.0); };
  ExpectFallback(
    "PointLightRadius -5", none, none, "PointLightRadius",
    [](vtkMultiMaterialVolumeMapper* m) { m->SetPointLightRadius(-5.0); }, zero);
  ExpectFallback(
    "PointLightRadius NaN", none, none, "PointLightRadius",
    [](vtkMultiMaterialVolumeMapper* m) { m->SetPointLightRadius(NaN); }, zero);
}

TEST(BadLightValues, IrradianceScaleOutsideZeroToOne)
{
  const LightSetup none = [](vtkLight*) {};
  ExpectFallback(
    "IrradianceScale 5", none, none, "IrradianceScale",
    [](vtkMultiMaterialVolumeMapper* m) { m->SetIrradianceScale(5.0); },
    [](vtkMultiMaterialVolumeMapper* m) { m->SetIrradianceScale(1.0); });
  ExpectFallback(
    "IrradianceScale -1", none, none, "IrradianceScale",
    [](vtkMultiMaterialVolumeMapper* m) { m->SetIrradianceScale(-1.0); },
    [](vtkMultiMaterialVolumeMapper* m) { m->SetIrradianceScale(0.0); });
  ExpectFallback(
    "IrradianceScale NaN", none, none, "IrradianceScale",
    [](vtkMultiMaterialVolumeMapper* m) { m->SetIrradianceScale(NaN); },
    [](vtkMultiMaterialVolumeMapper* m) { m->SetIrradianceScale(0.0); });
}

namespace
{
using FilterSetup = std::function<void(vtkIrradianceVolumeFilter*, vtkLight*)>;

/// The filter's irradiance of the spot light and its warnings.
std::vector<float> FilterIrradiance(const FilterSetup& setup, int& warnings, std::string& message)
{
  vtkNew<vtkIrradianceVolumeFilter> filter;
  mmvtest::ErrorCounter counter(filter);
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0.0, 0.0);
  opacity->AddPoint(120.0, 0.5);
  auto image = Ball();
  filter->SetInputData(image);
  filter->SetScalarOpacity(opacity);
  filter->SetIrradianceScale(0.5);
  auto light = Spot();
  setup(filter, light);
  filter->AddLight(light);
  filter->Update();
  warnings = counter.Warnings();
  message = counter.LastMessage();
  auto* array =
    vtkFloatArray::SafeDownCast(filter->GetOutput()->GetPointData()->GetArray("Irradiance_0"));
  return array
    ? std::vector<float>(array->GetPointer(0), array->GetPointer(0) + array->GetNumberOfTuples())
    : std::vector<float>();
}
} // namespace

TEST(BadLightValues, FilterWarnsAndFallsBackAsTheMapper)
{
  struct Case
  {
    const char* What;
    const char* Keyword;
    FilterSetup Bad;
    FilterSetup Fallback;
  };
  const FilterSetup none = [](vtkIrradianceVolumeFilter*, vtkLight*) {};
  const Case cases[] = {
    { "attenuation (-1, 0, 0)", "AttenuationValues",
      [](vtkIrradianceVolumeFilter*, vtkLight* l) { Attenuation(l, -1.0, 0.0, 0.0); }, none },
    { "cone 0", "ConeAngle", [](vtkIrradianceVolumeFilter*, vtkLight* l) { l->SetConeAngle(0.0); },
      [](vtkIrradianceVolumeFilter*, vtkLight* l) { l->SetConeAngle(120.0); } },
    { "exponent NaN", "Exponent",
      [](vtkIrradianceVolumeFilter*, vtkLight* l) { l->SetExponent(NaN); }, none },
    { "PointLightRadius -5", "PointLightRadius",
      [](vtkIrradianceVolumeFilter* f, vtkLight*) { f->SetPointLightRadius(-5.0); }, none },
    { "IrradianceScale 5", "IrradianceScale",
      [](vtkIrradianceVolumeFilter* f, vtkLight*) { f->SetIrradianceScale(5.0); },
      [](vtkIrradianceVolumeFilter* f, vtkLight*) { f->SetIrradianceScale(1.0); } },
  };
  for (const Case& c : cases)
  {
    int badWarnings = 0;
    int fallbackWarnings = 0;
    std::string badMessage;
    std::string fallbackMessage;
    const auto bad = FilterIrradiance(c.Bad, badWarnings, badMessage);
    const auto fallback = FilterIrradiance(c.Fallback, fallbackWarnings, fallbackMessage);
    std::printf("filter, %-24s warnings %d (\"%s\")\n", c.What, badWarnings, badMessage.c_str());
    EXPECT_EQ(badWarnings, 1) << c.What;
    EXPECT_NE(badMessage.find(c.Keyword), std::string::npos) << c.What << ": " << badMessage;
    EXPECT_EQ(fallbackWarnings, 0) << c.What << ": " << fallbackMessage;
    ASSERT_FALSE(bad.empty()) << c.What;
    EXPECT_EQ(bad, fallback) << c.What;
    float peak = 0.0f;
    for (float v : bad)
    {
      ASSERT_TRUE(std::isfinite(v)) << c.What;
      peak = std::max(peak, v);
    }
    EXPECT_GT(peak, 0.5f) << c.What << ": the fallback must light the ball";
  }
}
