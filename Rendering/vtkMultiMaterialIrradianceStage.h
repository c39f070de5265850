/**
 * @class   vtkMultiMaterialIrradianceStage
 * @brief   The irradiance step of vtkMultiMaterialVolumeMapper's frame (the
 *          paper's Algorithm 1).
 *
 * Chooses the irradiance grid (screen, budget, user scale or the global grid
 * of a volume in pieces), makes the frame's vtkIrradianceUpdatePlan (what
 * changed since the held irradiance, decided once), keeps the irradiance
 * when the plan allows it (current, or only the lights moved while
 * interacting: InteractiveIrradiance), and otherwise has
 * vtkIrradianceEstimator recompute the lights the plan marks, with VTK
 * progress events.
 * Settings in, report out: it reads one mmv::IrradianceStageInputs (the
 * mapper's settings among them) and says what it did in an
 * mmv::IrradianceStageReport, from which the mapper keeps its counters and
 * warns. Not a vtkObject: plain state owned by the mapper.
 */
#ifndef vtkMultiMaterialIrradianceStage_h
#define vtkMultiMaterialIrradianceStage_h

#include "vtkIrradianceEstimator.h"       // vtkNew
#include "vtkIrradianceGrid.h"            // IrradianceResolution
#include "vtkIrradianceInputCache.h"      // vtkNew
#include "vtkIrradianceResolutionProbe.h" // vtkNew
#include "vtkIrradianceStepCache.h"       // member
#include "vtkIrradianceUpdatePlan.h"      // the update's decisions
#include "vtkMultiMaterialCutaway.h"      // Cutaway
#include "vtkMultiMaterialLights.h"       // ShadingLight
#include "vtkMultiMaterialSettings.h"     // IlluminationSettings
#include "vtkMultiMaterialVolumeModule.h" // export macro
#include "vtkNew.h"
#include "vtkPreIntegrationTable.h" // vtkNew

#include <functional> // the kept steps' key, made on demand
#include <string>
#include <vector>

class vtkAlgorithm;
class vtkDataArray;
class vtkGlobalPrefilteredVolume;
class vtkImageData;
class vtkMaterialTransferFunction;
class vtkMultiMaterialSceneShadows;
class vtkOpenGLRenderWindow;
class vtkRenderer;
class vtkVolume;
class vtkVolumeProperty;
class vtkWindow;

namespace mmv
{
/// Wall seconds of each stage of the last irradiance update (the probe and
/// the pre-filter count only when they ran; the estimator's own stages end with
/// glFinish).
struct VTKMULTIMATERIALVOLUME_EXPORT IrradianceStageSeconds
{
  double Probe = 0.0;
  double Prefilter = 0.0;
  double Tables = 0.0;    // the shadow rays' pre-integrated table
  double Inputs = 0.0;    // the estimator's inputs: classes on the CPU, the diffusion plan
  double Shadows = 0.0;   // the transmittance toward every updated light
  double Diffusion = 0.0; // multiple scattering
  double Setup = 0.0;     // the estimator's uploads and texture allocations
  double Write = 0.0;     // the final write into the irradiance textures
  double Keep = 0.0;      // the copy kept for a series' later loops (animation caching)
  double Pass = 0.0;      // the whole GPU pass (shadows, diffusion, final write)
  double Total = 0.0;     // the whole update
  /// "probe 0.000 s, prefilter 0.012 s, ...": the information property's text.
  std::string Report() const;
};

/// What one update reads.
struct IrradianceStageInputs
{
  vtkRenderer* Renderer = nullptr;
  vtkVolume* Volume = nullptr;
  vtkImageData* Image = nullptr; // the input, or one piece of Global
  vtkDataArray* Scalars = nullptr;
  const double* PieceRange = nullptr;           // the input's finite range
  vtkGlobalPrefilteredVolume* Global = nullptr; // the whole volume of a piece; null: none
  vtkMaterialTransferFunction* Materials = nullptr;
  /// The opacity the shadows read (component 0): the volume's, or several
  /// fields' combined extinction (vtkMultiMaterialFields.h).
  vtkVolumeProperty* Property = nullptr;
  const std::vector<ShadingLight>* Lights = nullptr;
  Cutaway Cut; // cropping and clipping, in object space
  /// The other volumes of the renderer that shadow this one, gathered for
  /// this frame (its key joins the volume key); null: none.
  vtkMultiMaterialSceneShadows* Scene = nullptr;
  IlluminationSettings Settings;
  bool Interactive = false; // an interactive render (allocated time below 1 s)
  /// Receives VTK's progress events and names the errors (the mapper).
  vtkAlgorithm* Reporter = nullptr;
};

/// What one update did.
struct IrradianceStageReport
{
  int UpdatedLights = 0;   // lights whose irradiance was recomputed
  int DiffusionPasses = 0; // of that update
  double Seconds = 0.0;    // the estimator's time, when lights were recomputed
  bool Deferred = false;   // an interactive frame kept a stale irradiance
  bool CacheHit = false;   // an earlier input's kept irradiance is shown
  bool GridSet = false;    // Dimensions hold the grid now in use
  int Dimensions[3] = { 0, 0, 0 };
  std::vector<std::string> Warnings;
};
}

class VTKMULTIMATERIALVOLUME_EXPORT vtkMultiMaterialIrradianceStage
{
public:
  vtkMultiMaterialIrradianceStage();
  ~vtkMultiMaterialIrradianceStage();

  /// Brings the irradiance of the inputs' lights up to date for their image,
  /// or for the whole volume when the image is a piece of one. False: the
  /// GPU could not compute it (reported).
  bool Update(const mmv::IrradianceStageInputs& inputs, mmv::IrradianceStageReport& report);

  vtkIrradianceEstimator* GetEstimator() { return this->Estimator; }
  vtkIrradianceResolutionProbe* GetProbe() { return this->Probe; }

  /// The irradiance grid of the pre-filtered data.
  const mmv::IrradianceGrid& GetGrid() const { return this->Cache->GetGrid(); }

  /// The grid in use and why it was chosen.
  const std::string& GetResolutionReason() const { return this->ResolutionReason; }

  /// The stages of the last update that recomputed the irradiance.
  const mmv::IrradianceStageSeconds& GetStageSeconds() const { return this->Stages; }

  /// GPU memory the irradiance of earlier inputs holds (IrradianceCacheMB).
  size_t GetStepCacheBytes() const { return this->Steps.GetBytes(); }

  void ReleaseGraphicsResources(vtkWindow* window);

private:
  vtkMultiMaterialIrradianceStage(const vtkMultiMaterialIrradianceStage&) = delete;
  void operator=(const vtkMultiMaterialIrradianceStage&) = delete;

  mmv::IrradianceResolution ChooseGrid(vtkRenderer* ren, vtkVolume* vol, vtkImageData* image,
    vtkDataArray* scalars, const double range[2],
    const vtkIrradianceInputCache::VolumeKey& volumeKey, const mmv::Cutaway& cutaway);
  /// Coarsens an automatic `resolution` to the error probe's scale.
  void ApplyProbe(vtkRenderer* ren, vtkImageData* image, vtkDataArray* scalars,
    const double range[2], const vtkIrradianceInputCache::VolumeKey& volumeKey,
    const mmv::Cutaway& cutaway, double bound, int maxAxis, mmv::IrradianceResolution& resolution);
  /// Keeps the held irradiance when `plan` (to `now`) allows it: current,
  /// kept while interacting, nothing visible, or a kept step shown.
  /// False: the caller recomputes what the plan marks.
  bool KeepsHeld(const vtkIrradianceUpdatePlan& plan, const vtkIrradianceUpdatePlan::Inputs& now,
    vtkOpenGLRenderWindow* window, const double range[2], size_t stepBudget,
    const std::function<vtkIrradianceStepCache::Key()>& stepKey);
  /// The other volumes' transmittance on the irradiance grid toward
  /// `sources`, handed to the estimator (nothing to hand when alone).
  void UpdateSceneShadows(
    vtkOpenGLRenderWindow* window, const std::vector<mmv::LightSource>& sources);
  /// Has `pass` report the mapper's progress from `from` to `to` (nothing
  /// while no one observes it).
  void ReportProgressOf(vtkIrradianceEstimator* pass, double from, double to);
  /// The mapper's progress, with VTK's OpenGL state kept across the report.
  void ReportProgress(double progress);
  /// Estimates `sources` on `grid` into `pass` (the frame's pass, or the
  /// probe's without scattering).
  bool ComputeOn(vtkIrradianceEstimator* pass, vtkOpenGLRenderWindow* window, const double range[2],
    const mmv::Cutaway& cutaway, const mmv::IrradianceGrid& grid,
    const std::vector<float>& prefiltered, unsigned long version,
    const std::vector<mmv::LightSource>& sources, bool scattering);
  /// The last ComputeOn()'s stages: its tables, inputs and the estimator's own.
  void AddEstimatorStages(mmv::IrradianceStageSeconds& stages) const;
  void Record(const mmv::IrradianceResolution& resolution);

  // What the irradiance volume was computed from, and the estimator's inputs
  // kept between frames (pre-filtered data, material samples).
  vtkNew<vtkIrradianceInputCache> Cache;
  vtkNew<vtkPreIntegrationTable> ShadowTable;
  vtkNew<vtkIrradianceEstimator> Estimator;
  vtkNew<vtkIrradianceResolutionProbe> Probe;
  vtkIrradianceStepCache Steps;
  // The light placements the estimator's textures hold: its own record after an
  // update, the copy's after a restore (the estimator's record is then stale).
  std::vector<mmv::LightSource> HeldLights;
  // Whether Steps holds a copy of what the estimator's textures hold now.
  bool HeldKept = false;
  std::string ResolutionReason;
  mmv::IrradianceStageSeconds Stages;
  double TablesSeconds = 0.0;
  double InputsSeconds = 0.0;

  // The current Update()'s arguments.
  const mmv::IrradianceStageInputs* In = nullptr;
  mmv::IrradianceStageReport* Out = nullptr;
  vtkOpenGLRenderWindow* Context = nullptr;
};

#endif
