// Bad input: every case gives a clear error or warning or a correct image;
// never a crash, never a silently wrong image. Runs under Xvfb with Mesa
// llvmpipe; volumes <= 33^3, windows 64x64.
#include "mmvTestScenes.h"
#include "mmvTestUtilities.h"

#include "vtkCellData.h"
#include "vtkCharArray.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkIrradianceVolumeFilter.h"
#include "vtkMaterialLibrary.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMatrix3x3.h"
#include "vtkMultiMaterialVolumeMapper.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

namespace
{
const double Center[3] = { 16.0, 16.0, 16.0 };

float Sphere(int i, int j, int k)
{
  const double r =
    std::sqrt((i - 16.0) * (i - 16.0) + (j - 16.0) * (j - 16.0) + (k - 16.0) * (k - 16.0));
  return static_cast<float>(std::max(0.0, 12.0 - r) * 10.0); // 0 .. 120
}

struct Result
{
  bool Active = false;
  int Warnings = 0;
  int Errors = 0;
  std::string Message;
  std::vector<unsigned char> Pixels;
  double CenterLuminance = 0.0;
};

// Renders `image` with a lit multi-material mapper and a 0..120 colour and
// opacity ramp; `setup` may change the scene before the render.
Result Render(vtkImageData* image,
  const std::function<void(mmvtest::Scene&, vtkMultiMaterialVolumeMapper*)>& setup = nullptr,
  bool light = true)
{
  Result result;
  mmvtest::Scene scene;
  scene.Color->AddRGBPoint(0.0, 1.0, 0.8, 0.6);
  scene.Color->AddRGBPoint(120.0, 1.0, 0.8, 0.6);
  scene.Opacity->AddPoint(0.0, 0.0);
  scene.Opacity->AddPoint(120.0, 0.5);
  vtkNew<vtkMaterialTransferFunction> materials;
  materials->AddNode(60.0, 0.3, 0.6, 0.3, 20.0, 1.0, 0.0, 0.0);
  vtkNew<vtkMultiMaterialVolumeMapper> mapper;
  mmvtest::ErrorCounter counter(mapper);
  mapper->SetInputData(image);
  mapper->SetMaterialTransferFunction(materials);
  scene.Volume->SetMapper(mapper);
  double bounds[6] = { 0, 32, 0, 32, 0, 32 };
  scene.FrameBounds(bounds);
  if (light)
  {
    const double from[3] = { 50.0, 80.0, 100.0 };
    scene.AddDirectionalLight(from, Center);
  }
  if (setup)
  {
    setup(scene, mapper);
  }
  scene.Window->Render();
  result.Active = mapper->GetMultiMaterialActive();
  result.Warnings = counter.Warnings();
  result.Errors = counter.Errors();
  result.Message = counter.LastMessage();
  result.Pixels = scene.Pixels();
  result.CenterLuminance = 0.0;
  for (int c = 0; c < 3; ++c)
  {
    const int half = scene.Window->GetSize()[0] / 2;
    result.CenterLuminance += scene.Pixel(half, half)[c] / 3.0;
  }
  return result;
}

int MaxDifference(const std::vector<unsigned char>& a, const std::vector<unsigned char>& b)
{
  int worst = 255;
  if (a.size() == b.size())
  {
    worst = 0;
    for (size_t i = 0; i < a.size(); ++i)
    {
      worst = std::max(worst, std::abs(int(a[i]) - int(b[i])));
    }
  }
  return worst;
}

vtkSmartPointer<vtkImageData> SphereVolume()
{
  return mmvtest::MakeVolume(33, Sphere);
}

// Render()'s scene in closed form: colour C, opacity ramp 0 -> 0.5 over
// 0..120 per unit length, ka = 0.3, parallel camera on +z framing 48 units.
const double Ka = 0.3;
const double SceneColor[3] = { 1.0, 0.8, 0.6 };

double OpacityOf(double v)
{
  return std::min(std::max(v, 0.0), 120.0) / 240.0;
}

// World x (or y) of the centre of pixel p in a size-pixel window.
double PixelCentre(int p, int size)
{
  return 16.0 + (p + 0.5 - 0.5 * size) * 48.0 / size;
}

// Transmittance T = exp(integral of ln(1 - alpha(v)) dz) along the ray at
// (x, y) through a 33 x 33 x depth volume of voxel values voxel(i, j, k),
// trilinearly interpolated as the GPU texture is.
double Transmittance(
  const std::function<float(int, int, int)>& voxel, int depth, double x, double y)
{
  if (x < 0.0 || y < 0.0 || x > 32.0 || y > 32.0)
  {
    return 1.0;
  }
  const int i = std::min(static_cast<int>(x), 31), j = std::min(static_cast<int>(y), 31);
  const double fx = x - i, fy = y - j;
  auto plane = [&](int k)
  {
    return (1 - fy) * ((1 - fx) * voxel(i, j, k) + fx * voxel(i + 1, j, k)) +
      fy * ((1 - fx) * voxel(i, j + 1, k) + fx * voxel(i + 1, j + 1, k));
  };
  const int steps = 64; // per unit: the integrand is smooth between planes
  double opticalDepth = 0.0;
  for (int k = 0; k + 1 < depth; ++k)
  {
    const double a = plane(k), b = plane(k + 1);
    for (int s = 0; s < steps; ++s)
    {
      const double t = (s + 0.5) / steps;
      opticalDepth += std::log(1.0 - OpacityOf((1 - t) * a + t * b)) / steps;
    }
  }
  return std::exp(opticalDepth);
}

// Ambient-only closed form. Without lights the shader emits ka * I_c per
// segment (mmvShadeSegment), and with a constant colour the pre-integrated
// I_c = C * I_alpha, so front-to-back compositing telescopes to
//   pixel = ka * C * (1 - T).
// Returns the largest |rendered - expected| over all pixels and channels.
double AmbientClosedFormError(
  const Result& r, const std::function<float(int, int, int)>& voxel, int depth, int size)
{
  double worst = 0.0;
  for (int py = 0; py < size; ++py)
  {
    for (int px = 0; px < size; ++px)
    {
      const double opacity =
        1.0 - Transmittance(voxel, depth, PixelCentre(px, size), PixelCentre(py, size));
      for (int c = 0; c < 3; ++c)
      {
        const double rendered = r.Pixels[3 * (py * size + px) + c] / 255.0;
        worst = std::max(worst, std::abs(rendered - Ka * SceneColor[c] * opacity));
      }
    }
  }
  return worst;
}
}

//------------------------------------------------------------------------------
TEST(BadInput, ReferenceSphereRendersCleanly)
{
  const Result r = Render(SphereVolume());
  EXPECT_TRUE(r.Active);
  EXPECT_EQ(r.Warnings + r.Errors, 0) << r.Message;
  EXPECT_GT(r.CenterLuminance, 0.05);
}

TEST(BadInput, NonFiniteVoxels)
{
  // A few NaN and Inf voxels outside the sphere: the finite range is used,
  // so the sphere itself must render as without them.
  const Result reference = Render(SphereVolume());
  auto image = SphereVolume();
  auto* values = vtkFloatArray::SafeDownCast(image->GetPointData()->GetScalars());
  values->SetValue(0, std::numeric_limits<float>::quiet_NaN());
  values->SetValue(1, std::numeric_limits<float>::infinity());
  values->SetValue(2, -std::numeric_limits<float>::infinity());
  values->Modified();
  const Result r = Render(image);
  EXPECT_TRUE(r.Active);
  EXPECT_NEAR(r.CenterLuminance, reference.CenterLuminance, 2.0 / 255) << r.Message;
  std::printf(
    "non-finite voxels: active %d, warnings %d, errors %d, max pixel difference %d (%s)\n",
    r.Active, r.Warnings, r.Errors, MaxDifference(r.Pixels, reference.Pixels), r.Message.c_str());
  EXPECT_EQ(r.Warnings, 1) << "NaN/Inf must be reported";

  // The filter: finite irradiance in [0, 1] at full and coarse resolution.
  for (double scale : { 1.0, 0.5 })
  {
    vtkNew<vtkIrradianceVolumeFilter> filter;
    mmvtest::ErrorCounter counter(filter);
    vtkNew<vtkPiecewiseFunction> opacity;
    opacity->AddPoint(0.0, 0.0);
    opacity->AddPoint(120.0, 0.5);
    vtkNew<vtkLight> light;
    light->SetPosition(50.0, 80.0, 100.0);
    light->SetFocalPoint(16.0, 16.0, 16.0);
    filter->SetInputData(image);
    filter->SetScalarOpacity(opacity);
    filter->SetIrradianceScale(scale);
    filter->AddLight(light);
    filter->Update();
    auto* irradiance =
      vtkFloatArray::SafeDownCast(filter->GetOutput()->GetPointData()->GetArray("Irradiance_0"));
    ASSERT_NE(irradiance, nullptr);
    for (vtkIdType p = 0; p < irradiance->GetNumberOfTuples(); ++p)
    {
      ASSERT_TRUE(std::isfinite(irradiance->GetValue(p))) << "scale " << scale << " voxel " << p;
      ASSERT_GE(irradiance->GetValue(p), 0.0f);
      ASSERT_LE(irradiance->GetValue(p), 1.0f + 1e-5f);
    }
    EXPECT_EQ(counter.Warnings(), 1) << "NaN/Inf must be reported";
    std::printf("non-finite voxels, filter at scale %.1f: warnings %d errors %d (%s)\n", scale,
      counter.Warnings(), counter.Errors(), counter.LastMessage().c_str());
  }
}

TEST(BadInput, ConstantVolume)
{
  // Every voxel 60: a zero scalar range, alpha 0.25 per unit, no gradient.
  const auto constant = [](int, int, int) { return 60.0f; };
  auto image = mmvtest::MakeVolume(33, constant);
  const Result ambient = Render(image, nullptr, /*light*/ false);
  EXPECT_TRUE(ambient.Active);
  EXPECT_EQ(ambient.Errors, 0) << ambient.Message;
  // Measured: 0.49/255, the 8-bit rounding; 1.5/255 fails on a 3% error in ka.
  const double ambientError = AmbientClosedFormError(ambient, constant, 33, 64);
  std::printf(
    "constant volume, unlit: max |pixel - ka C (1 - T)| = %.2f/255\n", 255 * ambientError);
  EXPECT_LE(ambientError, 1.5 / 255);

  // Lit: without a gradient only the light's ambient term is left, scaled by
  // the irradiance E(d) = exp(-sigma d / l_z) at depth d below the front face
  // z = 32, through which the light enters near the centre (sigma = -ln 0.75
  // per unit, attenuation 1; the CPU filter gives exactly this). Each segment
  // of length h is shaded at its front (pre-integrated I_beta = 0 where the
  // opacity starts at once, eq. 7), so with a = 1 - 0.75^h and
  // q = exp(-sigma h / l_z) the 32 / h segments composite to
  //   pixel = ka C a (1 - ((1 - a) q)^(32 / h)) / (1 - (1 - a) q).
  // (The continuous integral, ka C sigma / (sigma + sigma / l_z), is its limit
  // for h -> 0: measured 6/255 below the render at h = 1, 1/255 at h = 0.1.)
  const double h = 1.0;
  const Result lit = Render(image,
    [h](mmvtest::Scene&, vtkMultiMaterialVolumeMapper* m)
    {
      m->AutoAdjustSampleDistancesOff();
      m->SetSampleDistance(h);
    });
  EXPECT_TRUE(lit.Active);
  EXPECT_EQ(lit.Warnings + lit.Errors, 0) << lit.Message;
  const double toLight[3] = { 50.0 - Center[0], 80.0 - Center[1], 100.0 - Center[2] };
  const double lz = toLight[2] /
    std::sqrt(toLight[0] * toLight[0] + toLight[1] * toLight[1] + toLight[2] * toLight[2]);
  const double a = 1.0 - std::pow(0.75, h);
  const double kept = (1.0 - a) * std::exp(std::log(0.75) * h / lz);
  const double fraction = a * (1.0 - std::pow(kept, 32.0 / h)) / (1.0 - kept);
  double worst = 0.0;
  for (int y = 28; y < 36; ++y) // the light's path leaves through z = 32 here
  {
    for (int x = 28; x < 36; ++x)
    {
      for (int c = 0; c < 3; ++c)
      {
        const double expected = Ka * SceneColor[c] * fraction;
        worst = std::max(worst, std::abs(lit.Pixels[3 * (y * 64 + x) + c] / 255.0 - expected));
      }
    }
  }
  // Measured: 0.44/255, the 8-bit rounding.
  std::printf("constant volume, lit: pixel = %.4f C, max |difference| %.2f/255\n", Ka * fraction,
    255 * worst);
  EXPECT_LE(worst, 1.5 / 255);
}

TEST(BadInput, EmptyVolume)
{
  vtkNew<vtkImageData> image;
  vtkNew<vtkFloatArray> values;
  image->GetPointData()->SetScalars(values);
  const Result r = Render(image);
  EXPECT_FALSE(r.Active);
  EXPECT_LT(r.CenterLuminance, 1.0 / 255) << "nothing to draw";
  std::printf(
    "empty volume: warnings %d, errors %d (%s)\n", r.Warnings, r.Errors, r.Message.c_str());

  // The filter reports empty input and produces an empty output.
  vtkNew<vtkIrradianceVolumeFilter> filter;
  mmvtest::ErrorCounter counter(filter);
  counter.Watch(filter->GetExecutive());
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0.0, 0.5);
  filter->SetScalarOpacity(opacity);
  filter->SetInputData(image);
  filter->Update();
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), 0);
  std::printf("empty volume filter: warnings %d, errors %d (%s)\n", counter.Warnings(),
    counter.Errors(), counter.LastMessage().c_str());
}

void SliceCase(int depth)
{
  {
    auto image = vtkSmartPointer<vtkImageData>::New();
    image->SetDimensions(33, 33, depth);
    vtkNew<vtkFloatArray> values;
    values->SetNumberOfTuples(33 * 33 * depth);
    for (vtkIdType p = 0; p < values->GetNumberOfTuples(); ++p)
    {
      values->SetValue(p, Sphere(p % 33, (p / 33) % 33, 16));
    }
    image->GetPointData()->SetScalars(values);
    // A 16x16 window: face-on, the zero-thickness slice makes llvmpipe spend
    // ~0.25 ms per pixel in the ray cast (16 s at 64x64).
    const auto small = [](mmvtest::Scene& s, vtkMultiMaterialVolumeMapper*)
    { s.Window->SetSize(16, 16); };
    const Result r = Render(image, small);
    std::printf("depth %d: active %d, warnings %d, errors %d, centre %.3f (%s)\n", depth, r.Active,
      r.Warnings, r.Errors, r.CenterLuminance, r.Message.c_str());
    if (depth == 1)
    {
      // Zero thickness seen face-on: black, so it must say so.
      EXPECT_EQ(r.Warnings, 1) << "a single slice must be reported";
      EXPECT_NE(r.Message.find("single slice"), std::string::npos) << r.Message;
      return;
    }
    // Two or more slices are a volume: multi-material, silently.
    EXPECT_TRUE(r.Active) << "depth " << depth;
    EXPECT_EQ(r.Warnings + r.Errors, 0) << r.Message;
    EXPECT_GT(r.CenterLuminance, 0.05) << "depth " << depth;
    // Unlit, the slab has the ambient closed form (depth - 1 units thick).
    const Result ambient = Render(image, small, /*light*/ false);
    EXPECT_TRUE(ambient.Active);
    const double error = AmbientClosedFormError(
      ambient, [](int i, int j, int) { return Sphere(i, j, 16); }, depth, 16);
    // Measured: 0.49/255 at depth 2, the 8-bit rounding.
    std::printf("depth %d, unlit: max |pixel - ka C (1 - T)| = %.2f/255\n", depth, 255 * error);
    EXPECT_LE(error, 1.5 / 255) << "depth " << depth;
  }
}

TEST(BadInput, SingleSlice)
{
  SliceCase(1);
}

TEST(BadInput, TwoSlices)
{
  SliceCase(2);
}

TEST(BadInput, NonUniformSpacingAndOrientation)
{
  auto image = SphereVolume();
  image->SetSpacing(1.0, 0.5, 2.0);
  image->SetOrigin(0.0, 8.0, -16.0); // same bounds as the unit cube 0..32
  Result r = Render(image);
  EXPECT_TRUE(r.Active);
  EXPECT_EQ(r.Errors, 0) << r.Message;
  EXPECT_GT(r.CenterLuminance, 0.05);

  // A direction matrix rotating the image 90 degrees about z around its
  // centre: the sphere is symmetric, so the image must match the axis-aligned one.
  const Result reference = Render(SphereVolume());
  auto rotated = SphereVolume();
  rotated->SetDirectionMatrix(0, -1, 0, 1, 0, 0, 0, 0, 1);
  rotated->SetOrigin(32.0, 0.0, 0.0);
  r = Render(rotated);
  const int difference = MaxDifference(r.Pixels, reference.Pixels);
  std::printf("oriented: active %d, warnings %d, max pixel difference %d (%s)\n", r.Active,
    r.Warnings, difference, r.Message.c_str());
  // Oriented images are supported: multi-material, and the grid is exactly
  // symmetric, so measured 0; 1 allows for rounding.
  EXPECT_TRUE(r.Active);
  EXPECT_EQ(r.Warnings + r.Errors, 0) << r.Message;
  EXPECT_LE(difference, 1);
}

// Cell data are lit on the grid of their cell centres (TestDataInputs compares
// them with their point-data equivalent).
TEST(BadInput, CellDataAreShadedWithMaterials)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(17, 17, 17);
  image->SetSpacing(2.0, 2.0, 2.0); // the scene frames 0..32
  vtkNew<vtkFloatArray> values;
  values->SetNumberOfTuples(16 * 16 * 16);
  for (vtkIdType c = 0; c < values->GetNumberOfTuples(); ++c)
  {
    values->SetValue(c, Sphere(2 * (c % 16), 2 * ((c / 16) % 16), 2 * (c / 256)));
  }
  image->GetCellData()->SetScalars(values);
  const Result r = Render(image,
    [](mmvtest::Scene&, vtkMultiMaterialVolumeMapper* m) { m->SetScalarModeToUseCellData(); });
  EXPECT_TRUE(r.Active) << r.Message;
  EXPECT_EQ(r.Warnings + r.Errors, 0) << r.Message;
  EXPECT_GT(r.CenterLuminance, 0.05);
}

TEST(BadInput, EveryScalarType)
{
  const Result reference = Render(SphereVolume());
  for (int type : { VTK_CHAR, VTK_SIGNED_CHAR, VTK_UNSIGNED_CHAR, VTK_SHORT, VTK_UNSIGNED_SHORT,
         VTK_INT, VTK_UNSIGNED_INT, VTK_LONG, VTK_UNSIGNED_LONG, VTK_LONG_LONG,
         VTK_UNSIGNED_LONG_LONG, VTK_FLOAT, VTK_DOUBLE })
  {
    auto image = SphereVolume();
    vtkSmartPointer<vtkDataArray> typed =
      vtkSmartPointer<vtkDataArray>::Take(vtkDataArray::CreateDataArray(type));
    typed->DeepCopy(image->GetPointData()->GetScalars());
    image->GetPointData()->SetScalars(typed);
    const Result r = Render(image);
    const int diff = MaxDifference(r.Pixels, reference.Pixels);
    std::printf("%-20s active %d warnings %d errors %d max pixel difference %d (%s)\n",
      typed->GetClassName(), r.Active, r.Warnings, r.Errors, diff, r.Message.c_str());
    if (type == VTK_CHAR)
    {
      // VTK's volume texture has no format for plain char (its signedness is
      // the platform's): VTK itself reports it, nothing is drawn in its place.
      EXPECT_FALSE(r.Active);
      EXPECT_EQ(r.Errors, 1);
      continue;
    }
    EXPECT_TRUE(r.Active) << typed->GetClassName();
    EXPECT_EQ(r.Warnings + r.Errors, 0) << typed->GetClassName() << ": " << r.Message;
    // Integer types round the 0..120 ramp (measured: at most 5 levels, for
    // unsigned char); floating-point types are uploaded as float (measured 0).
    EXPECT_LE(diff, type == VTK_FLOAT || type == VTK_DOUBLE ? 1 : 6) << typed->GetClassName();
  }
}

TEST(BadInput, DependentOrTooManyComponentsFallBack)
{
  // Dependent components (direct colour), and more than 4 independent ones
  // (more fields than VTK's volume property maps): a clear message each.
  for (int components : { 4, 5 })
  {
    const bool independent = components == 5;
    auto image = vtkSmartPointer<vtkImageData>::New();
    image->SetDimensions(17, 17, 17);
    vtkNew<vtkFloatArray> values;
    values->SetNumberOfComponents(components);
    values->SetNumberOfTuples(17 * 17 * 17);
    for (vtkIdType p = 0; p < values->GetNumberOfTuples(); ++p)
    {
      const float v = Sphere(2 * (p % 17), 2 * ((p / 17) % 17), 2 * (p / 289));
      for (int c = 0; c < components; ++c)
      {
        values->SetTypedComponent(p, c, v);
      }
    }
    image->GetPointData()->SetScalars(values);
    const Result r = Render(image,
      [independent](mmvtest::Scene& s, vtkMultiMaterialVolumeMapper*)
      { s.Property->SetIndependentComponents(independent); });
    // VTK's ray caster refuses 5 components itself, with an error.
    EXPECT_FALSE(r.Active);
    EXPECT_EQ(independent ? r.Errors : r.Warnings, 1) << r.Message;
    EXPECT_NE(r.Message.find(independent ? "Only 1 - 4 component" : "independent components"),
      std::string::npos)
      << r.Message;
  }
}

TEST(BadInput, NoLightsRendersAmbientWithAWarning)
{
  const Result r = Render(SphereVolume(), nullptr, /*light*/ false);
  EXPECT_TRUE(r.Active);
  EXPECT_EQ(r.Warnings, 1);
  EXPECT_NE(r.Message.find("no active light"), std::string::npos) << r.Message;
  // Ambient shading keeps the volume visible: the closed form at every pixel,
  // from the saturated centre (T ~ 6e-4) to the faint rim. Measured:
  // 0.50/255, the 8-bit rounding.
  const double error = AmbientClosedFormError(r, Sphere, 33, 64);
  std::printf("no lights: max |pixel - ka C (1 - T)| = %.2f/255\n", 255 * error);
  EXPECT_LE(error, 1.5 / 255);
}

TEST(BadInput, PartitionedVolume)
{
  // SetPartitions: the bricks are shaded with materials, from the very first
  // frame, as the whole volume is (TestVolumeBricking measures how closely).
  const Result whole = Render(SphereVolume());
  const Result r = Render(SphereVolume(),
    [](mmvtest::Scene&, vtkMultiMaterialVolumeMapper* m) { m->SetPartitions(2, 1, 1); });
  EXPECT_TRUE(r.Active);
  EXPECT_EQ(r.Warnings, 0) << r.Message;
  EXPECT_LE(MaxDifference(r.Pixels, whole.Pixels), 8);
}

//------------------------------------------------------------------------------
TEST(BadInput, MalformedMaterialNodes)
{
  vtkNew<vtkMaterialTransferFunction> materials;
  mmvtest::ErrorCounter counter(materials);
  const double good[8] = { 0.0, 0.2, 0.7, 0.3, 20.0, 1.0, 0.0, 0.0 };
  ASSERT_TRUE(materials->SetNodes(8, good));
  const vtkMTimeType time = materials->GetMTime();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  struct Case
  {
    const char* What;
    int Count;
    std::vector<double> Nodes;
  };
  const std::vector<Case> cases = {
    { "count not a multiple of 8", 7, { 0, 1, 1, 1, 1, 1, 1 } },
    { "count 9", 9, { 0, 1, 1, 1, 1, 1, 1, 0, 5 } },
    { "negative count", -8, { 0, 1, 1, 1, 1, 1, 1, 0 } },
    { "NaN value", 8, { nan, 1, 1, 1, 1, 1, 1, 0 } },
    { "NaN parameter", 8, { 0, 1, nan, 1, 1, 1, 1, 0 } },
    { "Inf parameter", 8, { 0, 1, 1, 1, inf, 1, 1, 0 } },
    { "negative parameter", 8, { 0, -0.5, 1, 1, 1, 1, 1, 0 } },
    { "huge parameter", 8, { 0, 1, 1, 1, 1e300, 1, 1, 0 } },
    { "null nodes", 8, {} },
  };
  for (const Case& c : cases)
  {
    counter.Reset();
    EXPECT_FALSE(materials->SetNodes(c.Count, c.Nodes.empty() ? nullptr : c.Nodes.data()))
      << c.What;
    EXPECT_EQ(counter.Errors(), 1) << c.What;
    EXPECT_EQ(materials->GetSize(), 1) << c.What;
    EXPECT_EQ(materials->GetMTime(), time) << c.What << " must leave the function unchanged";
  }
  double node[vtkMaterialTransferFunction::NodeStride];
  ASSERT_TRUE(materials->GetNode(0, node));
  for (int i = 0; i < 8; ++i)
  {
    EXPECT_EQ(node[i], good[i]);
  }
}

TEST(BadInput, UnknownPresetAndMalformedJSON)
{
  vtkNew<vtkMaterialTransferFunction> materials;
  vtkNew<vtkMaterialLibrary> library;
  mmvtest::ErrorCounter counter(materials);
  counter.Watch(library);
  materials->AddNode(1.0, 0.2, 0.7, 0.3, 20.0, 1.0, 0.0, 0.0);
  const int presets = library->GetNumberOfPresets();

  EXPECT_FALSE(materials->ApplyPreset("no-such-material", 0.0, 1.0));
  EXPECT_FALSE(materials->ApplyPreset(nullptr, 0.0, 1.0));
  EXPECT_EQ(counter.Errors(), 2);
  EXPECT_EQ(materials->GetSize(), 1);

  for (const char* json : { "", "{", "[", "null", "42", "{\"nodes\": 3}", "{\"nodes\": [{}]}",
         "{\"nodes\": [{\"value\": \"a\"}]}", "{\"nodes\": [{\"value\": 0, \"shininess\": -1}]}",
         "{\"nodes\": [{\"value\": 0, \"bogus\": 1}]}", "{\"nodes\": [{\"value\": 1e999}]}",
         "{\"nodes\": [{\"value\": 0, \"ambient\": NaN}]}" })
  {
    counter.Reset();
    EXPECT_FALSE(materials->FromJSON(json)) << json;
    EXPECT_EQ(counter.Errors(), 1) << json;
    EXPECT_EQ(materials->GetSize(), 1) << json;
  }
  for (const char* json :
    { "", "{", "[{]", "{}", "[{\"name\": 3}]", "{\"name\": \"x\", \"ambient\": -1}",
      "{\"name\": \"x\", \"color\": [1, 2]}", "{\"name\": \"x\", \"unknown\": 0}",
      "[{\"name\": \"ok\"}, {\"name\": \"bad\", \"diffuse\": \"x\"}]" })
  {
    counter.Reset();
    EXPECT_FALSE(library->AddPresetsFromJSON(json)) << json;
    EXPECT_EQ(counter.Errors(), 1) << json;
    EXPECT_EQ(library->GetNumberOfPresets(), presets)
      << json << " must leave the library unchanged";
  }
}
