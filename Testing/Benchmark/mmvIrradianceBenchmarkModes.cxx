// The modes of mmvIrradianceBenchmark that build windows of their own
// (--only probe, tolerance or orbit): the error probe, the light-direction
// tolerance and ParaView's light-kit orbit.
#include "mmvIrradianceBenchmarkModes.h"
#include "mmvTestWindow.h"

#include "vtkCamera.h"
#include "vtkImageData.h"
#include "vtkImageErrorMetrics.h"
#include "vtkIrradianceEstimator.h"
#include "vtkIrradianceResolutionProbe.h"
#include "vtkLight.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMultiMaterialParameters.h"
#include "vtkMultiMaterialVolumeMapper.h"
#include "vtkNew.h"
#include "vtkOpenGLGPUVolumeRayCastMapper.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace mmvirradiance
{
namespace
{
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

/// The orbit's methods, in the order of their windows.
enum OrbitMethod
{
  Phong,
  Scattering,
  OursDefault,
  OursSkin
};
const char* const OrbitNames[] = { "vtk-phong", "vtk-scattering", "mmv-default", "mmv-skin" };

/// The orbit's frame times per method: every interactive frame, the last
/// (up to) three of each step's, and the still frames.
struct OrbitTimes
{
  std::vector<std::vector<double>> Interactive = std::vector<std::vector<double>>(4);
  std::vector<std::vector<double>> Settled = std::vector<std::vector<double>>(4);
  std::vector<std::vector<double>> Still = std::vector<std::vector<double>>(4);
};

/// One orbit window of `method` under the light kit, rendered once.
std::unique_ptr<Bench> MakeOrbitBench(
  const mmvbench::SceneSpec& scene, int size, int method, const double range[2])
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
}

/// The orbit's table: medians per method against Phong's, and the image at
/// rest of ours against a fresh window at the same camera.
void WriteOrbitTable(const mmvbench::SceneSpec& scene, int size, const std::string& out, int steps,
  int interactive, std::vector<std::unique_ptr<Bench>>& benches, const OrbitTimes& times,
  const std::string& renderer)
{
  double range[2];
  scene.Image->GetScalarRange(range);
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
      auto fresh = MakeOrbitBench(scene, size, m, range);
      fresh->Renderer->GetActiveCamera()->DeepCopy(benches[m]->Renderer->GetActiveCamera());
      fresh->Renderer->ResetCameraClippingRange();
      benches[m]->Renderer->ResetCameraClippingRange();
      fresh->Window->Render();
      benches[m]->Window->Render();
      vtkNew<vtkImageErrorMetrics> metrics;
      metrics->Compute(Grab(benches[m]->Window), Grab(fresh->Window));
      psnr = metrics->GetPSNR();
    }
    const double i = Median(times.Interactive[m]), st = Median(times.Settled[m]),
                 sl = Median(times.Still[m]);
    const double pi = Median(times.Interactive[Phong]), pst = Median(times.Settled[Phong]),
                 psl = Median(times.Still[Phong]);
    csv << OrbitNames[m] << "," << steps << "," << interactive << "," << i << "," << st << "," << sl
        << "," << i / pi << "," << st / pst << "," << sl / psl << "," << psnr << ",\"" << renderer
        << "\"\n";
    std::printf("%-15s %12.4f %10.4f %8.4f %10.2f %14.2f %12.2f %16.1f\n", OrbitNames[m], i, st, sl,
      i / pi, st / pst, sl / psl, psnr);
  }
  std::cout << "== wrote " << out << "/lightkit_orbit_cxx.csv" << std::endl;
}

/// Where a still frame of ours goes: with the mapper's stage timers (each
/// stage ends with glFinish), after a 10-degree turn of the camera. Writes
/// OUT/lightkit_still_stages.csv.
void WriteStillStages(std::vector<std::unique_ptr<Bench>>& benches, const std::string& out)
{
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
      frame.push_back(TimedRender(b.Window));
      vtkIrradianceEstimator* irradiance = b.Ours->GetIrradianceEstimator();
      pass.push_back(b.Ours->GetLastIrradianceSeconds());
      estimation.push_back(irradiance->GetLastEstimationSeconds());
      diffusion.push_back(irradiance->GetLastDiffusionSeconds());
      cast.push_back(b.Ours->GetLastRayCastSeconds());
      rest.push_back(frame.back() - pass.back() - cast.back());
    }
    b.Ours->TimeStagesOff();
    stages << OrbitNames[m] << "," << Median(frame) << "," << Median(pass) << ","
           << Median(estimation) << "," << Median(diffusion) << "," << Median(cast) << ","
           << Median(rest) << "\n";
    std::printf("%-15s %8.4f  %8.4f (%8.4f, %8.4f)          %8.4f  %8.4f\n", OrbitNames[m],
      Median(frame), Median(pass), Median(estimation), Median(diffusion), Median(cast),
      Median(rest));
  }
  std::cout << "== wrote " << out << "/lightkit_still_stages.csv" << std::endl;
}
} // namespace

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
      const double keptSeconds = TimedRender(kept.Window);
      if (kept.Ours->GetIrradianceUpdateCount() != updates)
      {
        std::cerr << "the irradiance was recomputed within the tolerance\n";
        return 1;
      }
      exact.Renderer->GetActiveCamera()->DeepCopy(kept.Renderer->GetActiveCamera());
      exact.Renderer->ResetCameraClippingRange();
      kept.Renderer->ResetCameraClippingRange();
      const double exactSeconds = TimedRender(exact.Window);
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
  for (const std::string& name : mmvbench::SplitList(scenes))
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
    const double still = TimedRender(automatic->Window);
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
  double range[2];
  scene.Image->GetScalarRange(range);
  std::vector<std::unique_ptr<Bench>> benches;
  for (int m = Phong; m <= OursSkin; ++m)
  {
    benches.push_back(MakeOrbitBench(scene, size, m, range));
  }
  const std::string renderer = mmvtest::RendererString(benches[0]->Window);
  std::cout << "== light-kit orbit: " << steps << " steps x " << interactive
            << " interactive frames + 1 still, renderer " << renderer << std::endl;
  OrbitTimes times;
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
        const double t = TimedRender(b.Window);
        times.Interactive[m].push_back(t);
        if (f >= interactive - std::min(3, interactive))
        {
          times.Settled[m].push_back(t);
        }
      }
      b.Window->SetDesiredUpdateRate(0.0001); // the still render after the drag
      times.Still[m].push_back(TimedRender(b.Window));
    }
  }
  WriteOrbitTable(scene, size, out, steps, interactive, benches, times, renderer);
  WriteStillStages(benches, out);
  return 0;
}
} // namespace mmvirradiance
