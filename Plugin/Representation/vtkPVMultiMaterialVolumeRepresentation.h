/**
 * @class   vtkPVMultiMaterialVolumeRepresentation
 * @brief   ParaView's "Multi-Material Volume" representation of image data.
 *
 * A vtkImageVolumeRepresentation whose mapper is a vtkMultiMaterialVolumeMapper
 * (installed in the constructor, as ParaView's NVIDIA IndeX plugin does).
 * Everything the base class does (data delivery, ordered compositing, colour
 * and opacity transfer functions, cropping, outline LOD) is kept; the base
 * class forwards some settings by down-casting to its own mapper types, so
 * this class forwards the multi-material settings to the mapper as they
 * arrive, and the sampling and what depends on the view or the data (the
 * falloff radius, the step cache) in UpdateMapperParameters().
 *
 * Materials: MaterialNodes (13 numbers per node, see
 * vtkMaterialTransferFunction::SetNodes) or, when MaterialPreset names a
 * preset of vtkMaterialLibrary, that preset spread over the colour map's
 * range (the range ParaView keeps consistent on every rank). Invalid nodes
 * and unknown presets are reported with vtkErrorMacro and ignored, so the
 * previous materials stay in use.
 *
 * Lights are the view's renderer lights (light kit, headlight, lights added
 * with the Light Inspector or AddLight()); the mapper reads them every frame.
 *
 * Under MPI every rank renders its own piece, lit from one global coarse
 * copy of the whole volume that every rank holds (vtkGlobalPrefilteredVolume,
 * combined by mmv::ExchangeGlobalPrefilter at each view update after the
 * data or the irradiance settings changed), so shadows and scattered light
 * cross piece boundaries. The global grid follows the memory budget and
 * IrradianceScale, not the screen, and holds at most 128^3 voxels.
 */
#ifndef vtkPVMultiMaterialVolumeRepresentation_h
#define vtkPVMultiMaterialVolumeRepresentation_h

#include "vtkDoubleArray.h"             // for vtkNew ivar
#include "vtkGlobalPrefilteredVolume.h" // for vtkNew ivar
#include "vtkImageVolumeRepresentation.h"
#include "vtkMaterialTransferFunction.h"          // for vtkNew ivar
#include "vtkMultiMaterialVolumeParaViewModule.h" // export macro
#include "vtkNew.h"                               // for vtkNew
#include "vtkPVMaterialNodeBuffer.h"              // for ivar
#include "vtkStringArray.h"                       // for vtkNew ivar

#include <memory> // for the field settings
#include <string> // for the preset name
#include <vector> // for the exchange key

class vtkColorTransferFunction;
class vtkMultiMaterialFieldSettings;
class vtkMultiMaterialVolumeMapper;
class vtkPiecewiseFunction;

class VTKMULTIMATERIALVOLUMEPARAVIEW_EXPORT vtkPVMultiMaterialVolumeRepresentation
  : public vtkImageVolumeRepresentation
{
public:
  static vtkPVMultiMaterialVolumeRepresentation* New();
  vtkTypeMacro(vtkPVMultiMaterialVolumeRepresentation, vtkImageVolumeRepresentation);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * MaterialNodes arrive as ParaView pushes a repeated, indexed property: the
   * count first, then every value. The nodes are validated and applied once
   * the last value arrives, all or nothing.
   */
  void SetNumberOfMaterialNodeValues(int count);
  void SetMaterialNodeValue(int index, double value);
  ///@}

  /// The nodes in use (13 numbers per node), presets included.
  vtkDoubleArray* GetAppliedMaterialNodes();

  ///@{
  /**
   * A preset name of vtkMaterialLibrary, or "" / "Custom" to use
   * MaterialNodes. Unknown names are errors and change nothing.
   */
  void SetMaterialPreset(const char* name);
  const char* GetMaterialPreset() const { return this->MaterialPreset.c_str(); }
  ///@}

  /// The names of the built-in presets (the MaterialPreset domain).
  vtkStringArray* GetMaterialPresetNames();

  ///@{
  /**
   * Several fields: arrays besides the coloured one (same association, one
   * component, at most 3), each drawn through its own colour map, opacity
   * function and material preset (matched by position). Shadows and
   * scattering come from all of them together (vtkMultiMaterialVolumeMapper::
   * AddFieldArray). In the GUI and in pvpython, setting FieldArrays gives
   * each field the colour map and opacity function ParaView keeps for its
   * array name.
   */
  void ClearFieldArrays();
  void AddFieldArray(const char* name);
  void ClearFieldLookupTables();
  void AddFieldLookupTable(vtkColorTransferFunction* colors);
  void ClearFieldScalarOpacityFunctions();
  void AddFieldScalarOpacityFunction(vtkPiecewiseFunction* opacity);
  void ClearFieldMaterialPresets();
  void AddFieldMaterialPreset(const char* name);
  /// Fields drawn by the last render (1 for the coloured array alone).
  int GetNumberOfFields();
  ///@}

  ///@{
  /// Forwarded to vtkMultiMaterialVolumeMapper (vtkMultiMaterialSettings.h).
  void SetIrradianceMemoryMB(double megabytes);
  void SetIrradianceScale(double scale);
  void SetIrradianceErrorBound(double decibels);
  void SetGradientSmoothing(double sigma);
  void SetMultipleScattering(bool enabled);
  void SetPreIntegration(bool enabled);
  void SetPointLightRadius(double radius);
  void SetSampleDistance(double distance);
  void SetAutoAdjustSampleDistances(bool enabled);
  void SetLockSampleDistanceToInputSpacing(bool enabled);
  void SetInteractiveIrradiance(int mode);
  void SetShadowEstimation(int estimation);
  void SetPiecewiseShadowSlices(int slices);
  void SetExponentialDiffusion(bool exponential);
  /// Under MPI: each rank estimates only the irradiance its piece reads (on,
  /// default), or the whole global grid (off), vtkMultiMaterialVolumeMapper.
  void SetPieceIrradianceOnly(bool pieceOnly);
  /// vtkMultiMaterialVolumeMapper::SetDimLightCoarsening.
  void SetDimLightCoarsening(bool coarsening);
  void SetLightDirectionTolerance(double degrees);
  /// GPU memory for the irradiance of earlier time steps, used while the
  /// view caches them or Cache Geometry For Animation is on (the scene
  /// caches its own frames only); otherwise none.
  void SetIrradianceCacheMB(double megabytes);
  void SetReflectionSource(int source);
  void SetReflectionVisibility(int visibility);
  /// vtkMultiMaterialVolumeMapper::SetEnvironmentLighting: the background
  /// as a sky, this strong (0: off).
  void SetEnvironmentLighting(double strength);
  ///@}

  /// Point and spot lights' falloff: 0 (default), the lights' attenuation;
  /// 1, the paper's eq. 12 with PointLightRadius, or with a quarter of the
  /// data's diagonal while PointLightRadius is 0 (automatic): every pair of
  /// values is a valid choice.
  void SetLightFalloff(int falloff);

  ///@{
  /**
   * Sets the irradiance internals (ShadowEstimation, PiecewiseShadowSlices,
   * ExponentialDiffusion, PieceIrradianceOnly, LightDirectionTolerance,
   * ReflectionVisibility, IrradianceErrorBound, IrradianceMemoryMB,
   * IrradianceScale) to the row of mmv::LightingQualityTable for `level`
   * (Fast 0, Balanced 1, Exact 2). Custom (3) changes nothing: the internals
   * keep what their own setters were given. Other values are errors.
   */
  void SetLightingQuality(int level);
  vtkGetMacro(LightingQuality, int);
  ///@}

  ///@{
  /// The mapper's counters on this process (see vtkMultiMaterialVolumeMapper).
  int GetIrradianceUpdateCount();
  int GetSkyUpdateCount();
  double GetLastSkySeconds();
  int GetDiffusionPassCount();
  int GetPreIntegrationCount();
  int GetRayCastCount();
  int GetNumberOfShadedLights();
  int GetMultiMaterialActive();
  int GetDeferredIrradianceCount();
  int GetIrradianceCacheHitCount();
  double GetLastIrradianceSeconds();
  /// Voxels x lights the last irradiance update cast shadow rays from.
  double GetLastEstimatedIrradianceVoxels();
  const char* GetIrradianceResolutionInfo();
  /// Seconds of each stage of the last irradiance update.
  const char* GetLastIrradianceStages();
  /// Measurements of the irradiance error probe so far.
  int GetIrradianceProbeCount();
  /// Under MPI: the global grid, the bytes this rank contributed to its
  /// exchange and the seconds the exchange took ("" when not in use).
  const char* GetGlobalIrradianceInfo();
  ///@}

  /**
   * Data other than image data (unstructured, structured, rectilinear grids,
   * polydata and AMR) are resampled to an image of these many points over their
   * bounds, as Volume's "Resample To Image" does (default 128^3, ParaView's
   * SamplingDimensions); in parallel with vtkPResampleToImage. Below 2 on an
   * axis: an error, the old value is kept.
   */
  void SetSamplingDimensions(int x, int y, int z);
  /// What the last resampling made and what it cost; empty for image data.
  const char* GetResampleInfo() { return this->ResampleInfo.c_str(); }

  vtkMultiMaterialVolumeMapper* GetMultiMaterialMapper();

  /// REQUEST_UPDATE (on every rank at once) also combines the pieces for
  /// global shadows.
  int ProcessViewRequest(vtkInformationRequestKey* request_type, vtkInformation* inInfo,
    vtkInformation* outInfo) override;

protected:
  vtkPVMultiMaterialVolumeRepresentation();
  ~vtkPVMultiMaterialVolumeRepresentation() override;

  void UpdateMapperParameters() override;
  /// Image blocks (vtkMultiBlockDataSet, vtkPartitionedDataSet[Collection]
  /// of vtkImageData) are merged into the box they tile on each rank
  /// (mmv::MergeImageBlocks), then drawn as one image: the ray caster and
  /// the global irradiance exchange take one image per rank.
  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  // PointLightRadius, or the automatic radius while it is 0.
  double FalloffRadius() const;
  // Resamples `data` (a vtkDataSet, or AMR's levels of blocks, the finest
  // block that holds a point giving its value) to image data and draws that.
  int RequestResampledData(vtkInformation* request, vtkInformation* inInfo, vtkDataObject* data,
    vtkInformationVector* outputVector);

private:
  vtkPVMultiMaterialVolumeRepresentation(const vtkPVMultiMaterialVolumeRepresentation&) = delete;
  void operator=(const vtkPVMultiMaterialVolumeRepresentation&) = delete;

  bool UsesPreset() const;
  // The mapper's irradiance progress as this one's, which ParaView's
  // progress handler observes.
  void ForwardProgress(vtkObject* caller, unsigned long event, void* progress);
  // The mapper's VectorMode (and `component`) from the colour map, as
  // vtkImageVolumeRepresentation sets its mapper's.
  int MapperVectorMode(int& component);
  // Collective (every rank, same order): combines the pieces into
  // GlobalVolume when the data or the settings it depends on changed.
  void UpdateGlobalVolume();
  // Hands the mapper the view's background for reflections (REQUEST_RENDER).
  void PinReflectionBackground();

  // Nodes from MaterialNodes; kept apart from the mapper's function so that
  // switching a preset off brings them back.
  vtkNew<vtkMaterialTransferFunction> CustomMaterials;
  // What the mapper shades with: CustomMaterials or the preset.
  vtkNew<vtkMaterialTransferFunction> Materials;
  vtkNew<vtkDoubleArray> AppliedNodes;
  vtkNew<vtkStringArray> PresetNames;

  vtkPVMaterialNodeBuffer PendingNodes;
  std::unique_ptr<vtkMultiMaterialFieldSettings> Fields;

  std::string MaterialPreset;
  double PresetRange[2] = { 0.0, -1.0 };

  double PointLightRadius = 0.0;
  double SampleDistance = 1.0;
  bool AutoAdjustSampleDistances = true;
  bool LockSampleDistanceToInputSpacing = false;
  double IrradianceCacheMB = 1024.0;
  int LightFalloff = 0;
  int LightingQuality = 1; // mmv::DefaultLightingQuality

  vtkNew<vtkGlobalPrefilteredVolume> GlobalVolume;
  // RequestData runs on every rank together, so counting it gives every rank
  // the same key for deciding when to exchange (no rank may skip it alone).
  int DataGeneration = 0;
  std::vector<double> GlobalKey;
  std::string GlobalArray;
  std::string GlobalInfo;
  std::string StagesInfo;

  int SamplingDimensions[3] = { 128, 128, 128 };
  bool Resampled = false; // the data drawn are a resampled image
  std::string ResampleInfo;
};

#endif
