// Fits our free material parameters to the physical truth
// (vtkMultiMaterialPathTracer) for media of known single-scattering albedo a,
// Henyey-Greenstein anisotropy g and optical depth, the data behind the
// mapping from physical parameters to ours (mmv::PhysicalMediumToMaterial,
// docs/how-it-works.md and docs/performance.md, "Physical media").
//
//   mmvMediumCalibration --out DIR [--size 64] [--truth-spp 512] [--frames 3]
//                        [--albedos 0.3,0.6,0.9,0.99] [--anisotropies 0,0.3,0.6]
//                        [--depths 1,4,16] [--s-values LIST] [--ct-values LIST]
//                        [--cache DIR] [--no-fit] [--no-vtk] [--no-mapped]
//                        [--shape ball|cube]
//
// The controlled scene ("ball"): a homogeneous sphere of radius 18 voxels in a
// 48^3 volume (a one-voxel edge ramp), colour = albedo (grey), extinction
// sigma_t = depth / 18 per voxel (so `depth` is the optical depth of the
// radius), lit by one white directional light from the side (about 100
// degrees from the view) over a black background: no sky, so what is
// measured is the transport of the light alone. The truth is a pure medium:
// phase function at every event (no surface scattering), up to 1000 events
// per path. Truths are cached as .vti files under --cache (default
// DIR/truth-cache), keyed by every input, so reruns only render ours.
// --shape cube: the same medium in a cube of half-width 18 voxels instead
// (flat faces, edges and corners: how the mapping, fitted on the ball,
// transfers to another geometry); `depth` is then the optical depth of the
// half-width.
//
// Per medium it writes to DIR/medium_calibration.csv:
//  - ours-default: the default material (ka 0.2, kd 0.7, ks 0.2, ke 20,
//    c_t 1, s 0) with the medium's g;
//  - ours-fit: for every (s, c_t) of the grid, ka and kd by least squares
//    (the image is linear in them: two basis renders), then a render at the
//    fitted values; the lowest RMSE wins (every grid point:
//    DIR/medium_fit_grid.csv);
//  - ours-mapped: mmv::PhysicalMediumToMaterial(a, g, sigma_t per voxel);
//  - vtk-scattering: VTK's volumetric scattering, best of
//    VolumetricScatteringBlending x GlobalIlluminationReach x
//    ScatteringAnisotropy (mmv default ka/kd/ks).
// Errors over the 8-bit images: RMSE (0-255) of the whole image, and over
// the medium's pixels after the best brightness factor; the truth's noise
// floor (RMS standard error, 0-255). Frame time: median of --frames renders
// after an untimed one. Not a test: it asserts nothing.
#include "mmvCalibrationCommon.h"

#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkImageErrorMetrics.h"
#include "vtkMultiMaterialPathTracer.h"
#include "vtkMultiMaterialPhysicalMedium.h"
#include "vtkMultiMaterialVolumeMapper.h"
#include "vtkSMPTools.h"
#include "vtkXMLImageDataReader.h"
#include "vtkXMLImageDataWriter.h"

#include <cstdlib>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <sys/stat.h>

namespace
{
using mmvcal::GainCompensated;
using mmvcal::Numbers;
using mmvcal::Setting;
using mmvcal::Window;

constexpr int BallDimensions = 40;
// Key light intensity: pi would make a white Lambertian surface 1; 3 uses the
// 8 bits without saturating the truth.
constexpr double LightIntensity = 3.0;
// The ball's radius and the cube's half-width, in voxels.
constexpr double BallRadius = 18.0;

struct Options
{
  std::string Out = "medium-calibration-out";
  std::string Cache;
  int Size = 64;
  int TruthSamples = 512;
  int Frames = 3;
  std::vector<double> Albedos = { 0.3, 0.6, 0.9, 0.99 };
  std::vector<double> Anisotropies = { 0.0, 0.3, 0.6 };
  std::vector<double> Depths = { 1.0, 4.0, 16.0 };
  std::vector<double> Scattering = { 0.0, 1.0, 2.0, 4.0, 8.0, 16.0, 32.0, 64.0, 128.0 };
  std::vector<double> Attenuation = { 0.1, 0.2, 0.3, 0.45, 0.6, 0.8, 1.0 };
  bool Fit = true;
  bool VTK = true;
  bool Mapped = true;
  std::string Shape = "ball"; // or "cube"
};

bool Parse(int argc, char* argv[], Options& o)
{
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    auto next = [&]() -> std::string { return i + 1 < argc ? argv[++i] : ""; };
    if (a == "--out")
      o.Out = next();
    else if (a == "--cache")
      o.Cache = next();
    else if (a == "--size")
      o.Size = std::atoi(next().c_str());
    else if (a == "--truth-spp")
      o.TruthSamples = std::atoi(next().c_str());
    else if (a == "--frames")
      o.Frames = std::atoi(next().c_str());
    else if (a == "--albedos")
      o.Albedos = Numbers(next());
    else if (a == "--anisotropies")
      o.Anisotropies = Numbers(next());
    else if (a == "--depths")
      o.Depths = Numbers(next());
    else if (a == "--s-values")
      o.Scattering = Numbers(next());
    else if (a == "--ct-values")
      o.Attenuation = Numbers(next());
    else if (a == "--no-fit")
      o.Fit = false;
    else if (a == "--no-vtk")
      o.VTK = false;
    else if (a == "--no-mapped")
      o.Mapped = false;
    else if (a == "--shape")
      o.Shape = next();
    else
      return false;
  }
  if (o.Cache.empty())
  {
    o.Cache = o.Out + "/truth-cache";
  }
  return o.Size >= 8 && o.TruthSamples >= 2 && o.Frames >= 1 && !o.Out.empty() &&
    (o.Shape == "ball" || o.Shape == "cube") && !o.Scattering.empty() && !o.Attenuation.empty();
}

struct Medium
{
  double Albedo;
  double G;
  double Depth; // optical depth of the ball's radius

  double ExtinctionPerVoxel() const { return this->Depth / BallRadius; }
  std::string Key() const
  {
    std::ostringstream s;
    s << "a" << this->Albedo << "_g" << this->G << "_tau" << this->Depth;
    return s.str();
  }
};

// The material node list of the ball: one material everywhere.
void SetMaterial(
  vtkMaterialTransferFunction* materials, const double p[mmv::MaterialParameterCount])
{
  materials->RemoveAllNodes();
  materials->AddNode(0.0, p);
  materials->AddNode(1.0, p);
}

void DefaultMaterial(double g, double p[mmv::MaterialParameterCount])
{
  for (int i = 0; i < mmv::MaterialParameterCount; ++i)
  {
    p[i] = mmv::MaterialParameterTable[i].Default;
  }
  p[mmv::Anisotropy] = g;
}

mmvbench::SceneSpec MakeMedium(const Medium& m, const std::string& shape)
{
  mmvbench::SceneSpec s;
  s.Name = shape;
  const double c = 0.5 * (BallDimensions - 1);
  const bool cube = shape == "cube";
  s.Image = mmvtest::MakeVolume(BallDimensions,
    [&](double x, double y, double z)
    {
      // Distance to the centre: Euclidean (ball) or the largest per axis (cube).
      const double r = cube ? std::max({ std::abs(x - c), std::abs(y - c), std::abs(z - c) })
                            : std::sqrt((x - c) * (x - c) + (y - c) * (y - c) + (z - c) * (z - c));
      return std::min(std::max(BallRadius - r + 0.5, 0.0), 1.0);
    });
  s.Color = vtkSmartPointer<vtkColorTransferFunction>::New();
  s.Color->AddRGBPoint(0.0, m.Albedo, m.Albedo, m.Albedo);
  s.Color->AddRGBPoint(1.0, m.Albedo, m.Albedo, m.Albedo);
  s.Opacity = vtkSmartPointer<vtkPiecewiseFunction>::New();
  s.Opacity->AddPoint(0.0, 0.0);
  s.Opacity->AddPoint(1.0, 1.0 - std::exp(-m.ExtinctionPerVoxel()));
  s.Materials = vtkSmartPointer<vtkMaterialTransferFunction>::New();
  double p[mmv::MaterialParameterCount];
  DefaultMaterial(m.G, p);
  SetMaterial(s.Materials, p);
  s.UnitDistance = 1.0;
  for (int i = 0; i < 3; ++i)
  {
    s.Background[i] = s.Background2[i] = 0.0;
  }
  s.ViewDirection[0] = 0.0;
  s.ViewDirection[1] = -1.0;
  s.ViewDirection[2] = 0.25;
  s.ToLight[0] = 1.0;
  s.ToLight[1] = 0.2;
  s.ToLight[2] = 0.4;
  return s;
}

// The truth of one medium, from the cache or rendered (and cached).
vtkSmartPointer<vtkImageData> Truth(const Options& opt, const Medium& m, Window& window,
  const mmvbench::SceneSpec& scene, double& seconds)
{
  std::ostringstream path;
  path << opt.Cache << "/" << opt.Shape << "_" << m.Key() << "_size" << opt.Size << "_spp"
       << opt.TruthSamples << ".vti";
  struct stat info;
  if (stat(path.str().c_str(), &info) == 0)
  {
    vtkNew<vtkXMLImageDataReader> reader;
    reader->SetFileName(path.str().c_str());
    reader->Update();
    auto image = vtkSmartPointer<vtkImageData>::New();
    image->DeepCopy(reader->GetOutput());
    seconds = image->GetFieldData()->GetArray("Seconds")
      ? image->GetFieldData()->GetArray("Seconds")->GetComponent(0, 0)
      : 0.0;
    return image;
  }
  vtkNew<vtkMultiMaterialPathTracer> tracer;
  tracer->SetInputData(scene.Image);
  tracer->SetVolumeProperty(window.Property);
  tracer->SetMaterialTransferFunction(scene.Materials);
  tracer->SetSamplesPerPixel(opt.TruthSamples);
  tracer->SetMaxBounces(1000);
  tracer->SurfaceScatteringOff(); // a medium has no surfaces
  vtkImageData* rendered = tracer->Render(window.Renderer, opt.Size, opt.Size);
  if (!rendered)
  {
    return nullptr;
  }
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->DeepCopy(rendered);
  seconds = tracer->GetLastRenderSeconds();
  vtkNew<vtkDoubleArray> time;
  time->SetName("Seconds");
  time->InsertNextValue(seconds);
  image->GetFieldData()->AddArray(time);
  mkdir(opt.Cache.c_str(), 0755);
  vtkNew<vtkXMLImageDataWriter> writer;
  writer->SetFileName(path.str().c_str());
  writer->SetInputData(image);
  writer->Write();
  return image;
}

double RMSE(vtkImageData* a, vtkImageData* b)
{
  vtkDataArray* x = a->GetPointData()->GetScalars();
  vtkDataArray* y = b->GetPointData()->GetScalars();
  double e = 0.0;
  const vtkIdType n = x->GetNumberOfTuples();
  for (vtkIdType i = 0; i < n; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      const double d = x->GetComponent(i, c) - y->GetComponent(i, c);
      e += d * d;
    }
  }
  return std::sqrt(e / (3.0 * n));
}

// The ka, kd >= 0 with which `window` (whose image is linear in them: the
// compositing weights do not depend on them) best fits `truth`: two basis
// renders at k0, halved until neither saturates, then least squares.
void FitAmbientDiffuse(const std::function<void(double, double)>& set, Window& window,
  vtkImageData* truth, double& ka, double& kd)
{
  mmvcal::FitTwoScales(
    [&](double a, double b, vtkImageData* image)
    {
      set(a, b);
      window.Frames(0, image);
    },
    truth, 0.25, false, ka, kd);
  ka = std::min(ka, mmv::MaterialParameterTable[mmv::Ambient].HardMax);
  kd = std::min(kd, mmv::MaterialParameterTable[mmv::Diffuse].HardMax);
  set(ka, kd);
}

struct Result
{
  std::string Family;
  std::string Setting;
  double Parameters[mmv::MaterialParameterCount] = {};
  double Seconds = 0.0;
  double RMSE = 0.0;
  double Gain = 1.0;
  double GainRMSE = 0.0;
  double VolumeRMSE = 1e300;
  vtkSmartPointer<vtkImageData> Image;
};

/// What every row of one medium shares: the truth it is compared with and
/// where the rows go.
struct MediumContext
{
  const Options& Opt;
  const Medium& M;
  vtkImageData* Truth;
  const std::vector<bool>& Mask;
  double Floor;
  double TruthSeconds;
  std::ofstream& Csv;
};

/// The image of `w` (median time of `frames` frames) and its errors.
void Evaluate(const MediumContext& c, Result& r, Window& w, int frames)
{
  r.Image = vtkSmartPointer<vtkImageData>::New();
  r.Seconds = w.Frames(frames, r.Image);
  r.RMSE = RMSE(r.Image, c.Truth);
  r.GainRMSE = GainCompensated(r.Image, c.Truth, c.Mask, r.Gain, r.VolumeRMSE);
}

/// One row of medium_calibration.csv, its printed line and its image.
void Report(const MediumContext& c, const Result& r)
{
  const Options& opt = c.Opt;
  const Medium& medium = c.M;
  const double* p = r.Parameters;
  c.Csv << medium.Albedo << "," << medium.G << "," << medium.Depth << ","
        << medium.ExtinctionPerVoxel() << "," << r.Family << "," << r.Setting << ","
        << p[mmv::Ambient] << "," << p[mmv::Diffuse] << "," << p[mmv::Specular] << ","
        << p[mmv::Shininess] << "," << p[mmv::Attenuation] << "," << p[mmv::Scattering] << ","
        << 1e3 * r.Seconds << "," << r.RMSE << "," << r.VolumeRMSE << "," << r.Gain << ","
        << r.GainRMSE << "," << c.Floor << "," << opt.TruthSamples << "," << c.TruthSeconds << ","
        << opt.Size << "," << opt.Shape << "\n";
  c.Csv.flush();
  std::cout << "  " << std::setw(15) << r.Family << " " << std::setw(40) << r.Setting
            << std::setprecision(3) << " " << std::setw(7) << 1e3 * r.Seconds << " ms  RMSE "
            << std::setw(6) << r.RMSE << "  volume " << r.VolumeRMSE << ", x" << r.Gain << " -> "
            << r.GainRMSE << std::endl;
  vtkImageErrorMetrics::WritePNG(
    (opt.Out + "/" + opt.Shape + "_" + medium.Key() + "_" + r.Family + ".png").c_str(), r.Image);
}

/// Ours with material `p` everywhere: evaluated and reported as `family`.
void OursWith(const MediumContext& c, const std::string& family,
  const double p[mmv::MaterialParameterCount], vtkMaterialTransferFunction* materials,
  Window& window)
{
  Result r;
  r.Family = family;
  std::copy(p, p + mmv::MaterialParameterCount, r.Parameters);
  r.Setting = Setting({ { "ka", p[mmv::Ambient] }, { "kd", p[mmv::Diffuse] },
    { "ct", p[mmv::Attenuation] }, { "s", p[mmv::Scattering] } });
  SetMaterial(materials, p);
  Evaluate(c, r, window, c.Opt.Frames);
  Report(c, r);
}

/// Ours over the (s, c_t) grid, ka and kd fitted at every point (each a
/// row of `grid`); returns the point of the lowest volume RMSE.
Result FitGrid(const MediumContext& c, vtkMaterialTransferFunction* materials, Window& window,
  std::ofstream& grid)
{
  const Medium& medium = c.M;
  Result best;
  for (double s : c.Opt.Scattering)
  {
    for (double ct : c.Opt.Attenuation)
    {
      double q[mmv::MaterialParameterCount];
      DefaultMaterial(medium.G, q);
      q[mmv::Specular] = 0.0;
      q[mmv::Shininess] = 1.0;
      q[mmv::Scattering] = s;
      q[mmv::Attenuation] = ct;
      FitAmbientDiffuse(
        [&](double ka, double kd)
        {
          q[mmv::Ambient] = ka;
          q[mmv::Diffuse] = kd;
          SetMaterial(materials, q);
        },
        window, c.Truth, q[mmv::Ambient], q[mmv::Diffuse]);
      Result r;
      r.Family = "ours-fit";
      std::copy(q, q + mmv::MaterialParameterCount, r.Parameters);
      Evaluate(c, r, window, 0);
      grid << medium.Albedo << "," << medium.G << "," << medium.Depth << ","
           << medium.ExtinctionPerVoxel() << "," << s << "," << ct << "," << q[mmv::Ambient] << ","
           << q[mmv::Diffuse] << "," << r.VolumeRMSE << "\n";
      grid.flush();
      if (r.VolumeRMSE < best.VolumeRMSE)
      {
        best = r;
      }
    }
  }
  return best;
}

/// VTK's volumetric scattering at its best blending, reach and anisotropy:
/// evaluated and reported.
void BestVTKScattering(
  const MediumContext& c, const mmvbench::SceneSpec& scene, vtkCamera* camera, vtkLight* light)
{
  vtkNew<vtkOpenGLGPUVolumeRayCastMapper> vtkMapper;
  Window vtkWindow(scene, camera, light, c.Opt.Size, vtkMapper);
  mmvbench::ShadeWithDefaultMaterial(vtkWindow.Property);
  // Best over blending, reach and anisotropy at the mmv default
  // exposure. (Fitting VTK's ambient and diffuse as ours are does not
  // work: its image is not linear in them, the "fitted" renders were
  // worse than the defaults; its exposure error shows in the
  // gain-compensated column instead.)
  Result best;
  double setting[3] = {};
  for (double blending : { 0.25, 0.5, 1.0, 2.0 })
  {
    for (double reach : { 0.1, 0.5, 1.0 })
    {
      for (double vtkG : { 0.0, 0.3, 0.6, 0.8 })
      {
        vtkMapper->SetVolumetricScatteringBlending(static_cast<float>(blending));
        vtkMapper->SetGlobalIlluminationReach(static_cast<float>(reach));
        vtkWindow.Property->SetScatteringAnisotropy(vtkG);
        Result r;
        Evaluate(c, r, vtkWindow, 0);
        if (r.VolumeRMSE < best.VolumeRMSE)
        {
          best = r;
          setting[0] = blending;
          setting[1] = reach;
          setting[2] = vtkG;
        }
      }
    }
  }
  vtkMapper->SetVolumetricScatteringBlending(static_cast<float>(setting[0]));
  vtkMapper->SetGlobalIlluminationReach(static_cast<float>(setting[1]));
  vtkWindow.Property->SetScatteringAnisotropy(setting[2]);
  Result r;
  r.Family = "vtk-scattering";
  r.Setting =
    Setting({ { "blending", setting[0] }, { "reach", setting[1] }, { "anisotropy", setting[2] } });
  r.Parameters[mmv::Ambient] = mmv::MaterialParameterTable[mmv::Ambient].Default;
  r.Parameters[mmv::Diffuse] = mmv::MaterialParameterTable[mmv::Diffuse].Default;
  r.Parameters[mmv::Specular] = mmv::MaterialParameterTable[mmv::Specular].Default;
  r.Parameters[mmv::Shininess] = mmv::MaterialParameterTable[mmv::Shininess].Default;
  Evaluate(c, r, vtkWindow, c.Opt.Frames);
  Report(c, r);
}

/// One medium: its truth (cached), then every family's rows. False if the
/// truth could not be rendered or the mapping rejected the medium.
bool CalibrateMedium(
  const Options& opt, const Medium& medium, std::ofstream& csv, std::ofstream& grid)
{
  mmvbench::SceneSpec scene = MakeMedium(medium, opt.Shape);
  vtkNew<vtkCamera> camera;
  vtkNew<vtkLight> light;
  double radius = 0.0;
  mmvbench::FrameScene(scene, camera, light, radius);
  light->SetIntensity(LightIntensity);
  vtkNew<vtkMultiMaterialVolumeMapper> ours;
  vtkNew<vtkMaterialTransferFunction> materials;
  materials->DeepCopy(scene.Materials);
  ours->SetMaterialTransferFunction(materials);
  Window window(scene, camera, light, opt.Size, ours);

  double truthSeconds = 0.0;
  std::cout << "== " << medium.Key() << ": truth ..." << std::flush;
  vtkSmartPointer<vtkImageData> truthImage = Truth(opt, medium, window, scene, truthSeconds);
  if (!truthImage)
  {
    return false;
  }
  const mmvcal::Truth reference(truthImage, opt.Size);
  vtkImageData* truth = reference.Image;
  const double floor = reference.FloorRMSE;
  std::cout << " " << truthSeconds << " s, noise floor " << floor << "/255\n";
  vtkImageErrorMetrics::WritePNG(
    (opt.Out + "/" + opt.Shape + "_" + medium.Key() + "_truth.png").c_str(), truth);
  const MediumContext c{ opt, medium, truth, reference.Mask, floor, truthSeconds, csv };

  double p[mmv::MaterialParameterCount];
  DefaultMaterial(medium.G, p);
  OursWith(c, "ours-default", p, materials, window);
  if (opt.Fit)
  {
    const Result best = FitGrid(c, materials, window, grid);
    OursWith(c, "ours-fit", best.Parameters, materials, window);
  }
  if (opt.Mapped)
  {
    std::string why;
    if (!mmv::PhysicalMediumToMaterial(
          medium.Albedo, medium.G, medium.ExtinctionPerVoxel(), p, &why))
    {
      std::cerr << "mapping rejected the medium: " << why << "\n";
      return false;
    }
    OursWith(c, "ours-mapped", p, materials, window);
  }
  if (opt.VTK)
  {
    BestVTKScattering(c, scene, camera, light);
  }
  return true;
}
} // namespace

int main(int argc, char* argv[])
{
  Options opt;
  if (!Parse(argc, argv, opt))
  {
    std::cerr << "usage: " << argv[0]
              << " --out DIR [--size N] [--truth-spp N] [--frames N] [--albedos LIST]"
                 " [--anisotropies LIST] [--depths LIST] [--s-values LIST] [--ct-values LIST]"
                 " [--cache DIR] [--no-fit] [--no-vtk] [--no-mapped]\n";
    return 2;
  }
  vtkSMPTools::SetBackend("STDThread");
  mkdir(opt.Out.c_str(), 0755);
  std::ofstream csv(opt.Out + "/medium_calibration.csv");
  csv << "albedo,anisotropy,depth,extinction_per_voxel,family,setting,ka,kd,ks,ke,attenuation,"
         "scattering,frame_ms,rmse,volume_rmse,gain,volume_gain_rmse,truth_rmse_floor,truth_spp,"
         "truth_s,size,shape\n";
  std::ofstream grid(opt.Out + "/medium_fit_grid.csv");
  grid << "albedo,anisotropy,depth,extinction_per_voxel,scattering,attenuation,ka,kd,volume_rmse\n";

  for (double depth : opt.Depths)
  {
    for (double g : opt.Anisotropies)
    {
      for (double albedo : opt.Albedos)
      {
        if (!CalibrateMedium(opt, Medium{ albedo, g, depth }, csv, grid))
        {
          return 1;
        }
      }
    }
  }
  return 0;
}
