// Each MPI rank's share of the irradiance update (docs/scaling.md, "Each rank estimates its own
// voxels"), measured without MPI: the CT-sized head split into P slabs along one axis as ParaView
// splits it among P ranks (pieces sharing their boundary points), combined into the global
// pre-filtered volume as the ranks' exchange combines it, then each piece rendered in turn by its
// own mapper under ParaView's light kit (5 lights). The ranks run one after the other in one
// process, so each rank's time is its own work, not the oversubscription of this 2-core machine.
// Per piece: the irradiance update (the pass's glFinish-bracketed timer) and the voxels x lights it
// estimated, with PieceIrradianceOnly on (each rank what its piece reads)
// and off (each rank the whole global grid), interleaved.
//
//   mmvRankRegionBenchmark --out DIR [--ranks 1,2,4] [--axes x,z] [--reps R]
//                          [--scattering on,off] [--head FILE.vti] [--size N]
//
// Writes DIR/rank_regions.csv, one line per ranks/axis/scattering/mode: the
// slowest rank's update and its shadow rays' and diffusion's shares, the
// summed rank updates (medians over R), the largest rank's voxels and the
// whole grid's. Not a test: it asserts nothing.
#include "mmvBenchmarkScenes.h"
#include "mmvTestGlobalVolume.h"
#include "mmvTestWindow.h"

#include "vtkCamera.h"
#include "vtkExtractVOI.h"
#include "vtkGlobalPrefilteredVolume.h"
#include "vtkImageData.h"
#include "vtkIrradianceEstimator.h"
#include "vtkLightKit.h"
#include "vtkMultiMaterialVolumeMapper.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <fstream>
#include <iostream>
#include <string>
#include <sys/stat.h>
#include <vector>

namespace
{
double Median(std::vector<double> v)
{
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

/// Piece k of P along `axis`: the points ParaView's extent split gives
/// rank k, sharing the boundary point with its neighbour.
vtkSmartPointer<vtkImageData> Piece(vtkImageData* whole, int axis, int k, int p)
{
  int extent[6];
  whole->GetExtent(extent);
  const int n = extent[2 * axis + 1] - extent[2 * axis];
  const int first = extent[2 * axis] + n * k / p;
  const int last = extent[2 * axis] + n * (k + 1) / p;
  extent[2 * axis] = first;
  extent[2 * axis + 1] = last;
  vtkNew<vtkExtractVOI> voi;
  voi->SetInputData(whole);
  voi->SetVOI(extent);
  voi->Update();
  vtkSmartPointer<vtkImageData> piece = voi->GetOutput();
  return piece;
}

/// The command line's settings.
struct Options
{
  std::string Out;
  std::string Head = MMV_HEADSQ_PATH;
  std::vector<std::string> Ranks = { "1", "2", "4" };
  std::vector<std::string> Axes = { "x", "z" };
  std::vector<std::string> Scattering = { "on", "off" };
  int Reps = 3;
  int Size = 400;
};

/// Reads the command line into `o`; false (and a message) on a bad one.
bool Parse(int argc, char* argv[], Options& o)
{
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    const bool more = i + 1 < argc;
    if (arg == "--out" && more)
      o.Out = argv[++i];
    else if (arg == "--ranks" && more)
      o.Ranks = mmvbench::SplitList(argv[++i]);
    else if (arg == "--axes" && more)
      o.Axes = mmvbench::SplitList(argv[++i]);
    else if (arg == "--scattering" && more)
      o.Scattering = mmvbench::SplitList(argv[++i]);
    else if (arg == "--reps" && more)
      o.Reps = std::max(1, std::stoi(argv[++i]));
    else if (arg == "--head" && more)
      o.Head = argv[++i];
    else if (arg == "--size" && more)
      o.Size = std::max(64, std::stoi(argv[++i]));
    else
    {
      std::cerr << "usage: mmvRankRegionBenchmark --out DIR [--ranks 1,2,4] [--axes x,z] "
                   "[--reps R] [--scattering on,off] [--head FILE.vti] [--size N]\n";
      return false;
    }
  }
  if (o.Out.empty())
  {
    std::cerr << "--out DIR is required\n";
    return false;
  }
  return true;
}

/// The one window every rank's piece renders in: ParaView's default
/// lighting (the light kit, following the camera), the scene's camera, and
/// a volume whose mapper is the rank's.
struct RankView
{
  vtkSmartPointer<vtkRenderWindow> Window = mmvtest::NewRenderWindow();
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkLightKit> Kit;
  vtkNew<vtkVolumeProperty> Property;
  vtkNew<vtkVolume> Volume;

  RankView(const mmvbench::SceneSpec& scene, int size)
  {
    this->Window->SetOffScreenRendering(1);
    this->Window->SetSize(size, size);
    this->Window->AddRenderer(this->Renderer);
    this->Kit->AddLightsToRenderer(this->Renderer);
    vtkNew<vtkLight> unused;
    double radius = 0.0;
    mmvbench::FrameScene(scene, this->Renderer->GetActiveCamera(), unused, radius);
    this->Property->SetColor(scene.Color);
    this->Property->SetScalarOpacity(scene.Opacity);
    this->Property->SetScalarOpacityUnitDistance(scene.UnitDistance);
    this->Property->ShadeOn();
    this->Property->SetInterpolationTypeToLinear();
    this->Volume->SetProperty(this->Property);
    this->Renderer->AddVolume(this->Volume);
  }
};

/// Per mode (1: piece, 0: whole) and repetition: the slowest rank (and its
/// shadow rays' and diffusion's share), the sum over ranks, the largest
/// voxels.
struct ModeTimes
{
  std::vector<double> Slowest[2], Estimation[2], Diffusion[2], Sum[2], Voxels[2];
};

/// One repetition of one mode: every rank's piece rendered in turn.
void MeasureMode(RankView& view,
  std::vector<vtkSmartPointer<vtkMultiMaterialVolumeMapper>>& mappers, const std::string& scatter,
  int mode, int r, ModeTimes& t)
{
  double rankMax = 0.0, rankSum = 0.0, rankVoxels = 0.0, rankShadows = 0.0, rankDiffusion = 0.0;
  for (auto& mapper : mappers)
  {
    mapper->SetMultipleScattering(scatter == "on");
    mapper->SetPieceIrradianceOnly(mode == 1);
    view.Volume->SetMapper(mapper);
    // A small turn: the kit's lights move, every light is recomputed.
    view.Renderer->GetActiveCamera()->Azimuth(r % 2 == 0 ? 3.0 : -3.0);
    view.Window->Render();
    const double seconds = mapper->GetLastIrradianceSeconds();
    if (seconds >= rankMax)
    {
      rankShadows = mapper->GetIrradianceEstimator()->GetLastEstimationSeconds();
      rankDiffusion = mapper->GetIrradianceEstimator()->GetLastDiffusionSeconds();
    }
    rankMax = std::max(rankMax, seconds);
    rankSum += seconds;
    rankVoxels = std::max(
      rankVoxels, static_cast<double>(mapper->GetIrradianceEstimator()->GetLastEstimatedVoxels()));
  }
  t.Slowest[mode].push_back(rankMax);
  t.Estimation[mode].push_back(rankShadows);
  t.Diffusion[mode].push_back(rankDiffusion);
  t.Sum[mode].push_back(rankSum);
  t.Voxels[mode].push_back(rankVoxels);
}

/// The rows (and printed lines) of one split and scattering setting.
void ReportModes(std::ofstream& csv, int p, const std::string& axisName, const std::string& scatter,
  const int dims[3], double wholeVoxels, const ModeTimes& t)
{
  for (const int mode : { 1, 0 })
  {
    csv << p << "," << axisName << "," << scatter << "," << (mode ? "piece" : "whole") << ","
        << dims[0] << "x" << dims[1] << "x" << dims[2] << "," << Median(t.Slowest[mode]) << ","
        << Median(t.Estimation[mode]) << "," << Median(t.Diffusion[mode]) << ","
        << Median(t.Sum[mode]) << "," << Median(t.Voxels[mode]) << "," << wholeVoxels << "\n";
    std::cout << p << " ranks along " << axisName << ", scattering " << scatter << ", "
              << (mode ? "piece" : "whole") << ": slowest rank " << Median(t.Slowest[mode])
              << " s (shadow rays " << Median(t.Estimation[mode]) << " s, diffusion "
              << Median(t.Diffusion[mode]) << " s), all ranks " << Median(t.Sum[mode])
              << " s, largest rank's voxels " << Median(t.Voxels[mode]) << " of " << wholeVoxels
              << std::endl;
  }
  csv.flush();
}

/// The volume split among `p` ranks along one axis: its pieces combined,
/// then every scattering setting measured, both modes interleaved. False if
/// the pieces could not be combined.
bool RunSplit(const Options& o, const mmvbench::SceneSpec& scene, RankView& view, int p,
  const std::string& axisName, std::ofstream& csv)
{
  const int lights = 5;
  const int axis = axisName == "x" ? 0 : (axisName == "y" ? 1 : 2);
  std::vector<vtkSmartPointer<vtkImageData>> pieces;
  for (int k = 0; k < p; ++k)
  {
    pieces.push_back(Piece(scene.Image, axis, k, p));
  }
  // Combined as the ranks' exchange combines them (the default budget).
  vtkNew<vtkGlobalPrefilteredVolume> global;
  if (!mmvtest::CombinePieces(pieces, global, mmv::DefaultIrradianceBudgetMB, lights, 0.0))
  {
    std::cerr << "the pieces could not be combined\n";
    return false;
  }
  int dims[3];
  global->GetIrradianceDimensions(dims);
  const double wholeVoxels = static_cast<double>(global->GetNumberOfVoxels()) * lights;
  std::vector<vtkSmartPointer<vtkMultiMaterialVolumeMapper>> mappers;
  for (const auto& piece : pieces)
  {
    auto mapper = vtkSmartPointer<vtkMultiMaterialVolumeMapper>::New();
    mapper->SetInputData(piece);
    mapper->SetMaterialTransferFunction(scene.Materials);
    mapper->SetGlobalPrefilteredVolume(global);
    mappers.push_back(mapper);
  }
  for (const std::string& scatter : o.Scattering)
  {
    ModeTimes t;
    for (int r = 0; r < o.Reps; ++r)
    {
      for (const int mode : { 1, 0 })
      {
        MeasureMode(view, mappers, scatter, mode, r, t);
      }
    }
    ReportModes(csv, p, axisName, scatter, dims, wholeVoxels, t);
  }
  std::cout << "irradiance " << mappers.front()->GetIrradianceResolutionReason() << std::endl;
  for (auto& mapper : mappers)
  {
    mapper->ReleaseGraphicsResources(view.Window);
  }
  return true;
}
} // namespace

int main(int argc, char* argv[])
{
  Options o;
  if (!Parse(argc, argv, o))
  {
    return 2;
  }
  mkdir(o.Out.c_str(), 0755);
  const mmvbench::SceneSpec scene = mmvbench::MakeScene("ct", o.Head);
  if (!scene.Image)
  {
    std::cerr << "cannot read " << o.Head << "\n";
    return 1;
  }
  RankView view(scene, o.Size);

  const std::string csvPath = o.Out + "/rank_regions.csv";
  std::ofstream csv(csvPath);
  csv << "ranks,axis,scattering,mode,irradiance_grid,slowest_rank_update_s,"
         "its_shadow_rays_s,its_diffusion_s,sum_of_rank_updates_s,largest_rank_voxels,"
         "whole_grid_voxels\n";
  for (const std::string& ranksText : o.Ranks)
  {
    const int p = std::max(1, std::stoi(ranksText));
    for (const std::string& axisName : o.Axes)
    {
      if (p == 1 && axisName != o.Axes.front())
      {
        continue; // one piece is the whole volume along any axis
      }
      if (!RunSplit(o, scene, view, p, axisName, csv))
      {
        return 1;
      }
    }
  }
  std::cout << "wrote " << csvPath << "\n";
  return 0;
}
