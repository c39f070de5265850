// vtkIrradianceVolumeFilter (Zhang & Ma §5.1-5.2) against closed forms:
// Beer-Lambert through homogeneous slabs, eq. 12 falloff, eq. 14 cones, plus
// sparsity, diffusion on/off, resolution choice and error handling.
#include "vtkIrradianceGrid.h"
#include "vtkIrradianceVolumeFilter.h"
#include "vtkShadowSweep.h"

#include "mmvTestUtilities.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkExecutive.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMultiMaterialParameters.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <iostream>
#include <limits>

namespace
{

/// Image whose point scalar at world point p is value(p).
vtkSmartPointer<vtkImageData> MakeImage(const std::array<int, 3>& dims, double spacing,
  const std::function<float(const double p[3])>& value)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(dims[0], dims[1], dims[2]);
  image->SetSpacing(spacing, spacing, spacing);
  vtkNew<vtkFloatArray> scalars;
  scalars->SetName("density");
  scalars->SetNumberOfTuples(image->GetNumberOfPoints());
  for (vtkIdType i = 0; i < image->GetNumberOfPoints(); ++i)
  {
    double p[3];
    image->GetPoint(i, p);
    scalars->SetValue(i, value(p));
  }
  image->GetPointData()->SetScalars(scalars);
  return image;
}

/// Constant opacity `alpha` over the data range [0, 2].
vtkSmartPointer<vtkPiecewiseFunction> ConstantOpacity(double alpha)
{
  auto otf = vtkSmartPointer<vtkPiecewiseFunction>::New();
  otf->AddPoint(0.0, alpha);
  otf->AddPoint(2.0, alpha);
  return otf;
}

/// One material everywhere: attenuation c_t and scattering s.
vtkSmartPointer<vtkMaterialTransferFunction> Material(double attenuation, double scattering)
{
  auto m = vtkSmartPointer<vtkMaterialTransferFunction>::New();
  m->AddNode(0.0, 0.2, 0.7, 0.2, 20.0, attenuation, scattering, 0.0);
  return m;
}

vtkSmartPointer<vtkLight> DirectionalLight(const double toLight[3])
{
  auto light = vtkSmartPointer<vtkLight>::New();
  light->SetPositional(false);
  light->SetFocalPoint(0.0, 0.0, 0.0);
  light->SetPosition(toLight[0], toLight[1], toLight[2]);
  return light;
}

vtkSmartPointer<vtkLight> PositionalLight(const double position[3], double coneAngle)
{
  auto light = vtkSmartPointer<vtkLight>::New();
  light->SetPositional(true);
  light->SetPosition(position[0], position[1], position[2]);
  light->SetFocalPoint(position[0], position[1], position[2] - 1.0);
  light->SetConeAngle(coneAngle);
  return light;
}

vtkFloatArray* Irradiance(vtkIrradianceVolumeFilter* filter, int light)
{
  vtkImageData* out = filter->GetOutput();
  return vtkFloatArray::SafeDownCast(
    out->GetPointData()->GetArray(("Irradiance_" + std::to_string(light)).c_str()));
}

/// Distance from p along unit direction d to the box [lo, hi].
double DistanceToBoxExit(
  const double p[3], const double d[3], const double lo[3], const double hi[3])
{
  double t = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a)
  {
    if (d[a] > 1e-12)
    {
      t = std::min(t, (hi[a] - p[a]) / d[a]);
    }
    else if (d[a] < -1e-12)
    {
      t = std::min(t, (lo[a] - p[a]) / d[a]);
    }
  }
  return t;
}

/**
 * Homogeneous slab (value 1, opacity alpha per unit distance u, attenuation
 * c_t) lit by one directional light: the irradiance is exp(-sigma * depth)
 * with sigma = c_t * (-ln(1 - alpha) / u). Returns the largest relative error
 * (absolute with `absolute`) of full shadow rays, or of piecewise ones with
 * chunks of `slices` (> 0).
 */
double SlabError(const double toLight[3], double scale, const double origin[3] = nullptr,
  const double* direction = nullptr, int slices = 0, bool absolute = false)
{
  const double alpha = 0.3, u = 2.0, ct = 1.5, spacing = 0.5;
  auto image = MakeImage({ 20, 16, 12 }, spacing, [](const double*) { return 1.0f; });
  if (origin)
  {
    image->SetOrigin(origin);
  }
  if (direction)
  {
    image->SetDirectionMatrix(direction);
  }
  vtkNew<vtkIrradianceVolumeFilter> filter;
  filter->SetInputData(image);
  filter->SetScalarOpacity(ConstantOpacity(alpha));
  filter->SetScalarOpacityUnitDistance(u);
  filter->SetMaterialTransferFunction(Material(ct, 0.0));
  filter->SetIrradianceScale(scale);
  filter->SetShadowEstimation(slices > 0 ? mmv::PiecewiseShadowRays : mmv::FullShadowRays);
  filter->SetPiecewiseShadowSlices(std::max(slices, 1));
  filter->AddLight(DirectionalLight(toLight));
  filter->Update();

  const double sigma = ct * -std::log(1.0 - alpha) / u;
  vtkImageData* out = filter->GetOutput();
  vtkFloatArray* irradiance = Irradiance(filter, 0);
  EXPECT_NE(irradiance, nullptr);
  if (!irradiance)
  {
    return 1.0;
  }
  EXPECT_EQ(filter->GetNumberOfComputedVoxels(), out->GetNumberOfPoints());
  EXPECT_EQ(filter->GetNumberOfShadowRays(), out->GetNumberOfPoints());
  // Depth in the data's own (index-aligned) frame, where the box is simple.
  const double len =
    std::sqrt(toLight[0] * toLight[0] + toLight[1] * toLight[1] + toLight[2] * toLight[2]);
  double dWorld[3] = { toLight[0] / len, toLight[1] / len, toLight[2] / len };
  double d[3] = { dWorld[0], dWorld[1], dWorld[2] };
  if (direction) // into the frame of the index axes: D^T d
  {
    for (int a = 0; a < 3; ++a)
    {
      d[a] = direction[a] * dWorld[0] + direction[3 + a] * dWorld[1] + direction[6 + a] * dWorld[2];
    }
  }
  const double lo[3] = { 0.0, 0.0, 0.0 };
  const double hi[3] = { 19 * spacing, 15 * spacing, 11 * spacing };
  int dims[3];
  out->GetDimensions(dims);
  double outSpacing[3];
  out->GetSpacing(outSpacing);
  double maxError = 0.0;
  for (vtkIdType v = 0; v < out->GetNumberOfPoints(); ++v)
  {
    const int ijk[3] = { static_cast<int>(v % dims[0]), static_cast<int>((v / dims[0]) % dims[1]),
      static_cast<int>(v / (dims[0] * dims[1])) };
    const double p[3] = { ijk[0] * outSpacing[0], ijk[1] * outSpacing[1], ijk[2] * outSpacing[2] };
    const double expected = std::exp(-sigma * DistanceToBoxExit(p, d, lo, hi));
    maxError = std::max(
      maxError, std::abs(irradiance->GetValue(v) - expected) / (absolute ? 1.0 : expected));
  }
  return maxError;
}

} // namespace

// The pre-integrated segments are exact for a constant value, so the measured
// error is float rounding (2e-7); the bound leaves room for table changes.
constexpr double SlabTolerance = 1.0e-3;

TEST(IrradianceVolumeFilter, HomogeneousSlabAxisAlignedLight)
{
  const double toLight[3] = { 1.0, 0.0, 0.0 };
  EXPECT_LT(SlabError(toLight, 1.0), SlabTolerance);
}

TEST(IrradianceVolumeFilter, HomogeneousSlabObliqueLight)
{
  const double toLight[3] = { -0.6, 0.5, 0.8 };
  EXPECT_LT(SlabError(toLight, 1.0), SlabTolerance);
}

// Piecewise shadow rays (vtkShadowSweep.h) along an index axis end on grid
// points of their sweep plane: no interpolation, so they are as exact as
// full rays.
TEST(IrradianceVolumeFilter, PiecewiseRaysAlongAnAxisAreExact)
{
  for (const auto& toLight : { std::array<double, 3>{ 1.0, 0.0, 0.0 },
         std::array<double, 3>{ 0.0, -1.0, 0.0 }, std::array<double, 3>{ 0.0, 0.0, 1.0 } })
  {
    for (int slices : { 1, 3, 8 })
    {
      EXPECT_LT(SlabError(toLight.data(), 1.0, nullptr, nullptr, slices), SlabTolerance)
        << "K = " << slices;
    }
  }
}

// Oblique light: the transmittance is interpolated bilinearly in each sweep
// plane, and exp(-sigma * depth) is not bilinear where the depth to the box
// has a kink (the box's edges and corners). Measured on this 20 x 16 x 12
// slab: largest absolute error 0.063 (K = 1) and 0.033 (K = 8), full rays
// 2e-7; bounds with ~30 % margin. K at least the sweep axis' length is one
// chunk, i.e. full rays.
TEST(IrradianceVolumeFilter, PiecewiseRaysOnAnObliqueLightStayNearTheClosedForm)
{
  const double toLight[3] = { -0.6, 0.5, 0.8 };
  const double k1 = SlabError(toLight, 1.0, nullptr, nullptr, 1, true);
  const double k8 = SlabError(toLight, 1.0, nullptr, nullptr, 8, true);
  std::cout << "piecewise slab, largest |error|: K = 1: " << k1 << ", K = 8: " << k8 << std::endl;
  EXPECT_LT(k1, 0.08);
  EXPECT_LT(k8, 0.045);
  EXPECT_LT(k8, k1);     // longer pieces interpolate less often
  EXPECT_GT(k1, 1.0e-3); // the interpolation is really there
  EXPECT_LT(SlabError(toLight, 1.0, nullptr, nullptr, 12), SlabTolerance);
}

TEST(IrradianceVolumeFilter, HomogeneousSlabHalfResolution)
{
  const double toLight[3] = { 0.3, -1.0, 0.4 };
  EXPECT_LT(SlabError(toLight, 0.5), SlabTolerance);
}

TEST(IrradianceVolumeFilter, HomogeneousSlabWithOriginAndDirectionMatrix)
{
  // Rotation by 90 degrees about z followed by a flip of the new z axis.
  const double direction[9] = { 0, -1, 0, 1, 0, 0, 0, 0, -1 };
  const double origin[3] = { 3.0, -2.0, 7.0 };
  const double toLight[3] = { 0.2, 0.9, -0.5 };
  EXPECT_LT(SlabError(toLight, 1.0, origin, direction), SlabTolerance);
}

namespace
{

/// A 21 x 21 x 3 slab of opacity 0.5 that does not attenuate light
/// (c_t = 0), so the irradiance is the geometry term alone.
vtkSmartPointer<vtkIrradianceVolumeFilter> TransparentSlabFilter(double radius)
{
  auto filter = vtkSmartPointer<vtkIrradianceVolumeFilter>::New();
  filter->SetInputData(MakeImage({ 21, 21, 3 }, 1.0, [](const double*) { return 1.0f; }));
  filter->SetScalarOpacity(ConstantOpacity(0.5));
  filter->SetMaterialTransferFunction(Material(0.0, 0.0));
  filter->SetIrradianceScale(1.0);
  filter->SetPointLightRadius(radius);
  return filter;
}

double Distance2(const double a[3], const double b[3])
{
  return (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
    (a[2] - b[2]) * (a[2] - b[2]);
}

} // namespace

TEST(IrradianceVolumeFilter, PointLightFalloffOutsideAndInsideTheVolume)
{
  const double eps = 3.0;
  auto filter = TransparentSlabFilter(eps);
  const double outside[3] = { 10.0, 7.0, 12.0 };
  const double inside[3] = { 4.0, 4.0, 1.0 }; // on a voxel centre
  filter->AddLight(PositionalLight(outside, 120.0));
  filter->AddLight(PositionalLight(inside, 120.0));
  filter->Update();
  vtkImageData* out = filter->GetOutput();
  const double* lights[2] = { outside, inside };
  int clamped = 0;
  for (int l = 0; l < 2; ++l)
  {
    vtkFloatArray* irradiance = Irradiance(filter, l);
    ASSERT_NE(irradiance, nullptr);
    for (vtkIdType v = 0; v < out->GetNumberOfPoints(); ++v)
    {
      double p[3];
      out->GetPoint(v, p);
      const double d2 = Distance2(p, lights[l]);
      const double expected = eps * eps / std::max(eps * eps, d2);
      ASSERT_TRUE(std::isfinite(irradiance->GetValue(v)));
      ASSERT_NEAR(irradiance->GetValue(v), expected, 0.01 * expected)
        << "light " << l << " voxel " << v;
      clamped += d2 <= eps * eps ? 1 : 0;
    }
  }
  EXPECT_GT(clamped, 20); // the clamp was exercised
  // The light outside casts one ray per voxel. The one inside is swept in six
  // pyramids around it (index (4, 4, 1)): one ray per voxel, and one more
  // per further pyramid for the voxels on their edges.
  const int dims[3] = { 21, 21, 3 };
  vtkIdType swept = 0;
  for (const mmv::ShadowSweep& sweep :
    mmv::InsideLightSweeps(dims, glm::dvec3(4.0, 4.0, 1.0), mmv::DefaultPiecewiseShadowSlices))
  {
    for (vtkIdType v = 0; v < out->GetNumberOfPoints(); ++v)
    {
      const glm::vec3 index(v % 21, (v / 21) % 21, v / (21 * 21));
      const int slice = static_cast<int>(index[sweep.Axis]);
      swept += slice >= sweep.First && slice < sweep.First + sweep.Slices &&
          mmv::InSweptPyramid(sweep, index)
        ? 1
        : 0;
    }
  }
  EXPECT_GT(swept, out->GetNumberOfPoints());
  EXPECT_EQ(filter->GetNumberOfShadowRays(), out->GetNumberOfPoints() + swept);
}

TEST(IrradianceVolumeFilter, SpotLightIsPointLightTimesCosExponentInsideTheConeAndZeroOutside)
{
  const double position[3] = { 10.0, 10.0, 12.0 };
  const double coneAngle = 30.0;
  const double exponent = 3.0;
  auto filter = TransparentSlabFilter(2.0);
  filter->AddLight(PositionalLight(position, 120.0));
  auto spotLight = PositionalLight(position, coneAngle); // axis -z
  spotLight->SetExponent(exponent); // VTK's angular falloff: cos^3 inside the cone
  filter->AddLight(spotLight);
  filter->Update();
  vtkImageData* out = filter->GetOutput();
  vtkFloatArray* point = Irradiance(filter, 0);
  vtkFloatArray* spot = Irradiance(filter, 1);
  ASSERT_TRUE(point && spot);
  const double cosCone = std::cos(coneAngle * M_PI / 180.0);
  vtkIdType lit = 0;
  vtkIdType dark = 0;
  for (vtkIdType v = 0; v < out->GetNumberOfPoints(); ++v)
  {
    double p[3];
    out->GetPoint(v, p);
    const double c = (position[2] - p[2]) / std::sqrt(Distance2(p, position));
    if (std::abs(c - cosCone) < 1.0e-9)
    {
      continue; // on the edge: covered by TestLightModel
    }
    if (c > cosCone)
    {
      const double expected = point->GetValue(v) * std::pow(c, exponent);
      EXPECT_NEAR(spot->GetValue(v), expected, 1e-6 * expected) << "voxel " << v;
      ++lit;
    }
    else
    {
      EXPECT_EQ(spot->GetValue(v), 0.0f) << "voxel " << v;
      ++dark;
    }
  }
  EXPECT_GT(lit, 50);
  EXPECT_GT(dark, 50);
  // The spot casts rays only inside its cone.
  EXPECT_EQ(filter->GetNumberOfShadowRays(), out->GetNumberOfPoints() + lit);
}

TEST(IrradianceVolumeFilter, EmptyVoxelsAreSkippedAndTheirNeighboursFilled)
{
  // A ball of value 1 in empty space (value 0, opacity 0).
  const double centre = 11.5, radius = 7.0;
  auto image = MakeImage({ 24, 24, 24 }, 1.0,
    [&](const double p[3])
    {
      const double d2 = (p[0] - centre) * (p[0] - centre) + (p[1] - centre) * (p[1] - centre) +
        (p[2] - centre) * (p[2] - centre);
      return d2 < radius * radius ? 1.0f : 0.0f;
    });
  vtkNew<vtkPiecewiseFunction> otf;
  otf->AddPoint(0.0, 0.0);
  otf->AddPoint(0.5, 0.0);
  otf->AddPoint(1.0, 0.4);
  vtkNew<vtkIrradianceVolumeFilter> filter;
  filter->SetInputData(image);
  filter->SetScalarOpacity(otf);
  filter->SetIrradianceScale(1.0);
  const double toLight[3] = { 1.0, 2.0, 3.0 };
  filter->AddLight(DirectionalLight(toLight));
  filter->SetShadowEstimation(mmv::FullShadowRays);
  filter->Update();

  vtkFloatArray* scalars = vtkFloatArray::SafeDownCast(image->GetPointData()->GetScalars());
  vtkIdType ball = 0;
  for (vtkIdType v = 0; v < image->GetNumberOfPoints(); ++v)
  {
    ball += scalars->GetValue(v) > 0.5f ? 1 : 0;
  }
  EXPECT_EQ(filter->GetNumberOfComputedVoxels(), ball);
  EXPECT_LT(ball, image->GetNumberOfPoints() / 4);
  EXPECT_EQ(filter->GetNumberOfShadowRays(), ball);

  // Empty voxels: the mean of their computed 6-neighbours, or 0.
  vtkFloatArray* irradiance = Irradiance(filter, 0);
  ASSERT_NE(irradiance, nullptr);
  // The fill rule's value of empty voxel v, and whether it has neighbours.
  auto expectedFill = [&](vtkIdType v, bool& bordered)
  {
    const int ijk[3] = { static_cast<int>(v % 24), static_cast<int>((v / 24) % 24),
      static_cast<int>(v / 576) };
    const vtkIdType stride[3] = { 1, 24, 576 };
    double sum = 0.0;
    int count = 0;
    for (int a = 0; a < 3; ++a)
      for (int side = -1; side <= 1; side += 2)
      {
        const int n = ijk[a] + side;
        if (n >= 0 && n < 24 && scalars->GetValue(v + side * stride[a]) > 0.5f)
        {
          sum += irradiance->GetValue(v + side * stride[a]);
          ++count;
        }
      }
    bordered = count > 0;
    return count ? sum / count : 0.0;
  };
  vtkIdType filled = 0;
  for (vtkIdType v = 0; v < image->GetNumberOfPoints(); ++v)
  {
    const float value = irradiance->GetValue(v);
    if (scalars->GetValue(v) > 0.5f)
    {
      EXPECT_GT(value, 0.0f);
      continue;
    }
    bool bordered = false;
    const double expected = expectedFill(v, bordered);
    EXPECT_NEAR(value, expected, 1.0e-6 * (1.0 + expected)) << "voxel " << v;
    filled += bordered ? 1 : 0;
  }
  EXPECT_GT(filled, 100);

  // Piecewise rays (z is the sweep axis, light toward +z, chunks of 8):
  // the ball, plus the empty voxels of the slices a later chunk reads (z =
  // 16 and 8), and the same fill rule.
  filter->SetShadowEstimation(mmv::PiecewiseShadowRays);
  filter->SetPiecewiseShadowSlices(8);
  filter->Update();
  vtkIdType emptyOnReadSlices = 0;
  for (vtkIdType v = 0; v < image->GetNumberOfPoints(); ++v)
  {
    const int k = static_cast<int>(v / 576);
    emptyOnReadSlices += (k == 16 || k == 8) && scalars->GetValue(v) < 0.5f ? 1 : 0;
  }
  EXPECT_EQ(filter->GetNumberOfShadowRays(), ball + emptyOnReadSlices);
  irradiance = Irradiance(filter, 0);
  for (vtkIdType v = 0; v < image->GetNumberOfPoints(); ++v)
  {
    if (scalars->GetValue(v) < 0.5f)
    {
      bool bordered = false;
      ASSERT_NEAR(irradiance->GetValue(v), expectedFill(v, bordered), 1.0e-6) << "voxel " << v;
    }
  }

  filter->FillEmptyNeighborsOff();
  filter->Update();
  irradiance = Irradiance(filter, 0);
  for (vtkIdType v = 0; v < image->GetNumberOfPoints(); ++v)
  {
    if (scalars->GetValue(v) < 0.5f)
    {
      ASSERT_EQ(irradiance->GetValue(v), 0.0f) << "voxel " << v;
    }
  }
}

TEST(IrradianceVolumeFilter, SwitchedOffLightsCostNothing)
{
  auto image = MakeImage({ 12, 10, 8 }, 1.0, [](const double*) { return 1.0f; });
  vtkNew<vtkIrradianceVolumeFilter> filter;
  filter->SetInputData(image);
  filter->SetScalarOpacity(ConstantOpacity(0.2));
  filter->SetIrradianceScale(1.0);
  const double toLight[3] = { 0.0, 1.0, 0.0 };
  auto on = DirectionalLight(toLight);
  auto off = DirectionalLight(toLight);
  off->SwitchOff();
  auto dim = DirectionalLight(toLight);
  dim->SetIntensity(0.0);
  filter->AddLight(on);
  filter->AddLight(off);
  filter->AddLight(dim);
  filter->Update();
  EXPECT_EQ(filter->GetNumberOfShadowRays(), image->GetNumberOfPoints());
  for (int l = 1; l < 3; ++l)
  {
    vtkFloatArray* irradiance = Irradiance(filter, l);
    ASSERT_NE(irradiance, nullptr);
    double range[2];
    irradiance->GetRange(range);
    EXPECT_EQ(range[0], 0.0);
    EXPECT_EQ(range[1], 0.0);
  }
  double range[2];
  Irradiance(filter, 0)->GetRange(range);
  EXPECT_GT(range[0], 0.0);
}

TEST(IrradianceVolumeFilter, MultipleScatteringChangesOnlyScatteringVoxels)
{
  // Value 1 (s = 0) for x < 8, value 2 (s = 5) beyond.
  auto image =
    MakeImage({ 16, 12, 10 }, 1.0, [](const double p[3]) { return p[0] < 7.5 ? 1.0f : 2.0f; });
  vtkNew<vtkMaterialTransferFunction> material;
  material->AddNode(1.0, 0.2, 0.7, 0.2, 20.0, 1.0, 0.0, 0.0);
  material->AddNode(2.0, 0.2, 0.7, 0.2, 20.0, 1.0, 5.0, 0.0);
  vtkNew<vtkIrradianceVolumeFilter> filter;
  filter->SetInputData(image);
  filter->SetScalarOpacity(ConstantOpacity(0.3));
  filter->SetMaterialTransferFunction(material);
  filter->SetIrradianceScale(1.0);
  const double toLight[3] = { -1.0, 0.7, 0.4 };
  filter->AddLight(DirectionalLight(toLight));
  filter->MultipleScatteringOff();
  filter->Update();
  EXPECT_EQ(filter->GetDiffusionIterations(), 0);
  vtkNew<vtkFloatArray> single;
  single->DeepCopy(Irradiance(filter, 0));

  filter->MultipleScatteringOn();
  filter->Update();
  EXPECT_GT(filter->GetDiffusionIterations(), 0);
  vtkFloatArray* multiple = Irradiance(filter, 0);
  ASSERT_NE(multiple, nullptr);
  vtkFloatArray* scalars = vtkFloatArray::SafeDownCast(image->GetPointData()->GetScalars());
  double maxChange = 0.0, sumSingle = 0.0, sumMultiple = 0.0;
  for (vtkIdType v = 0; v < image->GetNumberOfPoints(); ++v)
  {
    if (scalars->GetValue(v) < 1.5f)
    {
      ASSERT_EQ(multiple->GetValue(v), single->GetValue(v)) << "voxel " << v;
    }
    else
    {
      maxChange = std::max(
        maxChange, std::abs(static_cast<double>(multiple->GetValue(v)) - single->GetValue(v)));
      sumSingle += single->GetValue(v);
      sumMultiple += multiple->GetValue(v);
    }
  }
  EXPECT_GT(maxChange, 0.01);
  // Diffusion redistributes light inside the scattering region. Here
  // (s = 5, diffusion length 3.2 voxels) the change is computed on 3-voxel
  // blocks: the blocks cut by the material boundary and the data's edge hold
  // one scattering voxel each but count as whole blocks there, and the
  // trilinear prolongation spreads their change, so the total is kept only
  // approximately (measured: +16 %). The exact conservation of the solver
  // itself is TestIrradianceDiffusion's.
  EXPECT_NEAR(sumMultiple, sumSingle, 0.2 * sumSingle);
}

TEST(IrradianceVolumeFilter, ComputeIrradianceDimensions)
{
  int dims[3];
  const int data[3] = { 100, 51, 1 };
  vtkIrradianceVolumeFilter::ComputeIrradianceDimensions(data, 1, 64.0, 0.5, dims);
  EXPECT_EQ(dims[0], 50);
  EXPECT_EQ(dims[1], 26); // round(25.5)
  EXPECT_EQ(dims[2], 1);
  vtkIrradianceVolumeFilter::ComputeIrradianceDimensions(data, 1, 64.0, 1.0, dims);
  EXPECT_EQ(dims[0], 100);
  EXPECT_EQ(dims[1], 51);
  EXPECT_EQ(dims[2], 1);
  vtkIrradianceVolumeFilter::ComputeIrradianceDimensions(data, 1, 64.0, 0.001, dims);
  EXPECT_EQ(dims[0], 2); // never below min(2, data)
  EXPECT_EQ(dims[1], 2);
  EXPECT_EQ(dims[2], 1);

  // Budget mode: fits, never above the data, and not wastefully small.
  const int big[3] = { 256, 200, 300 };
  // The GPU's textures: 16 bits per channel, four lights to a texture, the
  // last with R16, RG16 or RGBA16 (three lights take four channels).
  const double perVoxel[] = { 2, 2, 4, 8, 8, 10, 12, 16, 16 };
  for (int lights = 0; lights <= 8; ++lights)
  {
    EXPECT_EQ(mmv::IrradianceBytesPerVoxel(lights), perVoxel[lights]) << lights << " lights";
  }
  for (const int lights : { 1, 3, 5, 8 })
  {
    for (const double mb : { 1.0, 8.0, 20.0 })
    {
      vtkIrradianceVolumeFilter::ComputeIrradianceDimensions(big, lights, mb, 0.0, dims);
      const double bytes = mmv::IrradianceBytesPerVoxel(lights) * dims[0] * dims[1] * dims[2];
      EXPECT_LE(bytes, mb * 1024 * 1024) << lights << " lights, " << mb << " MB";
      EXPECT_GT(bytes, 0.9 * mb * 1024 * 1024) << lights << " lights, " << mb << " MB";
      for (int a = 0; a < 3; ++a)
      {
        EXPECT_LE(dims[a], big[a]);
      }
    }
  }
  // A generous budget keeps the data resolution; nLights 0 counts as 1.
  vtkIrradianceVolumeFilter::ComputeIrradianceDimensions(big, 0, 1.0e4, 0.0, dims);
  EXPECT_EQ(dims[0], 256);
  EXPECT_EQ(dims[1], 200);
  EXPECT_EQ(dims[2], 300);
  // An impossible budget gives the smallest grid.
  vtkIrradianceVolumeFilter::ComputeIrradianceDimensions(big, 8, 0.0, 0.0, dims);
  EXPECT_EQ(dims[0] * dims[1] * dims[2], 8);
  // 2-D data: the flat axis stays 1 and the others share the budget.
  const int flat[3] = { 1000, 1000, 1 };
  vtkIrradianceVolumeFilter::ComputeIrradianceDimensions(flat, 1, 0.5, 0.0, dims);
  EXPECT_EQ(dims[2], 1);
  EXPECT_LE(2.0 * dims[0] * dims[1], 0.5 * 1024 * 1024);
  EXPECT_GT(2.0 * dims[0] * dims[1], 0.45 * 1024 * 1024);
}

TEST(IrradianceVolumeFilter, OutputGridSpansTheInputBounds)
{
  auto image = MakeImage({ 21, 11, 6 }, 0.5, [](const double*) { return 1.0f; });
  image->SetExtent(5, 25, -3, 7, 2, 7); // does not start at 0
  image->GetPointData()->GetScalars()->SetNumberOfTuples(21 * 11 * 6);
  image->SetOrigin(1.0, 2.0, 3.0);
  vtkNew<vtkIrradianceVolumeFilter> filter;
  filter->SetInputData(image);
  filter->SetScalarOpacity(ConstantOpacity(0.1));
  filter->SetIrradianceScale(0.5);
  const double toLight[3] = { 0.0, 0.0, 1.0 };
  filter->AddLight(DirectionalLight(toLight));
  filter->Update();
  vtkImageData* out = filter->GetOutput();
  int dims[3];
  out->GetDimensions(dims);
  EXPECT_EQ(dims[0], 11);
  EXPECT_EQ(dims[1], 6);
  EXPECT_EQ(dims[2], 3);
  const int* ir = filter->GetIrradianceDimensions();
  EXPECT_EQ(ir[0], 11);
  EXPECT_EQ(ir[1], 6);
  EXPECT_EQ(ir[2], 3);
  double inBounds[6], outBounds[6];
  image->GetBounds(inBounds);
  out->GetBounds(outBounds);
  for (int i = 0; i < 6; ++i)
  {
    EXPECT_NEAR(outBounds[i], inBounds[i], 1e-12) << "bound " << i;
  }
  ASSERT_NE(Irradiance(filter, 0), nullptr);
  EXPECT_EQ(Irradiance(filter, 0)->GetNumberOfTuples(), 11 * 6 * 3);
}

TEST(IrradianceVolumeFilter, ErrorsFailWithoutCrashing)
{
  auto image = MakeImage({ 6, 6, 6 }, 1.0, [](const double*) { return 1.0f; });
  const double toLight[3] = { 0.0, 0.0, 1.0 };
  {
    vtkNew<vtkIrradianceVolumeFilter> filter; // no opacity function
    mmvtest::ErrorCounter events(filter);
    events.Watch(filter->GetExecutive());
    filter->SetInputData(image);
    filter->AddLight(DirectionalLight(toLight));
    EXPECT_EQ(filter->GetExecutive()->Update(), 0);
    EXPECT_GE(events.Errors(), 1);
    EXPECT_EQ(Irradiance(filter, 0), nullptr);
  }
  {
    vtkNew<vtkIrradianceVolumeFilter> filter;
    mmvtest::ErrorCounter events(filter);
    events.Watch(filter->GetExecutive());
    filter->SetInputData(image);
    filter->SetScalarOpacity(ConstantOpacity(0.5));
    filter->SetScalarOpacityUnitDistance(0.0);
    filter->AddLight(DirectionalLight(toLight));
    EXPECT_EQ(filter->GetExecutive()->Update(), 0);
    EXPECT_GE(events.Errors(), 1);
  }
  {
    vtkNew<vtkImageData> bare; // no scalars
    bare->SetDimensions(4, 4, 4);
    vtkNew<vtkIrradianceVolumeFilter> filter;
    mmvtest::ErrorCounter events(filter);
    events.Watch(filter->GetExecutive());
    filter->SetInputData(bare);
    filter->SetScalarOpacity(ConstantOpacity(0.5));
    filter->AddLight(DirectionalLight(toLight));
    EXPECT_EQ(filter->GetExecutive()->Update(), 0);
    EXPECT_GE(events.Errors(), 1);
  }
  {
    vtkNew<vtkIrradianceVolumeFilter> filter; // no lights: a warning only
    mmvtest::ErrorCounter events(filter);
    events.Watch(filter->GetExecutive());
    filter->SetInputData(image);
    filter->SetScalarOpacity(ConstantOpacity(0.5));
    EXPECT_EQ(filter->GetExecutive()->Update(), 1);
    EXPECT_EQ(events.Errors(), 0);
    EXPECT_EQ(events.Warnings(), 1);
    EXPECT_EQ(filter->GetOutput()->GetPointData()->GetNumberOfArrays(), 0);
    EXPECT_EQ(filter->GetNumberOfComputedVoxels(), 216);
  }
}

TEST(IrradianceVolumeFilter, ModifiedInputsReexecute)
{
  auto image = MakeImage({ 6, 6, 6 }, 1.0, [](const double*) { return 1.0f; });
  auto otf = ConstantOpacity(0.5);
  auto material = Material(1.0, 0.0);
  const double toLight[3] = { 0.0, 0.0, 1.0 };
  auto light = DirectionalLight(toLight);
  vtkNew<vtkIrradianceVolumeFilter> filter;
  filter->SetInputData(image);
  filter->SetScalarOpacity(otf);
  filter->SetMaterialTransferFunction(material);
  filter->AddLight(light);
  filter->Update();
  const float before = Irradiance(filter, 0)->GetValue(0);

  vtkMTimeType mtime = filter->GetMTime();
  light->SetPosition(1.0, 0.0, 0.0);
  EXPECT_GT(filter->GetMTime(), mtime);
  mtime = filter->GetMTime();
  otf->AddPoint(1.0, 0.6);
  EXPECT_GT(filter->GetMTime(), mtime);
  mtime = filter->GetMTime();
  material->AddNode(0.0, 0.2, 0.7, 0.2, 20.0, 2.0, 0.0, 0.0);
  EXPECT_GT(filter->GetMTime(), mtime);

  filter->Update();
  EXPECT_NE(Irradiance(filter, 0)->GetValue(0), before);
}

TEST(IrradianceVolumeFilter, AbortStopsWithoutIrradiance)
{
  for (const int estimation : { mmv::FullShadowRays, mmv::PiecewiseShadowRays })
  {
    auto image = MakeImage({ 16, 16, 16 }, 1.0, [](const double*) { return 1.0f; });
    vtkNew<vtkIrradianceVolumeFilter> filter;
    filter->SetShadowEstimation(estimation);
    filter->SetPiecewiseShadowSlices(2);
    filter->SetInputData(image);
    filter->SetScalarOpacity(ConstantOpacity(0.1));
    const double toLight[3] = { 1.0, 1.0, 1.0 };
    filter->AddLight(DirectionalLight(toLight));
    vtkNew<vtkCallbackCommand> abort;
    abort->SetCallback(
      [](vtkObject* caller, unsigned long, void*, void*)
      {
        auto* algorithm = static_cast<vtkAlgorithm*>(caller);
        if (algorithm->GetProgress() > 0.3)
        {
          algorithm->SetAbortExecute(1);
        }
      });
    filter->AddObserver(vtkCommand::ProgressEvent, abort);
    filter->Update();
    // Stopped between chunks: some rays, not all, and no partial result.
    EXPECT_GT(filter->GetNumberOfShadowRays(), 0);
    EXPECT_LT(filter->GetNumberOfShadowRays(), image->GetNumberOfPoints());
    EXPECT_EQ(Irradiance(filter, 0), nullptr);
  }
}
