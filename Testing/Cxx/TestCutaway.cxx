// Cutaway views: what the mapper's cropping region and clipping
// planes remove casts no shadow. A plate above a floor, lit from above and
// seen from above; removing the plate by cropping or by a clipping plane must
// render as the scene built without the plate (PSNR >= 35 dB), a plane moving
// through the volume must match fresh renders frame after frame, and the CPU
// filter must agree with the GPU pass on the cut irradiance.
#include "mmvPlateScene.h"

#include "vtkFloatArray.h"
#include "vtkIrradianceVolumeFilter.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMultiMaterialCutaway.h"
#include "vtkMultiMaterialReferenceRenderer.h"
#include "vtkMultiMaterialVolumeMapper.h"
#include "vtkPlane.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <string>

namespace
{
constexpr int Dims = 33;
constexpr double Target = 35.0; // dB

/// Floor: z in [3, 6]; plate (unless `withPlate` is false): z in [20, 23],
/// x and y in [8, 24]. Both of value 1 in empty space (0).
vtkSmartPointer<vtkImageData> PlateAboveFloor(bool withPlate)
{
  return mmvtest::MakeVolume(Dims,
    [withPlate](int i, int j, int k)
    {
      if (k >= 3 && k <= 6)
      {
        return 1.0f;
      }
      if (withPlate && k >= 20 && k <= 23 && i >= 8 && i <= 24 && j >= 8 && j <= 24)
      {
        return 1.0f;
      }
      return 0.0f;
    });
}

using Cut = std::function<void(vtkMultiMaterialVolumeMapper*)>;

/// The plate and floor (mmvPlateScene.h), with the plate or without it.
/// Attenuation 1 casts the shadows; no specular.
struct PlateScene : mmvtest::PlateScene
{
  explicit PlateScene(bool withPlate)
    : mmvtest::PlateScene(PlateAboveFloor(withPlate), 0.0)
  {
  }
};

using mmvtest::PSNR;

/// The plate removed by `cut` against the scene built without it.
double CutVersusNoPlate(const Cut& cut, const char* what)
{
  PlateScene withoutPlate(false);
  const auto reference = withoutPlate.Render();
  PlateScene cutAway(true);
  cut(cutAway.Mapper);
  const auto image = cutAway.Render();
  PlateScene uncut(true);
  const auto plate = uncut.Render();
  const double psnr = PSNR(image, reference);
  std::printf("%s: PSNR against the scene without the plate %.1f dB (the uncut plate scene: "
              "%.1f dB)\n",
    what, psnr, PSNR(plate, reference));
  EXPECT_TRUE(cutAway.Mapper->GetMultiMaterialActive());
  return psnr;
}

vtkSmartPointer<vtkPlane> Plane(double z, double nz)
{
  auto plane = vtkSmartPointer<vtkPlane>::New();
  plane->SetOrigin(16.0, 16.0, z);
  plane->SetNormal(0.0, 0.0, nz);
  return plane;
}
} // namespace

TEST(Cutaway, CroppingCastsNoShadow)
{
  // ParaView's UseCropping with CroppingScale (1, 1, 0.5): the lower half.
  const double psnr = CutVersusNoPlate(
    [](vtkMultiMaterialVolumeMapper* m)
    {
      m->CroppingOn();
      m->SetCroppingRegionPlanes(0.0, 32.0, 0.0, 32.0, 0.0, 16.0);
      m->SetCroppingRegionFlagsToSubVolume();
    },
    "cropping");
  EXPECT_GE(psnr, Target);
}

TEST(Cutaway, ClippingPlaneCastsNoShadow)
{
  const double psnr = CutVersusNoPlate([](vtkMultiMaterialVolumeMapper* m)
    { m->AddClippingPlane(Plane(16.0, -1.0)); },
    "clipping plane");
  EXPECT_GE(psnr, Target);
}

TEST(Cutaway, AMovingPlaneMatchesFreshRendersFrameAfterFrame)
{
  // One scene whose clipping plane sweeps down through the plate, frame
  // after frame, against a fresh scene per frame.
  PlateScene moving(true);
  auto plane = Plane(30.0, -1.0);
  moving.Mapper->AddClippingPlane(plane);
  moving.Render();
  int updates = moving.Mapper->GetIrradianceUpdateCount();
  double worst = std::numeric_limits<double>::infinity();
  for (const double z : { 25.0, 22.0, 21.0, 19.0, 12.0 })
  {
    plane->SetOrigin(16.0, 16.0, z);
    const auto image = moving.Render();
    EXPECT_GT(moving.Mapper->GetIrradianceUpdateCount(), updates) << "plane at z = " << z;
    updates = moving.Mapper->GetIrradianceUpdateCount();
    PlateScene fresh(true);
    fresh.Mapper->AddClippingPlane(Plane(z, -1.0));
    const double psnr = PSNR(image, fresh.Render());
    std::printf("plane at z = %.0f: PSNR against a fresh render %.1f dB\n", z, psnr);
    EXPECT_GE(psnr, Target) << "plane at z = " << z;
    worst = std::min(worst, psnr);
  }
  std::printf("moving plane: worst PSNR %.1f dB\n", worst);
}

TEST(Cutaway, AddingAndRemovingACutMatchesFreshRenders)
{
  // The shadow-ray programs compile the cutaway test only while something is
  // cut: one scene goes uncut -> clipped -> cropped -> uncut, each frame
  // against a fresh scene with the same cut.
  const Cut none = [](vtkMultiMaterialVolumeMapper*) {};
  const Cut clip = [](vtkMultiMaterialVolumeMapper* m) { m->AddClippingPlane(Plane(16.0, -1.0)); };
  const Cut crop = [](vtkMultiMaterialVolumeMapper* m)
  {
    m->RemoveAllClippingPlanes();
    m->CroppingOn();
    m->SetCroppingRegionPlanes(0.0, 32.0, 0.0, 32.0, 0.0, 16.0);
    m->SetCroppingRegionFlagsToSubVolume();
  };
  const Cut uncut = [](vtkMultiMaterialVolumeMapper* m)
  {
    m->RemoveAllClippingPlanes();
    m->CroppingOff();
  };
  PlateScene toggled(true);
  const std::pair<const char*, Cut> steps[] = { { "uncut", none }, { "clipped", clip },
    { "cropped", crop }, { "uncut again", uncut } };
  for (const auto& step : steps)
  {
    step.second(toggled.Mapper);
    const auto image = toggled.Render();
    PlateScene fresh(true);
    for (const auto& s : steps)
    {
      s.second(fresh.Mapper); // the same sequence of settings, rendered once
      if (s.first == step.first)
      {
        break;
      }
    }
    const double psnr = PSNR(image, fresh.Render());
    std::printf("%s: PSNR against a fresh render %.1f dB\n", step.first, psnr);
    EXPECT_GE(psnr, Target) << step.first;
  }
  // The plate's shadow must come back once the cut is gone.
  PlateScene withoutPlate(false);
  EXPECT_LT(PSNR(toggled.Render(), withoutPlate.Render()), Target);
}

TEST(Cutaway, CpuFilterMatchesGpuPassWithCroppingAndClipping)
{
  PlateScene scene(true);
  scene.Mapper->CroppingOn();
  scene.Mapper->SetCroppingRegionPlanes(0.0, 32.0, 0.0, 32.0, 0.0, 21.5);
  scene.Mapper->SetCroppingRegionFlagsToSubVolume();
  auto tilted = vtkSmartPointer<vtkPlane>::New();
  tilted->SetOrigin(12.0, 16.0, 16.0);
  tilted->SetNormal(0.6, 0.0, -0.8); // keeps 0.6 (x - 12) >= 0.8 (z - 16): a slanted cut
  scene.Mapper->AddClippingPlane(tilted);
  scene.Render();
  std::vector<float> gpu;
  ASSERT_TRUE(scene.Mapper->ReadIrradiance(scene.Window, 0, gpu));

  vtkNew<vtkIrradianceVolumeFilter> cpu;
  cpu->SetInputData(scene.Image);
  cpu->SetScalarOpacity(scene.Opacity);
  cpu->SetScalarOpacityUnitDistance(scene.Property->GetScalarOpacityUnitDistance());
  cpu->SetMaterialTransferFunction(scene.Materials);
  cpu->SetIrradianceScale(1.0);
  cpu->MultipleScatteringOff();
  cpu->CopyCutaway(scene.Mapper);
  cpu->SetLights(scene.Renderer->GetLights());
  cpu->Update();
  auto* reference =
    vtkFloatArray::SafeDownCast(cpu->GetOutput()->GetPointData()->GetArray("Irradiance_0"));
  ASSERT_NE(reference, nullptr);
  ASSERT_EQ(static_cast<vtkIdType>(gpu.size()), reference->GetNumberOfTuples());
  double worst = 0.0;
  double floorUnderPlate = 0.0;
  for (vtkIdType i = 0; i < reference->GetNumberOfTuples(); ++i)
  {
    worst = std::max(worst, std::abs(double(gpu[i]) - reference->GetValue(i)));
  }
  // The floor's top voxel (10, 16, 6) under the plate: the slanted plane
  // removes the plate (z 20-21 after cropping) where x < 17.3.
  const vtkIdType voxel = 6 * Dims * Dims + 16 * Dims + 10;
  floorUnderPlate = reference->GetValue(voxel);
  std::printf("cut irradiance: GPU vs CPU max |difference| %.2g; floor under the plate %.3f\n",
    worst, floorUnderPlate);
  EXPECT_LE(worst, 0.01);

  // Without the cutaway the same floor voxel lies in the plate's shadow.
  vtkNew<vtkIrradianceVolumeFilter> uncut;
  uncut->SetInputData(scene.Image);
  uncut->SetScalarOpacity(scene.Opacity);
  uncut->SetScalarOpacityUnitDistance(scene.Property->GetScalarOpacityUnitDistance());
  uncut->SetMaterialTransferFunction(scene.Materials);
  uncut->SetIrradianceScale(1.0);
  uncut->MultipleScatteringOff();
  uncut->SetLights(scene.Renderer->GetLights());
  uncut->Update();
  const double shadowed =
    vtkFloatArray::SafeDownCast(uncut->GetOutput()->GetPointData()->GetArray("Irradiance_0"))
      ->GetValue(voxel);
  std::printf("the same voxel without the cutaway: %.3f\n", shadowed);
  EXPECT_LT(shadowed, 0.2 * floorUnderPlate);
}

TEST(Cutaway, ReferenceRendererCutsAsTheMapper)
{
  // The reference renderer (the ground truth): the cropped plate scene
  // against the reference of the scene without the plate.
  auto reference = [](PlateScene& scene)
  {
    scene.Window->Render();
    vtkNew<vtkMultiMaterialReferenceRenderer> ref;
    vtkImageData* image = ref->RenderToImage(scene.Renderer, scene.Volume);
    EXPECT_NE(image, nullptr);
    auto* rgb = image ? image->GetPointData()->GetScalars() : nullptr;
    std::vector<unsigned char> bytes;
    for (vtkIdType i = 0; rgb && i < rgb->GetNumberOfTuples(); ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        bytes.push_back(static_cast<unsigned char>(rgb->GetComponent(i, c)));
      }
    }
    return bytes;
  };
  PlateScene withoutPlate(false);
  PlateScene cropped(true);
  cropped.Mapper->CroppingOn();
  cropped.Mapper->SetCroppingRegionPlanes(0.0, 32.0, 0.0, 32.0, 0.0, 16.0);
  cropped.Mapper->SetCroppingRegionFlagsToSubVolume();
  PlateScene clipped(true);
  clipped.Mapper->AddClippingPlane(Plane(16.0, -1.0));
  const auto expected = reference(withoutPlate);
  const double crop = PSNR(reference(cropped), expected);
  const double clip = PSNR(reference(clipped), expected);
  std::printf("reference renderer: cropping %.1f dB, clipping %.1f dB against the scene without "
              "the plate\n",
    crop, clip);
  EXPECT_GE(crop, Target);
  EXPECT_GE(clip, Target);
}

TEST(Cutaway, UniformsAreDeclaredOnceFromTheLayout)
{
  // The prelude declares every uniform of mmv::CutawayUniformLayout (the
  // names the passes set); Shaders/mmvCutaway.glsl declares none and reads
  // each, so the two cannot drift (the GPU-against-CPU cutaway tests above
  // fail if a name is not set).
  const std::string prelude = mmv::CutawayGLSLPrelude();
  std::ifstream file(std::string(MMV_SOURCE_DIR) + "/Shaders/mmvCutaway.glsl");
  ASSERT_TRUE(file.good());
  const std::string shader(
    (std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  EXPECT_EQ(shader.find("uniform "), std::string::npos);
  for (const mmv::CutawayUniformInfo& u : mmv::CutawayUniformLayout)
  {
    EXPECT_NE(prelude.find(std::string("uniform ") + u.GLSLType + " " + u.Name), std::string::npos)
      << u.Name;
    EXPECT_NE(shader.find(u.Name), std::string::npos) << u.Name;
    EXPECT_EQ(std::string(u.Name).rfind("mmv_", 0), 0u) << u.Name;
  }
}
