// Failure cases of the multi-material method (docs/stability.md): each test
// measures one known weak spot and asserts a bound on it. Volumes <= 33^3,
// windows 64x64; runs under Xvfb with Mesa llvmpipe.
#include "mmvTestScenes.h"
#include "mmvTestUtilities.h"

#include "vtkIrradianceDiffusion.h"
#include "vtkIrradianceVolumeFilter.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMultiMaterialShading.h"
#include "vtkMultiMaterialVolumeMapper.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <set>

namespace
{
constexpr int Dims = 33;
const double Center[3] = { 16.0, 16.0, 16.0 };

// Mean and variance of the luminance (0..255) of the w x w pixels around the
// window centre.
void CenterStatistics(mmvtest::Scene& scene, int w, double& mean, double& variance)
{
  const auto pixels = scene.Pixels();
  const int size = scene.Window->GetSize()[0];
  double sum = 0.0, sum2 = 0.0;
  int n = 0;
  for (int y = size / 2 - w / 2; y < size / 2 + w / 2; ++y)
  {
    for (int x = size / 2 - w / 2; x < size / 2 + w / 2; ++x)
    {
      const unsigned char* p = &pixels[3 * (y * size + x)];
      const double l = (p[0] + p[1] + p[2]) / 3.0;
      sum += l;
      sum2 += l * l;
      ++n;
    }
  }
  mean = sum / n;
  variance = std::max(0.0, sum2 / n - mean * mean);
}

vtkSmartPointer<vtkFloatArray> IrradianceArray(vtkIrradianceVolumeFilter* filter, int light)
{
  return vtkFloatArray::SafeDownCast(
    filter->GetOutput()->GetPointData()->GetArray(("Irradiance_" + std::to_string(light)).c_str()));
}
}

//------------------------------------------------------------------------------
// 1. Homogeneous regions: gradient noise must not turn into speckles.
TEST(FailureCases, HomogeneousRegionFadesToAmbient)
{
  // A volume of value 1 plus tiny noise; one voxel of 0 in a far corner sets
  // the scalar range to [0, 1] so the noise is ~amplitude in normalised units.
  auto render = [](double noise, bool shaded, double& mean, double& variance)
  {
    std::mt19937 random(7);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    auto image = mmvtest::MakeVolume(Dims,
      [&](int i, int j, int k)
      { return (i + j + k == 0) ? 0.0f : 1.0f + static_cast<float>(noise) * u(random); });
    mmvtest::Scene scene;
    scene.Color->AddRGBPoint(0.0, 1.0, 1.0, 1.0);
    scene.Opacity->AddPoint(0.0, 0.0);
    scene.Opacity->AddPoint(0.5, 0.05);
    scene.Opacity->AddPoint(2.0, 0.05);
    vtkNew<vtkMaterialTransferFunction> materials;
    if (shaded)
    {
      materials->AddNode(1.0, 0.2, 0.8, 1.0, 10.0, 0.2, 0.0, 0.0);
    }
    else
    {
      materials->AddNode(1.0, 1.0, 0.0, 0.0, 1.0, 0.2, 0.0, 0.0); // purely ambient
    }
    vtkNew<vtkMultiMaterialVolumeMapper> mapper;
    mapper->SetInputData(image);
    mapper->SetMaterialTransferFunction(materials);
    mapper->AutoAdjustSampleDistancesOff();
    mapper->SetSampleDistance(0.5);
    scene.Volume->SetMapper(mapper);
    scene.FrameBounds(image->GetBounds());
    const double from[3] = { 60.0, 40.0, 100.0 };
    scene.AddDirectionalLight(from, Center);
    scene.Window->Render();
    EXPECT_TRUE(mapper->GetMultiMaterialActive());
    CenterStatistics(scene, 32, mean, variance);
  };
  double ambientMean, ambientVar, fadedMean, fadedVar, noisyMean, noisyVar;
  render(1.0e-4, false, ambientMean, ambientVar);
  render(1.0e-4, true, fadedMean, fadedVar);
  // Gradient noise well above mmv::SurfaceEqualShareGradientPerVoxel: the
  // surface share nears 1 and normals turn per sample, which the hybrid
  // model's share keeps out of homogeneous regions.
  render(3.0e-2, true, noisyMean, noisyVar);
  std::printf("homogeneous: ambient mean %.2f var %.3f; faded mean %.2f var %.3f; "
              "unfaded noise mean %.2f var %.3f (luminance^2, 0..255)\n",
    ambientMean, ambientVar, fadedMean, fadedVar, noisyMean, noisyVar);
  EXPECT_GT(fadedMean, 5.0) << "the homogeneous volume must stay visible (no NaN/black)";
  EXPECT_LT(fadedVar, 1.0) << "speckles from gradient noise in a homogeneous region";
  EXPECT_LT(fadedVar, ambientVar + 1.0);
  EXPECT_GT(noisyVar, 4.0 * (fadedVar + 0.1))
    << "the measurement must see speckles when they exist";

  // CPU mirror of the shading: a zero normal with directional = 0 is finite
  // and equals the ambient term.
  const glm::dvec4 material(0.2, 0.8, 1.0, 10.0);
  const glm::dvec4 segment(0.5, 0.5, 0.5, 0.5);
  const glm::dvec3 c = mmv::mmvBlinnPhong(
    material, segment, glm::dvec3(0.0), glm::dvec3(0, 0, 1), glm::dvec3(0, 1, 0), 0.0);
  for (int i = 0; i < 3; ++i)
  {
    EXPECT_TRUE(std::isfinite(c[i]));
    EXPECT_DOUBLE_EQ(c[i], 0.2 * 0.5);
  }
}

//------------------------------------------------------------------------------
// 2. A narrow opacity spike sampled with large steps.
TEST(FailureCases, PreIntegrationBoundsSpikeError)
{
  // Values ramp 0 -> 1 along z (the view direction); opacity is a spike of
  // width 0.02 (0.64 voxels) at 0.5. Ambient emission only (no light).
  auto image = mmvtest::MakeVolume(Dims, [](int, int, int k) { return k / 32.0f; });
  // One window for every render (fewer X connections, less shader building).
  mmvtest::Scene scene;
  scene.Color->AddRGBPoint(0.0, 1.0, 1.0, 1.0);
  scene.Opacity->AddPoint(0.0, 0.0);
  scene.Opacity->AddPoint(0.49, 0.0);
  scene.Opacity->AddPoint(0.5, 0.9);
  scene.Opacity->AddPoint(0.51, 0.0);
  scene.Opacity->AddPoint(1.0, 0.0);
  vtkNew<vtkMaterialTransferFunction> materials;
  materials->AddNode(0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0);
  vtkNew<vtkMultiMaterialVolumeMapper> mapper;
  mmvtest::ErrorCounter quiet(mapper); // "no active light" is expected here
  mapper->SetInputData(image);
  mapper->SetMaterialTransferFunction(materials);
  mapper->AutoAdjustSampleDistancesOff();
  mapper->SetPreIntegrationTableSize(1024);
  scene.Volume->SetMapper(mapper);
  scene.FrameBounds(image->GetBounds());
  auto render = [&](double step, bool preintegration)
  {
    mapper->SetSampleDistance(step);
    mapper->SetPreIntegration(preintegration);
    scene.Window->Render();
    EXPECT_TRUE(mapper->GetMultiMaterialActive());
    double mean, variance;
    CenterStatistics(scene, 16, mean, variance);
    return mean / 255.0;
  };
  const double reference = render(0.1, true);
  double worstOn = 0.0, worstOff = 0.0;
  for (double step : { 2.0, 3.0, 4.0 })
  {
    const double on = render(step, true);
    const double off = render(step, false);
    std::printf("spike: step %.1f pre-integrated %.3f post-classified %.3f fine %.3f\n", step, on,
      off, reference);
    worstOn = std::max(worstOn, std::abs(on - reference));
    worstOff = std::max(worstOff, std::abs(off - reference));
  }
  std::printf("spike: worst error pre-integrated %.4f, post-classified %.4f\n", worstOn, worstOff);
  EXPECT_GT(reference, 0.2) << "the spike must be visible in the fine render";
  EXPECT_LT(worstOn, 0.05);
  EXPECT_GT(worstOff, 4.0 * worstOn);
}

//------------------------------------------------------------------------------
// 3. Diffusion with s from 0 to 1000: bounded, maximum principle, monotone.
TEST(FailureCases, DiffusionStaysBoundedAndMonotone)
{
  const int dims[3] = { 32, 1, 1 };
  const double spacing[3] = { 1.0, 1.0, 1.0 };
  std::vector<float> input(32);
  for (int i = 0; i < 32; ++i)
  {
    input[i] = i < 12 ? 0.0f : (i < 20 ? (i - 12) / 8.0f : 1.0f); // monotone ramp
  }
  for (double s : { 0.0, 1.0e-3, 0.1, 1.0, 10.0, 100.0, 1000.0 })
  {
    std::vector<float> strength(32, static_cast<float>(s));
    std::vector<float> out = input;
    const mmv::DiffusionReport report =
      mmv::DiffuseIrradiance(dims, spacing, strength.data(), out.data());
    double sum = 0.0, sumIn = 0.0;
    for (int i = 0; i < 32; ++i)
    {
      ASSERT_TRUE(std::isfinite(out[i])) << "s " << s;
      EXPECT_GE(out[i], -1.0e-5) << "new minimum, s " << s;
      EXPECT_LE(out[i], 1.0 + 1.0e-5) << "new maximum, s " << s;
      if (i > 0)
      {
        EXPECT_GE(out[i] - out[i - 1], -1.0e-5) << "oscillation at " << i << ", s " << s;
      }
      sum += out[i];
      sumIn += input[i];
    }
    EXPECT_NEAR(sum, sumIn, 1.0e-3 * sumIn) << "energy, s " << s;
    EXPECT_EQ(report.Skipped, s == 0.0) << "s " << s;
  }

  // Through the filter: a slab lit along +x, s = 0 .. 1000; the irradiance
  // profile decays monotonically along x and stays in [0, 1].
  auto image = mmvtest::MakeVolume(17, [](int, int, int) { return 1.0f; });
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0.0, 0.1);
  opacity->AddPoint(2.0, 0.1);
  vtkNew<vtkLight> light;
  light->PositionalOff();
  light->SetPosition(-100.0, 8.0, 8.0);
  light->SetFocalPoint(8.0, 8.0, 8.0);
  for (double s : { 0.0, 1.0, 100.0, 1000.0 })
  {
    vtkNew<vtkMaterialTransferFunction> materials;
    materials->AddNode(1.0, 0.2, 0.8, 0.0, 1.0, 1.0, s, 0.0);
    vtkNew<vtkIrradianceVolumeFilter> filter;
    filter->SetInputData(image);
    filter->SetScalarOpacity(opacity);
    filter->SetMaterialTransferFunction(materials);
    filter->SetIrradianceScale(1.0);
    filter->AddLight(light);
    filter->Update();
    auto values = IrradianceArray(filter, 0);
    ASSERT_NE(values, nullptr);
    for (int k = 0; k < 17; k += 8)
    {
      for (int i = 0; i < 17; ++i)
      {
        const float v = values->GetValue(k * 17 * 17 + 8 * 17 + i);
        ASSERT_TRUE(std::isfinite(v));
        EXPECT_GE(v, 0.0f);
        EXPECT_LE(v, 1.0f + 1e-5f);
        if (i > 0)
        {
          EXPECT_LE(v, values->GetValue(k * 17 * 17 + 8 * 17 + i - 1) + 1e-5f)
            << "not monotone at x " << i << ", s " << s;
        }
      }
    }
  }
}

//------------------------------------------------------------------------------
// 4. Degenerate light placements: finite values in [0, 1], filter and mapper.
TEST(FailureCases, DegenerateLightPlacements)
{
  auto image = mmvtest::MakeVolume(17,
    [](int i, int j, int k)
    {
      const double r =
        std::sqrt((i - 8.0) * (i - 8.0) + (j - 8.0) * (j - 8.0) + (k - 8.0) * (k - 8.0));
      return static_cast<float>(r < 7.0 ? 1.0 : 0.0);
    });
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0.0, 0.0);
  opacity->AddPoint(1.0, 0.2);
  vtkNew<vtkMaterialTransferFunction> materials;
  materials->AddNode(1.0, 0.2, 0.7, 0.3, 20.0, 1.0, 0.0, 0.0);

  // Point light exactly on the voxel centre (8, 8, 8), inside the volume.
  vtkNew<vtkLight> inside;
  inside->PositionalOn();
  inside->SetConeAngle(120.0);
  inside->SetPosition(8.0, 8.0, 8.0);
  inside->SetFocalPoint(8.0, 8.0, 0.0);
  // Directional light parallel to the x axis.
  vtkNew<vtkLight> axis;
  axis->PositionalOff();
  axis->SetPosition(1.0, 0.0, 0.0);
  axis->SetFocalPoint(0.0, 0.0, 0.0);
  // Spot at (8, 8, -8) looking along +z with a 45 degree half-angle: the
  // voxel (16, 8, 0) lies exactly on the cone edge.
  vtkNew<vtkLight> spot;
  spot->PositionalOn();
  spot->SetConeAngle(45.0);
  spot->SetPosition(8.0, 8.0, -8.0);
  spot->SetFocalPoint(8.0, 8.0, 8.0);

  vtkNew<vtkIrradianceVolumeFilter> filter;
  filter->SetInputData(image);
  filter->SetScalarOpacity(opacity);
  filter->SetMaterialTransferFunction(materials);
  filter->SetIrradianceScale(1.0);
  filter->MultipleScatteringOff();
  filter->FillEmptyNeighborsOff();
  filter->AddLight(inside);
  filter->AddLight(axis);
  filter->AddLight(spot);
  filter->Update();
  for (int l = 0; l < 3; ++l)
  {
    auto values = IrradianceArray(filter, l);
    ASSERT_NE(values, nullptr);
    for (vtkIdType i = 0; i < values->GetNumberOfTuples(); ++i)
    {
      ASSERT_TRUE(std::isfinite(values->GetValue(i))) << "light " << l << " voxel " << i;
      ASSERT_GE(values->GetValue(i), 0.0f);
      ASSERT_LE(values->GetValue(i), 1.0f + 1e-5f);
    }
  }
  auto at = [&](int l, int i, int j, int k)
  { return IrradianceArray(filter, l)->GetValue((k * 17 + j) * 17 + i); };
  EXPECT_GT(at(0, 8, 8, 8), 0.5f) << "the voxel holding a point light is lit";
  EXPECT_GT(at(1, 14, 8, 8), at(1, 2, 8, 8)) << "axis-parallel light comes from +x";
  EXPECT_GT(at(2, 8, 8, 2), 0.0f) << "inside the spot cone";
  EXPECT_EQ(at(2, 1, 1, 8), 0.0f) << "outside the spot cone";

  // The CPU result the mapper must reproduce: empty voxels next to lit ones
  // filled, as the mapper does (the filter above leaves them at 0 to test the
  // cone edge).
  vtkNew<vtkIrradianceVolumeFilter> matching;
  matching->SetInputData(image);
  matching->SetScalarOpacity(opacity);
  matching->SetMaterialTransferFunction(materials);
  matching->SetIrradianceScale(1.0);
  matching->MultipleScatteringOff();
  for (vtkLight* l : { inside.Get(), axis.Get(), spot.Get() })
  {
    matching->AddLight(l);
  }
  matching->Update();
  // The same lights through the mapper.
  mmvtest::Scene scene;
  scene.Color->AddRGBPoint(0.0, 1.0, 1.0, 1.0);
  scene.Opacity->DeepCopy(opacity);
  vtkNew<vtkMultiMaterialVolumeMapper> mapper;
  mapper->SetInputData(image);
  mapper->SetMaterialTransferFunction(materials);
  mapper->SetIrradianceScale(1.0);
  scene.Volume->SetMapper(mapper);
  scene.FrameBounds(image->GetBounds());
  for (vtkLight* l : { inside.Get(), axis.Get(), spot.Get() })
  {
    l->SetLightTypeToSceneLight();
    scene.Renderer->AddLight(l);
  }
  scene.Window->Render();
  ASSERT_TRUE(mapper->GetMultiMaterialActive());
  ASSERT_EQ(mapper->GetNumberOfShadedLights(), 3);
  for (int l = 0; l < 3; ++l)
  {
    std::vector<float> gpu;
    ASSERT_TRUE(mapper->ReadIrradiance(scene.Window, l, gpu));
    for (float v : gpu)
    {
      ASSERT_TRUE(std::isfinite(v)) << "light " << l;
      ASSERT_GE(v, 0.0f);
      ASSERT_LE(v, 1.0f);
    }
    // Measured: 7.6e-6 at most on llvmpipe, 1.0e-3 on an H100 (light 2: its
    // driver rounds the 16-bit result, whose step is 2^-10 = 9.8e-4 between
    // 1 and 2, by up to a step). 1.5e-3 allows one step; the unfilled CPU
    // result differs by 0.9 (light 1).
    auto cpu = IrradianceArray(matching, l);
    ASSERT_EQ(static_cast<vtkIdType>(gpu.size()), cpu->GetNumberOfTuples());
    double worst = 0.0;
    for (vtkIdType i = 0; i < cpu->GetNumberOfTuples(); ++i)
    {
      worst = std::max(worst, std::abs(double(gpu[i]) - cpu->GetValue(i)));
    }
    std::printf("light %d: GPU vs CPU max |irradiance difference| %.2g\n", l, worst);
    EXPECT_LE(worst, 1.5e-3) << "light " << l;
  }
  double mean, variance;
  CenterStatistics(scene, 8, mean, variance);
  EXPECT_GT(mean, 5.0) << "the lit sphere must not render black";
}

//------------------------------------------------------------------------------
// 5. Irradiance coarser than a thin opaque wall: light leaks through it.
TEST(FailureCases, ThinWallLeakGrowsWithCoarserIrradiance)
{
  // A 2-voxel wall (x = 15, 16) of opacity 0.99 in a nearly clear medium,
  // lit along +x. Leak = mean irradiance behind the wall / in front of it.
  // (A 1-voxel wall is a tent after trilinear reconstruction and lets ~15%
  // through even at full resolution: that is the data, not the grid.)
  auto image =
    mmvtest::MakeVolume(Dims, [](int i, int, int) { return (i == 15 || i == 16) ? 1.0f : 0.1f; });
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0.0, 0.0);
  opacity->AddPoint(0.1, 0.001);
  opacity->AddPoint(1.0, 0.99);
  vtkNew<vtkMaterialTransferFunction> materials;
  materials->AddNode(0.0, 0.2, 0.8, 0.0, 1.0, 1.0, 0.0, 0.0);
  vtkNew<vtkLight> light;
  light->PositionalOff();
  light->SetPosition(-100.0, 16.0, 16.0);
  light->SetFocalPoint(16.0, 16.0, 16.0);
  std::vector<double> leaks;
  for (double scale : { 1.0, 0.5, 0.25, 0.125 })
  {
    vtkNew<vtkIrradianceVolumeFilter> filter;
    filter->SetInputData(image);
    filter->SetScalarOpacity(opacity);
    filter->SetMaterialTransferFunction(materials);
    filter->SetIrradianceScale(scale);
    filter->MultipleScatteringOff();
    filter->AddLight(light);
    filter->Update();
    vtkImageData* out = filter->GetOutput();
    auto values = IrradianceArray(filter, 0);
    ASSERT_NE(values, nullptr);
    double front = 0.0, behind = 0.0;
    int nFront = 0, nBehind = 0;
    for (vtkIdType p = 0; p < out->GetNumberOfPoints(); ++p)
    {
      const double x = out->GetPoint(p)[0];
      if (x >= 4.0 && x <= 12.0)
      {
        front += values->GetValue(p);
        ++nFront;
      }
      else if (x >= 20.0 && x <= 28.0)
      {
        behind += values->GetValue(p);
        ++nBehind;
      }
    }
    ASSERT_GT(nFront, 0);
    ASSERT_GT(nBehind, 0);
    const double leak = (behind / nBehind) / (front / nFront);
    int d[3];
    out->GetDimensions(d);
    std::printf("thin wall: scale %.3f (grid %d, voxel %.2f data voxels) leak %.4f\n", scale, d[0],
      32.0 / (d[0] - 1), leak);
    leaks.push_back(leak);
  }
  EXPECT_LT(leaks[0], 0.05) << "irradiance at the data resolution must not leak";
  for (size_t i = 1; i < leaks.size(); ++i)
  {
    EXPECT_GE(leaks[i], leaks[i - 1] - 0.01) << "leak must grow as the grid gets coarser";
  }
  EXPECT_GT(leaks.back(), leaks.front() + 0.1) << "a coarse grid does leak (documented)";
}

//------------------------------------------------------------------------------
// 6. Shininess 0 and 1000, zero-length normals, lights behind the surface.
TEST(FailureCases, ExtremeShininessAndBackLightsStayFinite)
{
  // CPU mirror: every combination is finite.
  const glm::dvec3 v(0, 0, 1);
  for (double shininess : { 0.0, 1.0e-6, 1.0, 1000.0 })
  {
    for (const glm::dvec3& n : { glm::dvec3(0.0), glm::dvec3(0, 0, 1) })
    {
      for (const glm::dvec3& l : { glm::dvec3(0, 0, -1), glm::dvec3(0, 0, 1), glm::dvec3(1, 0, 0) })
      {
        const glm::dvec3 c = mmv::mmvBlinnPhong(
          glm::dvec4(0.2, 0.7, 1.0, shininess), glm::dvec4(0.5, 0.5, 0.5, 0.5), n, v, l, 1.0);
        for (int i = 0; i < 3; ++i)
        {
          ASSERT_TRUE(std::isfinite(c[i])) << "shininess " << shininess;
          ASSERT_GE(c[i], 0.0);
        }
      }
    }
  }

  // GPU: a sphere with a constant core (zero gradient), lit from the camera,
  // from exactly behind (l = -v) and from the side; every pixel of the
  // sphere's disk must be lit (NaN would composite to black).
  auto image = mmvtest::MakeVolume(Dims,
    [](int i, int j, int k)
    {
      const double r =
        std::sqrt((i - 16.0) * (i - 16.0) + (j - 16.0) * (j - 16.0) + (k - 16.0) * (k - 16.0));
      return static_cast<float>(std::min(1.0, std::max(0.0, 12.0 - r) / 4.0));
    });
  for (double shininess : { 0.0, 1000.0 })
  {
    mmvtest::Scene scene;
    scene.Color->AddRGBPoint(0.0, 1.0, 1.0, 1.0);
    scene.Opacity->AddPoint(0.0, 0.0);
    scene.Opacity->AddPoint(1.0, 0.3);
    vtkNew<vtkMaterialTransferFunction> materials;
    materials->AddNode(0.0, 0.3, 0.7, 1.0, shininess, 0.2, 0.0, 0.0);
    vtkNew<vtkMultiMaterialVolumeMapper> mapper;
    mapper->SetInputData(image);
    mapper->SetMaterialTransferFunction(materials);
    scene.Volume->SetMapper(mapper);
    scene.FrameBounds(image->GetBounds());
    const double front[3] = { 16.0, 16.0, 1000.0 };
    const double back[3] = { 16.0, 16.0, -1000.0 };
    const double side[3] = { 1000.0, 16.0, 16.0 };
    scene.AddDirectionalLight(front, Center);
    scene.AddDirectionalLight(back, Center);
    scene.AddDirectionalLight(side, Center);
    scene.Window->Render();
    ASSERT_TRUE(mapper->GetMultiMaterialActive());
    const auto pixels = scene.Pixels();
    int dark = 0, inside = 0;
    for (int y = 0; y < 64; ++y)
    {
      for (int x = 0; x < 64; ++x)
      {
        // The sphere (radius 11 voxels) spans 11/24 of the half-window.
        const double r = std::hypot(x - 31.5, y - 31.5) / 32.0 * 24.0;
        if (r < 9.0)
        {
          ++inside;
          const unsigned char* p = &pixels[3 * (y * 64 + x)];
          dark += (p[0] + p[1] + p[2]) < 6 ? 1 : 0;
        }
      }
    }
    EXPECT_GT(inside, 100);
    EXPECT_EQ(dark, 0) << "black (NaN) pixels inside the sphere, shininess " << shininess;
  }
}

//------------------------------------------------------------------------------
// 7. 16-bit irradiance storage: no visible banding in a smooth ramp.
TEST(FailureCases, SixteenBitIrradianceHasNoBanding)
{
  // A nearly clear homogeneous medium lit along +x: the irradiance decays
  // from 1 to ~0.995 across the volume, a ramp of ~1.6e-4 per voxel, i.e.
  // ~10 16-bit levels per voxel but under one 8-bit level.
  auto image = mmvtest::MakeVolume(Dims, [](int, int, int) { return 1.0f; });
  mmvtest::Scene scene;
  scene.Color->AddRGBPoint(0.0, 1.0, 1.0, 1.0);
  scene.Opacity->AddPoint(0.0, 1.5e-4);
  scene.Opacity->AddPoint(2.0, 1.5e-4);
  vtkNew<vtkMaterialTransferFunction> materials;
  materials->AddNode(1.0, 0.2, 0.8, 0.0, 1.0, 1.0, 0.0, 0.0);
  vtkNew<vtkMultiMaterialVolumeMapper> mapper;
  mapper->SetInputData(image);
  mapper->SetMaterialTransferFunction(materials);
  mapper->SetIrradianceScale(1.0);
  scene.Volume->SetMapper(mapper);
  scene.FrameBounds(image->GetBounds());
  const double from[3] = { -1000.0, 16.0, 16.0 };
  scene.AddDirectionalLight(from, Center);
  scene.Window->Render();
  ASSERT_TRUE(mapper->GetMultiMaterialActive());
  std::vector<float> values;
  ASSERT_TRUE(mapper->ReadIrradiance(scene.Window, 0, values));
  ASSERT_EQ(values.size(), static_cast<size_t>(Dims * Dims * Dims));
  std::set<float> levels16;
  std::set<int> levels8;
  double step16 = 0.0, step8 = 0.0, offLattice = 0.0;
  for (int k = 0; k < Dims; ++k)
  {
    for (int j = 0; j < Dims; ++j)
    {
      for (int i = 0; i < Dims; ++i)
      {
        const float v = values[(k * Dims + j) * Dims + i];
        ASSERT_TRUE(std::isfinite(v));
        levels16.insert(v);
        levels8.insert(static_cast<int>(std::lround(v * 255.0)));
        offLattice = std::max(offLattice, std::abs(v * 65535.0 - std::round(v * 65535.0)));
        if (i > 0)
        {
          const float u = values[(k * Dims + j) * Dims + i - 1];
          step16 = std::max(step16, std::abs(double(v) - u));
          step8 =
            std::max(step8, std::abs(std::lround(v * 255.0) - std::lround(u * 255.0)) / 255.0);
        }
      }
    }
  }
  const float lo = *levels16.begin(), hi = *levels16.rbegin();
  std::printf("banding: ramp %.5f..%.5f; 16-bit: %zu levels, max step %.2e (off the 1/65535 "
              "lattice by %.3f levels); 8-bit: %zu levels, max step %.2e\n",
    lo, hi, levels16.size(), step16, offLattice, levels8.size(), step8);
  ASSERT_GT(hi - lo, 2.0e-3) << "the ramp must span several 16-bit levels";
  EXPECT_LE(step16, 1.0 / 4000) << "16-bit irradiance must not band";
  EXPECT_GE(levels16.size(), 10 * levels8.size());
  EXPECT_GE(step8, 1.0 / 255 - 1e-9) << "8 bits would band this ramp";
}
