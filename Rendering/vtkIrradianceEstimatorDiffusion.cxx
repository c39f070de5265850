// vtkIrradianceEstimator: multiple scattering, the diffusion of the
// transmittance on the diffusion grid.
#include "vtkIrradianceEstimatorInternals.h"
#include "vtkMultiMaterialThreads.h"
#include "vtkTextureCopy.h"

#include "mmvDiffusionFS.h"
#include "mmvDiffusionGridFS.h"

#include <mutex>

using namespace mmv::voxelpass;

//------------------------------------------------------------------------------
// The diffusion grids and how long their solves run, exactly as the CPU's
// mmv::DiffuseIrradianceOnDiffusionGrid plans them: the lights' on the
// irradiance grid now, the strided lights' while one is strided. The
// strengths come from the CPU's classes: classified here where the diffusion
// will run (NeedsCPUClasses). Otherwise no voxel has a strength the diffusion
// would use (it is off, or the table has no s > 0), and the plan is the one
// for zero strength everywhere, made without touching the voxels.
void vtkIrradianceEstimator::vtkInternals::PlanDiffusion(
  double time, bool exponential, bool multipleScattering)
{
  this->Diffusion.Exponential = exponential;
  this->Diffusion.Time = time;
  if (!this->ClassesOnCPU && this->NeedsCPUClasses(multipleScattering, time))
  {
    this->Classify();
  }
  for (auto& plan : this->Diffusions)
  {
    plan.Planned = false;
  }
  float maxStrength = 0.0f;
  const std::vector<float>& strength = this->DiffusionStrengths(maxStrength);
  this->PlanDiffusionBlocks(this->Diffusions[0], this->Diffusion, strength, maxStrength);
  this->PlanStridedDiffusion(&strength, maxStrength);
}

void vtkIrradianceEstimator::vtkInternals::PlanStridedDiffusion(
  const std::vector<float>* strength, float maxStrength)
{
  const int stride = this->MaxLightGridStride();
  if (stride <= 1 || this->Diffusions[1].Planned)
  {
    return;
  }
  if (!strength)
  {
    strength = &this->DiffusionStrengths(maxStrength);
  }
  this->PlanDiffusionBlocks(this->Diffusions[1],
    mmv::LightGridDiffusionSettings(this->Diffusion, stride), *strength, maxStrength);
}

const std::vector<float>& vtkIrradianceEstimator::vtkInternals::DiffusionStrengths(
  float& maxStrength)
{
  maxStrength = 0.0f;
  std::vector<float>& strength = this->StrengthScratch;
  if (!this->ClassesOnCPU)
  {
    strength.clear(); // its capacity stays
  }
  else
  {
    strength.resize(this->Classes.size()); // every element written below
    std::mutex maxMutex;
    mmv::For(0, static_cast<vtkIdType>(strength.size()),
      [&](vtkIdType begin, vtkIdType end)
      {
        float chunkMax = 0.0f;
        for (vtkIdType v = begin; v < end; ++v)
        {
          strength[v] = std::max(0.0f, this->Classes[v]);
          chunkMax = std::max(chunkMax, strength[v]);
        }
        std::lock_guard<std::mutex> lock(maxMutex);
        maxStrength = std::max(maxStrength, chunkMax);
      });
  }
  return strength;
}

int vtkIrradianceEstimator::vtkInternals::DiffusionOf(int stride) const
{
  const DiffusionPlan& strided = this->Diffusions[1];
  const int* lights = this->Diffusions[0].Coarse.Factor;
  const bool coarser = stride > 1 && strided.Planned &&
    !std::equal(strided.Coarse.Factor, strided.Coarse.Factor + 3, lights) &&
    strided.FilledShare >= mmv::MinimumFilledBlockShare && strided.CoarseMaxRate > 0.0;
  return coarser ? 1 : 0;
}

std::array<int, 2> vtkIrradianceEstimator::vtkInternals::ScratchChannels() const
{
  std::array<int, 2> channels = { 0, 0 };
  for (size_t k = 0; k < this->Lights.size(); ++k)
  {
    const int plan = this->DiffusionOf(this->Lights[k].GridStride);
    channels[plan] = std::max(channels[plan], static_cast<int>(k % LightsPerTexture) + 1);
  }
  for (int& c : channels)
  {
    c = this->Compute || c > 2 ? 4 : std::max(c, 1);
  }
  return channels;
}

//------------------------------------------------------------------------------
// One diffusion grid of `settings` for `strength`.
void vtkIrradianceEstimator::vtkInternals::PlanDiffusionBlocks(DiffusionPlan& plan,
  const mmv::DiffusionSettings& settings, const std::vector<float>& strength, float maxStrength)
{
  const double time = settings.Time;
  const double spacing[3] = { this->Grid.DataVoxelsPerVoxel[0], this->Grid.DataVoxelsPerVoxel[1],
    this->Grid.DataVoxelsPerVoxel[2] };
  mmv::DiffusionGrid& grid = plan.Coarse;
  grid = mmv::PlanDiffusionGrid(this->Grid.Dimensions, spacing, maxStrength, settings);
  if (!this->ClassesOnCPU)
  {
    // Nothing the diffusion would use scatters (NeedsCPUClasses), so none
    // runs: one block stands for the grid, not a plan and a texture of the
    // irradiance grid's size at every opacity edit and time step.
    for (int a = 0; a < 3; ++a)
    {
      const int factor = std::max(1, this->Grid.Dimensions[a]);
      grid.Spacing[a] = grid.Spacing[a] / grid.Factor[a] * factor;
      grid.Factor[a] = factor;
      grid.Dimensions[a] = 1;
    }
  }
  std::vector<float> coarseStrength;
  std::vector<float> capacity;
  const float* blockStrength = nullptr;
  const float* blockCapacity = nullptr;
  if (this->ClassesOnCPU && grid.Factor[0] == 1 && grid.Factor[1] == 1 && grid.Factor[2] == 1)
  {
    // Blocks of one voxel (a diffusion length of a few voxels) are the
    // voxels: the restriction would copy the strengths (never negative) and
    // give capacity 1 where they scatter, which the texels take as 1
    // everywhere (none elsewhere); every scattering block is filled.
    blockStrength = strength.data();
    plan.FilledShare = maxStrength > 0.0f ? 1.0 : 0.0;
  }
  else
  {
    if (this->ClassesOnCPU)
    {
      mmv::RestrictToDiffusionGrid(
        this->Grid.Dimensions, grid, strength.data(), nullptr, &coarseStrength, nullptr, &capacity);
    }
    else
    {
      // What the restriction of zero strength gives.
      coarseStrength.assign(grid.GetNumberOfVoxels(), 0.0f);
      capacity.assign(grid.GetNumberOfVoxels(), 0.0f);
    }
    blockStrength = coarseStrength.data();
    blockCapacity = capacity.data();
    plan.FilledShare = mmv::FilledBlockShare(capacity.data(), grid.GetNumberOfVoxels());
  }
  // Two RGBA texels per block (face coefficients, capacity, whether it
  // scatters), the largest rate from the same faces; and the box of the
  // blocks that scatter, the only ones the sweeps change.
  const double maxRate = mmv::DiffusionBlockTexels(grid.Dimensions, grid.Spacing, blockStrength,
    blockCapacity, plan.CoarseFaces[0], plan.CoarseFaces[1], plan.CoarseExchanges);
  plan.CoarseMaxRate = time > 0.0 ? maxRate : 0.0;
  plan.CoarseFacesChanged = true;
  plan.Planned = true;
  const int* cd = grid.Dimensions;
  int* box = plan.ScatteringBox.Bounds;
  for (int a = 0; a < 3; ++a)
  {
    box[2 * a] = cd[a] - 1;
    box[2 * a + 1] = 0;
  }
  for (vtkIdType c = 0; c < grid.GetNumberOfVoxels(); ++c)
  {
    if (blockStrength[c] > 0.0f)
    {
      const int index[3] = { static_cast<int>(c % cd[0]), static_cast<int>((c / cd[0]) % cd[1]),
        static_cast<int>(c / (static_cast<size_t>(cd[0]) * cd[1])) };
      for (int a = 0; a < 3; ++a)
      {
        box[2 * a] = std::min(box[2 * a], index[a]);
        box[2 * a + 1] = std::max(box[2 * a + 1], index[a]);
      }
    }
  }
  if (settings.Exponential)
  {
    // One "sub-step" of as many passes as the series has terms. A quarter of
    // the sweeps' tolerance: the result is stored in 16 bits as well, and the
    // two errors together stay below the sweeps' (1e-3 of the largest
    // irradiance) for two or three more terms.
    plan.ExponentialSeries = mmv::ExponentialChebyshevCoefficients(
      plan.CoarseMaxRate * time, 0.25 * settings.SweepTolerance);
    plan.SubSteps = plan.ExponentialSeries.empty() ? 0 : 1;
    plan.SweepsPerStep = static_cast<int>(plan.ExponentialSeries.size());
    plan.SpectralRadius = 0.0;
    return;
  }
  plan.ExponentialSeries.clear();
  plan.SubSteps = mmv::DiffusionSubSteps(plan.CoarseMaxRate, settings);
  const double stiffness = plan.CoarseMaxRate * time / plan.SubSteps;
  plan.SweepsPerStep = mmv::ChebyshevSweeps(stiffness, settings);
  plan.SpectralRadius = mmv::JacobiSpectralRadius(stiffness);
}

//------------------------------------------------------------------------------
// ExchangeMask's depths from CoarseExchanges, in place while the diffusion
// grid keeps its size.
bool vtkIrradianceEstimator::vtkInternals::DiffusionPlan::UploadExchangeMask()
{
  const int* c = this->Coarse.Dimensions;
  GLint bound = 0;
  glGetIntegerv(GL_TEXTURE_BINDING_2D_ARRAY, &bound);
  const bool sameSize = this->ExchangeMask != 0 && this->ExchangeMaskDimensions[0] == c[0] &&
    this->ExchangeMaskDimensions[1] == c[1] && this->ExchangeMaskDimensions[2] == c[2];
  if (!this->ExchangeMask)
  {
    glGenTextures(1, &this->ExchangeMask);
  }
  glBindTexture(GL_TEXTURE_2D_ARRAY, this->ExchangeMask);
  if (sameSize)
  {
    glTexSubImage3D(GL_TEXTURE_2D_ARRAY, 0, 0, 0, 0, c[0], c[1], c[2], GL_DEPTH_COMPONENT, GL_FLOAT,
      this->CoarseExchanges.data());
  }
  else
  {
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_DEPTH_COMPONENT32F, c[0], c[1], c[2], 0,
      GL_DEPTH_COMPONENT, GL_FLOAT, this->CoarseExchanges.data());
    std::copy(c, c + 3, this->ExchangeMaskDimensions);
  }
  glBindTexture(GL_TEXTURE_2D_ARRAY, static_cast<GLuint>(bound));
  return glGetError() == GL_NO_ERROR;
}

//------------------------------------------------------------------------------
void vtkIrradianceEstimator::vtkInternals::DiffusionPlan::ReleaseScratch(vtkWindow* window)
{
  this->Series.ReleaseScratch();
  std::vector<float>().swap(this->Restricted);
  std::vector<float>().swap(this->Change);
  this->ReleaseScratchTextures(window);
}

void vtkIrradianceEstimator::vtkInternals::DiffusionPlan::ReleaseScratchTextures(vtkWindow* window)
{
  for (auto& texture : this->CoarseScratch)
  {
    if (texture)
    {
      texture->ReleaseGraphicsResources(window);
      texture = nullptr;
    }
  }
}

void vtkIrradianceEstimator::vtkInternals::DiffusionPlan::ReleaseTextures(vtkWindow* window)
{
  this->ReleaseScratchTextures(window);
  for (auto& texture : this->CoarseFacesTextures)
  {
    if (texture)
    {
      texture->ReleaseGraphicsResources(window);
      texture = nullptr;
    }
  }
  this->CoarseFacesChanged = true;
  if (this->ExchangeMask)
  {
    glDeleteTextures(1, &this->ExchangeMask);
    this->ExchangeMask = 0;
    this->ExchangeMaskHolds = false;
    std::fill(this->ExchangeMaskDimensions, this->ExchangeMaskDimensions + 3, 0);
  }
}

void vtkIrradianceEstimator::vtkInternals::DiffusionPlan::Release(vtkWindow* window)
{
  this->ReleaseScratch(window);
  this->ReleaseTextures(window);
}

//------------------------------------------------------------------------------
// Multiple scattering of FineScratch[0] into FineScratch[1]: restriction to
// the diffusion grid, the exponential's Chebyshev series (the default) or
// backward-Euler sub-steps each solved by Chebyshev-accelerated Jacobi sweeps
// (their number from the error bound, mmv::ChebyshevSweeps), then the
// prolongation of the change into the channels of `mask` (with `skipEmpty`,
// onto the occupied bricks alone: the final write reads nothing else), all
// on `plan`'s grid; the other channels keep what another plan wrote. Returns
// the passes drawn, or -1 on failure.
int vtkIrradianceEstimator::vtkInternals::Diffuse(
  vtkOpenGLRenderWindow* context, DiffusionPlan& plan, bool layered, int mask, bool skipEmpty)
{
  if (this->DiffusesOnCPU())
  {
    return this->DiffuseOnCPU(plan, mask, skipEmpty);
  }
  const bool exponential = !plan.ExponentialSeries.empty();
  vtkShaderProgram* restriction =
    this->Ready(context, this->RestrictQuad, mmvDiffusionGridFS, "#define MMV_RESTRICT\n", false);
  vtkShaderProgram* sweep = exponential
    ? this->Ready(
        context, this->ExponentialQuad, mmvDiffusionFS, "#define MMV_EXPONENTIAL\n", false)
    : this->Ready(context, this->SweepQuad, mmvDiffusionFS, "", false);
  vtkShaderProgram* changeProgram =
    this->Ready(context, this->ChangeQuad, mmvDiffusionFS, "#define MMV_CHANGE\n", false);
  vtkShaderProgram* prolong =
    this->Ready(context, this->ProlongQuad, mmvDiffusionGridFS, "", false);
  if (!restriction || !sweep || !changeProgram || !prolong)
  {
    return -1;
  }
  auto& coarse = plan.CoarseScratch;
  const int* blocks = DrawBox(plan.Blocks, plan.Coarse.Dimensions);
  {
    context->GetShaderCache()->ReadyShaderProgram(restriction);
    ScopedTextures bound{ this->FineScratch[0], this->ClassTexture };
    restriction->SetUniformi("fine", this->FineScratch[0]->GetTextureUnit());
    restriction->SetUniformi("classes", this->ClassTexture->GetTextureUnit());
    this->SetTransferUniforms(restriction, plan);
    // Only the blocks that exchange light read their restriction.
    this->DrawLayers(context, this->RestrictQuad, coarse[0], layered, blocks, 0xF, &plan);
  }

  int current = 0;
  const int sweeps = exponential
    ? this->ExponentialSweeps(context, plan, sweep, layered, current)
    : this->BackwardEulerSweeps(context, plan, sweep, layered, mask, current);

  const int change = current == 1 ? 2 : 1; // neither `before` nor `after`
  {
    context->GetShaderCache()->ReadyShaderProgram(changeProgram);
    SetDiffusionGridUniforms(changeProgram, plan);
    ScopedTextures bound{ coarse[current], coarse[0] };
    changeProgram->SetUniformi("current", coarse[current]->GetTextureUnit());
    changeProgram->SetUniformi("initial", coarse[0]->GetTextureUnit());
    this->DrawLayers(context, this->ChangeQuad, coarse[change], layered, blocks);
    ReleaseDiffusionGridTextures(plan);
  }
  context->GetShaderCache()->ReadyShaderProgram(prolong);
  ScopedTextures bound{ this->FineScratch[0], this->ClassTexture, coarse[change],
    plan.CoarseFacesTextures[1] };
  prolong->SetUniformi("change", coarse[change]->GetTextureUnit());
  prolong->SetUniformi("blocks", plan.CoarseFacesTextures[1]->GetTextureUnit());
  prolong->SetUniformi("fine", this->FineScratch[0]->GetTextureUnit());
  prolong->SetUniformi("classes", this->ClassTexture->GetTextureUnit());
  this->SetTransferUniforms(prolong, plan);
  // The final write reads the non-empty voxels alone (the occupied bricks').
  const mmv::IndexBox fine =
    skipEmpty ? this->OccupiedBox(this->Plan.Source, 1) : this->Plan.Source;
  if (!fine.IsEmpty())
  {
    this->DrawLayers(context, this->ProlongQuad, this->FineScratch[1], layered,
      DrawBox(fine, this->Grid.Dimensions), mask);
  }
  return sweeps;
}

//------------------------------------------------------------------------------
// The GPU passes' arithmetic (vtkBlockDiffusionSeries.h,
// vtkDiffusionGridTransfer.h) on the same blocks and voxels. FineOnCPU is
// diffused in place: the other plan's restriction reads its own channels
// alone, which this one's prolongation leaves as they were.
int vtkIrradianceEstimator::vtkInternals::DiffuseOnCPU(
  DiffusionPlan& plan, int mask, bool skipEmpty)
{
  const int channels = this->ScratchChannels()[&plan - this->Diffusions.data()];
  const int* d = plan.Coarse.Dimensions;
  const size_t values = static_cast<size_t>(channels) * d[0] * d[1] * d[2];
  plan.Restricted.resize(values);
  plan.Change.resize(values);
  const mmv::IndexBox fine =
    skipEmpty ? this->OccupiedBox(this->Plan.Source, 1) : this->Plan.Source;
  const mmv::IndexBox box = plan.ScatteringBox.Intersected(plan.Blocks);
  bool done = false;
  mmv::RunOnAllCores(
    [&]()
    {
      mmv::RestrictToDiffusionBlocks(this->Grid.Dimensions, this->FineOnCPU.data(),
        this->Classes.data(), plan.Coarse, channels, plan.Blocks.Bounds, plan.Restricted.data());
      done = plan.Series.Change(d, channels, plan.CoarseFaces[0].data(), plan.CoarseFaces[1].data(),
        box.Bounds, plan.ExponentialSeries, 1.0 / plan.CoarseMaxRate, plan.Restricted.data(),
        plan.Change.data());
      if (done && !fine.IsEmpty())
      {
        mmv::ProlongDiffusionChange(this->Grid.Dimensions, this->FineOnCPU.data(),
          this->Classes.data(), plan.Coarse, channels, plan.Change.data(),
          plan.CoarseFaces[1].data(), mask, fine.Bounds, this->FineOnCPU.data());
      }
    });
  this->DiffusionRanOnCPU = this->DiffusionRanOnCPU || done;
  return done ? static_cast<int>(plan.ExponentialSeries.size()) : -1;
}

bool vtkIrradianceEstimator::vtkInternals::ReadFineScratch()
{
  const int* d = this->Grid.Dimensions;
  this->FineOnCPU.resize(4 * static_cast<size_t>(d[0]) * d[1] * d[2]);
  GLint alignment = 4;
  glGetIntegerv(GL_PACK_ALIGNMENT, &alignment);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  this->FineScratch[0]->Activate();
  glGetTexImage(GL_TEXTURE_3D, 0, GL_RGBA, GL_FLOAT, this->FineOnCPU.data());
  this->FineScratch[0]->Deactivate();
  glPixelStorei(GL_PACK_ALIGNMENT, alignment);
  return glGetError() == GL_NO_ERROR;
}

bool vtkIrradianceEstimator::vtkInternals::UploadDiffusedFine()
{
  mmv::UploadTextureBox(this->FineScratch[1], nullptr, GL_RGBA, GL_FLOAT, this->FineOnCPU.data());
  return glGetError() == GL_NO_ERROR;
}

//------------------------------------------------------------------------------
// The uniforms of the transfers between the irradiance and diffusion grids.
void vtkIrradianceEstimator::vtkInternals::SetTransferUniforms(
  vtkShaderProgram* program, const DiffusionPlan& plan) const
{
  program->SetUniform1iv("dims", 3, this->Grid.Dimensions);
  program->SetUniform1iv("factor", 3, plan.Coarse.Factor);
  program->SetUniform1iv("coarseDims", 3, plan.Coarse.Dimensions);
}

//------------------------------------------------------------------------------
// The diffusion grid's block textures (activated here, deactivated by the
// caller) and dimensions, for the sweeps and the exponential's steps.
void vtkIrradianceEstimator::vtkInternals::SetDiffusionGridUniforms(
  vtkShaderProgram* program, const DiffusionPlan& plan)
{
  for (const auto& texture : plan.CoarseFacesTextures)
  {
    texture->Activate();
  }
  program->SetUniformi("facesXY", plan.CoarseFacesTextures[0]->GetTextureUnit());
  program->SetUniformi("facesZ", plan.CoarseFacesTextures[1]->GetTextureUnit());
  program->SetUniform1iv("dims", 3, plan.Coarse.Dimensions);
}

void vtkIrradianceEstimator::vtkInternals::ReleaseDiffusionGridTextures(const DiffusionPlan& plan)
{
  for (const auto& texture : plan.CoarseFacesTextures)
  {
    texture->Deactivate();
  }
}

//------------------------------------------------------------------------------
// Backward-Euler sub-steps on the diffusion grid, each solved by Chebyshev-
// accelerated Jacobi sweeps; `current` receives the texture of the result.
int vtkIrradianceEstimator::vtkInternals::BackwardEulerSweeps(vtkOpenGLRenderWindow* context,
  DiffusionPlan& plan, vtkShaderProgram* sweep, bool layered, int mask, int& current)
{
  auto& coarse = plan.CoarseScratch;
  context->GetShaderCache()->ReadyShaderProgram(sweep);
  SetDiffusionGridUniforms(sweep, plan);
  sweep->SetUniformf("dt", static_cast<float>(this->Diffusion.Time / plan.SubSteps));
  // Stop on the residual: |J(x) - x| <= (1 - rho) tol everywhere bounds the
  // error by tol; checked every few sweeps, the error bound's count at most.
  const float threshold =
    static_cast<float>((1.0 - plan.SpectralRadius) * this->Diffusion.SweepTolerance);
  const int checkInterval =
    plan.SweepsPerStep >= ResidualCheckMinimumSweeps ? plan.SweepsPerStep / 4 : plan.SweepsPerStep;
  sweep->SetUniformf("residualThreshold", 0.0f);
  // Only the lights being updated decide convergence: the scratch's other
  // channels hold whatever the GPU left there.
  const int residualChannels[4] = { (mask & 1) != 0, (mask & 2) != 0, (mask & 4) != 0,
    (mask & 8) != 0 };
  glUniform4iv(sweep->FindUniform("residualChannels"), 1, residualChannels);
  // Blocks outside ScatteringBox never change and are never read; of the
  // rest, those the region depends on.
  const mmv::IndexBox box = plan.ScatteringBox.Intersected(plan.Blocks);
  int rhs = 0;
  current = 0;
  int sweeps = 0;
  for (int step = 0; step < plan.SubSteps; ++step)
  {
    int previous = current;
    for (int k = 1; k <= plan.SweepsPerStep; ++k)
    {
      int next = 1;
      while (next == rhs || next == current || next == previous)
      {
        ++next;
      }
      {
        ScopedTextures bound{ coarse[rhs], coarse[current], coarse[previous] };
        sweep->SetUniformi("rhs", coarse[rhs]->GetTextureUnit());
        sweep->SetUniformi("current", coarse[current]->GetTextureUnit());
        sweep->SetUniformi("previous", coarse[previous]->GetTextureUnit());
        sweep->SetUniformf(
          "omega", static_cast<float>(mmv::ChebyshevWeight(k, plan.SpectralRadius)));
        this->DrawLayers(context, this->SweepQuad, coarse[next], layered, box.Bounds, 0xF, &plan);
      }
      ++sweeps;
      previous = current;
      current = next;
      if (k % checkInterval == 0 && k < plan.SweepsPerStep)
      {
        // The check draws into a texture no iterate lives in.
        int scratch = 1;
        while (scratch == rhs || scratch == current || scratch == previous)
        {
          ++scratch;
        }
        // The iterate just drawn, against the same right-hand side.
        ScopedTextures bound{ coarse[rhs], coarse[current] };
        sweep->SetUniformi("rhs", coarse[rhs]->GetTextureUnit());
        sweep->SetUniformi("current", coarse[current]->GetTextureUnit());
        sweep->SetUniformi("previous", coarse[current]->GetTextureUnit());
        sweep->SetUniformf("residualThreshold", threshold);
        const unsigned int unconverged =
          this->CountWrites(context, this->SweepQuad, coarse[scratch], layered, box.Bounds);
        context->GetShaderCache()->ReadyShaderProgram(sweep);
        sweep->SetUniformf("residualThreshold", 0.0f);
        if (unconverged == 0)
        {
          break;
        }
      }
    }
    rhs = current;
  }
  ReleaseDiffusionGridTextures(plan);
  return sweeps;
}

//------------------------------------------------------------------------------
// The exponential's Chebyshev series on the diffusion grid by the Clenshaw
// recurrence (Shaders/mmvDiffusionFS.glsl, MMV_EXPONENTIAL): b_k = c_k u0 +
// 2 B b_k+1 - b_k+2 from k = n down to 1, then c_0 u0 + B b_1 - b_2; u0 is
// the restricted irradiance (texture 0). `current` receives the result.
int vtkIrradianceEstimator::vtkInternals::ExponentialSweeps(vtkOpenGLRenderWindow* context,
  DiffusionPlan& plan, vtkShaderProgram* sweep, bool layered, int& current)
{
  auto& coarse = plan.CoarseScratch;
  context->GetShaderCache()->ReadyShaderProgram(sweep);
  SetDiffusionGridUniforms(sweep, plan);
  sweep->SetUniformf("invRate", static_cast<float>(1.0 / plan.CoarseMaxRate));
  const std::vector<double>& c = plan.ExponentialSeries;
  const int n = static_cast<int>(c.size()) - 1;
  // As in BackwardEulerSweeps: the scattering blocks the region depends on.
  const mmv::IndexBox box = plan.ScatteringBox.Intersected(plan.Blocks);
  // b_n+1 = b_n+2 = 0: their weights are 0 and texture 0 stands in for them.
  current = 0;
  int previous = 0;
  int passes = 0;
  for (int k = n; k >= 0; --k)
  {
    int next = 1;
    while (next == current || next == previous)
    {
      ++next;
    }
    ScopedTextures bound{ coarse[0], coarse[current], coarse[previous] };
    sweep->SetUniformi("initial", coarse[0]->GetTextureUnit());
    sweep->SetUniformi("current", coarse[current]->GetTextureUnit());
    sweep->SetUniformi("previous", coarse[previous]->GetTextureUnit());
    sweep->SetUniformf("alpha", static_cast<float>(c[k]));
    sweep->SetUniformf("beta", k == n ? 0.0f : (k == 0 ? 1.0f : 2.0f));
    sweep->SetUniformf("gammaWeight", k >= n - 1 ? 0.0f : -1.0f);
    this->DrawLayers(context, this->ExponentialQuad, coarse[next], layered, box.Bounds, 0xF, &plan);
    ++passes;
    previous = current;
    current = next;
  }
  ReleaseDiffusionGridTextures(plan);
  return passes;
}
