// What a change costs, in C++ and so on any OpenGL (a headless GPU too):
// camera moves under the light kit, an opacity-point drag, a colour-only edit
// and time steps, on the smooth MR head and on the fine chest, against VTK's
// GPU ray caster with Shade on; and the frame rate of a large volume while
// its opacity is edited. The C++ twin of pv_lighting_changes.py (same
// transfer functions, same changes), without ParaView.
//
//   mmvChangeBenchmark --out DIR [--head FILE.vti] [--chest PREFIX] [--size N]
//                      [--changes N] [--steps N] [--large N] [--large-size N]
//                      [--large-edits N] [--only changes|large]
//                      [--volumes head,chest]
//                      [--methods mmv-default,mmv-skin,mmv-smoke,mmv-sky]
//
// --chest PREFIX reads PREFIX_K.raw, K = 0 .. steps-1: 256 x 256 x 128
// uint16 written by mmv_fine_volume.py (chest(dims, phase=K/steps).tofile);
// without it only the head runs. --large N resamples each volume to N^3 and
// renders it at --large-size pixels with `skin` (s = 8) under the light kit.
//
// Each method has its own window; after every change each window renders one
// still frame, in an order that rotates. Writes DIR/changes_cxx.csv (medians
// per volume, sequence and method, ratios to VTK's Phong and to the method's
// own still frame, irradiance updates) and DIR/large_opacity_cxx.csv. Not a
// test: it asserts nothing about timings.
#include "mmvBenchmarkScenes.h"
#include "mmvTestWindow.h"

#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkImageData.h"
#include "vtkImageResample.h"
#include "vtkLightKit.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMath.h"
#include "vtkMultiMaterialVolumeMapper.h"
#include "vtkNew.h"
#include "vtkOpenGLGPUVolumeRayCastMapper.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkUnsignedShortArray.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <sys/stat.h>
#include <vector>

namespace
{
// pv_lightkit_orbit.py's transfer functions: (value, opacity) and
// (value, r, g, b) over the MR head's range, shared by every method.
const double OpacityPoints[][2] = { { 0.0, 0.0 }, { 500.0, 0.0 }, { 800.0, 0.12 }, { 1100.0, 0.2 },
  { 1400.0, 0.8 }, { 3926.0, 0.9 } };
const double ColorPoints[][4] = { { 0.0, 0.0, 0.0, 0.0 }, { 500.0, 0.35, 0.3, 0.28 },
  { 900.0, 0.78, 0.68, 0.62 }, { 1400.0, 0.93, 0.9, 0.82 }, { 3926.0, 1.0, 1.0, 1.0 } };
const double ValueRange[2] = { 0.0, 3926.0 };
const double OpacityUnitDistance = 2.0;

double Median(std::vector<double> v)
{
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n == 0 ? std::nan("") : (n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]));
}

double Seconds(vtkRenderWindow* window)
{
  const auto start = std::chrono::steady_clock::now();
  window->Render();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// The shared transfer functions: every window reads the same objects, as
/// ParaView's views share one colour map.
struct TransferFunctions
{
  vtkNew<vtkPiecewiseFunction> Opacity;
  vtkNew<vtkColorTransferFunction> Color;
  double DraggedOpacity = 0.2;

  TransferFunctions() { this->Reset(); }
  void Reset()
  {
    this->Opacity->RemoveAllPoints();
    for (const auto& p : OpacityPoints)
    {
      this->Opacity->AddPoint(p[0], p[1]);
    }
    this->Color->RemoveAllPoints();
    for (const auto& p : ColorPoints)
    {
      this->Color->AddRGBPoint(p[0], p[1], p[2], p[3]);
    }
    this->DraggedOpacity = 0.2;
  }
  /// One step of the drag: the 1100 point's opacity + 0.02.
  void DragOpacity()
  {
    this->DraggedOpacity += 0.02;
    this->Opacity->AddPoint(1100.0, this->DraggedOpacity);
  }
  /// A colour-only edit: the 900 point's green.
  void Recolour(int change)
  {
    this->Color->AddRGBPoint(900.0, 0.78, 0.6 + 0.04 * (change % 4), 0.62);
  }
};

/// One method in its own window, under ParaView's light kit.
struct View : mmvbench::VolumeWindow
{
  std::string Name;

  /// `preset` empty: VTK's Phong; "default": ours with no material nodes;
  /// "sky": the default material lit by the environment too (strength 1).
  View(const std::string& name, const std::string& preset, vtkImageData* image,
    TransferFunctions& tf, int size)
    : Name(name)
  {
    this->Window->SetOffScreenRendering(1);
    this->Window->SetSize(size, size);
    this->Window->SetMultiSamples(0);
    this->Window->AddRenderer(this->Renderer);
    this->Renderer->SetBackground(0.32, 0.34, 0.43); // ParaView's default
    this->Property->SetColor(tf.Color);
    this->Property->SetScalarOpacity(tf.Opacity);
    this->Property->SetScalarOpacityUnitDistance(OpacityUnitDistance);
    this->Property->SetInterpolationTypeToLinear();
    if (preset.empty())
    {
      this->Mapper = vtkSmartPointer<vtkOpenGLGPUVolumeRayCastMapper>::New();
      this->Property->ShadeOn();
    }
    else
    {
      vtkNew<vtkMultiMaterialVolumeMapper> mapper;
      if (preset == "sky")
      {
        mapper->SetEnvironmentLighting(1.0);
      }
      else if (preset != "default")
      {
        this->Materials->ApplyPreset(preset.c_str(), ValueRange[0], ValueRange[1]);
      }
      mapper->SetMaterialTransferFunction(this->Materials);
      this->Ours = mapper;
      this->Mapper = mapper;
    }
    this->Mapper->SetInputData(image);
    this->Mapper->SetAutoAdjustSampleDistances(0);
    this->Volume->SetMapper(this->Mapper);
    this->Volume->SetProperty(this->Property);
    this->Renderer->AddVolume(this->Volume);
    this->Renderer->RemoveAllLights();
    vtkNew<vtkLightKit> kit;
    kit->AddLightsToRenderer(this->Renderer);
    this->Renderer->ResetCamera();
    this->Renderer->GetActiveCamera()->Elevation(-80.0);
    this->Renderer->GetActiveCamera()->OrthogonalizeViewUp();
    this->Renderer->ResetCamera();
    this->Renderer->GetActiveCamera()->Zoom(1.3);
    this->Window->SetDesiredUpdateRate(0.0001); // still frames
  }

  int Updates() const { return this->Ours ? this->Ours->GetIrradianceUpdateCount() : 0; }
};

/// One uint16 volume of 256 x 256 x 128 from a raw file; nullptr if unread.
vtkSmartPointer<vtkImageData> ReadRaw(const std::string& path)
{
  const int dims[3] = { 256, 256, 128 };
  const size_t count = static_cast<size_t>(dims[0]) * dims[1] * dims[2];
  std::ifstream in(path, std::ios::binary);
  if (!in)
  {
    return nullptr;
  }
  vtkNew<vtkUnsignedShortArray> values;
  values->SetName("ImageFile");
  values->SetNumberOfValues(static_cast<vtkIdType>(count));
  in.read(reinterpret_cast<char*>(values->GetPointer(0)), count * sizeof(unsigned short));
  if (!in)
  {
    std::cerr << path << ": shorter than 256 x 256 x 128 uint16\n";
    return nullptr;
  }
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(dims);
  image->GetPointData()->SetScalars(values);
  return image;
}

/// The head's series: the CT-sized head with its values pulsing by 4 %, as
/// pv_lighting_changes.py's.
std::vector<vtkSmartPointer<vtkImageData>> HeadSeries(const std::string& head, int steps)
{
  std::vector<vtkSmartPointer<vtkImageData>> series;
  mmvbench::SceneSpec scene = mmvbench::MakeCTSized(head);
  if (!scene.Image)
  {
    return series;
  }
  vtkDataArray* base = scene.Image->GetPointData()->GetScalars();
  for (int k = 0; k < steps; ++k)
  {
    const double gain = 1.0 + 0.04 * std::sin(2.0 * vtkMath::Pi() * k / steps);
    auto image = vtkSmartPointer<vtkImageData>::New();
    image->CopyStructure(scene.Image);
    auto values = vtkSmartPointer<vtkDataArray>::Take(base->NewInstance());
    values->SetName("ImageFile");
    values->SetNumberOfTuples(base->GetNumberOfTuples());
    for (vtkIdType i = 0; i < base->GetNumberOfTuples(); ++i)
    {
      values->SetTuple1(i, gain * base->GetTuple1(i));
    }
    image->GetPointData()->SetScalars(values);
    series.push_back(image);
  }
  return series;
}

/// Whether `name` is in the comma-separated `list` (an empty list holds all).
bool Listed(const std::string& list, const std::string& name)
{
  return list.empty() || ("," + list + ",").find("," + name + ",") != std::string::npos;
}

struct Record
{
  std::vector<double> Seconds;
  int Updates = 0;
};

/// The methods (name, preset) of `wanted`; VTK's Phong always, as every
/// ratio's reference.
std::vector<std::pair<std::string, std::string>> WantedMethods(const std::string& wanted)
{
  std::vector<std::pair<std::string, std::string>> methods;
  for (const auto& m : std::vector<std::pair<std::string, std::string>>{ { "vtk-phong", "" },
         { "mmv-default", "default" }, { "mmv-skin", "skin" }, { "mmv-smoke", "smoke" },
         { "mmv-sky", "sky" } })
  {
    if (m.first == "vtk-phong" || Listed(wanted, m.first))
    {
      methods.push_back(m);
    }
  }
  return methods;
}

/// Where an opacity edit and a colour edit of ours go (stage timers: a
/// glFinish per stage).
void PrintOpacityEditStages(
  const std::string& volume, std::vector<std::unique_ptr<View>>& views, TransferFunctions& tf)
{
  for (auto& v : views)
  {
    if (v->Ours && v->Name != "mmv-smoke")
    {
      v->Ours->TimeStagesOn();
      tf.DragOpacity();
      v->Window->Render();
      std::printf("%s %s opacity edit: %s; ray cast %.4f s\n  irradiance: %s\n", volume.c_str(),
        v->Name.c_str(), v->Ours->GetLastPrepareStages().c_str(), v->Ours->GetLastRayCastSeconds(),
        v->Ours->GetLastIrradianceStages().c_str());
      tf.Recolour(1);
      v->Window->Render();
      std::printf(
        "%s %s colour edit: %s (of the tables, pre-integration %.4f s); ray cast %.4f s\n",
        volume.c_str(), v->Name.c_str(), v->Ours->GetLastPrepareStages().c_str(),
        v->Ours->GetLastPreIntegrationSeconds(), v->Ours->GetLastRayCastSeconds());
      v->Ours->TimeStagesOff();
    }
  }
}

/// Where a time step of ours goes: `step` with every value one higher (new
/// values, which nothing kept holds) with the stage timers on.
void PrintTimeStepStages(
  const std::string& volume, std::vector<std::unique_ptr<View>>& views, vtkImageData* step)
{
  vtkNew<vtkImageData> copy;
  copy->DeepCopy(step);
  vtkDataArray* values = copy->GetPointData()->GetScalars();
  for (vtkIdType i = 0; i < values->GetNumberOfTuples(); ++i)
  {
    values->SetTuple1(i, values->GetTuple1(i) + 1.0);
  }
  for (auto& v : views)
  {
    if (v->Ours && v->Name != "mmv-skin")
    {
      v->Ours->TimeStagesOn();
      v->Mapper->SetInputData(copy);
      v->Window->Render();
      std::printf("%s %s time step: %s; ray cast %.4f s\n  irradiance: %s\n", volume.c_str(),
        v->Name.c_str(), v->Ours->GetLastPrepareStages().c_str(), v->Ours->GetLastRayCastSeconds(),
        v->Ours->GetLastIrradianceStages().c_str());
      v->Ours->TimeStagesOff();
    }
  }
}

/// The medians per sequence and method, with their ratios to VTK's Phong and
/// to the method's own still frame: rows of `csv` and a printed table.
void ReportRecords(const std::string& volume,
  const std::vector<std::pair<std::string, std::string>>& methods,
  std::map<std::pair<std::string, std::string>, Record>& records, std::ofstream& csv,
  const std::string& renderer)
{
  std::printf("%-6s %-9s %-12s %9s %9s %9s %5s\n", "volume", "sequence", "method", "median s",
    "x phong", "x still", "upd");
  for (const char* sequence : { "still", "orbit", "opacity", "colour", "series", "series-2" })
  {
    for (const auto& m : methods)
    {
      auto it = records.find({ sequence, m.first });
      if (it == records.end())
      {
        continue;
      }
      const double median = Median(it->second.Seconds);
      const double phong = Median(records[{ sequence, "vtk-phong" }].Seconds);
      const double still = Median(records[{ "still", m.first }].Seconds);
      csv << volume << "," << sequence << "," << m.first << "," << it->second.Seconds.size() << ","
          << median << "," << median / phong << "," << median / still << "," << it->second.Updates
          << ",\"" << renderer << "\"\n";
      std::printf("%-6s %-9s %-12s %9.4f %9.2f %9.2f %5d\n", volume.c_str(), sequence,
        m.first.c_str(), median, median / phong, median / still, it->second.Updates);
    }
  }
}

/// The sequences of one volume; appends rows to `csv`.
void RunVolume(const std::string& volume, const std::vector<vtkSmartPointer<vtkImageData>>& series,
  int size, int changes, const std::string& wanted, std::ofstream& csv, const std::string& renderer)
{
  TransferFunctions tf;
  const std::vector<std::pair<std::string, std::string>> methods = WantedMethods(wanted);
  std::vector<std::unique_ptr<View>> views;
  for (const auto& m : methods)
  {
    views.push_back(std::make_unique<View>(m.first, m.second, series[0], tf, size));
  }
  for (int warm = 0; warm < 2; ++warm)
  {
    for (auto& v : views)
    {
      v->Window->Render();
    }
  }
  std::map<std::pair<std::string, std::string>, Record> records;
  int turn = 0;
  // One change, then one still frame per view in a rotating order; `smoke`
  // only in still frames and the series (as in pv_lighting_changes.py).
  auto each = [&](const std::string& sequence, const auto& apply)
  {
    apply();
    const size_t shift = turn++ % views.size();
    for (size_t i = 0; i < views.size(); ++i)
    {
      View& v = *views[(i + shift) % views.size()];
      const bool series = sequence.rfind("series", 0) == 0;
      if ((v.Name == "mmv-smoke" && !series && sequence != "still") ||
        (v.Name == "mmv-skin" && series))
      {
        continue;
      }
      const int before = v.Updates();
      Record& r = records[{ sequence, v.Name }];
      r.Seconds.push_back(Seconds(v.Window));
      r.Updates += v.Updates() - before;
    }
  };
  for (int c = 0; c < changes; ++c)
  {
    each("still", [] {});
  }
  for (int c = 0; c < changes; ++c)
  {
    each("orbit",
      [&]
      {
        for (auto& v : views)
        {
          v->Renderer->GetActiveCamera()->Azimuth(10.0);
          v->Renderer->GetActiveCamera()->OrthogonalizeViewUp();
          v->Renderer->ResetCameraClippingRange();
        }
      });
  }
  for (int c = 0; c < changes; ++c)
  {
    each("opacity", [&] { tf.DragOpacity(); });
  }
  for (int c = 0; c < changes; ++c)
  {
    each("colour", [&] { tf.Recolour(c); });
  }
  PrintOpacityEditStages(volume, views, tf);
  // The series with the irradiance of each step kept (what ParaView's
  // animation caching asks of the representation).
  for (auto& v : views)
  {
    if (v->Ours)
    {
      v->Ours->SetIrradianceCacheMB(4096.0);
    }
    v->Window->Render();
  }
  for (int loop = 0; loop < 2; ++loop)
  {
    for (size_t k = loop == 0 ? 1 : 0; k < series.size(); ++k)
    {
      each(loop == 0 ? "series" : "series-2",
        [&]
        {
          for (auto& v : views)
          {
            v->Mapper->SetInputData(series[k]);
          }
        });
    }
  }
  PrintTimeStepStages(volume, views, series.back());
  ReportRecords(volume, methods, records, csv, renderer);
}

/// A volume resampled to n^3.
vtkSmartPointer<vtkImageData> Resampled(vtkImageData* image, int n)
{
  int dims[3];
  image->GetDimensions(dims);
  vtkNew<vtkImageResample> resample;
  resample->SetInputData(image);
  resample->SetInterpolationModeToLinear();
  for (int a = 0; a < 3; ++a)
  {
    resample->SetAxisMagnificationFactor(a, (n - 1.0) / (dims[a] - 1.0));
  }
  resample->Update();
  auto out = vtkSmartPointer<vtkImageData>::New();
  out->ShallowCopy(resample->GetOutput());
  return out;
}

/// Opacity edits of a large volume: one still frame per edit, ours with
/// `skin` (s = 8) beside VTK's Phong; frames per second = 1 / median.
void RunLarge(const std::string& volume, vtkImageData* image, int size, int edits,
  std::ofstream& csv, const std::string& renderer)
{
  TransferFunctions tf;
  std::vector<std::unique_ptr<View>> views;
  views.push_back(std::make_unique<View>("vtk-phong", "", image, tf, size));
  views.push_back(std::make_unique<View>("mmv-skin", "skin", image, tf, size));
  for (int warm = 0; warm < 2; ++warm)
  {
    for (auto& v : views)
    {
      v->Window->Render();
    }
  }
  std::vector<std::vector<double>> still(views.size()), interactive(views.size());
  for (int e = 0; e < edits; ++e)
  {
    tf.DragOpacity();
    for (size_t i = 0; i < views.size(); ++i)
    {
      View& v = *views[(i + e) % views.size()];
      still[(i + e) % views.size()].push_back(Seconds(v.Window));
    }
  }
  // The same edits as interactive frames (a drag in the editor: the mapper
  // may keep the irradiance until the still frame).
  for (int e = 0; e < edits; ++e)
  {
    tf.DragOpacity();
    for (size_t i = 0; i < views.size(); ++i)
    {
      View& v = *views[(i + e) % views.size()];
      v.Window->SetDesiredUpdateRate(5.0);
      interactive[(i + e) % views.size()].push_back(Seconds(v.Window));
      v.Window->SetDesiredUpdateRate(0.0001);
    }
  }
  int dims[3];
  image->GetDimensions(dims);
  for (size_t i = 0; i < views.size(); ++i)
  {
    const double s = Median(still[i]), it = Median(interactive[i]);
    csv << volume << "," << dims[0] << "x" << dims[1] << "x" << dims[2] << "," << size << ","
        << views[i]->Name << "," << edits << "," << s << "," << 1.0 / s << "," << it << ","
        << 1.0 / it << "," << s / Median(still[0]) << ",\"" << renderer << "\"\n";
    std::printf("large %-6s %-10s still %.4f s (%.1f fps, %.2fx phong), interactive %.4f s "
                "(%.1f fps)\n",
      volume.c_str(), views[i]->Name.c_str(), s, 1.0 / s, s / Median(still[0]), it, 1.0 / it);
  }
  views[1]->Ours->TimeStagesOn();
  tf.DragOpacity();
  views[1]->Window->Render();
  std::printf("large %s mmv-skin opacity edit: %s; ray cast %.4f s\n  irradiance: %s\n",
    volume.c_str(), views[1]->Ours->GetLastPrepareStages().c_str(),
    views[1]->Ours->GetLastRayCastSeconds(), views[1]->Ours->GetLastIrradianceStages().c_str());
}
} // namespace

int main(int argc, char* argv[])
{
  std::string out = "change_benchmark";
  std::string head = MMV_HEADSQ_PATH;
  std::string chest;
  std::string only;
  std::string volumeList, methodList; // comma-separated; empty: all
  int size = 400, changes = 4, steps = 8, large = 0, largeSize = 1024, largeEdits = 10;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    auto next = [&]() { return i + 1 < argc ? std::string(argv[++i]) : std::string(); };
    auto number = [&](int least) { return std::max(least, std::atoi(next().c_str())); };
    if (arg == "--out")
      out = next();
    else if (arg == "--head")
      head = next();
    else if (arg == "--chest")
      chest = next();
    else if (arg == "--only")
      only = next();
    else if (arg == "--volumes")
      volumeList = next();
    else if (arg == "--methods")
      methodList = next();
    else if (arg == "--size")
      size = number(16);
    else if (arg == "--changes")
      changes = number(1);
    else if (arg == "--steps")
      steps = number(2);
    else if (arg == "--large")
      large = number(0);
    else if (arg == "--large-size")
      largeSize = number(16);
    else if (arg == "--large-edits")
      largeEdits = number(1);
    else
    {
      std::cerr << "unknown argument " << arg << "\n";
      return 2;
    }
  }
  mkdir(out.c_str(), 0755);
  std::vector<std::pair<std::string, std::vector<vtkSmartPointer<vtkImageData>>>> volumes;
  volumes.emplace_back("head", HeadSeries(head, steps));
  if (volumes.back().second.empty())
  {
    std::cerr << "cannot read " << head << "\n";
    return 1;
  }
  if (!chest.empty())
  {
    std::vector<vtkSmartPointer<vtkImageData>> series;
    for (int k = 0; k < steps; ++k)
    {
      auto image = ReadRaw(chest + "_" + std::to_string(k) + ".raw");
      if (!image)
      {
        std::cerr << "cannot read " << chest << "_" << k << ".raw\n";
        return 1;
      }
      series.push_back(image);
    }
    volumes.emplace_back("chest", series);
  }
  std::string renderer;
  {
    auto probe = mmvtest::NewRenderWindow();
    probe->SetOffScreenRendering(1);
    probe->SetSize(16, 16);
    probe->Render();
    renderer = mmvtest::RendererString(probe);
  }
  std::cout << "== renderer " << renderer << std::endl;
  if (only.empty() || only == "changes")
  {
    std::ofstream csv(out + "/changes_cxx.csv");
    csv << "volume,sequence,method,frames,median_s,ratio_to_phong,ratio_to_own_still,"
           "irradiance_updates,renderer\n";
    for (const auto& v : volumes)
    {
      if (Listed(volumeList, v.first))
      {
        RunVolume(v.first, v.second, size, changes, methodList, csv, renderer);
      }
    }
    std::cout << "== wrote " << out << "/changes_cxx.csv" << std::endl;
  }
  if (large > 0 && (only.empty() || only == "large"))
  {
    std::ofstream csv(out + "/large_opacity_cxx.csv");
    csv << "volume,dimensions,pixels,method,edits,still_median_s,still_fps,"
           "interactive_median_s,interactive_fps,still_over_phong,renderer\n";
    for (const auto& v : volumes)
    {
      if (Listed(volumeList, v.first))
        RunLarge(v.first, Resampled(v.second[0], large), largeSize, largeEdits, csv, renderer);
    }
    std::cout << "== wrote " << out << "/large_opacity_cxx.csv" << std::endl;
  }
  return 0;
}
