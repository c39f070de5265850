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
#include "mmvTestWindow.h"

#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkImageData.h"
#include "vtkImageErrorMetrics.h"
#include "vtkIrradianceEstimator.h"
#include "vtkIrradianceResolutionProbe.h"
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
#include <memory>
#include <sstream>
#include <string>
#include <sys/stat.h>
#include <vector>

namespace
{
double Median(std::vector<double> v)
{
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n == 0 ? std::nan("") : (n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]));
}

/// Directions toward the lights: the first five roughly where ParaView's
/// light kit puts its key, fill, back and head lights around a front view.
const double LightDirections[8][3] = { { 0.3, -0.8, 0.9 }, { -0.6, -0.9, -0.3 }, { 0.9, 0.8, 0.2 },
  { -0.9, 0.8, 0.2 }, { 0.0, -1.0, 0.1 }, { 0.5, 0.2, -0.9 }, { -0.4, 0.3, 0.9 },
  { 0.8, -0.3, -0.4 } };

/// One window rendering the CT-sized scene with N scene lights.
struct Bench : mmvbench::VolumeWindow
{
  std::vector<vtkSmartPointer<vtkLight>> Lights;
  double Center[3] = { 0.0, 0.0, 0.0 };
  double Turn = 0.0;

  Bench(const mmvbench::SceneSpec& scene, int size, bool ours)
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

  void SetLightCount(int count)
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

  /// Turns every light by a small, new angle, so all of them need updating
  /// (or to `turn`, when given).
  void PlaceLights(double turn = -1.0)
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
      this->Lights[l]->SetPosition(
        this->Center[0] + x, this->Center[1] + y, this->Center[2] + d[2]);
    }
  }

  void SetScattering(double strength)
  {
    // Every node's scattering becomes `strength`; the rest stays.
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

  /// Median seconds of `reps` frames, each after `change` (timed around
  /// Render with glFinish inside the mapper when it is ours).
  template <typename Change>
  double Frames(int reps, Change&& change, std::vector<double>* irradiance = nullptr)
  {
    std::vector<double> frames;
    for (int r = 0; r < reps; ++r)
    {
      change();
      const auto start = std::chrono::steady_clock::now();
      this->Window->Render();
      frames.push_back(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      if (irradiance && this->Ours)
      {
        irradiance->push_back(this->Ours->GetLastIrradianceSeconds());
      }
    }
    return Median(frames);
  }
};

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

std::string Join(const int v[3])
{
  std::ostringstream s;
  s << v[0] << "x" << v[1] << "x" << v[2];
  return s.str();
}
/// The window's back buffer as an image.
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

/// A ParaView light kit in place of the bench's lights.
void UseLightKit(Bench& bench)
{
  bench.Renderer->RemoveAllLights();
  vtkNew<vtkLightKit> kit;
  kit->AddLightsToRenderer(bench.Renderer);
}

/// LightDirectionTolerance: the camera (and the light kit with it) turns by
/// an angle after an exact frame, and the frame that keeps the irradiance is
/// compared with an exact frame of the same camera (PSNR), with the time of
/// both still frames. Default material and `skin`. Writes
/// OUT/light_tolerance.csv.
int RunLightTolerance(const mmvbench::SceneSpec& scene, int size, const std::string& out)
{
  double range[2];
  scene.Image->GetScalarRange(range);
  std::ofstream csv(out + "/light_tolerance.csv");
  csv << "material,angle_deg,psnr_kept_vs_exact_db,kept_frame_s,exact_frame_s,renderer\n";
  std::printf("material  angle deg  kept vs exact dB  kept frame s  exact frame s\n");
  auto timed = [](vtkRenderWindow* window)
  {
    const auto start = std::chrono::steady_clock::now();
    window->Render();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  for (const std::string material : { "default", "skin" })
  {
    Bench kept(scene, size, true);
    Bench exact(scene, size, true);
    for (Bench* b : { &kept, &exact })
    {
      UseLightKit(*b);
      if (material == "skin")
      {
        b->Materials->ApplyPreset("skin", range[0], range[1]);
      }
      b->Ours->TimeStagesOff();
      b->Window->SetDesiredUpdateRate(0.0001); // still renders only
    }
    const std::string renderer = mmvtest::RendererString(kept.Window);
    for (double angle : { 0.25, 0.5, 1.0, 2.0, 4.0, 8.0, 16.0 })
    {
      // An exact frame at the start camera, then the turn within tolerance.
      kept.Ours->SetLightDirectionTolerance(0.0);
      kept.Window->Render();
      kept.Ours->SetLightDirectionTolerance(mmv::MaxLightDirectionToleranceDegrees);
      kept.Renderer->GetActiveCamera()->Azimuth(angle);
      const int updates = kept.Ours->GetIrradianceUpdateCount();
      const double keptSeconds = timed(kept.Window);
      if (kept.Ours->GetIrradianceUpdateCount() != updates)
      {
        std::cerr << "the irradiance was recomputed within the tolerance\n";
        return 1;
      }
      exact.Renderer->GetActiveCamera()->DeepCopy(kept.Renderer->GetActiveCamera());
      exact.Renderer->ResetCameraClippingRange();
      kept.Renderer->ResetCameraClippingRange();
      const double exactSeconds = timed(exact.Window);
      kept.Window->Render(); // the same clipping range as the exact frame
      vtkNew<vtkImageErrorMetrics> metrics;
      metrics->Compute(Grab(kept.Window), Grab(exact.Window));
      csv << material << "," << angle << "," << metrics->GetPSNR() << "," << keptSeconds << ","
          << exactSeconds << ",\"" << renderer << "\"\n";
      std::printf("%-9s %9.2f %17.1f %13.3f %14.3f\n", material.c_str(), angle, metrics->GetPSNR(),
        keptSeconds, exactSeconds);
      kept.Renderer->GetActiveCamera()->Azimuth(-angle);
    }
  }
  std::cout << "== wrote " << out << "/light_tolerance.csv" << std::endl;
  return 0;
}

/// A window of `scene` as the accuracy benchmark frames it (mmvBenchmark's
/// camera and key light) or, for the CT, as the orbit does (light kit).
std::unique_ptr<Bench> ProbeBench(const mmvbench::SceneSpec& scene, int size, bool kit)
{
  auto bench = std::unique_ptr<Bench>(new Bench(scene, size, true));
  bench->Ours->TimeStagesOff();
  bench->Window->SetDesiredUpdateRate(0.0001); // still renders only
  if (kit)
  {
    UseLightKit(*bench);
  }
  else
  {
    vtkNew<vtkLight> light;
    double radius = 0.0;
    mmvbench::FrameScene(scene, bench->Renderer->GetActiveCamera(), light, radius);
    bench->Renderer->AddLight(light);
  }
  return bench;
}

/// The error probe (IrradianceErrorBound): per scene, the probe's PSNR of
/// each grid it measured against the image PSNR of that grid, both against
/// the probe's reference grid, and what the default bound chooses, with the
/// probe's time and a still frame's. Writes OUT/error_probe.csv.
int RunErrorProbe(const std::string& head, int ctSize, int smallSize, const std::string& out,
  double bound, const std::string& scenes)
{
  std::ofstream csv(out + "/error_probe.csv");
  csv << "scene,image_px,scale,dimensions,probe_psnr_db,image_psnr_db_vs_reference,chosen,"
         "probe_s,still_frame_s,resolution_reason\n";
  std::printf("scene      px   scale  dimensions     probe dB  image dB  chosen\n");
  std::stringstream list(scenes);
  std::string name;
  while (std::getline(list, name, ','))
  {
    const mmvbench::SceneSpec scene = mmvbench::MakeScene(name, head);
    if (!scene.Image)
    {
      std::cerr << "unknown scene " << name << "\n";
      return 2;
    }
    const bool kit = name == "ct";
    const int size = kit ? ctSize : smallSize;
    auto automatic = ProbeBench(scene, size, kit);
    if (bound >= 0.0)
    {
      automatic->Ours->SetIrradianceErrorBound(bound);
    }
    automatic->Window->Render();
    vtkIrradianceResolutionProbe* probe = automatic->Ours->GetIrradianceResolutionProbe();
    const double probeSeconds = probe->GetLastProbeSeconds();
    const std::string reason = automatic->Ours->GetIrradianceResolutionReason();
    const int* chosen = automatic->Ours->GetIrradianceDimensions();
    // A still frame after a camera move (the kit's lights move with it).
    automatic->Renderer->GetActiveCamera()->Azimuth(10.0);
    const auto start = std::chrono::steady_clock::now();
    automatic->Window->Render();
    const double still =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    automatic->Renderer->GetActiveCamera()->Azimuth(-10.0);
    const std::vector<vtkIrradianceResolutionProbe::Candidate> candidates = probe->GetCandidates();
    vtkSmartPointer<vtkImageData> reference;
    for (const auto& candidate : candidates)
    {
      auto fixed = ProbeBench(scene, size, kit);
      fixed->Ours->SetIrradianceScale(candidate.Scale);
      fixed->Window->Render();
      vtkSmartPointer<vtkImageData> image = Grab(fixed->Window);
      double psnr = std::numeric_limits<double>::infinity();
      if (!reference)
      {
        reference = image;
      }
      else
      {
        vtkNew<vtkImageErrorMetrics> metrics;
        metrics->Compute(image, reference);
        psnr = metrics->GetPSNR();
      }
      const int* d = candidate.Dimensions;
      const bool isChosen = d[0] == chosen[0] && d[1] == chosen[1] && d[2] == chosen[2];
      csv << name << "," << size << "," << candidate.Scale << "," << Join(d) << ","
          << candidate.PSNR << "," << psnr << "," << (isChosen ? 1 : 0) << "," << probeSeconds
          << "," << still << ",\"" << reason << "\"\n";
      std::printf("%-9s %4d %7.3f  %-13s %8.1f %9.1f  %s\n", name.c_str(), size, candidate.Scale,
        Join(d).c_str(), candidate.PSNR, psnr, isChosen ? "yes" : "");
    }
    std::printf("  %s: probe %.2f s, still frame %.2f s; %s\n", name.c_str(), probeSeconds, still,
      reason.c_str());
  }
  std::cout << "== wrote " << out << "/error_probe.csv" << std::endl;
  return 0;
}

/// ParaView's default lighting in C++: a light kit (key, fill, two back
/// lights and the head light, all following the camera), a camera orbit of
/// `steps` steps, each of `interactive` frames with a small allocated render
/// time (what ParaView's interactive renders and VTK's LOD use) and one still
/// frame; VTK's Phong, VTK's volumetric scattering, ours by default and with
/// `skin`, round-robin per step. Then the image at rest against a fresh
/// window at the same camera. Writes OUT/lightkit_orbit_cxx.csv.
int RunLightKitOrbit(
  const mmvbench::SceneSpec& scene, int size, const std::string& out, int steps, int interactive)
{
  enum Method
  {
    Phong,
    Scattering,
    OursDefault,
    OursSkin
  };
  const char* names[] = { "vtk-phong", "vtk-scattering", "mmv-default", "mmv-skin" };
  double range[2];
  scene.Image->GetScalarRange(range);
  auto make = [&](int method)
  {
    auto bench = std::make_unique<Bench>(scene, size, method >= OursDefault);
    UseLightKit(*bench);
    if (method == Scattering)
    {
      bench->Mapper->SetVolumetricScatteringBlending(1.0);
      bench->Mapper->SetGlobalIlluminationReach(0.5);
    }
    if (method == OursSkin)
    {
      bench->Materials->ApplyPreset("skin", range[0], range[1]);
    }
    if (bench->Ours)
    {
      bench->Ours->TimeStagesOff(); // its glFinish calls would stall the frames
    }
    bench->Window->SetDesiredUpdateRate(0.0001);
    bench->Window->Render();
    return bench;
  };
  std::vector<std::unique_ptr<Bench>> benches;
  for (int m = Phong; m <= OursSkin; ++m)
  {
    benches.push_back(make(m));
  }
  const std::string renderer = mmvtest::RendererString(benches[0]->Window);
  std::cout << "== light-kit orbit: " << steps << " steps x " << interactive
            << " interactive frames + 1 still, renderer " << renderer << std::endl;
  auto timed = [](vtkRenderWindow* window)
  {
    const auto start = std::chrono::steady_clock::now();
    window->Render();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  std::vector<std::vector<double>> inter(4), settled(4), still(4);
  for (int step = 0; step < steps; ++step)
  {
    for (int i = 0; i < 4; ++i)
    {
      const int m = (step + i) % 4; // the order rotates: the machine may be shared
      Bench& b = *benches[m];
      b.Window->SetDesiredUpdateRate(5.0); // ParaView's interactive renders
      for (int f = 0; f < interactive; ++f)
      {
        b.Renderer->GetActiveCamera()->Azimuth(10.0 / interactive);
        const double t = timed(b.Window);
        inter[m].push_back(t);
        if (f >= interactive - std::min(3, interactive))
        {
          settled[m].push_back(t);
        }
      }
      b.Window->SetDesiredUpdateRate(0.0001); // the still render after the drag
      still[m].push_back(timed(b.Window));
    }
  }
  std::ofstream csv(out + "/lightkit_orbit_cxx.csv");
  csv << "method,steps,interactive_frames,interactive_median_s,interactive_settled_median_s,"
         "still_median_s,interactive_over_phong,settled_over_phong,still_over_phong,"
         "psnr_rest_vs_fresh_db,renderer\n";
  std::printf("method          interactive s  settled s  still s   int/phong  settled/phong  "
              "still/phong  rest vs fresh dB\n");
  for (int m = Phong; m <= OursSkin; ++m)
  {
    double psnr = std::nan("");
    if (m >= OursDefault)
    {
      // A fresh window at the orbit's final camera: the image at rest must equal it.
      auto fresh = make(m);
      fresh->Renderer->GetActiveCamera()->DeepCopy(benches[m]->Renderer->GetActiveCamera());
      fresh->Renderer->ResetCameraClippingRange();
      benches[m]->Renderer->ResetCameraClippingRange();
      fresh->Window->Render();
      benches[m]->Window->Render();
      vtkNew<vtkImageErrorMetrics> metrics;
      metrics->Compute(Grab(benches[m]->Window), Grab(fresh->Window));
      psnr = metrics->GetPSNR();
    }
    const double i = Median(inter[m]), st = Median(settled[m]), sl = Median(still[m]);
    const double pi = Median(inter[Phong]), pst = Median(settled[Phong]),
                 psl = Median(still[Phong]);
    csv << names[m] << "," << steps << "," << interactive << "," << i << "," << st << "," << sl
        << "," << i / pi << "," << st / pst << "," << sl / psl << "," << psnr << ",\"" << renderer
        << "\"\n";
    std::printf("%-15s %12.4f %10.4f %8.4f %10.2f %14.2f %12.2f %16.1f\n", names[m], i, st, sl,
      i / pi, st / pst, sl / psl, psnr);
  }
  std::cout << "== wrote " << out << "/lightkit_orbit_cxx.csv" << std::endl;

  // Where a still frame of ours goes: with the mapper's stage timers (each
  // stage ends with glFinish), after a 10-degree turn of the camera.
  std::ofstream stages(out + "/lightkit_still_stages.csv");
  stages << "method,frame_s,irradiance_pass_s,estimation_s,diffusion_s,ray_cast_s,rest_s\n";
  std::printf(
    "still frame of   frame s  irradiance pass (estimation, diffusion)  ray cast  rest\n");
  for (int m = OursDefault; m <= OursSkin; ++m)
  {
    Bench& b = *benches[m];
    b.Ours->TimeStagesOn();
    std::vector<double> frame, pass, estimation, diffusion, cast, rest;
    for (int r = 0; r < 5; ++r)
    {
      b.Renderer->GetActiveCamera()->Azimuth(10.0);
      frame.push_back(timed(b.Window));
      vtkIrradianceEstimator* irradiance = b.Ours->GetIrradianceEstimator();
      pass.push_back(b.Ours->GetLastIrradianceSeconds());
      estimation.push_back(irradiance->GetLastEstimationSeconds());
      diffusion.push_back(irradiance->GetLastDiffusionSeconds());
      cast.push_back(b.Ours->GetLastRayCastSeconds());
      rest.push_back(frame.back() - pass.back() - cast.back());
    }
    b.Ours->TimeStagesOff();
    stages << names[m] << "," << Median(frame) << "," << Median(pass) << "," << Median(estimation)
           << "," << Median(diffusion) << "," << Median(cast) << "," << Median(rest) << "\n";
    std::printf("%-15s %8.4f  %8.4f (%8.4f, %8.4f)          %8.4f  %8.4f\n", names[m],
      Median(frame), Median(pass), Median(estimation), Median(diffusion), Median(cast),
      Median(rest));
  }
  std::cout << "== wrote " << out << "/lightkit_still_stages.csv" << std::endl;
  return 0;
}
} // namespace

int main(int argc, char* argv[])
{
  std::string out = "irradiance_benchmark";
  std::string head = MMV_HEADSQ_PATH;
  int size = 400;
  int reps = 3;
  bool quick = false;
  std::string only;                 // one section: updates, resolution or estimation
  double imageSampleDistance = 1.0; // raycast: > 1 as in ParaView's interactive frames
  int raycastLights = 5;            // raycast: scene lights
  int orbitSteps = 6;               // orbit: camera steps of 10 degrees
  int orbitInteractive = 8;         // orbit: interactive frames per step
  double probeBound = -1.0;         // probe: IrradianceErrorBound (< 0: the default)
  std::string probeScenes = "synthetic,headsq,orbital,ct";
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    auto next = [&]() { return i + 1 < argc ? std::string(argv[++i]) : std::string(); };
    if (arg == "--out")
    {
      out = next();
    }
    else if (arg == "--size")
    {
      size = std::max(16, std::atoi(next().c_str()));
    }
    else if (arg == "--reps")
    {
      reps = std::max(1, std::atoi(next().c_str()));
    }
    else if (arg == "--head")
    {
      head = next();
    }
    else if (arg == "--quick")
    {
      quick = true;
    }
    else if (arg == "--only")
    {
      only = next();
    }
    else if (arg == "--lights")
    {
      raycastLights = std::max(0, std::min(8, std::atoi(next().c_str())));
    }
    else if (arg == "--orbit-steps")
    {
      orbitSteps = std::max(1, std::atoi(next().c_str()));
    }
    else if (arg == "--orbit-interactive-frames")
    {
      orbitInteractive = std::max(1, std::atoi(next().c_str()));
    }
    else if (arg == "--probe-bound")
    {
      probeBound = std::atof(next().c_str());
    }
    else if (arg == "--probe-scenes")
    {
      probeScenes = next();
    }
    else if (arg == "--image-sample-distance")
    {
      imageSampleDistance = std::atof(next().c_str());
    }
    else
    {
      std::cerr << "unknown argument " << arg << "\n";
      return 2;
    }
  }
  mkdir(out.c_str(), 0755);
  mmvbench::SceneSpec scene = mmvbench::MakeCTSized(head);
  if (!scene.Image)
  {
    std::cerr << "cannot read " << head << "\n";
    return 1;
  }
  int dims[3];
  scene.Image->GetDimensions(dims);
  std::cout << "== CT-sized scene " << Join(dims) << ", " << size << "^2 pixels, " << reps
            << " updates per configuration" << std::endl;

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

  if (Wanted(only, "probe") && !only.empty()) // alone: windows of its own
  {
    return RunErrorProbe(head, size, 128, out, probeBound, probeScenes);
  }
  if (Wanted(only, "tolerance") && !only.empty()) // alone: windows of its own
  {
    return RunLightTolerance(scene, size, out);
  }
  if (Wanted(only, "orbit") && !only.empty()) // alone: four windows of its own
  {
    return RunLightKitOrbit(scene, size, out, orbitSteps, orbitInteractive);
  }
  Bench ours(scene, size, true);
  Bench phong(scene, size, false);
  if (Wanted(only, "compute") && !only.empty())
  {
    // Compute dispatches against layered fragment draws, alternating update
    // by update (the machine may be shared): 5 lights, scale 0.5.
    ours.SetLightCount(5);
    ours.Ours->SetIrradianceScale(0.5);
    vtkIrradianceEstimator* pass = ours.Ours->GetIrradianceEstimator();
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
      csv << s << "," << Median(compute) << "," << Median(fragment) << "," << Median(ratios)
          << ",\"" << renderer << "\"\n";
      std::printf("s = %g: compute %.4f s, fragment %.4f s, fragment / compute %.2f (%s)\n", s,
        Median(compute), Median(fragment), Median(ratios), renderer.c_str());
    }
    return 0;
  }
  if (Wanted(only, "progress") && !only.empty())
  {
    // What progress reporting costs an update: with a ProgressEvent observer
    // on the mapper (as ParaView's representation has; the pass then reports
    // after glFinish, per light and per texture's diffusion) and without,
    // alternating update by update (the machine may be shared): 5 lights,
    // scale 0.5 and 1, s = 0 and 8. The mapper's default: no stage timing.
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
  if (Wanted(only, "diffusion") && !only.empty())
  {
    // The diffusion's two integrators, each in its own window (switching
    // one pass between them would re-upload the volume), updates alternating
    // window by window (the machine may be shared): 5 lights, scale 0.5 and
    // the default scale, several s; the image's PSNR of the series against
    // backward Euler at the same lights.
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
          vtkNew<vtkWindowToImageFilter> grab;
          grab->SetInput(benches[e]->Window);
          grab->ReadFrontBufferOff();
          grab->Update();
          images[e] = vtkSmartPointer<vtkImageData>::New();
          images[e]->DeepCopy(grab->GetOutput());
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
  if (Wanted(only, "raycast")) // alone: it changes the mappers' sampling
  {
    // Camera-only frames (the irradiance cached): ours against Phong with
    // the same lights, interleaved, 5x the repetitions of the others.
    ours.SetLightCount(raycastLights);
    phong.SetLightCount(raycastLights);
    for (Bench* bench : { &ours, &phong })
    {
      bench->Mapper->SetAutoAdjustSampleDistances(0);
      bench->Mapper->SetImageSampleDistance(static_cast<float>(imageSampleDistance));
    }
    ours.Ours->TimeStagesOff(); // its glFinish calls would stall the frames
    ours.Window->Render();
    phong.Window->Render();
    const int tables = ours.Ours->GetPreIntegrationCount();
    std::vector<double> casts;
    std::vector<double> phongFrames;
    std::vector<double> ratios;
    std::vector<double> prepare;
    for (int r = 0; r < 5 * reps; ++r)
    {
      casts.push_back(ours.Frames(1, [&]() { ours.Renderer->GetActiveCamera()->Azimuth(0.5); }));
      prepare.push_back(ours.Ours->GetLastPrepareSeconds());
      phongFrames.push_back(
        phong.Frames(1, [&]() { phong.Renderer->GetActiveCamera()->Azimuth(0.5); }));
      ratios.push_back(casts.back() / phongFrames.back());
    }
    std::printf("image sample distance %g: ray cast %.4f s (CPU preparation %.4f s), Phong %.4f s, "
                "median ratio %.2f (tables rebuilt %d times)\n",
      imageSampleDistance, Median(casts), Median(prepare), Median(phongFrames), Median(ratios),
      ours.Ours->GetPreIntegrationCount() - tables);
    return 0;
  }
  std::ofstream csv(out + "/irradiance_updates.csv");
  csv << "sweep,lights,scattering,irradiance_scale,layered_draws,skip_empty_voxels,compute_shaders,"
         "irradiance_dims,diffusion_dims,sub_steps,sweeps_per_step,computed_voxels,"
         "update_s,ours_raycast_frame_s,phong_frame_s,update_over_phong\n";
  std::cout
    << "sweep        lights    s  scale layered skip   cs  irradiance   diffusion    update s  "
       "ray cast s  phong s  update/phong"
    << std::endl;
  for (const Config& c : configs)
  {
    if (!Wanted(only, "updates"))
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
    for (int r = 0; r < reps; ++r)
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
  std::cout << "== wrote " << out << "/irradiance_updates.csv" << std::endl;

  // Accuracy against speed: the still frame after a light move at each
  // irradiance scale, and its image against the full-resolution one (the
  // lights at the same place for every image).
  std::ofstream acc(out + "/ct_resolution.csv");
  acc << "scattering,irradiance_scale,irradiance_dims,still_frame_s,phong_frame_s,"
         "still_over_phong,psnr_vs_full_db\n";
  std::cout << "s  scale  irradiance    still s  phong s  still/phong  PSNR vs full (dB)"
            << std::endl;
  auto capture = [](vtkRenderWindow* window)
  {
    vtkNew<vtkWindowToImageFilter> grab;
    grab->SetInput(window);
    grab->ReadFrontBufferOff();
    grab->Update();
    auto image = vtkSmartPointer<vtkImageData>::New();
    image->DeepCopy(grab->GetOutput());
    return image;
  };
  // The image with the lights at a fixed place: the first becomes `full`,
  // the reference; later ones return their PSNR against it.
  auto scoreAtRest = [&](vtkSmartPointer<vtkImageData>& full)
  {
    ours.PlaceLights(0.5);
    ours.Window->Render();
    vtkSmartPointer<vtkImageData> image = capture(ours.Window);
    if (!full)
    {
      full = image;
      return std::numeric_limits<double>::infinity();
    }
    vtkNew<vtkImageErrorMetrics> metrics;
    metrics->Compute(image, full);
    return metrics->GetPSNR();
  };
  ours.SetLightCount(5);
  phong.SetLightCount(5);
  ours.Ours->GetIrradianceEstimator()->SetLayeredRendering(true);
  ours.Ours->GetIrradianceEstimator()->SetComputeShaders(
    vtkIrradianceEstimator::ComputeUnlessSoftware);
  ours.Ours->GetIrradianceEstimator()->SetSkipEmptyVoxels(true);
  const std::vector<double> accuracyScales =
    quick ? std::vector<double>{ 1.0, 0.5 } : std::vector<double>{ 1.0, 0.75, 0.5, 0.35, 0.25 };
  for (double s : { 0.0, 8.0 })
  {
    if (!Wanted(only, "resolution"))
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
      for (int r = 0; r < reps; ++r)
      {
        still.push_back(ours.Frames(1, [&]() { ours.PlaceLights(); }));
        phongFrames.push_back(phong.Frames(1, [&]() { phong.PlaceLights(); }));
      }
      const double psnr = scoreAtRest(full);
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
  std::cout << "== wrote " << out << "/ct_resolution.csv" << std::endl;

  // Piecewise against full shadow rays: the light update and the image
  // against the full rays' image of the same lights, per chunk length K.
  std::ofstream est(out + "/shadow_estimation.csv");
  est << "scattering,irradiance_scale,irradiance_dims,estimation,slices,update_s,"
         "shadow_rays_s,diffusion_s,phong_frame_s,update_over_phong,psnr_vs_full_rays_db\n";
  std::cout << "s  scale  irradiance    estimation  K   update s  phong s  update/phong  PSNR vs "
               "full rays (dB)"
            << std::endl;
  const std::vector<double> estimationScales =
    quick ? std::vector<double>{ 0.0 } : std::vector<double>{ 0.5, 0.0 };
  const std::vector<int> chunkLengths =
    quick ? std::vector<int>{ 0, 2, 8, 32, 128 } : std::vector<int>{ 0, 2, 4, 8, 16, 32 };
  for (double s : { 0.0, 8.0 })
  {
    if (!Wanted(only, "estimation"))
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
        for (int r = 0; r < reps; ++r)
        {
          ours.Frames(
            1, [&]() { ours.PlaceLights(); }, &updates);
          shadowRays.push_back(pass->GetLastEstimationSeconds());
          diffusions.push_back(pass->GetLastDiffusionSeconds());
          phongFrames.push_back(phong.Frames(1, [&]() { phong.PlaceLights(); }));
        }
        const double psnr = scoreAtRest(full);
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
  std::cout << "== wrote " << out << "/shadow_estimation.csv" << std::endl;
  return 0;
}
