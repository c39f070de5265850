/**
 * @class   vtkMultiMaterialVolumeMapper
 * @brief   Decoupled multi-material shading (Zhang & Ma) inside VTK's GPU ray caster.
 *
 * A vtkOpenGLGPUVolumeRayCastMapper whose composite ray casting shades every
 * pre-integrated ray segment with the material of its data value (ka, kd, ks,
 * shininess, reflection from a vtkMaterialTransferFunction), the irradiance
 * of every renderer light (shadows from an irradiance volume estimated on the
 * GPU, multiple scattering by diffusion) and an environment reflection.
 * Colour and opacity come from the usual vtkVolumeProperty; sampling from the
 * usual SetSampleDistance / AutoAdjustSampleDistances. Everything else VTK's
 * mapper does (cropping, clipping planes, depth compositing with geometry,
 * other blend modes) is left to the base class.
 *
 * Only what changed is recomputed (the paper's Algorithm 1): segment tables
 * when the colour/opacity functions or the step change; the irradiance of a
 * light when that light moves relative to the volume, of every light when
 * opacity, scattering materials, data or the irradiance grid change; a
 * camera move with scene lights costs one ray cast. Camera-attached lights
 * (ParaView's default light kit) move with the camera: interactive renders
 * keep their last irradiance (InteractiveIrradiance) and the still render
 * after the interaction updates it. The irradiance resolution follows the
 * screen and the memory budget (mmv::ChooseIrradianceResolution), and the
 * diffusion runs on a grid coarsened to the diffusion length. Counters and
 * stage timers expose this.
 *
 * Shading semantics: with ka = 1, kd = ks = r = 0 and one white light of
 * intensity 1, a segment emits c * mu * I_k (I_k the light's transmittance to
 * it, with sigma = attenuation * mu), composited front to back with
 * transmittance exp(-int mu).
 *
 * Cell scalars are lit on the grid of the cell centres, where VTK's ray
 * caster knows their field (mmv::MakeCellCentreImage); vectors are shaded by
 * their magnitude or one component (VectorMode, VectorComponent), as
 * vtkSmartVolumeMapper draws them.
 *
 * Several components are several fields (SetFieldMaterialTransferFunction)
 * when the volume property's components are independent.
 *
 * Falls back to the base class (warning once) for what it does not model:
 * dependent components without a VectorMode, more than 4 fields, blend
 * modes other than composite, cell scalars or several fields in bricks or
 * pieces, and volumes longer than the largest 3D texture (rendered in
 * bricks).
 */
#ifndef vtkMultiMaterialVolumeMapper_h
#define vtkMultiMaterialVolumeMapper_h

#include "vtkMultiMaterialParameters.h"   // ShadowEstimation
#include "vtkMultiMaterialSettings.h"     // IlluminationSettings
#include "vtkMultiMaterialVolumeModule.h" // export macro
#include "vtkOpenGLGPUVolumeRayCastMapper.h"
#include "vtkVolumeInputScalars.h" // VectorModes

#include <string> // shader source
#include <vector> // ReadIrradiance

class vtkDataArray;
class vtkDataSet;
class vtkGlobalPrefilteredVolume;
class vtkImageData;
class vtkIrradianceEstimator;
class vtkIrradianceResolutionProbe;
class vtkMaterialTransferFunction;
class vtkMatrix4x4;
class vtkOpenGLRenderWindow;
#ifndef __VTK_WRAP__
namespace mmv
{
class CoarseExtinction;
}
#endif
class vtkVolumeProperty;

class VTKMULTIMATERIALVOLUME_EXPORT vtkMultiMaterialVolumeMapper
  : public vtkOpenGLGPUVolumeRayCastMapper
{
public:
  static vtkMultiMaterialVolumeMapper* New();
  vtkTypeMacro(vtkMultiMaterialVolumeMapper, vtkOpenGLGPUVolumeRayCastMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Material parameters by data value; null means the defaults everywhere.
  void SetMaterialTransferFunction(vtkMaterialTransferFunction* materials);
  vtkMaterialTransferFunction* GetMaterialTransferFunction();

  /**
   * Several fields on one grid: with the volume property's
   * IndependentComponents on (VTK's default) and VectorMode disabled, each
   * of the 2-4 components of the scalars is a field with its own colour and
   * opacity (the property's component `field`) and its own materials, set
   * here; field 0's are MaterialTransferFunction. Shadows and scattering
   * come from their combined extinction, and each segment is shaded by each
   * field's share of its opacity (vtkMultiMaterialFields.h). A field out of
   * [0, 3] is an error.
   */
  void SetFieldMaterialTransferFunction(int field, vtkMaterialTransferFunction* materials);
  vtkMaterialTransferFunction* GetFieldMaterialTransferFunction(int field);
  /// Fields shaded by the last render (1 for one-component scalars).
  vtkGetMacro(NumberOfFields, int);

  ///@{
  /**
   * Several fields from several arrays: each named array of the input (with
   * the scalars' association, one component, up to 3 of them) is read as
   * the next field after the scalars, as if the scalars had it as their next
   * component. The ray caster's copy of the input gets the combined array in
   * the scalars' place. An array that is missing or does not fit is
   * reported (vtkErrorMacro) and the scalars are shaded alone.
   */
  void AddFieldArray(const char* name);
  void RemoveAllFieldArrays();
#ifndef __VTK_WRAP__
  /// All at once; the mapper is modified only when the list changes.
  void SetFieldArrays(const std::vector<std::string>& names);
#endif
  int GetNumberOfFieldArrays() const
  {
    return static_cast<int>(this->FieldArrays.size());
  }
  const char* GetFieldArray(int i) const;
  ///@}

  /**
   * How multi-component scalars are shaded, as vtkSmartVolumeMapper's
   * VectorMode (ParaView's colour map Magnitude / X / Y / Z):
   * mmv::VectorModeDisabled (-1, default; several components render with
   * VTK's shading), mmv::VectorModeMagnitude (0, the Euclidean norm) or
   * mmv::VectorModeComponent (1, component VectorComponent). The reduced
   * array replaces the vector in the ray caster's copy of the input, so
   * VTK's ray cast and the lighting see the same values; one-component
   * scalars are used as they are in every mode. Out of [-1, 1]: clamped.
   */
  vtkSetClampMacro(VectorMode, int, mmv::VectorModeDisabled, mmv::VectorModeComponent);
  vtkGetMacro(VectorMode, int);
  void SetVectorModeToMagnitude()
  {
    this->SetVectorMode(mmv::VectorModeMagnitude);
  }
  void SetVectorModeToComponent()
  {
    this->SetVectorMode(mmv::VectorModeComponent);
  }
  void SetVectorModeToDisabled()
  {
    this->SetVectorMode(mmv::VectorModeDisabled);
  }

  /// The component VectorModeComponent shades (default 0). A negative value
  /// is an error (kept as it was); one at or past the array's number of
  /// components is reported (vtkErrorMacro) at render time and nothing is
  /// drawn until it is fixed.
  virtual void SetVectorComponent(int component);
  vtkGetMacro(VectorComponent, int);

  ///@{
  /**
   * The settings, one mmv::IlluminationSettings (vtkMultiMaterialSettings.h
   * gives each one's default, range and meaning). A setter clamps to the
   * range and marks the mapper modified only on a change; SetSettings takes
   * them all at once, clamped the same way.
   */
#ifndef __VTK_WRAP__
  void SetSettings(const mmv::IlluminationSettings& settings);
  const mmv::IlluminationSettings& GetSettings() const
  {
    return this->Settings;
  }
#endif
  void SetIrradianceMemoryMB(double megabytes);
  double GetIrradianceMemoryMB();
  void SetIrradianceCacheMB(double megabytes);
  double GetIrradianceCacheMB();
  void SetIrradianceScale(double scale);
  double GetIrradianceScale();
  void SetIrradianceErrorBound(double decibels);
  double GetIrradianceErrorBound();
  void SetGradientSmoothing(double sigma);
  double GetGradientSmoothing();
  void SetMultipleScattering(bool enabled);
  bool GetMultipleScattering();
  void MultipleScatteringOn()
  {
    this->SetMultipleScattering(true);
  }
  void MultipleScatteringOff()
  {
    this->SetMultipleScattering(false);
  }
  void SetShadowEstimation(int estimation);
  int GetShadowEstimation();
  void SetPiecewiseShadowSlices(int slices);
  int GetPiecewiseShadowSlices();
  void SetExponentialDiffusion(bool exponential);
  bool GetExponentialDiffusion();
  void ExponentialDiffusionOn()
  {
    this->SetExponentialDiffusion(true);
  }
  void ExponentialDiffusionOff()
  {
    this->SetExponentialDiffusion(false);
  }
  void SetLightDirectionTolerance(double degrees);
  double GetLightDirectionTolerance();
  void SetDimLightCoarsening(bool coarsening);
  bool GetDimLightCoarsening();
  void DimLightCoarseningOn()
  {
    this->SetDimLightCoarsening(true);
  }
  void DimLightCoarseningOff()
  {
    this->SetDimLightCoarsening(false);
  }
  void SetPreIntegration(bool enabled);
  bool GetPreIntegration();
  void PreIntegrationOn()
  {
    this->SetPreIntegration(true);
  }
  void PreIntegrationOff()
  {
    this->SetPreIntegration(false);
  }
  void SetPreIntegrationTableSize(int size);
  int GetPreIntegrationTableSize();
  void SetPointLightRadius(double radius);
  double GetPointLightRadius();
  void SetCompileUnusedOpticalTerms(bool compile);
  bool GetCompileUnusedOpticalTerms();
  /**
   * The environment light: the renderer's background (its environment
   * texture when ReflectionSource takes it) as a sky that lights the volume
   * through its occlusion, times this strength (default 0: off, and no sky
   * code in the shader; 1: the background's radiance). Negative or NaN: off,
   * with a warning. See vtkMultiMaterialSky.h.
   */
  void SetEnvironmentLighting(double strength);
  double GetEnvironmentLighting();
  /// Estimations of the sky's visibility so far, and the last one's seconds.
  int GetSkyUpdateCount();
  double GetLastSkySeconds();
  void SetReflectionSource(int source);
  int GetReflectionSource();
  void SetReflectionVisibility(int visibility);
  int GetReflectionVisibility();
  void SetInteractiveIrradiance(int mode);
  int GetInteractiveIrradiance();
  void SetTimeStages(bool timed);
  bool GetTimeStages();
  void TimeStagesOn()
  {
    this->SetTimeStages(true);
  }
  void TimeStagesOff()
  {
    this->SetTimeStages(false);
  }
  void SetPieceIrradianceOnly(bool pieceOnly);
  bool GetPieceIrradianceOnly();
  void PieceIrradianceOnlyOn()
  {
    this->SetPieceIrradianceOnly(true);
  }
  void PieceIrradianceOnlyOff()
  {
    this->SetPieceIrradianceOnly(false);
  }
  void SetMaxBrickMB(double megabytes);
  double GetMaxBrickMB();
  ///@}

  /// The error probe's measurements so far (a camera move adds none).
  int GetNumberOfIrradianceProbes();
#ifndef __VTK_WRAP__
  /// The error probe itself (its last measurement's candidates).
  vtkIrradianceResolutionProbe* GetIrradianceResolutionProbe();
#endif

  /// Pins the background gradient reflections read (bottom and top colours)
  /// instead of the renderer's at render time. ParaView's representation
  /// pins its view's background before each render: under parallel
  /// compositing the ranks draw over a background cleared to black.
  void SetReflectionBackground(const double bottom[3], const double top[3]);
  void ClearReflectionBackground();

  /// InteractiveIrradiance's values (mmv::InteractiveIrradianceMode).
  enum InteractiveIrradianceModes
  {
    UpdateAlways = mmv::UpdateAlways,
    ReuseWhileInteracting = mmv::ReuseWhileInteracting
  };

  ///@{
  /// What rendering did so far / in the last frame.
  vtkGetMacro(PreIntegrationCount, int);
  vtkGetMacro(IrradianceUpdateCount, int);
  vtkGetMacro(DiffusionPassCount, int);
  vtkGetMacro(RayCastCount, int);
  vtkGetMacro(LastPreIntegrationSeconds, double);
  vtkGetMacro(LastIrradianceSeconds, double);
  vtkGetMacro(LastRayCastSeconds, double);
  /// CPU time of the last frame's preparation (inputs checked, keys, tables,
  /// uniforms), the irradiance pass excluded; kept without TimeStages.
  vtkGetMacro(LastPrepareSeconds, double);
  vtkGetVector3Macro(IrradianceDimensions, int);
  vtkGetMacro(NumberOfShadedLights, int);
  /// Lights whose irradiance the last update recomputed (the others kept theirs).
  vtkGetMacro(NumberOfUpdatedLights, int);
  /// Interactive frames that kept a stale irradiance (InteractiveIrradiance).
  vtkGetMacro(DeferredIrradianceCount, int);
  /// Updates served from the irradiance of an earlier input (IrradianceCacheMB),
  /// and the memory those copies hold now.
  vtkGetMacro(IrradianceCacheHitCount, int);
  size_t GetIrradianceCacheBytes();
  /// Whether the last render was interactive (allocated render time < 1 s).
  vtkGetMacro(LastRenderInteractive, bool);
  /// The irradiance (and diffusion) resolution in use, and why it was chosen.
  const char* GetIrradianceResolutionReason();
  /// Seconds of each stage of the last irradiance update: the error probe,
  /// the pre-filter, the shadow table, the estimator's inputs (classes on the
  /// CPU and the diffusion plan), the shadows, the diffusion, the estimator
  /// and the whole update.
  std::string GetLastIrradianceStages();
  /// Wall-clock seconds of each stage of the last render's preparation on
  /// the CPU: the input (checks, ranges), the segment tables, the gradient
  /// volume, the lights, the irradiance update (all of it, GetLastIrradianceStages
  /// splits it), the environment light and the shading's uniforms.
  std::string GetLastPrepareStages();

  /// How often the view-dependent visibility of reflections
  /// (mmv::ViewDependentReflectionVisibility) was computed: only when the
  /// camera or the volume changed.
  vtkIdType GetReflectionVisibilityUpdateCount();
  /// Whether the last render used multi-material shading (false: base class).
  vtkGetMacro(MultiMaterialActive, bool);
  /// Uploads of the gradient volume so far: one per data change.
  int GetGradientUploadCount();
  ///@}

  /// GPU memory held by our textures (irradiance + tables), in bytes.
  vtkIdType GetMultiMaterialMemoryBytes();

  /// Test hook: the irradiance of shaded light k (in the order of the
  /// renderer's active lights), x fastest. Needs the render window.
  bool ReadIrradiance(vtkRenderWindow* window, int light, std::vector<float>& values);

  /// Benchmark hook: the estimator that estimates the irradiance (its
  /// LayeredRendering and SkipEmptyVoxels switches, its diffusion grid).
  vtkIrradianceEstimator* GetIrradianceEstimator();

  /// Test hook: the fragment shader of the last shader build.
  std::string GetLastFragmentShaderSource();

  /// Bricks (VTK's partitioned textures): each block is shaded with
  /// materials through the whole volume's gradient and irradiance textures
  /// (Shaders/mmvRayCastDec.glsl, mmvWholeTexCoord), so shadows and
  /// gradients are continuous across block faces. A volume larger than the
  /// largest 3D texture is bricked by itself but, since its gradient volume
  /// does not fit one texture, shaded by VTK (with a warning).
  void SetPartitions(unsigned short x, unsigned short y, unsigned short z);

  /**
   * Global shadows for a volume split into pieces (MPI ranks): the
   * pre-filtered whole volume (vtkGlobalPrefilteredVolume, combined by the
   * caller). While it is set and valid, the irradiance is estimated on its
   * grid (its resolution, not the screen's) from its data and scalar range,
   * the gradient is normalised by that range, and this mapper's input (one
   * piece) maps its texture coordinates into the global irradiance. Null
   * (default) or invalid: the input alone.
   */
  void SetGlobalPrefilteredVolume(vtkGlobalPrefilteredVolume* volume);
  vtkGlobalPrefilteredVolume* GetGlobalPrefilteredVolume();

  /**
   * Several volumes in one renderer shadow each other: every visible
   * vtkVolume of the renderer whose mapper is a vtkMultiMaterialVolumeMapper
   * dims the lights of the others (vtkMultiMaterialSceneShadows.h), moved,
   * edited, hidden or removed at any time. Overlapping volumes shadow each
   * other but are not composited within one ray.
   * Volumes that shadowed this one in the last irradiance update, how
   * often their transmittance was computed, and the last one's seconds.
   */
  int GetNumberOfSceneOccluders();
  int GetSceneShadowUpdateCount();
  double GetLastSceneShadowSeconds();
#ifndef __VTK_WRAP__
  /// This mapper's data drawn by `vol`, as the other volumes' shadows see
  /// it (its extinction on a coarse grid of its object space); null when it
  /// casts none.
  const mmv::CoarseExtinction* GetSceneOccluder(vtkVolume* vol);
#endif

  /// The partitions (bricks) of the last render: those of SetPartitions, or
  /// more where a brick would exceed the largest 3D texture of the context
  /// (mmv::ChooseBrickPartitions), so that long volumes render instead of
  /// aborting in VTK's texture upload.
  vtkGetVector3Macro(BrickPartitions, int);

  /// Reduces a vector (VectorMode) before VTK validates and draws the input.
  void Render(vtkRenderer* ren, vtkVolume* vol) override;
  void GPURender(vtkRenderer* ren, vtkVolume* vol) override;
  void ReleaseGraphicsResources(vtkWindow* window) override;
  vtkMTimeType GetMTime() override;

protected:
  vtkMultiMaterialVolumeMapper();
  ~vtkMultiMaterialVolumeMapper() override;

  mmv::IlluminationSettings Settings;
  int VectorMode = mmv::VectorModeDisabled;
  int VectorComponent = 0;

  int PreIntegrationCount = 0;
  int IrradianceUpdateCount = 0;
  int DiffusionPassCount = 0;
  int RayCastCount = 0;
  double LastPreIntegrationSeconds = 0.0;
  double LastIrradianceSeconds = 0.0;
  double LastRayCastSeconds = 0.0;
  double LastPrepareSeconds = 0.0;
  int IrradianceDimensions[3] = { 0, 0, 0 };
  int NumberOfShadedLights = 0;
  bool SkyShaded = false; // the environment light is in this frame's shader
  int NumberOfUpdatedLights = 0;
  int DeferredIrradianceCount = 0;
  int IrradianceCacheHitCount = 0;
  bool LastRenderInteractive = false;
  bool MultiMaterialActive = false;
  int NumberOfFields = 1;
  std::vector<std::string> FieldArrays;
  bool PartitionsRequested = false;
  int RequestedPartitions[3] = { 1, 1, 1 };
  int BrickPartitions[3] = { 1, 1, 1 };

private:
  vtkMultiMaterialVolumeMapper(const vtkMultiMaterialVolumeMapper&) = delete;
  void operator=(const vtkMultiMaterialVolumeMapper&) = delete;

  // Validates the inputs and refreshes every cache the frame needs; false
  // means "render with the base class". Its steps follow.
  bool PrepareMultiMaterial(vtkRenderer* ren, vtkVolume* vol);
  // Puts the array VectorMode selects, with the FieldArrays, into the ray
  // caster's copy of the input; false (with an error) when it cannot, and
  // nothing is drawn.
  bool SelectDrawnScalars(vtkRenderer* ren);
  // `scalars` with the FieldArrays of `input` as further components (the
  // scalars themselves when there are none or they do not fit).
  vtkDataArray* WithFieldArrays(vtkDataSet* input, int cellFlag, vtkDataArray* scalars);
  bool UpdateSegmentTables(vtkOpenGLRenderWindow* context, vtkVolume* vol, vtkImageData* image);
  // With several fields: the combined extinction the lighting reads (false,
  // warned, when it cannot be made).
  bool UpdateFieldLighting(vtkVolume* vol, vtkDataArray* scalars);
  bool UpdateGradient(vtkOpenGLRenderWindow* context, vtkImageData* image, vtkDataArray* scalars,
    const double range[2]);
  // The irradiance stage on this frame's inputs; its report becomes the
  // counters and warnings.
  /// The environment light's visibility and colours; false: no sky this frame.
  bool UpdateSky(vtkRenderer* ren, vtkImageData* image, vtkDataArray* scalars,
    const double range[2], vtkVolumeProperty* property, vtkMatrix4x4* worldToObject);
  bool UpdateIrradiance(vtkRenderer* ren, vtkVolume* vol, vtkImageData* image,
    vtkDataArray* scalars, const double range[2], vtkMatrix4x4* worldToObject);
  void CollectShadedLights(vtkRenderer* ren, vtkMatrix4x4* worldToObject);
  void UpdateShading(
    vtkRenderer* ren, vtkImageData* image, vtkMatrix4x4* worldToObject, const double range[2]);
  void UpdateReflection(vtkRenderer* ren, vtkMatrix4x4* worldToObject, const double range[2]);
  void WarnOnce(const std::string& message);
  // Partitions the texture so that every brick fits the context's largest
  // 3D texture; false (with an error) when nothing fits.
  bool FitBricksToTextureLimit(vtkRenderer* ren);

  class vtkInternals;
  vtkInternals* Internals;
  // The irradiance step reads the settings and keeps the counters above.
};

#endif
