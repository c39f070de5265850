// Error against the *physical* reference (vtkMultiMaterialPathTracer) and
// frame time of the real-time methods, with each method's free parameters
// swept so that its best fit to the Monte Carlo truth is known:
//
//  - ours (vtkMultiMaterialVolumeMapper): every node's scattering s and
//    attenuation c_t scaled by factors (1, 1 = the scene's defaults);
//    with --anisotropy G every node (truth and ours) has g = G, and ours is
//    measured twice per setting: "ours" shading with HG(G) (optical model
//    v2) and "ours-v1" with g = 0 (the isotropic particle term);
//  - with --mapped, "ours-mapped": every node's parameters from
//    mmv::PhysicalMediumToMaterial, with the node's mean colour as the
//    albedo, its g, and the extinction per voxel its opacity implies; and
//    "ours-mapped-surface": the same but the scene's surface terms (kd, ks,
//    shininess, r) kept;
//  - with --fit-exposure, "ours-exposure": at every (s, c_t), every node's
//    ka and kd also scaled, by the factors that fit the truth best (least
//    squares: the image less the ka = kd = 0 one is linear in them);
//  - VTK Phong (vtkOpenGLGPUVolumeRayCastMapper, shading on, mmv default
//    material);
//  - VTK volumetric scattering: VolumetricScatteringBlending x
//    GlobalIlluminationReach x the property's ScatteringAnisotropy.
//
//   mmvPhysicalCalibration --out DIR [--size 128] [--truth-spp 1024] [--frames 3]
//                          [--scenes synthetic,headsq,orbital,ct] [--head FILE.vti]
//                          [--s-scales 1,0,0.5,2,4,8,16] [--ct-scales 1,0.5,2,4] [--no-vtk]
//                          [--anisotropy G] [--back-light] [--mapped] [--black-background]
//                          [--fit-exposure] [--sky-strengths 0,1] [--ka-kd A,B]
//
// Same camera, key light and gradient background as mmvBenchmark
// (mmvbench::FrameScene); --back-light turns the key light to the opposite
// direction (the volume lit from behind, where forward scattering shows);
// --sky-strengths measures ours at each EnvironmentLighting (family "ours-sky"
// above 0: the background lights our volume as it lights the truth's);
// --ka-kd A,B adds ours at each strength with every node's ka and kd scaled
// by A and B (family "ours-scaled", or "ours-sky-scaled"): one scale pair
// for every scene, as a default would be;
// --black-background makes the background black for every method and the
// truth, so the truth has no sky (its escaping paths gather nothing): what
// remains is the light's transport alone, which sizes the sky's share. Errors are over the 8-bit
// images, as displayed: RMSE (0-255), PSNR and SSIM over the whole image, and over the volume's
// pixels (where the truth's paths met the medium) the RMSE as is and after the
// best single brightness factor k (least squares, k = <M, T> / <M, M>), which
// separates a wrong exposure from a wrong distribution of light. The truth's own noise floor
// is the RMS of its per-pixel standard error, in the same units. Frame time
// is the median of --frames renders after one untimed render per setting.
// Writes DIR/physical_calibration.csv and, per scene, the truth and the
// best-fitting images of each family. Not a test: it asserts nothing.
#include "mmvBenchmarkScenes.h"
#include "mmvCalibrationCommon.h"
#include "mmvTestWindow.h"

#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkImageErrorMetrics.h"
#include "vtkLight.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMultiMaterialParameters.h"
#include "vtkMultiMaterialPathTracer.h"
#include "vtkMultiMaterialPhysicalMedium.h"
#include "vtkMultiMaterialVolumeMapper.h"
#include "vtkNew.h"
#include "vtkOpenGLGPUVolumeRayCastMapper.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSMPTools.h"
#include "vtkUnsignedCharArray.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <sys/stat.h>
#include <vector>

namespace
{
using mmvcal::GainCompensated;
using mmvcal::Numbers;
using mmvcal::ScaleAmbientDiffuse;
using mmvcal::ScaleMaterials;
using mmvcal::Setting;
using mmvcal::Window;

struct Options
{
  std::string Out = "calibration-out";
  int Size = 128;
  int TruthSamples = 1024;
  int Frames = 5;
  std::vector<std::string> Scenes = { "synthetic", "headsq", "orbital", "ct" };
  std::string Head = MMV_HEADSQ_PATH;
  std::vector<double> ScatteringScales = { 1.0, 0.0, 0.5, 2.0, 4.0, 8.0, 16.0 };
  std::vector<double> AttenuationScales = { 1.0, 0.5, 2.0, 4.0 };
  bool VTK = true;
  double Anisotropy = 0.0; // every node's g, truth and ours; 0: the scene's
  bool BackLight = false;
  bool Mapped = false;
  bool BlackBackground = false;               // no sky in the truth
  bool FitExposure = false;                   // ka and kd fitted at every (s, c_t)
  std::vector<double> SkyStrengths = { 0.0 }; // ours' EnvironmentLighting
  std::vector<double> AmbientDiffuse;         // one ka and kd scale for every scene
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
    else if (a == "--truth-spp")
    {
      o.TruthSamples = std::atoi(next().c_str());
    }
    else if (a == "--frames")
    {
      o.Frames = std::atoi(next().c_str());
    }
    else if (a == "--scenes")
    {
      o.Scenes = mmvbench::SplitList(next());
    }
    else if (a == "--head")
    {
      o.Head = next();
    }
    else if (a == "--s-scales")
    {
      o.ScatteringScales = Numbers(next());
    }
    else if (a == "--ct-scales")
    {
      o.AttenuationScales = Numbers(next());
    }
    else if (a == "--no-vtk")
    {
      o.VTK = false;
    }
    else if (a == "--anisotropy")
    {
      o.Anisotropy = std::atof(next().c_str());
    }
    else if (a == "--back-light")
    {
      o.BackLight = true;
    }
    else if (a == "--black-background")
    {
      o.BlackBackground = true;
    }
    else if (a == "--fit-exposure")
    {
      o.FitExposure = true;
    }
    else if (a == "--ka-kd")
    {
      o.AmbientDiffuse = Numbers(next());
      if (o.AmbientDiffuse.size() != 2)
      {
        return false;
      }
    }
    else if (a == "--sky-strengths")
    {
      o.SkyStrengths = Numbers(next());
    }
    else if (a == "--mapped")
    {
      o.Mapped = true;
    }
    else
    {
      return false;
    }
  }
  return o.Size >= 16 && o.TruthSamples >= 2 && o.Frames >= 1 && !o.Out.empty() &&
    !o.ScatteringScales.empty() && !o.AttenuationScales.empty() && !o.SkyStrengths.empty();
}

struct Row
{
  std::string Family;
  std::string Setting;
  double Seconds = 0.0;
  double RMSE = 0.0;
  double PSNR = 0.0;
  double SSIM = 0.0;
  double VolumeRMSE = 0.0;
  double Gain = 1.0;
  double GainRMSE = 0.0;
  vtkSmartPointer<vtkImageData> Image;
};

// Every node of the scene's materials replaced by the mapping of the medium
// it describes: albedo = the node's mean colour, its g, and the extinction
// per voxel of the densest value the node governs (halfway to its
// neighbours: a band's end nodes often sit where the opacity is still 0).
bool MapMaterials(
  const mmvbench::SceneSpec& scene, vtkMaterialTransferFunction* target, bool keepSurface)
{
  const int stride = vtkMaterialTransferFunction::NodeStride;
  std::vector<double> nodes(static_cast<size_t>(scene.Materials->GetSize()) * stride);
  scene.Materials->GetNodes(nodes.data());
  const double* spacing = scene.Image->GetSpacing();
  const double voxel = std::min({ spacing[0], spacing[1], spacing[2] });
  double range[2];
  scene.Image->GetPointData()->GetScalars()->GetRange(range);
  const size_t count = nodes.size() / stride;
  for (size_t i = 0; i < count; ++i)
  {
    double* node = &nodes[i * stride];
    const double lo = i > 0 ? 0.5 * (nodes[(i - 1) * stride] + node[0]) : range[0];
    const double hi = i + 1 < count ? 0.5 * (node[0] + nodes[(i + 1) * stride]) : range[1];
    double opacity = 0.0;
    for (int k = 0; k <= 64; ++k)
    {
      opacity = std::max(opacity, scene.Opacity->GetValue(lo + (hi - lo) * k / 64.0));
    }
    double rgb[3];
    scene.Color->GetColor(node[0], rgb);
    const double albedo = (rgb[0] + rgb[1] + rgb[2]) / 3.0;
    const double extinction = voxel * mmv::ExtinctionFromOpacity(opacity, scene.UnitDistance);
    std::string why;
    double surface[mmv::MaterialParameterCount];
    std::copy(node + 1, node + 1 + mmv::MaterialParameterCount, surface);
    if (!mmv::PhysicalMediumToMaterial(
          albedo, node[1 + mmv::Anisotropy], std::max(extinction, 1e-3), node + 1, &why))
    {
      std::cerr << "node at " << node[0] << ": " << why << "\n";
      return false;
    }
    for (int p : { mmv::Diffuse, mmv::Specular, mmv::Shininess, mmv::Reflection })
    {
      node[1 + p] = keepSurface ? surface[p] : node[1 + p];
    }
    std::cout << "  mapped node " << node[0] << ": albedo " << albedo << ", extinction/voxel "
              << extinction << " -> ka " << node[1 + mmv::Ambient] << ", c_t "
              << node[1 + mmv::Attenuation] << ", s " << node[1 + mmv::Scattering] << "\n";
  }
  return target->SetNodes(static_cast<int>(nodes.size()), nodes.data());
}

/// What every row of one scene shares: the truth it is compared with, and
/// where the rows go.
struct SceneContext
{
  const Options& Opt;
  const std::string& Name;
  vtkImageData* Truth;
  const std::vector<bool>& VolumePixels;
  double FloorRMSE;
  double TruthSeconds;
  std::ofstream& Csv;
  vtkImageErrorMetrics* Metrics;
  std::vector<Row>& Rows;
};

/// One row: the frames and image of `window` against the truth, written,
/// printed and kept.
void Measure(
  const SceneContext& c, const std::string& family, const std::string& setting, Window& window)
{
  const Options& opt = c.Opt;
  Row r;
  r.Family = family;
  r.Setting = setting;
  r.Image = vtkSmartPointer<vtkImageData>::New();
  r.Seconds = window.Frames(opt.Frames, r.Image);
  c.Metrics->Compute(r.Image, c.Truth);
  r.RMSE = c.Metrics->GetRMSE();
  r.PSNR = c.Metrics->GetPSNR();
  r.SSIM = c.Metrics->GetSSIM();
  r.GainRMSE = GainCompensated(r.Image, c.Truth, c.VolumePixels, r.Gain, r.VolumeRMSE);
  c.Csv << c.Name << "," << family << "," << setting << "," << 1e3 * r.Seconds << "," << r.RMSE
        << "," << r.PSNR << "," << r.SSIM << "," << r.VolumeRMSE << "," << r.Gain << ","
        << r.GainRMSE << "," << c.FloorRMSE << "," << opt.TruthSamples << "," << c.TruthSeconds
        << "," << opt.Size << "\n";
  c.Csv.flush();
  std::cout << "  " << std::setw(15) << family << " " << std::setw(28) << setting << " "
            << std::setw(7) << std::setprecision(3) << 1e3 * r.Seconds << " ms  RMSE "
            << std::setw(6) << r.RMSE << "  volume " << r.VolumeRMSE << ", x" << r.Gain << " -> "
            << r.GainRMSE << std::endl;
  c.Rows.push_back(r);
}

/// Ours with every node's ka and kd scaled by the factors that fit the
/// truth best at (s, c_t), less the (0, 0) render (background, specular).
void FitExposure(const SceneContext& c, const mmvbench::SceneSpec& scene,
  vtkMaterialTransferFunction* materials, Window& oursWindow, double s, double ct, double sky)
{
  auto render = [&](double ambient, double diffuse, vtkImageData* image)
  {
    ScaleMaterials(scene.Materials, s, ct, materials);
    ScaleAmbientDiffuse(materials, ambient, diffuse);
    oursWindow.Frames(0, image);
  };
  double ambient = 1.0, diffuse = 1.0;
  mmvcal::FitTwoScales(render, c.Truth, 1.0, true, ambient, diffuse);
  ScaleMaterials(scene.Materials, s, ct, materials);
  ScaleAmbientDiffuse(materials, ambient, diffuse);
  Measure(c, sky > 0.0 ? "ours-sky-exposure" : "ours-exposure",
    Setting({ { "s_scale", s }, { "ct_scale", ct }, { "ka_scale", ambient },
      { "kd_scale", diffuse }, { "sky", sky } }),
    oursWindow);
}

/// Ours: s and c_t scaled, (1, 1) the default; then, with --mapped, the
/// mapped materials. False if a node could not be mapped.
bool MeasureOurs(const SceneContext& c, const mmvbench::SceneSpec& scene,
  vtkMaterialTransferFunction* materials, Window& oursWindow, vtkMultiMaterialVolumeMapper* ours)
{
  const Options& opt = c.Opt;
  for (double sky : opt.SkyStrengths)
  {
    ours->SetEnvironmentLighting(sky);
    const std::string family = sky > 0.0 ? "ours-sky" : "ours";
    for (double s : opt.ScatteringScales)
    {
      for (double ct : opt.AttenuationScales)
      {
        if (opt.FitExposure)
        {
          FitExposure(c, scene, materials, oursWindow, s, ct, sky);
        }
        ScaleMaterials(scene.Materials, s, ct, materials);
        Measure(c, s == 1.0 && ct == 1.0 ? family + "-default" : family,
          sky > 0.0 ? Setting({ { "s_scale", s }, { "ct_scale", ct }, { "sky", sky } })
                    : Setting({ { "s_scale", s }, { "ct_scale", ct } }),
          oursWindow);
        if (opt.AmbientDiffuse.size() == 2)
        {
          ScaleAmbientDiffuse(materials, opt.AmbientDiffuse[0], opt.AmbientDiffuse[1]);
          Measure(c, family + "-scaled",
            Setting({ { "s_scale", s }, { "ct_scale", ct }, { "ka_scale", opt.AmbientDiffuse[0] },
              { "kd_scale", opt.AmbientDiffuse[1] }, { "sky", sky } }),
            oursWindow);
        }
      }
    }
  }
  ours->SetEnvironmentLighting(0.0);
  for (double s : opt.ScatteringScales)
  {
    for (double ct : opt.AttenuationScales)
    {
      if (opt.Anisotropy != 0.0)
      {
        ScaleMaterials(scene.Materials, s, ct, materials, 0.0);
        Measure(c, "ours-v1", Setting({ { "s_scale", s }, { "ct_scale", ct } }), oursWindow);
      }
    }
  }
  if (opt.Mapped)
  {
    if (!MapMaterials(scene, materials, false))
    {
      return false;
    }
    Measure(c, "ours-mapped", "PhysicalMediumToMaterial", oursWindow);
    if (!MapMaterials(scene, materials, true))
    {
      return false;
    }
    Measure(
      c, "ours-mapped-surface", "PhysicalMediumToMaterial with the scene's kd ks ke r", oursWindow);
  }
  return true;
}

/// VTK's Phong, and its volumetric scattering over blending, reach and the
/// property's anisotropy.
void MeasureVTK(
  const SceneContext& c, const mmvbench::SceneSpec& scene, vtkCamera* camera, vtkLight* light)
{
  vtkNew<vtkOpenGLGPUVolumeRayCastMapper> phong;
  Window window(scene, camera, light, c.Opt.Size, phong);
  mmvbench::ShadeWithDefaultMaterial(window.Property);
  Measure(c, "vtk-phong", "", window);
  for (double blending : { 0.25, 0.5, 1.0, 2.0 })
  {
    for (double reach : { 0.1, 0.5, 1.0 })
    {
      for (double g : { 0.0, 0.5, 0.8 })
      {
        phong->SetVolumetricScatteringBlending(static_cast<float>(blending));
        phong->SetGlobalIlluminationReach(static_cast<float>(reach));
        window.Property->SetScatteringAnisotropy(g);
        Measure(c, "vtk-scattering",
          Setting({ { "blending", blending }, { "reach", reach }, { "anisotropy", g } }), window);
      }
    }
  }
}

/// Best fit per family (lowest RMSE), and its image.
void ReportBest(const std::vector<Row>& rows, const Options& opt, const std::string& name)
{
  std::map<std::string, const Row*> best;
  for (const Row& r : rows)
  {
    const std::string family = r.Family == "ours-default"
      ? "ours"
      : (r.Family == "ours-sky-default" ? "ours-sky" : r.Family);
    if (!best.count(family) || r.RMSE < best[family]->RMSE)
    {
      best[family] = &r;
    }
  }
  for (const auto& b : best)
  {
    std::cout << "  best " << b.first << ": " << b.second->Setting << " RMSE " << b.second->RMSE
              << " at " << 1e3 * b.second->Seconds << " ms\n";
    vtkImageErrorMetrics::WritePNG(
      (opt.Out + "/" + name + "_best_" + b.first + ".png").c_str(), b.second->Image);
  }
}

/// One scene: the physical truth, every method's rows, and the best fit per
/// family. False if the scene, its truth or a mapping failed.
bool CalibrateScene(
  const Options& opt, const std::string& name, std::ofstream& csv, vtkImageErrorMetrics* metrics)
{
  mmvbench::SceneSpec scene = mmvbench::MakeScene(name, opt.Head);
  if (!scene.Image)
  {
    std::cerr << "unknown or unreadable scene " << name << "\n";
    return false;
  }
  if (opt.Anisotropy != 0.0)
  {
    ScaleMaterials(scene.Materials, 1.0, 1.0, scene.Materials, opt.Anisotropy);
  }
  for (int a = 0; a < 3 && opt.BackLight; ++a)
  {
    scene.ToLight[a] = -scene.ToLight[a];
  }
  for (int a = 0; a < 3 && opt.BlackBackground; ++a)
  {
    scene.Background[a] = scene.Background2[a] = 0.0;
  }
  vtkNew<vtkCamera> camera;
  vtkNew<vtkLight> light;
  double radius = 0.0;
  mmvbench::FrameScene(scene, camera, light, radius);

  // The physical truth, through a window's renderer so that camera, light
  // and background are exactly what the methods see.
  vtkNew<vtkMultiMaterialVolumeMapper> ours;
  vtkNew<vtkMaterialTransferFunction> materials;
  materials->DeepCopy(scene.Materials);
  ours->SetMaterialTransferFunction(materials);
  Window oursWindow(scene, camera, light, opt.Size, ours);
  std::cout << "== " << name << ": truth " << opt.TruthSamples << " spp ..." << std::flush;
  vtkNew<vtkMultiMaterialPathTracer> tracer;
  tracer->SetInputData(scene.Image);
  tracer->SetVolumeProperty(oursWindow.Property);
  tracer->SetMaterialTransferFunction(scene.Materials);
  tracer->SetSamplesPerPixel(opt.TruthSamples);
  vtkSmartPointer<vtkImageData> truthImage =
    tracer->Render(oursWindow.Renderer, opt.Size, opt.Size);
  if (!truthImage)
  {
    return false;
  }
  const mmvcal::Truth reference(truthImage, opt.Size);
  const double truthSeconds = tracer->GetLastRenderSeconds();
  std::cout << " " << truthSeconds << " s, noise floor RMSE " << reference.FloorRMSE << "/255\n";
  vtkImageErrorMetrics::WritePNG((opt.Out + "/" + name + "_truth.png").c_str(), reference.Image);

  std::vector<Row> rows;
  const SceneContext c{ opt, name, reference.Image, reference.Mask, reference.FloorRMSE,
    truthSeconds, csv, metrics, rows };
  if (!MeasureOurs(c, scene, materials, oursWindow, ours))
  {
    return false;
  }
  if (opt.VTK)
  {
    MeasureVTK(c, scene, camera, light);
  }
  ReportBest(rows, opt, name);
  return true;
}
} // namespace

int main(int argc, char* argv[])
{
  Options opt;
  if (!Parse(argc, argv, opt))
  {
    std::cerr << "usage: " << argv[0]
              << " --out DIR [--size N] [--truth-spp N] [--frames N]"
                 " [--scenes synthetic,headsq,orbital,ct] [--head FILE.vti]"
                 " [--s-scales LIST] [--ct-scales LIST] [--no-vtk] [--anisotropy G] [--back-light]"
                 " [--mapped] [--black-background] [--fit-exposure]\n";
    return 2;
  }
  vtkSMPTools::SetBackend("STDThread");
  mkdir(opt.Out.c_str(), 0755);
  std::ofstream csv(opt.Out + "/physical_calibration.csv");
  csv << "scene,family,setting,frame_ms,rmse,psnr,ssim,volume_rmse,gain,volume_gain_rmse,"
         "truth_rmse_floor,truth_spp,"
         "truth_s,size\n";
  vtkNew<vtkImageErrorMetrics> metrics;

  for (const std::string& name : opt.Scenes)
  {
    if (!CalibrateScene(opt, name, csv, metrics))
    {
      return 1;
    }
  }
  return 0;
}
