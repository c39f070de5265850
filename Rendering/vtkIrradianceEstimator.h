/**
 * @class   vtkIrradianceEstimator
 * @brief   The irradiance volume on the GPU (Zhang & Ma §5.1, §5.2, Algorithm 1
 *          lines 7-9): shadow rays at voxel centres and diffusion passes, in GLSL.
 *
 * The GPU twin of vtkIrradianceVolumeFilter: same grid (mmv::IrradianceGrid),
 * same pre-filtered samples, same pre-integrated shadow table, same light
 * model (Shaders/mmvLightModel.glsl), so the two agree within 1% of the light
 * intensity. Results live in RGBA16 3D textures (16 bits per light: 8 bits
 * bands visibly), four lights per texture: light k is channel k % 4 of
 * texture k / 4. Values are the fraction of each light reaching the voxel,
 * without colour and intensity.
 *
 * Passes (fragment shaders; each fills a whole 3D texture in one instanced
 * draw, layered rendering):
 *  1. the transmittance toward each light: directional lights by piecewise
 *     shadow rays (vtkShadowSweep.h: one draw per chunk of slices, swept
 *     along the light, every voxel) unless ShadowEstimation asks for full
 *     rays; other lights by full shadow rays for every non-empty voxel
 *     (opacity > 0; empty voxels are skipped and written as 0). Both march
 *     with steps of the shadow table's length, exact exit distance and
 *     partial last step, early termination;
 *  2. multiple scattering (only when some s > 0 and enabled), as
 *     mmv::DiffuseIrradianceOnDiffusionGrid does it on the CPU: restriction
 *     to the diffusion grid (coarsened to the diffusion length), then, drawn
 *     only over the box of blocks that scatter, by default
 *     (ExponentialDiffusion) the exponential's Chebyshev series, one pass
 *     per term, cut where the remaining coefficients bound the error by the
 *     tolerance; or backward-Euler sub-steps solved by Chebyshev-accelerated
 *     Jacobi sweeps, a long sub-step stopping on its residual (an occlusion
 *     query counts the blocks whose Jacobi correction exceeds (1 - rho)
 *     mmv::DiffusionSettings::SweepTolerance, which bounds the error by the
 *     tolerance), every sub-step at the latest after the sweeps the
 *     Chebyshev error bound needs; then the change is prolonged trilinearly
 *     to the irradiance grid;
 *  3. empty voxels bordering non-empty ones take the mean of those neighbours,
 *     and every voxel takes the transmittance through the other volumes of
 *     the scene, when there are any (SetSceneTransmittance).
 *
 * A piece of a volume split across MPI ranks needs only the voxels around
 * it (SetRegion): the passes then draw only what those voxels depend on
 * (vtkIrradianceRegion.h), and the region comes out as the whole grid's.
 *
 * Each light keeps its own channel: Render() recomputes only the lights that
 * changed since the last Render() (all of them when the volume, tables or
 * grid changed), writing their channels alone.
 *
 * Needs OpenGL 3.2 core (layered rendering into 3D textures); Render() returns
 * false with an error when the context cannot do it.
 */
#ifndef vtkIrradianceEstimator_h
#define vtkIrradianceEstimator_h

// The wrappers never see the GLM-typed API: parsing GLM's templates makes
// ParaView's client-server wrapping take minutes, and no wrapped language
// could call it anyway.
#ifndef __VTK_WRAP__
#include "vtkIrradianceGrid.h"       // IrradianceGrid
#ifndef __VTK_WRAP__                 // GLM: the wrappers take minutes to parse it
#include "vtkMultiMaterialCutaway.h" // Cutaway
#endif
#include "vtkMultiMaterialLightModel.h" // LightSource
#endif
#include "vtkMultiMaterialParameters.h"   // ShadowEstimation
#include "vtkMultiMaterialSettings.h"     // the shared defaults
#include "vtkMultiMaterialVolumeModule.h" // export macro
#include "vtkObject.h"

#include <functional> // progress callback
#include <vector>     // inputs

class vtkOpenGLRenderWindow;
class vtkShaderProgram;
class vtkTextureObject;
class vtkWindow;

class VTKMULTIMATERIALVOLUME_EXPORT vtkIrradianceEstimator : public vtkObject
{
public:
  static vtkIrradianceEstimator* New();
  vtkTypeMacro(vtkIrradianceEstimator, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Inputs (all on the CPU; uploaded by Render()):
   *  - grid and the pre-filtered scalars on it, normalised to the tables'
   *    coordinate: (value - range[0]) / (range[1] - range[0]);
   *  - the n x n shadow-opacity table of vtkPreIntegrationTable
   *    (GetShadowOpacityTable) over the same range, built for `stepLength`
   *    (object units), which is also the shadow-ray step;
   *  - n-entry classification tables over the same range: opacity (> 0 marks
   *    a voxel non-empty) and scattering strength s (data voxel^2 units);
   *  - the lights (at most mmv::MaxLights) in object space;
   *  - optionally a version that names the scalars' values (not 0;
   *    vtkIrradianceInputCache::GetPrefilteredVersion): the same version as
   *    last time means the same scalars, another version other scalars, and
   *    they are not compared. Without one they are compared.
   */
#ifndef __VTK_WRAP__
  void SetInputs(const mmv::IrradianceGrid& grid, const std::vector<float>& normalizedScalars,
    int tableSize, const float* shadowTable, double stepLength, const float* opacityTable,
    const float* scatteringTable, const std::vector<mmv::LightSource>& lights,
    unsigned long scalarsVersion = 0);
#endif

#ifndef __VTK_WRAP__
  /// What the shadow rays treat as empty (object space); a change recomputes
  /// every light.
  void SetCutaway(const mmv::Cutaway& cutaway);
  const mmv::Cutaway& GetCutaway() const;
#endif

  /// The uniforms of Shaders/mmvCutaway.glsl for the estimator's cutaway on its
  /// grid, for other marches through the pre-filtered volume (the
  /// reflections' visibility); nothing while nothing is cut.
  void SetCutawayUniforms(vtkShaderProgram* program) const;

  /// Diffusion for multiple scattering (default on); time T of eq. 15.
  vtkSetMacro(MultipleScattering, bool);
  vtkGetMacro(MultipleScattering, bool);
  vtkSetMacro(DiffusionTime, double);
  vtkGetMacro(DiffusionTime, double);

  /// The diffusion's time integration (mmv::DiffusionSettings::Exponential):
  /// on (default, mmv::DefaultExponentialDiffusion), the exponential's
  /// Chebyshev series, exact in time; off, backward-Euler sub-steps of
  /// Jacobi sweeps, several times more passes.
  vtkSetMacro(ExponentialDiffusion, bool);
  vtkGetMacro(ExponentialDiffusion, bool);
  vtkBooleanMacro(ExponentialDiffusion, bool);

  /// One instanced draw per pass into the whole 3D texture (default on), or
  /// one draw per slice; kept switchable to measure the difference.
  vtkSetMacro(LayeredRendering, bool);
  vtkGetMacro(LayeredRendering, bool);

  /**
   * How the voxel passes (shadow rays, diffusion, fill) run: 0, layered
   * fragment draws; 1, compute dispatches (OpenGL 4.3; fragment draws where
   * the context lacks it); 2, automatic (default): compute dispatches except
   * on a CPU rasterizer (llvmpipe, softpipe, swrast). Both give the same
   * irradiance. A GPU runs compute dispatches much faster, a CPU rasterizer
   * fragment draws (docs/performance.md, "On a GPU: NVIDIA H100").
   */
  enum ComputeShaderUse
  {
    FragmentDraws = 0,
    ComputeDispatches = 1,
    ComputeUnlessSoftware = 2
  };
  vtkSetClampMacro(ComputeShaders, int, FragmentDraws, ComputeUnlessSoftware);
  vtkGetMacro(ComputeShaders, int);
  /// Whether the last update ran compute dispatches.
  vtkGetMacro(ComputeShadersUsed, bool);

  /// Where a stage that both the GPU and the CPU can run runs
  /// (Classification, DiffusionPlace): on the GPU, on the CPU, or
  /// automatically on the GPU except on a CPU rasterizer.
  enum WorkPlace
  {
    OnGPU = 0,
    OnCPU = 1,
    OnGPUUnlessSoftware = 2
  };

  /**
   * Where the voxels' classes (which voxels are empty, and each one's
   * scattering) are made when the data or the opacity's support change: 0,
   * on the GPU (a pass over the irradiance grid; an opacity edit uploads two
   * small tables); 1, on the CPU, copied into the texture in place; 2,
   * automatic (default): on the GPU except on a CPU rasterizer, where that
   * pass and the dim lights' marks from it cost about 0.45 s a time step on
   * a 237 x 237 x 119 grid, the CPU's classes and their copy 0.1 s
   * (docs/performance.md, "Irradiance update stages"). Both give the same
   * classes. (A WorkPlace.)
   */
  vtkSetClampMacro(Classification, int, OnGPU, OnGPUUnlessSoftware);
  vtkGetMacro(Classification, int);
  /// Whether the last classification was made on the CPU and copied.
  vtkGetMacro(ClassesCopied, bool);

  /**
   * Where the diffusion with the exponential series (ExponentialDiffusion,
   * the default) runs: 0, in GPU passes (restriction to the diffusion grid,
   * one pass per term of the series, the change, the prolongation); 1, on
   * the CPU, between a read-back of the irradiance before it and an upload
   * after it; 2, automatic (default): on the GPU except on a CPU rasterizer,
   * whose fragment passes cost several times the same loops (`smoke`'s time
   * step on a 237 x 237 x 119 grid: 2.2-2.7 s of passes against 0.8 s;
   * docs/performance.md, "Irradiance update stages"). Both give the same
   * irradiance to a 16-bit texel's rounding. Backward-Euler diffusion
   * always runs on the GPU. (A WorkPlace.)
   */
  vtkSetClampMacro(DiffusionPlace, int, OnGPU, OnGPUUnlessSoftware);
  vtkGetMacro(DiffusionPlace, int);
  /// Whether the last update diffused on the CPU.
  vtkGetMacro(DiffusedOnCPU, bool);

  /**
   * Where a directional light's piecewise shadow rays run: 0, in fragment
   * passes (Shaders/mmvPiecewiseShadowFS.glsl), one per chunk; 1, on the
   * CPU (mmv::SweepTransmittanceOnCPU), uploaded into the pass's target, or,
   * where the CPU swept every light of an irradiance texture, written into
   * its texels there too (mmv::WriteIrradianceTexels); 2, automatic
   * (default): on the GPU except on a CPU rasterizer, where the parallel
   * rays share their weights across a row (the light kit's five lights on a
   * 237 x 237 x 119 grid: 0.22 s with the write against about 0.7 s of
   * passes; docs/performance.md, "Shadow rays on the CPU"). The CPU needs its own
   * classes (Classification on the CPU, the default there) and nothing cut;
   * point and spot lights, and lights under full rays, stay on the GPU.
   * Both give the same transmittance to 1e-5. (A WorkPlace.)
   */
  vtkSetClampMacro(ShadowRaysPlace, int, OnGPU, OnGPUUnlessSoftware);
  vtkGetMacro(ShadowRaysPlace, int);
  /// The lights whose shadow rays the last update swept on the CPU.
  vtkGetMacro(NumberOfLightsSweptOnCPU, int);
  /// The irradiance textures the last update wrote on the CPU: those whose
  /// lights it all swept there, without multiple scattering or with it
  /// diffused there too (DiffusionPlace), and without other volumes'
  /// shadows (mmv::WriteIrradianceTexels, the final write's arithmetic in
  /// place of its passes).
  vtkGetMacro(NumberOfTexturesWrittenOnCPU, int);

  /**
   * Keeps the float scratch textures the passes work in between updates
   * (default on): an update then allocates nothing, which on a software
   * rasterizer is a large share of a light update (docs/performance.md,
   * "Irradiance update stages"). The price is holding them: 16 bytes a voxel,
   * up to three times that with multiple scattering (GetScratchMemoryBytes;
   * the diffusion grids' scratch holds as many channels as the lights it
   * diffuses need; a diffusion on the CPU holds its buffers in main memory
   * instead of the diffusion grids' textures; the fine textures are made
   * when a pass first needs them, and an update that writes every
   * irradiance texture on the CPU needs none).
   * Off: released after every update.
   */
  vtkSetMacro(KeepScratch, bool);
  vtkGetMacro(KeepScratch, bool);
  vtkBooleanMacro(KeepScratch, bool);
  /// Memory the scratch holds now, in bytes: its textures, and the buffers
  /// of a diffusion or shadow rays on the CPU.
  vtkIdType GetScratchMemoryBytes() const;

  /// Empty voxels cost nothing (default on): the shadow draws cover only
  /// the 4^3 bricks that may hold non-empty voxels (mmv::VoxelOccupancy),
  /// and piecewise rays still compute the slices a later chunk reads. Off
  /// draws and computes every voxel, to measure what the skipping saves.
  vtkSetMacro(SkipEmptyVoxels, bool);
  vtkGetMacro(SkipEmptyVoxels, bool);

  /**
   * How lights are estimated (mmv::ShadowEstimation): 1, piecewise shadow
   * rays swept along the light (default; vtkShadowSweep.h; around a point or
   * spot light inside the grid, in six pyramids), or 0, full shadow rays.
   * Piecewise rays need glTextureBarrier (OpenGL 4.5); without it the estimator
   * warns once and takes full rays.
   */
  vtkSetClampMacro(ShadowEstimation, int, 0, 1);
  vtkGetMacro(ShadowEstimation, int);

  /// Slices a piecewise shadow ray spans at most (default
  /// mmv::DefaultPiecewiseShadowSlices).
  vtkSetClampMacro(PiecewiseShadowSlices, int, 1, 4096);
  vtkGetMacro(PiecewiseShadowSlices, int);

  /**
   * Degrees a light may move and keep its irradiance (directional: its
   * direction; point and spot: the angle its move subtends at the grid's
   * centre, and the spot axis). Default 0: every move recomputes (up to
   * mmv::LightRoundingRadians, the camera's rounding). Always compared with
   * the placement the irradiance was computed for, so moves do not add up.
   * Clamped to [0, mmv::MaxLightDirectionToleranceDegrees].
   */
  vtkSetClampMacro(LightDirectionTolerance, double, 0.0, mmv::MaxLightDirectionToleranceDegrees);
  vtkGetMacro(LightDirectionTolerance, double);

#ifndef __VTK_WRAP__
  /**
   * Which lights the next Render() recomputes besides those its own inputs
   * recompute (all of them when the volume, tables, settings or textures
   * changed): vtkIrradianceUpdatePlan::GetMovedLights() of a plan made from
   * the placements GetComputedLights() holds, so the estimator does not compare
   * the lights again. Without marks (the default; they hold for one
   * Render()) the estimator marks them with vtkIrradianceUpdatePlan::MarkLights.
   */
  void SetLightsToUpdate(const std::vector<bool>& marks);
#endif

#ifndef __VTK_WRAP__
  /**
   * The transmittance toward each light through the other volumes of the
   * scene (vtkMultiMaterialSceneShadows): one RGBA texture per irradiance
   * texture (light 4i + c in channel c of texture i), linearly filtered,
   * spanning the irradiance grid's voxel centres. The final write multiplies
   * the irradiance by it, so the ray cast reads nothing more. Empty (the
   * default): no texture read, as for a volume alone. A new `version`
   * recomputes every light.
   */
  void SetSceneTransmittance(const std::vector<vtkTextureObject*>& textures, unsigned long version);
#endif

  /// The light placements the irradiance textures hold (empty before the
  /// first Render() or after a failed one).
  const std::vector<mmv::LightSource>& GetComputedLights() const;

#ifndef __VTK_WRAP__
  /// Shows `irradiance` and `tints` (a kept step's copies of this
  /// estimator's textures, of their sizes: vtkIrradianceStepCache) in place
  /// of its own until the next Render() or release, which recomputes every
  /// light into its own textures: showing a kept step copies nothing.
  void ShowKeptTextures(
    const std::vector<vtkTextureObject*>& irradiance, const std::vector<vtkTextureObject*>& tints);
  /// Whether ShowKeptTextures' textures are shown.
  bool ShowsKeptTextures() const;
#endif

  /**
   * The tint table of a non-white transmission colour
   * (vtkPreIntegrationTable::GetShadowTintTable, 4 floats per entry, the
   * shadow table's size and range; call after SetInputs), or nullptr for
   * grey materials (the default): no tint textures, no tint passes. A change
   * recomputes every light. With a table, each light also gets its tint K
   * (vtkMultiMaterialParameters.h) in an RGBA16F texture on the tint grid
   * (mmv::TintDimension of the irradiance grid), by full shadow rays of the
   * selective extinction (Shaders/mmvIrradianceTintFS.glsl), not diffused.
   */
  void SetTintTable(const float* tintTable);
  bool IsTinted() const;
  /// Light k's tint texture shown (nullptr when grey or before Render()).
  vtkTextureObject* GetTintTexture(int light) const;
  void GetTintDimensions(int dims[3]) const;
  /// Light k's tint, 3 floats (r, g, b) per tint voxel, x fastest.
  bool ReadBackTint(vtkOpenGLRenderWindow* context, int light, std::vector<float>& rgb);

  /**
   * The voxels the caller will read, (i0, i1, j0, j1, k0, k1) inclusive in
   * grid index (clamped to the grid): the passes estimate only what they
   * depend on (the fill pass's neighbours, the diffusion's reach, the
   * slices a directional light's sweep reads on the way), so they equal
   * the whole grid's there: bit for bit with the default exponential
   * diffusion, within the sweeps' tolerance with backward Euler. Voxels
   * outside hold no meaningful value. A change recomputes every light.
   * ResetRegion: the whole grid (the default).
   */
  void SetRegion(const int bounds[6]);
  void ResetRegion();
  void GetRegion(int bounds[6]) const;

  /// Runs the passes. Needs the context current. False (with an error) if
  /// inputs are missing or the context lacks what the passes need.
  bool Render(vtkOpenGLRenderWindow* context);

#ifndef __VTK_WRAP__
  /**
   * Called during Render() with the fraction of its work done (0 < x <= 1,
   * increasing): after each light's shadows and each texture's diffusion,
   * counted per light, once the GPU finished them (glFinish). A callback
   * that leaves another context current (a GUI repainting) gets Render()'s
   * made current again. Empty (the default): no calls and no extra glFinish.
   */
  void SetProgressCallback(std::function<void(double)> callback);
#endif

  /// RGBA16 3D texture holding lights 4i..4i+3 shown (nullptr before
  /// Render()): the estimator's own or a kept step's (ShowKeptTextures).
  vtkTextureObject* GetIrradianceTexture(int i) const;
  /// The pre-filtered scalars (R32F, linear) and the shadow-opacity table the
  /// shadow rays march, for other marches through the same extinction (the
  /// reflections' visibility); nullptr before Render().
  vtkTextureObject* GetScalarTexture() const;
  vtkTextureObject* GetShadowTableTexture() const;
  int GetNumberOfIrradianceTextures() const;

  /// Light k's irradiance, GetNumberOfVoxels() floats, x fastest.
  bool ReadBack(vtkOpenGLRenderWindow* context, int light, std::vector<float>& values);
#ifndef __VTK_WRAP__
  /// Lights first to last - 1, one vector each, reading each texture once
  /// (vtkIrradianceResolutionProbe compares whole fields).
  bool ReadBackLights(
    vtkOpenGLRenderWindow* context, int first, int last, std::vector<std::vector<float>>& values);
#endif

  ///@{
  /// What the last Render() did.
  vtkGetMacro(NumberOfComputedVoxels, vtkIdType);
  vtkGetMacro(DiffusionPasses, int); // Jacobi sweeps drawn
  vtkGetMacro(NumberOfUpdatedLights, int);
  /// Voxels its shadow draws covered, summed over the lights (a light's
  /// grid, or what its region depends on, within the occupied bricks).
  vtkGetMacro(LastEstimatedVoxels, vtkIdType);
  vtkGetMacro(LastRenderSeconds, double);
  /// Its uploads and allocations, its shadow rays, its diffusion and its
  /// final write (glFinish after each).
  vtkGetMacro(LastSetupSeconds, double);
  vtkGetMacro(LastEstimationSeconds, double);
  vtkGetMacro(LastDiffusionSeconds, double);
  vtkGetMacro(LastWriteSeconds, double);
  ///@}

  ///@{
  /// The diffusion grid of the current inputs and its solve; with a light
  /// grid stride over 1, the grid that lights of that stride diffuse on
  /// (mmv::LightGridDiffusionSettings).
  void GetDiffusionGridDimensions(int dims[3], int lightGridStride = 1) const;
  int GetDiffusionSubSteps() const;
  int GetDiffusionSweepsPerStep() const;
  double GetDiffusionLength() const; // in data voxels
  ///@}

  /// How often the pre-filtered volume and tables went to the GPU: only when
  /// they change, not when only the lights move.
  vtkIdType GetNumberOfVolumeUploads() const;
  /// How often the voxels were classified on the GPU: not for an opacity
  /// edit that keeps which table entries are positive and the scattering.
  vtkIdType GetNumberOfClassifications() const;

  ///@{
  /**
   * The classification of the irradiance voxels (s, -1 where empty; x
   * fastest): as the GPU computed it at the last upload
   * (Shaders/mmvClassifyFS.glsl), and as the CPU computes it from the same
   * inputs. The CPU classifies during an update only where the diffusion
   * plan needs the strengths (multiple scattering on, a positive diffusion
   * time and some s > 0 in the scattering table): GetClassifiedOnCPU().
   */
  bool ReadBackClasses(vtkOpenGLRenderWindow* context, std::vector<float>& classes);
  void ClassifyOnCPU(std::vector<float>& classes) const;
  bool GetClassifiedOnCPU() const;
  ///@}

  ///@{
  /**
   * The strided light grid's needed points (255 where the interpolation to a
   * non-empty voxel reads the point, else 0; x fastest) and the light grid's
   * dimensions: as the GPU marked them at the last Render() with a strided
   * light (Shaders/mmvLightGridNeededFS.glsl; false without one), and as the
   * CPU marks them from its classification, for the largest light's stride.
   */
  bool ReadBackLightGridNeeded(
    vtkOpenGLRenderWindow* context, std::vector<unsigned char>& needed, int dims[3]);
  void LightGridNeededOnCPU(std::vector<unsigned char>& needed, int dims[3]) const;
  ///@}

  /// GPU memory held by the irradiance textures, in bytes.
  vtkIdType GetTextureMemoryBytes() const;

  void ReleaseGraphicsResources(vtkWindow* window);

protected:
  vtkIrradianceEstimator();
  ~vtkIrradianceEstimator() override;

  // The settings it shares with the mapper start at the mapper's defaults.
  bool MultipleScattering = mmv::DefaultIlluminationSettings.MultipleScattering;
  double DiffusionTime = 1.0;
  bool ExponentialDiffusion = mmv::DefaultIlluminationSettings.ExponentialDiffusion;
  bool LayeredRendering = true;
  int ComputeShaders = ComputeUnlessSoftware;
  bool ComputeShadersUsed = false;
  int Classification = OnGPUUnlessSoftware;
  bool ClassesCopied = false;
  int DiffusionPlace = OnGPUUnlessSoftware;
  bool DiffusedOnCPU = false;
  int ShadowRaysPlace = OnGPUUnlessSoftware;
  int NumberOfLightsSweptOnCPU = 0;
  int NumberOfTexturesWrittenOnCPU = 0;
  bool SkipEmptyVoxels = true;
  bool KeepScratch = true;
  int ShadowEstimation = mmv::DefaultIlluminationSettings.ShadowEstimation;
  int PiecewiseShadowSlices = mmv::DefaultIlluminationSettings.PiecewiseShadowSlices;
  double LightDirectionTolerance = mmv::DefaultIlluminationSettings.LightDirectionTolerance;
  vtkIdType NumberOfComputedVoxels = 0;
  int DiffusionPasses = 0;
  int NumberOfUpdatedLights = 0;
  vtkIdType LastEstimatedVoxels = 0;
  double LastRenderSeconds = 0.0;
  double LastEstimationSeconds = 0.0;
  double LastDiffusionSeconds = 0.0;
  double LastSetupSeconds = 0.0;
  double LastWriteSeconds = 0.0;

private:
  vtkIrradianceEstimator(const vtkIrradianceEstimator&) = delete;
  void operator=(const vtkIrradianceEstimator&) = delete;

  // The steps of Render().
  bool CanRender(vtkOpenGLRenderWindow* context);
  int PrepareSettings(bool& diffusion);
  bool UpdateGroup(vtkOpenGLRenderWindow* context, int group, const std::vector<bool>& updated,
    int estimation, bool diffusion);
  // The updated lights of one irradiance texture (vtkIrradianceEstimatorInternals.h).
  struct GroupLights;
  bool PassesOfGroup(vtkOpenGLRenderWindow* context, int group, const GroupLights& lights,
    bool diffusion, const std::function<double()>& elapsed);
  bool DiffuseGroup(vtkOpenGLRenderWindow* context, const GroupLights& lights,
    const std::function<double()>& elapsed);
  // Finishes the GPU's work, adds `units` to what is done and calls the
  // progress callback (nothing without one).
  void ReportProgress(vtkOpenGLRenderWindow* context, double units);
  std::function<void(double)> Progress;
  double ProgressDone = 0.0;
  double ProgressTotal = 0.0;

  class vtkInternals;
  vtkInternals* Internals;
};

#endif
