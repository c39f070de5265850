/**
 * @class   vtkIrradianceStepCache
 * @brief   The irradiance of earlier inputs (the steps of a time series),
 *          kept on the GPU so that data coming back costs a copy, not an
 *          update.
 *
 * ParaView's animation caching keeps each time step's data object, so the
 * second loop through a series hands the mapper the same scalar arrays
 * again. An entry holds copies of the irradiance (and tint) textures for one
 * input and everything the irradiance depends on; a later frame with the
 * same key has the estimator show them as they are instead of recomputing
 * (nothing is copied back).
 * Entries whose data can never come back are dropped for new ones; entries
 * whose data can are kept, and a step that finds no room is not kept
 * (vtkKeptStep.h). A budget lowered drops the least recently used first.
 *
 * The key names the data by its scalar array and that array's modification
 * time: a modified or new array never matches (modification times only
 * grow), and the same array on another geometry is another key.
 */
#ifndef vtkIrradianceStepCache_h
#define vtkIrradianceStepCache_h

#include "vtkIrradianceInputCache.h"      // VolumeKey
#include "vtkKeptStep.h"                  // KeptStepData
#include "vtkMultiMaterialLightModel.h"   // LightSource
#include "vtkMultiMaterialVolumeModule.h" // export macro
#include "vtkSmartPointer.h"              // entries' textures
#include "vtkType.h"                      // vtkMTimeType

#include <cstddef>
#include <list>
#include <vector>

class vtkDataArray;
class vtkImageData;
class vtkIrradianceEstimator;
class vtkOpenGLRenderWindow;
class vtkTextureObject;
class vtkWindow;

class VTKMULTIMATERIALVOLUME_EXPORT vtkIrradianceStepCache
{
public:
  struct Key
  {
    /// With DataTime and MaterialVersion 0: the data and the materials are
    /// named by the fields below.
    vtkIrradianceInputCache::VolumeKey Volume;
    vtkMTimeType MaterialsTime = 0;
    mmv::KeptStepData Data; // the scalar array and its modification time
    int DataDimensions[3] = { 0, 0, 0 };
    double Origin[3] = { 0.0, 0.0, 0.0 };
    double Spacing[3] = { 0.0, 0.0, 0.0 };
    int IrradianceDimensions[3] = { 0, 0, 0 };
    std::vector<mmv::LightSource> Lights;

    bool operator==(const Key& o) const;
    /// Lit the same way (everything but the data): keys whose lighting
    /// differs can never match again, as modification times only grow.
    bool SameLighting(const Key& o) const;
  };

  /// The key of `scalars` (point data of `image`) under `volume` and
  /// materials of modification time `materialsTime`, lit by `lights` on a
  /// grid of `dims`.
  static Key MakeKey(const vtkIrradianceInputCache::VolumeKey& volume, vtkMTimeType materialsTime,
    vtkImageData* image, vtkDataArray* scalars, const std::vector<mmv::LightSource>& lights,
    const int dims[3]);

  /// Has `pass` show the entry of `key`, if there is one, in place of its
  /// own textures (when they have its sizes) until its next update, which
  /// recomputes every light; `computed` gets the light placements the entry
  /// holds. False: no such entry, or the estimator's textures have other
  /// sizes.
  bool Restore(vtkOpenGLRenderWindow* context, const Key& key, vtkIrradianceEstimator* pass,
    std::vector<mmv::LightSource>& computed);

  /// Keeps a copy of `pass`'s textures, which hold the light placements
  /// `computed`, under `key` if it fits in `budgetBytes` once the entries lit
  /// otherwise and those whose data cannot come back are dropped (a lowered
  /// budget is Trim's). False: nothing kept (no room, or no copy support).
  bool Store(vtkOpenGLRenderWindow* context, const Key& key, vtkIrradianceEstimator* pass,
    const std::vector<mmv::LightSource>& computed, size_t budgetBytes);

  /// Drops entries until the rest fit in `budgetBytes` (0: all).
  void Trim(size_t budgetBytes);

  size_t GetBytes() const { return this->Bytes; }
  int GetNumberOfEntries() const { return static_cast<int>(this->Entries.size()); }

  void ReleaseGraphicsResources(vtkWindow* window);

private:
  struct Entry
  {
    Key EntryKey;
    std::vector<vtkSmartPointer<vtkTextureObject>> Textures; // irradiance, then tints
    std::vector<mmv::LightSource> ComputedLights;
    size_t Bytes = 0;
    bool CanReturn() const { return this->EntryKey.Data.CanReturn(); }
  };
  static std::vector<vtkTextureObject*> PassTextures(vtkIrradianceEstimator* pass);
  void Drop(std::list<Entry>::iterator entry);

  std::list<Entry> Entries; // most recently used first
  size_t Bytes = 0;
};

#endif
