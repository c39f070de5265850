/**
 * @class   vtkMultiMaterialSceneShadows
 * @brief   Shadows between the volumes of one renderer: what one
 *          vtkMultiMaterialVolumeMapper's volume casts on the others and
 *          receives from them.
 *
 * Every visible vtkVolume of the renderer whose mapper is a
 * vtkMultiMaterialVolumeMapper shadows the others. Each volume's irradiance
 * toward a light is its own self-shadowed irradiance times the transmittance
 * through the other volumes (vtkSceneTransmittance.h): exact for single
 * scattering where the volumes do not overlap.
 *
 * As an occluder (UpdateOccluder), a mapper hands out its volume's
 * extinction on a coarse grid of its object space (mmv::CoarseExtinction,
 * the same sampling as the environment light's), recomputed only when its
 * data or extinction change. As a receiver (Gather, then Update), it
 * collects the other visible volumes' grids with their placement relative
 * to its own volume (the vtkProp3D matrices: user matrix, position,
 * orientation, scale, origin) into GetKey(), which joins the irradiance's
 * volume key (vtkIrradianceUpdatePlan::VolumeKey::Occluders), so that the
 * one update plan decides: moving, editing, hiding or removing another
 * volume relights this one. Update() then computes the transmittance on a
 * coarse grid over the irradiance grid and uploads it as one RGBA texture
 * per irradiance texture, which the estimator's final write multiplies in
 * (vtkIrradianceEstimator::SetSceneTransmittance): the ray cast's cost per
 * sample does not grow. A volume alone has an empty key and no texture.
 *
 * What casts: one-component point scalars, through the first opacity and
 * materials (of several fields from FieldArrays, the scalars' field alone;
 * vectors, multi-component scalars and cell scalars are lit but cast no
 * shadow on other volumes, with a warning). A volume in pieces (MPI ranks)
 * casts from the whole volume's pre-filtered values
 * (vtkGlobalPrefilteredVolume), which every rank holds alike, and receives
 * on its global grid, so every rank computes the same shadows. The
 * environment light's occlusion and the reflections' visibility see each
 * volume alone. Overlapping volumes shadow each other, but VTK's ray caster
 * composites each volume on its own: within their overlap the images are
 * blended, not integrated along one ray.
 * Not a vtkObject: plain state owned by the mapper.
 */
#ifndef vtkMultiMaterialSceneShadows_h
#define vtkMultiMaterialSceneShadows_h

#include "vtkCoarseExtinction.h"          // CoarseExtinction
#include "vtkIrradianceGrid.h"            // IrradianceGrid
#include "vtkMultiMaterialLightModel.h"   // LightSource
#include "vtkMultiMaterialVolumeModule.h" // export macro
#include "vtkSceneTransmittance.h"        // Occluder
#include "vtkSmartPointer.h"

#include <string>
#include <vector>

class vtkAbstractVolumeMapper;
class vtkDataArray;
class vtkGlobalPrefilteredVolume;
class vtkImageData;
class vtkMaterialTransferFunction;
class vtkOpenGLRenderWindow;
class vtkRenderer;
class vtkTextureObject;
class vtkVolume;
class vtkVolumeProperty;
class vtkWindow;

class VTKMULTIMATERIALVOLUME_EXPORT vtkMultiMaterialSceneShadows
{
public:
  vtkMultiMaterialSceneShadows();
  ~vtkMultiMaterialSceneShadows();

  /**
   * This volume as an occluder: the extinction of `scalars` (one-component
   * point data of `image`) under `property`'s first opacity and the
   * `materials`' attenuation, over the scalars' finite range. Null when it
   * casts nothing (no scalars or points); null with `problem` set when it
   * cannot (cell scalars, several components).
   */
  const mmv::CoarseExtinction* UpdateOccluder(vtkImageData* image, vtkDataArray* scalars,
    int cellFlag, vtkVolumeProperty* property, vtkMaterialTransferFunction* materials,
    int tableSize, std::string* problem);

  /**
   * The same for a volume in pieces (MPI ranks, blocks): the whole volume's
   * pre-filtered values on `global`'s grid, which every rank holds alike,
   * so each rank casts the whole volume's shadow. Null when `global` is
   * not valid.
   */
  const mmv::CoarseExtinction* UpdateOccluder(vtkGlobalPrefilteredVolume* global,
    vtkVolumeProperty* property, vtkMaterialTransferFunction* materials, int tableSize);

  /**
   * As a receiver: the other visible volumes of `ren` with a
   * vtkMultiMaterialVolumeMapper that cast a shadow, placed relative to
   * `self`, drawn by `selfMapper`. Volumes drawn by `selfMapper` itself are
   * not others: ParaView's vtkPVLODVolume holds the volume `self` that
   * renders, with the same mapper. Valid until the end of the frame (it
   * points into the other mappers).
   */
  void Gather(vtkRenderer* ren, vtkVolume* self, vtkAbstractVolumeMapper* selfMapper);
  /// Forgets the occluders.
  void Clear();

  /// Per occluder, the version of its extinction and the 16 entries of the
  /// map from this volume's object space into its own; empty when alone.
  const std::vector<double>& GetKey() const { return this->Key; }
  int GetNumberOfOccluders() const { return static_cast<int>(this->Occluders.size()); }
  /// Whether a gathered volume's box overlaps this one's: VTK composites
  /// each volume's ray cast over the other's, not along one ray.
  bool GetOverlapping() const { return this->Overlapping; }

  /**
   * The transmittance toward `lights` (object space) through the gathered
   * occluders, on a grid of at most mmv::SceneShadowVoxelsPerAxis voxels
   * per axis spanning `grid`'s voxel centres, into the textures; only when
   * the key, the grid or the lights changed. False: a texture could not be
   * made (`problem`).
   */
  bool Update(vtkOpenGLRenderWindow* context, const mmv::IrradianceGrid& grid,
    const std::vector<mmv::LightSource>& lights, std::string* problem);

  /// One RGBA texture per group of four lights (empty when alone).
  std::vector<vtkTextureObject*> GetTextures() const;
  /// Names the textures' values: 0 when alone, new after each computation.
  unsigned long GetVersion() const { return this->Version; }
  /// Computations so far, and the last one's wall seconds (the CPU march
  /// and the upload).
  int GetUpdateCount() const { return this->UpdateCount; }
  double GetLastSeconds() const { return this->LastSeconds; }

  void ReleaseGraphicsResources(vtkWindow* window);

private:
  vtkMultiMaterialSceneShadows(const vtkMultiMaterialSceneShadows&) = delete;
  void operator=(const vtkMultiMaterialSceneShadows&) = delete;

  bool Upload(vtkOpenGLRenderWindow* context, const mmv::IrradianceGrid& coarse,
    const std::vector<std::vector<float>>& groups, std::string* problem);

  mmv::CoarseExtinction Extinction; // this volume, as the others see it
  std::vector<mmv::Occluder> Occluders;
  std::vector<double> Key;
  bool Overlapping = false;

  // What the textures hold.
  bool HasTextures = false;
  std::vector<double> HeldKey;
  mmv::IrradianceGrid HeldGrid;
  std::vector<mmv::LightSource> HeldLights;
  std::vector<vtkSmartPointer<vtkTextureObject>> Textures;
  unsigned long Version = 0;
  int UpdateCount = 0;
  double LastSeconds = 0.0;
};

#endif
