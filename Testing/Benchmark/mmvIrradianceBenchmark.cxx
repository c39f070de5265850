// How long one irradiance update takes on the CT-sized scene (the head
// resampled to 256 x 256 x 128), against the number of lights, the
// scattering strength s and the irradiance resolution, and what layered
// draws and empty-voxel skipping save; beside it, one ray-cast frame of ours
// and of VTK's Phong with the same lights, measured in the same run.
//
//   mmvIrradianceBenchmark --out DIR [--size N] [--reps N] [--head FILE.vti] [--quick]
//                          [--only SECTION[,SECTION...]]  (updates, resolution,
//                          estimation, raycast, orbit, compute, diffusion,
//                          tolerance, progress; all but raycast, orbit, compute,
//                          diffusion, tolerance and progress by default)
//                          [--orbit-steps N] [--orbit-interactive-frames K]
//                          [--image-sample-distance D] [--lights N]  (raycast: both
//                          mappers, no auto-adjust, N scene lights, default 5)
//
// Each configuration moves every light a little (so every light is
// recomputed), renders, and reads the mapper's irradiance time (glFinish
// before and after); medians over --reps updates. Writes
// DIR/irradiance_updates.csv, DIR/ct_resolution.csv: the still frame
// after a light move (update + ray cast) against a VTK Phong frame, and the
// image's PSNR against the full-resolution irradiance, per irradiance scale;
// and DIR/shadow_estimation.csv: piecewise against full shadow rays, the
// update and the image's PSNR against the full rays', per chunk length K.
// Not a test: it asserts nothing about timings.
#include "mmvBenchmarkScenes.h"
#include "mmvIrradianceBenchmarkModes.h"
#include "mmvTestWindow.h"

#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkImageData.h"
#include "vtkImageErrorMetrics.h"
#include "vtkIrradianceEstimator.h"
#include "vtkLight.h"
#include "vtkLightKit.h"
#include "vtkMultiMaterialParameters.h"
#include "vtkMultiMaterialVolumeMapper.h"
#include "vtkNew.h"
#include "vtkOpenGLGPUVolumeRayCastMapper.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include "vtkWindowToImageFilter.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <sys/stat.h>
#include <vector>

namespace mmvirradiance
{
namespace
{
/// Directions toward the lights: the first five roughly where ParaView's
/// light kit puts its key, fill, back and head lights around a front view.
const double LightDirections[8][3] = { { 0.3, -0.8, 0.9 }, { -0.6, -0.9, -0.3 }, { 0.9, 0.8, 0.2 },
  { -0.9, 0.8, 0.2 }, { 0.0, -1.0, 0.1 }, { 0.5, 0.2, -0.9 }, { -0.4, 0.3, 0.9 },
  { 0.8, -0.3, -0.4 } };
} // namespace

double Median(std::vector<double> v)
{
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n == 0 ? std::nan("") : (n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]));
}

std::string Join(const int v[3])
{
  std::ostringstream s;
  s << v[0] << "x" << v[1] << "x" << v[2];
  return s.str();
}

vtkSmartPointer<vtkImageData> Grab(vtkRenderWindow* window)
{
  vtkNew<vtkWindowToImageFilter> filter;
  filter->SetInput(window);
  filter->ReadFrontBufferOff();
  filter->Update();
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->DeepCopy(filter->GetOutput());
  return image;
}

double TimedRender(vtkRenderWindow* window)
{
  const auto start = std::chrono::steady_clock::now();
  window->Render();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

Bench::Bench(const mmvbench::SceneSpec& scene, int size, bool ours)
{
  this->Window->SetOffScreenRendering(1);
  this->Window->SetSize(size, size);
  this->Window->SetMultiSamples(0);
  this->Window->AddRenderer(this->Renderer);
  this->Renderer->AutomaticLightCreationOff();
  this->Renderer->SetBackground(0.1, 0.1, 0.12);
  this->Property->SetColor(scene.Color);
  this->Property->SetScalarOpacity(scene.Opacity);
  this->Property->SetScalarOpacityUnitDistance(scene.UnitDistance);
  this->Property->SetInterpolationTypeToLinear();
  this->Materials->DeepCopy(scene.Materials);
  if (ours)
  {
    vtkNew<vtkMultiMaterialVolumeMapper> mapper;
    mapper->SetMaterialTransferFunction(this->Materials);
    mapper->TimeStagesOn();
    this->Ours = mapper;
    this->Mapper = mapper;
  }
  else
  {
    this->Mapper = vtkSmartPointer<vtkOpenGLGPUVolumeRayCastMapper>::New();
    this->Property->ShadeOn();
  }
  this->Mapper->SetInputData(scene.Image);
  this->Volume->SetMapper(this->Mapper);
  this->Volume->SetProperty(this->Property);
  this->Renderer->AddVolume(this->Volume);
  scene.Image->GetCenter(this->Center);
  this->Renderer->ResetCamera();
  this->Renderer->GetActiveCamera()->Elevation(-80.0);
  this->Renderer->GetActiveCamera()->OrthogonalizeViewUp();
  this->Renderer->ResetCamera();
  this->Renderer->GetActiveCamera()->Zoom(1.3);
}

void Bench::SetLightCount(int count)
{
  this->Renderer->RemoveAllLights();
  this->Lights.clear();
  for (int l = 0; l < count; ++l)
  {
    vtkNew<vtkLight> light;
    light->SetLightTypeToSceneLight();
    light->PositionalOff();
    light->SetIntensity(l == 0 ? 1.0 : 0.4);
    this->Renderer->AddLight(light);
    this->Lights.push_back(light.Get());
  }
  this->PlaceLights();
}

void Bench::PlaceLights(double turn)
{
  this->Turn = turn >= 0.0 ? turn : this->Turn + 0.02;
  for (size_t l = 0; l < this->Lights.size(); ++l)
  {
    const double* d = LightDirections[l];
    const double c = std::cos(this->Turn);
    const double s = std::sin(this->Turn);
    const double x = c * d[0] - s * d[1];
    const double y = s * d[0] + c * d[1];
    this->Lights[l]->SetFocalPoint(this->Center);
    this->Lights[l]->SetPosition(this->Center[0] + x, this->Center[1] + y, this->Center[2] + d[2]);
  }
}

void Bench::SetScattering(double strength)
{
  vtkNew<vtkMaterialTransferFunction> copy;
  copy->DeepCopy(this->Materials);
  this->Materials->RemoveAllNodes();
  for (int i = 0; i < copy->GetSize(); ++i)
  {
    double node[mmv::MaterialParameterCount + 1];
    copy->GetNode(i, node);
    node[1 + mmv::Scattering] = strength;
    this->Materials->AddNode(node[0], node[1 + mmv::Ambient], node[1 + mmv::Diffuse],
      node[1 + mmv::Specular], node[1 + mmv::Shininess], node[1 + mmv::Attenuation],
      node[1 + mmv::Scattering], node[1 + mmv::Reflection]);
  }
}

void UseLightKit(Bench& bench)
{
  bench.Renderer->RemoveAllLights();
  vtkNew<vtkLightKit> kit;
  kit->AddLightsToRenderer(bench.Renderer);
}
} // namespace mmvirradiance

namespace
{
using mmvirradiance::Bench;
using mmvirradiance::Grab;
using mmvirradiance::Join;
using mmvirradiance::Median;

struct Config
{
  std::string Sweep;
  int Lights = 5;
  double S = 8.0;
  double Scale = 0.5;
  bool Layered = true;
  bool SkipEmpty = true;
  bool Compute = true; // compute dispatches (fragment draws without OpenGL 4.3)
};

/// The command line's settings.
struct Options
{
  std::string Out = "irradiance_benchmark";
  std::string Head = MMV_HEADSQ_PATH;
  int Size = 400;
  int Reps = 3;
  bool Quick = false;
  std::string Only;                 // one section: updates, resolution or estimation
  double ImageSampleDistance = 1.0; // raycast: > 1 as in ParaView's interactive frames
  int RaycastLights = 5;            // raycast: scene lights
  int OrbitSteps = 6;               // orbit: camera steps of 10 degrees
  int OrbitInteractive = 8;         // orbit: interactive frames per step
  double ProbeBound = -1.0;         // probe: IrradianceErrorBound (< 0: the default)
  std::string ProbeScenes = "synthetic,headsq,orbital,ct";
};

/// Reads the command line into `o`; false (and a message) on an unknown
/// argument.
bool ParseOptions(int argc, char* argv[], Options& o)
{
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    auto next = [&]() { return i + 1 < argc ? std::string(argv[++i]) : std::string(); };
    if (arg == "--out")
    {
      o.Out = next();
    }
    else if (arg == "--size")
    {
      o.Size = std::max(16, std::atoi(next().c_str()));
    }
    else if (arg == "--reps")
    {
      o.Reps = std::max(1, std::atoi(next().c_str()));
    }
    else if (arg == "--head")
    {
      o.Head = next();
    }
    else if (arg == "--quick")
    {
      o.Quick = true;
    }
    else if (arg == "--only")
    {
      o.Only = next();
    }
    else if (arg == "--lights")
    {
      o.RaycastLights = std::max(0, std::min(8, std::atoi(next().c_str())));
    }
    else if (arg == "--orbit-steps")
    {
      o.OrbitSteps = std::max(1, std::atoi(next().c_str()));
    }
    else if (arg == "--orbit-interactive-frames")
    {
      o.OrbitInteractive = std::max(1, std::atoi(next().c_str()));
    }
    else if (arg == "--probe-bound")
    {
      o.ProbeBound = std::atof(next().c_str());
    }
    else if (arg == "--probe-scenes")
    {
      o.ProbeScenes = next();
    }
    else if (arg == "--image-sample-distance")
    {
      o.ImageSampleDistance = std::atof(next().c_str());
    }
    else
    {
      std::cerr << "unknown argument " << arg << "\n";
      return false;
    }
  }
  return true;
}

/// Whether section `name` runs: all of them without --only, else those named
/// in its comma-separated list.
bool Wanted(const std::string& only, const std::string& name)
{
  if (only.empty())
  {
    return name != "raycast";
  }
  std::stringstream list(only);
  std::string item;
  while (std::getline(list, item, ','))
  {
    if (item == name)
    {
      return true;
    }
  }
  return false;
}

/// Whether section `name`, which only runs when named, was named by --only.
bool Alone(const std::string& only, const std::string& name)
{
  return Wanted(only, name) && !only.empty();
}

/// The configurations of the updates section: sweeps of the light count,
/// the scattering, the irradiance scale, and each saving switched off.
std::vector<Config> MakeConfigs(bool quick)
{
  std::vector<Config> configs;
  const std::vector<int> lightCounts =
    quick ? std::vector<int>{ 1, 5 } : std::vector<int>{ 1, 2, 5, 8 };
  const std::vector<double> strengths =
    quick ? std::vector<double>{ 0, 8 } : std::vector<double>{ 0, 8, 20, 100 };
  const std::vector<double> scales =
    quick ? std::vector<double>{ 0.25, 0.5 } : std::vector<double>{ 0.25, 0.35, 0.5, 0.75, 1.0 };
  for (int lights : lightCounts)
  {
    configs.push_back({ "lights", lights, 8.0, 0.5 });
  }
  for (double s : strengths)
  {
    configs.push_back({ "scattering", 5, s, 0.5 });
  }
  for (double s : { 0.0, 8.0 })
  {
    for (double scale : scales)
    {
      configs.push_back({ "resolution", 5, s, scale });
    }
  }
  for (double s : { 0.0, 8.0 })
  {
    configs.push_back({ "draws", 5, s, 0.5, false, true });
    configs.push_back({ "empty-space", 5, s, 0.5, true, false });
    configs.push_back({ "fragment", 5, s, 0.5, true, true, false });
  }
  return configs;
}

/// Compute dispatches against layered fragment draws, alternating update
/// by update (the machine may be shared): 5 lights, scale 0.5. Writes
/// OUT/compute_vs_fragment.csv.
int RunComputeVsFragment(Bench& ours, int reps, const std::string& out)
{
  ours.SetLightCount(5);
  ours.Ours->SetIrradianceScale(0.5);
  vtkIrradianceEstimator* pass = ours.Ours->GetIrradianceEstimator();
  // The two GPU executors: a CPU rasterizer's default sweeps the
  // directional lights on the CPU instead.
  pass->SetShadowRaysPlace(vtkIrradianceEstimator::OnGPU);
  std::ofstream csv(out + "/compute_vs_fragment.csv");
  csv << "scattering,compute_update_s,fragment_update_s,fragment_over_compute,renderer\n";
  std::string renderer;
  for (double s : { 0.0, 8.0 })
  {
    ours.SetScattering(s);
    std::vector<double> compute, fragment, ratios;
    for (int r = 0; r <= reps; ++r) // the first repetition warms both up
    {
      std::vector<double> pair;
      for (int kind :
        { vtkIrradianceEstimator::ComputeDispatches, vtkIrradianceEstimator::FragmentDraws })
      {
        pass->SetComputeShaders(kind);
        std::vector<double> update;
        ours.Frames(
          1, [&]() { ours.PlaceLights(); }, &update);
        pair.push_back(update.back());
      }
      if (r > 0)
      {
        compute.push_back(pair[0]);
        fragment.push_back(pair[1]);
        ratios.push_back(pair[1] / pair[0]);
      }
    }
    renderer = mmvtest::RendererString(ours.Window);
    csv << s << "," << Median(compute) << "," << Median(fragment) << "," << Median(ratios) << ",\""
        << renderer << "\"\n";
    std::printf("s = %g: compute %.4f s, fragment %.4f s, fragment / compute %.2f (%s)\n", s,
      Median(compute), Median(fragment), Median(ratios), renderer.c_str());
  }
  return 0;
}

/// What progress reporting costs an update: with a ProgressEvent observer
/// on the mapper (as ParaView's representation has; the pass then reports
/// after glFinish, per light and per texture's diffusion) and without,
/// alternating update by update (the machine may be shared): 5 lights,
/// scale 0.5 and 1, s = 0 and 8. The mapper's default: no stage timing.
/// Writes OUT/progress_overhead.csv.
int RunProgressOverhead(Bench& ours, int reps, const std::string& out)
{
  ours.SetLightCount(5);
  ours.Ours->TimeStagesOff();
  int reports = 0;
  vtkNew<vtkCallbackCommand> observer;
  observer->SetClientData(&reports);
  observer->SetCallback(
    [](vtkObject*, unsigned long, void* client, void*) { ++*static_cast<int*>(client); });
  std::ofstream csv(out + "/progress_overhead.csv");
  csv << "irradiance_scale,scattering,reports_per_update,with_progress_update_s,"
         "without_progress_update_s,with_over_without,renderer\n";
  for (double scale : { 0.5, 1.0 })
  {
    ours.Ours->SetIrradianceScale(scale);
    for (double s : { 0.0, 8.0 })
    {
      ours.SetScattering(s);
      std::vector<double> with, without, ratios;
      int reportsPerUpdate = 0;
      for (int r = 0; r <= reps; ++r) // the first repetition warms both up
      {
        // Which goes first alternates, so neither profits from the order.
        std::vector<double> pair(2);
        for (bool observed : { r % 2 == 0, r % 2 != 0 })
        {
          const unsigned long tag =
            observed ? ours.Ours->AddObserver(vtkCommand::ProgressEvent, observer) : 0;
          reports = 0;
          std::vector<double> update;
          ours.Frames(
            1, [&]() { ours.PlaceLights(); }, &update);
          pair[observed ? 0 : 1] = update.back();
          if (observed)
          {
            reportsPerUpdate = reports;
            ours.Ours->RemoveObserver(tag);
          }
        }
        if (r > 0)
        {
          with.push_back(pair[0]);
          without.push_back(pair[1]);
          ratios.push_back(pair[0] / pair[1]);
        }
      }
      const std::string renderer = mmvtest::RendererString(ours.Window);
      csv << scale << "," << s << "," << reportsPerUpdate << "," << Median(with) << ","
          << Median(without) << "," << Median(ratios) << ",\"" << renderer << "\"\n";
      std::printf("scale %.2g, s = %g: %d reports, with progress %.4f s, without %.4f s, "
                  "with / without %.4f (%s)\n",
        scale, s, reportsPerUpdate, Median(with), Median(without), Median(ratios),
        renderer.c_str());
    }
  }
  return 0;
}

/// The diffusion's two integrators, each in its own window (switching one
/// pass between them would re-upload the volume), updates alternating window
/// by window (the machine may be shared): 5 lights, scale 0.5 and the
/// default scale, several s; the image's PSNR of the series against backward
/// Euler at the same lights. Writes OUT/diffusion_integrators.csv.
int RunDiffusionIntegrators(
  const mmvbench::SceneSpec& scene, int size, Bench& ours, int reps, const std::string& out)
{
  Bench euler(scene, size, true);
  Bench* benches[2] = { &ours, &euler };
  ours.Ours->SetExponentialDiffusion(true);
  euler.Ours->SetExponentialDiffusion(false);
  std::ofstream csv(out + "/diffusion_integrators.csv");
  csv << "scattering,irradiance_scale,diffusion_grid,exponential_passes,backward_euler_passes,"
         "exponential_update_s,backward_euler_update_s,backward_euler_over_exponential,"
         "psnr_exponential_vs_backward_euler_db,renderer\n";
  std::string renderer;
  for (double scale : { 0.5, 0.0 })
  {
    for (double s : { 8.0, 20.0, 100.0 })
    {
      for (Bench* b : benches)
      {
        b->SetLightCount(5);
        b->Ours->SetIrradianceScale(scale);
        b->SetScattering(s);
        b->PlaceLights(0.5);
        b->Window->Render(); // the volume, tables and textures: not timed
      }
      std::vector<double> times[2], ratios;
      int passes[2] = { 0, 0 };
      for (int r = 0; r < reps; ++r)
      {
        double pair[2];
        for (int e = 0; e < 2; ++e)
        {
          std::vector<double> update;
          benches[e]->Frames(
            1, [&]() { benches[e]->PlaceLights(); }, &update);
          pair[e] = update.back();
          passes[e] = benches[e]->Ours->GetIrradianceEstimator()->GetDiffusionPasses();
        }
        times[0].push_back(pair[0]);
        times[1].push_back(pair[1]);
        ratios.push_back(pair[1] / pair[0]);
      }
      vtkSmartPointer<vtkImageData> images[2];
      for (int e = 0; e < 2; ++e)
      {
        benches[e]->PlaceLights(1.0);
        benches[e]->Window->Render();
        images[e] = Grab(benches[e]->Window);
      }
      vtkNew<vtkImageErrorMetrics> metrics;
      metrics->Compute(images[0], images[1]);
      int dims[3];
      ours.Ours->GetIrradianceEstimator()->GetDiffusionGridDimensions(dims);
      renderer = mmvtest::RendererString(ours.Window);
      csv << s << "," << scale << "," << Join(dims) << "," << passes[0] << "," << passes[1] << ","
          << Median(times[0]) << "," << Median(times[1]) << "," << Median(ratios) << ","
          << metrics->GetPSNR() << ",\"" << renderer << "\"\n";
      std::printf("s = %g, scale %g, diffusion grid %s: exponential %d passes %.4f s, backward "
                  "Euler %d passes %.4f s, ratio %.2f, PSNR %.1f dB (%s)\n",
        s, scale, Join(dims).c_str(), passes[0], Median(times[0]), passes[1], Median(times[1]),
        Median(ratios), metrics->GetPSNR(), renderer.c_str());
    }
  }
  return 0;
}

/// Camera-only frames (the irradiance cached): ours against Phong with the
/// same lights, interleaved, 5x the repetitions of the others.
int RunRaycast(Bench& ours, Bench& phong, const Options& o)
{
  ours.SetLightCount(o.RaycastLights);
  phong.SetLightCount(o.RaycastLights);
  for (Bench* bench : { &ours, &phong })
  {
    bench->Mapper->SetAutoAdjustSampleDistances(0);
    bench->Mapper->SetImageSampleDistance(static_cast<float>(o.ImageSampleDistance));
  }
  ours.Ours->TimeStagesOff(); // its glFinish calls would stall the frames
  ours.Window->Render();
  phong.Window->Render();
  const int tables = ours.Ours->GetPreIntegrationCount();
  std::vector<double> casts;
  std::vector<double> phongFrames;
  std::vector<double> ratios;
  std::vector<double> prepare;
  for (int r = 0; r < 5 * o.Reps; ++r)
  {
    casts.push_back(ours.Frames(1, [&]() { ours.Renderer->GetActiveCamera()->Azimuth(0.5); }));
    prepare.push_back(ours.Ours->GetLastPrepareSeconds());
    phongFrames.push_back(
      phong.Frames(1, [&]() { phong.Renderer->GetActiveCamera()->Azimuth(0.5); }));
    ratios.push_back(casts.back() / phongFrames.back());
  }
  std::printf("image sample distance %g: ray cast %.4f s (CPU preparation %.4f s), Phong %.4f s, "
              "median ratio %.2f (tables rebuilt %d times)\n",
    o.ImageSampleDistance, Median(casts), Median(prepare), Median(phongFrames), Median(ratios),
    ours.Ours->GetPreIntegrationCount() - tables);
  return 0;
}

/// The updates section: one irradiance update, a camera-only frame of ours
/// and a Phong frame per configuration. Writes OUT/irradiance_updates.csv.
void RunUpdates(Bench& ours, Bench& phong, const std::vector<Config>& configs, const Options& o)
{
  std::ofstream csv(o.Out + "/irradiance_updates.csv");
  csv << "sweep,lights,scattering,irradiance_scale,layered_draws,skip_empty_voxels,compute_shaders,"
         "irradiance_dims,diffusion_dims,sub_steps,sweeps_per_step,computed_voxels,"
         "update_s,ours_raycast_frame_s,phong_frame_s,update_over_phong\n";
  std::cout
    << "sweep        lights    s  scale layered skip   cs  irradiance   diffusion    update s  "
       "ray cast s  phong s  update/phong"
    << std::endl;
  for (const Config& c : configs)
  {
    if (!Wanted(o.Only, "updates"))
    {
      break;
    }
    ours.SetLightCount(c.Lights);
    phong.SetLightCount(c.Lights);
    ours.SetScattering(c.S);
    ours.Ours->SetIrradianceScale(c.Scale);
    vtkIrradianceEstimator* pass = ours.Ours->GetIrradianceEstimator();
    pass->SetLayeredRendering(c.Layered);
    pass->SetSkipEmptyVoxels(c.SkipEmpty);
    pass->SetComputeShaders(c.Compute ? vtkIrradianceEstimator::ComputeDispatches
                                      : vtkIrradianceEstimator::FragmentDraws);
    // Warm-up: shaders, tables, uploads for this configuration.
    ours.Window->Render();
    phong.Window->Render();
    if (&c == &configs.front())
    {
      std::cout << "== renderer " << mmvtest::RendererString(ours.Window) << std::endl;
    }
    // Interleaved: an update of ours, a camera-only frame of ours, a Phong
    // frame, per repetition.
    std::vector<double> updates;
    std::vector<double> casts;
    std::vector<double> phongFrames;
    for (int r = 0; r < o.Reps; ++r)
    {
      ours.Frames(
        1, [&]() { ours.PlaceLights(); }, &updates);
      casts.push_back(ours.Frames(1, [&]() { ours.Renderer->GetActiveCamera()->Azimuth(0.5); }));
      phongFrames.push_back(phong.Frames(1, [&]() { phong.PlaceLights(); }));
    }
    int irradiance[3];
    ours.Ours->GetIrradianceDimensions(irradiance);
    int diffusion[3];
    pass->GetDiffusionGridDimensions(diffusion);
    const bool diffuses = c.S > 0.0;
    const double update = Median(updates);
    const double phongFrame = Median(phongFrames);
    csv << c.Sweep << "," << c.Lights << "," << c.S << "," << c.Scale << "," << c.Layered << ","
        << c.SkipEmpty << "," << pass->GetComputeShadersUsed() << "," << Join(irradiance) << ","
        << (diffuses ? Join(diffusion) : "-") << ","
        << (diffuses ? pass->GetDiffusionSubSteps() : 0) << ","
        << (diffuses ? pass->GetDiffusionSweepsPerStep() : 0) << ","
        << pass->GetNumberOfComputedVoxels() << "," << update << "," << Median(casts) << ","
        << phongFrame << "," << update / phongFrame << "\n";
    csv.flush();
    std::printf("%-12s %6d %4g %6.2f %7d %5d %4d  %-11s  %-11s %8.3f  %9.3f  %7.3f  %8.2f\n",
      c.Sweep.c_str(), c.Lights, c.S, c.Scale, int(c.Layered), int(c.SkipEmpty),
      int(pass->GetComputeShadersUsed()), Join(irradiance).c_str(),
      diffuses ? Join(diffusion).c_str() : "-", update, Median(casts), phongFrame,
      update / phongFrame);
    std::fflush(stdout);
  }
  std::cout << "== wrote " << o.Out << "/irradiance_updates.csv" << std::endl;
}

/// The image with the lights at a fixed place: the first becomes `full`,
/// the reference; later ones return their PSNR against it.
double ScoreAtRest(Bench& ours, vtkSmartPointer<vtkImageData>& full)
{
  ours.PlaceLights(0.5);
  ours.Window->Render();
  vtkSmartPointer<vtkImageData> image = Grab(ours.Window);
  if (!full)
  {
    full = image;
    return std::numeric_limits<double>::infinity();
  }
  vtkNew<vtkImageErrorMetrics> metrics;
  metrics->Compute(image, full);
  return metrics->GetPSNR();
}

/// Accuracy against speed: the still frame after a light move at each
/// irradiance scale, and its image against the full-resolution one (the
/// lights at the same place for every image). Writes OUT/ct_resolution.csv.
void RunResolution(Bench& ours, Bench& phong, const Options& o)
{
  std::ofstream acc(o.Out + "/ct_resolution.csv");
  acc << "scattering,irradiance_scale,irradiance_dims,still_frame_s,phong_frame_s,"
         "still_over_phong,psnr_vs_full_db\n";
  std::cout << "s  scale  irradiance    still s  phong s  still/phong  PSNR vs full (dB)"
            << std::endl;
  ours.SetLightCount(5);
  phong.SetLightCount(5);
  ours.Ours->GetIrradianceEstimator()->SetLayeredRendering(true);
  ours.Ours->GetIrradianceEstimator()->SetComputeShaders(
    vtkIrradianceEstimator::ComputeUnlessSoftware);
  ours.Ours->GetIrradianceEstimator()->SetSkipEmptyVoxels(true);
  const std::vector<double> accuracyScales =
    o.Quick ? std::vector<double>{ 1.0, 0.5 } : std::vector<double>{ 1.0, 0.75, 0.5, 0.35, 0.25 };
  for (double s : { 0.0, 8.0 })
  {
    if (!Wanted(o.Only, "resolution"))
    {
      break;
    }
    ours.SetScattering(s);
    vtkSmartPointer<vtkImageData> full;
    for (double scale : accuracyScales)
    {
      ours.Ours->SetIrradianceScale(scale);
      ours.Window->Render();
      std::vector<double> still;
      std::vector<double> phongFrames;
      for (int r = 0; r < o.Reps; ++r)
      {
        still.push_back(ours.Frames(1, [&]() { ours.PlaceLights(); }));
        phongFrames.push_back(phong.Frames(1, [&]() { phong.PlaceLights(); }));
      }
      const double psnr = ScoreAtRest(ours, full);
      int irradiance[3];
      ours.Ours->GetIrradianceDimensions(irradiance);
      const double stillFrame = Median(still);
      const double phongFrame = Median(phongFrames);
      acc << s << "," << scale << "," << Join(irradiance) << "," << stillFrame << "," << phongFrame
          << "," << stillFrame / phongFrame << "," << psnr << "\n";
      acc.flush();
      std::printf("%-3g %5.2f  %-12s %7.3f  %7.3f  %11.2f  %8.1f\n", s, scale,
        Join(irradiance).c_str(), stillFrame, phongFrame, stillFrame / phongFrame, psnr);
      std::fflush(stdout);
    }
  }
  std::cout << "== wrote " << o.Out << "/ct_resolution.csv" << std::endl;
}

/// Piecewise against full shadow rays: the light update and the image
/// against the full rays' image of the same lights, per chunk length K.
/// Writes OUT/shadow_estimation.csv.
void RunEstimation(Bench& ours, Bench& phong, const Options& o)
{
  std::ofstream est(o.Out + "/shadow_estimation.csv");
  est << "scattering,irradiance_scale,irradiance_dims,estimation,slices,update_s,"
         "shadow_rays_s,diffusion_s,phong_frame_s,update_over_phong,psnr_vs_full_rays_db\n";
  std::cout << "s  scale  irradiance    estimation  K   update s  phong s  update/phong  PSNR vs "
               "full rays (dB)"
            << std::endl;
  const std::vector<double> estimationScales =
    o.Quick ? std::vector<double>{ 0.0 } : std::vector<double>{ 0.5, 0.0 };
  const std::vector<int> chunkLengths =
    o.Quick ? std::vector<int>{ 0, 2, 8, 32, 128 } : std::vector<int>{ 0, 2, 4, 8, 16, 32 };
  for (double s : { 0.0, 8.0 })
  {
    if (!Wanted(o.Only, "estimation"))
    {
      break;
    }
    ours.SetScattering(s);
    for (double scale : estimationScales)
    {
      ours.Ours->SetIrradianceScale(scale);
      vtkSmartPointer<vtkImageData> full;
      for (int k : chunkLengths) // 0: full rays, first, as the reference
      {
        ours.Ours->SetShadowEstimation(k == 0 ? mmv::FullShadowRays : mmv::PiecewiseShadowRays);
        ours.Ours->SetPiecewiseShadowSlices(std::max(1, k));
        ours.Window->Render();
        std::vector<double> updates;
        std::vector<double> shadowRays;
        std::vector<double> diffusions;
        std::vector<double> phongFrames;
        vtkIrradianceEstimator* pass = ours.Ours->GetIrradianceEstimator();
        for (int r = 0; r < o.Reps; ++r)
        {
          ours.Frames(
            1, [&]() { ours.PlaceLights(); }, &updates);
          shadowRays.push_back(pass->GetLastEstimationSeconds());
          diffusions.push_back(pass->GetLastDiffusionSeconds());
          phongFrames.push_back(phong.Frames(1, [&]() { phong.PlaceLights(); }));
        }
        const double psnr = ScoreAtRest(ours, full);
        int irradiance[3];
        ours.Ours->GetIrradianceDimensions(irradiance);
        const double update = Median(updates);
        const double phongFrame = Median(phongFrames);
        const char* name = k == 0 ? "full" : "piecewise";
        est << s << "," << scale << "," << Join(irradiance) << "," << name << "," << k << ","
            << update << "," << Median(shadowRays) << "," << Median(diffusions) << "," << phongFrame
            << "," << update / phongFrame << "," << psnr << "\n";
        est.flush();
        std::printf("%-3g %5.2f  %-12s %-10s %3d %8.3f (rays %6.3f, diffusion %6.3f)  %7.3f  "
                    "%11.2f  %8.1f\n",
          s, scale, Join(irradiance).c_str(), name, k, update, Median(shadowRays),
          Median(diffusions), phongFrame, update / phongFrame, psnr);
        std::fflush(stdout);
      }
    }
  }
  ours.Ours->SetShadowEstimation(mmv::PiecewiseShadowRays);
  ours.Ours->SetPiecewiseShadowSlices(mmv::DefaultPiecewiseShadowSlices);
  std::cout << "== wrote " << o.Out << "/shadow_estimation.csv" << std::endl;
}
} // namespace

int main(int argc, char* argv[])
{
  Options o;
  if (!ParseOptions(argc, argv, o))
  {
    return 2;
  }
  mkdir(o.Out.c_str(), 0755);
  mmvbench::SceneSpec scene = mmvbench::MakeCTSized(o.Head);
  if (!scene.Image)
  {
    std::cerr << "cannot read " << o.Head << "\n";
    return 1;
  }
  int dims[3];
  scene.Image->GetDimensions(dims);
  std::cout << "== CT-sized scene " << Join(dims) << ", " << o.Size << "^2 pixels, " << o.Reps
            << " updates per configuration" << std::endl;
  const std::vector<Config> configs = MakeConfigs(o.Quick);

  if (Alone(o.Only, "probe")) // alone: windows of its own
  {
    return mmvirradiance::RunErrorProbe(o.Head, o.Size, 128, o.Out, o.ProbeBound, o.ProbeScenes);
  }
  if (Alone(o.Only, "tolerance")) // alone: windows of its own
  {
    return mmvirradiance::RunLightTolerance(scene, o.Size, o.Out);
  }
  if (Alone(o.Only, "orbit")) // alone: four windows of its own
  {
    return mmvirradiance::RunLightKitOrbit(scene, o.Size, o.Out, o.OrbitSteps, o.OrbitInteractive);
  }
  Bench ours(scene, o.Size, true);
  Bench phong(scene, o.Size, false);
  if (Alone(o.Only, "compute"))
  {
    return RunComputeVsFragment(ours, o.Reps, o.Out);
  }
  if (Alone(o.Only, "progress"))
  {
    return RunProgressOverhead(ours, o.Reps, o.Out);
  }
  if (Alone(o.Only, "diffusion"))
  {
    return RunDiffusionIntegrators(scene, o.Size, ours, o.Reps, o.Out);
  }
  if (Wanted(o.Only, "raycast")) // alone: it changes the mappers' sampling
  {
    return RunRaycast(ours, phong, o);
  }
  RunUpdates(ours, phong, configs, o);
  RunResolution(ours, phong, o);
  RunEstimation(ours, phong, o);
  return 0;
}
