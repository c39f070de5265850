// vtkIrradianceVolumePass: the transmittance toward each light (full and
// piecewise shadow rays) and the tints of a non-white transmission colour.
#include "vtkIrradianceVolumePassInternals.h"

#include "mmvIrradianceFS.h"
#include "mmvIrradianceTintFS.h"
#include "mmvPiecewiseShadowFS.h"
#include "mmvShadowRay.h"

using namespace mmv::voxelpass;

//------------------------------------------------------------------------------
// The uniforms of the transfers between the irradiance and diffusion grids.
void vtkIrradianceVolumePass::vtkInternals::SetTransferUniforms(vtkShaderProgram* program) const
{
  program->SetUniform1iv("dims", 3, this->Grid.Dimensions);
  program->SetUniform1iv("factor", 3, this->Coarse.Factor);
  program->SetUniform1iv("coarseDims", 3, this->Coarse.Dimensions);
}

//------------------------------------------------------------------------------
// The shadow rays' constants, and MMV_CUTAWAY while something is cut: without
// it the cutaway test compiles away (Shaders/mmvCutaway.glsl).
std::string vtkIrradianceVolumePass::vtkInternals::ShadowRayDefines() const
{
  return mmv::ShadowRayGLSLPrelude() + (this->Cut.IsEmpty() ? "" : mmv::CutawayGLSLDefine);
}

//------------------------------------------------------------------------------
// The uniforms of Shaders/mmvShadowRay.glsl (and the class texture), shared by
// the full and the piecewise shadow rays; their textures must be active.
void vtkIrradianceVolumePass::vtkInternals::SetShadowRayUniforms(vtkShaderProgram* program) const
{
  glm::mat3 toIndex(this->Grid.PhysicalToIndexMatrix());
  program->SetUniformi("scalars", this->ScalarTexture->GetTextureUnit());
  program->SetUniformi("classes", this->ClassTexture->GetTextureUnit());
  program->SetUniformi("shadowTable", this->TableTexture->GetTextureUnit());
  program->SetUniformf("tableSize", static_cast<float>(this->TableSize));
  program->SetUniform1iv("dims", 3, this->Grid.Dimensions);
  program->SetUniformMatrix3x3("worldToIndex", glm::value_ptr(toIndex));
  program->SetUniformf("stepLength", static_cast<float>(this->StepLength));
  if (!this->Cut.IsEmpty())
  {
    ::SetCutawayUniforms(program, mmv::ToIndexSpace(this->Cut, this->Grid));
  }
}

//------------------------------------------------------------------------------
bool vtkIrradianceVolumePass::vtkInternals::ShadowPass(
  vtkOpenGLRenderWindow* context, int group, int mask, bool skipEmpty, bool layered)
{
  vtkShaderProgram* program = this->Ready(context, this->ShadowQuad,
    std::string(mmvShadowRay) + mmvIrradianceFS, this->ShadowRayDefines(), true);
  if (!program)
  {
    return false;
  }
  glm::mat3 toWorld(this->Grid.IndexToPhysicalMatrix());
  const glm::vec3 origin(this->Grid.Origin);
  ScopedTextures bound{ this->ScalarTexture, this->ClassTexture, this->TableTexture };
  this->SetShadowRayUniforms(program);
  program->SetUniform3f("origin", glm::value_ptr(origin));
  program->SetUniformMatrix3x3("indexToWorld", glm::value_ptr(toWorld));
  program->SetUniformi("computeEmptyVoxels", skipEmpty ? 0 : 1);
  SetLightUniforms(program, this->Lights, group * LightsPerTexture, mask);
  const mmv::IndexBox& box = this->Plan.Estimated;
  this->DrawLayers(
    context, this->ShadowQuad, this->FineScratch[0], layered, DrawBox(box, this->Grid.Dimensions));
  for (int l = 0; l < LightsPerTexture; ++l)
  {
    this->EstimatedVoxels += (mask & (1 << l)) != 0 ? box.GetNumberOfVoxels() : 0;
  }
  return true;
}

//------------------------------------------------------------------------------
// The tint of light `light` into its tint texture (mmvIrradianceTintFS.glsl):
// full shadow rays of the selective extinction from every tint voxel.
bool vtkIrradianceVolumePass::vtkInternals::TintPass(
  vtkOpenGLRenderWindow* context, int light, bool layered)
{
  vtkShaderProgram* program = this->Ready(context, this->TintQuad,
    std::string(mmvShadowRay) + mmvIrradianceTintFS, this->ShadowRayDefines() + "#define MMV_TINT\n",
    true);
  if (!program)
  {
    return false;
  }
  int tintDims[3];
  this->TintDimensions(tintDims);
  float tintToIndex[3];
  for (int a = 0; a < 3; ++a)
  {
    tintToIndex[a] = tintDims[a] > 1
      ? static_cast<float>(this->Grid.Dimensions[a] - 1) / static_cast<float>(tintDims[a] - 1)
      : 0.0f;
  }
  glm::mat3 toWorld(this->Grid.IndexToPhysicalMatrix());
  const glm::vec3 origin(this->Grid.Origin);
  ScopedTextures bound{ this->ScalarTexture, this->ClassTexture, this->TableTexture,
    this->TintTableTexture };
  this->SetShadowRayUniforms(program);
  program->SetUniformi("tintTable", this->TintTableTexture->GetTextureUnit());
  program->SetUniform1iv("tintDims", 3, tintDims);
  program->SetUniform3f("tintToIndex", tintToIndex);
  program->SetUniform3f("origin", glm::value_ptr(origin));
  program->SetUniformMatrix3x3("indexToWorld", glm::value_ptr(toWorld));
  SetLightUniforms(program, this->Lights, light, 1);
  const mmv::IndexBox box =
    mmv::ResampledBox(this->Plan.Region, this->Grid.Dimensions, tintDims);
  this->DrawLayers(context, this->TintQuad, this->Tint[light], layered, DrawBox(box, tintDims));
  return true;
}

//------------------------------------------------------------------------------
// Piecewise shadow rays of directional light `light` into its channel of
// FineScratch[0] (vtkShadowSweep.h): one draw per chunk of slices, nearest
// the light first; a texture barrier lets each chunk read what the earlier
// ones wrote into the same texture.
bool vtkIrradianceVolumePass::vtkInternals::PiecewiseShadowPass(vtkOpenGLRenderWindow* context,
  int light, int slicesPerChunk, bool skipEmpty, bool layered)
{
  vtkShaderProgram* program = this->Ready(context, this->PiecewiseQuad,
    std::string(mmvShadowRay) + mmvPiecewiseShadowFS, this->ShadowRayDefines(), false);
  if (!program)
  {
    return false;
  }
  const mmv::LightSource& source = this->Lights[light];
  const int* d = this->Grid.Dimensions;
  const glm::dvec3 toLightIndex = this->Grid.PhysicalToIndexMatrix() * source.ToLight;
  const mmv::ShadowSweep sweep = mmv::PlanShadowSweep(d, toLightIndex, slicesPerChunk);
  // Each chunk draws what the region's voxels depend on (its whole slab
  // for the whole grid).
  const std::vector<mmv::IndexBox> boxes =
    mmv::PlanSweepBoxes(sweep, d, toLightIndex, this->Plan.Estimated);
  glm::vec3 toLight(source.ToLight);
  const int channel = light % LightsPerTexture;
  vtkTextureObject* target = this->FineScratch[0];
  ScopedTextures bound{ this->ScalarTexture, this->ClassTexture, this->TableTexture, target };
  this->SetShadowRayUniforms(program);
  program->SetUniformi("transmittance", target->GetTextureUnit());
  program->SetUniform3f("toLight", glm::value_ptr(toLight));
  program->SetUniformi("channel", channel);
  program->SetUniformi("computeEmptyVoxels", skipEmpty ? 0 : 1);
  program->SetUniformi("sweepAxis", sweep.Axis);
  for (int chunk = 0; chunk < sweep.GetNumberOfChunks(); ++chunk)
  {
    const mmv::IndexBox& box = boxes[chunk];
    if (box.IsEmpty())
    {
      continue;
    }
    int first, last, plane;
    sweep.GetChunk(chunk, first, last, plane);
    this->EstimatedVoxels += box.GetNumberOfVoxels();
    program->SetUniformi("sweepPlane", plane);
    program->SetUniformi("readSlice", sweep.GetReadSlice(chunk));
    // The earlier chunks' writes become visible to this draw's fetches.
    // (A compute dispatch ends with a memory barrier instead.)
    if (!this->Compute)
    {
      glTextureBarrier();
    }
    // The write mask keeps the other lights' channels.
    this->DrawLayers(context, this->PiecewiseQuad, target, layered, box.Bounds, 1 << channel);
  }
  return true;
}
