// The speed of the physical reference (vtkMultiMaterialPathTracer): on each
// benchmark scene, with mmvBenchmark's camera, key light and gradient
// background, the time to reach a target relative standard error (1 %) on a
// size x size image.
//
//   mmvPathTracerBenchmark --out DIR [--size 256] [--spp 8] [--target 0.01]
//                          [--scenes synthetic,headsq,orbital,ct] [--head FILE.vti]
//                          [--verify]
//
// The image's relative standard error is e(N) = sqrt(mean SE^2) / mean L
// over the pixels and channels the volume covers (those with SE > 0): the
// error of a typical pixel relative to a typical radiance. Each scene renders
// at N and 4 N paths per pixel: the two times give the cost per path sample
// and the fixed setup (tables, majorant grid), the two errors confirm the
// 1/sqrt(N) law; the samples for the target follow from e(4N) (e ~ 1/sqrt N)
// and their time from the measured cost. --verify then renders at that
// sample count and reports the error actually reached. On a shared machine
// wall time depends on the others' load: the process's CPU time divided by
// the thread count ("dedicated" seconds) is what the same work takes on that
// many cores of its own. Writes DIR/pathtracer.csv
// and DIR/pathtracer_<scene>.png (the 4 N image). vtkSMPTools' STDThread
// backend runs on every core of the machine (set VTK_SMP_MAX_THREADS to
// limit it). Not a test: it asserts nothing.
#include "mmvBenchmarkScenes.h"

#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkImageErrorMetrics.h"
#include "vtkLight.h"
#include "vtkMultiMaterialPathTracer.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkRenderer.h"
#include "vtkSMPTools.h"
#include "vtkVolumeProperty.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <sys/resource.h>
#include <sys/stat.h>
#include <thread>
#include <vector>

namespace
{
struct Options
{
  std::string Out = "pathtracer-out";
  int Size = 256;
  int Samples = 8;
  double Target = 0.01;
  std::vector<std::string> Scenes = { "synthetic", "headsq", "orbital", "ct" };
  std::string Head = MMV_HEADSQ_PATH;
  bool Verify = false;
};

bool Parse(int argc, char* argv[], Options& o)
{
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    auto next = [&]() -> std::string { return i + 1 < argc ? argv[++i] : ""; };
    if (a == "--out")
    {
      o.Out = next();
    }
    else if (a == "--size")
    {
      o.Size = std::atoi(next().c_str());
    }
    else if (a == "--spp")
    {
      o.Samples = std::atoi(next().c_str());
    }
    else if (a == "--target")
    {
      o.Target = std::atof(next().c_str());
    }
    else if (a == "--scenes")
    {
      o.Scenes = mmvbench::SplitList(next());
    }
    else if (a == "--head")
    {
      o.Head = next();
    }
    else if (a == "--verify")
    {
      o.Verify = true;
    }
    else
    {
      return false;
    }
  }
  return o.Size >= 8 && o.Samples >= 2 && o.Target > 0.0 && !o.Out.empty();
}

// CPU seconds (user + system) this process has used, all threads.
double CPUSeconds()
{
  rusage usage;
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_utime.tv_sec + usage.ru_stime.tv_sec +
    1e-6 * (usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

// Relative standard error of an image and the fraction of pixels it covers.
struct ImageError
{
  double Relative = 0.0;
  double Coverage = 0.0;
  double MeanRadiance = 0.0;
};

ImageError Measure(vtkImageData* image)
{
  vtkDataArray* radiance = image->GetPointData()->GetArray("Radiance");
  vtkDataArray* error = image->GetPointData()->GetArray("StandardError");
  double se2 = 0.0;
  double sum = 0.0;
  long long values = 0;
  long long pixels = 0;
  for (vtkIdType p = 0; p < radiance->GetNumberOfTuples(); ++p)
  {
    bool covered = false;
    for (int c = 0; c < 3; ++c)
    {
      covered = covered || error->GetComponent(p, c) > 0.0;
    }
    if (!covered)
    {
      continue;
    }
    ++pixels;
    for (int c = 0; c < 3; ++c)
    {
      se2 += error->GetComponent(p, c) * error->GetComponent(p, c);
      sum += radiance->GetComponent(p, c);
      ++values;
    }
  }
  ImageError e;
  if (values > 0 && sum > 0.0)
  {
    e.MeanRadiance = sum / values;
    e.Relative = std::sqrt(se2 / values) / e.MeanRadiance;
  }
  e.Coverage = static_cast<double>(pixels) / radiance->GetNumberOfTuples();
  return e;
}

}

int main(int argc, char* argv[])
{
  Options opt;
  if (!Parse(argc, argv, opt))
  {
    std::cerr << "usage: " << argv[0]
              << " --out DIR [--size N] [--spp N] [--target E]"
                 " [--scenes synthetic,headsq,orbital,ct] [--head FILE.vti] [--verify]\n";
    return 2;
  }
  vtkSMPTools::SetBackend("STDThread");
  mkdir(opt.Out.c_str(), 0755);
  std::ofstream csv(opt.Out + "/pathtracer.csv");
  csv << "scene,size,threads,spp_a,seconds_a,rel_se_a,spp_b,seconds_b,rel_se_b,coverage,"
         "mean_radiance,setup_s,ms_per_spp,spp_for_target,seconds_for_target,"
         "dedicated_seconds_for_target,verified_spp,verified_seconds,verified_dedicated_seconds,"
         "verified_rel_se,paths_per_s,events_per_path,cpu_seconds_a,cpu_seconds_b\n";
  const int threads = vtkSMPTools::GetEstimatedNumberOfThreads();
  std::cout << "threads " << threads << " (hardware " << std::thread::hardware_concurrency()
            << "), " << opt.Size << "^2, target " << 100.0 * opt.Target << " %\n";

  for (const std::string& name : opt.Scenes)
  {
    mmvbench::SceneSpec scene = mmvbench::MakeScene(name, opt.Head);
    if (!scene.Image)
    {
      std::cerr << "unknown or unreadable scene " << name << "\n";
      return 1;
    }
    vtkNew<vtkRenderer> renderer;
    vtkNew<vtkCamera> camera;
    vtkNew<vtkLight> light;
    double radius = 0.0;
    mmvbench::FrameScene(scene, camera, light, radius);
    mmvbench::SetUpRenderer(scene, renderer, camera, light);
    vtkNew<vtkVolumeProperty> property;
    mmvbench::SetUpProperty(scene, property);

    vtkNew<vtkMultiMaterialPathTracer> tracer;
    tracer->SetInputData(scene.Image);
    tracer->SetVolumeProperty(property);
    tracer->SetMaterialTransferFunction(scene.Materials);

    double cpu = 0.0; // CPU seconds of the last render
    auto render = [&](int spp, ImageError& e)
    {
      tracer->SetSamplesPerPixel(spp);
      const double start = CPUSeconds();
      vtkImageData* image = tracer->Render(renderer, opt.Size, opt.Size);
      cpu = CPUSeconds() - start;
      e = Measure(image);
      return image;
    };
    ImageError a, b;
    render(opt.Samples, a);
    const double secondsA = tracer->GetLastRenderSeconds();
    const double cpuA = cpu;
    vtkImageData* image = render(4 * opt.Samples, b);
    const double secondsB = tracer->GetLastRenderSeconds();
    const double cpuB = cpu;
    const double eventsPerPath = double(tracer->GetNumberOfEvents()) / tracer->GetNumberOfPaths();
    vtkImageErrorMetrics::WritePNG((opt.Out + "/pathtracer_" + name + ".png").c_str(), image);

    const double perSpp = (secondsB - secondsA) / (3.0 * opt.Samples);
    const double setup = std::max(0.0, secondsA - opt.Samples * perSpp);
    const double sppTarget =
      4.0 * opt.Samples * (b.Relative / opt.Target) * (b.Relative / opt.Target);
    const double secondsTarget = setup + sppTarget * perSpp;
    // The same from CPU time: what the target costs on `threads` cores of
    // their own, whatever else shared them during the run.
    const double cpuPerSpp = (cpuB - cpuA) / (3.0 * opt.Samples);
    const double cpuSetup = std::max(0.0, cpuA - opt.Samples * cpuPerSpp);
    const double dedicatedTarget = (cpuSetup + sppTarget * cpuPerSpp) / threads;
    int verifiedSpp = 0;
    double verifiedSeconds = std::nan("");
    double verifiedDedicated = std::nan("");
    ImageError verified;
    verified.Relative = std::nan("");
    if (opt.Verify)
    {
      verifiedSpp = static_cast<int>(std::ceil(sppTarget));
      render(verifiedSpp, verified);
      verifiedSeconds = tracer->GetLastRenderSeconds();
      verifiedDedicated = cpu / threads;
    }
    const double pathsPerSecond = double(opt.Size) * opt.Size / perSpp;
    csv << name << "," << opt.Size << "," << threads << "," << opt.Samples << "," << secondsA << ","
        << a.Relative << "," << 4 * opt.Samples << "," << secondsB << "," << b.Relative << ","
        << b.Coverage << "," << b.MeanRadiance << "," << setup << "," << 1e3 * perSpp << ","
        << sppTarget << "," << secondsTarget << "," << dedicatedTarget << "," << verifiedSpp << ","
        << verifiedSeconds << "," << verifiedDedicated << "," << verified.Relative << ","
        << pathsPerSecond << "," << eventsPerPath << "," << cpuA << "," << cpuB << "\n";
    csv.flush();
    std::cout << std::setw(10) << name << ": " << opt.Samples << " spp " << std::setprecision(3)
              << secondsA << " s e " << 100.0 * a.Relative << " %; " << 4 * opt.Samples << " spp "
              << secondsB << " s e " << 100.0 * b.Relative << " % (ratio "
              << a.Relative / b.Relative << ", 1/sqrt N: 2); setup " << setup << " s, "
              << 1e3 * perSpp << " ms/spp, " << eventsPerPath << " events/path -> " << sppTarget
              << " spp, " << secondsTarget << " s for " << 100.0 * opt.Target << " % ("
              << dedicatedTarget << " s on " << threads << " cores of its own)";
    if (opt.Verify)
    {
      std::cout << "; verified " << verifiedSpp << " spp: " << verifiedSeconds << " s ("
                << verifiedDedicated << " s on its own cores), e " << 100.0 * verified.Relative
                << " %";
    }
    std::cout << std::endl;
  }
  return 0;
}
