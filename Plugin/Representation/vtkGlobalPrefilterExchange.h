/**
 * @file   vtkGlobalPrefilterExchange.h
 * @brief  Combines every rank's piece into one vtkGlobalPrefilteredVolume on
 *         every rank, through vtkMultiProcessController, so that shadows
 *         cross rank boundaries under MPI.
 *
 * Collective: every process of the controller must call it the same number of
 * times, with or without data (a rank with an empty piece passes null or an
 * empty image and takes part with neutral values). Two all-reductions:
 *  1. 34 doubles (MIN): the whole volume's points, spacing, direction and
 *     scalar range;
 *  2. 2 floats per irradiance voxel (SUM): the pieces' footprint sums and
 *     sample counts, at most maxVoxels voxels (8 * maxVoxels bytes).
 * When the pieces disagree (different spacings or directions) every rank
 * gets the same invalid volume and the same error text.
 */
#ifndef vtkGlobalPrefilterExchange_h
#define vtkGlobalPrefilterExchange_h

#include "vtkMultiMaterialParameters.h" // mmv::DefaultIrradianceBudgetMB
#include "vtkType.h"

#include <string>

class vtkGlobalPrefilteredVolume;
class vtkImageData;
class vtkMultiProcessController;

namespace mmv
{

struct GlobalPrefilterSettings
{
  double BudgetMB = mmv::DefaultIrradianceBudgetMB; // the irradiance memory budget
  int ExpectedLights = 4; // lights the budget is shared by (not known before rendering)
  double Scale = 0.0;     // IrradianceScale; 0: from the budget
  vtkIdType MaxVoxels = 128 * 128 * 128; // bound on the exchanged grid
};

/**
 * Fills `result` with the whole volume of which `piece` (may be null) is this
 * process's part, pre-filtered from point array `arrayName`. Returns false
 * with `error` set when the pieces cannot be combined (same on every rank).
 * A null controller or one of one process reduces locally.
 */
bool ExchangeGlobalPrefilter(vtkMultiProcessController* controller, vtkImageData* piece,
  const char* arrayName, const GlobalPrefilterSettings& settings,
  vtkGlobalPrefilteredVolume* result, std::string& error);

} // namespace mmv

#endif
