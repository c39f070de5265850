/**
 * @file   vtkCoarseExtinction.h
 * @brief  A volume's extinction on a coarse grid of its own object space:
 *         what the environment light (vtkMultiMaterialSky) and the other
 *         volumes' shadows (vtkSceneTransmittance.h) march through.
 *
 * The extinction is the one the shadows use: the materials' attenuation
 * times mmv::ExtinctionFromOpacity of the first scalar opacity, per object
 * unit, sampled over the data's range (SampleExtinction). It is averaged
 * over each coarse voxel (mmv::AverageOntoGrid with that table), which keeps
 * the optical depth of structures thinner than a coarse voxel.
 */
#ifndef vtkCoarseExtinction_h
#define vtkCoarseExtinction_h

#include "vtkIrradianceGrid.h"                   // IrradianceGrid
#include "vtkMultiMaterialVolumeFiltersModule.h" // export macro
#include "vtkType.h"                             // vtkMTimeType

#include <vector>

class vtkDataArray;
class vtkImageData;
class vtkMaterialTransferFunction;
class vtkPiecewiseFunction;

namespace mmv
{

/**
 * Extinction per object unit at `tableSize` values evenly over `range`:
 * attenuation (1 without materials) times ExtinctionFromOpacity of
 * `opacity` given per `unitDistance`.
 */
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT std::vector<float> SampleExtinction(
  vtkPiecewiseFunction* opacity, double unitDistance, vtkMaterialTransferFunction* materials,
  const double range[2], int tableSize);

/// Component 0 of `scalars` normalised to [0, 1] over `range` (NaN: 0,
/// beyond the range: clamped), into `values`.
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT void NormalizeScalars(
  vtkDataArray* scalars, const double range[2], std::vector<float>& values);

/// A coarsening (mmv::CoarsenIrradianceGrid) of `points` with at most
/// `maxVoxelsPerAxis` voxels along any axis.
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT IrradianceGrid CoarsenToAtMost(
  const IrradianceGrid& points, int maxVoxelsPerAxis);

/**
 * One volume's extinction on a coarse grid, recomputed only when its inputs
 * change. Each new estimate gets a version unique among all instances, so a
 * version names one volume's extinction values.
 */
class VTKMULTIMATERIALVOLUMEFILTERS_EXPORT CoarseExtinction
{
public:
  /**
   * The extinction of `scalars` (point data of `image`, component 0) under
   * `table` (SampleExtinction over `range`) on a grid of at most
   * `maxVoxelsPerAxis` voxels per axis spanning the image's points.
   * Returns whether it was recomputed.
   */
  bool Update(vtkImageData* image, vtkDataArray* scalars, const double range[2],
    const std::vector<float>& table, int maxVoxelsPerAxis);

  /**
   * The same from `values` in data units, one per voxel of `points` (x
   * fastest), which `source` names until `sourceTime` changes: a volume in
   * pieces casts from its pre-filtered values on the global grid
   * (vtkGlobalPrefilteredVolume), the same on every rank.
   */
  bool Update(const IrradianceGrid& points, const std::vector<float>& values, const void* source,
    vtkMTimeType sourceTime, const double range[2], const std::vector<float>& table,
    int maxVoxelsPerAxis);

  const IrradianceGrid& GetGrid() const { return this->Grid; }
  /// Per object unit, one per voxel of GetGrid(), x fastest.
  const std::vector<float>& GetValues() const { return this->Values; }
  /// The data normalised over the range (NormalizeScalars), one per point
  /// (of the global grid, for pre-filtered values):
  /// kept while the array, its time and the range are (a new table only
  /// averages them again).
  const std::vector<float>& GetNormalized() const { return this->Normalized; }
  unsigned long GetVersion() const { return this->Version; }
  /// Forgets the inputs: the next Update() recomputes.
  void Invalidate() { this->HasKey = false; }

private:
  struct Key
  {
    const void* Source = nullptr; // the scalars, or the pre-filtered values
    vtkMTimeType SourceTime = 0;
    IrradianceGrid Points;
    double Range[2] = { 0.0, 0.0 };
    std::vector<float> Table;
    int MaxVoxelsPerAxis = 0;
    bool operator==(const Key& o) const;
  };
  /// Both Update()s once `key` names the source, whose values `scalars` hold.
  bool Update(Key key, vtkDataArray* scalars);
  bool HasKey = false;
  Key Held;
  IrradianceGrid Grid;
  std::vector<float> Normalized; // kept between updates
  std::vector<float> Values;
  unsigned long Version = 0;
};

} // namespace mmv

#endif
