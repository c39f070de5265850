// Optical model: Henyey-Greenstein in-scattering of the
// particle (ambient) term, emission (Yang et al. eq. 27), and shaders that
// carry neither when no material uses them. Closed forms on a homogeneous
// cube, the reference renderer and the path tracer against the GPU mapper.
#include "mmvTestScenes.h"
#include "mmvTestUtilities.h"

#include "vtkDataArray.h"
#include "vtkImageErrorMetrics.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMultiMaterialParameters.h"
#include "vtkMultiMaterialPathTracer.h"
#include "vtkMultiMaterialPhaseFunction.h"
#include "vtkMultiMaterialReferenceRenderer.h"
#include "vtkMultiMaterialVolumeMapper.h"
#include "vtkSMPTools.h"

#include <gtest/gtest.h>

#include <algorithm>
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
constexpr int Size = 24;       // pixels
const double CubeColor[3] = { 1.0, 0.6, 0.3 };
const double CubeCenter[3] = { 8.0, 8.0, 8.0 };

// A homogeneous cube (value 1) seen down -z by a parallel camera, drawn by
// the GPU mapper; the reference renderer and the path tracer render the
// same scene. Material: particle term only (kd = ks = 0).
struct CubeScene : Scene
{
  vtkNew<vtkMaterialTransferFunction> Materials;
  vtkNew<vtkMultiMaterialVolumeMapper> Mapper;
  vtkSmartPointer<vtkImageData> Image;

  explicit CubeScene(int size = Size)
    : Scene(size)
  {
    vtkSMPTools::SetBackend("STDThread");
    this->Image = MakeVolume(Dims, [](int, int, int) { return 1.0f; });
    this->Color->AddRGBPoint(0.0, CubeColor[0], CubeColor[1], CubeColor[2]);
    this->Color->AddRGBPoint(2.0, CubeColor[0], CubeColor[1], CubeColor[2]);
    this->Opacity->AddPoint(0.0, 1.0 - std::exp(-Mu)); // unit distance 1
    this->Opacity->AddPoint(2.0, 1.0 - std::exp(-Mu));
    this->Property->SetScalarOpacityUnitDistance(1.0);
    this->Mapper->SetInputData(this->Image);
    this->Mapper->SetMaterialTransferFunction(this->Materials);
    this->Mapper->AutoAdjustSampleDistancesOff();
    this->Mapper->SetSampleDistance(0.25);
    this->Mapper->SetIrradianceScale(1.0);
    this->Volume->SetMapper(this->Mapper);
    this->FrameBounds(this->Image->GetBounds());
  }

  void SetMaterial(double ambient, double anisotropy, double emission)
  {
    this->Materials->RemoveAllNodes();
    this->Materials->AddNode(1.0, ambient, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, anisotropy, emission);
  }

  void LightFrom(double z)
  {
    const double from[3] = { CubeCenter[0], CubeCenter[1], z };
    this->AddDirectionalLight(from, CubeCenter);
  }

  /// The window's pixels as an image the error metrics read.
  vtkSmartPointer<vtkImageData> GPUImage()
  {
    this->Window->Render();
    EXPECT_TRUE(this->Mapper->GetMultiMaterialActive());
    const std::vector<unsigned char> pixels = this->Pixels();
    auto image = vtkSmartPointer<vtkImageData>::New();
    const int* size = this->Window->GetSize();
    image->SetDimensions(size[0], size[1], 1);
    vtkNew<vtkUnsignedCharArray> colors;
    colors->SetNumberOfComponents(3);
    colors->SetNumberOfTuples(static_cast<vtkIdType>(size[0]) * size[1]);
    std::copy(pixels.begin(), pixels.end(), colors->GetPointer(0));
    image->GetPointData()->SetScalars(colors);
    return image;
  }
};

/// RGB of the pixel nearest the image centre from an image's array `name`,
/// as doubles; bytes are scaled to [0, 1].
std::vector<double> Center(vtkImageData* image, const char* name = nullptr)
{
  vtkDataArray* array =
    name ? image->GetPointData()->GetArray(name) : image->GetPointData()->GetScalars();
  const int* dims = image->GetDimensions();
  const vtkIdType id = static_cast<vtkIdType>(dims[1] / 2) * dims[0] + dims[0] / 2;
  const double scale = name ? 1.0 : 1.0 / 255.0;
  return { array->GetComponent(id, 0) * scale, array->GetComponent(id, 1) * scale,
    array->GetComponent(id, 2) * scale };
}

/// The path tracer's mean over the central 8 x 8 pixels (all inside the
/// cube's image) and its standard error, per channel: 8 times tighter than
/// one pixel's.
void CentralMean(vtkImageData* image, std::vector<double>& mean, std::vector<double>& error)
{
  vtkDataArray* radiance = image->GetPointData()->GetArray("Radiance");
  vtkDataArray* se = image->GetPointData()->GetArray("StandardError");
  const int* dims = image->GetDimensions();
  mean.assign(3, 0.0);
  error.assign(3, 0.0);
  constexpr int K = 8;
  for (int j = dims[1] / 2 - K / 2; j < dims[1] / 2 + K / 2; ++j)
  {
    for (int i = dims[0] / 2 - K / 2; i < dims[0] / 2 + K / 2; ++i)
    {
      const vtkIdType id = static_cast<vtkIdType>(j) * dims[0] + i;
      for (int c = 0; c < 3; ++c)
      {
        mean[c] += radiance->GetComponent(id, c) / (K * K);
        error[c] += se->GetComponent(id, c) * se->GetComponent(id, c) / (K * K * K * K);
      }
    }
  }
  for (double& e : error)
  {
    e = std::sqrt(e);
  }
}

/// Closed forms of the cube's centre pixel, for ka = 1 and g = 0 (times the
/// colour): light from behind, c mu D exp(-mu D); from the camera's side
/// (shadow extinction = mu), c (1 - exp(-2 mu D)) / 2.
double BackLit()
{
  return Mu * D * std::exp(-Mu * D);
}
double FrontLit()
{
  return 0.5 * (1.0 - std::exp(-2.0 * Mu * D));
}

void ExpectColor(
  const std::vector<double>& pixel, double expected, double tolerance, const char* what)
{
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_NEAR(pixel[c], CubeColor[c] * expected, tolerance) << what << ", channel " << c;
  }
}

// The largest difference, in 8-bit levels, between two images' bytes.
int MaxByteDifference(vtkImageData* a, vtkImageData* b)
{
  vtkDataArray* x = a->GetPointData()->GetScalars();
  vtkDataArray* y = b->GetPointData()->GetScalars();
  int largest = 0;
  for (vtkIdType i = 0; i < x->GetNumberOfValues(); ++i)
  {
    largest = std::max(largest,
      static_cast<int>(std::abs(x->GetVariantValue(i).ToInt() - y->GetVariantValue(i).ToInt())));
  }
  return largest;
}

bool Has(const std::string& text, const std::string& part)
{
  return text.find(part) != std::string::npos;
}
}

TEST(OpticalModel, HenyeyGreensteinIsNormalisedWithMeanCosineG)
{
  // 2 pi times the integral over cos in [-1, 1] (Simpson, 200 000 intervals:
  // the g = 0.95 peak is 1 / (1 - g)^2 / 4 pi wide in cos).
  for (double g : { -0.95, -0.6, -0.2, 0.0, 0.3, 0.6, 0.95 })
  {
    constexpr int N = 200000;
    double total = 0.0;
    double mean = 0.0;
    for (int i = 0; i <= N; ++i)
    {
      const double c = -1.0 + 2.0 * i / N;
      const double w = (i == 0 || i == N) ? 1.0 : (i % 2 ? 4.0 : 2.0);
      const double p = mmv::HenyeyGreenstein(g, c);
      total += w * p;
      mean += w * p * c;
    }
    total *= 2.0 * M_PI * (2.0 / N) / 3.0;
    mean *= 2.0 * M_PI * (2.0 / N) / 3.0;
    EXPECT_NEAR(total, 1.0, 1e-9) << "g " << g;
    EXPECT_NEAR(mean, g, 1e-9) << "g " << g;
  }
  // The shading form is 4 pi HG: exactly 1 at g = 0, in double and in float
  // (the GLSL's precision), so g = 0 leaves the isotropic model's images.
  for (double c : { -1.0, -0.3, 0.0, 0.7, 1.0 })
  {
    EXPECT_EQ(mmv::mmvHenyeyGreensteinRelative(0.0, c), 1.0);
    const float cf = static_cast<float>(c);
    const float denominator = 1.0f + 0.0f * 0.0f - 2.0f * 0.0f * cf;
    EXPECT_EQ((1.0f - 0.0f) / (denominator * std::sqrt(denominator)), 1.0f);
    EXPECT_DOUBLE_EQ(
      mmv::mmvHenyeyGreensteinRelative(0.6, c), 4.0 * M_PI * mmv::HenyeyGreenstein(0.6, c));
  }
  // Straight on: (1 + g) / (1 - g)^2; straight back: (1 - g) / (1 + g)^2.
  EXPECT_NEAR(mmv::mmvHenyeyGreensteinRelative(0.6, 1.0), 10.0, 1e-12);
  EXPECT_NEAR(mmv::mmvHenyeyGreensteinRelative(0.6, -1.0), 0.4 / 2.56, 1e-12);
}

TEST(OpticalModel, ZeroAnisotropyMatchesIsotropicClosedForms)
{
  // g = 0 written explicitly (10-number node) against the isotropic model's
  // closed forms, on the reference renderer (0.5 %) and the GPU mapper with
  // the phase function compiled in (2/255 + 2 %: 8-bit output, tables).
  for (double z : { 1000.0, -1000.0 })
  {
    CubeScene scene;
    scene.SetMaterial(1.0, 0.0, 0.0);
    scene.LightFrom(z);
    const double expected = z > 0.0 ? FrontLit() : BackLit();
    const char* what = z > 0.0 ? "front-lit" : "back-lit";
    vtkNew<vtkMultiMaterialReferenceRenderer> reference;
    vtkImageData* truth = reference->RenderToImage(scene.Renderer, scene.Volume);
    ASSERT_NE(truth, nullptr);
    const std::vector<double> r = Center(truth, "Radiance");
    for (int c = 0; c < 3; ++c)
    {
      EXPECT_NEAR(r[c], CubeColor[c] * expected, 0.005 * CubeColor[c] * expected) << what;
    }
    scene.Mapper->SetCompileUnusedOpticalTerms(true);
    vtkSmartPointer<vtkImageData> gpu = scene.GPUImage();
    ASSERT_TRUE(Has(scene.Mapper->GetLastFragmentShaderSource(), "#define MMV_USE_ANISOTROPY 1"));
    const std::vector<double> p = Center(gpu);
    std::cout << what << ": closed form " << expected << ", reference " << r[0] << ", GPU " << p[0]
              << "\n";
    ExpectColor(p, expected, 2.0 / 255.0 + 0.02 * expected, what);
  }
}

TEST(OpticalModel, ForwardScatteringBrightensBackLitCubeAsPredicted)
{
  // Light straight from behind: the particle term scales by 4 pi HG(g, 1) =
  // (1 + g) / (1 - g)^2 = 10 at g = 0.6; from the camera's side by
  // (1 - g) / (1 + g)^2 = 0.156. ka = 0.09 keeps the bright case below 1;
  // the dim one takes ka = 1.
  constexpr double G = 0.6;
  const double forward = mmv::mmvHenyeyGreensteinRelative(G, 1.0);
  const double backward = mmv::mmvHenyeyGreensteinRelative(G, -1.0);
  for (double z : { -1000.0, 1000.0 })
  {
    const bool backLit = z < 0.0;
    const char* what = backLit ? "back-lit" : "front-lit";
    const double Ka = backLit ? 0.09 : 1.0;
    const double expected = Ka * (backLit ? forward * BackLit() : backward * FrontLit());
    const double isotropic = Ka * (backLit ? BackLit() : FrontLit());
    CubeScene scene;
    scene.SetMaterial(Ka, G, 0.0);
    scene.LightFrom(z);
    vtkSmartPointer<vtkImageData> gpu = scene.GPUImage();
    ASSERT_TRUE(Has(scene.Mapper->GetLastFragmentShaderSource(), "#define MMV_USE_ANISOTROPY 1"));
    vtkNew<vtkMultiMaterialReferenceRenderer> reference;
    vtkImageData* truth = reference->RenderToImage(scene.Renderer, scene.Volume);
    ASSERT_NE(truth, nullptr);
    const std::vector<double> r = Center(truth, "Radiance");
    const std::vector<double> p = Center(gpu);
    vtkNew<vtkImageErrorMetrics> metrics;
    ASSERT_TRUE(metrics->Compute(gpu, truth));
    std::cout << what << " g = " << G << ": closed form " << expected << " (g = 0: " << isotropic
              << "), reference " << r[0] << ", GPU " << p[0] << "; GPU vs reference PSNR "
              << metrics->GetPSNR() << " dB, max error " << metrics->GetMaximumError() << "/255\n";
    for (int c = 0; c < 3; ++c)
    {
      EXPECT_NEAR(r[c], CubeColor[c] * expected, 0.005 * CubeColor[c] * expected) << what;
    }
    ExpectColor(p, expected, 2.0 / 255.0 + 0.02 * expected, what);
    // Measured with Mesa llvmpipe: see docs/performance.md ("Anisotropy and
    // the hybrid shading").
    EXPECT_GT(metrics->GetPSNR(), 40.0) << what;
  }
}

TEST(OpticalModel, SingleScatteringMatchesPathTracerAtKaOneOverFourPi)
{
  // The same HG in all three renderers: with ka = 1 / (4 pi) our particle
  // term is the physical single scattering of a medium with albedo = colour
  // and phase function HG(g) per steradian. Lit straight from behind,
  // g = 0.6: c HG(0.6, 1) mu D exp(-mu D) = c 0.2928, for the GPU, the
  // reference renderer and the path tracer limited to one scattering event
  // (MaxBounces 1, phase function only).
  constexpr double G = 0.6;
  const double expected = mmv::HenyeyGreenstein(G, 1.0) * BackLit();
  CubeScene scene;
  scene.SetMaterial(1.0 / (4.0 * M_PI), G, 0.0);
  scene.LightFrom(-1000.0);
  vtkSmartPointer<vtkImageData> gpu = scene.GPUImage();
  vtkNew<vtkMultiMaterialReferenceRenderer> reference;
  vtkImageData* truth = reference->RenderToImage(scene.Renderer, scene.Volume);
  ASSERT_NE(truth, nullptr);
  vtkNew<vtkMultiMaterialPathTracer> tracer;
  tracer->SetMaxBounces(1);
  tracer->SurfaceScatteringOff();
  tracer->SetSamplesPerPixel(512);
  vtkImageData* physical = tracer->RenderToImage(scene.Renderer, scene.Volume);
  ASSERT_NE(physical, nullptr);
  const std::vector<double> r = Center(truth, "Radiance");
  const std::vector<double> p = Center(gpu);
  std::vector<double> t;
  std::vector<double> se;
  CentralMean(physical, t, se);
  std::cout << "single scattering g = " << G << ": closed form " << expected << ", reference "
            << r[0] << ", GPU " << p[0] << ", path tracer " << t[0] << " +- " << se[0] << "\n";
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_NEAR(r[c], CubeColor[c] * expected, 0.005 * CubeColor[c] * expected) << "reference";
    EXPECT_NEAR(t[c], CubeColor[c] * expected, 5.0 * se[c]) << "path tracer, channel " << c;
    EXPECT_GT(se[c], 0.0);
  }
  ExpectColor(p, expected, 2.0 / 255.0 + 0.02 * expected, "GPU");
}

TEST(OpticalModel, EmissionWithoutLightsMatchesClosedForm)
{
  // No light, ka = 0, e = 0.8: the cube glows with e c (1 - exp(-mu D))
  // (the integral of e c mu exp(-mu s) over the depth), on the GPU, the
  // reference renderer and the path tracer (MaxBounces 0: emission and
  // attenuation, no scattering of the emitted light; 512 paths, mean of the
  // central 8 x 8 pixels).
  constexpr double E = 0.8;
  const double expected = E * (1.0 - std::exp(-Mu * D));
  CubeScene scene;
  scene.SetMaterial(0.0, 0.0, E);
  ErrorCounter quiet(scene.Mapper); // "no active light" is expected here
  vtkSmartPointer<vtkImageData> gpu = scene.GPUImage();
  EXPECT_TRUE(Has(scene.Mapper->GetLastFragmentShaderSource(), "#define MMV_USE_EMISSION 1"));
  vtkNew<vtkMultiMaterialReferenceRenderer> reference;
  vtkImageData* truth = reference->RenderToImage(scene.Renderer, scene.Volume);
  ASSERT_NE(truth, nullptr);
  vtkNew<vtkMultiMaterialPathTracer> tracer;
  tracer->SetMaxBounces(0);
  tracer->SetSamplesPerPixel(512);
  vtkImageData* physical = tracer->RenderToImage(scene.Renderer, scene.Volume);
  ASSERT_NE(physical, nullptr);
  const std::vector<double> r = Center(truth, "Radiance");
  const std::vector<double> p = Center(gpu);
  std::vector<double> t;
  std::vector<double> se;
  CentralMean(physical, t, se);
  vtkNew<vtkImageErrorMetrics> metrics;
  ASSERT_TRUE(metrics->Compute(gpu, truth));
  std::cout << "emission: closed form " << expected << ", reference " << r[0] << ", GPU " << p[0]
            << ", path tracer " << t[0] << " +- " << se[0] << "; GPU vs reference PSNR "
            << metrics->GetPSNR() << " dB\n";
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_NEAR(r[c], CubeColor[c] * expected, 1e-6) << "reference, channel " << c;
    // Bernoulli per path (e c or 0): the reported error is that one, and the
    // central mean is within 5 of them.
    const double pathSE =
      E * CubeColor[c] * std::sqrt(expected / E * (1.0 - expected / E) / 512.0) / 8.0;
    EXPECT_NEAR(se[c], pathSE, 0.1 * pathSE) << "path tracer, channel " << c;
    EXPECT_NEAR(t[c], CubeColor[c] * expected, 5.0 * pathSE) << "path tracer, channel " << c;
  }
  ExpectColor(p, expected, 2.0 / 255.0, "GPU");
  EXPECT_GT(metrics->GetPSNR(), 40.0);
  // Emission ignores lights: a light from behind adds only the (ka = 0)
  // particle term, i.e. nothing.
  scene.LightFrom(-1000.0);
  ExpectColor(Center(scene.GPUImage()), expected, 2.0 / 255.0, "GPU, lit");
}

TEST(OpticalModel, DefaultMaterialsComposeNoPhaseOrEmissionCode)
{
  // The HG function and the emission term enter the shader source only while
  // some material uses them (g != 0 with a light, e != 0), and leave it
  // again: the variant follows the materials.
  CubeScene scene;
  const std::string hg = "float mmvHenyeyGreensteinRelative(";
  const std::string glow = "vec3 mmvEmission(";
  scene.Materials->AddNode(1.0, 0.2, 0.7, 0.2, 20.0, 1.0, 0.0, 0.0); // 8-number node
  scene.LightFrom(1000.0);
  scene.Window->Render();
  std::string source = scene.Mapper->GetLastFragmentShaderSource();
  ASSERT_TRUE(Has(source, "mmvShadeSegment")) << "not our shader";
  EXPECT_FALSE(Has(source, hg));
  EXPECT_FALSE(Has(source, glow));
  EXPECT_TRUE(Has(source, "#define MMV_USE_ANISOTROPY 0"));
  EXPECT_TRUE(Has(source, "#define MMV_USE_EMISSION 0"));

  scene.Materials->AddNode(1.0, 0.2, 0.7, 0.2, 20.0, 1.0, 0.0, 0.0, -0.3);
  scene.Window->Render();
  source = scene.Mapper->GetLastFragmentShaderSource();
  EXPECT_TRUE(Has(source, hg));
  EXPECT_FALSE(Has(source, glow));

  scene.Materials->AddNode(1.0, 0.2, 0.7, 0.2, 20.0, 1.0, 0.0, 0.0, -0.3, 1.5);
  scene.Window->Render();
  source = scene.Mapper->GetLastFragmentShaderSource();
  EXPECT_TRUE(Has(source, hg));
  EXPECT_TRUE(Has(source, glow));

  scene.Materials->AddNode(1.0, 0.2, 0.7, 0.2, 20.0, 1.0, 0.0, 0.0, 0.0, 0.0);
  scene.Window->Render();
  source = scene.Mapper->GetLastFragmentShaderSource();
  EXPECT_FALSE(Has(source, hg));
  EXPECT_FALSE(Has(source, glow));

  // Without a light no particle term is lit: g alone compiles no HG code.
  scene.Renderer->RemoveAllLights();
  scene.Materials->AddNode(1.0, 0.2, 0.7, 0.2, 20.0, 1.0, 0.0, 0.0, 0.6);
  ErrorCounter quiet(scene.Mapper); // "no active light" is expected here
  scene.Window->Render();
  source = scene.Mapper->GetLastFragmentShaderSource();
  EXPECT_FALSE(Has(source, hg));
  EXPECT_TRUE(Has(source, "#define MMV_NUMBER_OF_LIGHTS 0"));
}

TEST(OpticalModel, TermsCompiledInWithZeroValuesChangeNoPixel)
{
  // A lit two-material ball with every g = 0 and e = 0: the variant without
  // the terms and the one with them render identical bytes, so leaving them
  // out is a pure saving.
  constexpr int Ball = 25;
  Scene scene(48);
  auto image = ShellAndCoreBall(scene, Ball, 0.08);
  vtkNew<vtkMaterialTransferFunction> materials;
  materials->AddNode(0.3, 0.3, 0.7, 0.2, 20.0, 1.0, 0.0, 0.1);
  materials->AddNode(0.6, 0.1, 0.6, 0.8, 40.0, 1.0, 0.0, 0.0);
  vtkNew<vtkMultiMaterialVolumeMapper> mapper;
  mapper->SetInputData(image);
  mapper->SetMaterialTransferFunction(materials);
  scene.Volume->SetMapper(mapper);
  scene.FrameBounds(image->GetBounds(), 1.2);
  const double from[3] = { 40.0, 50.0, 60.0 };
  const double to[3] = { 12.0, 12.0, 12.0 };
  scene.AddDirectionalLight(from, to);
  const double behind[3] = { -10.0, 30.0, -50.0 };
  scene.AddDirectionalLight(behind, to);

  scene.Window->Render();
  ASSERT_TRUE(mapper->GetMultiMaterialActive());
  const std::vector<unsigned char> without = scene.Pixels();
  EXPECT_FALSE(Has(mapper->GetLastFragmentShaderSource(), "float mmvHenyeyGreensteinRelative("));

  mapper->SetCompileUnusedOpticalTerms(true);
  scene.Window->Render();
  const std::string source = mapper->GetLastFragmentShaderSource();
  ASSERT_TRUE(Has(source, "float mmvHenyeyGreensteinRelative("));
  ASSERT_TRUE(Has(source, "vec3 mmvEmission("));
  const std::vector<unsigned char> with = scene.Pixels();
  ASSERT_EQ(with.size(), without.size());
  int differing = 0;
  int lit = 0;
  for (size_t i = 0; i < with.size(); ++i)
  {
    differing += with[i] != without[i] ? 1 : 0;
    lit += without[i] > 8 ? 1 : 0;
  }
  EXPECT_EQ(differing, 0);
  EXPECT_GT(lit, static_cast<int>(with.size() / 10)) << "the ball must cover the image";
}

// Item 5's shortcut for selective absorption: no RGB irradiance while every
// transmission colour is white. The tint declarations and fetches enter the
// shader only with a non-white T and leave again; grey nodes written as 10
// numbers or as 13 with T = (1, 1, 1) render the same bytes.
TEST(OpticalModel, WhiteTransmissionComposesNoRGBIrradianceCode)
{
  CubeScene scene;
  const std::string fetch = "void mmvFetchTints(";
  scene.LightFrom(-1000.0);
  const double ten[10] = { 1.0, 1.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0 };
  ASSERT_TRUE(scene.Materials->SetNodes(10, ten));
  vtkSmartPointer<vtkImageData> grey = scene.GPUImage();
  std::string source = scene.Mapper->GetLastFragmentShaderSource();
  ASSERT_TRUE(Has(source, "mmvShadeSegment")) << "not our shader";
  EXPECT_TRUE(Has(source, "#define MMV_USE_RGB_IRRADIANCE 0"));
  EXPECT_FALSE(Has(source, fetch));

  scene.Materials->AddNode(1.0, 1.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0);
  vtkSmartPointer<vtkImageData> white = scene.GPUImage();
  EXPECT_FALSE(Has(scene.Mapper->GetLastFragmentShaderSource(), fetch));
  EXPECT_EQ(MaxByteDifference(grey, white), 0);

  scene.Materials->AddNode(1.0, 1.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.6, 0.3);
  vtkSmartPointer<vtkImageData> tinted = scene.GPUImage();
  source = scene.Mapper->GetLastFragmentShaderSource();
  EXPECT_TRUE(Has(source, "#define MMV_USE_RGB_IRRADIANCE 1"));
  EXPECT_TRUE(Has(source, fetch));
  EXPECT_GT(MaxByteDifference(grey, tinted), 10) << "the tint must show";

  scene.Materials->AddNode(1.0, 1.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0);
  vtkSmartPointer<vtkImageData> again = scene.GPUImage();
  EXPECT_FALSE(Has(scene.Mapper->GetLastFragmentShaderSource(), fetch));
  EXPECT_EQ(MaxByteDifference(grey, again), 0);
}

// Selective absorption in the image: the cube lit from behind with ka = 1,
// c_t = 1 and transmission colour T; channel lambda's extinction toward the
// light is mu w_lambda (w = 1 - ln T), toward the camera mu, so the centre
// pixel is c (exp(-mu D) - exp(-mu D w)) / (w - 1) (c mu D exp(-mu D) at
// w = 1). The reference renderer (tint per sample) within 0.5 %, the GPU
// (tint on every second irradiance point) within 2/255 + 2 %.
TEST(OpticalModel, TintedBackLitCubeMatchesTheClosedForm)
{
  const double transmission[3] = { 1.0, 0.5, 0.2 };
  CubeScene scene;
  scene.Materials->AddNode(1.0, 1.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0, transmission[0],
    transmission[1], transmission[2]);
  scene.LightFrom(-1000.0);
  double expected[3];
  for (int c = 0; c < 3; ++c)
  {
    const double w = mmv::TransmissionWeight(transmission[c]);
    expected[c] = CubeColor[c] *
      (w > 1.0 ? (std::exp(-Mu * D) - std::exp(-Mu * D * w)) / (w - 1.0) : BackLit());
  }
  vtkNew<vtkMultiMaterialReferenceRenderer> reference;
  vtkImageData* truth = reference->RenderToImage(scene.Renderer, scene.Volume);
  ASSERT_NE(truth, nullptr);
  const std::vector<double> r = Center(truth, "Radiance");
  vtkSmartPointer<vtkImageData> gpu = scene.GPUImage();
  ASSERT_TRUE(Has(scene.Mapper->GetLastFragmentShaderSource(), "#define MMV_USE_RGB_IRRADIANCE 1"));
  const std::vector<double> p = Center(gpu);
  for (int c = 0; c < 3; ++c)
  {
    std::cout << "tinted back-lit channel " << c << ": closed form " << expected[c]
              << ", reference " << r[c] << ", GPU " << p[c] << "\n";
    EXPECT_NEAR(r[c], expected[c], 0.005 * expected[c]) << "channel " << c;
    EXPECT_NEAR(p[c], expected[c], 2.0 / 255.0 + 0.02 * expected[c]) << "channel " << c;
  }
  // The blue shadow is visibly deeper than the grey one (0.6 of it at most).
  EXPECT_LT(expected[2] / CubeColor[2], 0.6 * BackLit());
}

TEST(OpticalModel, OlderNodeLayoutsLoadWithNewValuesAtDefaults)
{
  // 13 numbers a node now; 10 (before the transmission colour), 9 (before
  // emission) and 8 (before anisotropy) still load, the missing values at
  // their defaults (T = 1: grey; g = e = 0).
  vtkNew<vtkMaterialTransferFunction> f;
  constexpr int Stride = vtkMaterialTransferFunction::NodeStride;
  ASSERT_EQ(Stride, 13);
  const std::vector<double> current = { 0.0, 0.2, 0.7, 0.2, 20.0, 1.0, 0.5, 0.1, 0.6, 2.0, 0.9, 0.5,
    0.25, 1.0, 0.3, 0.6, 0.1, 10.0, 2.0, 1.0, 0.0, -0.4, 0.5, 0.0, 1.0, 0.5 };
  ASSERT_TRUE(f->SetNodes(26, current.data()));
  std::vector<double> back(26);
  f->GetNodes(back.data());
  EXPECT_EQ(back, current);

  std::vector<double> expected = current;
  for (int i : { 10, 11, 12, 23, 24, 25 })
  {
    expected[i] = 1.0;
  }
  const std::vector<double> ten = { 0.0, 0.2, 0.7, 0.2, 20.0, 1.0, 0.5, 0.1, 0.6, 2.0, 1.0, 0.3,
    0.6, 0.1, 10.0, 2.0, 1.0, 0.0, -0.4, 0.5 };
  ASSERT_TRUE(f->SetNodes(20, ten.data()));
  f->GetNodes(back.data());
  EXPECT_EQ(back, expected);
  EXPECT_FALSE(f->HasChromaticTransmission());

  const std::vector<double> nine = { 0.0, 0.2, 0.7, 0.2, 20.0, 1.0, 0.5, 0.1, 0.6, 1.0, 0.3, 0.6,
    0.1, 10.0, 2.0, 1.0, 0.0, -0.4 };
  ASSERT_TRUE(f->SetNodes(18, nine.data()));
  f->GetNodes(back.data());
  expected[9] = expected[22] = 0.0;
  EXPECT_EQ(back, expected);

  // 40 numbers: 4 nodes of 10 or 5 nodes of 8. The legacy list's 9th number
  // is the next node's value (> 0.99), invalid as g: read as 8 a node.
  std::vector<double> eight;
  for (int n = 0; n < 5; ++n)
  {
    const std::vector<double> node = { 10.0 * n, 0.2, 0.7, 0.2, 20.0, 1.0, 0.5, 0.1 };
    eight.insert(eight.end(), node.begin(), node.end());
  }
  EXPECT_EQ(vtkMaterialTransferFunction::DetectNodeStride(40, eight.data()),
    vtkMaterialTransferFunction::LegacyNodeStride);
  ASSERT_TRUE(f->SetNodes(40, eight.data()));
  ASSERT_EQ(f->GetSize(), 5);
  double node[Stride];
  ASSERT_TRUE(f->GetNode(4, node));
  EXPECT_EQ(node[0], 40.0);
  EXPECT_EQ(node[1 + mmv::Anisotropy], 0.0);
  EXPECT_EQ(node[1 + mmv::Emission], 0.0);
  EXPECT_EQ(node[1 + mmv::TransmissionR], 1.0);
  EXPECT_EQ(node[1 + mmv::TransmissionB], 1.0);
  // 130 numbers: 10 nodes of 13 or 13 nodes of 10. Written by GetNodes (13
  // a node) they stay 13 a node; a 10-a-node list of 13 nodes reads as 10 (as
  // 13 its 11th number, the next node's value 10, is an invalid T > 1).
  std::vector<double> thirteen, tens;
  for (int n = 0; n < 13; ++n)
  {
    const std::vector<double> one = { 10.0 * n, 0.2, 0.7, 0.2, 20.0, 1.0, 0.5, 0.1, 0.3, 1.0, 0.5,
      0.5, 1.0 };
    if (n < 10)
    {
      thirteen.insert(thirteen.end(), one.begin(), one.end());
    }
    tens.insert(tens.end(), one.begin(), one.begin() + 10);
  }
  EXPECT_EQ(vtkMaterialTransferFunction::DetectNodeStride(130, thirteen.data()), Stride);
  EXPECT_EQ(vtkMaterialTransferFunction::DetectNodeStride(130, tens.data()),
    vtkMaterialTransferFunction::EmissionNodeStride);
  // The old AddNode overloads keep working, with the new values at 0.
  f->RemoveAllNodes();
  EXPECT_EQ(f->AddNode(5.0, 0.2, 0.7, 0.2, 20.0, 1.0, 0.5, 0.1), 0);
  EXPECT_EQ(f->EvaluateParameter(5.0, mmv::Emission), 0.0);
  EXPECT_EQ(f->EvaluateParameter(5.0, mmv::Anisotropy), 0.0);
  EXPECT_FALSE(f->HasNonZero(mmv::Emission));
  EXPECT_EQ(f->AddNode(6.0, 0.2, 0.7, 0.2, 20.0, 1.0, 0.5, 0.1, 0.0, 3.0), 1);
  EXPECT_TRUE(f->HasNonZero(mmv::Emission));
  // A negative or non-finite emission is an input error.
  ErrorCounter errors(f);
  EXPECT_EQ(f->AddNode(7.0, 0.2, 0.7, 0.2, 20.0, 1.0, 0.5, 0.1, 0.0, -1.0), -1);
  EXPECT_EQ(f->AddNode(7.0, 0.2, 0.7, 0.2, 20.0, 1.0, 0.5, 0.1, 0.0, std::nan("")), -1);
  EXPECT_EQ(errors.Errors(), 2);
  EXPECT_NE(errors.LastMessage().find("emission"), std::string::npos) << errors.LastMessage();
  EXPECT_EQ(f->GetSize(), 2);
  // The 10-number AddNode is grey; the 13-number one takes a colour.
  EXPECT_FALSE(f->HasChromaticTransmission());
  EXPECT_EQ(f->AddNode(8.0, 0.2, 0.7, 0.2, 20.0, 1.0, 0.5, 0.1, 0.0, 0.0, 1.0, 0.5, 0.25), 2);
  EXPECT_TRUE(f->HasChromaticTransmission());
}
} // namespace mmvtest
