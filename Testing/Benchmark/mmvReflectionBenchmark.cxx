// Frame time of the environment reflection (eq. 17; docs/performance.md, "Material terms: cost") on
// the benchmark scenes, against the same scene without reflection:
//
//   r=0              the scene's materials, r = 0 on every node: no
//                    reflection code in the shader
//   r=0.5 unoccluded r = 0.5 on every node, ReflectionVisibility 0 (I = 1):
//                    the environment lookup alone
//   r=0.5 marched    r = 0.5, ReflectionVisibility 1: each reflecting
//                    sample marches its mirror ray through the pre-filtered
//                    extinction
//   r=0.5 view pass  r = 0.5, ReflectionVisibility 2: the same march once
//                    per irradiance voxel (vtkReflectionVisibilityPass), on
//                    every frame here since the camera turns every frame
//   r=0.5 last node, view pass
//                    r = 0.5 on the densest material only: the pass skips
//                    voxels where nothing can reflect
//   r=0.5 last node, others 1e-6, view pass
//                    the same image, but r = 1e-6 elsewhere: nothing skipped
//
//   mmvReflectionBenchmark --out DIR [--size N] [--frames N]
//                          [--scenes synthetic,headsq,ct] [--head FILE.vti]
//
// The environment is a 32 x 32 cube map (a sky gradient). As
// mmvOpticalModelBenchmark: one window per variant, one shared camera
// turning 10 degrees a frame and one fixed light (the irradiance is built
// once: the frames time the ray cast, and with it the visibility, which
// Algorithm 1 recomputes on every camera change), windows rendered in an
// order rotating frame by frame; wall-clock and process-CPU medians and
// their ratios to r=0 go to DIR/reflection.csv. Not a test.
#include "mmvBenchmarkScenes.h"
#include "mmvTestWindow.h"

#include "vtkCamera.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMultiMaterialParameters.h"
#include "vtkMultiMaterialVolumeMapper.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkTexture.h"
#include "vtkUnsignedCharArray.h"
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
  double Reflection;
  int Visibility;
  /// >= 0: the reflection on the last (densest) node only, this on the
  /// others (a tiny value changes no pixel but keeps every voxel from the
  /// view pass's skip of what cannot reflect).
  double Others = -1.0;
};

const Variant Variants[] = {
  { "r=0", 0.0, 1 },
  { "r=0.5 unoccluded", 0.5, 0 },
  { "r=0.5 marched", 0.5, 1 },
  { "r=0.5 view pass", 0.5, 2 },
  { "r=0.5 last node, view pass", 0.5, 2, 0.0 },
  { "r=0.5 last node, others 1e-6, view pass", 0.5, 2, 1e-6 },
};

/// The scene's nodes with r replaced on every node, or (others >= 0) on the
/// last node and `others` on the rest.
vtkSmartPointer<vtkMaterialTransferFunction> WithReflection(
  vtkMaterialTransferFunction* materials, double r, double others)
{
  constexpr int Stride = vtkMaterialTransferFunction::NodeStride;
  std::vector<double> nodes(static_cast<size_t>(materials->GetSize()) * Stride);
  materials->GetNodes(nodes.data());
  for (size_t i = 0; i < nodes.size(); i += Stride)
  {
    nodes[i + 1 + mmv::Reflection] = others < 0.0 || i + Stride == nodes.size() ? r : others;
  }
  auto out = vtkSmartPointer<vtkMaterialTransferFunction>::New();
  out->SetNodes(static_cast<int>(nodes.size()), nodes.data());
  return out;
}

/// A sky: blue above, brown below, by the face row (32 x 32 per face).
vtkSmartPointer<vtkTexture> MakeSky()
{
  auto texture = vtkSmartPointer<vtkTexture>::New();
  texture->CubeMapOn();
  texture->InterpolateOn();
  for (int face = 0; face < 6; ++face)
  {
    auto image = vtkSmartPointer<vtkImageData>::New();
    image->SetDimensions(32, 32, 1);
    vtkNew<vtkUnsignedCharArray> rgb;
    rgb->SetNumberOfComponents(3);
    rgb->SetNumberOfTuples(32 * 32);
    for (int j = 0; j < 32; ++j)
    {
      for (int i = 0; i < 32; ++i)
      {
        const double up = face == 2 ? 1.0 : (face == 3 ? 0.0 : 1.0 - (j + 0.5) / 32.0);
        const unsigned char c[3] = { static_cast<unsigned char>(120 - 60 * up),
          static_cast<unsigned char>(90 + 60 * up), static_cast<unsigned char>(60 + 180 * up) };
        rgb->SetTypedTuple(j * 32 + i, c);
      }
    }
    image->GetPointData()->SetScalars(rgb);
    texture->SetInputData(face, image);
  }
  return texture;
}

struct Instance
{
  const Variant* Spec = nullptr;
  vtkSmartPointer<vtkRenderWindow> Window = mmvtest::NewRenderWindow();
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkVolume> Volume;
  vtkNew<vtkVolumeProperty> Property;
  vtkNew<vtkMultiMaterialVolumeMapper> Mapper;
  vtkSmartPointer<vtkMaterialTransferFunction> Materials;
  std::vector<double> Seconds;
  std::vector<double> CPUSeconds;

  void Render()
  {
    const auto start = Clock::now();
    const double cpu = ProcessCPUSeconds();
    this->Window->Render();
    this->Window->WaitForCompletion();
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
  std::string Out = "reflection-out";
  int Size = 256;
  int Frames = 15;
  std::vector<std::string> Scenes = { "headsq" };
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
  std::ofstream csv(opt.Out + "/reflection.csv");
  csv << "scene,size,variant,reflection,visibility,frames,median_ms,p25_ms,p75_ms,"
         "ratio_to_r0,cpu_median_ms,cpu_p25_ms,cpu_p75_ms,cpu_ratio_to_r0,"
         "irradiance_dims,visibility_pass_updates,renderer\n";

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
      in->Window->SetOffScreenRendering(1);
      in->Window->SetSize(opt.Size, opt.Size);
      in->Window->SetMultiSamples(0);
      in->Window->AddRenderer(in->Renderer);
      in->Renderer->SetBackground(const_cast<double*>(scene.Background));
      // One texture per window: a vtkOpenGLTexture's GL object lives in one
      // context (shared across windows, binding it fails: GL_INVALID_OPERATION).
      in->Renderer->SetEnvironmentTexture(MakeSky());
      in->Renderer->AutomaticLightCreationOff();
      in->Renderer->AddLight(light);
      in->Renderer->SetActiveCamera(camera);
      in->Property->SetColor(scene.Color);
      in->Property->SetScalarOpacity(scene.Opacity);
      in->Property->SetScalarOpacityUnitDistance(scene.UnitDistance);
      in->Property->SetInterpolationTypeToLinear();
      in->Materials = WithReflection(scene.Materials, v.Reflection, v.Others);
      in->Mapper->SetInputData(scene.Image);
      in->Mapper->SetMaterialTransferFunction(in->Materials);
      in->Mapper->SetReflectionVisibility(v.Visibility);
      in->Volume->SetMapper(in->Mapper);
      in->Volume->SetProperty(in->Property);
      in->Renderer->AddVolume(in->Volume);
      in->Render(); // build the tables, irradiance and program: untimed
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
    const std::string renderer = mmvtest::RendererString(instances.front()->Window);
    for (const auto& in : instances)
    {
      const double median = Quantile(in->Seconds, 0.5);
      const double p25 = Quantile(in->Seconds, 0.25);
      const double p75 = Quantile(in->Seconds, 0.75);
      const double cpu = Quantile(in->CPUSeconds, 0.5);
      const double cpu25 = Quantile(in->CPUSeconds, 0.25);
      const double cpu75 = Quantile(in->CPUSeconds, 0.75);
      const int* d = in->Mapper->GetIrradianceDimensions();
      const std::string dims =
        std::to_string(d[0]) + "x" + std::to_string(d[1]) + "x" + std::to_string(d[2]);
      std::cout << std::setw(10) << name << std::setw(18) << in->Spec->Name << "  wall "
                << std::fixed << std::setprecision(1) << 1e3 * median << " ms (" << 1e3 * p25 << "-"
                << 1e3 * p75 << ") x" << std::setprecision(3) << median / base << "  cpu "
                << std::setprecision(1) << 1e3 * cpu << " ms (" << 1e3 * cpu25 << "-" << 1e3 * cpu75
                << ") x" << std::setprecision(3) << cpu / cpuBase << "  irradiance " << dims
                << ", visibility pass updates " << in->Mapper->GetReflectionVisibilityUpdateCount()
                << "\n";
      csv << name << "," << opt.Size << "," << in->Spec->Name << "," << in->Spec->Reflection << ","
          << in->Spec->Visibility << "," << in->Seconds.size() << "," << std::setprecision(4)
          << 1e3 * median << "," << 1e3 * p25 << "," << 1e3 * p75 << "," << median / base << ","
          << 1e3 * cpu << "," << 1e3 * cpu25 << "," << 1e3 * cpu75 << "," << cpu / cpuBase << ","
          << dims << "," << in->Mapper->GetReflectionVisibilityUpdateCount() << ",\"" << renderer
          << "\"\n";
    }
    csv.flush();
  }
  return 0;
}
