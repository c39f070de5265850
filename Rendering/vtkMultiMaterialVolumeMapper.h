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
 * Falls back to the base class (warning once) for what it does not model:
 * several components without a VectorMode, blend modes other than
 * composite, cell scalars in bricks, and volumes longer than the largest 3D
 * texture (rendered in bricks).
 */
#ifndef vtkMultiMaterialVolumeMapper_h
#define vtkMultiMaterialVolumeMapper_h

#include "vtkMultiMaterialParameters.h"   // ShadowEstimation
#include "vtkMultiMaterialVolumeModule.h" // export macro
#include "vtkVolumeInputScalars.h"         // VectorModes
#include "vtkOpenGLGPUVolumeRayCastMapper.h"

#include <string> // shader source
#include <vector> // ReadIrradiance

class vtkDataArray;
class vtkGlobalPrefilteredVolume;
class vtkImageData;
class vtkIrradianceVolumePass;
class vtkIrradianceResolutionProbe;
class vtkMaterialTransferFunction;
class vtkMatrix4x4;
class vtkOpenGLRenderWindow;
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
  void SetVectorModeToMagnitude() { this->SetVectorMode(mmv::VectorModeMagnitude); }
  void SetVectorModeToComponent() { this->SetVectorMode(mmv::VectorModeComponent); }
  void SetVectorModeToDisabled() { this->SetVectorMode(mmv::VectorModeDisabled); }

  /// The component VectorModeComponent shades (default 0). A negative value
  /// is an error (kept as it was); one at or past the array's number of
  /// components is reported (vtkErrorMacro) at render time and nothing is
  /// drawn until it is fixed.
  virtual void SetVectorComponent(int component);
  vtkGetMacro(VectorComponent, int);

  /// Irradiance memory budget in MB (16 bits per light per voxel). Default 64.
  vtkSetClampMacro(IrradianceMemoryMB, double, 0.001, 1.0e6);
  vtkGetMacro(IrradianceMemoryMB, double);

  /**
   * GPU memory in MB for the irradiance of earlier inputs, kept so that data
   * coming back (the steps of a series on its second loop, with ParaView's
   * animation caching) costs a copy instead of an update
   * (vtkIrradianceStepCache); their gradient volumes are kept within the
   * same amount again. 0 (the default) keeps none. The irradiance is not
   * kept for a piece of a volume in pieces.
   */
  vtkSetClampMacro(IrradianceCacheMB, double, 0.0, 1.0e6);
  vtkGetMacro(IrradianceCacheMB, double);

  /// Irradiance resolution as a fraction of the data's (0 < x <= 1); 0 (the
  /// default) chooses it from the memory budget, the screen and the error
  /// probe (IrradianceErrorBound).
  /// Values above 1 are reported (warning) and used as 1; negative or NaN
  /// ones as 0.
  vtkSetMacro(IrradianceScale, double);
  vtkGetMacro(IrradianceScale, double);

  /**
   * With an automatic resolution (IrradianceScale 0): the error the
   * irradiance may lose to a coarser grid, in dB (default
   * mmv::DefaultIrradianceErrorBoundDB). Once per data or transfer-function
   * change, vtkIrradianceResolutionProbe measures the opacity-weighted
   * PSNR of coarser grids against the budget's and keeps the coarsest
   * within this bound (smooth data gets a coarse grid, thin shells keep a
   * fine one; camera and light moves never re-measure). 0: no probe, the
   * budget and the screen alone choose. Negative or NaN: 0, above
   * mmv::MaxIrradianceErrorBoundDB: that maximum (both reported).
   */
  vtkSetMacro(IrradianceErrorBound, double);
  vtkGetMacro(IrradianceErrorBound, double);

  /// The error probe's measurements so far (a camera move adds none).
  int GetNumberOfIrradianceProbes();
#ifndef __VTK_WRAP__
  /// The error probe itself (its last measurement's candidates).
  vtkIrradianceResolutionProbe* GetIrradianceResolutionProbe();
#endif

  /// Smooths the shading normal: the gradient volume is blurred by a Gaussian
  /// whose standard deviation is this many times the largest data spacing
  /// (round in world space). Default 0 (none: the references' model). About
  /// 1 removes the stripes that thin shells sampled coarsely show at the
  /// voxel spacing (docs/stability.md, "Stripes on thin shells"). Negative or NaN: reported, used as 0;
  /// above mmv::MaxGradientSmoothing (4): reported, clamped.
  vtkSetMacro(GradientSmoothing, double);
  vtkGetMacro(GradientSmoothing, double);

  /// Diffusion for multiple scattering (default on; skipped when every s = 0).
  vtkSetMacro(MultipleScattering, bool);
  vtkGetMacro(MultipleScattering, bool);
  vtkBooleanMacro(MultipleScattering, bool);

  /**
   * How directional lights (ParaView's light kit, VTK's default light) are
   * estimated: mmv::PiecewiseShadowRays (1, default), shadow rays swept
   * along the light that end on the transmittance of a slice computed
   * before (vtkShadowSweep.h; O(n^3 K) for an n^3 grid), or
   * mmv::FullShadowRays (0), one ray per voxel to the boundary (exact,
   * O(n^4)). Point and spot lights always take full rays. Accuracy and
   * speed of both: docs/performance.md, "Piecewise shadow rays".
   */
  vtkSetClampMacro(ShadowEstimation, int, 0, 1);
  vtkGetMacro(ShadowEstimation, int);

  /// Slices a piecewise shadow ray spans at most (default
  /// mmv::DefaultPiecewiseShadowSlices): fewer blur shadow edges more.
  vtkSetClampMacro(PiecewiseShadowSlices, int, 1, 4096);
  vtkGetMacro(PiecewiseShadowSlices, int);

  /// The diffusion's time integration (vtkIrradianceVolumePass): on
  /// (default, mmv::DefaultExponentialDiffusion), the exponential's
  /// Chebyshev series, exact in time, in far fewer passes than off,
  /// backward-Euler sub-steps (docs/performance.md, "Diffusion: exponential
  /// series against backward Euler").
  vtkSetMacro(ExponentialDiffusion, bool);
  vtkGetMacro(ExponentialDiffusion, bool);
  vtkBooleanMacro(ExponentialDiffusion, bool);

  /**
   * Degrees a light may move and keep its irradiance (ParaView's light kit
   * follows the camera, so a rotation moves every kit light). Default
   * mmv::DefaultLightDirectionToleranceDegrees (0): every move recomputes,
   * and the image at rest equals a fresh render. Directional lights compare
   * directions; point and spot lights the angle their move subtends at the
   * volume's centre, and the spot axis. The comparison is with the placement
   * the irradiance holds, so small moves do not add up; shading terms always
   * use the current placement. The image error against the exact one per
   * angle is in docs/performance.md ("Light tolerance"). Clamped to [0, 45];
   * NaN: 0.
   */
  vtkSetClampMacro(LightDirectionTolerance, double, 0.0, mmv::MaxLightDirectionToleranceDegrees);
  vtkGetMacro(LightDirectionTolerance, double);

  /**
   * Dim lights on a coarser grid (default on): a light at most
   * mmv::DimLightRatio of the brightest light's radiance (the light kit's
   * fill, back and head lights) gets its shadows on every
   * mmv::DimLightStride-th irradiance point per axis, interpolated, an
   * eighth of its shadow rays (vtkMultiMaterialParameters.h). Off: every
   * light on the irradiance grid.
   */
  vtkSetMacro(DimLightCoarsening, bool);
  vtkGetMacro(DimLightCoarsening, bool);
  vtkBooleanMacro(DimLightCoarsening, bool);

  /// Pre-integrated segments (default on); off: post-classified samples.
  vtkSetMacro(PreIntegration, bool);
  vtkGetMacro(PreIntegration, bool);
  vtkBooleanMacro(PreIntegration, bool);

  /// Falloff of point and spot lights. 0 (default): VTK's, by each light's
  /// AttenuationValues (constant, linear, quadratic; the default (1, 0, 0)
  /// means none). > 0: the paper's eq. 12 with this radius epsilon (object
  /// units), (epsilon / distance)^2 beyond it. A negative or non-finite
  /// value is reported (warning) and treated as 0.
  vtkSetMacro(PointLightRadius, double);
  vtkGetMacro(PointLightRadius, double);

  /// Compile the Henyey-Greenstein and emission terms in even when every
  /// material leaves them at 0 (default off: the shader then leaves them
  /// out). For tests and benchmarks: at g = 0 and e = 0 the image is the same.
  vtkSetMacro(CompileUnusedOpticalTerms, bool);
  vtkGetMacro(CompileUnusedOpticalTerms, bool);

  /// Where reflections take their environment colour c_r (eq. 17) from:
  /// 0 (mmv::ReflectEnvironmentTexture, default), the renderer's environment
  /// texture (cube map or equirectangular image) when one is set, else the
  /// background; 1 (mmv::ReflectBackground), the background colour or
  /// gradient. A texture that is not a cube map or 2D image, or is empty, is
  /// reported (warning) and the background used (vtkMultiMaterialEnvironment).
  vtkSetClampMacro(ReflectionSource, int, 0, 1);
  vtkGetMacro(ReflectionSource, int);

  /// Pins the background gradient reflections read (bottom and top colours)
  /// instead of the renderer's at render time. ParaView's representation
  /// pins its view's background before each render: under parallel
  /// compositing the ranks draw over a background cleared to black.
  void SetReflectionBackground(const double bottom[3], const double top[3]);
  void ClearReflectionBackground();

  /// The visibility I(x, w_r) of reflections (eq. 17): 3
  /// (mmv::AutomaticReflectionVisibility, default), per frame the cheaper of
  /// 1 and 2 for the view's size (mmv::PerSampleMarchPixelsPerVoxel); 2
  /// (mmv::ViewDependentReflectionVisibility), a march through the
  /// pre-filtered extinction once per irradiance voxel when the camera or the
  /// volume changes, interpolated by the ray cast; 1
  /// (mmv::MarchedReflectionVisibility), the same march from every shaded
  /// sample with r > 0 (dearer than 2 on large views while the camera turns;
  /// docs/performance.md, "Material terms: cost");
  /// 0 (mmv::UnoccludedReflections), none. Both marches honour the cropping
  /// region and clipping planes (cut material does not occlude). Needs a
  /// light (the pre-filtered volume comes with the irradiance): without one,
  /// unoccluded (warning).
  vtkSetClampMacro(ReflectionVisibility, int, 0, 3);
  vtkGetMacro(ReflectionVisibility, int);

  /// Pre-integration table size n (n x n). Default 256.
  vtkSetClampMacro(PreIntegrationTableSize, int, 16, 1024);
  vtkGetMacro(PreIntegrationTableSize, int);

  /**
   * What interactive renders (VTK's signal: the volume's allocated render
   * time below 1 s, as during a mouse drag in ParaView or a
   * vtkRenderWindowInteractor) do when only the lights moved, e.g. the
   * camera-attached light kit while orbiting:
   *  - ReuseWhileInteracting (default): keep the last irradiance (shadows lag
   *    until the interaction ends) and ray cast only; the next still render
   *    brings it up to date, so the image at rest equals a fresh render.
   *    The view-dependent visibility of reflections
   *    (mmv::ViewDependentReflectionVisibility) likewise keeps the camera
   *    it was computed for while the camera moves;
   *  - UpdateAlways: every frame recomputes what changed.
   * A change of data, opacity or scattering materials updates either way.
   */
  enum InteractiveIrradianceModes
  {
    UpdateAlways = 0,
    ReuseWhileInteracting = 1
  };
  vtkSetClampMacro(InteractiveIrradiance, int, UpdateAlways, ReuseWhileInteracting);
  vtkGetMacro(InteractiveIrradiance, int);

  /// Brackets the stages with glFinish to time them (default off: it stalls
  /// the pipeline). Counters are always kept.
  vtkSetMacro(TimeStages, bool);
  vtkGetMacro(TimeStages, bool);
  vtkBooleanMacro(TimeStages, bool);

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
  /// the pre-filter, the shadow table, the shadows, the diffusion, the pass
  /// and the whole update.
  std::string GetLastIrradianceStages();

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

  /// Benchmark hook: the pass that estimates the irradiance (its
  /// LayeredRendering and SkipEmptyVoxels switches, its diffusion grid).
  vtkIrradianceVolumePass* GetIrradianceVolumePass();

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
   * With a global pre-filtered volume: estimate only the irradiance this
   * piece reads, and what that depends on (default on; the region equals
   * the whole grid's there, vtkIrradianceRegion.h), so that each rank's
   * share of the work falls with the number of ranks. Off: every rank
   * estimates the whole global grid.
   */
  vtkSetMacro(PieceIrradianceOnly, bool);
  vtkGetMacro(PieceIrradianceOnly, bool);
  vtkBooleanMacro(PieceIrradianceOnly, bool);

  /// The partitions (bricks) of the last render: those of SetPartitions, or
  /// more where a brick would exceed the largest 3D texture of the context
  /// (mmv::ChooseBrickPartitions), so that long volumes render instead of
  /// aborting in VTK's texture upload.
  vtkGetVector3Macro(BrickPartitions, int);

  /// The most megabytes one brick's texture may take (default 512): larger
  /// volumes are cut into more bricks, since a texture allocation the OpenGL
  /// implementation refuses (llvmpipe: over 1 GiB) aborts in VTK.
  vtkSetClampMacro(MaxBrickMB, double, 1.0, 1.0e6);
  vtkGetMacro(MaxBrickMB, double);

  /// Reduces a vector (VectorMode) before VTK validates and draws the input.
  void Render(vtkRenderer* ren, vtkVolume* vol) override;
  void GPURender(vtkRenderer* ren, vtkVolume* vol) override;
  void ReleaseGraphicsResources(vtkWindow* window) override;
  vtkMTimeType GetMTime() override;

protected:
  vtkMultiMaterialVolumeMapper();
  ~vtkMultiMaterialVolumeMapper() override;

  double IrradianceMemoryMB = mmv::DefaultIrradianceBudgetMB;
  double IrradianceScale = 0.0;
  double IrradianceErrorBound = mmv::DefaultIrradianceErrorBoundDB;
  double GradientSmoothing = 0.0;
  bool MultipleScattering = true;
  int ShadowEstimation = mmv::PiecewiseShadowRays;
  int PiecewiseShadowSlices = mmv::DefaultPiecewiseShadowSlices;
  bool ExponentialDiffusion = mmv::DefaultExponentialDiffusion;
  bool PreIntegration = true;
  double PointLightRadius = 0.0;
  int InteractiveIrradiance = ReuseWhileInteracting;
  double LightDirectionTolerance = mmv::DefaultLightDirectionToleranceDegrees;
  bool DimLightCoarsening = true;
  int PreIntegrationTableSize = 256;
  bool TimeStages = false;
  bool CompileUnusedOpticalTerms = false;
  int ReflectionSource = 0;     // mmv::ReflectEnvironmentTexture
  int ReflectionVisibility = 3; // mmv::AutomaticReflectionVisibility
  bool PieceIrradianceOnly = true;
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
  int NumberOfUpdatedLights = 0;
  int DeferredIrradianceCount = 0;
  int IrradianceCacheHitCount = 0;
  double IrradianceCacheMB = 0.0;
  bool LastRenderInteractive = false;
  bool MultiMaterialActive = false;
  bool PartitionsRequested = false;
  int RequestedPartitions[3] = { 1, 1, 1 };
  int BrickPartitions[3] = { 1, 1, 1 };
  double MaxBrickMB = 512.0;

private:
  vtkMultiMaterialVolumeMapper(const vtkMultiMaterialVolumeMapper&) = delete;
  void operator=(const vtkMultiMaterialVolumeMapper&) = delete;

  // Validates the inputs and refreshes every cache the frame needs; false
  // means "render with the base class". Its steps follow.
  bool PrepareMultiMaterial(vtkRenderer* ren, vtkVolume* vol);
  // Puts the array VectorMode selects into the ray caster's copy of the
  // input; false (with an error) when it cannot, and nothing is drawn.
  bool SelectVectorScalars(vtkRenderer* ren);
  bool UpdateSegmentTables(
    vtkOpenGLRenderWindow* context, vtkVolume* vol, vtkImageData* image, const double range[2]);
  bool UpdateGradient(vtkOpenGLRenderWindow* context, vtkImageData* image,
    vtkDataArray* scalars, const double range[2]);
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
  friend class vtkMultiMaterialIrradianceStage;
};

#endif
