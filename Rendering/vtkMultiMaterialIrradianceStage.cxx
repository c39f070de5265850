#include "vtkMultiMaterialIrradianceStage.h"

#include "vtkAlgorithm.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkGlobalPrefilteredVolume.h"
#include "vtkImageData.h"
#include "vtkIrradianceRegion.h"
#include "vtkIrradianceUpdatePlan.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMatrix4x4.h"
#include "vtkMultiMaterialLightTolerance.h"
#include "vtkMultiMaterialSceneShadows.h"
#include "vtkMultiMaterialVolumeGeometry.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkPiecewiseFunction.h"
#include "vtkRenderer.h"
#include "vtkTextureObject.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace
{
/// What the whole irradiance volume depends on besides the lights and the grid.
vtkIrradianceInputCache::VolumeKey MakeVolumeKey(const mmv::IlluminationSettings& settings,
  vtkVolumeProperty* property, vtkMTimeType dataTime, int materialVersion, int lights,
  const double range[2], const mmv::Cutaway& cutaway)
{
  vtkIrradianceInputCache::VolumeKey key;
  key.DataTime = dataTime;
  key.OpacityTime = property->GetScalarOpacity(0)->GetMTime();
  key.MaterialVersion = materialVersion;
  key.UnitDistance = property->GetScalarOpacityUnitDistance(0);
  key.Range[0] = range[0];
  key.Range[1] = range[1];
  key.MultipleScattering = settings.MultipleScattering;
  key.TableSize = settings.PreIntegrationTableSize;
  key.NumberOfLights = lights;
  key.ShadowEstimation = settings.ShadowEstimation;
  key.PiecewiseShadowSlices = settings.PiecewiseShadowSlices;
  key.ExponentialDiffusion = settings.ExponentialDiffusion;
  key.Cut = cutaway.Key();
  return key;
}

/// The irradiance voxels `image` reads: around the piece in the global
/// grid, or all of a grid of `dims`.
mmv::IndexBox ReadRegion(
  vtkImageData* image, vtkGlobalPrefilteredVolume* global, bool pieceOnly, const int dims[3])
{
  if (!global || !pieceOnly)
  {
    return mmv::IndexBox::Whole(dims);
  }
  int pieceDims[3];
  image->GetDimensions(pieceDims);
  const glm::dvec3 offset = global->PieceOffset(image);
  const double o[3] = { offset[0], offset[1], offset[2] };
  return mmv::PieceIrradianceBox(global->GetGrid(), o, pieceDims);
}

using Clock = std::chrono::steady_clock;
double SecondsSince(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// The scalar opacity at `n` points over `range` (> 0 marks a voxel
/// non-empty for the estimator; the probe's weights).
std::vector<float> SampleOpacityTable(vtkPiecewiseFunction* opacity, const double range[2], int n)
{
  std::vector<float> table(n);
  for (int i = 0; i < n; ++i)
  {
    const double value = range[0] + (range[1] - range[0]) * i / (n - 1);
    table[i] = static_cast<float>(opacity->GetValue(value));
  }
  return table;
}
}

vtkMultiMaterialIrradianceStage::vtkMultiMaterialIrradianceStage() = default;
vtkMultiMaterialIrradianceStage::~vtkMultiMaterialIrradianceStage() = default;

void vtkMultiMaterialIrradianceStage::ReleaseGraphicsResources(vtkWindow* window)
{
  // The estimator first: it stops showing a kept step, so the step cache
  // releases every copy here.
  this->Estimator->ReleaseGraphicsResources(window);
  this->Steps.ReleaseGraphicsResources(window);
  this->HeldKept = false;
  this->Probe->ReleaseGraphicsResources(window);
  this->Cache->Invalidate();
}

mmv::IrradianceResolution vtkMultiMaterialIrradianceStage::ChooseGrid(vtkRenderer* ren,
  vtkVolume* vol, vtkImageData* image, vtkDataArray* scalars, const double range[2],
  const vtkIrradianceInputCache::VolumeKey& volumeKey, const mmv::Cutaway& cutaway)
{
  int dataDims[3];
  image->GetDimensions(dataDims);
  // The screen only matters when the resolution is automatic.
  std::string scaleProblem;
  const double scale = mmv::ValidIrradianceScale(this->In->Settings.IrradianceScale, &scaleProblem);
  if (!scaleProblem.empty())
  {
    this->Out->Warnings.push_back(scaleProblem);
  }
  const double pixelsPerVoxel = scale > 0.0 ? 0.0 : mmv::ProjectedPixelsPerVoxel(ren, vol, image);
  mmv::IrradianceResolution resolution;
  if (vtkGlobalPrefilteredVolume* global = this->In->Global)
  {
    global->GetIrradianceDimensions(resolution.Dimensions);
    resolution.Reason = "the global grid of a volume in pieces";
    return resolution;
  }
  const int lights = static_cast<int>(this->In->Lights->size());
  // A non-white transmission colour adds each light's tint to the budget.
  const bool tinted = this->In->Materials && this->In->Materials->HasChromaticTransmission();
  resolution = mmv::ChooseIrradianceResolution(
    dataDims, lights, this->In->Settings.IrradianceMemoryMB, scale, pixelsPerVoxel, tinted);
  std::string boundProblem;
  const double bound =
    mmv::ValidIrradianceErrorBound(this->In->Settings.IrradianceErrorBound, &boundProblem);
  if (!boundProblem.empty())
  {
    this->Out->Warnings.push_back(boundProblem);
  }
  // The irradiance is one 3D texture: no axis longer than the largest one
  // (a long volume is drawn in bricks, its irradiance spans it whole).
  const int largest = vtkTextureObject::GetMaximumTextureSize3D(
    vtkOpenGLRenderWindow::SafeDownCast(ren->GetRenderWindow()));
  if (scale <= 0.0 && bound > 0.0)
  {
    this->ApplyProbe(ren, image, scalars, range, volumeKey, cutaway, bound, largest, resolution);
  }
  for (int a = 0; a < 3 && largest > 1; ++a)
  {
    resolution.Dimensions[a] = std::min(resolution.Dimensions[a], largest);
  }
  return resolution;
}

void vtkMultiMaterialIrradianceStage::ApplyProbe(vtkRenderer* ren, vtkImageData* image,
  vtkDataArray* scalars, const double range[2], const vtkIrradianceInputCache::VolumeKey& volumeKey,
  const mmv::Cutaway& cutaway, double bound, int maxAxis, mmv::IrradianceResolution& resolution)
{
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(ren->GetRenderWindow());
  vtkVolumeProperty* property = this->In->Property;
  const int n = this->In->Settings.PreIntegrationTableSize;
  // Sampled only when the volume key changed, over the opacity function's
  // own range (vtkIrradianceProbeRule.h).
  const auto signature = [&]()
  {
    vtkPiecewiseFunction* opacity = property->GetScalarOpacity(0);
    double own[2];
    opacity->GetRange(own);
    std::vector<float> attenuation(n, 1.0f);
    for (int i = 0; this->In->Materials && i < n; ++i)
    {
      attenuation[i] = static_cast<float>(this->In->Materials->EvaluateParameter(
        own[0] + (own[1] - own[0]) * i / (n - 1), mmv::Attenuation));
    }
    return mmv::MakeProbeSignature(SampleOpacityTable(opacity, own, n), attenuation, own,
      property->GetScalarOpacityUnitDistance(0));
  };
  // A measurement takes seconds on a software GPU: it reports progress, as
  // the update that follows does.
  const double budget = this->In->Settings.IrradianceMemoryMB;
  const bool measures = !this->Probe->Holds(volumeKey, image, budget, bound, signature);
  // The weights only matter to a measurement: no table on the per-frame path.
  std::vector<float> opacityTable;
  if (measures)
  {
    opacityTable = SampleOpacityTable(property->GetScalarOpacity(0), range, n);
    this->In->Reporter->SetProgressText("Irradiance resolution probe");
    this->ReportProgress(0.0);
  }
  int estimates = 0;
  const double probed = this->Probe->Choose(window, volumeKey, image, scalars, range, budget,
    maxAxis, bound, opacityTable, signature,
    [&](vtkIrradianceEstimator* pass, const mmv::IrradianceGrid& grid,
      const std::vector<float>& prefiltered, unsigned long version,
      const std::vector<mmv::LightSource>& lights)
    {
      // Each grid the probe lights has about 2^-1.5 the voxels of the one
      // before: after n of them, about 0.35^n of its work is left.
      const double shrink = std::exp2(-1.5);
      const double from = 1.0 - std::pow(shrink, estimates);
      const double to = 1.0 - std::pow(shrink, ++estimates);
      this->ReportProgressOf(pass, from, to);
      const bool ok =
        this->ComputeOn(pass, window, range, cutaway, grid, prefiltered, version, lights, false);
      pass->SetProgressCallback(nullptr);
      return ok;
    });
  if (measures && this->In->Reporter->GetProgress() < 1.0)
  {
    this->ReportProgress(1.0);
  }
  if (measures)
  {
    this->In->Reporter->SetProgressText(nullptr);
    vtkDebugWithObjectMacro(this->In->Reporter,
      << this->Probe->GetSummary() << " in " << this->Probe->GetLastProbeSeconds() << " s");
  }
  if (probed < resolution.Scale)
  {
    int dataDims[3];
    image->GetDimensions(dataDims);
    resolution.Scale = probed;
    mmv::ComputeIrradianceDimensions(dataDims, static_cast<int>(this->In->Lights->size()),
      this->In->Settings.IrradianceMemoryMB, probed, resolution.Dimensions,
      this->In->Materials && this->In->Materials->HasChromaticTransmission());
    resolution.Reason = this->Probe->GetSummary();
  }
}

bool vtkMultiMaterialIrradianceStage::Update(
  const mmv::IrradianceStageInputs& inputs, mmv::IrradianceStageReport& report)
{
  this->In = &inputs;
  this->Out = &report;
  report = mmv::IrradianceStageReport();
  vtkRenderer* ren = inputs.Renderer;
  vtkVolume* vol = inputs.Volume;
  vtkImageData* image = inputs.Image;
  vtkDataArray* scalars = inputs.Scalars;
  vtkGlobalPrefilteredVolume* global = inputs.Global;
  this->Context = vtkOpenGLRenderWindow::SafeDownCast(ren->GetRenderWindow());
  const Clock::time_point start = Clock::now();
  const int probesBefore = this->Probe->GetNumberOfProbes();
  // A piece of a larger volume is lit from the whole volume's pre-filtered
  // data, on its grid and over its range.
  const double* range = global ? global->GetScalarRange() : inputs.PieceRange;
  // Kept irradiance of earlier inputs (a budget lowered since goes now).
  // Not for a piece of a global volume: its data is the global copy.
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(ren->GetRenderWindow());
  const size_t stepBudget =
    global ? 0 : static_cast<size_t>(this->In->Settings.IrradianceCacheMB * 1048576.0);
  this->Steps.Trim(stepBudget);

  this->Cache->SampleMaterials(
    this->In->Materials, range, this->In->Settings.PreIntegrationTableSize);
  const vtkMTimeType dataTime =
    global ? global->GetMTime() : std::max(image->GetMTime(), scalars->GetMTime());
  // What cropping and clipping remove casts no shadow: part of the key, so a
  // moved crop box or plane updates the irradiance.
  const mmv::Cutaway& cutaway = inputs.Cut;
  vtkIrradianceInputCache::VolumeKey volumeKey =
    MakeVolumeKey(inputs.Settings, inputs.Property, dataTime, this->Cache->GetMaterialVersion(),
      static_cast<int>(this->In->Lights->size()), range, cutaway);
  const mmv::IrradianceResolution resolution =
    this->ChooseGrid(ren, vol, image, scalars, range, volumeKey, cutaway);
  const int* dims = resolution.Dimensions;
  // A piece of a volume in pieces: only what its ray cast reads.
  const mmv::IndexBox region =
    ReadRegion(image, global, this->In->Settings.PieceIrradianceOnly, dims);
  std::copy(region.Bounds, region.Bounds + 6, volumeKey.Region);
  // The other volumes' shadows: after the probe, which measures this volume's own.
  volumeKey.Occluders = inputs.Scene ? inputs.Scene->GetKey() : std::vector<double>();
  const std::vector<mmv::LightSource> sources =
    mmv::IrradianceLightSources(*inputs.Lights, dims, this->In->Settings.DimLightCoarsening);
  // What changed since the held irradiance, and so what this update
  // recomputes: decided here, once.
  vtkIrradianceUpdatePlan::Inputs now;
  now.Volume = volumeKey;
  std::copy(dims, dims + 3, now.Dimensions);
  now.Lights = sources;
  const vtkIrradianceUpdatePlan plan =
    this->Cache->Plan(now, mmv::LightToleranceRadians(this->In->Settings.LightDirectionTolerance));
  // The key of the kept steps, made only where they are looked up or stored.
  const auto stepKey = [&]()
  {
    return vtkIrradianceStepCache::MakeKey(volumeKey,
      this->In->Materials ? this->In->Materials->GetMTime() : 0, image, scalars, sources, dims);
  };
  if (this->KeepsHeld(plan, now, window, range, stepBudget, stepKey))
  {
    return true;
  }
  // A real update (seconds on a software GPU): VTK progress events mark its
  // start, its lights and its end.
  this->In->Reporter->SetProgressText("Irradiance volume");
  this->ReportProgress(0.0);

  // Pre-filtered data: only when the data or the grid changed.
  const Clock::time_point prefilterStart = Clock::now();
  const bool nonFinite =
    this->Cache->UpdatePrefiltered(image, scalars, global, dims, dataTime, range);
  mmv::IrradianceStageSeconds stages;
  stages.Prefilter = SecondsSince(prefilterStart);
  if (this->Probe->GetNumberOfProbes() != probesBefore)
  {
    stages.Probe = this->Probe->GetLastProbeSeconds();
  }
  if (nonFinite)
  {
    this->Out->Warnings.push_back(mmv::NonFiniteScalarsMessage);
  }
  this->Estimator->SetRegion(region.Bounds);
  this->UpdateSceneShadows(window, sources);
  // The plan compared the lights with what the textures hold: the estimator
  // recomputes those it marks (and every light where its inputs changed).
  this->Estimator->SetLightsToUpdate(plan.GetMovedLights());
  this->ReportProgressOf(this->Estimator, 0.0, 1.0);
  const bool estimated =
    this->ComputeOn(this->Estimator, vtkOpenGLRenderWindow::SafeDownCast(ren->GetRenderWindow()),
      range, cutaway, this->Cache->GetGrid(), this->Cache->GetPrefiltered(),
      this->Cache->GetPrefilteredVersion(), sources, this->In->Settings.MultipleScattering);
  this->Estimator->SetProgressCallback(nullptr);
  if (!estimated)
  {
    this->Cache->Invalidate();
    this->In->Reporter->SetProgressText(nullptr);
    return false;
  }
  this->HeldLights = this->Estimator->GetComputedLights();
  this->Cache->Store(volumeKey, this->HeldLights, dims);
  const Clock::time_point keepStart = Clock::now();
  this->HeldKept = stepBudget > 0 &&
    this->Steps.Store(window, stepKey(), this->Estimator, this->HeldLights, stepBudget);
  stages.Keep = SecondsSince(keepStart);
  this->AddEstimatorStages(stages);
  stages.Total = SecondsSince(start);
  this->Stages = stages;
  if (this->In->Reporter->GetProgress() < 1.0)
  {
    this->ReportProgress(1.0);
  }
  // The mapper's own pipeline progress (its input's update) is not this.
  this->In->Reporter->SetProgressText(nullptr);
  this->Record(resolution);
  return true;
}

bool vtkMultiMaterialIrradianceStage::KeepsHeld(const vtkIrradianceUpdatePlan& plan,
  const vtkIrradianceUpdatePlan::Inputs& now, vtkOpenGLRenderWindow* window, const double range[2],
  size_t stepBudget, const std::function<vtkIrradianceStepCache::Key()>& stepKey)
{
  if (this->Estimator->GetNumberOfIrradianceTextures() == 0)
  {
    return false; // nothing computed yet, or released
  }
  if (plan.IsCurrent())
  {
    // Current but not yet kept (the step shown before caching was on).
    if (stepBudget > 0 && !this->HeldKept)
    {
      this->HeldKept =
        this->Steps.Store(window, stepKey(), this->Estimator, this->HeldLights, stepBudget);
    }
    return true;
  }
  // Interactive frames keep the last irradiance while only the lights or the
  // screen-chosen grid moved; the still frame after them updates it.
  if (this->In->Interactive &&
    this->In->Settings.InteractiveIrradiance == mmv::ReuseWhileInteracting && plan.KeepsVolume())
  {
    this->Out->Deferred = true;
    return true;
  }
  // No value of the data is visible (a time step outside the opacity):
  // nothing casts a shadow or is drawn, so the last irradiance serves.
  const std::vector<float> opacity = SampleOpacityTable(
    this->In->Property->GetScalarOpacity(0), range, this->In->Settings.PreIntegrationTableSize);
  if (std::all_of(opacity.begin(), opacity.end(), [](float a) { return !(a > 0.0f); }))
  {
    return true;
  }
  // Data seen before with everything else the same (a series' earlier step):
  // its kept irradiance is shown.
  std::vector<mmv::LightSource> restored;
  if (stepBudget > 0 && this->Steps.Restore(window, stepKey(), this->Estimator, restored))
  {
    this->Cache->Store(now.Volume, restored, now.Dimensions);
    this->HeldLights = restored;
    this->HeldKept = true;
    this->Out->CacheHit = true;
    this->Out->GridSet = true;
    std::copy(now.Dimensions, now.Dimensions + 3, this->Out->Dimensions);
    return true;
  }
  return false;
}

void vtkMultiMaterialIrradianceStage::UpdateSceneShadows(
  vtkOpenGLRenderWindow* window, const std::vector<mmv::LightSource>& sources)
{
  vtkMultiMaterialSceneShadows* scene = this->In->Scene;
  std::string problem;
  if (scene && !scene->Update(window, this->Cache->GetGrid(), sources, &problem))
  {
    this->Out->Warnings.push_back(problem + "; the other volumes cast no shadow on this one");
  }
  this->Estimator->SetSceneTransmittance(
    scene ? scene->GetTextures() : std::vector<vtkTextureObject*>(),
    scene ? scene->GetVersion() : 0);
}

void vtkMultiMaterialIrradianceStage::ReportProgressOf(
  vtkIrradianceEstimator* pass, double from, double to)
{
  // Without an observer the estimator runs without progress, and without the
  // glFinish each report takes.
  if (!this->In->Reporter->HasObserver(vtkCommand::ProgressEvent))
  {
    pass->SetProgressCallback(nullptr);
    return;
  }
  pass->SetProgressCallback(
    [this, from, to](double done) { this->ReportProgress(from + (to - from) * done); });
}

void vtkMultiMaterialIrradianceStage::ReportProgress(double progress)
{
  if (!this->Context || !this->In->Reporter->HasObserver(vtkCommand::ProgressEvent))
  {
    this->In->Reporter->UpdateProgress(progress);
    return;
  }
  // An observer may paint other OpenGL widgets (ParaView's client repaints
  // its progress bar): VTK's context, its recorded state and the bound
  // program come back before the update goes on.
  vtkOpenGLState* state = this->Context->GetState();
  state->Push();
  this->In->Reporter->UpdateProgress(progress);
  this->Context->MakeCurrent();
  state->Pop();
  this->Context->GetShaderCache()->ReleaseCurrentShader();
}

bool vtkMultiMaterialIrradianceStage::ComputeOn(vtkIrradianceEstimator* pass,
  vtkOpenGLRenderWindow* window, const double range[2], const mmv::Cutaway& cutaway,
  const mmv::IrradianceGrid& grid, const std::vector<float>& prefiltered, unsigned long version,
  const std::vector<mmv::LightSource>& sources, bool scattering)
{
  vtkPiecewiseFunction* opacity = this->In->Property->GetScalarOpacity(0);
  const int n = this->In->Settings.PreIntegrationTableSize;
  // Shadow rays step one irradiance voxel, with their own pre-integrated table.
  const double shadowStep = std::min({ grid.Spacing.x, grid.Spacing.y, grid.Spacing.z });
  vtkPreIntegrationTable* shadow = this->ShadowTable;
  shadow->SetScalarOpacity(opacity);
  shadow->SetMaterialTransferFunction(this->In->Materials);
  shadow->SetScalarOpacityUnitDistance(this->In->Property->GetScalarOpacityUnitDistance(0));
  shadow->SetTableSize(n);
  shadow->SetScalarRange(range[0], range[1]);
  shadow->SetStepLength(shadowStep);
  const Clock::time_point tablesStart = Clock::now();
  if (!shadow->Update())
  {
    return false;
  }
  this->TablesSeconds = SecondsSince(tablesStart);

  const std::vector<float> opacityTable = SampleOpacityTable(opacity, range, n);
  const std::vector<float> scatteringTable =
    scattering ? this->Cache->GetScattering() : std::vector<float>(n, 0.0f);

  pass->SetMultipleScattering(scattering);
  pass->SetShadowEstimation(this->In->Settings.ShadowEstimation);
  pass->SetPiecewiseShadowSlices(this->In->Settings.PiecewiseShadowSlices);
  pass->SetExponentialDiffusion(this->In->Settings.ExponentialDiffusion);
  pass->SetLightDirectionTolerance(this->In->Settings.LightDirectionTolerance);
  pass->SetCutaway(cutaway);
  const Clock::time_point inputsStart = Clock::now();
  pass->SetInputs(grid, prefiltered, n, shadow->GetShadowOpacityTable(), shadowStep,
    opacityTable.data(), scatteringTable.data(), sources, version);
  this->InputsSeconds = SecondsSince(inputsStart);
  // Under MPI the tint marches the global pre-filtered values, as the grey
  // shadows do, so tinted shadows cross the ranks too.
  pass->SetTintTable(shadow->GetShadowTintTable()); // nullptr: grey, no tints
  if (!pass->Render(window))
  {
    vtkErrorWithObjectMacro(
      this->In->Reporter, "the irradiance volume could not be computed on the GPU");
    return false;
  }
  return true;
}

void vtkMultiMaterialIrradianceStage::AddEstimatorStages(mmv::IrradianceStageSeconds& stages) const
{
  stages.Tables = this->TablesSeconds;
  stages.Inputs = this->InputsSeconds;
  stages.Shadows = this->Estimator->GetLastEstimationSeconds();
  stages.Diffusion = this->Estimator->GetLastDiffusionSeconds();
  stages.Setup = this->Estimator->GetLastSetupSeconds();
  stages.Write = this->Estimator->GetLastWriteSeconds();
  stages.Pass = this->Estimator->GetLastRenderSeconds();
}

void vtkMultiMaterialIrradianceStage::Record(const mmv::IrradianceResolution& resolution)
{
  vtkIrradianceEstimator* pass = this->Estimator;
  const int* dims = resolution.Dimensions;
  this->Out->GridSet = true;
  std::copy(dims, dims + 3, this->Out->Dimensions);
  this->Out->UpdatedLights = pass->GetNumberOfUpdatedLights();
  if (this->Out->UpdatedLights > 0)
  {
    this->Out->DiffusionPasses = pass->GetDiffusionPasses();
    this->Out->Seconds = pass->GetLastRenderSeconds();
  }
  int coarse[3];
  pass->GetDiffusionGridDimensions(coarse);
  std::ostringstream reason;
  reason << dims[0] << "x" << dims[1] << "x" << dims[2] << " (" << resolution.Reason << ")";
  if (pass->GetDiffusionLength() > 0.0 && this->In->Settings.MultipleScattering)
  {
    reason << "; diffusion on " << coarse[0] << "x" << coarse[1] << "x" << coarse[2]
           << " (diffusion length " << pass->GetDiffusionLength() << " data voxels, "
           << pass->GetDiffusionSubSteps() << " sub-steps x " << pass->GetDiffusionSweepsPerStep()
           << " sweeps)";
    int dim[3];
    pass->GetDiffusionGridDimensions(dim, mmv::DimLightStride);
    if (!std::equal(dim, dim + 3, coarse))
    {
      reason << ", the dim lights' on " << dim[0] << "x" << dim[1] << "x" << dim[2];
    }
  }
  this->ResolutionReason = reason.str();
  vtkDebugWithObjectMacro(this->In->Reporter,
    << "irradiance " << this->ResolutionReason << ", " << this->Out->UpdatedLights << " of "
    << this->In->Lights->size() << " lights updated in " << this->Out->Seconds << " s");
}

std::string mmv::IrradianceStageSeconds::Report() const
{
  char text[256];
  std::snprintf(text, sizeof(text),
    "probe %.3f s, prefilter %.3f s, shadow table %.3f s, inputs %.3f s, setup %.3f s, "
    "shadows %.3f s, diffusion %.3f s, write %.3f s, keep %.3f s, pass %.3f s, total %.3f s",
    this->Probe, this->Prefilter, this->Tables, this->Inputs, this->Setup, this->Shadows,
    this->Diffusion, this->Write, this->Keep, this->Pass, this->Total);
  return text;
}
