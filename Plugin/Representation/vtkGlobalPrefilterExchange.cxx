#include "vtkGlobalPrefilterExchange.h"

#include "vtkCommunicator.h"
#include "vtkDataArray.h"
#include "vtkGlobalPrefilteredVolume.h"
#include "vtkImageData.h"
#include "vtkMultiProcessController.h"
#include "vtkPointData.h"

#include <chrono>
#include <vector>

namespace mmv
{
namespace
{
template <typename T>
void AllReduce(
  vtkMultiProcessController* controller, const T* send, T* receive, vtkIdType length, int operation)
{
  if (controller && controller->GetNumberOfProcesses() > 1)
  {
    controller->AllReduce(send, receive, length, operation);
  }
  else
  {
    std::copy(send, send + length, receive);
  }
}
}

bool ExchangeGlobalPrefilter(vtkMultiProcessController* controller, vtkImageData* piece,
  const char* arrayName, const GlobalPrefilterSettings& settings,
  vtkGlobalPrefilteredVolume* result, std::string& error)
{
  const auto start = std::chrono::steady_clock::now();
  vtkDataArray* scalars = piece && arrayName ? piece->GetPointData()->GetArray(arrayName) : nullptr;
  if (piece && piece->GetNumberOfPoints() == 0)
  {
    piece = nullptr; // an empty piece takes part with neutral values
  }

  double summary[vtkGlobalPrefilteredVolume::SummarySize];
  double reduced[vtkGlobalPrefilteredVolume::SummarySize];
  vtkGlobalPrefilteredVolume::SummarizePiece(piece, scalars, summary);
  AllReduce(
    controller, summary, reduced, vtkGlobalPrefilteredVolume::SummarySize, vtkCommunicator::MIN_OP);
  vtkIdType bytes = static_cast<vtkIdType>(sizeof(summary));
  // Every rank reduced the same summary, so every rank returns here or none.
  if (!result->SetGeometry(
        reduced, settings.BudgetMB, settings.ExpectedLights, settings.Scale, settings.MaxVoxels))
  {
    error = result->GetLastError();
    result->SetBytesExchanged(bytes);
    return false;
  }

  std::vector<float> sums;
  result->AccumulatePiece(piece, scalars, sums);
  std::vector<float> total(sums.size());
  AllReduce(controller, sums.data(), total.data(), static_cast<vtkIdType>(sums.size()),
    vtkCommunicator::SUM_OP);
  bytes += static_cast<vtkIdType>(sums.size() * sizeof(float));
  result->SetReducedSums(total);
  result->SetBytesExchanged(bytes);
  result->SetExchangeSeconds(
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  error.clear();
  return true;
}

} // namespace mmv
