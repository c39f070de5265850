/**
 * @class   vtkGlobalPrefilteredVolume
 * @brief   The pre-filtered data of a whole volume split into pieces (MPI
 *          ranks, blocks), on one coarse irradiance grid every piece shares.
 *
 * Shadows must cross piece boundaries: a plate on one rank shadows a floor on
 * another. The irradiance is estimated on a pre-filtered, low-resolution copy
 * of the data (Zhang & Ma §5.1), small enough for every rank to hold whole.
 * Each piece contributes its share of the box filter; summed over the pieces
 * the shares give exactly what mmv::PrefilterScalars gives for the whole
 * volume, because every footprint sample is owned by exactly one piece
 * (pieces of one image share their boundary points; a sample on a shared
 * face belongs to the piece above it).
 *
 * The combination is collective and happens in three steps, each a plain
 * element-wise reduction that vtkMultiProcessController::AllReduce (or, for
 * blocks of one process, a loop) performs:
 *  1. SummarizePiece -> MIN-reduce -> SetGeometry: the whole volume's
 *     points, spacing and scalar range, and the irradiance grid over them;
 *  2. AccumulatePiece -> SUM-reduce (sums and sample counts, 2 floats per
 *     voxel) -> SetReducedSums: the pre-filtered values.
 * A piece with no points takes part with neutral values, so every rank
 * reaches every reduction.
 *
 * The mapper (SetGlobalPrefilteredVolume) then estimates the irradiance on
 * this grid and maps its piece's texture coordinates into it.
 */
#ifndef vtkGlobalPrefilteredVolume_h
#define vtkGlobalPrefilteredVolume_h

#ifndef __VTK_WRAP__
#include "vtkIrradianceGrid.h" // IrradianceGrid
#endif
#include "vtkMultiMaterialVolumeFiltersModule.h" // export macro
#include "vtkObject.h"

#include <string> // error text
#include <vector> // values

class vtkDataArray;
class vtkImageData;

class VTKMULTIMATERIALVOLUMEFILTERS_EXPORT vtkGlobalPrefilteredVolume : public vtkObject
{
public:
  static vtkGlobalPrefilteredVolume* New();
  vtkTypeMacro(vtkGlobalPrefilteredVolume, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Doubles a piece's summary takes (step 1), reduced with MIN.
  static constexpr int SummarySize = 34;

  /// Step 1: this piece's summary; a null or empty piece (or null scalars)
  /// gives the neutral summary.
  static void SummarizePiece(vtkImageData* piece, vtkDataArray* scalars, double summary[34]);

  /**
   * Step 1, after the MIN-reduction of every piece's summary: the whole
   * volume and its irradiance grid. The grid is what the mapper would choose
   * for the whole volume from `budgetMB`, `expectedLights` and `scale`
   * (mmv::ComputeIrradianceDimensions), and never more than `maxVoxels`
   * voxels (the bound on what is exchanged). False (invalid, error text in
   * GetLastError) when no piece has data or the pieces' spacings or
   * directions differ; every rank reaches the same answer.
   */
  bool SetGeometry(const double reduced[34], double budgetMB, int expectedLights, double scale,
    vtkIdType maxVoxels);

  /// Step 2: this piece's sums then counts of footprint samples, 2 *
  /// GetNumberOfVoxels() floats (zeros for an empty piece).
  void AccumulatePiece(vtkImageData* piece, vtkDataArray* scalars, std::vector<float>& sums) const;

  /// Step 2, after the SUM-reduction: the pre-filtered values.
  void SetReducedSums(const std::vector<float>& sums);

  /// Whether both steps succeeded (the mapper ignores an invalid volume).
  vtkGetMacro(Valid, bool);
  /// Why the last SetGeometry failed ("" if it did not).
  const char* GetLastError() const { return this->LastError.c_str(); }
  /// Points of the whole volume and its scalar range.
  vtkGetVector3Macro(DataDimensions, int);
  vtkGetVector2Macro(ScalarRange, double);
  vtkIdType GetNumberOfVoxels() const;
  void GetIrradianceDimensions(int dims[3]) const;

  /// Bookkeeping of whoever exchanged the data (bytes this process sent
  /// per update and seconds the exchange took), for benchmarks and logs.
  vtkSetMacro(BytesExchanged, vtkIdType);
  vtkGetMacro(BytesExchanged, vtkIdType);
  vtkSetMacro(ExchangeSeconds, double);
  vtkGetMacro(ExchangeSeconds, double);

#ifndef __VTK_WRAP__
  const mmv::IrradianceGrid& GetGrid() const
  {
    return this->Grid;
  }
  /// Pre-filtered values in data units, x fastest.
  const std::vector<float>& GetValues() const
  {
    return this->Values;
  }
  /// The continuous index of `piece`'s first point in the whole volume.
  glm::dvec3 PieceOffset(vtkImageData* piece) const;
#endif

  /// Makes the volume invalid (e.g. when a rank's exchange failed).
  void Invalidate();

protected:
  vtkGlobalPrefilteredVolume();
  ~vtkGlobalPrefilteredVolume() override;

  bool Valid = false;
  int DataDimensions[3] = { 0, 0, 0 };
  double ScalarRange[2] = { 0.0, 1.0 };
  vtkIdType BytesExchanged = 0;
  double ExchangeSeconds = 0.0;

private:
  vtkGlobalPrefilteredVolume(const vtkGlobalPrefilteredVolume&) = delete;
  void operator=(const vtkGlobalPrefilteredVolume&) = delete;

#ifndef __VTK_WRAP__
  mmv::IrradianceGrid Grid;
  glm::dvec3 FirstPoint{ 0.0 }; // in the direction frame
  glm::dvec3 Spacing{ 1.0 };
#endif
  std::vector<float> Values;
  std::string LastError;
};

#endif
