// The CPU references (MultiMaterialVolume::Filters) cannot include the
// mapper (MultiMaterialVolume::Rendering); the rendering module registers a
// reader of its settings when it loads (vtkMultiMaterialMapperSettings.h).
// RenderToImage() must still adopt the mapper's materials and switches.
#include "mmvTestScenes.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMultiMaterialEnvironmentLookup.h"
#include "vtkMultiMaterialMapperSettings.h"
#include "vtkMultiMaterialPathTracer.h"
#include "vtkMultiMaterialReferenceRenderer.h"
#include "vtkMultiMaterialVolumeMapper.h"
#include "vtkNew.h"
#include "vtkOpenGLGPUVolumeRayCastMapper.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iterator>
#include <type_traits>

namespace mmvtest
{
namespace
{
// A 4^3 volume, half opaque, in an 8 x 8 scene with one light.
struct SmallScene : Scene
{
  SmallScene()
    : Scene(8)
  {
    this->Image = MakeVolume(4, [](int i, int, int) { return i < 2 ? 0.0f : 1.0f; });
    this->Color->AddRGBPoint(0.0, 1.0, 1.0, 1.0);
    this->Color->AddRGBPoint(1.0, 1.0, 1.0, 1.0);
    this->Opacity->AddPoint(0.0, 0.0);
    this->Opacity->AddPoint(1.0, 0.5);
    const double bounds[6] = { 0, 3, 0, 3, 0, 3 };
    this->FrameBounds(bounds);
    const double from[3] = { 0, 0, 10 }, to[3] = { 0, 0, 0 };
    this->AddDirectionalLight(from, to);
  }
  vtkSmartPointer<vtkImageData> Image;
};
}

TEST(MapperSettingsReader, ReadsOnlyTheMultiMaterialMapper)
{
  vtkNew<vtkMaterialTransferFunction> materials;
  vtkNew<vtkMultiMaterialVolumeMapper> mapper;
  mapper->SetMaterialTransferFunction(materials);
  mapper->SetMultipleScattering(false);
  mapper->SetPointLightRadius(0.37);
  mapper->SetReflectionSource(mmv::ReflectBackground);
  mapper->SetReflectionVisibility(mmv::UnoccludedReflections);

  mmv::MapperSettings settings;
  ASSERT_TRUE(mmv::ReadMapperSettings(mapper, settings));
  EXPECT_EQ(settings.Materials, materials.Get());
  EXPECT_FALSE(settings.Illumination.MultipleScattering);
  EXPECT_EQ(settings.Illumination.PointLightRadius, 0.37);
  EXPECT_EQ(settings.Illumination.ReflectionSource, mmv::ReflectBackground);
  EXPECT_EQ(settings.Illumination.ReflectionVisibility, mmv::UnoccludedReflections);

  mmv::MapperSettings untouched;
  untouched.Illumination.PointLightRadius = 5.0;
  vtkNew<vtkOpenGLGPUVolumeRayCastMapper> other;
  EXPECT_FALSE(mmv::ReadMapperSettings(other, untouched));
  EXPECT_FALSE(mmv::ReadMapperSettings(nullptr, untouched));
  EXPECT_EQ(untouched.Illumination.PointLightRadius, 5.0);
  EXPECT_EQ(untouched.Materials, nullptr);
}

TEST(MapperSettings, AccessorsFollowTheTable)
{
  vtkNew<vtkMultiMaterialVolumeMapper> mapper;
  const mmv::IlluminationSettings defaults;
  int rows = 0;
  // Every accessor starts at its row's default and clamps to its row's range.
#define MMV_CHECK_SETTING(type, name, init, low, high, doc)                                        \
  {                                                                                                \
    const mmv::SettingDescription& row = mmv::IlluminationSettingDescriptions[rows++];             \
    EXPECT_STREQ(row.Name, #name);                                                                 \
    EXPECT_EQ(static_cast<double>(mapper->Get##name()), row.Default) << #name;                     \
    EXPECT_EQ(static_cast<double>(defaults.name), row.Default) << #name;                           \
    if (!std::is_same<type, bool>::value && std::isfinite(row.Max))                                \
    {                                                                                              \
      mapper->Set##name(static_cast<type>(row.Max + 1.0));                                         \
      EXPECT_EQ(static_cast<double>(mapper->Get##name()), row.Max) << #name;                       \
      mapper->Set##name(static_cast<type>(row.Min - 1.0));                                         \
      EXPECT_EQ(static_cast<double>(mapper->Get##name()), row.Min) << #name;                       \
    }                                                                                              \
  }
  MMV_ILLUMINATION_SETTINGS(MMV_CHECK_SETTING)
#undef MMV_CHECK_SETTING
  EXPECT_EQ(rows, static_cast<int>(std::size(mmv::IlluminationSettingDescriptions)));

  // SetSettings takes them all, clamped the same way, and marks the mapper
  // modified only when something changed.
  mmv::IlluminationSettings wanted;
  wanted.PiecewiseShadowSlices = 5;
  wanted.ReflectionVisibility = mmv::MarchedReflectionVisibility;
  wanted.MultipleScattering = false;
  wanted.LightDirectionTolerance = 90.0; // above the row's maximum
  mapper->SetSettings(wanted);
  EXPECT_EQ(mapper->GetSettings().PiecewiseShadowSlices, 5);
  EXPECT_EQ(mapper->GetReflectionVisibility(), mmv::MarchedReflectionVisibility);
  EXPECT_FALSE(mapper->GetMultipleScattering());
  EXPECT_EQ(mapper->GetLightDirectionTolerance(), mmv::MaxLightDirectionToleranceDegrees);
  const vtkMTimeType time = mapper->GetMTime();
  mapper->SetSettings(mapper->GetSettings());
  EXPECT_EQ(mapper->GetMTime(), time);
}

TEST(MapperSettingsReader, ReferencesAdoptTheMapperInRenderToImage)
{
  SmallScene scene;
  vtkNew<vtkMaterialTransferFunction> materials;
  vtkNew<vtkMultiMaterialVolumeMapper> mapper;
  mapper->SetInputData(scene.Image);
  mapper->SetMaterialTransferFunction(materials);
  mapper->SetMultipleScattering(false);
  mapper->SetPointLightRadius(0.37);
  mapper->SetReflectionSource(mmv::ReflectBackground);
  mapper->SetReflectionVisibility(mmv::UnoccludedReflections);
  scene.Volume->SetMapper(mapper);

  vtkNew<vtkMultiMaterialReferenceRenderer> reference;
  ASSERT_TRUE(reference->GetMultipleScattering()) << "the default differs from the mapper's";
  ASSERT_NE(reference->GetPointLightRadius(), 0.37);
  ASSERT_NE(reference->GetReflectionSource(), mmv::ReflectBackground);
  ASSERT_NE(reference->GetReflectionVisibility(), mmv::UnoccludedReflections);
  ASSERT_NE(reference->RenderToImage(scene.Renderer, scene.Volume), nullptr);
  EXPECT_EQ(reference->GetMaterialTransferFunction(), materials.Get());
  EXPECT_FALSE(reference->GetMultipleScattering());
  EXPECT_EQ(reference->GetPointLightRadius(), 0.37);
  EXPECT_EQ(reference->GetReflectionSource(), mmv::ReflectBackground);
  EXPECT_EQ(reference->GetReflectionVisibility(), mmv::UnoccludedReflections);
  EXPECT_EQ(reference->GetInput(), scene.Image.Get());

  vtkNew<vtkMultiMaterialPathTracer> tracer;
  tracer->SetSamplesPerPixel(1);
  ASSERT_NE(tracer->RenderToImage(scene.Renderer, scene.Volume), nullptr);
  EXPECT_EQ(tracer->GetMaterialTransferFunction(), materials.Get());
  EXPECT_EQ(tracer->GetPointLightRadius(), 0.37);
}

TEST(MapperSettingsReader, AnotherMapperGivesTheSceneButKeepsTheReferenceSettings)
{
  SmallScene scene;
  vtkNew<vtkOpenGLGPUVolumeRayCastMapper> mapper;
  mapper->SetInputData(scene.Image);
  scene.Volume->SetMapper(mapper);
  vtkNew<vtkMaterialTransferFunction> own;
  vtkNew<vtkMultiMaterialReferenceRenderer> reference;
  reference->SetMaterialTransferFunction(own);
  reference->SetPointLightRadius(0.25);
  ASSERT_NE(reference->RenderToImage(scene.Renderer, scene.Volume), nullptr);
  EXPECT_EQ(reference->GetInput(), scene.Image.Get());
  EXPECT_EQ(reference->GetMaterialTransferFunction(), own.Get());
  EXPECT_EQ(reference->GetPointLightRadius(), 0.25);
  EXPECT_TRUE(reference->GetMultipleScattering());
}
}
