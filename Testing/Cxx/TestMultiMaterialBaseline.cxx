// A synthetic multi-material scene against a baseline image: three materials
// (plastic, reflective metal, scattering skin), a directional key light and a
// spot light, gradient background (the reflection's environment).
//
// Threshold: mean absolute difference <= 2 (of 255) per channel and at most
// 1% of the pixels off by more than 24. Rendering differences between Mesa
// versions stay well inside that; a shading change does not.
// MMV_WRITE_BASELINE=1 in the environment rewrites the baseline.
#include "mmvTestScenes.h"

#include "vtkImageData.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMultiMaterialVolumeMapper.h"
#include "vtkPNGReader.h"
#include "vtkPNGWriter.h"
#include "vtkWindowToImageFilter.h"
#include "vtksys/SystemTools.hxx"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <string>

namespace
{
constexpr int N = 48;

// 1: a slab (skin), 2: a box (metal), 3: a sphere (plastic); smooth 1-voxel
// edges so the gradient gives normals. With a 1D transfer function an edge
// from 0 to v passes through every value below v, so the order puts the
// faint skin band and the narrow metal band on the way to the others.
float SceneValue(int i, int j, int k)
{
  auto smooth = [](double signedDistance)
  { return std::min(1.0, std::max(0.0, 0.5 - signedDistance)); };
  const double sphere =
    std::sqrt((i - 16.0) * (i - 16.0) + (j - 28.0) * (j - 28.0) + (k - 24.0) * (k - 24.0)) - 9.0;
  const double box =
    std::max({ std::abs(i - 33.0) - 7.0, std::abs(j - 27.0) - 8.0, std::abs(k - 24.0) - 7.0 });
  const double slab =
    std::max({ std::abs(i - 24.0) - 20.0, std::abs(j - 11.0) - 4.0, std::abs(k - 24.0) - 20.0 });
  const double s = smooth(sphere);
  const double b = smooth(box);
  const double l = smooth(slab);
  return static_cast<float>(std::max({ 3.0 * s, 2.0 * b, 1.0 * l }));
}

struct BaselineScene : mmvtest::Scene
{
  vtkNew<vtkMultiMaterialVolumeMapper> Mapper;
  vtkNew<vtkMaterialTransferFunction> Materials;

  BaselineScene()
    : mmvtest::Scene(160)
  {
    auto image = mmvtest::MakeVolume(N, SceneValue);
    this->Color->AddRGBPoint(0.0, 0.0, 0.0, 0.0);
    this->Color->AddRGBPoint(0.8, 0.95, 0.7, 0.55); // skin
    this->Color->AddRGBPoint(1.2, 0.95, 0.7, 0.55);
    this->Color->AddRGBPoint(1.9, 0.8, 0.8, 0.85); // metal: grey
    this->Color->AddRGBPoint(2.1, 0.8, 0.8, 0.85);
    this->Color->AddRGBPoint(2.8, 0.85, 0.15, 0.1); // plastic: red
    this->Color->AddRGBPoint(3.0, 0.85, 0.15, 0.1);
    this->Opacity->AddPoint(0.0, 0.0);
    this->Opacity->AddPoint(0.6, 0.0);
    this->Opacity->AddPoint(0.8, 0.2);
    this->Opacity->AddPoint(1.2, 0.2);
    this->Opacity->AddPoint(1.4, 0.0);
    this->Opacity->AddPoint(1.85, 0.0);
    this->Opacity->AddPoint(1.95, 0.9);
    this->Opacity->AddPoint(2.05, 0.9);
    this->Opacity->AddPoint(2.15, 0.0);
    this->Opacity->AddPoint(2.7, 0.0);
    this->Opacity->AddPoint(2.85, 0.9);
    this->Opacity->AddPoint(3.0, 0.9);
    this->Materials->AddNode(1.0, 0.25, 0.7, 0.3, 15.0, 0.5, 8.0, 0.0); // skin
    this->Materials->AddNode(2.0, 0.1, 0.3, 0.9, 120.0, 1.0, 0.0, 0.6); // metal
    this->Materials->AddNode(3.0, 0.15, 0.7, 0.6, 60.0, 1.0, 0.0, 0.0); // plastic
    mmvtest::SetUpFullGridMapper(this->Mapper.Get(), image, this->Materials, this->Volume);
    this->Renderer->SetBackground(0.15, 0.15, 0.2);
    this->Renderer->SetBackground2(0.6, 0.7, 0.9);
    this->Renderer->GradientBackgroundOn();

    vtkCamera* camera = this->Renderer->GetActiveCamera();
    camera->SetFocalPoint(24.0, 22.0, 24.0);
    camera->SetPosition(24.0 + 60.0, 22.0 + 45.0, 24.0 + 90.0);
    camera->SetViewUp(0.0, 1.0, 0.0);
    camera->SetViewAngle(30.0);
    this->Renderer->ResetCameraClippingRange();

    const double from[3] = { -40.0, 90.0, 80.0 };
    const double to[3] = { 24.0, 22.0, 24.0 };
    this->AddDirectionalLight(from, to);
    vtkNew<vtkLight> spot;
    spot->SetLightTypeToSceneLight();
    spot->PositionalOn();
    spot->SetPosition(80.0, 30.0, 30.0);
    spot->SetFocalPoint(30.0, 25.0, 24.0);
    spot->SetConeAngle(20.0);
    spot->SetColor(0.6, 0.8, 1.0);
    spot->SetIntensity(1.5);
    this->Renderer->AddLight(spot);
  }
};

vtkSmartPointer<vtkImageData> Capture(vtkRenderWindow* window)
{
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->Update();
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->DeepCopy(grab->GetOutput());
  return image;
}
}

TEST(MultiMaterialBaseline, ThreeMaterialsTwoLights)
{
  BaselineScene scene;
  scene.Window->Render();
  ASSERT_TRUE(scene.Mapper->GetMultiMaterialActive());
  ASSERT_EQ(scene.Mapper->GetNumberOfShadedLights(), 2);
  auto image = Capture(scene.Window);

  const std::string baseline = std::string(MMV_BASELINE_DIR) + "/MultiMaterialScene.png";
  const char* rewrite = std::getenv("MMV_WRITE_BASELINE");
  if (rewrite && std::string(rewrite) == "1")
  {
    vtkNew<vtkPNGWriter> writer;
    writer->SetFileName(baseline.c_str());
    writer->SetInputData(image);
    writer->Write();
    GTEST_SKIP() << "baseline rewritten: " << baseline;
  }
  ASSERT_TRUE(vtksys::SystemTools::FileExists(baseline)) << "missing baseline " << baseline;
  vtkNew<vtkPNGReader> reader;
  reader->SetFileName(baseline.c_str());
  reader->Update();
  vtkImageData* expected = reader->GetOutput();

  int a[3];
  int b[3];
  image->GetDimensions(a);
  expected->GetDimensions(b);
  ASSERT_EQ(a[0], b[0]);
  ASSERT_EQ(a[1], b[1]);
  ASSERT_GE(expected->GetNumberOfScalarComponents(), 3);
  const int na = image->GetNumberOfScalarComponents();
  const int nb = expected->GetNumberOfScalarComponents();
  const auto* pa = static_cast<unsigned char*>(image->GetScalarPointer());
  const auto* pb = static_cast<unsigned char*>(expected->GetScalarPointer());
  double sum = 0.0;
  int badPixels = 0;
  const int pixels = a[0] * a[1];
  for (int p = 0; p < pixels; ++p)
  {
    int worst = 0;
    for (int c = 0; c < 3; ++c)
    {
      const int d = std::abs(int(pa[p * na + c]) - int(pb[p * nb + c]));
      sum += d;
      worst = std::max(worst, d);
    }
    badPixels += worst > 24 ? 1 : 0;
  }
  const double meanDifference = sum / (3.0 * pixels);
  if (meanDifference > 2.0 || badPixels > pixels / 100)
  {
    vtkNew<vtkPNGWriter> writer;
    writer->SetFileName("MultiMaterialScene-actual.png");
    writer->SetInputData(image);
    writer->Write();
  }
  EXPECT_LE(meanDifference, 2.0);
  EXPECT_LE(badPixels, pixels / 100);
}
