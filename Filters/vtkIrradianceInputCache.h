/**
 * @class   vtkIrradianceInputCache
 * @brief   What vtkMultiMaterialVolumeMapper's irradiance volume was computed
 *          from, and the inputs of vtkIrradianceEstimator kept between frames.
 *
 * Three caches, each behind a key of named fields, so that a frame recomputes
 * only what changed (the paper's Algorithm 1):
 *  - the material samples the irradiance depends on (attenuation and
 *    scattering over the scalar range), with a version bumped only when the
 *    sampled values change, so editing a colour-only parameter keeps the
 *    irradiance;
 *  - the data pre-filtered onto the irradiance grid, normalised to [0, 1] over
 *    the scalar range with NaN and Inf cleaned up, and a version that names
 *    its values (the estimator re-uploads on a new version, without comparing);
 *  - what the last computed irradiance was computed from: the volume (data,
 *    opacity, materials, settings, cutaway), each light, and the grid; what
 *    a new update recomputes is vtkIrradianceUpdatePlan's decision (Plan()).
 */
#ifndef vtkIrradianceInputCache_h
#define vtkIrradianceInputCache_h

#include "vtkIrradianceGrid.h"                   // mmv::IrradianceGrid
#include "vtkIrradianceUpdatePlan.h"             // VolumeKey, the held inputs
#include "vtkMultiMaterialLightModel.h"          // mmv::LightSource
#include "vtkMultiMaterialVolumeFiltersModule.h" // export macro
#include "vtkObject.h"

#include <vector> // keys, samples

class vtkDataArray;
class vtkGlobalPrefilteredVolume;
class vtkImageData;
class vtkMaterialTransferFunction;

class VTKMULTIMATERIALVOLUMEFILTERS_EXPORT vtkIrradianceInputCache : public vtkObject
{
public:
  static vtkIrradianceInputCache* New();
  vtkTypeMacro(vtkIrradianceInputCache, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Everything the whole irradiance volume depends on besides the lights and
  /// the grid (vtkIrradianceUpdatePlan.h).
  using VolumeKey = vtkIrradianceUpdatePlan::VolumeKey;

  ///@{
  /// Attenuation, transmission colour and scattering sampled at `tableSize` points over `range`
  /// (materials null: attenuation 1, scattering 0), resampled only when the
  /// materials, the range or the size changed.
  void SampleMaterials(
    vtkMaterialTransferFunction* materials, const double range[2], int tableSize);
  /// Bumped only when the sampled values change.
  int GetMaterialVersion() const { return this->MaterialVersion; }
  const std::vector<float>& GetScattering() const { return this->Scattering; }
  ///@}

  ///@{
  /**
   * The data on a grid of `dims` voxels, normalised to [0, 1] over `range`:
   * the global pre-filtered volume's when `global` is set, else `scalars`
   * (point data of `image`) box-filtered onto the grid. Recomputed only when
   * the grid, `dataTime` or the range changed. NaN voxels become 0 (empty)
   * and +-Inf the range's ends; returns true when the recomputed data had
   * any (so the caller can say so), false otherwise.
   */
  bool UpdatePrefiltered(vtkImageData* image, vtkDataArray* scalars,
    vtkGlobalPrefilteredVolume* global, const int dims[3], vtkMTimeType dataTime,
    const double range[2]);
  const mmv::IrradianceGrid& GetGrid() const { return this->Grid; }
  const std::vector<float>& GetPrefiltered() const { return this->Prefiltered; }
  /// Names the pre-filtered values: bumped when they or their grid change,
  /// not when the data were pre-filtered again to the same values.
  unsigned long GetPrefilteredVersion() const { return this->PrefilteredVersion; }
  ///@}

  ///@{
  /// What an update to `now` recomputes against the irradiance stored last,
  /// with each light kept within `toleranceRadians` of its stored placement
  /// (about the pre-filtered grid's centre).
  vtkIrradianceUpdatePlan Plan(
    const vtkIrradianceUpdatePlan::Inputs& now, double toleranceRadians) const;
  /// Whether the irradiance stored last was computed from `volume` and a grid
  /// of `dims`, with each light within `toleranceRadians` of `lights`
  /// (Plan(...).IsCurrent()).
  bool IsCurrent(const VolumeKey& volume, const std::vector<mmv::LightSource>& lights,
    const int dims[3], double toleranceRadians) const;
  /// Whether only the lights or the grid differ from the stored irradiance's
  /// (Plan(...).KeepsVolume()).
  bool SameVolume(const VolumeKey& volume) const;
  /// Records a successfully computed irradiance: `lights` are the placements
  /// it holds (vtkIrradianceEstimator::GetComputedLights()).
  void Store(
    const VolumeKey& volume, const std::vector<mmv::LightSource>& lights, const int dims[3]);
  /// Forgets the stored volume key (graphics resources released, a failed
  /// computation): the next frame recomputes.
  void Invalidate() { this->HasVolume = false; }
  ///@}

protected:
  vtkIrradianceInputCache();
  ~vtkIrradianceInputCache() override;

private:
  vtkIrradianceInputCache(const vtkIrradianceInputCache&) = delete;
  void operator=(const vtkIrradianceInputCache&) = delete;

  struct MaterialKey
  {
    vtkMTimeType MaterialTime = 0;
    double Range[2] = { 0.0, 0.0 };
    int TableSize = 0;
    bool operator==(const MaterialKey& o) const;
  };
  struct PrefilterKey
  {
    int Dimensions[3] = { 0, 0, 0 };
    vtkMTimeType DataTime = 0;
    double Range[2] = { 0.0, 0.0 };
    bool operator==(const PrefilterKey& o) const;
  };

  bool HasMaterials = false;
  MaterialKey Materials;
  std::vector<float> Extinction; // attenuation, then the transmission colour
  std::vector<float> Scattering;
  int MaterialVersion = 0;

  bool HasPrefiltered = false;
  PrefilterKey PrefilteredFrom;
  mmv::IrradianceGrid Grid;
  std::vector<float> Prefiltered;
  unsigned long PrefilteredVersion = 0;
  // The previous step's values and the filter's slab buffers, reused by the
  // next step instead of new memory.
  std::vector<float> SpareValues;
  mmv::PrefilterScratch Scratch;

  bool HasVolume = false;
  vtkIrradianceUpdatePlan::Inputs Held;
};

#endif
