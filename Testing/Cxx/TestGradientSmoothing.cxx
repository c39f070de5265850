// GradientSmoothing (the demo's banding, docs/stability.md, "Stripes on thin shells"): the MR
// head's skin is a thin shell sampled every 3.2 mm in x and y, and the gradient of its trilinear
// reconstruction turns at every voxel face, which the shading draws as stripes at the voxel spacing
// on the cheek and neck (docs/stability.md, "Stripes on thin shells": not the sampling, the
// pre-integration or the irradiance). Smoothing the shading normal by a Gaussian of one voxel must
// remove most of that high-frequency energy without changing the image's brightness, and bad values
// must be reported and render as no smoothing.
#include "mmvTestScenes.h"
#include "mmvTestUtilities.h"

#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMultiMaterialVolumeMapper.h"
#include "vtkPointData.h"
#include "vtkXMLImageDataReader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

namespace
{
constexpr int Size = 640; // the demo's: the stripes are a few pixels apart

/// The demo's view of the head (Testing/Examples/MultiMaterialVolumeDemo.cxx)
/// with its key and spot lights, GradientSmoothing `sigma`; returns the RGB bytes.
std::vector<unsigned char> RenderHead(double sigma, int* warnings = nullptr, int size = Size)
{
  vtkNew<vtkXMLImageDataReader> reader;
  reader->SetFileName(MMV_TEST_DATA_DIR "/headsq.vti");
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  double range[2];
  image->GetPointData()->GetScalars()->GetRange(range);
  const double r0 = range[0];
  const double dr = range[1] - range[0];
  mmvtest::Scene scene(size);
  scene.Color->AddRGBPoint(r0, 0.0, 0.0, 0.0);
  scene.Color->AddRGBPoint(r0 + 0.15 * dr, 0.90, 0.60, 0.50);
  scene.Color->AddRGBPoint(r0 + 0.28 * dr, 0.90, 0.65, 0.55);
  scene.Color->AddRGBPoint(r0 + 0.35 * dr, 1.00, 0.98, 0.90);
  scene.Color->AddRGBPoint(range[1], 1.00, 1.00, 0.95);
  scene.Opacity->AddPoint(r0, 0.0);
  scene.Opacity->AddPoint(r0 + 0.12 * dr, 0.0);
  scene.Opacity->AddPoint(r0 + 0.18 * dr, 0.25);
  scene.Opacity->AddPoint(r0 + 0.28 * dr, 0.25);
  scene.Opacity->AddPoint(r0 + 0.33 * dr, 0.6);
  scene.Opacity->AddPoint(range[1], 0.8);
  scene.Property->SetScalarOpacityUnitDistance(image->GetSpacing()[0]);
  vtkNew<vtkMaterialTransferFunction> materials;
  materials->AddNode(r0 + 0.20 * dr, 0.35, 0.7, 0.3, 15, 0.5, 8, 0); // skin
  materials->AddNode(r0 + 0.35 * dr, 0.2, 0.8, 0.2, 25, 1.0, 1, 0);  // bone
  vtkNew<vtkMultiMaterialVolumeMapper> mapper;
  mmvtest::ErrorCounter counter(mapper);
  mapper->SetInputData(image);
  mapper->SetMaterialTransferFunction(materials);
  mapper->SetGradientSmoothing(sigma);
  scene.Volume->SetMapper(mapper);
  scene.Renderer->SetBackground(0.08, 0.09, 0.12);
  scene.Renderer->SetBackground2(0.35, 0.38, 0.45);
  scene.Renderer->GradientBackgroundOn();
  scene.Renderer->ResetCamera();
  vtkCamera* camera = scene.Renderer->GetActiveCamera();
  camera->Elevation(80.0);
  camera->OrthogonalizeViewUp();
  camera->Azimuth(20.0);
  scene.Renderer->ResetCamera();
  camera->Zoom(1.3);
  vtkNew<vtkLight> key;
  key->SetLightTypeToCameraLight();
  key->SetPosition(-0.6, 0.8, 1.0);
  key->SetFocalPoint(0.0, 0.0, 0.0);
  key->SetColor(1.0, 0.95, 0.85);
  scene.Renderer->AddLight(key);
  // The demo's spot light from the side: it lights the cheek and neck.
  double center[3];
  image->GetCenter(center);
  vtkNew<vtkLight> spot;
  spot->SetLightTypeToSceneLight();
  spot->PositionalOn();
  spot->SetConeAngle(25.0);
  spot->SetPosition(center[0] + 300, center[1] - 150, center[2] + 50);
  spot->SetFocalPoint(center);
  spot->SetColor(0.7, 0.8, 1.0);
  spot->SetIntensity(0.8);
  scene.Renderer->AddLight(spot);
  scene.Window->Render();
  EXPECT_TRUE(mapper->GetMultiMaterialActive());
  if (warnings)
  {
    *warnings = counter.Warnings();
  }
  return scene.Pixels();
}

struct Texture
{
  double HighPassRMS = 0.0; // luminance minus its 7 x 7 box blur
  double Mean = 0.0;
};

/// Over the cheek and neck (x 0.62-0.80, y 0.35-0.60 of the image, bottom
/// row first): where the stripes are.
Texture Measure(const std::vector<unsigned char>& rgb)
{
  std::vector<double> lum(Size * Size);
  for (int p = 0; p < Size * Size; ++p)
  {
    lum[p] = (rgb[3 * p] + rgb[3 * p + 1] + rgb[3 * p + 2]) / 3.0;
  }
  auto at = [&](int x, int y)
  { return lum[std::min(std::max(y, 0), Size - 1) * Size + std::min(std::max(x, 0), Size - 1)]; };
  Texture t;
  int n = 0;
  for (int y = static_cast<int>(0.35 * Size); y < static_cast<int>(0.60 * Size); ++y)
  {
    for (int x = static_cast<int>(0.62 * Size); x < static_cast<int>(0.80 * Size); ++x)
    {
      double blur = 0.0;
      for (int dy = -3; dy <= 3; ++dy)
      {
        for (int dx = -3; dx <= 3; ++dx)
        {
          blur += at(x + dx, y + dy);
        }
      }
      const double h = at(x, y) - blur / 49.0;
      t.HighPassRMS += h * h;
      t.Mean += at(x, y);
      ++n;
    }
  }
  t.HighPassRMS = std::sqrt(t.HighPassRMS / n);
  t.Mean /= n;
  return t;
}
} // namespace

TEST(GradientSmoothing, RemovesTheVoxelStripesOfAThinShell)
{
  const Texture sharp = Measure(RenderHead(0.0));
  const Texture smooth = Measure(RenderHead(1.0));
  std::printf("cheek and neck: high-pass RMS %.3f -> %.3f grey levels (%.0f %%), mean %.1f -> "
              "%.1f\n",
    sharp.HighPassRMS, smooth.HighPassRMS, 100.0 * smooth.HighPassRMS / sharp.HighPassRMS,
    sharp.Mean, smooth.Mean);
  EXPECT_LT(smooth.HighPassRMS, 0.75 * sharp.HighPassRMS);
  EXPECT_NEAR(smooth.Mean, sharp.Mean, 0.1 * sharp.Mean);
}

TEST(GradientSmoothing, BadValuesAreReportedAndRenderUnsmoothed)
{
  const int small = 160;
  const std::vector<unsigned char> none = RenderHead(0.0, nullptr, small);
  for (const double bad : { std::nan(""), -1.0 })
  {
    int warnings = 0;
    const std::vector<unsigned char> image = RenderHead(bad, &warnings, small);
    EXPECT_EQ(warnings, 1) << bad;
    EXPECT_EQ(image, none) << bad;
  }
  int warnings = 0;
  const std::vector<unsigned char> clamped = RenderHead(1.0e9, &warnings, small);
  EXPECT_EQ(warnings, 1);
  EXPECT_EQ(clamped, RenderHead(4.0, nullptr, small));
  EXPECT_NE(clamped, none);
}
