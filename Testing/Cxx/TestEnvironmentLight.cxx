// The environment light on the GPU mapper (Rendering/vtkMultiMaterialSky.h):
// a homogeneous cube lit only by a uniform sky against the quadrature of its
// exact single scattering and against the path tracer; a new background
// reshades without estimating again; off compiles no sky code; bad
// strengths are refused.
#include "mmvTestScenes.h"
#include "mmvTestUtilities.h"

#include "vtkDataArray.h"
#include "vtkImageErrorMetrics.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMultiMaterialPathTracer.h"
#include "vtkMultiMaterialReferenceRenderer.h"
#include "vtkMultiMaterialVolumeMapper.h"
#include "vtkSMPTools.h"
#include "vtkSkyVisibility.h"
#include "vtkUnsignedCharArray.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <string>
#include <vector>

namespace mmvtest
{
namespace
{

constexpr int Dims = 17; // cube of side D = 16 (spacing 1)
constexpr double D = Dims - 1;
constexpr double Mu = 1.0 / D; // optical depth 1 through the cube
constexpr int Size = 24;
const double CubeColor[3] = { 1.0, 0.6, 0.3 };

// A homogeneous cube seen down -z by a parallel camera, no lights, lit by
// the background as a sky; particle term only (kd = ks = 0).
struct SkyScene : Scene
{
  vtkNew<vtkMaterialTransferFunction> Materials;
  vtkNew<vtkMultiMaterialVolumeMapper> Mapper;
  vtkSmartPointer<vtkImageData> Image;

  explicit SkyScene(double grey)
    : Scene(Size)
  {
    vtkSMPTools::SetBackend("STDThread");
    this->Image = MakeVolume(Dims, [](int, int, int) { return 1.0f; });
    this->Color->AddRGBPoint(0.0, CubeColor[0], CubeColor[1], CubeColor[2]);
    this->Color->AddRGBPoint(2.0, CubeColor[0], CubeColor[1], CubeColor[2]);
    this->Opacity->AddPoint(0.0, 1.0 - std::exp(-Mu));
    this->Opacity->AddPoint(2.0, 1.0 - std::exp(-Mu));
    this->Property->SetScalarOpacityUnitDistance(1.0);
    // ka = 1 / (4 pi): without the sky, the ambient fallback is the
    // physical single scattering of a light of intensity 1.
    this->Materials->AddNode(1.0, 1.0 / (4.0 * M_PI), 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0);
    this->Mapper->SetInputData(this->Image);
    this->Mapper->SetMaterialTransferFunction(this->Materials);
    this->Mapper->AutoAdjustSampleDistancesOff();
    this->Mapper->SetSampleDistance(0.25);
    this->Mapper->SetEnvironmentLighting(1.0);
    this->Volume->SetMapper(this->Mapper);
    this->Renderer->SetBackground(grey, grey, grey);
    this->FrameBounds(this->Image->GetBounds());
  }

  std::vector<double> CenterPixel()
  {
    this->Window->Render();
    EXPECT_TRUE(this->Mapper->GetMultiMaterialActive());
    return this->Pixel(Size / 2, Size / 2);
  }
};

/// S0 at p in the cube: the sky it sees through the homogeneous medium, by
/// exact exit distances over many directions.
double ExactS0(const glm::dvec3& p)
{
  const std::vector<glm::dvec3> directions = mmv::SkyDirections(20000);
  double sum = 0.0;
  for (const glm::dvec3& w : directions)
  {
    double t = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a)
    {
      if (w[a] != 0.0)
      {
        t = std::min(t, ((w[a] > 0.0 ? D : 0.0) - p[a]) / w[a]);
      }
    }
    sum += std::exp(-Mu * t);
  }
  return 4.0 * M_PI * sum / directions.size();
}

/// The single scattering along the central ray (per unit colour) under a
/// uniform sky of radiance L, L int (S0 / 4 pi) mu exp(-mu z) dz, by the
/// midpoint rule (the pixel adds the background through the cube).
double ExactCenter(double L)
{
  constexpr int Steps = 64;
  double scattered = 0.0;
  for (int i = 0; i < Steps; ++i)
  {
    const double z = (i + 0.5) * D / Steps; // depth from the camera's face
    const glm::dvec3 p(D / 2, D / 2, D - z);
    scattered += ExactS0(p) / (4.0 * M_PI) * Mu * std::exp(-Mu * z) * D / Steps;
  }
  return L * scattered;
}

bool Has(const std::string& text, const std::string& part)
{
  return text.find(part) != std::string::npos;
}

/// A two-material ball of `dims`^3 points (a translucent diffuse shell
/// around a glossy core), one directional light and a gradient sky: the GPU
/// image and the reference renderer's, with their PSNR, and the PSNR of the
/// GPU image against itself without the sky (how much the sky changes).
void CompareBallWithReference(int dims, double& psnr, double& skyShare, double scattering = 0.0)
{
  constexpr int ImageSize = 64;
  Scene scene(ImageSize);
  const double c = 0.5 * (dims - 1);
  vtkNew<vtkMaterialTransferFunction> materials;
  auto image = TwoMaterialBall(scene, materials, dims);
  if (scattering > 0.0)
  {
    // The same materials scattering, lit by the sky alone.
    materials->RemoveAllNodes();
    materials->AddNode(0.3, 0.2, 0.7, 0.2, 20.0, 1.0, scattering, 0.0);
    materials->AddNode(0.6, 0.1, 0.6, 0.8, 40.0, 1.0, scattering, 0.0);
  }
  vtkNew<vtkMultiMaterialVolumeMapper> mapper;
  mapper->SetInputData(image);
  mapper->SetMaterialTransferFunction(materials);
  mapper->AutoAdjustSampleDistancesOff();
  mapper->SetSampleDistance(0.5 * (dims - 1) / 32.0);
  mapper->SetIrradianceScale(1.0);
  mapper->SetEnvironmentLighting(1.0);
  scene.Volume->SetMapper(mapper);
  scene.Renderer->GradientBackgroundOn();
  scene.Renderer->SetBackground(0.15, 0.1, 0.05);
  scene.Renderer->SetBackground2(0.5, 0.6, 0.8);
  scene.FrameBounds(image->GetBounds(), 1.2);
  const double from[3] = { 2.0 * dims, 2.5 * dims, 3.0 * dims };
  const double to[3] = { c, c, c };
  if (scattering == 0.0)
  {
    scene.AddDirectionalLight(from, to);
  }
  auto grab = [&]()
  {
    scene.Window->Render();
    EXPECT_TRUE(mapper->GetMultiMaterialActive());
    const std::vector<unsigned char> pixels = scene.Pixels();
    auto out = vtkSmartPointer<vtkImageData>::New();
    out->SetDimensions(ImageSize, ImageSize, 1);
    vtkNew<vtkUnsignedCharArray> colors;
    colors->SetNumberOfComponents(3);
    colors->SetNumberOfTuples(ImageSize * ImageSize);
    std::copy(pixels.begin(), pixels.end(), colors->GetPointer(0));
    out->GetPointData()->SetScalars(colors);
    return out;
  };
  vtkSmartPointer<vtkImageData> gpu = grab();
  vtkNew<vtkMultiMaterialReferenceRenderer> reference;
  reference->ExponentialDiffusionOn(); // as the mapper integrates
  vtkImageData* truth = reference->RenderToImage(scene.Renderer, scene.Volume);
  ASSERT_NE(truth, nullptr);
  vtkNew<vtkImageErrorMetrics> metrics;
  ASSERT_TRUE(metrics->Compute(gpu, truth));
  psnr = metrics->GetPSNR();
  // What the sky (or, with scattering, its diffusion) changes.
  if (scattering > 0.0)
  {
    mapper->MultipleScatteringOff();
  }
  else
  {
    mapper->SetEnvironmentLighting(0.0);
  }
  ErrorCounter quiet(mapper); // "no active light" without the sky
  vtkSmartPointer<vtkImageData> dark = grab();
  ASSERT_TRUE(metrics->Compute(dark, gpu));
  skyShare = metrics->GetPSNR();
  std::cout << dims << "^3 ball under a gradient sky" << (scattering > 0.0 ? ", scattering" : "")
            << ": GPU vs reference " << psnr << " dB; without the "
            << (scattering > 0.0 ? "diffusion " : "sky ") << skyShare << " dB from it\n";
}

} // namespace

TEST(EnvironmentLight, UniformSkyOnACubeMatchesItsSingleScatteringAndThePathTracer)
{
  // The path tracer limited to one scattering event, phase function only,
  // is the physical truth of this scene; the quadrature of the exact
  // single scattering is its closed form. The GPU takes the sky's
  // visibility from 64 swept directions.
  constexpr double L = 0.6;
  SkyScene scene(L);
  const double scattered = ExactCenter(L);
  const double background = L * std::exp(-Mu * D);
  const std::vector<double> gpu = scene.CenterPixel();
  EXPECT_EQ(scene.Mapper->GetSkyUpdateCount(), 1);
  vtkNew<vtkMultiMaterialPathTracer> tracer;
  tracer->SetMaxBounces(1);
  tracer->SurfaceScatteringOff();
  tracer->SetSamplesPerPixel(256);
  vtkImageData* physical = tracer->RenderToImage(scene.Renderer, scene.Volume);
  ASSERT_NE(physical, nullptr);
  vtkDataArray* radiance = physical->GetPointData()->GetArray("Radiance");
  vtkDataArray* error = physical->GetPointData()->GetArray("StandardError");
  // The mean of the central 6 x 6 pixels.
  double truth[3] = { 0.0, 0.0, 0.0 };
  double se[3] = { 0.0, 0.0, 0.0 };
  for (int j = Size / 2 - 3; j < Size / 2 + 3; ++j)
  {
    for (int i = Size / 2 - 3; i < Size / 2 + 3; ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        truth[c] += radiance->GetComponent(j * Size + i, c) / 36.0;
        se[c] += std::pow(error->GetComponent(j * Size + i, c) / 36.0, 2.0);
      }
    }
  }
  std::cout << "uniform sky " << L << ": single scattering " << scattered << " + background "
            << background << "; GPU " << gpu[0] << ", path tracer " << truth[0] << " +- "
            << std::sqrt(se[0]) << "\n";
  for (int c = 0; c < 3; ++c)
  {
    const double expected = CubeColor[c] * scattered + background;
    EXPECT_NEAR(truth[c], expected, 5.0 * std::sqrt(se[c]) + 0.002) << "path tracer " << c;
    EXPECT_NEAR(gpu[c], expected, 2.0 / 255.0 + 0.03 * expected) << "GPU " << c;
  }
  // The sky is what lights it: without it (and without lights) the
  // ambient term ka I_c alone remains over the background.
  scene.Mapper->SetEnvironmentLighting(0.0);
  ErrorCounter quiet(scene.Mapper); // "no active light"
  const std::vector<double> dark = scene.CenterPixel();
  for (int c = 0; c < 3; ++c)
  {
    const double ambient = CubeColor[c] * (1.0 - std::exp(-Mu * D)) / (4.0 * M_PI);
    EXPECT_NEAR(dark[c], background + ambient, 2.0 / 255.0) << c;
  }
  EXPECT_GE(quiet.Warnings(), 1);
}

TEST(EnvironmentLight, BackgroundChangeReshadesWithoutEstimating)
{
  // The visibility depends on the data and the opacity only: a new
  // background colour changes the image by the sky's share, with no new
  // estimation; an opacity edit estimates again.
  SkyScene scene(0.3);
  const std::vector<double> first = scene.CenterPixel();
  ASSERT_EQ(scene.Mapper->GetSkyUpdateCount(), 1);
  scene.Renderer->SetBackground(0.6, 0.6, 0.6);
  const std::vector<double> second = scene.CenterPixel();
  EXPECT_EQ(scene.Mapper->GetSkyUpdateCount(), 1);
  // Every term is proportional to the background: twice as bright.
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_NEAR(second[c], 2.0 * first[c], 3.0 / 255.0) << c;
  }
  // A gradient background rotates nothing either: still no estimation.
  scene.Renderer->GradientBackgroundOn();
  scene.Renderer->SetBackground2(0.9, 0.9, 0.9);
  scene.CenterPixel();
  EXPECT_EQ(scene.Mapper->GetSkyUpdateCount(), 1);
  // A material edit that leaves the extinction and the scattering alone
  // (ka here) estimates nothing either.
  scene.Materials->RemoveAllNodes();
  scene.Materials->AddNode(1.0, 0.3, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0);
  scene.CenterPixel();
  EXPECT_EQ(scene.Mapper->GetSkyUpdateCount(), 1);
  scene.Opacity->AddPoint(1.0, 0.2);
  scene.CenterPixel();
  EXPECT_EQ(scene.Mapper->GetSkyUpdateCount(), 2);
}

TEST(EnvironmentLight, OffOrBlackSkyCompilesNoSkyCode)
{
  SkyScene scene(0.5);
  scene.CenterPixel();
  EXPECT_TRUE(Has(scene.Mapper->GetLastFragmentShaderSource(), "#define MMV_USE_SKY 1"));
  scene.Mapper->SetEnvironmentLighting(0.0);
  {
    ErrorCounter quiet(scene.Mapper); // "no active light"
    scene.CenterPixel();
  }
  EXPECT_TRUE(Has(scene.Mapper->GetLastFragmentShaderSource(), "#define MMV_USE_SKY 0"));
  scene.Mapper->SetEnvironmentLighting(1.0);
  scene.Renderer->SetBackground(0.0, 0.0, 0.0);
  {
    ErrorCounter quiet(scene.Mapper);
    scene.CenterPixel();
  }
  EXPECT_TRUE(Has(scene.Mapper->GetLastFragmentShaderSource(), "#define MMV_USE_SKY 0"));
  EXPECT_EQ(scene.Mapper->GetSkyUpdateCount(), 1); // a black sky estimates nothing
}

TEST(EnvironmentLight, NegativeOrNaNStrengthIsOffWithAWarning)
{
  for (double strength : { -1.0, std::nan("") })
  {
    SkyScene scene(0.5);
    scene.Mapper->SetEnvironmentLighting(strength);
    ErrorCounter counter(scene.Mapper);
    scene.CenterPixel();
    EXPECT_GE(counter.Warnings(), 1) << strength;
    EXPECT_EQ(counter.Errors(), 0) << strength;
    EXPECT_TRUE(Has(scene.Mapper->GetLastFragmentShaderSource(), "#define MMV_USE_SKY 0"));
    EXPECT_EQ(scene.Mapper->GetSkyUpdateCount(), 0);
  }
}

TEST(EnvironmentLight, ReferenceRendererAgreesWithGPU)
{
  // The same sky model on the CPU (visibility moments on the data's grid,
  // exact shadow rays for the light) and on the GPU: at 33^3 points both
  // estimate the sky on the same grid; at 97^3 the GPU's grid is 3x
  // coarser (at most 40 per axis). The sky changes the image far more than
  // the two differ. Measured with llvmpipe: 41.4 and 37.9 dB, the sky
  // 29.6 and 25.6 dB of the image.
  vtkSMPTools::SetBackend("STDThread");
  for (int dims : { 33, 97 })
  {
    double psnr = 0.0, skyShare = 0.0;
    CompareBallWithReference(dims, psnr, skyShare);
    EXPECT_GT(psnr, dims == 33 ? 39.0 : 35.5) << dims;
    EXPECT_LT(skyShare, psnr - 8.0) << dims;
  }
}

} // namespace mmvtest

namespace mmvtest
{
TEST(EnvironmentLight, BricksAreLitByTheWholeVolumesSky)
{
  // In bricks the ray cast reads the sky of the whole volume: the image
  // equals the one-brick image.
  std::vector<unsigned char> images[2];
  for (int bricks : { 1, 2 })
  {
    SkyScene scene(0.6);
    scene.Mapper->SetPartitions(bricks, 1, 1);
    scene.Window->Render();
    ASSERT_TRUE(scene.Mapper->GetMultiMaterialActive());
    EXPECT_EQ(scene.Mapper->GetBrickPartitions()[0], bricks);
    EXPECT_TRUE(Has(scene.Mapper->GetLastFragmentShaderSource(), "#define MMV_USE_SKY 1"));
    images[bricks - 1] = scene.Pixels();
  }
  const double psnr = PSNR(images[0], images[1]);
  std::cout << "two bricks against one: " << psnr << " dB\n";
  EXPECT_GT(psnr, 45.0);
}
} // namespace mmvtest

namespace mmvtest
{
TEST(EnvironmentLight, SkyLightDiffusesWhereMaterialsScatter)
{
  // s = 40 on both materials, no light: the sky's moments are diffused as the
  // lights' irradiance is, on the GPU (on the sky's grid) and in the
  // reference renderer (on the data's grid). The diffusion changes the
  // image, and the two agree. Measured with llvmpipe: 54.1 dB apart; the
  // diffusion 44.2 dB of the image.
  vtkSMPTools::SetBackend("STDThread");
  double psnr = 0.0, diffusionShare = 0.0;
  CompareBallWithReference(33, psnr, diffusionShare, 40.0);
  EXPECT_GT(psnr, 50.0);
  EXPECT_LT(diffusionShare, psnr - 6.0);
}
} // namespace mmvtest

namespace mmvtest
{
TEST(EnvironmentLight, EarlierDataComeBackWithoutAnEstimation)
{
  // A series' steps handed back (as ParaView's animation caching does):
  // the sky's moments of earlier data are kept, so returning to them
  // estimates nothing and draws the same image.
  SkyScene scene(0.6);
  scene.Opacity->AddPoint(0.0, 0.0); // extinction grows with the value
  auto other = MakeVolume(Dims, [](int i, int, int) { return i < Dims / 2 ? 2.0f : 1.0f; });
  scene.CenterPixel();
  const std::vector<unsigned char> firstImage = scene.Pixels();
  EXPECT_EQ(scene.Mapper->GetSkyUpdateCount(), 1);
  scene.Mapper->SetInputData(other);
  scene.CenterPixel();
  EXPECT_EQ(scene.Mapper->GetSkyUpdateCount(), 2);
  EXPECT_LT(PSNR(scene.Pixels(), firstImage), 35.0); // another volume and its sky
  scene.Mapper->SetInputData(scene.Image);
  scene.CenterPixel();
  EXPECT_EQ(scene.Mapper->GetSkyUpdateCount(), 2);
  EXPECT_EQ(PSNR(scene.Pixels(), firstImage), std::numeric_limits<double>::infinity());
}
} // namespace mmvtest

namespace mmvtest
{
namespace
{
/// Values from 1 to 2 across the cube, growing along +x or -x (the same
/// range either way).
void FillRamp(vtkImageData* image, bool reversed)
{
  vtkDataArray* values = image->GetPointData()->GetScalars();
  for (vtkIdType i = 0; i < values->GetNumberOfTuples(); ++i)
  {
    const double x = (i % Dims) / D;
    values->SetTuple1(i, 1.0 + (reversed ? 1.0 - x : x));
  }
  values->Modified();
}
}

TEST(EnvironmentLight, EditsAndValuesChangedInPlaceEqualAFreshMapper)
{
  // The normalised values are kept across opacity edits; values changed in
  // the same array (a new modification time) are read again. Both images
  // equal a mapper that saw only the final state.
  SkyScene scene(0.6);
  scene.Opacity->AddPoint(1.0, 0.0); // extinction grows with the value
  FillRamp(scene.Image, false);
  scene.CenterPixel();
  scene.Opacity->AddPoint(1.5, 0.3);
  scene.CenterPixel();
  FillRamp(scene.Image, true);
  scene.CenterPixel();
  EXPECT_EQ(scene.Mapper->GetSkyUpdateCount(), 3);
  SkyScene fresh(0.6);
  fresh.Opacity->AddPoint(1.0, 0.0);
  fresh.Opacity->AddPoint(1.5, 0.3);
  FillRamp(fresh.Image, true);
  fresh.CenterPixel();
  EXPECT_EQ(PSNR(scene.Pixels(), fresh.Pixels()), std::numeric_limits<double>::infinity());
  // And the stale values would show: the edit before the change differs.
  SkyScene before(0.6);
  before.Opacity->AddPoint(1.0, 0.0);
  before.Opacity->AddPoint(1.5, 0.3);
  FillRamp(before.Image, false);
  before.CenterPixel();
  EXPECT_LT(PSNR(before.Pixels(), fresh.Pixels()), 45.0);
}
} // namespace mmvtest
