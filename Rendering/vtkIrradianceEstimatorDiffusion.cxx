// vtkIrradianceEstimator: multiple scattering, the diffusion of the
// transmittance on the diffusion grid.
#include "vtkIrradianceEstimatorInternals.h"

#include "mmvDiffusionFS.h"
#include "mmvDiffusionGridFS.h"

using namespace mmv::voxelpass;

//------------------------------------------------------------------------------
// The diffusion grid and how long its solve runs, exactly as the CPU's
// mmv::DiffuseIrradianceOnDiffusionGrid plans them. The strengths come from
// the CPU's classes: classified here where the diffusion will run
// (NeedsCPUClasses). Otherwise no voxel has a strength the diffusion would
// use (it is off, or the table has no s > 0), and the plan is the one for
// zero strength everywhere, made without touching the voxels.
void vtkIrradianceEstimator::vtkInternals::PlanDiffusion(
  double time, bool exponential, bool multipleScattering)
{
  this->Diffusion.Exponential = exponential;
  this->Diffusion.Time = time;
  if (!this->ClassesOnCPU && this->NeedsCPUClasses(multipleScattering, time))
  {
    this->Classify();
  }
  std::vector<float> strength;
  float maxStrength = 0.0f;
  if (this->ClassesOnCPU)
  {
    strength.resize(this->Classes.size());
    for (size_t v = 0; v < strength.size(); ++v)
    {
      strength[v] = std::max(0.0f, this->Classes[v]);
      maxStrength = std::max(maxStrength, strength[v]);
    }
  }
  const double spacing[3] = { this->Grid.DataVoxelsPerVoxel[0], this->Grid.DataVoxelsPerVoxel[1],
    this->Grid.DataVoxelsPerVoxel[2] };
  this->Coarse =
    mmv::PlanDiffusionGrid(this->Grid.Dimensions, spacing, maxStrength, this->Diffusion);
  if (!this->ClassesOnCPU)
  {
    // Nothing the diffusion would use scatters (NeedsCPUClasses), so none
    // runs: one block stands for the grid, not a plan and a texture of the
    // irradiance grid's size at every opacity edit and time step.
    for (int a = 0; a < 3; ++a)
    {
      const int factor = std::max(1, this->Grid.Dimensions[a]);
      this->Coarse.Spacing[a] = this->Coarse.Spacing[a] / this->Coarse.Factor[a] * factor;
      this->Coarse.Factor[a] = factor;
      this->Coarse.Dimensions[a] = 1;
    }
  }
  std::vector<float> coarseStrength;
  std::vector<float> capacity;
  if (this->ClassesOnCPU)
  {
    mmv::RestrictToDiffusionGrid(this->Grid.Dimensions, this->Coarse, strength.data(), nullptr,
      &coarseStrength, nullptr, &capacity);
  }
  else
  {
    // What the restriction of zero strength gives.
    coarseStrength.assign(this->Coarse.GetNumberOfVoxels(), 0.0f);
    capacity.assign(this->Coarse.GetNumberOfVoxels(), 0.0f);
  }
  this->CoarseMaxRate = time > 0.0 ? mmv::MaxDiffusionRate(this->Coarse.Dimensions,
                                       this->Coarse.Spacing, coarseStrength.data(), capacity.data())
                                   : 0.0;
  // Two RGBA texels per block (face coefficients, capacity, whether it
  // scatters); and the box of the blocks that scatter, the only ones the
  // sweeps change.
  mmv::DiffusionBlockTexels(this->Coarse.Dimensions, this->Coarse.Spacing, coarseStrength.data(),
    capacity.data(), this->CoarseFaces[0], this->CoarseFaces[1], this->CoarseExchanges);
  this->CoarseFacesChanged = true;
  const int* cd = this->Coarse.Dimensions;
  int* box = this->ScatteringBox.Bounds;
  for (int a = 0; a < 3; ++a)
  {
    box[2 * a] = cd[a] - 1;
    box[2 * a + 1] = 0;
  }
  for (size_t c = 0; c < coarseStrength.size(); ++c)
  {
    if (coarseStrength[c] > 0.0f)
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
  if (this->Diffusion.Exponential)
  {
    // One "sub-step" of as many passes as the series has terms. A quarter of
    // the sweeps' tolerance: the result is stored in 16 bits as well, and the
    // two errors together stay below the sweeps' (1e-3 of the largest
    // irradiance) for two or three more terms.
    this->ExponentialSeries = mmv::ExponentialChebyshevCoefficients(
      this->CoarseMaxRate * time, 0.25 * this->Diffusion.SweepTolerance);
    this->SubSteps = this->ExponentialSeries.empty() ? 0 : 1;
    this->SweepsPerStep = static_cast<int>(this->ExponentialSeries.size());
    this->SpectralRadius = 0.0;
    return;
  }
  this->ExponentialSeries.clear();
  this->SubSteps = mmv::DiffusionSubSteps(this->CoarseMaxRate, this->Diffusion);
  const double stiffness = this->CoarseMaxRate * time / this->SubSteps;
  this->SweepsPerStep = mmv::ChebyshevSweeps(stiffness, this->Diffusion);
  this->SpectralRadius = mmv::JacobiSpectralRadius(stiffness);
}

//------------------------------------------------------------------------------
// ExchangeMask's depths from CoarseExchanges, in place while the diffusion
// grid keeps its size.
bool vtkIrradianceEstimator::vtkInternals::UploadExchangeMask()
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
// Multiple scattering of FineScratch[0] into FineScratch[1]: restriction to
// the diffusion grid, the exponential's Chebyshev series (the default) or
// backward-Euler sub-steps each solved by Chebyshev-accelerated Jacobi sweeps
// (their number from the error bound, mmv::ChebyshevSweeps), then the
// prolongation of the change (with `skipEmpty`, onto the occupied bricks
// alone: the final write reads nothing else). Returns the passes drawn, or
// -1 on failure.
int vtkIrradianceEstimator::vtkInternals::Diffuse(
  vtkOpenGLRenderWindow* context, bool layered, int mask, bool skipEmpty)
{
  const bool exponential = !this->ExponentialSeries.empty();
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
  auto& coarse = this->CoarseScratch;
  {
    context->GetShaderCache()->ReadyShaderProgram(restriction);
    ScopedTextures bound{ this->FineScratch[0], this->ClassTexture };
    restriction->SetUniformi("fine", this->FineScratch[0]->GetTextureUnit());
    restriction->SetUniformi("classes", this->ClassTexture->GetTextureUnit());
    this->SetTransferUniforms(restriction);
    // Only the blocks that exchange light read their restriction.
    this->DrawLayers(context, this->RestrictQuad, coarse[0], layered,
      DrawBox(this->Plan.Coarse, this->Coarse.Dimensions), 0xF, true);
  }

  int current = 0;
  const int sweeps = exponential
    ? this->ExponentialSweeps(context, sweep, layered, current)
    : this->BackwardEulerSweeps(context, sweep, layered, mask, current);

  const int change = current == 1 ? 2 : 1; // neither `before` nor `after`
  {
    context->GetShaderCache()->ReadyShaderProgram(changeProgram);
    this->SetDiffusionGridUniforms(changeProgram);
    ScopedTextures bound{ coarse[current], coarse[0] };
    changeProgram->SetUniformi("current", coarse[current]->GetTextureUnit());
    changeProgram->SetUniformi("initial", coarse[0]->GetTextureUnit());
    this->DrawLayers(context, this->ChangeQuad, coarse[change], layered,
      DrawBox(this->Plan.Coarse, this->Coarse.Dimensions));
    this->ReleaseDiffusionGridTextures();
  }
  context->GetShaderCache()->ReadyShaderProgram(prolong);
  ScopedTextures bound{ this->FineScratch[0], this->ClassTexture, coarse[change],
    this->CoarseFacesTextures[1] };
  prolong->SetUniformi("change", coarse[change]->GetTextureUnit());
  prolong->SetUniformi("blocks", this->CoarseFacesTextures[1]->GetTextureUnit());
  prolong->SetUniformi("fine", this->FineScratch[0]->GetTextureUnit());
  prolong->SetUniformi("classes", this->ClassTexture->GetTextureUnit());
  this->SetTransferUniforms(prolong);
  // The final write reads the non-empty voxels alone (the occupied bricks').
  const mmv::IndexBox fine =
    skipEmpty ? this->OccupiedBox(this->Plan.Source, 1) : this->Plan.Source;
  if (!fine.IsEmpty())
  {
    this->DrawLayers(context, this->ProlongQuad, this->FineScratch[1], layered,
      DrawBox(fine, this->Grid.Dimensions));
  }
  return sweeps;
}

//------------------------------------------------------------------------------
// The diffusion grid's block textures (activated here, deactivated by the
// caller) and dimensions, for the sweeps and the exponential's steps.
void vtkIrradianceEstimator::vtkInternals::SetDiffusionGridUniforms(vtkShaderProgram* program)
{
  for (auto& texture : this->CoarseFacesTextures)
  {
    texture->Activate();
  }
  program->SetUniformi("facesXY", this->CoarseFacesTextures[0]->GetTextureUnit());
  program->SetUniformi("facesZ", this->CoarseFacesTextures[1]->GetTextureUnit());
  program->SetUniform1iv("dims", 3, this->Coarse.Dimensions);
}

void vtkIrradianceEstimator::vtkInternals::ReleaseDiffusionGridTextures()
{
  for (auto& texture : this->CoarseFacesTextures)
  {
    texture->Deactivate();
  }
}

//------------------------------------------------------------------------------
// Backward-Euler sub-steps on the diffusion grid, each solved by Chebyshev-
// accelerated Jacobi sweeps; `current` receives the texture of the result.
int vtkIrradianceEstimator::vtkInternals::BackwardEulerSweeps(
  vtkOpenGLRenderWindow* context, vtkShaderProgram* sweep, bool layered, int mask, int& current)
{
  auto& coarse = this->CoarseScratch;
  context->GetShaderCache()->ReadyShaderProgram(sweep);
  this->SetDiffusionGridUniforms(sweep);
  sweep->SetUniformf("dt", static_cast<float>(this->Diffusion.Time / this->SubSteps));
  // Stop on the residual: |J(x) - x| <= (1 - rho) tol everywhere bounds the
  // error by tol; checked every few sweeps, the error bound's count at most.
  const float threshold =
    static_cast<float>((1.0 - this->SpectralRadius) * this->Diffusion.SweepTolerance);
  const int checkInterval = this->SweepsPerStep >= ResidualCheckMinimumSweeps
    ? this->SweepsPerStep / 4
    : this->SweepsPerStep;
  sweep->SetUniformf("residualThreshold", 0.0f);
  // Only the lights being updated decide convergence: the scratch's other
  // channels hold whatever the GPU left there.
  const int residualChannels[4] = { (mask & 1) != 0, (mask & 2) != 0, (mask & 4) != 0,
    (mask & 8) != 0 };
  glUniform4iv(sweep->FindUniform("residualChannels"), 1, residualChannels);
  // Blocks outside ScatteringBox never change and are never read; of the
  // rest, those the region depends on.
  const mmv::IndexBox box = this->ScatteringBox.Intersected(this->Plan.Coarse);
  int rhs = 0;
  current = 0;
  int sweeps = 0;
  for (int step = 0; step < this->SubSteps; ++step)
  {
    int previous = current;
    for (int k = 1; k <= this->SweepsPerStep; ++k)
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
          "omega", static_cast<float>(mmv::ChebyshevWeight(k, this->SpectralRadius)));
        this->DrawLayers(context, this->SweepQuad, coarse[next], layered, box.Bounds, 0xF, true);
      }
      ++sweeps;
      previous = current;
      current = next;
      if (k % checkInterval == 0 && k < this->SweepsPerStep)
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
  this->ReleaseDiffusionGridTextures();
  return sweeps;
}

//------------------------------------------------------------------------------
// The exponential's Chebyshev series on the diffusion grid by the Clenshaw
// recurrence (Shaders/mmvDiffusionFS.glsl, MMV_EXPONENTIAL): b_k = c_k u0 +
// 2 B b_k+1 - b_k+2 from k = n down to 1, then c_0 u0 + B b_1 - b_2; u0 is
// the restricted irradiance (texture 0). `current` receives the result.
int vtkIrradianceEstimator::vtkInternals::ExponentialSweeps(
  vtkOpenGLRenderWindow* context, vtkShaderProgram* sweep, bool layered, int& current)
{
  auto& coarse = this->CoarseScratch;
  context->GetShaderCache()->ReadyShaderProgram(sweep);
  this->SetDiffusionGridUniforms(sweep);
  sweep->SetUniformf("invRate", static_cast<float>(1.0 / this->CoarseMaxRate));
  const std::vector<double>& c = this->ExponentialSeries;
  const int n = static_cast<int>(c.size()) - 1;
  // As in BackwardEulerSweeps: the scattering blocks the region depends on.
  const mmv::IndexBox box = this->ScatteringBox.Intersected(this->Plan.Coarse);
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
    this->DrawLayers(context, this->ExponentialQuad, coarse[next], layered, box.Bounds, 0xF, true);
    ++passes;
    previous = current;
    current = next;
  }
  this->ReleaseDiffusionGridTextures();
  return passes;
}
