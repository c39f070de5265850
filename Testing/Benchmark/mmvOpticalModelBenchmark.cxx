// Frame time of the optical model's shader variants (docs/performance.md,
// "Material terms: cost") against the
// default variant, on the benchmark scenes:
//
//   default     the scene's materials (g = 0, e = 0): no HG, no emission code
//   zero-terms  the same materials, HG and emission compiled in
//               (CompileUnusedOpticalTerms): the code's own cost
//   hg          every node g = 0.6
//   emission    every node e = 0.5
//   hg+emission both
//   rgb         every node transmission colour (1, 0.6, 0.3): the RGB
//               irradiance variant (tints)
//
//   mmvOpticalModelBenchmark --out DIR [--size N] [--frames N]
//                            [--scenes synthetic,headsq,orbital] [--head FILE.vti]
//
// Every variant has its own window (one mapper, one shader program each);
// all share one camera and one light. Each frame the camera turns 10 degrees
// and every window renders once, the order rotating frame by frame, so
// machine drift hits every variant alike; the light does not move, so the
// irradiance volume is built once and the frames time the ray cast. Medians
// and their ratios to the default variant go to DIR/optical_model.csv. Each
// frame is timed twice: wall clock, and the process's CPU time, which on
// llvmpipe (it renders on threads of this process) is the work done, far
// less disturbed by other processes on a shared machine. Not a test: it
// asserts nothing about timings.
#include "mmvBenchmarkScenes.h"
#include "mmvTestWindow.h"

#include "vtkCamera.h"
#include "vtkLight.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMultiMaterialParameters.h"
#include "vtkMultiMaterialVolumeMapper.h"
#include "vtkNew.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

namespace
{
using Clock = std::chrono::steady_clock;

/// The q-quantile (0.5: the median), linear between order statistics.
double Quantile(std::vector<double> v, double q)
{
  if (v.empty())
  {
    return 0.0;
  }
  std::sort(v.begin(), v.end());
  const double x = q * (v.size() - 1);
  const size_t i = static_cast<size_t>(x);
  const size_t j = std::min(i + 1, v.size() - 1);
  return v[i] + (x - i) * (v[j] - v[i]);
}

struct Variant
{
  std::string Name;
  double Anisotropy;
  double Emission;
  bool CompileUnused;
  bool Tinted = false;
};

const Variant Variants[] = {
  { "default", 0.0, 0.0, false },
  { "zero-terms", 0.0, 0.0, true },
  { "hg", 0.6, 0.0, false },
  { "emission", 0.0, 0.5, false },
  { "hg+emission", 0.6, 0.5, false },
  { "rgb", 0.0, 0.0, false, true },
};

/// The transmission colour of the rgb variant.
const double Tint[3] = { 1.0, 0.6, 0.3 };

/// The scene's nodes with g and e replaced on every node.
vtkSmartPointer<vtkMaterialTransferFunction> WithTerms(
  vtkMaterialTransferFunction* materials, double g, double e, bool tinted)
{
  constexpr int Stride = vtkMaterialTransferFunction::NodeStride;
  std::vector<double> nodes(static_cast<size_t>(materials->GetSize()) * Stride);
  materials->GetNodes(nodes.data());
  for (size_t i = 0; i < nodes.size(); i += Stride)
  {
    nodes[i + 1 + mmv::Anisotropy] = g;
    nodes[i + 1 + mmv::Emission] = e;
    for (int c = 0; tinted && c < 3; ++c)
    {
      nodes[i + 1 + mmv::TransmissionR + c] = Tint[c];
    }
  }
  auto out = vtkSmartPointer<vtkMaterialTransferFunction>::New();
  out->SetNodes(static_cast<int>(nodes.size()), nodes.data());
  return out;
}

struct Instance : mmvbench::View
{
  const Variant* Spec = nullptr;
  vtkNew<vtkMultiMaterialVolumeMapper> Mapper;
  vtkSmartPointer<vtkMaterialTransferFunction> Materials;
  std::vector<double> Seconds;
  std::vector<double> CPUSeconds;
  double FirstIrradianceSeconds = 0.0; // the untimed first frame's update

  void Render()
  {
    const auto start = Clock::now();
    const double cpu = ProcessCPUSeconds();
    this->RenderWindow->Render();
    this->RenderWindow->WaitForCompletion();
    this->CPUSeconds.push_back(ProcessCPUSeconds() - cpu);
    this->Seconds.push_back(std::chrono::duration<double>(Clock::now() - start).count());
  }

  static double ProcessCPUSeconds()
  {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
  }
};

struct Options
{
  std::string Out = "optical-model-out";
  int Size = 256;
  int Frames = 15;
  std::vector<std::string> Scenes = { "synthetic", "headsq", "orbital" };
  std::string Head = MMV_HEADSQ_PATH;
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
      o.Size = std::max(16, std::atoi(next().c_str()));
    }
    else if (a == "--frames")
    {
      o.Frames = std::max(1, std::atoi(next().c_str()));
    }
    else if (a == "--scenes")
    {
      o.Scenes = mmvbench::SplitList(next());
    }
    else if (a == "--head")
    {
      o.Head = next();
    }
    else
    {
      return false;
    }
  }
  return !o.Out.empty();
}
}

int main(int argc, char* argv[])
{
  Options opt;
  if (!Parse(argc, argv, opt))
  {
    std::cerr << "usage: " << argv[0]
              << " --out DIR [--size N] [--frames N] [--scenes a,b] [--head FILE.vti]\n";
    return 2;
  }
  const std::string mkdir = "mkdir -p '" + opt.Out + "'";
  if (std::system(mkdir.c_str()) != 0)
  {
    std::cerr << "cannot create " << opt.Out << "\n";
    return 1;
  }
  std::ofstream csv(opt.Out + "/optical_model.csv");
  csv << "scene,variant,anisotropy,emission,compile_unused,frames,median_ms,p25_ms,p75_ms,"
         "ratio_to_default,cpu_median_ms,cpu_p25_ms,cpu_p75_ms,cpu_ratio_to_default,renderer,"
         "tinted,irradiance_update_ms,gpu_memory_bytes\n";
  for (const std::string& name : opt.Scenes)
  {
    const mmvbench::SceneSpec scene = mmvbench::MakeScene(name, opt.Head);
    if (!scene.Image)
    {
      std::cerr << "unknown or unreadable scene " << name << "\n";
      return 1;
    }
    vtkNew<vtkCamera> camera;
    vtkNew<vtkLight> light;
    double radius = 0.0;
    mmvbench::FrameScene(scene, camera, light, radius);

    std::vector<std::unique_ptr<Instance>> instances;
    for (const Variant& v : Variants)
    {
      auto in = std::make_unique<Instance>();
      in->Spec = &v;
      // A flat background, as in the figures of docs/performance.md.
      in->SetUp(scene, camera, light, opt.Size, in->Mapper, /*gradient=*/false);
      in->Materials = WithTerms(scene.Materials, v.Anisotropy, v.Emission, v.Tinted);
      in->Mapper->SetMaterialTransferFunction(in->Materials);
      in->Mapper->SetCompileUnusedOpticalTerms(v.CompileUnused);
      in->Render(); // build the tables, irradiance and program: untimed
      in->FirstIrradianceSeconds = in->Mapper->GetLastIrradianceSeconds();
      in->Render();
      in->Seconds.clear();
      in->CPUSeconds.clear();
      instances.push_back(std::move(in));
    }
    const size_t count = instances.size();
    for (int f = 0; f < opt.Frames; ++f)
    {
      camera->Azimuth(10.0);
      for (size_t n = 0; n < count; ++n)
      {
        instances[(n + f) % count]->Render();
      }
    }
    const double base = Quantile(instances.front()->Seconds, 0.5);
    const double cpuBase = Quantile(instances.front()->CPUSeconds, 0.5);
    const std::string renderer = mmvtest::RendererString(instances.front()->RenderWindow);
    for (const auto& in : instances)
    {
      const double median = Quantile(in->Seconds, 0.5);
      const double p25 = Quantile(in->Seconds, 0.25);
      const double p75 = Quantile(in->Seconds, 0.75);
      const double cpu = Quantile(in->CPUSeconds, 0.5);
      const double cpu25 = Quantile(in->CPUSeconds, 0.25);
      const double cpu75 = Quantile(in->CPUSeconds, 0.75);
      std::cout << std::setw(10) << name << std::setw(13) << in->Spec->Name << "  wall "
                << std::fixed << std::setprecision(1) << 1e3 * median << " ms (" << 1e3 * p25 << "-"
                << 1e3 * p75 << ") x" << std::setprecision(3) << median / base << "  cpu "
                << std::setprecision(1) << 1e3 * cpu << " ms (" << 1e3 * cpu25 << "-" << 1e3 * cpu75
                << ") x" << std::setprecision(3) << cpu / cpuBase << "  irradiance update "
                << std::setprecision(1) << 1e3 * in->FirstIrradianceSeconds << " ms\n";
      csv << name << "," << in->Spec->Name << "," << in->Spec->Anisotropy << ","
          << in->Spec->Emission << "," << (in->Spec->CompileUnused ? 1 : 0) << ","
          << in->Seconds.size() << "," << std::setprecision(4) << 1e3 * median << "," << 1e3 * p25
          << "," << 1e3 * p75 << "," << median / base << "," << 1e3 * cpu << "," << 1e3 * cpu25
          << "," << 1e3 * cpu75 << "," << cpu / cpuBase << ",\"" << renderer << "\","
          << (in->Spec->Tinted ? 1 : 0) << "," << 1e3 * in->FirstIrradianceSeconds << ","
          << in->Mapper->GetMultiMaterialMemoryBytes() << "\n";
    }
    csv.flush();
  }
  return 0;
}
