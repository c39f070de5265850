// vtkMultiMaterialReferenceRenderer: the closed-form cube images of the
// mapper tests (parallel and perspective cameras, background), multiple
// scattering, and agreement with the GPU mapper on a small lit scene.
#include "mmvTestScenes.h"

#include "vtkDataArray.h"
#include "vtkImageErrorMetrics.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMultiMaterialReferenceRenderer.h"
#include "vtkMultiMaterialVolumeMapper.h"
#include "vtkSMPTools.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

namespace
{
constexpr int Dims = 33; // cube of side D = 32 (spacing 1)
constexpr double D = Dims - 1;
constexpr double Mu = 0.05; // extinction per unit length
constexpr int Size = 16;    // pixels: only the centre is checked
const double CubeColor[3] = { 1.0, 0.6, 0.3 };
const double CubeCenter[3] = { 16.0, 16.0, 16.0 };

// The mapper tests' homogeneous cube: ambient-only material (ka = 1).
struct CubeScene : mmvtest::Scene
{
  vtkNew<vtkMultiMaterialReferenceRenderer> Reference;
  vtkNew<vtkMaterialTransferFunction> Materials;
  vtkSmartPointer<vtkImageData> Image;

  explicit CubeScene(double attenuation, double scattering = 0.0)
    : mmvtest::Scene(Size)
  {
    vtkSMPTools::SetBackend("STDThread");
    this->Image = mmvtest::MakeVolume(Dims, [](int, int, int) { return 1.0f; });
    this->Color->AddRGBPoint(0.0, CubeColor[0], CubeColor[1], CubeColor[2]);
    this->Color->AddRGBPoint(2.0, CubeColor[0], CubeColor[1], CubeColor[2]);
    this->Opacity->AddPoint(0.0, 1.0 - std::exp(-Mu)); // unit distance 1
    this->Opacity->AddPoint(2.0, 1.0 - std::exp(-Mu));
    this->Property->SetScalarOpacityUnitDistance(1.0);
    this->Materials->AddNode(1.0, 1.0, 0.0, 0.0, 1.0, attenuation, scattering, 0.0);
    this->Reference->SetInputData(this->Image);
    this->Reference->SetVolumeProperty(this->Property);
    this->Reference->SetMaterialTransferFunction(this->Materials);
    this->FrameBounds(this->Image->GetBounds());
  }

  // Unclamped radiance of the pixel nearest the image centre.
  std::vector<double> Center()
  {
    vtkImageData* out = this->Reference->Render(this->Renderer, Size, Size);
    EXPECT_NE(out, nullptr);
    if (!out)
    {
      return { 0.0, 0.0, 0.0 };
    }
    vtkDataArray* radiance = out->GetPointData()->GetArray("Radiance");
    const vtkIdType id = (Size / 2) * Size + Size / 2;
    return { radiance->GetComponent(id, 0), radiance->GetComponent(id, 1),
      radiance->GetComponent(id, 2) };
  }
};

void ExpectRelative(const std::vector<double>& pixel, double expected, double tolerance)
{
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_NEAR(pixel[c], CubeColor[c] * expected, tolerance * CubeColor[c] * expected)
      << "channel " << c;
  }
}
}

TEST(ReferenceRenderer, LightFromCameraSideMatchesClosedForm)
{
  // sigma = mu: pixel = c mu/(sigma+mu) (1 - exp(-(sigma+mu) D)).
  CubeScene scene(1.0);
  const double from[3] = { 16.0, 16.0, 1000.0 };
  scene.AddDirectionalLight(from, CubeCenter);
  ExpectRelative(scene.Center(), 0.5 * (1.0 - std::exp(-2.0 * Mu * D)), 0.005);
}

TEST(ReferenceRenderer, LightFromCameraSideWithOtherAttenuation)
{
  // sigma = 2 mu: pixel = c mu/(3 mu) (1 - exp(-3 mu D)).
  CubeScene scene(2.0);
  const double from[3] = { 16.0, 16.0, 1000.0 };
  scene.AddDirectionalLight(from, CubeCenter);
  ExpectRelative(scene.Center(), (1.0 - std::exp(-3.0 * Mu * D)) / 3.0, 0.005);
}

TEST(ReferenceRenderer, LightFromBehindMatchesClosedForm)
{
  // sigma = mu: pixel = c mu D exp(-mu D).
  CubeScene scene(1.0);
  const double from[3] = { 16.0, 16.0, -1000.0 };
  scene.AddDirectionalLight(from, CubeCenter);
  ExpectRelative(scene.Center(), Mu * D * std::exp(-Mu * D), 0.005);
}

TEST(ReferenceRenderer, PerspectiveCameraMatchesClosedForm)
{
  // The centre ray of a perspective camera on the axis sees the same slab.
  CubeScene scene(1.0);
  vtkCamera* camera = scene.Renderer->GetActiveCamera();
  camera->ParallelProjectionOff();
  camera->SetPosition(16.0, 16.0, 120.0);
  camera->SetViewAngle(30.0);
  scene.Renderer->ResetCameraClippingRange(scene.Image->GetBounds());
  const double from[3] = { 16.0, 16.0, -1000.0 };
  scene.AddDirectionalLight(from, CubeCenter);
  // The pixel centre is half a pixel off the axis: its ray is tilted by
  // about 1 degree, which lengthens the path by 2e-4.
  ExpectRelative(scene.Center(), Mu * D * std::exp(-Mu * D), 0.005);
}

TEST(ReferenceRenderer, CompositesOverBackground)
{
  CubeScene scene(1.0);
  scene.Renderer->SetBackground(0.2, 0.4, 0.6);
  const double from[3] = { 16.0, 16.0, 1000.0 };
  scene.AddDirectionalLight(from, CubeCenter);
  vtkImageData* out = scene.Reference->Render(scene.Renderer, Size, Size);
  ASSERT_NE(out, nullptr);
  vtkDataArray* radiance = out->GetPointData()->GetArray("Radiance");
  // A corner misses the cube (the camera frames it with a 1.5 margin).
  EXPECT_NEAR(radiance->GetComponent(0, 0), 0.2, 1e-12);
  EXPECT_NEAR(radiance->GetComponent(0, 2), 0.6, 1e-12);
  // The centre: emission plus the background behind the slab.
  const vtkIdType id = (Size / 2) * Size + Size / 2;
  const double expected =
    CubeColor[1] * 0.5 * (1.0 - std::exp(-2.0 * Mu * D)) + 0.4 * std::exp(-Mu * D);
  EXPECT_NEAR(radiance->GetComponent(id, 1), expected, 0.005 * expected);
  vtkDataArray* bytes = out->GetPointData()->GetScalars();
  EXPECT_EQ(bytes->GetNumberOfComponents(), 3);
  EXPECT_EQ(bytes->GetComponent(0, 1), 102.0); // round(0.4 * 255)
}

TEST(ReferenceRenderer, NoLightGivesAmbientEmission)
{
  // No active light: emission ka * c * (1 - exp(-mu D)).
  CubeScene scene(1.0);
  ExpectRelative(scene.Center(), 1.0 - std::exp(-Mu * D), 0.005);
}

TEST(ReferenceRenderer, MultipleScatteringRedistributesLight)
{
  const double from[3] = { 16.0, 16.0, 1000.0 };
  CubeScene plain(1.0);
  plain.AddDirectionalLight(from, CubeCenter);
  const double direct = plain.Center()[0];
  EXPECT_FALSE(plain.Reference->GetScatteringApplied());

  CubeScene scattering(1.0, 5.0);
  scattering.AddDirectionalLight(from, CubeCenter);
  const double diffused = scattering.Center()[0];
  EXPECT_TRUE(scattering.Reference->GetScatteringApplied());
  // Diffusion along the light moves irradiance from the lit front to the
  // back, where the camera sees less of it: darker, but not much.
  EXPECT_LT(diffused, direct);
  EXPECT_GT(diffused, 0.8 * direct);

  scattering.Reference->MultipleScatteringOff();
  EXPECT_NEAR(scattering.Center()[0], direct, 1e-9);
  EXPECT_FALSE(scattering.Reference->GetScatteringApplied());
}

TEST(ReferenceRenderer, RejectsInvalidInput)
{
  vtkObject::GlobalWarningDisplayOff();
  CubeScene scene(1.0);
  EXPECT_EQ(scene.Reference->Render(scene.Renderer, 0, Size), nullptr);
  EXPECT_EQ(scene.Reference->Render(nullptr, Size, Size), nullptr);
  scene.Reference->SetInputData(nullptr);
  EXPECT_EQ(scene.Reference->Render(scene.Renderer, Size, Size), nullptr);
  vtkObject::GlobalWarningDisplayOn();
}

TEST(ReferenceRenderer, AgreesWithGPUMapper)
{
  // A lit two-material ball: a translucent diffuse shell around a glossy core.
  vtkSMPTools::SetBackend("STDThread");
  constexpr int ImageSize = 64;
  mmvtest::Scene scene(ImageSize);
  vtkNew<vtkMaterialTransferFunction> materials;
  auto image = mmvtest::TwoMaterialBall(scene, materials, Dims);
  vtkNew<vtkMultiMaterialVolumeMapper> mapper;
  mmvtest::SetUpFullGridMapper(mapper.Get(), image, materials, scene.Volume);
  scene.FrameBounds(image->GetBounds(), 1.2);
  const double from[3] = { 60.0, 80.0, 100.0 };
  scene.AddDirectionalLight(from, CubeCenter);
  scene.Window->Render();
  ASSERT_TRUE(mapper->GetMultiMaterialActive());

  const std::vector<unsigned char> pixels = scene.Pixels();
  vtkNew<vtkImageData> gpu;
  gpu->SetDimensions(ImageSize, ImageSize, 1);
  vtkNew<vtkUnsignedCharArray> gpuColors;
  gpuColors->SetNumberOfComponents(3);
  gpuColors->SetNumberOfTuples(ImageSize * ImageSize);
  std::copy(pixels.begin(), pixels.end(), gpuColors->GetPointer(0));
  gpu->GetPointData()->SetScalars(gpuColors);

  vtkNew<vtkMultiMaterialReferenceRenderer> reference;
  vtkImageData* truth = reference->RenderToImage(scene.Renderer, scene.Volume);
  ASSERT_NE(truth, nullptr);
  vtkNew<vtkImageErrorMetrics> metrics;
  ASSERT_TRUE(metrics->Compute(gpu, truth));
  std::cout << "GPU mapper vs reference: PSNR " << metrics->GetPSNR() << " dB, SSIM "
            << metrics->GetSSIM() << ", max error " << metrics->GetMaximumError() << "/255, "
            << "reference " << reference->GetLastRenderSeconds() << " s\n";
  // Measured with Mesa llvmpipe: 43.3 dB, SSIM 0.997, largest error 14/255
  // (the irradiance volume's trilinear shadows at the ball's terminator).
  EXPECT_GT(metrics->GetPSNR(), 40.0);
  EXPECT_GT(metrics->GetSSIM(), 0.99);
}
