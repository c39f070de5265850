// Speed-versus-accuracy benchmark of vtkMultiMaterialVolumeMapper against
// VTK's own GPU shading (Phong, volumetric scattering), with the error of
// every method measured against vtkMultiMaterialReferenceRenderer.
//
//   mmvBenchmark --out DIR [--size N] [--frames N] [--light-frames N]
//                [--scenes synthetic,headsq,orbital] [--head FILE.vti] [--quick]
//                [--reference-exponential]  (the ground truth's diffusion exact in time;
//                                            default: 8 backward-Euler steps)
//
// Every (scene, method) pair gets its own offscreen window; all windows share
// one camera and one light. Frames are timed interleaved, method after method
// for the same camera position (the order rotating every frame), so machine
// drift hits every method alike; medians are reported. Writes DIR/benchmark.csv,
// DIR/machine.txt and, in DIR/images, the reference, a few method images and
// their error heat maps. Not a test: it asserts nothing about timings.
#include "mmvBenchmarkScenes.h"
#include "mmvTestWindow.h"

#include "vtkCamera.h"
#include "vtkImageErrorMetrics.h"
#include "vtkLight.h"
#include "vtkMultiMaterialParameters.h"
#include "vtkMultiMaterialReferenceRenderer.h"
#include "vtkMultiMaterialVolumeMapper.h"
#include "vtkNew.h"
#include "vtkOpenGLGPUVolumeRayCastMapper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPreIntegrationTable.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSMPTools.h"
#include "vtkUnsignedCharArray.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <sys/stat.h>
#include <thread>
#include <vector>

namespace
{
using Clock = std::chrono::steady_clock;

double Since(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

double Median(std::vector<double> v)
{
  if (v.empty())
  {
    return std::nan("");
  }
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

struct MethodSpec
{
  std::string Name;
  std::string Family;           // "ours", "vtk-phong" or "vtk-scattering"
  double IrradianceScale = 0.0; // ours; 0: chosen from the memory budget
  double SampleVoxels = 1.0;    // sample distance in smallest-spacing units
  bool PreIntegration = true;
  bool Scattering = true;
  bool BackwardEuler = false; // ours: the diffusion's former default integrator
  double Blending = 0.0;      // VTK volumetric scattering
  double Reach = 0.0;
};

// What one method measured.
struct Result
{
  MethodSpec Spec;
  double FirstFrame = std::nan("");
  double PreIntegration = std::nan("");
  double Irradiance = std::nan("");
  int IrradianceDims[3] = { 0, 0, 0 };
  std::vector<double> Interaction;
  std::vector<double> InteractionRayCast;
  std::vector<double> LightChange;
  std::vector<double> LightIrradiance;
  double MemoryBytes = 0.0;
  double PSNR = 0.0;
  double SSIM = 0.0;
  double RMSE = 0.0;
};

std::string Number(double v)
{
  std::ostringstream s;
  s << v;
  return s.str();
}

/**
 * One window per entry, each a list of methods it renders. Ours at its
 * defaults, the irradiance-resolution sweep (paper Fig. 6) and scattering off
 * each get a window; the sample-distance sweep with and without
 * pre-integration (paper Fig. 9) shares one window, since neither setting
 * changes the irradiance volume: that window cycles through its variants
 * (an untimed render after each switch absorbs the table rebuild and shader
 * change) instead of paying one more full irradiance estimation per variant.
 * The full product of settings (48 per scene) would take hours on a software
 * rasteriser. VTK: Phong, and volumetric scattering at blending 1 and 2
 * times reach 0.25 and 1.
 */
std::vector<std::vector<MethodSpec>> MakeMethods(bool quick)
{
  std::vector<std::vector<MethodSpec>> windows;
  windows.push_back({ { "ours", "ours" } });
  if (!quick)
  {
    std::vector<MethodSpec> sweep;
    for (bool pre : { true, false })
    {
      for (double sd : { 0.5, 1.0, 2.0, 4.0 })
      {
        if (pre && sd == 1.0)
        {
          continue; // the default window
        }
        MethodSpec s{ "ours sd=" + Number(sd) + (pre ? "" : " no-preint"), "ours" };
        s.SampleVoxels = sd;
        s.PreIntegration = pre;
        sweep.push_back(s);
      }
    }
    windows.push_back(sweep);
    for (double scale : { 0.25, 0.5 })
    {
      MethodSpec s{ "ours irr=" + Number(scale), "ours" };
      s.IrradianceScale = scale;
      windows.push_back({ s });
    }
    MethodSpec noScatter{ "ours no-scattering", "ours" };
    noScatter.Scattering = false;
    windows.push_back({ noScatter });
    MethodSpec euler{ "ours backward-euler", "ours" };
    euler.BackwardEuler = true;
    windows.push_back({ euler });
  }
  windows.push_back({ { "vtk phong", "vtk-phong" } });
  if (!quick)
  {
    for (double blending : { 1.0, 2.0 })
    {
      for (double reach : { 0.25, 1.0 })
      {
        MethodSpec s{ "vtk scatter b=" + Number(blending) + " reach=" + Number(reach),
          "vtk-scattering" };
        s.Blending = blending;
        s.Reach = reach;
        windows.push_back({ s });
      }
    }
  }
  return windows;
}

// One window rendering one scene with one or more methods.
struct Instance : mmvbench::View
{
  std::vector<Result> Results;
  vtkSmartPointer<vtkOpenGLGPUVolumeRayCastMapper> Mapper;
  vtkMultiMaterialVolumeMapper* Ours = nullptr;
  double SmallestSpacing = 1.0;

  double Render()
  {
    const auto start = Clock::now();
    this->RenderWindow->Render();
    this->RenderWindow->WaitForCompletion();
    return Since(start);
  }

  // Switches to variant v; with several variants, renders once untimed so
  // the timed frame that follows pays no table rebuild or shader change.
  void Select(size_t v, bool warm)
  {
    const MethodSpec& m = this->Results[v].Spec;
    this->Mapper->SetSampleDistance(static_cast<float>(m.SampleVoxels * this->SmallestSpacing));
    if (this->Ours)
    {
      this->Ours->SetPreIntegration(m.PreIntegration);
    }
    if (warm && this->Results.size() > 1)
    {
      this->Render();
    }
  }

  vtkSmartPointer<vtkImageData> Grab(int size)
  {
    vtkNew<vtkUnsignedCharArray> rgb;
    this->RenderWindow->GetPixelData(0, 0, size - 1, size - 1, 0, rgb);
    auto image = vtkSmartPointer<vtkImageData>::New();
    image->SetDimensions(size, size, 1);
    image->GetPointData()->SetScalars(rgb);
    return image;
  }
};

struct Options
{
  std::string Out = "benchmark-out";
  int Size = 256;
  int Frames = 8;
  int LightFrames = 4;
  std::vector<std::string> Scenes = { "synthetic", "headsq", "orbital" };
  std::string Head = MMV_HEADSQ_PATH;
  bool Quick = false;
  bool ReferenceExponential = false; // the ground truth's diffusion integrated exactly
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
    else if (a == "--frames")
    {
      o.Frames = std::atoi(next().c_str());
    }
    else if (a == "--light-frames")
    {
      o.LightFrames = std::atoi(next().c_str());
    }
    else if (a == "--scenes")
    {
      o.Scenes = mmvbench::SplitList(next());
    }
    else if (a == "--head")
    {
      o.Head = next();
    }
    else if (a == "--quick")
    {
      o.Quick = true;
    }
    else if (a == "--reference-exponential")
    {
      o.ReferenceExponential = true;
    }
    else
    {
      return false;
    }
  }
  return o.Size >= 16 && o.Frames >= 1 && o.LightFrames >= 1 && !o.Out.empty();
}

std::string FileStem(const std::string& scene, const std::string& method)
{
  std::string s = scene + "_" + method;
  for (char& c : s)
  {
    c = std::isalnum(static_cast<unsigned char>(c)) || c == '.' ? c : '_';
  }
  return s;
}

void Rotate(double v[3], const double axis[3], double degrees)
{
  // Rodrigues' formula about a unit axis.
  const double a = degrees * M_PI / 180.0;
  const double c = std::cos(a);
  const double s = std::sin(a);
  const double d = axis[0] * v[0] + axis[1] * v[1] + axis[2] * v[2];
  const double x[3] = { axis[1] * v[2] - axis[2] * v[1], axis[2] * v[0] - axis[0] * v[2],
    axis[0] * v[1] - axis[1] * v[0] };
  for (int i = 0; i < 3; ++i)
  {
    v[i] = v[i] * c + x[i] * s + axis[i] * d * (1.0 - c);
  }
}

void Normalize(double v[3])
{
  const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  for (int i = 0; i < 3; ++i)
  {
    v[i] /= n;
  }
}

// Median seconds to build the scene's 256^2 segment table (the step changes
// between builds so each Update() really rebuilds).
double PreIntegrationTableSeconds(const mmvbench::SceneSpec& scene, double step)
{
  vtkNew<vtkPreIntegrationTable> table;
  table->SetColorTransferFunction(scene.Color);
  table->SetScalarOpacity(scene.Opacity);
  table->SetMaterialTransferFunction(scene.Materials);
  table->SetScalarOpacityUnitDistance(scene.UnitDistance);
  table->SetTableSize(256);
  double range[2];
  scene.Image->GetPointData()->GetScalars()->GetRange(range);
  table->SetScalarRange(range);
  std::vector<double> seconds;
  for (int i = 0; i < 7; ++i)
  {
    table->SetStepLength(step * (1.0 + 0.01 * i));
    table->Update();
    seconds.push_back(table->GetLastBuildSeconds());
  }
  return Median(seconds);
}

void SetUpInstance(Instance& in, const mmvbench::SceneSpec& scene, vtkCamera* camera,
  vtkLight* light, int size, double smallestSpacing)
{
  const MethodSpec& m = in.Results.front().Spec;
  in.SmallestSpacing = smallestSpacing;
  if (m.Family == "ours")
  {
    vtkNew<vtkMultiMaterialVolumeMapper> ours;
    ours->SetMaterialTransferFunction(scene.Materials);
    ours->SetIrradianceScale(m.IrradianceScale);
    ours->SetPreIntegration(m.PreIntegration);
    ours->SetMultipleScattering(m.Scattering);
    ours->SetExponentialDiffusion(!m.BackwardEuler);
    ours->TimeStagesOn();
    in.Ours = ours;
    in.Mapper = ours;
  }
  else
  {
    in.Mapper = vtkSmartPointer<vtkOpenGLGPUVolumeRayCastMapper>::New();
    mmvbench::ShadeWithDefaultMaterial(in.Property);
    if (m.Family == "vtk-scattering")
    {
      in.Mapper->SetVolumetricScatteringBlending(static_cast<float>(m.Blending));
      in.Mapper->SetGlobalIlluminationReach(static_cast<float>(m.Reach));
    }
  }
  in.SetUp(scene, camera, light, size, in.Mapper);
  in.Mapper->AutoAdjustSampleDistancesOff();
  in.Mapper->LockSampleDistanceToInputSpacingOff();
  in.Select(0, false);
}

/// The first frame of every method: set-up, stage timers, and the image
/// compared with the ground truth (written with its error heat map).
void MeasureFirstFrames(std::vector<std::unique_ptr<Instance>>& instances,
  const mmvbench::SceneSpec& scene, const std::string& name, const Options& opt,
  const std::string& imageDir, vtkImageData* truth, std::ofstream& machine, bool& rendererReported)
{
  vtkNew<vtkImageErrorMetrics> metrics;
  const int bytesPerScalar = scene.Image->GetPointData()->GetScalars()->GetDataTypeSize();
  for (auto& in : instances)
  {
    for (size_t v = 0; v < in->Results.size(); ++v)
    {
      Result& r = in->Results[v];
      in->Select(v, false);
      r.FirstFrame = in->Render();
      if (!rendererReported)
      {
        machine << "renderer " << mmvtest::RendererString(in->RenderWindow) << "\n";
        rendererReported = true;
      }
      if (in->Ours)
      {
        r.PreIntegration = in->Ours->GetLastPreIntegrationSeconds();
        r.Irradiance = in->Ours->GetLastIrradianceSeconds();
        in->Ours->GetIrradianceDimensions(r.IrradianceDims);
        if (!in->Ours->GetMultiMaterialActive())
        {
          std::cerr << "warning: " << r.Spec.Name << " fell back to VTK's shading\n";
        }
      }
      vtkSmartPointer<vtkImageData> image = in->Grab(opt.Size);
      metrics->Compute(image, truth);
      r.PSNR = metrics->GetPSNR();
      r.SSIM = metrics->GetSSIM();
      r.RMSE = metrics->GetRMSE();
      // VTK's methods: the scalar texture (estimated: one value per voxel
      // at the data's size); ours adds its own textures.
      r.MemoryBytes = static_cast<double>(scene.Image->GetNumberOfPoints()) * bytesPerScalar +
        (in->Ours ? static_cast<double>(in->Ours->GetMultiMaterialMemoryBytes()) : 0.0);
      const std::string stem = imageDir + "/" + FileStem(name, r.Spec.Name);
      vtkImageErrorMetrics::WritePNG((stem + ".png").c_str(), image);
      metrics->WriteErrorHeatMap((stem + "_error.png").c_str(), image, truth, 64.0);
    }
  }
}

/// Camera moves: azimuth steps about the view-up, window after window.
void TimeCameraMoves(
  std::vector<std::unique_ptr<Instance>>& instances, vtkCamera* camera, int frames)
{
  const size_t count = instances.size();
  for (int f = 0; f < frames; ++f)
  {
    camera->Azimuth(10.0);
    for (size_t n = 0; n < count; ++n)
    {
      Instance& in = *instances[(n + f) % count];
      for (size_t v = 0; v < in.Results.size(); ++v)
      {
        in.Select(v, true);
        in.Results[v].Interaction.push_back(in.Render());
        if (in.Ours)
        {
          in.Results[v].InteractionRayCast.push_back(in.Ours->GetLastRayCastSeconds());
        }
      }
    }
  }
}

/// Light changes: the key light turns about the view-up. The sweep window
/// is skipped: its irradiance volume is the default window's.
void TimeLightChanges(std::vector<std::unique_ptr<Instance>>& instances, vtkCamera* camera,
  vtkLight* light, const double toLight[3], const double center[3], int lightFrames)
{
  const size_t count = instances.size();
  for (int f = 0; f < lightFrames; ++f)
  {
    double l[3] = { toLight[0], toLight[1], toLight[2] };
    Rotate(l, camera->GetViewUp(), 15.0 * (f + 1));
    light->SetPosition(center[0] + l[0], center[1] + l[1], center[2] + l[2]);
    for (size_t n = 0; n < count; ++n)
    {
      Instance& in = *instances[(n + f) % count];
      if (in.Results.size() > 1)
      {
        continue;
      }
      in.Results[0].LightChange.push_back(in.Render());
      if (in.Ours)
      {
        in.Results[0].LightIrradiance.push_back(in.Ours->GetLastIrradianceSeconds());
      }
    }
  }
}

/// One CSV row and one printed line per method of the scene.
void WriteResults(const std::vector<std::unique_ptr<Instance>>& instances, const std::string& name,
  const Options& opt, double preintTable, double referenceSeconds, std::ofstream& csv)
{
  for (auto& in : instances)
  {
    for (const Result& r : in->Results)
    {
      const MethodSpec& m = r.Spec;
      std::ostringstream dims;
      dims << r.IrradianceDims[0] << "x" << r.IrradianceDims[1] << "x" << r.IrradianceDims[2];
      const bool ours = in->Ours != nullptr;
      csv << std::setprecision(6) << name << "," << m.Name << "," << m.Family << ","
          << (ours ? m.IrradianceScale : 0.0) << "," << (ours ? dims.str() : "") << ","
          << m.SampleVoxels << "," << (ours ? int(m.PreIntegration) : 0) << ","
          << (ours ? int(m.Scattering) : 0) << "," << m.Blending << "," << m.Reach << ","
          << 1e3 * r.FirstFrame << "," << 1e3 * r.PreIntegration << "," << 1e3 * r.Irradiance << ","
          << 1e3 * Median(r.InteractionRayCast) << "," << 1e3 * Median(r.Interaction) << ","
          << 1e3 * Median(r.LightChange) << "," << 1e3 * Median(r.LightIrradiance) << ","
          << 1e3 * preintTable << "," << r.MemoryBytes / (1024.0 * 1024.0) << "," << r.PSNR << ","
          << r.SSIM << "," << r.RMSE << "," << referenceSeconds << "," << opt.Size << ","
          << opt.Frames << "," << opt.LightFrames << "\n";
      std::cout << std::setw(30) << std::left << m.Name << std::right << std::fixed
                << std::setprecision(1) << " frame " << std::setw(7) << 1e3 * Median(r.Interaction)
                << " ms  light " << std::setw(8) << 1e3 * Median(r.LightChange) << " ms  PSNR "
                << std::setw(5) << r.PSNR << " dB  SSIM " << std::setprecision(3) << r.SSIM << "\n"
                << std::defaultfloat;
    }
  }
}

/// One scene: its windows, the ground truth, every method's first frame,
/// the timed camera moves and light changes, and its rows. False if the
/// scene or its reference could not be made.
bool RunScene(const std::string& name, const Options& opt,
  const std::vector<std::vector<MethodSpec>>& windows, const std::string& imageDir,
  std::ofstream& csv, std::ofstream& machine, bool& rendererReported)
{
  mmvbench::SceneSpec scene = mmvbench::MakeScene(name, opt.Head);
  if (!scene.Image)
  {
    std::cerr << "unknown or unreadable scene " << name << "\n";
    return false;
  }
  const double* spacing = scene.Image->GetSpacing();
  const double smallestSpacing = std::min({ spacing[0], spacing[1], spacing[2] });
  double bounds[6];
  scene.Image->GetBounds(bounds);
  const double center[3] = { 0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3]),
    0.5 * (bounds[4] + bounds[5]) };

  // The shared camera and key light (mmvbench::FrameScene).
  vtkNew<vtkCamera> camera;
  vtkNew<vtkLight> light;
  double radius = 0.0;
  const double distance = mmvbench::FrameScene(scene, camera, light, radius);
  double toLight[3] = { scene.ToLight[0], scene.ToLight[1], scene.ToLight[2] };
  Normalize(toLight);

  std::vector<std::unique_ptr<Instance>> instances;
  for (const std::vector<MethodSpec>& methods : windows)
  {
    instances.push_back(std::make_unique<Instance>());
    for (const MethodSpec& m : methods)
    {
      Result r;
      r.Spec = m;
      instances.back()->Results.push_back(r);
    }
    SetUpInstance(*instances.back(), scene, camera, light, opt.Size, smallestSpacing);
  }
  camera->SetClippingRange(distance - 1.05 * radius, distance + 1.05 * radius);

  // Ground truth at the first camera position.
  std::cout << "== " << name << ": reference " << opt.Size << "^2 ..." << std::flush;
  vtkNew<vtkMultiMaterialReferenceRenderer> reference;
  reference->SetInputData(scene.Image);
  reference->SetVolumeProperty(instances.front()->Property);
  reference->SetMaterialTransferFunction(scene.Materials);
  reference->SetExponentialDiffusion(opt.ReferenceExponential);
  vtkSmartPointer<vtkImageData> truth =
    reference->Render(instances.front()->Renderer, opt.Size, opt.Size);
  if (!truth)
  {
    return false;
  }
  std::cout << " " << reference->GetLastRenderSeconds() << " s (scattering "
            << reference->GetLastScatteringSeconds() << " s)\n";
  vtkImageErrorMetrics::WritePNG((imageDir + "/" + name + "_reference.png").c_str(), truth);

  const double preintTable = PreIntegrationTableSeconds(scene, smallestSpacing);
  MeasureFirstFrames(instances, scene, name, opt, imageDir, truth, machine, rendererReported);
  TimeCameraMoves(instances, camera, opt.Frames);
  TimeLightChanges(instances, camera, light, toLight, center, opt.LightFrames);
  WriteResults(instances, name, opt, preintTable, reference->GetLastRenderSeconds(), csv);
  return true;
}
} // namespace

int main(int argc, char* argv[])
{
  Options opt;
  if (!Parse(argc, argv, opt))
  {
    std::cerr << "usage: " << argv[0]
              << " --out DIR [--size N] [--frames N] [--light-frames N]"
                 " [--scenes synthetic,headsq,orbital] [--head FILE.vti] [--quick]\n";
    return 2;
  }
  vtkSMPTools::SetBackend("STDThread");
  mkdir(opt.Out.c_str(), 0755);
  const std::string imageDir = opt.Out + "/images";
  mkdir(imageDir.c_str(), 0755);

  std::ofstream csv(opt.Out + "/benchmark.csv");
  csv << "scene,method,family,irradiance_scale,irradiance_dims,sample_voxels,preintegration,"
         "scattering,blending,reach,first_frame_ms,preint_ms,irradiance_ms,raycast_ms,"
         "interaction_ms,light_change_ms,light_irradiance_ms,preint_table_256_ms,gpu_memory_mb,"
         "psnr,ssim,rmse,reference_s,size,frames,light_frames\n";
  std::ofstream machine(opt.Out + "/machine.txt");
  machine << "cores " << std::thread::hardware_concurrency() << "\nsize " << opt.Size << "\nframes "
          << opt.Frames << "\nlight_frames " << opt.LightFrames << "\n";

  const std::vector<std::vector<MethodSpec>> windows = MakeMethods(opt.Quick);
  bool rendererReported = false;
  for (const std::string& name : opt.Scenes)
  {
    if (!RunScene(name, opt, windows, imageDir, csv, machine, rendererReported))
    {
      return 1;
    }
    csv.flush();
  }
  return 0;
}
