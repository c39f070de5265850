/**
 * The global pre-filtered volume of several pieces in one process: both of
 * vtkGlobalPrefilteredVolume's reductions done by hand, as
 * mmv::ExchangeGlobalPrefilter does them across MPI ranks. For the tests and
 * the benchmarks that stand in for ranks.
 */
#ifndef mmvTestGlobalVolume_h
#define mmvTestGlobalVolume_h

#include "vtkGlobalPrefilteredVolume.h"
#include "vtkImageData.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <cfloat>
#include <vector>

namespace mmvtest
{
/// Combines `pieces` (nulls are ranks without data) into `global` with the
/// grid settings of SetGeometry; false when the geometry is refused.
inline bool CombinePieces(const std::vector<vtkSmartPointer<vtkImageData>>& pieces,
  vtkGlobalPrefilteredVolume* global, double budgetMB = 64.0, int lights = 1, double scale = 1.0,
  vtkIdType maxVoxels = 128 * 128 * 128)
{
  std::vector<double> reduced(vtkGlobalPrefilteredVolume::SummarySize, DBL_MAX);
  for (const auto& piece : pieces)
  {
    double summary[vtkGlobalPrefilteredVolume::SummarySize];
    vtkGlobalPrefilteredVolume::SummarizePiece(
      piece, piece ? piece->GetPointData()->GetScalars() : nullptr, summary);
    for (int i = 0; i < vtkGlobalPrefilteredVolume::SummarySize; ++i)
    {
      reduced[i] = std::min(reduced[i], summary[i]);
    }
  }
  if (!global->SetGeometry(reduced.data(), budgetMB, lights, scale, maxVoxels))
  {
    return false;
  }
  std::vector<float> total(2 * global->GetNumberOfVoxels(), 0.0f);
  for (const auto& piece : pieces)
  {
    std::vector<float> sums;
    global->AccumulatePiece(piece, piece ? piece->GetPointData()->GetScalars() : nullptr, sums);
    for (size_t i = 0; i < sums.size(); ++i)
    {
      total[i] += sums[i];
    }
  }
  global->SetReducedSums(total);
  return global->GetValid();
}
} // namespace mmvtest

#endif
