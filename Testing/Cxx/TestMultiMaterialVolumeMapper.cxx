// vtkMultiMaterialVolumeMapper: closed-form images, caching (the paper's
// Algorithm 1), shader variants, fallbacks and graphics resources. Runs under
// Xvfb with Mesa llvmpipe in CI.
#include "mmvTestScenes.h"

#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkInformation.h"
#include "vtkInformationObjectBaseVectorKey.h"
#include "vtkIrradianceEstimator.h"
#include "vtkIrradianceGrid.h"
#include "vtkIrradianceResolutionProbe.h"
#include "vtkIrradianceVolumeFilter.h"
#include "vtkLightCollection.h"
#include "vtkLightKit.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMath.h"
#include "vtkMultiMaterialLights.h"
#include "vtkMultiMaterialLiveObjects.h"
#include "vtkMultiMaterialShaderHook.h"
#include "vtkMultiMaterialVolumeMapper.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLGPUVolumeRayCastMapper.h"
#include "vtkOpenGLRenderPass.h"
#include "vtkPointData.h"
#include "vtkRenderer.h"
#include "vtkWeakPointer.h"
#include "vtk_glew.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <initializer_list>
#include <map>
#include <sstream>
#include <string>
#include <unistd.h>
#include <utility>
#include <vector>

namespace
{
constexpr int Dims = 33; // cube of side D = 32 (spacing 1)
constexpr double D = Dims - 1;
constexpr double Mu = 0.05; // extinction per unit length
const double CubeColor[3] = { 1.0, 0.6, 0.3 };

// A homogeneous cube, ambient-only material (ka = 1), attenuation c_t.
struct CubeScene : mmvtest::Scene
{
  vtkNew<vtkMultiMaterialVolumeMapper> Mapper;
  vtkNew<vtkMaterialTransferFunction> Materials;
  vtkSmartPointer<vtkImageData> Image;

  explicit CubeScene(double attenuation)
  {
    this->Image = mmvtest::MakeVolume(Dims, [](int, int, int) { return 1.0f; });
    this->Color->AddRGBPoint(0.0, CubeColor[0], CubeColor[1], CubeColor[2]);
    this->Color->AddRGBPoint(2.0, CubeColor[0], CubeColor[1], CubeColor[2]);
    const double alpha = 1.0 - std::exp(-Mu); // unit distance 1
    this->Opacity->AddPoint(0.0, alpha);
    this->Opacity->AddPoint(2.0, alpha);
    this->Property->SetScalarOpacityUnitDistance(1.0);
    this->Materials->AddNode(1.0, 1.0, 0.0, 0.0, 1.0, attenuation, 0.0, 0.0);
    this->Mapper->SetInputData(this->Image);
    this->Mapper->SetMaterialTransferFunction(this->Materials);
    this->Mapper->AutoAdjustSampleDistancesOff();
    this->Mapper->SetSampleDistance(0.25);
    this->Mapper->SetIrradianceScale(1.0);
    this->Volume->SetMapper(this->Mapper);
    this->FrameBounds(this->Image->GetBounds());
  }

  double Center(int c)
  {
    this->Window->Render();
    return this->Pixel(32, 32)[c];
  }
};

const double CubeCenter[3] = { 16.0, 16.0, 16.0 };
}

TEST(MultiMaterialVolumeMapper, LightFromCameraSideMatchesClosedForm)
{
  // sigma = mu (attenuation 1): pixel = c mu/(sigma+mu) (1 - exp(-(sigma+mu) D)).
  CubeScene scene(1.0);
  const double from[3] = { 16.0, 16.0, 1000.0 };
  scene.AddDirectionalLight(from, CubeCenter);
  const double expected = 0.5 * (1.0 - std::exp(-2.0 * Mu * D));
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_NEAR(
      scene.Center(c), CubeColor[c] * expected, 0.03 * CubeColor[c] * expected + 1.0 / 255)
      << "channel " << c;
  }
  EXPECT_TRUE(scene.Mapper->GetMultiMaterialActive());
  EXPECT_EQ(scene.Mapper->GetNumberOfShadedLights(), 1);
}

TEST(MultiMaterialVolumeMapper, LightFromBehindMatchesClosedForm)
{
  // sigma = mu: pixel = c mu D exp(-mu D).
  CubeScene scene(1.0);
  const double from[3] = { 16.0, 16.0, -1000.0 };
  scene.AddDirectionalLight(from, CubeCenter);
  const double expected = Mu * D * std::exp(-Mu * D);
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_NEAR(
      scene.Center(c), CubeColor[c] * expected, 0.03 * CubeColor[c] * expected + 1.0 / 255)
      << "channel " << c;
  }
}

TEST(MultiMaterialVolumeMapper, NoShadowsWithZeroAttenuation)
{
  // sigma = 0: pixel = c (1 - exp(-mu D)), whichever side the light is on.
  CubeScene scene(0.0);
  const double from[3] = { 16.0, 16.0, -1000.0 };
  scene.AddDirectionalLight(from, CubeCenter);
  const double expected = 1.0 - std::exp(-Mu * D);
  EXPECT_NEAR(scene.Center(0), expected, 0.03 * expected);
}

TEST(MultiMaterialVolumeMapper, LightIntensityAndColourScaleTheImage)
{
  CubeScene scene(1.0);
  const double from[3] = { 16.0, 16.0, 1000.0 };
  vtkLight* light = scene.AddDirectionalLight(from, CubeCenter);
  const double full = scene.Center(0);
  light->SetIntensity(0.5);
  EXPECT_NEAR(scene.Center(0), 0.5 * full, 2.0 / 255);
  light->SetIntensity(1.0);
  light->SetColor(0.0, 1.0, 1.0);
  EXPECT_NEAR(scene.Center(0), 0.0, 1.0 / 255);
}

TEST(MultiMaterialVolumeMapper, CameraMovesDoNotRecomputeIrradiance)
{
  CubeScene scene(1.0);
  const double from[3] = { 16.0, 16.0, 1000.0 };
  vtkLight* light = scene.AddDirectionalLight(from, CubeCenter);
  scene.Window->Render();
  ASSERT_EQ(scene.Mapper->GetIrradianceUpdateCount(), 1);
  const int tables = scene.Mapper->GetPreIntegrationCount();
  const int casts = scene.Mapper->GetRayCastCount();

  // Camera only: no irradiance, no pre-integration, one ray cast per frame.
  for (int i = 0; i < 3; ++i)
  {
    scene.Renderer->GetActiveCamera()->Azimuth(20.0);
    scene.Window->Render();
  }
  EXPECT_EQ(scene.Mapper->GetIrradianceUpdateCount(), 1);
  EXPECT_EQ(scene.Mapper->GetPreIntegrationCount(), tables);
  EXPECT_EQ(scene.Mapper->GetRayCastCount(), casts + 3);

  // Light colour only: irradiance is stored without colour.
  light->SetColor(1.0, 0.5, 0.5);
  scene.Window->Render();
  EXPECT_EQ(scene.Mapper->GetIrradianceUpdateCount(), 1);

  // Moving the light: exactly one update.
  light->SetPosition(16.0, 1000.0, 16.0);
  scene.Window->Render();
  scene.Window->Render();
  EXPECT_EQ(scene.Mapper->GetIrradianceUpdateCount(), 2);

  // Opacity change: tables and irradiance once each.
  scene.Opacity->AddPoint(1.0, 0.1);
  scene.Window->Render();
  EXPECT_EQ(scene.Mapper->GetIrradianceUpdateCount(), 3);
  EXPECT_EQ(scene.Mapper->GetPreIntegrationCount(), tables + 1);

  // The gradient volume depends on the data alone: uploaded once so far,
  // and again only when the scalars change.
  EXPECT_EQ(scene.Mapper->GetGradientUploadCount(), 1);
  scene.Image->GetPointData()->GetScalars()->Modified();
  scene.Window->Render();
  EXPECT_EQ(scene.Mapper->GetGradientUploadCount(), 2);
}

TEST(MultiMaterialVolumeMapper, IrradianceUpdatesReportProgress)
{
  // An irradiance update (seconds on llvmpipe) reports VTK progress 0 when it
  // starts and 1 when it ends, with the text "Irradiance volume"; a frame
  // that reuses the irradiance reports none. The mapper's other
  // progress (its input's update) carries no text.
  CubeScene scene(1.0);
  std::vector<std::pair<double, std::string>> events;
  vtkNew<vtkCallbackCommand> observer;
  observer->SetClientData(&events);
  observer->SetCallback(
    [](vtkObject* caller, unsigned long, void* client, void* data)
    {
      auto* algorithm = vtkAlgorithm::SafeDownCast(caller);
      if (algorithm && algorithm->GetProgressText())
      {
        static_cast<std::vector<std::pair<double, std::string>>*>(client)->emplace_back(
          *static_cast<double*>(data), algorithm->GetProgressText());
      }
    });
  scene.Mapper->AddObserver(vtkCommand::ProgressEvent, observer);
  const double from[3] = { 16.0, 16.0, 1000.0 };
  vtkLight* light = scene.AddDirectionalLight(from, CubeCenter);
  const std::vector<std::pair<double, std::string>> startEnd = { { 0.0, "Irradiance volume" },
    { 1.0, "Irradiance volume" } };
  scene.Window->Render();
  EXPECT_EQ(scene.Mapper->GetIrradianceUpdateCount(), 1);
  EXPECT_EQ(events, startEnd);
  events.clear();
  scene.Renderer->GetActiveCamera()->Azimuth(20.0);
  scene.Window->Render();
  EXPECT_TRUE(events.empty()) << events.size() << " events for a camera move";
  light->SetPosition(16.0, 1000.0, 16.0);
  scene.Window->Render();
  EXPECT_EQ(scene.Mapper->GetIrradianceUpdateCount(), 2);
  EXPECT_EQ(events, startEnd);
  EXPECT_EQ(scene.Mapper->GetProgressText(), nullptr) << "the text is cleared after an update";

  // With an automatic resolution, the error probe's measurement reports its
  // own progress, rising from 0 to 1 after each grid it lights, before the
  // update's; a camera move reports nothing.
  events.clear();
  scene.Mapper->SetIrradianceScale(0.0);
  scene.Window->Render();
  ASSERT_GE(events.size(), 5u);
  const std::string probe = "Irradiance resolution probe";
  EXPECT_EQ(events.front(), std::make_pair(0.0, probe));
  size_t probeEnd = 1;
  for (; probeEnd < events.size() && events[probeEnd].second == probe; ++probeEnd)
  {
    EXPECT_GT(events[probeEnd].first, events[probeEnd - 1].first) << "probe report " << probeEnd;
  }
  EXPECT_GE(probeEnd, 3u) << "the probe lights several grids";
  EXPECT_EQ(events[probeEnd - 1].first, 1.0);
  const std::vector<std::pair<double, std::string>> update(events.begin() + probeEnd, events.end());
  EXPECT_EQ(update, startEnd);
  EXPECT_EQ(scene.Mapper->GetNumberOfIrradianceProbes(), 1);
  events.clear();
  scene.Renderer->GetActiveCamera()->Azimuth(20.0);
  scene.Window->Render();
  EXPECT_TRUE(events.empty()) << events.size() << " events for a camera move";
}

TEST(MultiMaterialVolumeMapper, IrradianceProgressRisesPerLight)
{
  // An update of several lights with diffusion reports progress between its
  // passes (each light's shadows, each texture's diffusion), increasing from
  // 0 to 1; a camera move or a colour edit reports nothing.
  CubeScene scene(1.0);
  scene.Materials->RemoveAllNodes();
  scene.Materials->AddNode(1.0, 0.2, 0.8, 0.0, 1.0, 1.0, 4.0, 0.0);
  scene.Mapper->MultipleScatteringOn();
  std::vector<double> progress;
  vtkNew<vtkCallbackCommand> observer;
  observer->SetClientData(&progress);
  observer->SetCallback(
    [](vtkObject* caller, unsigned long, void* client, void* data)
    {
      auto* algorithm = vtkAlgorithm::SafeDownCast(caller);
      if (algorithm && algorithm->GetProgressText() &&
        std::string(algorithm->GetProgressText()) == "Irradiance volume")
      {
        static_cast<std::vector<double>*>(client)->push_back(*static_cast<double*>(data));
      }
    });
  scene.Mapper->AddObserver(vtkCommand::ProgressEvent, observer);
  // Five lights: two irradiance textures (four lights each).
  const double from[5][3] = { { 16, 16, 1000 }, { 1000, 16, 16 }, { 16, 1000, 16 },
    { -1000, 16, 16 }, { 16, 16, -1000 } };
  std::vector<vtkLight*> lights;
  for (const auto& f : from)
  {
    lights.push_back(scene.AddDirectionalLight(f, CubeCenter));
  }
  const auto expectRising = [&progress](size_t reports, const char* what)
  {
    ASSERT_FALSE(progress.empty()) << what;
    EXPECT_EQ(progress.front(), 0.0) << what;
    EXPECT_EQ(progress.back(), 1.0) << what;
    for (size_t i = 1; i < progress.size(); ++i)
    {
      EXPECT_GT(progress[i], progress[i - 1]) << what << ", report " << i;
    }
    // The start, then one report per light's shadows and one per texture's
    // diffusion.
    EXPECT_EQ(progress.size(), 1 + reports) << what;
  };
  scene.Window->Render();
  ASSERT_EQ(scene.Mapper->GetNumberOfShadedLights(), 5);
  EXPECT_GT(scene.Mapper->GetDiffusionPassCount(), 0);
  expectRising(5 + 2, "first update");

  progress.clear();
  scene.Renderer->GetActiveCamera()->Azimuth(20.0);
  scene.Window->Render();
  scene.Color->AddRGBPoint(1.0, 0.2, 0.9, 0.4);
  scene.Window->Render();
  EXPECT_TRUE(progress.empty()) << progress.size() << " reports without an update";

  // One light moved: its shadows and its texture's diffusion.
  lights[4]->SetPosition(16.0, -1000.0, 16.0);
  scene.Window->Render();
  expectRising(1 + 1, "one light moved");
}

TEST(MultiMaterialVolumeMapper, ColourOnlyMaterialEditsKeepTheIrradiance)
{
  CubeScene scene(1.0);
  const double from[3] = { 16.0, 16.0, 1000.0 };
  scene.AddDirectionalLight(from, CubeCenter);
  scene.Window->Render();
  ASSERT_EQ(scene.Mapper->GetIrradianceUpdateCount(), 1);
  const std::string shader = scene.Mapper->GetLastFragmentShaderSource();

  // Ambient, diffuse, specular and shininess only change the shading: the
  // irradiance stays, the shader stays, the image changes.
  const double before = scene.Center(0);
  scene.Materials->AddNode(1.0, 0.5, 0.3, 0.4, 30.0, 1.0, 0.0, 0.0);
  const double after = scene.Center(0);
  EXPECT_EQ(scene.Mapper->GetIrradianceUpdateCount(), 1);
  EXPECT_EQ(scene.Mapper->GetLastFragmentShaderSource(), shader);
  EXPECT_LT(after, before - 0.1);

  // Attenuation reaches the shadows: exactly one update.
  scene.Materials->AddNode(1.0, 0.5, 0.3, 0.4, 30.0, 0.5, 0.0, 0.0);
  scene.Window->Render();
  scene.Window->Render();
  EXPECT_EQ(scene.Mapper->GetIrradianceUpdateCount(), 2);
}

TEST(MultiMaterialVolumeMapper, SwitchedOffLightCostsNothing)
{
  CubeScene scene(1.0);
  const double from[3] = { 16.0, 16.0, 1000.0 };
  scene.AddDirectionalLight(from, CubeCenter);
  const double behind[3] = { 16.0, 16.0, -1000.0 };
  vtkLight* off = scene.AddDirectionalLight(behind, CubeCenter);
  off->SwitchOff();
  const double withOff = scene.Center(0);
  EXPECT_EQ(scene.Mapper->GetNumberOfShadedLights(), 1);
  scene.Renderer->RemoveLight(off);
  EXPECT_NEAR(scene.Center(0), withOff, 1.0 / 255);
}

TEST(MultiMaterialVolumeMapper, NoDiffusionWithoutScattering)
{
  CubeScene scene(1.0);
  const double from[3] = { 16.0, 16.0, 1000.0 };
  scene.AddDirectionalLight(from, CubeCenter);
  scene.Window->Render();
  EXPECT_EQ(scene.Mapper->GetDiffusionPassCount(), 0);
  scene.Materials->AddNode(1.0, 1.0, 0.0, 0.0, 1.0, 1.0, 5.0, 0.0);
  scene.Window->Render();
  EXPECT_GT(scene.Mapper->GetDiffusionPassCount(), 0);
}

TEST(MultiMaterialVolumeMapper, ReflectionCodeOnlyWhenSomeMaterialReflects)
{
  CubeScene scene(1.0);
  const double from[3] = { 16.0, 16.0, 1000.0 };
  scene.AddDirectionalLight(from, CubeCenter);
  scene.Window->Render();
  std::string source = scene.Mapper->GetLastFragmentShaderSource();
  ASSERT_NE(source.find("#define MMV_NUMBER_OF_LIGHTS 1"), std::string::npos);
  EXPECT_NE(source.find("#define MMV_USE_REFLECTION 0"), std::string::npos);
  scene.Materials->AddNode(1.0, 1.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.5);
  scene.Window->Render();
  source = scene.Mapper->GetLastFragmentShaderSource();
  EXPECT_NE(source.find("#define MMV_USE_REFLECTION 1"), std::string::npos);
}

TEST(MultiMaterialVolumeMapper, OtherBlendModesMatchTheBaseClass)
{
  auto render = [](vtkOpenGLGPUVolumeRayCastMapper* mapper)
  {
    mmvtest::Scene scene;
    auto image = mmvtest::MakeVolume(
      17, [](int i, int j, int k) { return static_cast<float>(i + 2 * j + 3 * k); });
    scene.Color->AddRGBPoint(0.0, 0.0, 0.0, 1.0);
    scene.Color->AddRGBPoint(96.0, 1.0, 1.0, 0.0);
    scene.Opacity->AddPoint(0.0, 0.0);
    scene.Opacity->AddPoint(96.0, 1.0);
    mapper->SetInputData(image);
    mapper->SetBlendModeToMaximumIntensity();
    scene.Volume->SetMapper(mapper);
    scene.FrameBounds(image->GetBounds());
    scene.Window->Render();
    return scene.Pixels();
  };
  vtkNew<vtkMultiMaterialVolumeMapper> ours;
  vtkNew<vtkOpenGLGPUVolumeRayCastMapper> base;
  const auto a = render(ours);
  const auto b = render(base);
  EXPECT_FALSE(ours->GetMultiMaterialActive());
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(a, b);
}

TEST(MultiMaterialVolumeMapper, ReleaseAndNewWindowRenderTheSameImage)
{
  std::vector<unsigned char> first;
  vtkNew<vtkMultiMaterialVolumeMapper> mapper;
  vtkNew<vtkMaterialTransferFunction> materials;
  materials->AddNode(1.0, 0.3, 0.7, 0.4, 20.0, 1.0, 2.0, 0.0);
  auto image = mmvtest::MakeVolume(Dims,
    [](int i, int j, int k)
    {
      const double r =
        std::sqrt((i - 16.0) * (i - 16.0) + (j - 16.0) * (j - 16.0) + (k - 16.0) * (k - 16.0));
      return static_cast<float>(r < 10.0 ? 1.0 : 0.0);
    });
  mapper->SetInputData(image);
  mapper->SetMaterialTransferFunction(materials);
  for (int round = 0; round < 2; ++round)
  {
    mmvtest::Scene scene;
    scene.Color->AddRGBPoint(0.0, 1.0, 0.8, 0.6);
    scene.Color->AddRGBPoint(1.0, 1.0, 0.8, 0.6);
    scene.Opacity->AddPoint(0.0, 0.0);
    scene.Opacity->AddPoint(1.0, 0.3);
    scene.Volume->SetMapper(mapper);
    scene.FrameBounds(image->GetBounds());
    const double from[3] = { 100.0, 200.0, 300.0 };
    scene.AddDirectionalLight(from, CubeCenter);
    scene.Window->Render();
    const auto pixels = scene.Pixels();
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
    mapper->ReleaseGraphicsResources(scene.Window);
    scene.Window->Render();
    EXPECT_EQ(scene.Pixels(), pixels) << "after ReleaseGraphicsResources";
    if (round == 0)
    {
      first = pixels;
    }
    else
    {
      EXPECT_EQ(pixels, first) << "in a new window";
    }
    mapper->ReleaseGraphicsResources(scene.Window);
  }
}

TEST(MultiMaterialVolumeMapper, GpuIrradianceMatchesCpuFilter)
{
  // A sphere lit by a directional and a point light; no diffusion.
  auto image = mmvtest::MakeVolume(Dims,
    [](int i, int j, int k)
    {
      const double r =
        std::sqrt((i - 16.0) * (i - 16.0) + (j - 14.0) * (j - 14.0) + (k - 17.0) * (k - 17.0));
      return static_cast<float>(std::max(0.0, 12.0 - r));
    });
  mmvtest::Scene scene;
  scene.Color->AddRGBPoint(0.0, 1.0, 1.0, 1.0);
  scene.Opacity->AddPoint(0.0, 0.0);
  scene.Opacity->AddPoint(12.0, 0.6);
  vtkNew<vtkMaterialTransferFunction> materials;
  materials->AddNode(0.0, 0.2, 0.7, 0.2, 20.0, 1.0, 0.0, 0.0);
  materials->AddNode(12.0, 0.2, 0.7, 0.2, 20.0, 0.5, 0.0, 0.0);
  vtkNew<vtkMultiMaterialVolumeMapper> mapper;
  mapper->SetInputData(image);
  mapper->SetMaterialTransferFunction(materials);
  mapper->SetIrradianceScale(0.5);
  scene.Volume->SetMapper(mapper);
  scene.FrameBounds(image->GetBounds());
  const double from[3] = { -50.0, 80.0, 100.0 };
  vtkLight* sun = scene.AddDirectionalLight(from, CubeCenter);
  vtkNew<vtkLight> lamp;
  lamp->SetLightTypeToSceneLight();
  lamp->PositionalOn();
  lamp->SetConeAngle(120.0);
  lamp->SetAttenuationValues(1.0, 0.02, 0.0005); // VTK's falloff, non-default
  lamp->SetPosition(40.0, 10.0, 20.0);
  lamp->SetFocalPoint(16.0, 16.0, 16.0);
  scene.Renderer->AddLight(lamp);
  scene.Window->Render();
  ASSERT_TRUE(mapper->GetMultiMaterialActive());

  vtkNew<vtkIrradianceVolumeFilter> cpu;
  cpu->SetInputData(image);
  cpu->SetScalarOpacity(scene.Opacity);
  cpu->SetScalarOpacityUnitDistance(scene.Property->GetScalarOpacityUnitDistance());
  cpu->SetMaterialTransferFunction(materials);
  cpu->SetIrradianceScale(0.5);
  cpu->AddLight(sun);
  cpu->AddLight(lamp);
  cpu->MultipleScatteringOff();
  cpu->Update();
  int dims[3];
  mapper->GetIrradianceDimensions(dims);
  int cpuDims[3];
  cpu->GetOutput()->GetDimensions(cpuDims);
  ASSERT_EQ(std::vector<int>(dims, dims + 3), std::vector<int>(cpuDims, cpuDims + 3));

  for (int light = 0; light < 2; ++light)
  {
    std::vector<float> gpu;
    ASSERT_TRUE(mapper->ReadIrradiance(scene.Window, light, gpu));
    auto* reference = vtkFloatArray::SafeDownCast(
      cpu->GetOutput()->GetPointData()->GetArray(("Irradiance_" + std::to_string(light)).c_str()));
    ASSERT_NE(reference, nullptr);
    ASSERT_EQ(static_cast<vtkIdType>(gpu.size()), reference->GetNumberOfTuples());
    double worst = 0.0;
    for (vtkIdType i = 0; i < reference->GetNumberOfTuples(); ++i)
    {
      worst = std::max(worst, std::abs(double(gpu[i]) - reference->GetValue(i)));
    }
    EXPECT_LE(worst, 0.01) << "light " << light;
  }
}

TEST(MultiMaterialVolumeMapper, InteractiveFramesKeepTheIrradianceAndTheStillFrameIsExact)
{
  // ParaView's default lighting: the light kit, attached to the camera, so
  // every camera move moves the lights.
  auto addKit = [](mmvtest::Scene& scene)
  {
    vtkNew<vtkLightKit> kit;
    kit->AddLightsToRenderer(scene.Renderer);
  };
  CubeScene scene(1.0);
  addKit(scene);
  scene.Window->SetDesiredUpdateRate(0.0001); // a still render
  scene.Window->Render();
  ASSERT_EQ(scene.Mapper->GetIrradianceUpdateCount(), 1);
  EXPECT_FALSE(scene.Mapper->GetLastRenderInteractive());
  EXPECT_EQ(scene.Mapper->GetNumberOfUpdatedLights(), scene.Mapper->GetNumberOfShadedLights());

  // A drag: interactive frames (allocated render time < 1 s) keep it.
  scene.Window->SetDesiredUpdateRate(30.0);
  for (int i = 0; i < 3; ++i)
  {
    scene.Renderer->GetActiveCamera()->Azimuth(15.0);
    scene.Renderer->GetActiveCamera()->Elevation(5.0);
    scene.Renderer->GetActiveCamera()->OrthogonalizeViewUp();
    scene.Window->Render();
    EXPECT_TRUE(scene.Mapper->GetLastRenderInteractive());
  }
  EXPECT_EQ(scene.Mapper->GetIrradianceUpdateCount(), 1);
  EXPECT_EQ(scene.Mapper->GetDeferredIrradianceCount(), 3);
  const std::vector<unsigned char> stale = scene.Pixels();

  // The still frame after the drag updates it and equals a fresh render.
  scene.Window->SetDesiredUpdateRate(0.0001);
  scene.Window->Render();
  EXPECT_EQ(scene.Mapper->GetIrradianceUpdateCount(), 2);
  const std::vector<unsigned char> rest = scene.Pixels();

  CubeScene fresh(1.0);
  addKit(fresh);
  fresh.Renderer->GetActiveCamera()->DeepCopy(scene.Renderer->GetActiveCamera());
  fresh.Renderer->ResetCameraClippingRange(fresh.Image->GetBounds());
  fresh.Window->SetDesiredUpdateRate(0.0001);
  fresh.Window->Render();
  const std::vector<unsigned char> reference = fresh.Pixels();
  ASSERT_EQ(rest.size(), reference.size());
  auto psnr = [&](const std::vector<unsigned char>& a)
  {
    double sum = 0.0;
    for (size_t i = 0; i < a.size(); ++i)
    {
      const double d = static_cast<double>(a[i]) - reference[i];
      sum += d * d;
    }
    const double mse = sum / a.size();
    return mse > 0.0 ? 10.0 * std::log10(255.0 * 255.0 / mse) : 999.0;
  };
  std::cout << "PSNR at rest vs fresh: " << psnr(rest)
            << " dB; stale interactive frame vs fresh: " << psnr(stale) << " dB" << std::endl;
  EXPECT_GE(psnr(rest), 40.0);
  EXPECT_LT(psnr(stale), psnr(rest)) << "the interactive frames did not show stale lighting";

  // UpdateAlways: interactive frames update too.
  scene.Mapper->SetInteractiveIrradiance(vtkMultiMaterialVolumeMapper::UpdateAlways);
  scene.Window->SetDesiredUpdateRate(30.0);
  scene.Renderer->GetActiveCamera()->Azimuth(15.0);
  scene.Window->Render();
  EXPECT_EQ(scene.Mapper->GetIrradianceUpdateCount(), 3);
  EXPECT_EQ(scene.Mapper->GetDeferredIrradianceCount(), 3);
}

TEST(MultiMaterialVolumeMapper, SceneLightsThatDidNotMoveKeepTheirIrradiance)
{
  CubeScene scene(1.0);
  const double from1[3] = { 16.0, 16.0, 1000.0 };
  const double from2[3] = { 1000.0, 16.0, 16.0 };
  scene.AddDirectionalLight(from1, CubeCenter);
  vtkLight* moving = scene.AddDirectionalLight(from2, CubeCenter);
  scene.Window->Render();
  EXPECT_EQ(scene.Mapper->GetNumberOfUpdatedLights(), 2);
  moving->SetPosition(1000.0, 1000.0, 16.0);
  scene.Window->Render();
  EXPECT_EQ(scene.Mapper->GetIrradianceUpdateCount(), 2);
  EXPECT_EQ(scene.Mapper->GetNumberOfUpdatedLights(), 1);
}

TEST(MultiMaterialVolumeMapper, LightsWithinTheToleranceKeepTheirIrradianceWithoutDrift)
{
  CubeScene scene(1.0);
  const double from1[3] = { 1000.0, 16.0, 16.0 };
  scene.AddDirectionalLight(from1, CubeCenter);
  vtkLight* turning = scene.AddDirectionalLight(CubeCenter, CubeCenter);
  auto turn = [&](double degrees)
  {
    const double a = degrees * vtkMath::Pi() / 180.0;
    turning->SetPosition(16.0 + 984.0 * std::sin(a), 16.0, 16.0 + 984.0 * std::cos(a));
  };
  turn(0.0);
  scene.Mapper->SetLightDirectionTolerance(1.0);
  scene.Window->Render();
  ASSERT_EQ(scene.Mapper->GetIrradianceUpdateCount(), 1);

  // 0.6 degrees: within the tolerance, kept.
  turn(0.6);
  scene.Window->Render();
  EXPECT_EQ(scene.Mapper->GetIrradianceUpdateCount(), 1);
  // 1.2 degrees from what the irradiance holds (0.6 from the last frame):
  // recomputed, that light alone. Comparing with the last frame instead
  // would let small moves add up without end.
  turn(1.2);
  scene.Window->Render();
  EXPECT_EQ(scene.Mapper->GetIrradianceUpdateCount(), 2);
  EXPECT_EQ(scene.Mapper->GetNumberOfUpdatedLights(), 1);
  // Back by 0.6: within the tolerance of 1.2.
  turn(0.6);
  scene.Window->Render();
  EXPECT_EQ(scene.Mapper->GetIrradianceUpdateCount(), 2);

  // Tolerance 0 (the default): any move beyond the camera's rounding updates.
  scene.Mapper->SetLightDirectionTolerance(mmv::DefaultLightDirectionToleranceDegrees);
  turn(0.61);
  scene.Window->Render();
  EXPECT_EQ(scene.Mapper->GetIrradianceUpdateCount(), 3);

  // Out-of-range values are clamped by the setter.
  scene.Mapper->SetLightDirectionTolerance(1000.0);
  EXPECT_EQ(scene.Mapper->GetLightDirectionTolerance(), mmv::MaxLightDirectionToleranceDegrees);
  scene.Mapper->SetLightDirectionTolerance(-1.0);
  EXPECT_EQ(scene.Mapper->GetLightDirectionTolerance(), 0.0);
}

TEST(MultiMaterialVolumeMapper, ReportsTheChosenIrradianceResolution)
{
  CubeScene scene(1.0);
  const double from[3] = { 16.0, 16.0, 1000.0 };
  scene.AddDirectionalLight(from, CubeCenter);
  scene.Window->Render();
  EXPECT_NE(std::string(scene.Mapper->GetIrradianceResolutionReason()).find("set by the user"),
    std::string::npos)
    << scene.Mapper->GetIrradianceResolutionReason();
  // Automatic, zoomed out: the 64-pixel view spans 128 units (0.5 pixel
  // per data voxel), so the screen rule picks 0.5 / PixelsPerIrradianceVoxel.
  scene.Mapper->SetIrradianceScale(0.0);
  // The error probe would coarsen this homogeneous cube further (below).
  scene.Mapper->SetIrradianceErrorBound(0.0);
  scene.Renderer->GetActiveCamera()->SetParallelScale(64.0);
  scene.Window->Render();
  const std::string reason = scene.Mapper->GetIrradianceResolutionReason();
  EXPECT_NE(reason.find("screen"), std::string::npos) << reason;
  const mmv::IrradianceResolution expected =
    mmv::ChooseIrradianceResolution(scene.Image->GetDimensions(), 1, 64.0, 0.0, 0.5);
  int dims[3];
  scene.Mapper->GetIrradianceDimensions(dims);
  EXPECT_EQ(dims[0], expected.Dimensions[0]) << reason;
  EXPECT_LT(dims[0], Dims) << reason;
  // Zoomed back in: the full grid again.
  scene.Renderer->GetActiveCamera()->SetParallelScale(16.0);
  scene.Window->Render();
  scene.Mapper->GetIrradianceDimensions(dims);
  EXPECT_EQ(dims[0], Dims) << scene.Mapper->GetIrradianceResolutionReason();
  // With the probe (the default): a constant field loses nothing on the
  // coarsest grid it tries, a quarter of the reference's.
  scene.Mapper->SetIrradianceErrorBound(mmv::DefaultIrradianceErrorBoundDB);
  scene.Window->Render();
  scene.Mapper->GetIrradianceDimensions(dims);
  const std::string probed = scene.Mapper->GetIrradianceResolutionReason();
  EXPECT_NE(probed.find("error probe"), std::string::npos) << probed;
  EXPECT_EQ(dims[0], 8) << probed;
}

namespace
{
/// Diffusely lit data of `Dims`^3 points from `value`, the light kit's key
/// light on it, an automatic irradiance resolution.
struct ProbeScene : mmvtest::Scene
{
  vtkNew<vtkMultiMaterialVolumeMapper> Mapper;
  vtkNew<vtkMaterialTransferFunction> Materials;
  vtkSmartPointer<vtkImageData> Image;

  explicit ProbeScene(
    const std::function<float(int, int, int)>& value, double opacity, double scattering = 0.0)
  {
    this->Image = mmvtest::MakeVolume(Dims, value);
    this->Color->AddRGBPoint(0.0, 1.0, 0.9, 0.8);
    this->Color->AddRGBPoint(1.0, 1.0, 0.9, 0.8);
    this->Opacity->AddPoint(0.0, 0.0);
    this->Opacity->AddPoint(1.0, opacity);
    this->Property->SetScalarOpacityUnitDistance(1.0);
    this->Materials->AddNode(0.0, 0.1, 0.9, 0.0, 1.0, 1.0, scattering, 0.0);
    this->Materials->AddNode(1.0, 0.1, 0.9, 0.0, 1.0, 1.0, scattering, 0.0);
    this->Mapper->SetInputData(this->Image);
    this->Mapper->SetMaterialTransferFunction(this->Materials);
    this->Mapper->SetMultipleScattering(scattering > 0.0);
    this->Volume->SetMapper(this->Mapper);
    this->FrameBounds(this->Image->GetBounds());
    vtkNew<vtkLightKit> kit;
    kit->AddLightsToRenderer(this->Renderer);
  }
};

/// A smooth blob: its lighting needs no fine grid.
float SmoothBlob(int i, int j, int k)
{
  const double r2 = (i - 16.0) * (i - 16.0) + (j - 16.0) * (j - 16.0) + (k - 16.0) * (k - 16.0);
  return static_cast<float>(std::exp(-r2 / (2.0 * 9.0 * 9.0)));
}

/// A spherical shell one voxel thick: its self-shadowing needs every voxel.
float ThinShell(int i, int j, int k)
{
  const double r =
    std::sqrt((i - 16.0) * (i - 16.0) + (j - 16.0) * (j - 16.0) + (k - 16.0) * (k - 16.0));
  return std::abs(r - 12.0) < 0.75 ? 1.0f : 0.0f;
}

}

TEST(MultiMaterialVolumeMapper, ErrorProbeCoarsensSmoothDataWithinItsBound)
{
  ProbeScene probed(SmoothBlob, 0.3);
  probed.Window->Render();
  int dims[3];
  probed.Mapper->GetIrradianceDimensions(dims);
  const std::string reason = probed.Mapper->GetIrradianceResolutionReason();
  EXPECT_LT(dims[0], Dims) << reason;
  EXPECT_NE(reason.find("error probe"), std::string::npos) << reason;
  EXPECT_EQ(probed.Mapper->GetNumberOfIrradianceProbes(), 1);
  // The image it gives against the full grid's: no worse than the bound.
  ProbeScene full(SmoothBlob, 0.3);
  full.Mapper->SetIrradianceScale(1.0);
  full.Window->Render();
  const double psnr = mmvtest::PSNR(probed.Pixels(), full.Pixels());
  EXPECT_GE(psnr, mmv::DefaultIrradianceErrorBoundDB) << reason;
  std::printf("smooth blob: %s; image %.1f dB against the full grid\n", reason.c_str(), psnr);

  // No probe: the screen and the budget keep the full grid here.
  ProbeScene unprobed(SmoothBlob, 0.3);
  unprobed.Mapper->SetIrradianceErrorBound(0.0);
  unprobed.Window->Render();
  unprobed.Mapper->GetIrradianceDimensions(dims);
  EXPECT_EQ(dims[0], Dims) << unprobed.Mapper->GetIrradianceResolutionReason();
  EXPECT_EQ(unprobed.Mapper->GetNumberOfIrradianceProbes(), 0);
}

TEST(MultiMaterialVolumeMapper, ErrorProbeKeepsTheGridOfThinShells)
{
  ProbeScene scene(ThinShell, 0.9);
  scene.Window->Render();
  int dims[3];
  scene.Mapper->GetIrradianceDimensions(dims);
  EXPECT_EQ(dims[0], Dims) << scene.Mapper->GetIrradianceResolutionReason();
  const auto& candidates = scene.Mapper->GetIrradianceResolutionProbe()->GetCandidates();
  ASSERT_GE(candidates.size(), 2u);
  EXPECT_LT(candidates[1].PSNR, mmv::DefaultIrradianceErrorBoundDB);
}

// The light kit's fill, back and head lights (1/3 to 1/3.5 of the key
// light) take the strided grid, the key light and lights of equal strength
// the irradiance grid; a grid too small to stride keeps every light.
TEST(MultiMaterialVolumeMapper, DimLightsAreTheOnesOnACoarserGrid)
{
  auto lights = [](std::initializer_list<double> intensities)
  {
    std::vector<mmv::ShadingLight> result;
    for (const double intensity : intensities)
    {
      mmv::ShadingLight light;
      light.Radiance = glm::dvec3(intensity, 0.5 * intensity, 0.2 * intensity);
      result.push_back(light);
    }
    return result;
  };
  auto strides = [](const std::vector<mmv::LightSource>& sources)
  {
    std::vector<int> result;
    for (const auto& source : sources)
    {
      result.push_back(source.GridStride);
    }
    return result;
  };
  const int big[3] = { 64, 64, 33 };
  const double key = 0.75;
  const auto kit = lights({ key, key / 3.0, key / 3.5, key / 3.5, key / 3.0 });
  EXPECT_EQ(strides(mmv::IrradianceLightSources(kit, big, true)),
    (std::vector<int>{
      1, mmv::DimLightStride, mmv::DimLightStride, mmv::DimLightStride, mmv::DimLightStride }));
  EXPECT_EQ(strides(mmv::IrradianceLightSources(kit, big, false)), (std::vector<int>(5, 1)));
  EXPECT_EQ(strides(mmv::IrradianceLightSources(lights({ 1.0, 0.6, 1.0 }), big, true)),
    (std::vector<int>{ 1, 1, 1 }));
  const int small[3] = { 64, 64, 13 }; // 7 points of light grid along z
  EXPECT_EQ(strides(mmv::IrradianceLightSources(kit, small, true)), (std::vector<int>(5, 1)));
}

// Under the light kit, a one-voxel shell (the grid the error probe keeps)
// with the dim lights strided stays within the error probe's bound of the
// image with every light on the full grid, from a third of the shadow rays.
// Where it scatters, the dim lights would diffuse on blocks of 2, but the
// shell fills none of them (mmv::FilledBlockShare; 29.9 dB if they did), so
// they diffuse with the others; a smooth blob fills its blocks, and its dim
// lights take them within the same bound. A light that brightens past the
// ratio is recomputed on the full grid.
TEST(MultiMaterialVolumeMapper, DimLightsOnACoarserGridKeepTheImage)
{
  const struct
  {
    const char* Name;
    float (*Value)(int, int, int);
    double Opacity;
    double Scattering; // 2: a diffusion length of 2 voxels, the lights' grid the irradiance grid's
    int DimDiffusionGrid; // what the dim lights diffuse on, per axis
  } scenes[] = {
    { "thin shell", ThinShell, 0.9, 0.0, 1 },
    { "scattering thin shell", ThinShell, 0.9, 2.0, Dims },
    { "scattering smooth blob", SmoothBlob, 0.3, 2.0, (Dims + 1) / 2 },
  };
  for (const auto& scene : scenes)
  {
    ProbeScene strided(scene.Value, scene.Opacity, scene.Scattering);
    ProbeScene exact(scene.Value, scene.Opacity, scene.Scattering);
    exact.Mapper->DimLightCoarseningOff();
    for (ProbeScene* probed : { &strided, &exact })
    {
      // The blob's lighting would take a coarser grid (the error probe's);
      // the comparison is of the dim lights alone.
      probed->Mapper->SetIrradianceErrorBound(0.0);
      probed->Window->Render();
    }
    int dims[3];
    strided.Mapper->GetIrradianceDimensions(dims);
    ASSERT_EQ(dims[0], Dims) << strided.Mapper->GetIrradianceResolutionReason();
    const double psnr = mmvtest::PSNR(strided.Pixels(), exact.Pixels());
    vtkIrradianceEstimator* estimator = strided.Mapper->GetIrradianceEstimator();
    const double rays = static_cast<double>(estimator->GetLastEstimatedVoxels()) /
      exact.Mapper->GetIrradianceEstimator()->GetLastEstimatedVoxels();
    int grid[3];
    estimator->GetDiffusionGridDimensions(grid, mmv::DimLightStride);
    std::printf("light kit on a %s: dim lights strided %.1f dB, %.2f of the shadow rays, "
                "their diffusion grid %d\n",
      scene.Name, psnr, rays, grid[0]);
    // A shell one voxel thick at opacity 0.9 is the worst case: its
    // self-shadowing changes within a voxel (measured 34.1 dB, the error
    // probe's bound for any coarser grid; a CT's ribs give 57.7 dB,
    // docs/performance.md).
    EXPECT_GE(psnr, mmv::DefaultIrradianceErrorBoundDB) << scene.Name;
    EXPECT_LT(psnr, 200.0) << scene.Name; // the strided grid was used
    EXPECT_LT(rays, 0.5) << scene.Name;
    EXPECT_EQ(grid[0], scene.DimDiffusionGrid) << scene.Name;
  }
  ProbeScene strided(ThinShell, 0.9);
  strided.Window->Render();

  // A dim light made as bright as the key light: only it is recomputed.
  vtkLightCollection* kitLights = strided.Renderer->GetLights();
  vtkLight* keyLight = nullptr;
  vtkLight* dimLight = nullptr;
  kitLights->InitTraversal();
  while (vtkLight* light = kitLights->GetNextItem())
  {
    if (!keyLight || light->GetIntensity() > keyLight->GetIntensity())
    {
      keyLight = light;
    }
  }
  kitLights->InitTraversal();
  while (vtkLight* light = kitLights->GetNextItem())
  {
    dimLight = light != keyLight ? light : dimLight;
  }
  ASSERT_NE(dimLight, nullptr);
  dimLight->SetIntensity(keyLight->GetIntensity());
  strided.Window->Render();
  EXPECT_EQ(strided.Mapper->GetNumberOfUpdatedLights(), 1);
}

TEST(MultiMaterialVolumeMapper, ErrorProbeRunsOncePerTransferFunctionNotPerCamera)
{
  ProbeScene scene(SmoothBlob, 0.3);
  scene.Window->Render();
  int first[3];
  scene.Mapper->GetIrradianceDimensions(first);
  // An orbit: the kit's lights follow the camera, the probe light does not.
  for (int step = 0; step < 3; ++step)
  {
    scene.Renderer->GetActiveCamera()->Azimuth(25.0);
    scene.Renderer->GetActiveCamera()->Elevation(10.0);
    scene.Renderer->ResetCameraClippingRange();
    scene.Window->Render();
  }
  EXPECT_EQ(scene.Mapper->GetNumberOfIrradianceProbes(), 1);
  EXPECT_GT(scene.Mapper->GetIrradianceUpdateCount(), 1);
  int after[3];
  scene.Mapper->GetIrradianceDimensions(after);
  EXPECT_EQ(after[0], first[0]);
  // The image at rest equals a fresh render of that camera.
  ProbeScene fresh(SmoothBlob, 0.3);
  fresh.Renderer->GetActiveCamera()->DeepCopy(scene.Renderer->GetActiveCamera());
  fresh.Renderer->ResetCameraClippingRange();
  scene.Renderer->ResetCameraClippingRange();
  fresh.Window->Render();
  scene.Window->Render();
  EXPECT_EQ(mmvtest::PSNR(scene.Pixels(), fresh.Pixels()), INFINITY);
  // A transfer-function change measures again.
  scene.Opacity->AddPoint(1.0, 0.6);
  scene.Window->Render();
  EXPECT_EQ(scene.Mapper->GetNumberOfIrradianceProbes(), 2);
}

namespace
{
/// The smooth blob moved along x: the next step of a series on the same grid.
float MovedBlob(int i, int j, int k)
{
  return SmoothBlob(i - 2, j, k);
}

/// Renders a fresh scene of `value` with `peak` opacity through `scene`'s
/// camera: its image and grid against `scene`'s (which must equal them).
void ExpectSameAsFresh(ProbeScene& scene, const std::function<float(int, int, int)>& value,
  double peak, const char* what)
{
  ProbeScene fresh(value, peak);
  fresh.Renderer->GetActiveCamera()->DeepCopy(scene.Renderer->GetActiveCamera());
  fresh.Renderer->ResetCameraClippingRange();
  scene.Renderer->ResetCameraClippingRange();
  fresh.Window->Render();
  scene.Window->Render();
  int kept[3], chosen[3];
  scene.Mapper->GetIrradianceDimensions(kept);
  fresh.Mapper->GetIrradianceDimensions(chosen);
  EXPECT_EQ(kept[0], chosen[0]) << what << ": " << fresh.Mapper->GetIrradianceResolutionReason();
  EXPECT_EQ(mmvtest::PSNR(scene.Pixels(), fresh.Pixels()), INFINITY) << what;
}
}

TEST(MultiMaterialVolumeMapper, ErrorProbeKeepsItsChoiceThroughAnOpacityDrag)
{
  // One opacity point dragged within the support (vtkIrradianceProbeRule.h):
  // every edit recomputes the irradiance, none measures again, and the grid
  // kept is the one a fresh probe of the final transfer function chooses.
  const struct
  {
    float (*Value)(int, int, int);
    std::vector<double> Peaks;
  } drags[] = { { SmoothBlob, { 0.3, 0.33, 0.36, 0.4 } }, { ThinShell, { 0.9, 0.85, 0.8, 0.75 } } };
  for (const auto& drag : drags)
  {
    ProbeScene scene(drag.Value, drag.Peaks.front());
    scene.Window->Render();
    ASSERT_EQ(scene.Mapper->GetNumberOfIrradianceProbes(), 1);
    for (size_t e = 1; e < drag.Peaks.size(); ++e)
    {
      const int updates = scene.Mapper->GetIrradianceUpdateCount();
      scene.Opacity->AddPoint(1.0, drag.Peaks[e]);
      scene.Window->Render();
      EXPECT_EQ(scene.Mapper->GetIrradianceUpdateCount(), updates + 1) << drag.Peaks[e];
    }
    EXPECT_EQ(scene.Mapper->GetNumberOfIrradianceProbes(), 1);
    ExpectSameAsFresh(scene, drag.Value, drag.Peaks.back(), "after the drag");
    // Past the rule (optical depth more than doubled): measured again.
    scene.Opacity->AddPoint(
      1.0, 1.0 - (1.0 - drag.Peaks.front()) * (1.0 - drag.Peaks.front()) * 0.8);
    scene.Window->Render();
    EXPECT_EQ(scene.Mapper->GetNumberOfIrradianceProbes(), 2);
  }
}

TEST(MultiMaterialVolumeMapper, TimeStepsOnTheSameGridKeepTheProbesChoice)
{
  ProbeScene scene(SmoothBlob, 0.3);
  scene.Window->Render();
  int first[3];
  scene.Mapper->GetIrradianceDimensions(first);
  const int updates = scene.Mapper->GetIrradianceUpdateCount();
  // The next step: new values on the same grid.
  scene.Mapper->SetInputData(mmvtest::MakeVolume(Dims, MovedBlob));
  scene.Window->Render();
  EXPECT_EQ(scene.Mapper->GetNumberOfIrradianceProbes(), 1);
  EXPECT_EQ(scene.Mapper->GetIrradianceUpdateCount(), updates + 1);
  ExpectSameAsFresh(scene, MovedBlob, 0.3, "the next step");
  // A step on another grid (dimensions, then spacing) measures again and
  // re-allocates: the image equals a fresh render of it.
  const int larger = Dims + 8;
  scene.Mapper->SetInputData(mmvtest::MakeVolume(larger, SmoothBlob));
  scene.Window->Render();
  EXPECT_EQ(scene.Mapper->GetNumberOfIrradianceProbes(), 2);
  {
    ProbeScene fresh(SmoothBlob, 0.3);
    fresh.Mapper->SetInputData(mmvtest::MakeVolume(larger, SmoothBlob));
    fresh.Renderer->GetActiveCamera()->DeepCopy(scene.Renderer->GetActiveCamera());
    fresh.Renderer->ResetCameraClippingRange();
    fresh.Window->Render();
    int dims[3], chosen[3];
    scene.Mapper->GetIrradianceDimensions(dims);
    fresh.Mapper->GetIrradianceDimensions(chosen);
    EXPECT_EQ(dims[0], chosen[0]) << scene.Mapper->GetIrradianceResolutionReason();
    EXPECT_NE(dims[0], first[0]) << scene.Mapper->GetIrradianceResolutionReason();
    EXPECT_EQ(mmvtest::PSNR(scene.Pixels(), fresh.Pixels()), INFINITY);
  }
  auto spaced = mmvtest::MakeVolume(larger, SmoothBlob);
  spaced->SetSpacing(0.5, 0.5, 0.5);
  scene.Mapper->SetInputData(spaced);
  scene.Window->Render();
  EXPECT_EQ(scene.Mapper->GetNumberOfIrradianceProbes(), 3);
  // Back to the first grid: the buffers and textures kept from the larger
  // steps (pre-filter slabs, the gradient texture) give way to this one's.
  scene.Mapper->SetInputData(mmvtest::MakeVolume(Dims, MovedBlob));
  scene.Window->Render();
  ExpectSameAsFresh(scene, MovedBlob, 0.3, "back on the first grid");
}

TEST(MultiMaterialVolumeMapper, AStepOutsideTheOpacityDrawsTheBackgroundWithoutAnUpdate)
{
  // The opacity covers [0, 1]; the second step's values lie in [2, 3].
  ProbeScene scene(SmoothBlob, 0.3);
  scene.Opacity->AddPoint(1.5, 0.0);
  scene.Window->Render();
  const int updates = scene.Mapper->GetIrradianceUpdateCount();
  ASSERT_GE(updates, 1);
  scene.Mapper->SetInputData(
    mmvtest::MakeVolume(Dims, [](int i, int j, int k) { return 2.0f + SmoothBlob(i, j, k); }));
  scene.Window->Render();
  EXPECT_EQ(scene.Mapper->GetIrradianceUpdateCount(), updates);
  EXPECT_TRUE(scene.Mapper->GetMultiMaterialActive());
  const std::vector<unsigned char> pixels = scene.Pixels();
  size_t lit = 0;
  for (unsigned char p : pixels)
  {
    lit += p != 0;
  }
  EXPECT_EQ(lit, 0u);
  // Back inside: updated, and the image equals a fresh render.
  scene.Mapper->SetInputData(mmvtest::MakeVolume(Dims, MovedBlob));
  scene.Window->Render();
  EXPECT_EQ(scene.Mapper->GetIrradianceUpdateCount(), updates + 1);
}

TEST(MultiMaterialVolumeMapper, KeptStepsComeBackWithoutAnUpdate)
{
  // Three steps of a series on one grid, each its own data object (as
  // ParaView's animation cache hands them back), with scattering so the
  // copies include diffused light.
  ProbeScene scene(SmoothBlob, 0.3);
  scene.Materials->AddNode(1.0, 0.1, 0.9, 0.0, 1.0, 1.0, 8.0, 0.0);
  scene.Mapper->MultipleScatteringOn();
  scene.Mapper->SetIrradianceCacheMB(64.0);
  const std::function<float(int, int, int)> values[] = { SmoothBlob, MovedBlob,
    [](int i, int j, int k) { return 0.5f * SmoothBlob(i, j - 3, k); } };
  std::vector<vtkSmartPointer<vtkImageData>> steps;
  for (const auto& value : values)
  {
    steps.push_back(mmvtest::MakeVolume(Dims, value));
  }
  const auto show = [&scene, &steps](size_t k)
  {
    scene.Mapper->SetInputData(steps[k]);
    scene.Window->Render();
  };
  std::vector<std::vector<unsigned char>> first;
  for (size_t k = 0; k < steps.size(); ++k)
  {
    const int updates = scene.Mapper->GetIrradianceUpdateCount();
    show(k);
    EXPECT_EQ(scene.Mapper->GetIrradianceUpdateCount(), updates + 1) << "first loop, step " << k;
    first.push_back(scene.Pixels());
  }
  EXPECT_EQ(scene.Mapper->GetIrradianceCacheHitCount(), 0);
  // Five light-kit lights: an RGBA16 and an R16 texture, 10 bytes a voxel.
  int dims[3];
  scene.Mapper->GetIrradianceDimensions(dims);
  const size_t entry = 10u * static_cast<size_t>(dims[0]) * dims[1] * dims[2];
  EXPECT_EQ(scene.Mapper->GetIrradianceCacheBytes(), 3 * entry);

  // The second loop: the kept copies shown as they are, not updates (of
  // the irradiance or the gradient volume), and the very same images.
  const int updates = scene.Mapper->GetIrradianceUpdateCount();
  const int gradients = scene.Mapper->GetGradientUploadCount();
  vtkIrradianceEstimator* estimator = scene.Mapper->GetIrradianceEstimator();
  std::vector<vtkTextureObject*> shown;
  for (size_t k = 0; k < steps.size(); ++k)
  {
    show(k);
    EXPECT_EQ(scene.Mapper->GetIrradianceCacheHitCount(), static_cast<int>(k + 1));
    EXPECT_EQ(mmvtest::PSNR(scene.Pixels(), first[k]), INFINITY) << "second loop, step " << k;
    EXPECT_TRUE(estimator->ShowsKeptTextures()) << "second loop, step " << k;
    shown.push_back(estimator->GetIrradianceTexture(0));
  }
  EXPECT_NE(shown[0], shown[1]);
  EXPECT_NE(shown[1], shown[2]);
  EXPECT_EQ(scene.Mapper->GetIrradianceUpdateCount(), updates);
  EXPECT_EQ(scene.Mapper->GetGradientUploadCount(), gradients);

  // Room for two and a half entries: the least recently used step (0) goes
  // first and is recomputed; step 2 is still there.
  const double mib = 1048576.0;
  scene.Mapper->SetIrradianceCacheMB(2.5 * entry / mib);
  show(0);
  EXPECT_EQ(scene.Mapper->GetIrradianceUpdateCount(), updates + 1);
  EXPECT_EQ(mmvtest::PSNR(scene.Pixels(), first[0]), INFINITY);
  EXPECT_EQ(scene.Mapper->GetIrradianceCacheBytes(), 2 * entry);
  // The update wrote the estimator's own textures, not a kept copy shown
  // before it: step 2's copy is the one shown in the second loop, intact.
  EXPECT_FALSE(estimator->ShowsKeptTextures());
  show(2);
  EXPECT_EQ(scene.Mapper->GetIrradianceUpdateCount(), updates + 1);
  EXPECT_EQ(scene.Mapper->GetIrradianceCacheHitCount(), 4);
  EXPECT_EQ(estimator->GetIrradianceTexture(0), shown[2]);
  EXPECT_EQ(mmvtest::PSNR(scene.Pixels(), first[2]), INFINITY);

  // The pass last computed step 0 but holds step 2's copy; with step 0's
  // entry dropped, step 0 comes back through a full update, not through
  // the pass's stale record of its textures.
  scene.Mapper->SetIrradianceCacheMB(1.5 * entry / mib);
  show(0);
  EXPECT_EQ(scene.Mapper->GetIrradianceUpdateCount(), updates + 2);
  EXPECT_EQ(mmvtest::PSNR(scene.Pixels(), first[0]), INFINITY);

  // What the copies depend on: new values in the same array, then moved
  // lights, are updates whose images equal fresh renders.
  scene.Mapper->SetIrradianceCacheMB(64.0);
  show(1);
  show(2);
  const auto expectFresh = [&scene](
                             const std::function<float(int, int, int)>& value, const char* what)
  {
    ProbeScene fresh(value, 0.3);
    fresh.Materials->AddNode(1.0, 0.1, 0.9, 0.0, 1.0, 1.0, 8.0, 0.0);
    fresh.Mapper->MultipleScatteringOn();
    fresh.Renderer->GetActiveCamera()->DeepCopy(scene.Renderer->GetActiveCamera());
    fresh.Renderer->ResetCameraClippingRange();
    scene.Renderer->ResetCameraClippingRange();
    fresh.Window->Render();
    scene.Window->Render();
    EXPECT_EQ(mmvtest::PSNR(scene.Pixels(), fresh.Pixels()), INFINITY) << what;
  };
  const int before = scene.Mapper->GetIrradianceUpdateCount();
  const int hits = scene.Mapper->GetIrradianceCacheHitCount();
  vtkDataArray* array = steps[1]->GetPointData()->GetScalars();
  for (vtkIdType t = 0; t < array->GetNumberOfTuples(); ++t)
  {
    array->SetTuple1(t, 0.8 * array->GetTuple1(t));
  }
  array->Modified();
  show(1);
  expectFresh([](int i, int j, int k) { return 0.8f * MovedBlob(i, j, k); }, "new values");
  scene.Renderer->GetActiveCamera()->Azimuth(40.0);
  show(2);
  expectFresh(values[2], "moved lights");
  EXPECT_EQ(scene.Mapper->GetIrradianceUpdateCount(), before + 2);
  EXPECT_EQ(scene.Mapper->GetIrradianceCacheHitCount(), hits);
  scene.Opacity->AddPoint(1.0, 0.35);
  show(2);
  EXPECT_EQ(scene.Mapper->GetIrradianceUpdateCount(), before + 3);
  EXPECT_EQ(scene.Mapper->GetIrradianceCacheHitCount(), hits);
  // No budget, no copies.
  scene.Mapper->SetIrradianceCacheMB(0.0);
  show(2);
  EXPECT_EQ(scene.Mapper->GetIrradianceCacheBytes(), 0u);

  // Released while a kept step is shown: the next frame computes it again,
  // the same image.
  scene.Mapper->SetIrradianceCacheMB(64.0);
  show(0);
  show(2);
  show(0);
  ASSERT_TRUE(estimator->ShowsKeptTextures());
  const std::vector<unsigned char> kept = scene.Pixels();
  scene.Mapper->ReleaseGraphicsResources(scene.Window);
  EXPECT_FALSE(estimator->ShowsKeptTextures());
  EXPECT_EQ(scene.Mapper->GetIrradianceCacheBytes(), 0u);
  scene.Window->Render();
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  EXPECT_EQ(mmvtest::PSNR(scene.Pixels(), kept), INFINITY) << "after the release";
}

TEST(MultiMaterialVolumeMapper, ASeriesLongerThanTheBudgetKeepsItsFirstSteps)
{
  // Four steps, room for two: the first two kept are copies on every later
  // loop; the other two are computed each time and never push the first two
  // out (which would leave no copy for the next loop). Once with room for
  // two irradiance copies, once with room for two gradient volumes (and
  // every irradiance copy).
  ProbeScene scene(SmoothBlob, 0.3);
  std::vector<vtkSmartPointer<vtkImageData>> steps;
  for (int k = 0; k < 4; ++k)
  {
    steps.push_back(
      mmvtest::MakeVolume(Dims, [k](int i, int j, int l) { return SmoothBlob(i, j - 2 * k, l); }));
  }
  const auto show = [&scene, &steps](size_t k)
  {
    scene.Mapper->SetInputData(steps[k]);
    scene.Window->Render();
  };
  show(0);
  int dims[3];
  scene.Mapper->GetIrradianceDimensions(dims);
  // Five light-kit lights: 10 bytes an irradiance voxel; the gradient
  // volume is RGB16F on the data's points.
  const size_t entry = 10u * static_cast<size_t>(dims[0]) * dims[1] * dims[2];
  const size_t gradient = 6u * Dims * Dims * Dims;
  ASSERT_LT(entry * 4, gradient * 5 / 2) << "the second budget must hold every irradiance copy";
  std::vector<std::vector<unsigned char>> first;
  for (size_t budget : { entry * 5 / 2, gradient * 5 / 2 })
  {
    const int irradianceKept = static_cast<int>(std::min<size_t>(4, budget / entry));
    const int gradientsKept = static_cast<int>(std::min<size_t>(4, budget / gradient));
    scene.Mapper->SetIrradianceCacheMB(budget / 1048576.0);
    for (size_t k = 0; k < steps.size(); ++k)
    {
      show(k);
      if (first.size() < steps.size())
      {
        first.push_back(scene.Pixels());
      }
    }
    for (int loop = 2; loop <= 3; ++loop)
    {
      const int updates = scene.Mapper->GetIrradianceUpdateCount();
      const int hits = scene.Mapper->GetIrradianceCacheHitCount();
      const int gradients = scene.Mapper->GetGradientUploadCount();
      for (size_t k = 0; k < steps.size(); ++k)
      {
        show(k);
        EXPECT_EQ(mmvtest::PSNR(scene.Pixels(), first[k]), INFINITY)
          << budget << " bytes, loop " << loop << ", step " << k;
      }
      EXPECT_EQ(scene.Mapper->GetIrradianceCacheHitCount(), hits + irradianceKept) << budget;
      EXPECT_EQ(scene.Mapper->GetIrradianceUpdateCount(), updates + 4 - irradianceKept) << budget;
      EXPECT_EQ(scene.Mapper->GetGradientUploadCount(), gradients + 4 - gradientsKept) << budget;
      EXPECT_EQ(scene.Mapper->GetIrradianceCacheBytes(), irradianceKept * entry) << budget;
    }
  }
}

TEST(MultiMaterialVolumeMapper, CopiesOfDataThatCannotComeBackAreDropped)
{
  // Steps written into one array in place (a simulation in situ), then steps
  // whose data objects are deleted once shown: no step can come back, so
  // their copies are dropped instead of filling the budget.
  ProbeScene scene(SmoothBlob, 0.3);
  scene.Mapper->SetIrradianceCacheMB(64.0);
  vtkSmartPointer<vtkImageData> image = mmvtest::MakeVolume(Dims, SmoothBlob);
  scene.Mapper->SetInputData(image);
  scene.Window->Render();
  int dims[3];
  scene.Mapper->GetIrradianceDimensions(dims);
  const size_t entry = 10u * static_cast<size_t>(dims[0]) * dims[1] * dims[2];
  vtkDataArray* array = image->GetPointData()->GetScalars();
  for (int step = 1; step <= 3; ++step)
  {
    const int updates = scene.Mapper->GetIrradianceUpdateCount();
    for (vtkIdType t = 0; t < array->GetNumberOfTuples(); ++t)
    {
      array->SetTuple1(t, 0.9 * array->GetTuple1(t));
    }
    array->Modified();
    scene.Window->Render();
    EXPECT_EQ(scene.Mapper->GetIrradianceUpdateCount(), updates + 1) << "in place, step " << step;
    EXPECT_EQ(scene.Mapper->GetIrradianceCacheBytes(), entry) << "in place, step " << step;
  }
  // Data objects deleted once the next replaces them. VTK's ray caster
  // holds a shallow copy of its last input until it draws the next, so a
  // step's copy is dropped when the step after next is kept: never more than
  // the shown step and the one before.
  vtkWeakPointer<vtkDataArray> shown = array;
  image = nullptr;
  for (int step = 1; step <= 3; ++step)
  {
    vtkWeakPointer<vtkDataArray> before = shown;
    vtkSmartPointer<vtkImageData> next =
      mmvtest::MakeVolume(Dims, [step](int i, int j, int k) { return SmoothBlob(i, j - step, k); });
    shown = next->GetPointData()->GetScalars();
    scene.Mapper->SetInputData(next);
    next = nullptr;
    scene.Window->Render();
    EXPECT_EQ(before.GetPointer(), nullptr) << "deleted, step " << step;
    EXPECT_EQ(scene.Mapper->GetIrradianceCacheBytes(), 2 * entry) << "deleted, step " << step;
  }
}

namespace
{
/// The process's resident memory in bytes (Linux).
double ResidentBytes()
{
  long pages = 0;
  long resident = 0;
  if (FILE* statm = std::fopen("/proc/self/statm", "r"))
  {
    if (std::fscanf(statm, "%ld %ld", &pages, &resident) != 2)
    {
      resident = 0;
    }
    std::fclose(statm);
  }
  return static_cast<double>(resident) * sysconf(_SC_PAGESIZE);
}
}

TEST(MultiMaterialVolumeMapper, AnOpacityEditEveryFrameKeepsTheMemoryFlat)
{
  // 100 frames, each after an opacity edit (an update each), with time
  // steps being kept: the GPU memory stays what the first frame allocated,
  // the kept copies hold only the current lighting's step, and the process
  // does not grow.
  ProbeScene scene(SmoothBlob, 0.3);
  scene.Mapper->SetIrradianceCacheMB(64.0);
  scene.Window->Render();
  const vtkIdType memory = scene.Mapper->GetMultiMaterialMemoryBytes();
  int dims[3];
  scene.Mapper->GetIrradianceDimensions(dims);
  const size_t entry = 10u * static_cast<size_t>(dims[0]) * dims[1] * dims[2];
  double settled = 0.0;
  const int updates = scene.Mapper->GetIrradianceUpdateCount();
  for (int frame = 1; frame <= 100; ++frame)
  {
    scene.Opacity->AddPoint(1.0, frame % 2 ? 0.31 : 0.3);
    scene.Window->Render();
    if (frame == 10)
    {
      settled = ResidentBytes();
    }
  }
  EXPECT_EQ(scene.Mapper->GetIrradianceUpdateCount(), updates + 100);
  EXPECT_EQ(scene.Mapper->GetMultiMaterialMemoryBytes(), memory);
  EXPECT_EQ(scene.Mapper->GetIrradianceCacheBytes(), entry);
  // A leak of the smallest per-update allocation (a 256 x 256 pre-integration
  // table, 1 MB) would add 90 MB over the last 90 frames.
  const double grown = ResidentBytes() - settled;
  std::printf("resident growth over 90 updates: %.2f MB\n", grown / 1048576.0);
  EXPECT_GT(settled, 0.0);
#if defined(__SANITIZE_ADDRESS__)
  // AddressSanitizer keeps freed blocks in quarantine (256 MB) instead of
  // reusing them, so the resident size grows with every block freed (38 MB
  // here with the shadow passes on the GPU); LeakSanitizer checks for leaks
  // in that build instead.
#else
  EXPECT_LT(grown, 16.0 * 1048576.0) << grown / 1048576.0 << " MB";
#endif
}

TEST(MultiMaterialVolumeMapper, StageReportNamesEveryStageInsideTheWholeUpdate)
{
  // An opacity edit with multiple scattering runs every stage of an update
  // but the probe and the pre-filter; each is reported, none is negative, and
  // the stages that run one after another fit in the whole update.
  ProbeScene scene(ThinShell, 0.8);
  scene.Materials->AddNode(1.0, 0.1, 0.9, 0.0, 1.0, 1.0, 8.0, 0.0);
  scene.Mapper->MultipleScatteringOn();
  scene.Window->Render();
  scene.Opacity->AddPoint(1.0, 0.6);
  scene.Window->Render();
  std::map<std::string, double> seconds;
  std::istringstream report(scene.Mapper->GetLastIrradianceStages());
  std::string part;
  while (std::getline(report, part, ','))
  {
    // " name words 0.012 s"
    std::istringstream words(part);
    std::string word, name;
    std::vector<std::string> all;
    while (words >> word)
    {
      all.push_back(word);
    }
    ASSERT_GE(all.size(), 3u) << part;
    EXPECT_EQ(all.back(), "s") << part;
    for (size_t w = 0; w + 2 < all.size(); ++w)
    {
      name += (w ? " " : "") + all[w];
    }
    seconds[name] = std::stod(all[all.size() - 2]);
  }
  const char* const names[] = { "probe", "prefilter", "shadow table", "inputs", "setup", "shadows",
    "diffusion", "write", "keep", "pass", "total" };
  for (const char* name : names)
  {
    ASSERT_EQ(seconds.count(name), 1u) << name;
    EXPECT_GE(seconds[name], 0.0) << name;
  }
  EXPECT_EQ(seconds.size(), 11u);
  EXPECT_GT(seconds["shadows"], 0.0);
  EXPECT_GT(seconds["diffusion"], 0.0);
  // Reported to the millisecond: each rounding may add half of one.
  EXPECT_LE(seconds["setup"] + seconds["shadows"] + seconds["diffusion"] + seconds["write"],
    seconds["pass"] + 0.002);
  EXPECT_LE(seconds["prefilter"] + seconds["shadow table"] + seconds["inputs"] + seconds["pass"] +
      seconds["keep"],
    seconds["total"] + 0.002);
}

TEST(MultiMaterialVolumeMapper, KeptScratchGivesTheImagesOfFreshScratch)
{
  // The pass keeps its float scratch between updates (no allocation per
  // update); nothing of an earlier update may leak into a later one. The
  // shadow rays in passes on any machine: on a CPU rasterizer the CPU's
  // sweeps write every texture there and the passes' scratch goes unused.
  ProbeScene kept(ThinShell, 0.8);
  ProbeScene fresh(ThinShell, 0.8);
  fresh.Mapper->GetIrradianceEstimator()->KeepScratchOff();
  for (ProbeScene* scene : { &kept, &fresh })
  {
    scene->Materials->AddNode(1.0, 0.1, 0.9, 0.0, 1.0, 1.0, 8.0, 0.0);
    scene->Mapper->MultipleScatteringOn();
    scene->Mapper->GetIrradianceEstimator()->SetShadowRaysPlace(vtkIrradianceEstimator::OnGPU);
  }
  const std::function<void(ProbeScene&)> changes[] = {
    [](ProbeScene&) {},
    [](ProbeScene& s) { s.Renderer->GetActiveCamera()->Azimuth(30.0); },
    [](ProbeScene& s) { s.Opacity->AddPoint(1.0, 0.6); },
    [](ProbeScene& s) { s.Mapper->MultipleScatteringOff(); },
    [](ProbeScene& s) { s.Renderer->GetActiveCamera()->Elevation(20.0); },
    [](ProbeScene& s) { s.Mapper->MultipleScatteringOn(); },
  };
  int step = 0;
  for (const auto& change : changes)
  {
    for (ProbeScene* scene : { &kept, &fresh })
    {
      change(*scene);
      scene->Renderer->ResetCameraClippingRange();
      scene->Window->Render();
    }
    EXPECT_EQ(mmvtest::PSNR(kept.Pixels(), fresh.Pixels()), INFINITY) << "change " << step;
    EXPECT_EQ(fresh.Mapper->GetIrradianceEstimator()->GetScratchMemoryBytes(), 0);
    ++step;
  }
  EXPECT_GE(kept.Mapper->GetIrradianceUpdateCount(), 5);
  // With scattering the scratch is the fine pair and the diffusion grid's;
  // without, one fine texture; both with the light kit's dim lights' grid.
  int dims[3];
  kept.Mapper->GetIrradianceDimensions(dims);
  const vtkIdType voxels = static_cast<vtkIdType>(dims[0]) * dims[1] * dims[2];
  vtkIdType lightGridVoxels = 1;
  for (const int d : dims)
  {
    lightGridVoxels *= mmv::LightGridDimension(d, mmv::DimLightStride);
  }
  EXPECT_GT(kept.Mapper->GetIrradianceEstimator()->GetScratchMemoryBytes(), 2 * 16 * voxels);
  kept.Mapper->MultipleScatteringOff();
  kept.Window->Render();
  vtkIrradianceEstimator* estimator = kept.Mapper->GetIrradianceEstimator();
  EXPECT_EQ(estimator->GetScratchMemoryBytes(), 16 * (voxels + lightGridVoxels));
  // The shadow rays and the final write on the CPU (a CPU rasterizer's
  // default, asked for here with the classes they need) keep their
  // buffers too: the sweeps' targets' contents (the key light's channel,
  // the dim lights' four) and a texture of four lights' texels; the
  // passes' scratch stays as it was.
  estimator->SetShadowRaysPlace(vtkIrradianceEstimator::OnCPU);
  estimator->SetClassification(vtkIrradianceEstimator::OnCPU);
  kept.Renderer->GetActiveCamera()->Azimuth(10.0);
  kept.Window->Render();
  EXPECT_EQ(estimator->GetNumberOfLightsSweptOnCPU(), 5);
  EXPECT_EQ(estimator->GetNumberOfTexturesWrittenOnCPU(), 2);
  EXPECT_EQ(estimator->GetScratchMemoryBytes(),
    16 * (voxels + lightGridVoxels) + 4 * (voxels + 4 * lightGridVoxels) + 2 * 4 * voxels);
}

namespace
{
// Counts the deaths of the objects it watches (VTK here is built without
// vtkDebugLeaks, so DeleteEvent is the live-object count we have).
struct DeletionWatch
{
  int Watched = 0;
  int Deleted = 0;
  vtkNew<vtkCallbackCommand> Callback;

  DeletionWatch()
  {
    this->Callback->SetClientData(this);
    this->Callback->SetCallback([](vtkObject*, unsigned long, void* watch, void*)
      { ++static_cast<DeletionWatch*>(watch)->Deleted; });
  }
  void Watch(vtkObject* object)
  {
    object->AddObserver(vtkCommand::DeleteEvent, this->Callback);
    ++this->Watched;
  }
  int Alive() const { return this->Watched - this->Deleted; }
};

// Someone else's pass in the volume's keys, as dual depth peeling puts itself
// there: its owner appends and removes it, and our pass must not unbalance it.
class ForeignRenderPass : public vtkOpenGLRenderPass
{
public:
  static ForeignRenderPass* New();
  vtkTypeMacro(ForeignRenderPass, vtkOpenGLRenderPass);
  void Render(const vtkRenderState*) override {}

protected:
  ForeignRenderPass() { this->SetActiveDrawBuffers(1); }
};
vtkStandardNewMacro(ForeignRenderPass);

vtkMultiMaterialShaderHook* FindPass(vtkInformation* keys)
{
  vtkInformationObjectBaseVectorKey* key = vtkOpenGLRenderPass::RenderPasses();
  for (int i = 0; keys && keys->Has(key) && i < key->Length(keys); ++i)
  {
    if (auto* pass = vtkMultiMaterialShaderHook::SafeDownCast(key->Get(keys, i)))
    {
      return pass;
    }
  }
  return nullptr;
}

// A lit 16x16 scene of `image` shaded by a multi-material mapper, ready to
// render. Members die in reverse order: the scene (volume, keys, window)
// before the mapper.
struct LitMaterialScene
{
  vtkSmartPointer<vtkMultiMaterialVolumeMapper> Mapper =
    vtkSmartPointer<vtkMultiMaterialVolumeMapper>::New();
  vtkNew<vtkMaterialTransferFunction> Materials;
  mmvtest::Scene Scene{ 16 };

  explicit LitMaterialScene(vtkImageData* image)
  {
    this->Materials->AddNode(4.0, 0.3, 0.7, 0.3, 20.0, 1.0, 0.0, 0.0);
    this->Mapper->SetInputData(image);
    this->Mapper->SetMaterialTransferFunction(this->Materials);
    this->Scene.Color->AddRGBPoint(0.0, 1.0, 1.0, 1.0);
    this->Scene.Opacity->AddPoint(0.0, 0.1);
    this->Scene.Opacity->AddPoint(8.0, 0.5);
    this->Scene.Volume->SetMapper(this->Mapper);
    this->Scene.FrameBounds(image->GetBounds());
    const double from[3] = { 4.0, 4.0, 100.0 };
    const double to[3] = { 4.0, 4.0, 4.0 };
    this->Scene.AddDirectionalLight(from, to);
  }
};
}

TEST(MultiMaterialVolumeMapper, MappersVolumesAndPassesAreFreed)
{
  // VTK 9.2's RenderPasses key Append() registers twice and only Remove()
  // gives both back: LeakSanitizer found one pass leaked per mapper. Each
  // round builds a lit scene, renders it (which installs the pass) and drops
  // it in one of three orders; every watched object must then be gone (the
  // live count back to zero).
  DeletionWatch watch;
  auto image = mmvtest::MakeVolume(9, [](int i, int, int) { return static_cast<float>(i); });
  for (int round = 0; round < 6; ++round)
  {
    const int order = round % 3; // 0: volume dies first, 1: mapper first, 2: pass removed first
    vtkNew<ForeignRenderPass> foreign;
    watch.Watch(foreign);
    {
      LitMaterialScene lit(image);
      vtkSmartPointer<vtkMultiMaterialVolumeMapper>& mapper = lit.Mapper;
      vtkMaterialTransferFunction* materials = lit.Materials;
      mmvtest::Scene& scene = lit.Scene;
      {
        vtkNew<vtkInformation> newKeys; // the volume's only: they die with it
        scene.Volume->SetPropertyKeys(newKeys);
      }
      vtkInformation* keys = scene.Volume->GetPropertyKeys();
      watch.Watch(keys);
      vtkOpenGLRenderPass::RenderPasses()->Append(keys, foreign);
      scene.Window->Render();
      ASSERT_TRUE(mapper->GetMultiMaterialActive());
      vtkMultiMaterialShaderHook* pass = FindPass(keys);
      ASSERT_NE(pass, nullptr) << "the render installs the pass in the volume's keys";
      EXPECT_EQ(vtkOpenGLRenderPass::RenderPasses()->Length(keys), 2);
      EXPECT_EQ(vtkOpenGLRenderPass::RenderPasses()->Get(keys, 1), foreign.Get());
      for (vtkObject* object : std::initializer_list<vtkObject*>{ pass, mapper.Get(),
             scene.Volume.Get(), scene.Renderer.Get(), scene.Window.Get(), materials })
      {
        watch.Watch(object);
      }
      if (order == 2)
      {
        // A fallback render takes the pass out of the keys.
        mapper->SetBlendModeToMaximumIntensity();
        scene.Window->Render();
        ASSERT_FALSE(mapper->GetMultiMaterialActive());
        EXPECT_EQ(FindPass(keys), nullptr);
      }
      // The foreign pass's owner takes it out, as vtkOpenGLRenderPass does.
      vtkOpenGLRenderPass::RenderPasses()->Remove(keys, foreign);
      if (order == 1)
      {
        scene.Volume->SetMapper(nullptr);
        mapper = nullptr;
      }
      scene.Window->Finalize();
      // Order 0: the scene, with the volume and its keys, goes before `mapper`;
      // order 1: the volume and its keys outlive the mapper.
    }
  }
  std::printf("deletion watch: %d objects watched, %d deleted\n", watch.Watched, watch.Deleted);
  EXPECT_EQ(watch.Alive(), 0) << "objects still alive out of " << watch.Watched;
}

namespace
{
// The counted classes a rendered mapper brings to life: itself, its render
// pass, its two pre-integration tables (segments, shadows), its irradiance
// input cache and the error probe's.
constexpr int ObjectsPerMapper = 6;

// Renders a lit multi-material scene once, so that the mapper makes its GL
// resources (tables, gradient, irradiance volume, shader) and installs its
// pass in the volume's keys; returns the mapper (the scene dies here).
vtkSmartPointer<vtkMultiMaterialVolumeMapper> RenderOnce(vtkImageData* image)
{
  LitMaterialScene lit(image);
  vtkSmartPointer<vtkMultiMaterialVolumeMapper> mapper = lit.Mapper;
  lit.Scene.Window->Render();
  EXPECT_TRUE(mapper->GetMultiMaterialActive());
  EXPECT_EQ(mapper->GetIrradianceUpdateCount(), 1);
  EXPECT_EQ(vtkMultiMaterialLiveObjects::GetCount("vtkMultiMaterialVolumeMapper"),
    vtkMultiMaterialLiveObjects::GetCount("vtkMultiMaterialShaderHook"));
  lit.Scene.Window->Finalize();
  return mapper;
}
}

TEST(MultiMaterialVolumeMapper, CreateRenderDestroyLoopKeepsLiveObjectCount)
{
  // vtkDebugLeaks is off in Debian's VTK, so the project's classes count
  // their live instances (vtkMultiMaterialLiveObjects). Rounds of create,
  // render (GL resources made, the pass in the volume's keys) and destroy
  // must leave the count where it was.
  auto image = mmvtest::MakeVolume(9, [](int i, int, int) { return static_cast<float>(i); });
  const int start = vtkMultiMaterialLiveObjects::GetCount();
  for (int round = 0; round < 5; ++round)
  {
    {
      vtkSmartPointer<vtkMultiMaterialVolumeMapper> mapper = RenderOnce(image);
      EXPECT_EQ(vtkMultiMaterialLiveObjects::GetCount(), start + ObjectsPerMapper)
        << "round " << round << ": one mapper with its pass, tables and cache";
    }
    const int alive = vtkMultiMaterialLiveObjects::GetCount();
    std::printf("round %d: %d live counted objects (start %d)\n", round, alive, start);
    EXPECT_EQ(alive, start) << "round " << round << " left objects alive";
  }

  // The count sees a leak: a mapper kept by one extra reference keeps its
  // pass, tables and cache; giving the reference back frees them.
  vtkMultiMaterialVolumeMapper* leaked = nullptr;
  {
    vtkSmartPointer<vtkMultiMaterialVolumeMapper> mapper = RenderOnce(image);
    leaked = mapper;
    leaked->Register(nullptr);
  }
  const int withLeak = vtkMultiMaterialLiveObjects::GetCount();
  leaked->UnRegister(nullptr);
  std::printf("one mapper leaked: %d live counted objects; given back: %d\n", withLeak,
    vtkMultiMaterialLiveObjects::GetCount());
  EXPECT_EQ(withLeak, start + ObjectsPerMapper);
  EXPECT_EQ(vtkMultiMaterialLiveObjects::GetCount(), start);
}
