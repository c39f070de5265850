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

} // namespace

int main(int argc, char* argv[])
{
  std::string out, head = MMV_HEADSQ_PATH;
  std::vector<std::string> rankList = { "1", "2", "4" }, axes = { "x", "z" },
                           scattering = { "on", "off" };
  int reps = 3, size = 400;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    const bool more = i + 1 < argc;
    if (arg == "--out" && more)
      out = argv[++i];
    else if (arg == "--ranks" && more)
      rankList = mmvbench::SplitList(argv[++i]);
    else if (arg == "--axes" && more)
      axes = mmvbench::SplitList(argv[++i]);
    else if (arg == "--scattering" && more)
      scattering = mmvbench::SplitList(argv[++i]);
    else if (arg == "--reps" && more)
      reps = std::max(1, std::stoi(argv[++i]));
    else if (arg == "--head" && more)
      head = argv[++i];
    else if (arg == "--size" && more)
      size = std::max(64, std::stoi(argv[++i]));
    else
    {
      std::cerr << "usage: mmvRankRegionBenchmark --out DIR [--ranks 1,2,4] [--axes x,z] "
                   "[--reps R] [--scattering on,off] [--head FILE.vti] [--size N]\n";
      return 2;
    }
  }
  if (out.empty())
  {
    std::cerr << "--out DIR is required\n";
    return 2;
  }
  mkdir(out.c_str(), 0755);
  const mmvbench::SceneSpec scene = mmvbench::MakeScene("ct", head);
  if (!scene.Image)
  {
    std::cerr << "cannot read " << head << "\n";
    return 1;
  }

  vtkSmartPointer<vtkRenderWindow> window = mmvtest::NewRenderWindow();
  window->SetOffScreenRendering(1);
  window->SetSize(size, size);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  // ParaView's default lighting: the light kit, following the camera.
  vtkNew<vtkLightKit> kit;
  kit->AddLightsToRenderer(renderer);
  vtkNew<vtkLight> unused;
  double radius = 0.0;
  mmvbench::FrameScene(scene, renderer->GetActiveCamera(), unused, radius);
  vtkNew<vtkVolumeProperty> property;
  property->SetColor(scene.Color);
  property->SetScalarOpacity(scene.Opacity);
  property->SetScalarOpacityUnitDistance(scene.UnitDistance);
  property->ShadeOn();
  property->SetInterpolationTypeToLinear();
  vtkNew<vtkVolume> volume;
  volume->SetProperty(property);
  renderer->AddVolume(volume);

  const std::string csvPath = out + "/rank_regions.csv";
  std::ofstream csv(csvPath);
  csv << "ranks,axis,scattering,mode,irradiance_grid,slowest_rank_update_s,"
         "its_shadow_rays_s,its_diffusion_s,sum_of_rank_updates_s,largest_rank_voxels,"
         "whole_grid_voxels\n";
  const int lights = 5;
  for (const std::string& ranksText : rankList)
  {
    const int p = std::max(1, std::stoi(ranksText));
    for (const std::string& axisName : axes)
    {
      if (p == 1 && axisName != axes.front())
      {
        continue; // one piece is the whole volume along any axis
      }
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
        return 1;
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
      for (const std::string& scatter : scattering)
      {
        // [mode][rep]: the slowest rank (and its shadow rays' and
        // diffusion's share), the sum over ranks, the largest voxels.
        std::vector<double> slowest[2], estimation[2], diffusion[2], sum[2], voxels[2];
        for (int r = 0; r < reps; ++r)
        {
          for (const int mode : { 1, 0 })
          {
            double rankMax = 0.0, rankSum = 0.0, rankVoxels = 0.0, rankShadows = 0.0,
                   rankDiffusion = 0.0;
            for (auto& mapper : mappers)
            {
              mapper->SetMultipleScattering(scatter == "on");
              mapper->SetPieceIrradianceOnly(mode == 1);
              volume->SetMapper(mapper);
              // A small turn: the kit's lights move, every light is recomputed.
              renderer->GetActiveCamera()->Azimuth(r % 2 == 0 ? 3.0 : -3.0);
              window->Render();
              const double seconds = mapper->GetLastIrradianceSeconds();
              if (seconds >= rankMax)
              {
                rankShadows = mapper->GetIrradianceEstimator()->GetLastEstimationSeconds();
                rankDiffusion = mapper->GetIrradianceEstimator()->GetLastDiffusionSeconds();
              }
              rankMax = std::max(rankMax, seconds);
              rankSum += seconds;
              rankVoxels = std::max(rankVoxels,
                static_cast<double>(mapper->GetIrradianceEstimator()->GetLastEstimatedVoxels()));
            }
            slowest[mode].push_back(rankMax);
            estimation[mode].push_back(rankShadows);
            diffusion[mode].push_back(rankDiffusion);
            sum[mode].push_back(rankSum);
            voxels[mode].push_back(rankVoxels);
          }
        }
        for (const int mode : { 1, 0 })
        {
          csv << p << "," << axisName << "," << scatter << "," << (mode ? "piece" : "whole") << ","
              << dims[0] << "x" << dims[1] << "x" << dims[2] << "," << Median(slowest[mode]) << ","
              << Median(estimation[mode]) << "," << Median(diffusion[mode]) << ","
              << Median(sum[mode]) << "," << Median(voxels[mode]) << "," << wholeVoxels << "\n";
          std::cout << p << " ranks along " << axisName << ", scattering " << scatter << ", "
                    << (mode ? "piece" : "whole") << ": slowest rank " << Median(slowest[mode])
                    << " s (shadow rays " << Median(estimation[mode]) << " s, diffusion "
                    << Median(diffusion[mode]) << " s), all ranks " << Median(sum[mode])
                    << " s, largest rank's voxels " << Median(voxels[mode]) << " of " << wholeVoxels
                    << std::endl;
        }
        csv.flush();
      }
      std::cout << "irradiance " << mappers.front()->GetIrradianceResolutionReason() << std::endl;
      for (auto& mapper : mappers)
      {
        mapper->ReleaseGraphicsResources(window);
      }
    }
  }
  std::cout << "wrote " << csvPath << "\n";
  return 0;
}
