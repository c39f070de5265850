#include "vtkIrradianceEstimatorInternals.h"

using namespace mmv::voxelpass;

namespace
{
// Lights set in a channel mask.
int PopCount(int mask)
{
  int count = 0;
  for (; mask != 0; mask &= mask - 1)
  {
    ++count;
  }
  return count;
}
}

//------------------------------------------------------------------------------
vtkStandardNewMacro(vtkIrradianceEstimator);

vtkIrradianceEstimator::vtkIrradianceEstimator()
  : Internals(new vtkInternals)
{
}

vtkIrradianceEstimator::~vtkIrradianceEstimator()
{
  delete this->Internals;
}

//------------------------------------------------------------------------------
void vtkIrradianceEstimator::SetInputs(const mmv::IrradianceGrid& grid,
  const std::vector<float>& normalizedScalars, int tableSize, const float* shadowTable,
  double stepLength, const float* opacityTable, const float* scatteringTable,
  const std::vector<mmv::LightSource>& lights, unsigned long scalarsVersion)
{
  vtkInternals& internals = *this->Internals;
  this->Modified();
  if (static_cast<vtkIdType>(normalizedScalars.size()) != grid.GetNumberOfVoxels() ||
    grid.GetNumberOfVoxels() <= 0 || tableSize < 2 || !shadowTable || !opacityTable ||
    !scatteringTable || !(stepLength > 0.0))
  {
    internals.HasInputs = false;
    vtkErrorMacro("Invalid irradiance inputs: need " << grid.GetNumberOfVoxels()
                                                     << " scalars, tables of size >= 2 and a "
                                                        "positive step length.");
    return;
  }
  if (static_cast<int>(lights.size()) > mmv::MaxLights)
  {
    vtkWarningMacro(
      "" << lights.size() << " lights given; only the first " << mmv::MaxLights << " are used.");
  }
  internals.Lights.assign(
    lights.begin(), lights.begin() + std::min<size_t>(lights.size(), mmv::MaxLights));
  // One strided light grid: every strided light takes the largest stride.
  const int stride = internals.MaxLightGridStride();
  for (mmv::LightSource& light : internals.Lights)
  {
    light.GridStride = light.GridStride > 1 ? stride : 1;
  }
  // A light move changes only the lights: keep the classified, uploaded
  // volume and tables unless one of them differs.
  const std::vector<float> shadow(shadowTable, shadowTable + tableSize * tableSize);
  const std::vector<float> opacity(opacityTable, opacityTable + tableSize);
  const std::vector<float> scattering(scatteringTable, scatteringTable + tableSize);
  // A caller's version names its scalars (vtkIrradianceInputCache compares
  // them once, where they are made): no second comparison of 27 MB on the
  // CT-sized head. Without one (0) they are compared here.
  const bool sameScalars = scalarsVersion != 0 ? scalarsVersion == internals.ScalarsVersion
                                               : internals.Scalars == normalizedScalars;
  const bool sameGrid = internals.HasInputs && internals.Grid.IsSameGrid(grid);
  const bool sameVolume = sameGrid && internals.StepLength == stepLength && sameScalars &&
    internals.ShadowTable == shadow && internals.OpacityTable == opacity &&
    internals.ScatteringTable == scattering;
  if (!sameVolume)
  {
    if (!sameScalars || !sameGrid)
    {
      internals.ScalarsUploaded = false;
    }
    internals.Grid = grid;
    if (!sameScalars)
    {
      internals.Scalars = normalizedScalars;
      internals.ValueHistogram.clear();
    }
    internals.TableSize = tableSize;
    internals.ShadowTable = shadow;
    internals.StepLength = stepLength;
    internals.OpacityTable = opacity;
    internals.ScatteringTable = scattering;
    // The one decision on the classes: classes that still hold keep the
    // GPU's class texture, the CPU's classes and the diffusion plan made
    // from them. Otherwise they are made again: on the GPU at the upload,
    // on the CPU as well only where the diffusion plan needs the strengths
    // (NeedsCPUClasses).
    if (!(sameScalars && sameGrid && internals.ClassesHold()))
    {
      internals.ClassifiedOpacity = opacity;
      internals.ClassifiedScattering = scattering;
      internals.ClassesStale = true;
      internals.ClassesOnCPU = false;
      internals.PlanDiffusion(
        this->DiffusionTime, this->ExponentialDiffusion, this->MultipleScattering);
      if (!internals.ClassesOnCPU)
      {
        internals.CountNonEmptyVoxels();
      }
    }
    internals.Uploaded = false;
    internals.VolumeChanged = true;
  }
  internals.HasInputs = true;
  internals.ScalarsVersion = scalarsVersion;
}

//------------------------------------------------------------------------------
void vtkIrradianceEstimator::SetSceneTransmittance(
  const std::vector<vtkTextureObject*>& textures, unsigned long version)
{
  vtkInternals& internals = *this->Internals;
  if (version != internals.SceneTransmittanceVersion ||
    textures.size() != internals.SceneTransmittance.size())
  {
    internals.VolumeChanged = true;
    this->Modified();
  }
  internals.SceneTransmittance.assign(textures.begin(), textures.end());
  internals.SceneTransmittanceVersion = version;
}

//------------------------------------------------------------------------------
void vtkIrradianceEstimator::SetCutaway(const mmv::Cutaway& cutaway)
{
  vtkInternals& internals = *this->Internals;
  if (cutaway.Key() != internals.Cut.Key())
  {
    internals.Cut = cutaway;
    internals.VolumeChanged = true;
    this->Modified();
  }
}

const mmv::Cutaway& vtkIrradianceEstimator::GetCutaway() const
{
  return this->Internals->Cut;
}

void vtkIrradianceEstimator::SetCutawayUniforms(vtkShaderProgram* program) const
{
  if (!this->Internals->Cut.IsEmpty())
  {
    ::SetCutawayUniforms(program, mmv::ToIndexSpace(this->Internals->Cut, this->Internals->Grid));
  }
}

//------------------------------------------------------------------------------
void vtkIrradianceEstimator::SetRegion(const int bounds[6])
{
  mmv::IndexBox region;
  std::copy(bounds, bounds + 6, region.Bounds);
  if (region != this->Internals->RequestedRegion)
  {
    this->Internals->RequestedRegion = region;
    this->Modified();
  }
}

void vtkIrradianceEstimator::ResetRegion()
{
  this->SetRegion(mmv::IndexBox::Everything().Bounds);
}

void vtkIrradianceEstimator::GetRegion(int bounds[6]) const
{
  const mmv::IndexBox region = this->Internals->Region();
  std::copy(region.Bounds, region.Bounds + 6, bounds);
}

//------------------------------------------------------------------------------
bool vtkIrradianceEstimator::Render(vtkOpenGLRenderWindow* context)
{
  vtkInternals& internals = *this->Internals;
  this->NumberOfComputedVoxels = 0;
  this->DiffusionPasses = 0;
  this->NumberOfUpdatedLights = 0;
  this->NumberOfLightsSweptOnCPU = 0;
  this->NumberOfTexturesWrittenOnCPU = 0;
  this->LastEstimatedVoxels = 0;
  this->LastEstimationSeconds = 0.0;
  this->LastDiffusionSeconds = 0.0;
  this->LastSetupSeconds = 0.0;
  this->LastWriteSeconds = 0.0;
  // The caller's light marks hold for this Render() alone.
  std::vector<bool> given;
  given.swap(internals.GivenMarks);
  if (!this->CanRender(context))
  {
    return false;
  }
  // From here on the own textures are written and shown.
  internals.ShownIrradiance.clear();
  internals.ShownTint.clear();
  bool diffusion = false;
  const int estimation = this->PrepareSettings(diffusion);
  glFinish();
  const auto start = std::chrono::steady_clock::now();
  vtkOpenGLState* state = context->GetState();
  state->PushFramebufferBindings();
  bool ok = true;
  {
    vtkOpenGLState::ScopedglViewport viewport(state);
    vtkOpenGLState::ScopedglEnableDisable blend(state, GL_BLEND);
    vtkOpenGLState::ScopedglEnableDisable depth(state, GL_DEPTH_TEST);
    vtkOpenGLState::ScopedglEnableDisable scissor(state, GL_SCISSOR_TEST);
    vtkOpenGLState::ScopedglColorMask colorMask(state);
    // The diffusion's draws test depths against the blocks that exchange.
    vtkOpenGLState::ScopedglDepthMask depthMask(state);
    vtkOpenGLState::ScopedglDepthFunc depthFunc(state);
    // The diffusion sweeps scissor to their blocks: the renderer's own
    // scissor box must come back for the ray cast.
    vtkOpenGLState::ScopedglScissor scissorBox(state);
    state->vtkglDisable(GL_BLEND); // blending would garble the float outputs
    state->vtkglDisable(GL_DEPTH_TEST);
    state->vtkglDisable(GL_SCISSOR_TEST);
    state->vtkglColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    const bool software = vtkIrradianceComputeProgram::IsSoftwareRenderer();
    internals.Compute = this->ComputeShaders != FragmentDraws &&
      vtkIrradianceComputeProgram::IsSupported() &&
      (this->ComputeShaders == ComputeDispatches || !software);
    this->ComputeShadersUsed = internals.Compute;
    auto onCPU = [software](int place)
    { return place == OnCPU || (place == OnGPUUnlessSoftware && software); };
    const bool cpuClasses = onCPU(this->Classification);
    internals.DiffusionOnCPU = onCPU(this->DiffusionPlace);
    internals.SweepsOnCPU = onCPU(this->ShadowRaysPlace);
    internals.DiffusionRanOnCPU = false;
    bool reallocated = false;
    ok = internals.Upload(context, this->LayeredRendering, cpuClasses, this->ClassesCopied) &&
      internals.AllocateTargets(context, diffusion, this->LayeredRendering, reallocated);
    glFinish();
    this->LastSetupSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    // Only the lights that moved (or all, when the volume changed) are
    // recomputed: each light keeps its own channel.
    const std::vector<bool> updated =
      internals.MarkLightsToUpdate(internals.VolumeChanged || reallocated,
        mmv::LightToleranceRadians(this->LightDirectionTolerance), given);
    // Progress counts a light's shadows and its share of a diffusion as one
    // unit each.
    this->ProgressDone = 0.0;
    this->ProgressTotal =
      static_cast<double>(std::count(updated.begin(), updated.end(), true) * (diffusion ? 2 : 1));
    for (int group = 0; ok && group < this->GetNumberOfIrradianceTextures(); ++group)
    {
      ok = this->UpdateGroup(context, group, updated, estimation, diffusion);
    }
    this->DiffusedOnCPU = internals.DiffusionRanOnCPU;
    if (!this->KeepScratch)
    {
      internals.ReleaseScratch(context);
    }
  }
  state->PopFramebufferBindings();
  glFinish();
  this->LastRenderSeconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!ok)
  {
    internals.ComputedLights.clear();
    vtkErrorMacro("The irradiance passes failed (shader or texture setup).");
    return false;
  }
  internals.VolumeChanged = false;
  this->NumberOfComputedVoxels = internals.NonEmptyVoxels;
  this->LastEstimatedVoxels = internals.EstimatedVoxels;
  return true;
}

//------------------------------------------------------------------------------
bool vtkIrradianceEstimator::CanRender(vtkOpenGLRenderWindow* context)
{
  if (!context || !this->Internals->HasInputs)
  {
    vtkErrorMacro("Render() needs a context and valid inputs (SetInputs).");
    return false;
  }
  int major = 0;
  int minor = 0;
  context->GetOpenGLVersion(major, minor);
  if (major * 10 + minor < 32)
  {
    vtkErrorMacro(
      "The irradiance volume needs OpenGL 3.2, the context has " << major << "." << minor << ".");
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
// Settings that changed since the last update recompute every light; returns
// the shadow estimation this context can run.
int vtkIrradianceEstimator::PrepareSettings(bool& diffusion)
{
  vtkInternals& internals = *this->Internals;
  // (Multiple scattering turned on over a volume the CPU did not classify
  // needs its strengths now.)
  if (internals.Diffusion.Time != this->DiffusionTime ||
    internals.Diffusion.Exponential != this->ExponentialDiffusion ||
    (!internals.ClassesOnCPU &&
      internals.NeedsCPUClasses(this->MultipleScattering, this->DiffusionTime)))
  {
    internals.PlanDiffusion(
      this->DiffusionTime, this->ExponentialDiffusion, this->MultipleScattering);
    internals.Uploaded = false;
    internals.VolumeChanged = true;
  }
  // glTextureBarrier (OpenGL 4.5 or ARB_texture_barrier) lets a chunk of
  // piecewise rays read the earlier chunks' results from the same texture.
  const bool barrier = glTextureBarrier != nullptr;
  const int estimation = barrier ? this->ShadowEstimation : mmv::FullShadowRays;
  if (estimation != this->ShadowEstimation && !internals.WarnedNoBarrier)
  {
    internals.WarnedNoBarrier = true;
    vtkWarningMacro("Piecewise shadow rays need glTextureBarrier (OpenGL 4.5 or "
                    "ARB_texture_barrier): this context takes full shadow rays.");
  }
  if (internals.ShadowEstimationUsed != estimation ||
    internals.PiecewiseSlicesUsed != this->PiecewiseShadowSlices)
  {
    internals.ShadowEstimationUsed = estimation;
    internals.PiecewiseSlicesUsed = this->PiecewiseShadowSlices;
    internals.VolumeChanged = true;
  }
  if (internals.MultipleScatteringUsed != this->MultipleScattering)
  {
    internals.MultipleScatteringUsed = this->MultipleScattering;
    internals.VolumeChanged = true;
  }
  diffusion = this->MultipleScattering && this->DiffusionTime > 0.0 &&
    internals.Diffusions[0].CoarseMaxRate > 0.0;
  if (diffusion)
  {
    // A light that became dim gets its grid now.
    internals.PlanStridedDiffusion();
  }
  const mmv::IndexBox region = internals.Region();
  if (region != internals.RegionUsed)
  {
    internals.RegionUsed = region;
    internals.VolumeChanged = true;
  }
  internals.PlanRegion(diffusion);
  internals.EstimatedVoxels = 0;
  return estimation;
}

//------------------------------------------------------------------------------
// The lights of irradiance texture `group` marked in `updated`: their
// transmittance (by piecewise rays unless full rays are asked for, each
// into its own channel), the diffusion, the final write and the tints.
bool vtkIrradianceEstimator::UpdateGroup(vtkOpenGLRenderWindow* context, int group,
  const std::vector<bool>& updated, int estimation, bool diffusion)
{
  vtkInternals& internals = *this->Internals;
  GroupLights lights;
  for (int l = 0; l < LightsPerTexture; ++l)
  {
    const size_t k = static_cast<size_t>(group * LightsPerTexture + l);
    if (k < internals.Lights.size() && updated[k])
    {
      lights.Mask |= 1 << l;
      ++this->NumberOfUpdatedLights;
      const bool strided = internals.Lights[k].GridStride > 1;
      lights.StridedMask |= strided ? 1 << l : 0;
      std::vector<mmv::ShadowSweep> sweeps =
        internals.LightSweeps(static_cast<int>(k), estimation, this->PiecewiseShadowSlices);
      if (!sweeps.empty())
      {
        lights.Swept.emplace_back(static_cast<int>(k), std::move(sweeps));
      }
      else
      {
        (strided ? lights.StridedFullMask : lights.FullMask) |= 1 << l;
      }
    }
  }
  if (lights.Mask == 0)
  {
    return true;
  }
  auto stage = std::chrono::steady_clock::now();
  auto elapsed = [&stage]()
  {
    glFinish();
    const auto now = std::chrono::steady_clock::now();
    const double seconds = std::chrono::duration<double>(now - stage).count();
    stage = now;
    return seconds;
  };
  // The CPU's sweeps first: their upload sets every channel of its box.
  // Where they are all the group's lights, the CPU makes the texels too.
  const bool writeOnCPU = internals.WritesOnCPU(group, lights.Mask, lights.Swept, diffusion);
  if (!writeOnCPU && !internals.EnsurePassScratch(context, diffusion))
  {
    return false;
  }
  this->NumberOfLightsSweptOnCPU += internals.SweepOnCPU(lights.Swept, this->SkipEmptyVoxels,
    !writeOnCPU, [this, context]() { this->ReportProgress(context, 1.0); });
  bool ok = true;
  if (writeOnCPU)
  {
    // The sweeps' values go straight to the diffusion, or to the texels.
    this->LastEstimationSeconds += elapsed();
    if (diffusion)
    {
      internals.GatherOnCPU(group, this->SkipEmptyVoxels);
      ok = this->DiffuseGroup(context, lights, elapsed);
    }
    internals.WriteOnCPU(group, this->SkipEmptyVoxels, diffusion);
    this->LastWriteSeconds += elapsed();
    ++this->NumberOfTexturesWrittenOnCPU;
    if (ok && diffusion)
    {
      this->ReportProgress(context, PopCount(lights.Mask)); // the diffusion, with the write
    }
  }
  else
  {
    ok = this->PassesOfGroup(context, group, lights, diffusion, elapsed);
  }
  for (int l = 0; ok && !internals.Tint.empty() && l < LightsPerTexture; ++l)
  {
    if ((lights.Mask & (1 << l)) != 0)
    {
      ok = internals.TintPass(context, group * LightsPerTexture + l, this->LayeredRendering);
    }
  }
  if (!internals.Tint.empty())
  {
    this->LastEstimationSeconds += elapsed();
  }
  return ok;
}

//------------------------------------------------------------------------------
// The passes of UpdateGroup for what the CPU did not sweep: shadows, the
// dim lights' upsampling, the diffusion and the final write. `elapsed`
// returns the seconds since its last call, once the GPU is done.
bool vtkIrradianceEstimator::PassesOfGroup(vtkOpenGLRenderWindow* context, int group,
  const GroupLights& lights, bool diffusion, const std::function<double()>& elapsed)
{
  vtkInternals& internals = *this->Internals;
  const int stride = internals.MaxLightGridStride();
  const int fullMask = lights.FullMask;
  const int stridedFullMask = lights.StridedFullMask;
  bool ok = fullMask == 0 ||
    internals.ShadowPass(
      context, group, fullMask, 1, this->SkipEmptyVoxels, this->LayeredRendering);
  ok = ok &&
    (stridedFullMask == 0 ||
      internals.ShadowPass(
        context, group, stridedFullMask, stride, this->SkipEmptyVoxels, this->LayeredRendering));
  if (ok && (fullMask | stridedFullMask) != 0)
  {
    this->ReportProgress(context, PopCount(fullMask | stridedFullMask));
  }
  for (const auto& light : lights.Swept)
  {
    ok = ok &&
      internals.PiecewiseShadowPass(
        context, light.first, light.second, this->SkipEmptyVoxels, this->LayeredRendering);
    if (ok)
    {
      this->ReportProgress(context, 1.0);
    }
  }
  // The dim lights' grid, interpolated to the irradiance grid: from here on
  // they are lit as the others.
  ok = ok &&
    (lights.StridedMask == 0 ||
      internals.UpsamplePass(
        context, lights.StridedMask, stride, this->SkipEmptyVoxels, this->LayeredRendering));
  this->LastEstimationSeconds += elapsed();
  const int mask = lights.Mask;
  vtkTextureObject* result = internals.FineScratch[0];
  if (ok && diffusion)
  {
    const bool onCPU = internals.DiffusesOnCPU();
    ok = (!onCPU || internals.ReadFineScratch()) && this->DiffuseGroup(context, lights, elapsed) &&
      (!onCPU || internals.UploadDiffusedFine());
    result = internals.FineScratch[1];
  }
  ok = ok &&
    internals.FillPass(context, result, group, mask, this->SkipEmptyVoxels, this->LayeredRendering);
  this->LastWriteSeconds += elapsed();
  if (ok && diffusion)
  {
    this->ReportProgress(context, PopCount(mask)); // the diffusion, with the short write
  }
  return ok;
}

//------------------------------------------------------------------------------
// Each diffusion grid diffuses its lights into their channels (the strided
// ones on their own where DiffusionOf picks it): FineScratch[0] into
// FineScratch[1], or FineOnCPU in place.
bool vtkIrradianceEstimator::DiffuseGroup(
  vtkOpenGLRenderWindow* context, const GroupLights& lights, const std::function<double()>& elapsed)
{
  vtkInternals& internals = *this->Internals;
  const bool ownGrid = internals.DiffusionOf(internals.MaxLightGridStride()) == 1;
  const int lightsOf[2] = { ownGrid ? lights.Mask & ~lights.StridedMask : lights.Mask,
    ownGrid ? lights.StridedMask : 0 };
  bool ok = true;
  for (int p = 0; ok && p < 2; ++p)
  {
    const int sweeps = lightsOf[p] == 0
      ? 0
      : internals.Diffuse(context, internals.Diffusions[p], this->LayeredRendering, lightsOf[p],
          this->SkipEmptyVoxels);
    ok = sweeps >= 0;
    this->DiffusionPasses += std::max(0, sweeps);
  }
  this->LastDiffusionSeconds += elapsed();
  return ok;
}

//------------------------------------------------------------------------------
void vtkIrradianceEstimator::SetProgressCallback(std::function<void(double)> callback)
{
  this->Progress = std::move(callback);
}

void vtkIrradianceEstimator::ReportProgress(vtkOpenGLRenderWindow* context, double units)
{
  if (!this->Progress || !(this->ProgressTotal > 0.0))
  {
    return;
  }
  // What is reported done is done, not queued.
  glFinish();
  this->ProgressDone = std::min(this->ProgressDone + units, this->ProgressTotal);
  this->Progress(this->ProgressDone / this->ProgressTotal);
  // A GUI that repaints in the callback may leave its own context current;
  // the passes' GL calls and VTK's state cache are this context's.
  if (!context->IsCurrent())
  {
    context->MakeCurrent();
  }
}

//------------------------------------------------------------------------------
void vtkIrradianceEstimator::GetDiffusionGridDimensions(int dims[3], int lightGridStride) const
{
  const auto& plan = this->Internals->Diffusions[this->Internals->DiffusionOf(lightGridStride)];
  std::copy(plan.Coarse.Dimensions, plan.Coarse.Dimensions + 3, dims);
}

int vtkIrradianceEstimator::GetDiffusionSubSteps() const
{
  return this->Internals->Diffusions[0].SubSteps;
}

int vtkIrradianceEstimator::GetDiffusionSweepsPerStep() const
{
  return this->Internals->Diffusions[0].SweepsPerStep;
}

double vtkIrradianceEstimator::GetDiffusionLength() const
{
  return this->Internals->Diffusions[0].Coarse.DiffusionLength;
}

//------------------------------------------------------------------------------
vtkTextureObject* vtkIrradianceEstimator::GetIrradianceTexture(int i) const
{
  const vtkInternals& internals = *this->Internals;
  const auto& textures =
    internals.ShownIrradiance.empty() ? internals.Irradiance : internals.ShownIrradiance;
  return i >= 0 && i < static_cast<int>(textures.size()) ? textures[i].Get() : nullptr;
}

vtkTextureObject* vtkIrradianceEstimator::GetScalarTexture() const
{
  return this->Internals->Uploaded ? this->Internals->ScalarTexture.Get() : nullptr;
}

vtkTextureObject* vtkIrradianceEstimator::GetShadowTableTexture() const
{
  return this->Internals->Uploaded ? this->Internals->TableTexture.Get() : nullptr;
}

int vtkIrradianceEstimator::GetNumberOfIrradianceTextures() const
{
  return static_cast<int>(this->Internals->Irradiance.size());
}

void vtkIrradianceEstimator::SetLightsToUpdate(const std::vector<bool>& marks)
{
  this->Internals->GivenMarks = marks;
  this->Modified();
}

const std::vector<mmv::LightSource>& vtkIrradianceEstimator::GetComputedLights() const
{
  return this->Internals->ComputedLights;
}

void vtkIrradianceEstimator::ShowKeptTextures(
  const std::vector<vtkTextureObject*>& irradiance, const std::vector<vtkTextureObject*>& tints)
{
  vtkInternals& internals = *this->Internals;
  internals.ShownIrradiance.assign(irradiance.begin(), irradiance.end());
  internals.ShownTint.assign(tints.begin(), tints.end());
  // The own textures keep what they hold (and their filled boxes); the
  // placements they hold are no longer those shown.
  internals.VolumeChanged = true;
  this->Modified();
}

bool vtkIrradianceEstimator::ShowsKeptTextures() const
{
  return !this->Internals->ShownIrradiance.empty();
}

//------------------------------------------------------------------------------
namespace
{
// Slices 0 .. depth-1 of a 3D texture in turn as the read buffer of the
// pass's framebuffer; `read(z)` reads the slice with glReadPixels.
template <typename ReadSlice>
void ForEachTextureSlice(vtkOpenGLRenderWindow* context, vtkOpenGLFramebufferObject* framebuffer,
  vtkTextureObject* texture, int depth, ReadSlice&& read)
{
  vtkOpenGLState* state = context->GetState();
  state->PushFramebufferBindings();
  framebuffer->Bind();
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  for (int z = 0; z < depth; ++z)
  {
    framebuffer->RemoveColorAttachment(0);
    framebuffer->AddColorAttachment(0, texture, z);
    framebuffer->ActivateReadBuffer(0);
    read(z);
  }
  framebuffer->RemoveColorAttachment(0);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  state->PopFramebufferBindings();
}

// Every slice of a single-channel 3D texture.
template <typename T>
bool ReadBackTexture(vtkOpenGLRenderWindow* context, vtkOpenGLFramebufferObject* framebuffer,
  vtkTextureObject* texture, GLenum type, std::vector<T>& values)
{
  if (!context || !framebuffer || !texture || !texture->GetHandle())
  {
    return false;
  }
  const int d[3] = { static_cast<int>(texture->GetWidth()), static_cast<int>(texture->GetHeight()),
    static_cast<int>(texture->GetDepth()) };
  const size_t sliceSize = static_cast<size_t>(d[0]) * d[1];
  values.assign(sliceSize * d[2], T());
  ForEachTextureSlice(context, framebuffer, texture, d[2],
    [&](int z) { glReadPixels(0, 0, d[0], d[1], GL_RED, type, values.data() + z * sliceSize); });
  return true;
}
}

//------------------------------------------------------------------------------
bool vtkIrradianceEstimator::ReadBack(
  vtkOpenGLRenderWindow* context, int light, std::vector<float>& values)
{
  std::vector<std::vector<float>> lights;
  if (!this->ReadBackLights(context, light, light + 1, lights))
  {
    return false;
  }
  values.swap(lights[0]);
  return true;
}

bool vtkIrradianceEstimator::ReadBackLights(
  vtkOpenGLRenderWindow* context, int first, int last, std::vector<std::vector<float>>& values)
{
  vtkInternals& internals = *this->Internals;
  const int computed = static_cast<int>(internals.Lights.size());
  if (!context || !internals.Framebuffer || first < 0 || last > computed || first >= last)
  {
    vtkErrorMacro("No irradiance of lights " << first << " to " << last - 1 << " to read back.");
    return false;
  }
  const int* d = internals.Grid.Dimensions;
  const vtkIdType sliceSize = static_cast<vtkIdType>(d[0]) * d[1];
  std::vector<float> rgba(4 * sliceSize);
  values.assign(last - first, std::vector<float>(sliceSize * d[2]));
  // Each texture is read once for all the lights it holds.
  for (int t = first / LightsPerTexture; t * LightsPerTexture < last; ++t)
  {
    vtkTextureObject* texture = this->GetIrradianceTexture(t);
    if (!texture)
    {
      continue;
    }
    ForEachTextureSlice(context, internals.Framebuffer, texture, d[2],
      [&](int z)
      {
        glReadPixels(0, 0, d[0], d[1], GL_RGBA, GL_FLOAT, rgba.data());
        for (int c = 0; c < LightsPerTexture; ++c)
        {
          const int light = t * LightsPerTexture + c;
          if (light < first || light >= last)
          {
            continue;
          }
          float* out = values[light - first].data() + z * sliceSize;
          for (vtkIdType p = 0; p < sliceSize; ++p)
          {
            out[p] = rgba[4 * p + c];
          }
        }
      });
  }
  return true;
}

//------------------------------------------------------------------------------
vtkIdType vtkIrradianceEstimator::GetNumberOfVolumeUploads() const
{
  return this->Internals->VolumeUploads;
}

vtkIdType vtkIrradianceEstimator::GetNumberOfClassifications() const
{
  return this->Internals->Classifications;
}

bool vtkIrradianceEstimator::ReadBackClasses(
  vtkOpenGLRenderWindow* context, std::vector<float>& classes)
{
  vtkInternals& internals = *this->Internals;
  return internals.Uploaded &&
    ReadBackTexture(context, internals.Framebuffer, internals.ClassTexture, GL_FLOAT, classes);
}

void vtkIrradianceEstimator::ClassifyOnCPU(std::vector<float>& classes) const
{
  const vtkInternals& internals = *this->Internals;
  std::vector<unsigned char> nonEmpty;
  vtkInternals::ClassifyValues(internals.Scalars, internals.Grid.Dimensions, internals.OpacityTable,
    internals.ScatteringTable, classes, nonEmpty);
}

bool vtkIrradianceEstimator::GetClassifiedOnCPU() const
{
  return this->Internals->ClassesOnCPU;
}

bool vtkIrradianceEstimator::ReadBackLightGridNeeded(
  vtkOpenGLRenderWindow* context, std::vector<unsigned char>& needed, int dims[3])
{
  vtkInternals& internals = *this->Internals;
  internals.LightGridDimensions(internals.MaxLightGridStride(), dims);
  return internals.MaxLightGridStride() > 1 &&
    ReadBackTexture(
      context, internals.Framebuffer, internals.LightGridClassTexture, GL_UNSIGNED_BYTE, needed);
}

void vtkIrradianceEstimator::LightGridNeededOnCPU(
  std::vector<unsigned char>& needed, int dims[3]) const
{
  const vtkInternals& internals = *this->Internals;
  const int stride = internals.MaxLightGridStride();
  internals.LightGridDimensions(stride, dims);
  std::vector<float> classes;
  this->ClassifyOnCPU(classes);
  needed = internals.LightGridNeededOnCPU(classes, stride);
}

vtkIdType vtkIrradianceEstimator::GetTextureMemoryBytes() const
{
  vtkIdType bytes = 0;
  for (const auto& texture : this->Internals->Irradiance)
  {
    bytes += static_cast<vtkIdType>(texture->GetWidth()) * texture->GetHeight() *
      texture->GetDepth() * texture->GetComponents() * sizeof(unsigned short);
  }
  for (const auto& texture : this->Internals->Tint)
  {
    // RGBA16F: 4 channels of 2 bytes.
    bytes += static_cast<vtkIdType>(texture->GetWidth()) * texture->GetHeight() *
      texture->GetDepth() * 4 * 2;
  }
  return bytes;
}

vtkIdType vtkIrradianceEstimator::GetScratchMemoryBytes() const
{
  vtkIdType bytes = 0;
  auto add = [&bytes](const vtkSmartPointer<vtkTextureObject>& texture)
  {
    // 32-bit floats.
    bytes += texture ? static_cast<vtkIdType>(texture->GetWidth()) * texture->GetHeight() *
        texture->GetDepth() * texture->GetComponents() * 4
                     : 0;
  };
  std::for_each(this->Internals->FineScratch.begin(), this->Internals->FineScratch.end(), add);
  for (const auto& plan : this->Internals->Diffusions)
  {
    std::for_each(plan.CoarseScratch.begin(), plan.CoarseScratch.end(), add);
    bytes += static_cast<vtkIdType>(plan.CPUScratchBytes());
  }
  add(this->Internals->LightGridScratch);
  // A diffusion on the CPU: its copy of the irradiance.
  bytes += static_cast<vtkIdType>(4 * this->Internals->FineOnCPU.size());
  // Shadow rays on the CPU: their targets' contents.
  for (const auto& buffer : this->Internals->SweptOnCPU)
  {
    bytes += static_cast<vtkIdType>(4 * buffer.size());
  }
  // The final write on the CPU: one texture's texels.
  bytes += static_cast<vtkIdType>(2 * this->Internals->WrittenOnCPU.size());
  return bytes;
}

//------------------------------------------------------------------------------
void vtkIrradianceEstimator::SetTintTable(const float* tintTable)
{
  vtkInternals& internals = *this->Internals;
  std::vector<float> table;
  if (tintTable && internals.TableSize > 0)
  {
    table.assign(
      tintTable, tintTable + 4 * static_cast<size_t>(internals.TableSize) * internals.TableSize);
  }
  if (table != internals.TintTable)
  {
    internals.TintTable.swap(table);
    internals.Uploaded = false;
    internals.VolumeChanged = true;
  }
}

bool vtkIrradianceEstimator::IsTinted() const
{
  return !this->Internals->TintTable.empty();
}

vtkTextureObject* vtkIrradianceEstimator::GetTintTexture(int light) const
{
  const vtkInternals& internals = *this->Internals;
  const auto& tint = internals.ShownIrradiance.empty() ? internals.Tint : internals.ShownTint;
  return light >= 0 && light < static_cast<int>(tint.size()) ? tint[light].Get() : nullptr;
}

void vtkIrradianceEstimator::GetTintDimensions(int dims[3]) const
{
  this->Internals->TintDimensions(dims);
}

bool vtkIrradianceEstimator::ReadBackTint(
  vtkOpenGLRenderWindow* context, int light, std::vector<float>& rgb)
{
  vtkInternals& internals = *this->Internals;
  vtkTextureObject* texture = this->GetTintTexture(light);
  if (!context || !texture || !internals.Framebuffer)
  {
    vtkErrorMacro("No tint of light " << light << " to read back.");
    return false;
  }
  int d[3];
  internals.TintDimensions(d);
  const vtkIdType sliceSize = static_cast<vtkIdType>(d[0]) * d[1];
  std::vector<float> rgba(4 * sliceSize);
  rgb.assign(3 * sliceSize * d[2], 0.0f);
  ForEachTextureSlice(context, internals.Framebuffer, texture, d[2],
    [&](int z)
    {
      glReadPixels(0, 0, d[0], d[1], GL_RGBA, GL_FLOAT, rgba.data());
      for (vtkIdType p = 0; p < sliceSize; ++p)
      {
        for (int c = 0; c < 3; ++c)
        {
          rgb[3 * (z * sliceSize + p) + c] = rgba[4 * p + c];
        }
      }
    });
  return true;
}

//------------------------------------------------------------------------------
void vtkIrradianceEstimator::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Internals->Release(window);
}

//------------------------------------------------------------------------------
void vtkIrradianceEstimator::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  const vtkInternals& internals = *this->Internals;
  os << indent << "Dimensions: " << internals.Grid.Dimensions[0] << " "
     << internals.Grid.Dimensions[1] << " " << internals.Grid.Dimensions[2] << "\n";
  os << indent << "Lights: " << internals.Lights.size() << "\n";
  os << indent << "MultipleScattering: " << this->MultipleScattering << "\n";
  os << indent << "DiffusionTime: " << this->DiffusionTime << "\n";
  os << indent << "LayeredRendering: " << this->LayeredRendering << "\n";
  os << indent << "ComputeShaders: " << this->ComputeShaders
     << " (last update: " << (this->ComputeShadersUsed ? "compute" : "fragment") << ")\n";
  os << indent << "SkipEmptyVoxels: " << this->SkipEmptyVoxels << "\n";
  os << indent << "ShadowEstimation: " << this->ShadowEstimation << "\n";
  os << indent << "PiecewiseShadowSlices: " << this->PiecewiseShadowSlices << "\n";
  for (const auto& plan : internals.Diffusions)
  {
    if (plan.Planned)
    {
      os << indent << (&plan == &internals.Diffusions[0] ? "DiffusionGrid: " : "StridedLights: ")
         << plan.Coarse.Dimensions[0] << " " << plan.Coarse.Dimensions[1] << " "
         << plan.Coarse.Dimensions[2] << " (" << plan.SubSteps << " sub-steps x "
         << plan.SweepsPerStep << " sweeps)\n";
    }
  }
  os << indent << "LightDirectionTolerance: " << this->LightDirectionTolerance << "\n";
  os << indent << "NumberOfUpdatedLights: " << this->NumberOfUpdatedLights << "\n";
  os << indent << "NumberOfComputedVoxels: " << this->NumberOfComputedVoxels << "\n";
  const mmv::IndexBox region = internals.Region();
  os << indent << "Region: " << region.Bounds[0] << " " << region.Bounds[1] << " "
     << region.Bounds[2] << " " << region.Bounds[3] << " " << region.Bounds[4] << " "
     << region.Bounds[5] << "\n";
  os << indent << "LastEstimatedVoxels: " << this->LastEstimatedVoxels << "\n";
  os << indent << "DiffusionPasses: " << this->DiffusionPasses << "\n";
  os << indent << "LastRenderSeconds: " << this->LastRenderSeconds << "\n";
  os << indent << "LastEstimationSeconds: " << this->LastEstimationSeconds << "\n";
  os << indent << "LastDiffusionSeconds: " << this->LastDiffusionSeconds << "\n";
  os << indent << "TextureMemoryBytes: " << this->GetTextureMemoryBytes() << "\n";
  os << indent << "Classification: " << this->Classification
     << " (last: " << (this->ClassesCopied ? "CPU" : "GPU") << ")\n";
  os << indent << "DiffusionPlace: " << this->DiffusionPlace
     << " (last: " << (this->DiffusedOnCPU ? "CPU" : "GPU") << ")\n";
  os << indent << "ShadowRaysPlace: " << this->ShadowRaysPlace
     << " (last: " << this->NumberOfLightsSweptOnCPU << " light(s) on the CPU)\n";
  os << indent << "KeepScratch: " << this->KeepScratch << "\n";
  os << indent << "ScratchMemoryBytes: " << this->GetScratchMemoryBytes() << "\n";
}
