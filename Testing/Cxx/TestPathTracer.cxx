// vtkMultiMaterialPathTracer against closed forms: the white furnace, a pure
// absorber, single scattering in a thin slab (isotropic and Henyey-Greenstein),
// the phase-function sampler, 1/sqrt(N) convergence, reproducibility and bad
// input. Small volumes and images: the whole file runs in seconds.
#include "mmvTestUtilities.h"

#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMultiMaterialParameters.h"
#include "vtkMultiMaterialPathTracer.h"
#include "vtkMultiMaterialPhaseFunction.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkRenderer.h"
#include "vtkSMPTools.h"
#include "vtkVolumeProperty.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <memory>
#include <random>
#include <vector>

namespace mmvtest
{
namespace
{

// A box of nx x ny x nz points (spacing 1) with values f(i, j, k), a camera
// looking down -z at it, framing `frame` times its height.
struct PathScene
{
  vtkNew<vtkImageData> Image;
  vtkNew<vtkVolumeProperty> Property;
  vtkNew<vtkColorTransferFunction> Color;
  vtkNew<vtkPiecewiseFunction> Opacity;
  vtkNew<vtkMaterialTransferFunction> Materials;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkMultiMaterialPathTracer> Tracer;

  PathScene(int nx, int ny, int nz, const std::function<float(int, int, int)>& f, double frame)
  {
    vtkSMPTools::SetBackend("STDThread");
    this->Image->SetDimensions(nx, ny, nz);
    vtkNew<vtkFloatArray> values;
    values->SetNumberOfTuples(static_cast<vtkIdType>(nx) * ny * nz);
    vtkIdType id = 0;
    for (int k = 0; k < nz; ++k)
    {
      for (int j = 0; j < ny; ++j)
      {
        for (int i = 0; i < nx; ++i)
        {
          values->SetValue(id++, f(i, j, k));
        }
      }
    }
    this->Image->GetPointData()->SetScalars(values);
    this->Property->SetColor(this->Color);
    this->Property->SetScalarOpacity(this->Opacity);
    this->Property->SetScalarOpacityUnitDistance(1.0);
    this->Renderer->AutomaticLightCreationOff();
    this->Renderer->SetBackground(0.0, 0.0, 0.0);
    double b[6];
    this->Image->GetBounds(b);
    vtkCamera* camera = this->Renderer->GetActiveCamera();
    camera->ParallelProjectionOn();
    camera->SetFocalPoint(0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5]));
    camera->SetPosition(0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), b[5] + 50.0);
    camera->SetViewUp(0.0, 1.0, 0.0);
    camera->SetParallelScale(frame * 0.5 * (b[3] - b[2]));
    camera->SetClippingRange(1.0, 200.0);
    this->Tracer->SetInputData(this->Image);
    this->Tracer->SetVolumeProperty(this->Property);
    this->Tracer->SetMaterialTransferFunction(this->Materials);
  }

  // One colour and one extinction (per unit length) for every value.
  void SetMedium(double r, double g, double b, double sigma)
  {
    for (double x : { -10.0, 10.0 })
    {
      this->Color->AddRGBPoint(x, r, g, b);
      this->Opacity->AddPoint(x, -std::expm1(-sigma));
    }
  }

  void AddLightAlong(double x, double y, double z)
  {
    vtkNew<vtkLight> light;
    light->SetLightTypeToSceneLight();
    light->PositionalOff();
    light->SetPosition(x, y, z);
    light->SetFocalPoint(0.0, 0.0, 0.0);
    light->SetIntensity(1.0);
    this->Renderer->AddLight(light);
  }

  vtkImageData* Render(int size)
  {
    vtkImageData* out = this->Tracer->Render(this->Renderer, size, size);
    EXPECT_NE(out, nullptr);
    return out;
  }
};

std::vector<double> Array(vtkImageData* image, const char* name)
{
  vtkDataArray* a = image->GetPointData()->GetArray(name);
  std::vector<double> v(a->GetNumberOfValues());
  for (vtkIdType i = 0; i < a->GetNumberOfValues(); ++i)
  {
    v[i] = a->GetComponent(i / 3, i % 3);
  }
  return v;
}

// Root-mean-square difference from `expected` per channel value.
double RMSError(const std::vector<double>& values, const double expected[3])
{
  double sum = 0.0;
  for (size_t i = 0; i < values.size(); ++i)
  {
    const double d = values[i] - expected[i % 3];
    sum += d * d;
  }
  return std::sqrt(sum / values.size());
}

double Mean(const std::vector<double>& values, int channel)
{
  double sum = 0.0;
  for (size_t i = channel; i < values.size(); i += 3)
  {
    sum += values[i];
  }
  return sum / (values.size() / 3);
}

// An absorbing slab 9 x 9 x 5 points (4 units thick), optical depth 0.8.
constexpr double SlabSigma = 0.2;
constexpr double SlabThickness = 4.0;
const double Background[3] = { 0.2, 0.6, 1.0 };

void MakeAbsorber(PathScene& scene)
{
  scene.SetMedium(0.0, 0.0, 0.0, SlabSigma);
  scene.Renderer->SetBackground(Background[0], Background[1], Background[2]);
}

PathScene* NewSlab()
{
  return new PathScene(
    9, 9, 5, [](int, int, int) { return 1.0f; }, 0.5);
}
}

TEST(PathTracer, WhiteFurnaceSphereIsInvisible)
{
  // A soft sphere of albedo 1 (optical diameter about 5) under a uniform sky:
  // whatever the paths do inside, they return the sky. With albedo 0 the
  // same sphere is clearly dark, so the furnace is not trivially passed.
  for (bool surface : { false, true })
  {
    SCOPED_TRACE(surface ? "surface scattering on" : "phase function only");
    PathScene scene(
      17, 17, 17,
      [](int i, int j, int k)
      {
        const double r =
          std::sqrt((i - 8.0) * (i - 8.0) + (j - 8.0) * (j - 8.0) + (k - 8.0) * (k - 8.0));
        return static_cast<float>(std::min(1.0, std::max(0.0, 7.0 - r)));
      },
      1.1);
    scene.Color->AddRGBPoint(0.0, 1.0, 1.0, 1.0);
    scene.Color->AddRGBPoint(1.0, 1.0, 1.0, 1.0);
    scene.Opacity->AddPoint(0.0, 0.0);
    scene.Opacity->AddPoint(1.0, -std::expm1(-0.5));
    // ks = 0: the Lambertian lobe reflects all it receives (a Blinn lobe
    // loses what falls below the horizon); g = 0.6 forward scattering.
    // Every path then returns the sky exactly, unless energy is lost or
    // made (a wrong weight, a path cut short): the tolerance is the
    // standard error, 0 when all paths agree.
    scene.Materials->AddNode(0.0, 0.2, 0.7, 0.0, 20.0, 1.0, 0.0, 0.0, 0.6);
    scene.Renderer->SetBackground(0.5, 0.5, 0.5);
    scene.Tracer->SetSurfaceScattering(surface);
    scene.Tracer->SetSamplesPerPixel(64);
    vtkImageData* out = scene.Render(16);
    ASSERT_NE(out, nullptr);
    const std::vector<double> radiance = Array(out, "Radiance");
    const std::vector<double> error = Array(out, "StandardError");
    for (size_t i = 0; i < radiance.size(); ++i)
    {
      EXPECT_NEAR(radiance[i], 0.5, 4.5 * error[i] + 1e-12) << "value " << i;
    }
    // Paths did scatter, several times each where they met the sphere.
    EXPECT_GT(scene.Tracer->GetNumberOfEvents(), 16 * 16 * 64);
  }
  // The same sphere, black: the centre pixels lose most of the sky.
  PathScene dark(
    17, 17, 17,
    [](int i, int j, int k)
    {
      const double r =
        std::sqrt((i - 8.0) * (i - 8.0) + (j - 8.0) * (j - 8.0) + (k - 8.0) * (k - 8.0));
      return static_cast<float>(std::min(1.0, std::max(0.0, 7.0 - r)));
    },
    1.1);
  dark.Color->AddRGBPoint(0.0, 0.0, 0.0, 0.0);
  dark.Opacity->AddPoint(0.0, 0.0);
  dark.Opacity->AddPoint(1.0, -std::expm1(-0.5));
  dark.Renderer->SetBackground(0.5, 0.5, 0.5);
  dark.Tracer->SetSamplesPerPixel(64);
  vtkImageData* out = dark.Render(16);
  ASSERT_NE(out, nullptr);
  EXPECT_LT(out->GetPointData()->GetArray("Radiance")->GetComponent(8 * 16 + 8, 0), 0.1);
}

TEST(PathTracer, PureAbsorberSlabFaceOn)
{
  std::unique_ptr<PathScene> scene(NewSlab());
  MakeAbsorber(*scene);
  scene->Tracer->SetSamplesPerPixel(256);
  vtkImageData* out = scene->Render(8);
  ASSERT_NE(out, nullptr);
  const double t = std::exp(-SlabSigma * SlabThickness);
  const std::vector<double> radiance = Array(out, "Radiance");
  const std::vector<double> error = Array(out, "StandardError");
  for (int c = 0; c < 3; ++c)
  {
    // 64 pixels: the image mean has a standard error of about SE / 8.
    const double expected = Background[c] * t;
    const double se = Background[c] * std::sqrt(t * (1.0 - t) / (256.0 * 64.0));
    EXPECT_NEAR(Mean(radiance, c), expected, 4.0 * se) << "channel " << c;
    // The reported error is the Bernoulli one.
    const double bernoulli = Background[c] * std::sqrt(t * (1.0 - t) / 256.0);
    EXPECT_NEAR(Mean(error, c), bernoulli, 0.1 * bernoulli);
  }
  // Colors are the clamped, rounded radiance.
  vtkDataArray* colors = out->GetPointData()->GetArray("Colors");
  ASSERT_NE(colors, nullptr);
  EXPECT_EQ(colors->GetNumberOfComponents(), 3);
  EXPECT_EQ(colors->GetComponent(0, 2), std::lround(radiance[2] * 255.0));
}

TEST(PathTracer, ThinSlabSingleScatteringClosedForm)
{
  // Light from the camera's side, camera looking down -z: a photon entering
  // at the top face, scattered back at depth s, travelled 2 s, so
  //   L = E albedo p(-1) (1 - exp(-2 sigma L)) / 2.
  constexpr double Sigma = 0.05; // optical depth 0.2
  const double albedo[3] = { 1.0, 0.5, 0.25 };
  for (double g : { 0.0, 0.5 })
  {
    SCOPED_TRACE("g = " + std::to_string(g));
    std::unique_ptr<PathScene> scene(NewSlab());
    scene->SetMedium(albedo[0], albedo[1], albedo[2], Sigma);
    scene->Materials->AddNode(0.0, 0.2, 0.7, 0.2, 20.0, 1.0, 0.0, 0.0, g);
    scene->AddLightAlong(0.0, 0.0, 1.0);
    scene->Tracer->SetMaxBounces(1);
    scene->Tracer->SetSamplesPerPixel(1024);
    vtkImageData* out = scene->Render(8);
    ASSERT_NE(out, nullptr);
    const std::vector<double> radiance = Array(out, "Radiance");
    const std::vector<double> error = Array(out, "StandardError");
    const double phase = mmv::HenyeyGreenstein(g, -1.0);
    const double single = phase * 0.5 * -std::expm1(-2.0 * Sigma * SlabThickness);
    for (int c = 0; c < 3; ++c)
    {
      const double seOfMean = Mean(error, c) / 8.0; // 64 independent pixels
      EXPECT_NEAR(Mean(radiance, c), albedo[c] * single, 4.0 * seOfMean + 1e-12) << "channel " << c;
      EXPECT_LT(seOfMean, 0.03 * albedo[c] * single) << "the test resolves 3 %";
    }
    // All bounces: multiple scattering adds a little (optically thin).
    scene->Tracer->SetMaxBounces(64);
    out = scene->Render(8);
    ASSERT_NE(out, nullptr);
    const double all = Mean(Array(out, "Radiance"), 0);
    EXPECT_GT(all, single);
    EXPECT_LT(all, single * 2.0);
  }
}

TEST(PathTracer, HenyeyGreensteinSamplerIsNormalisedWithMeanCosineG)
{
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  for (double g : { -0.7, 0.0, 0.3, 0.9 })
  {
    SCOPED_TRACE("g = " + std::to_string(g));
    // 2 pi * integral over cos of p = 1 (midpoint rule, fine grid).
    const int n = 200000;
    double integral = 0.0;
    double mean = 0.0;
    for (int i = 0; i < n; ++i)
    {
      const double c = -1.0 + (i + 0.5) * 2.0 / n;
      integral += 2.0 * M_PI * mmv::HenyeyGreenstein(g, c) * 2.0 / n;
      mean += 2.0 * M_PI * c * mmv::HenyeyGreenstein(g, c) * 2.0 / n;
    }
    EXPECT_NEAR(integral, 1.0, 1e-3);
    EXPECT_NEAR(mean, g, 1e-3);
    // Samples: mean cosine g, and their CDF matches the density's.
    const int samples = 200000;
    double sum = 0.0, sum2 = 0.0;
    int below = 0;
    for (int i = 0; i < samples; ++i)
    {
      const double c = mmv::SampleHenyeyGreensteinCosine(g, uniform(rng));
      ASSERT_GE(c, -1.0);
      ASSERT_LE(c, 1.0);
      sum += c;
      sum2 += c * c;
      below += c < 0.0;
    }
    const double sampleMean = sum / samples;
    const double sd = std::sqrt(sum2 / samples - sampleMean * sampleMean);
    EXPECT_NEAR(sampleMean, g, 4.0 * sd / std::sqrt(double(samples)));
    // P(cos < 0) = (1 - g^2)/(2g) (1/sqrt(1+g^2) - 1/(1+g)) for g != 0, 1/2 for g = 0.
    const double p0 = std::abs(g) < 1e-9
      ? 0.5
      : (1.0 - g * g) / (2.0 * g) * (1.0 / std::sqrt(1.0 + g * g) - 1.0 / (1.0 + g));
    EXPECT_NEAR(double(below) / samples, p0, 4.0 * std::sqrt(p0 * (1.0 - p0) / samples));
  }
}

TEST(PathTracer, ErrorFallsAsOneOverSqrtN)
{
  // The absorber's estimate is Bernoulli: RMS error sqrt(t (1 - t) / N) b.
  std::unique_ptr<PathScene> scene(NewSlab());
  MakeAbsorber(*scene);
  const double t = std::exp(-SlabSigma * SlabThickness);
  const double expected[3] = { Background[0] * t, Background[1] * t, Background[2] * t };
  std::vector<double> rms;
  for (int n : { 16, 64, 256 })
  {
    scene->Tracer->SetSamplesPerPixel(n);
    vtkImageData* out = scene->Render(16);
    ASSERT_NE(out, nullptr);
    rms.push_back(RMSError(Array(out, "Radiance"), expected));
    const double predicted = std::sqrt(t * (1.0 - t) / n) *
      std::sqrt((Background[0] * Background[0] + Background[1] * Background[1] +
                  Background[2] * Background[2]) /
        3.0);
    // 768 values: the RMS itself is known to a few per cent.
    EXPECT_NEAR(rms.back(), predicted, 0.15 * predicted) << n << " samples";
  }
  EXPECT_NEAR(rms[0] / rms[1], 2.0, 0.4);
  EXPECT_NEAR(rms[1] / rms[2], 2.0, 0.4);
}

TEST(PathTracer, SameSeedSameImageAnyThreadCount)
{
  std::unique_ptr<PathScene> scene(NewSlab());
  scene->SetMedium(0.9, 0.8, 0.7, 0.3);
  scene->AddLightAlong(1.0, 2.0, 3.0);
  scene->Renderer->SetBackground(0.1, 0.2, 0.3);
  scene->Tracer->SetSamplesPerPixel(8);
  const std::vector<double> first = Array(scene->Render(12), "Radiance");
  const std::vector<double> again = Array(scene->Render(12), "Radiance");
  EXPECT_EQ(first, again);
  vtkSMPTools::SetBackend("Sequential");
  const std::vector<double> sequential = Array(scene->Render(12), "Radiance");
  vtkSMPTools::SetBackend("STDThread");
  EXPECT_EQ(first, sequential);
  scene->Tracer->SetSeed(1);
  EXPECT_NE(first, Array(scene->Render(12), "Radiance"));
}

TEST(PathTracer, BadInputIsReportedNotCrashed)
{
  std::unique_ptr<PathScene> scene(NewSlab());
  MakeAbsorber(*scene);
  vtkMultiMaterialPathTracer* tracer = scene->Tracer;
  ErrorCounter errors(tracer);
  struct Case
  {
    const char* What;
    std::function<void()> Break;
    std::function<void()> Repair;
  };
  const std::vector<Case> cases = {
    { "null input", [&] { tracer->SetInputData(nullptr); },
      [&] { tracer->SetInputData(scene->Image); } },
    { "no property", [&] { tracer->SetVolumeProperty(nullptr); },
      [&] { tracer->SetVolumeProperty(scene->Property); } },
    { "zero samples", [&] { tracer->SetSamplesPerPixel(0); },
      [&] { tracer->SetSamplesPerPixel(4); } },
    { "negative bounces", [&] { tracer->SetMaxBounces(-1); }, [&] { tracer->SetMaxBounces(8); } },
  };
  for (const Case& c : cases)
  {
    SCOPED_TRACE(c.What);
    errors.Reset();
    c.Break();
    EXPECT_EQ(tracer->Render(scene->Renderer, 4, 4), nullptr);
    EXPECT_EQ(errors.Errors(), 1) << errors.LastMessage();
    c.Repair();
    EXPECT_NE(tracer->Render(scene->Renderer, 4, 4), nullptr);
  }
  errors.Reset();
  EXPECT_EQ(tracer->Render(nullptr, 4, 4), nullptr);
  EXPECT_EQ(tracer->Render(scene->Renderer, 0, 4), nullptr);
  EXPECT_EQ(tracer->RenderToImage(scene->Renderer, nullptr), nullptr);
  EXPECT_EQ(errors.Errors(), 3);
}

} // namespace mmvtest
