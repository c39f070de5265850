// vtkIrradianceEstimator: the transmittance toward each light (full and
// piecewise shadow rays) and the tints of a non-white transmission colour.
#include "vtkIrradianceEstimatorInternals.h"

#include "mmvIrradianceFS.h"
#include "mmvIrradianceTintFS.h"
#include "mmvLightGrid.h"
#include "mmvLightGridUpsampleFS.h"
#include "mmvPiecewiseShadowFS.h"
#include "mmvShadowRay.h"
#include "vtkMultiMaterialThreads.h"
#include "vtkSweptTransmittance.h"
#include "vtkTextureCopy.h"

using namespace mmv::voxelpass;

//------------------------------------------------------------------------------
// The shadow rays' constants, and MMV_CUTAWAY while something is cut: without
// it the cutaway test compiles away (Shaders/mmvCutaway.glsl).
std::string vtkIrradianceEstimator::vtkInternals::ShadowRayDefines() const
{
  return mmv::ShadowRayGLSLPrelude() + (this->Cut.IsEmpty() ? "" : mmv::CutawayGLSLDefine);
}

//------------------------------------------------------------------------------
// The uniforms of Shaders/mmvShadowRay.glsl (and the class texture), shared by
// the full and the piecewise shadow rays; their textures must be active.
void vtkIrradianceEstimator::vtkInternals::SetShadowRayUniforms(vtkShaderProgram* program) const
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
void vtkIrradianceEstimator::vtkInternals::LightGridDimensions(int stride, int dims[3]) const
{
  for (int a = 0; a < 3; ++a)
  {
    dims[a] = mmv::LightGridDimension(this->Grid.Dimensions[a], stride);
  }
}

void vtkIrradianceEstimator::vtkInternals::LightGridRatio(int stride, double ratio[3]) const
{
  int dims[3];
  this->LightGridDimensions(stride, dims);
  for (int a = 0; a < 3; ++a)
  {
    const int n = this->Grid.Dimensions[a];
    ratio[a] = n > 1 ? static_cast<double>(dims[a] - 1) / (n - 1) : 1.0;
  }
}

glm::dmat3 vtkIrradianceEstimator::vtkInternals::LightGridPhysicalToIndex(int stride) const
{
  double ratio[3];
  this->LightGridRatio(stride, ratio);
  const glm::dmat3 scale(
    glm::dvec3(ratio[0], 0.0, 0.0), glm::dvec3(0.0, ratio[1], 0.0), glm::dvec3(0.0, 0.0, ratio[2]));
  return scale * this->Grid.PhysicalToIndexMatrix();
}

vtkTextureObject* vtkIrradianceEstimator::vtkInternals::LightGridTarget(int stride) const
{
  return stride > 1 ? this->LightGridScratch.Get() : this->FineScratch[0].Get();
}

// (On the irradiance grid the shaders read `classes` instead; any texture
// serves the unused sampler.)
vtkTextureObject* vtkIrradianceEstimator::vtkInternals::LightGridClasses(int stride) const
{
  return stride > 1 ? this->LightGridClassTexture.Get() : this->ClassTexture.Get();
}

int vtkIrradianceEstimator::vtkInternals::MaxLightGridStride() const
{
  int stride = 1;
  for (const mmv::LightSource& light : this->Lights)
  {
    stride = std::max(stride, light.GridStride);
  }
  return stride;
}

void vtkIrradianceEstimator::vtkInternals::SetLightGridUniforms(
  vtkShaderProgram* program, int stride) const
{
  int dims[3];
  this->LightGridDimensions(stride, dims);
  double ratio[3];
  this->LightGridRatio(stride, ratio);
  const float toIndex[3] = { static_cast<float>(1.0 / ratio[0]), static_cast<float>(1.0 / ratio[1]),
    static_cast<float>(1.0 / ratio[2]) };
  program->SetUniform1iv("targetDims", 3, dims);
  program->SetUniform3f("targetToIndex", toIndex);
  program->SetUniformi("strided", stride > 1 ? 1 : 0);
  program->SetUniformi("lightGridClasses", this->LightGridClasses(stride)->GetTextureUnit());
}

//------------------------------------------------------------------------------
mmv::IndexBox vtkIrradianceEstimator::vtkInternals::OccupiedBox(
  const mmv::IndexBox& box, int stride) const
{
  if (stride <= 1)
  {
    return this->Occupancy.Shrink(box);
  }
  // The irradiance voxels whose interpolation may read the box's points
  // (point p is read by voxels whose point below is p - 1 or p), one more
  // on each side; then the points around the non-empty ones among them.
  const int* d = this->Grid.Dimensions;
  int dims[3];
  this->LightGridDimensions(stride, dims);
  double ratio[3];
  this->LightGridRatio(stride, ratio);
  mmv::IndexBox voxels;
  for (int a = 0; a < 3; ++a)
  {
    const double r = ratio[a] > 0.0 ? ratio[a] : 1.0;
    voxels.Bounds[2 * a] =
      std::max(0, static_cast<int>(std::floor((box.Bounds[2 * a] - 1) / r)) - 1);
    voxels.Bounds[2 * a + 1] =
      std::min(d[a] - 1, static_cast<int>(std::ceil((box.Bounds[2 * a + 1] + 1) / r)) + 1);
  }
  return mmv::ResampledBox(this->Occupancy.Shrink(voxels), d, dims).Intersected(box);
}

//------------------------------------------------------------------------------
// Full shadow rays of the lights of `mask` whose grid stride is `stride`,
// into their channels of that grid's target.
bool vtkIrradianceEstimator::vtkInternals::ShadowPass(
  vtkOpenGLRenderWindow* context, int group, int mask, int stride, bool skipEmpty, bool layered)
{
  vtkShaderProgram* program = this->Ready(context, this->ShadowQuad,
    std::string(mmvShadowRay) + mmvLightGrid + mmvIrradianceFS, this->ShadowRayDefines(), true);
  if (!program)
  {
    return false;
  }
  glm::mat3 toWorld(this->Grid.IndexToPhysicalMatrix());
  const glm::vec3 origin(this->Grid.Origin);
  ScopedTextures bound{ this->ScalarTexture, this->ClassTexture, this->TableTexture,
    this->LightGridClasses(stride) };
  this->SetShadowRayUniforms(program);
  this->SetLightGridUniforms(program, stride);
  program->SetUniform3f("origin", glm::value_ptr(origin));
  program->SetUniformMatrix3x3("indexToWorld", glm::value_ptr(toWorld));
  program->SetUniformi("computeEmptyVoxels", skipEmpty ? 0 : 1);
  SetLightUniforms(program, this->Lights, group * LightsPerTexture, mask);
  int dims[3];
  this->LightGridDimensions(stride, dims);
  const mmv::IndexBox estimated = this->EstimatedOnLightGrid(stride);
  const mmv::IndexBox box = skipEmpty ? this->OccupiedBox(estimated, stride) : estimated;
  this->DrawLayers(
    context, this->ShadowQuad, this->LightGridTarget(stride), layered, DrawBox(box, dims));
  for (int l = 0; l < LightsPerTexture; ++l)
  {
    this->EstimatedVoxels += (mask & (1 << l)) != 0 ? box.GetNumberOfVoxels() : 0;
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkIrradianceEstimator::vtkInternals::UpsamplePass(
  vtkOpenGLRenderWindow* context, int mask, int stride, bool skipEmpty, bool layered)
{
  vtkShaderProgram* program =
    this->Ready(context, this->UpsampleQuad, mmvLightGridUpsampleFS, "", false);
  if (!program)
  {
    return false;
  }
  int dims[3];
  this->LightGridDimensions(stride, dims);
  double ratio[3];
  this->LightGridRatio(stride, ratio);
  const float toLightGrid[3] = { static_cast<float>(ratio[0]), static_cast<float>(ratio[1]),
    static_cast<float>(ratio[2]) };
  ScopedTextures bound{ this->LightGridScratch, this->ClassTexture };
  program->SetUniformi("lightGrid", this->LightGridScratch->GetTextureUnit());
  program->SetUniformi("classes", this->ClassTexture->GetTextureUnit());
  program->SetUniform1iv("lightGridDims", 3, dims);
  program->SetUniform3f("indexToLightGrid", toLightGrid);
  program->SetUniform1iv("dims", 3, this->Grid.Dimensions);
  const mmv::IndexBox box =
    skipEmpty ? this->OccupiedBox(this->Plan.Estimated, 1) : this->Plan.Estimated;
  this->DrawLayers(context, this->UpsampleQuad, this->FineScratch[0], layered,
    DrawBox(box, this->Grid.Dimensions), mask);
  return true;
}

//------------------------------------------------------------------------------
// The tint of light `light` into its tint texture (mmvIrradianceTintFS.glsl):
// full shadow rays of the selective extinction from every tint voxel.
bool vtkIrradianceEstimator::vtkInternals::TintPass(
  vtkOpenGLRenderWindow* context, int light, bool layered)
{
  vtkShaderProgram* program =
    this->Ready(context, this->TintQuad, std::string(mmvShadowRay) + mmvIrradianceTintFS,
      this->ShadowRayDefines() + "#define MMV_TINT\n", true);
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
  const mmv::IndexBox box = mmv::ResampledBox(this->Plan.Region, this->Grid.Dimensions, tintDims);
  this->DrawLayers(context, this->TintQuad, this->Tint[light], layered, DrawBox(box, tintDims));
  return true;
}

//------------------------------------------------------------------------------
// The sweeps of light `light`'s piecewise rays on its light grid
// (mmv::PlanLightSweeps), none for full rays.
std::vector<mmv::ShadowSweep> vtkIrradianceEstimator::vtkInternals::LightSweeps(
  int light, int estimation, int slicesPerChunk) const
{
  const mmv::LightSource& source = this->Lights[light];
  const int stride = source.GridStride;
  int d[3];
  this->LightGridDimensions(stride, d);
  return mmv::PlanLightSweeps(estimation, source, d, this->LightGridPhysicalToIndex(stride),
    this->Grid.Origin, std::max(1, slicesPerChunk / stride));
}

//------------------------------------------------------------------------------
// Piecewise shadow rays of light `light` in its `sweeps` (LightSweeps: one,
// or six pyramids around a point or spot light inside the grid) into its
// channel of its light grid's target (vtkShadowSweep.h): one draw per chunk
// of slices, nearest the light first; a texture barrier lets each chunk read
// what the earlier ones wrote into the same texture. A point or spot
// light's channel then takes its geometry term in one more draw.
bool vtkIrradianceEstimator::vtkInternals::PiecewiseShadowPass(vtkOpenGLRenderWindow* context,
  int light, const std::vector<mmv::ShadowSweep>& sweeps, bool skipEmpty, bool layered)
{
  const mmv::LightSource& source = this->Lights[light];
  const bool point = source.Kind != mmv::DirectionalLight;
  const bool pyramids = !sweeps.empty() && sweeps[0].Pyramid;
  VoxelPrograms& pass =
    pyramids ? this->PyramidSweepQuad : (point ? this->PointSweepQuad : this->PiecewiseQuad);
  vtkShaderProgram* program =
    this->Ready(context, pass, std::string(mmvShadowRay) + mmvLightGrid + mmvPiecewiseShadowFS,
      this->ShadowRayDefines() + (point ? "#define MMV_POINT_SWEEP\n" : "") +
        (pyramids ? "#define MMV_PYRAMID_SWEEP\n" : ""),
      point);
  if (!program)
  {
    return false;
  }
  // The sweep runs over the light's grid: a strided grid takes chunks of as
  // many irradiance slices as the irradiance grid's, so each ray marches as
  // far before it reads an earlier chunk.
  const int stride = source.GridStride;
  int d[3];
  this->LightGridDimensions(stride, d);
  glm::vec3 toLight(source.ToLight);
  const int channel = light % LightsPerTexture;
  vtkTextureObject* target = this->LightGridTarget(stride);
  ScopedTextures bound{ this->ScalarTexture, this->ClassTexture, this->TableTexture, target,
    this->LightGridClasses(stride) };
  this->SetShadowRayUniforms(program);
  this->SetLightGridUniforms(program, stride);
  program->SetUniformi("transmittance", target->GetTextureUnit());
  program->SetUniform3f("toLight", glm::value_ptr(toLight));
  program->SetUniformi("channel", channel);
  program->SetUniformi("computeEmptyVoxels", skipEmpty ? 0 : 1);
  if (point)
  {
    glm::mat3 toWorld(this->Grid.IndexToPhysicalMatrix());
    const glm::vec3 origin(this->Grid.Origin);
    program->SetUniform3f("origin", glm::value_ptr(origin));
    program->SetUniformMatrix3x3("indexToWorld", glm::value_ptr(toWorld));
    program->SetUniformi("applyGeometry", 0);
    mmv::SetLightUniforms(program, &source, nullptr, 1, LightsPerTexture);
  }
  for (const mmv::ShadowSweep& sweep : sweeps)
  {
    const std::vector<mmv::IndexBox> boxes = this->SweepBoxes(light, sweep, skipEmpty);
    program->SetUniformi("sweepAxis", sweep.Axis);
    if (pyramids)
    {
      program->SetUniform3f("pyramidLight", glm::value_ptr(sweep.Light));
      program->SetUniformi("sweepTowardPositive", sweep.TowardPositive ? 1 : 0);
    }
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
      int range[4] = { 0, -1, 0, -1 }; // the first chunk reads no slice
      if (plane >= 0)
      {
        mmv::SliceReadRange(sweep, plane, d, range);
      }
      program->SetUniformi("sweepPlane", plane);
      program->SetUniformi("readSlice", sweep.GetReadSlice(chunk));
      program->SetUniform1iv("sliceRange", 4, range);
      // The earlier chunks' writes become visible to this draw's fetches.
      // (A compute dispatch ends with a memory barrier instead.)
      if (!this->Compute)
      {
        glTextureBarrier();
      }
      // The write mask keeps the other lights' channels.
      this->DrawLayers(context, pass, target, layered, box.Bounds, 1 << channel);
    }
  }
  if (point)
  {
    program->SetUniformi("applyGeometry", 1);
    if (!this->Compute)
    {
      glTextureBarrier();
    }
    this->DrawLayers(
      context, pass, target, layered, DrawBox(this->EstimatedOnLightGrid(stride), d), 1 << channel);
  }
  return true;
}

//------------------------------------------------------------------------------
mmv::IndexBox vtkIrradianceEstimator::vtkInternals::EstimatedOnLightGrid(int stride) const
{
  int d[3];
  this->LightGridDimensions(stride, d);
  return stride > 1 ? mmv::ResampledBox(this->Plan.Estimated, this->Grid.Dimensions, d)
                    : this->Plan.Estimated;
}

// What each chunk computes: what the region's voxels depend on (its whole
// slab for the whole grid), along a directional light's parallel rays or a
// point or spot light's converging on its position.
std::vector<mmv::IndexBox> vtkIrradianceEstimator::vtkInternals::SweepBoxes(
  int light, const mmv::ShadowSweep& sweep, bool skipEmpty) const
{
  const mmv::LightSource& source = this->Lights[light];
  const int stride = source.GridStride;
  int d[3];
  this->LightGridDimensions(stride, d);
  const glm::dmat3 toIndex = this->LightGridPhysicalToIndex(stride);
  const glm::dvec3 lightIndex = toIndex * (source.Position - this->Grid.Origin);
  std::function<mmv::IndexBox(const mmv::IndexBox&)> nonEmpty;
  if (skipEmpty)
  {
    nonEmpty = [this, stride](const mmv::IndexBox& box) { return this->OccupiedBox(box, stride); };
  }
  return mmv::PlanSweepBoxes(sweep, d, toIndex * source.ToLight, this->EstimatedOnLightGrid(stride),
    nonEmpty, source.Kind != mmv::DirectionalLight ? &lightIndex : nullptr);
}

//------------------------------------------------------------------------------
bool vtkIrradianceEstimator::vtkInternals::SweepsLightOnCPU(
  int light, const std::vector<mmv::ShadowSweep>& sweeps) const
{
  const mmv::LightSource& source = this->Lights[light];
  if (!this->SweepsOnCPU || source.Kind != mmv::DirectionalLight || sweeps.size() != 1 ||
    sweeps[0].Pyramid || !this->Cut.IsEmpty())
  {
    return false;
  }
  return source.GridStride > 1 ? this->CopiedLightGridNeededStamp == this->Classifications &&
      this->CopiedLightGridNeededStride == source.GridStride
                               : this->CopiedClassesStamp == this->Classifications;
}

// Each target's lights in one buffer of as many channels as its highest
// light's, uploaded once over what they computed (unless the final write
// runs on the CPU too).
int vtkIrradianceEstimator::vtkInternals::SweepOnCPU(
  std::vector<std::pair<int, std::vector<mmv::ShadowSweep>>>& swept, bool skipEmpty, bool upload,
  const std::function<void()>& lightDone)
{
  std::vector<std::pair<int, std::vector<mmv::ShadowSweep>>> onCPU;
  std::vector<std::pair<int, std::vector<mmv::ShadowSweep>>> onGPU;
  std::array<int, 2> channels = { 0, 0 };
  for (auto& light : swept)
  {
    if (this->SweepsLightOnCPU(light.first, light.second))
    {
      int& n = channels[this->Lights[light.first].GridStride > 1 ? 1 : 0];
      n = std::max(n, light.first % LightsPerTexture + 1);
      onCPU.push_back(std::move(light));
    }
    else
    {
      onGPU.push_back(std::move(light));
    }
  }
  swept.swap(onGPU);
  // What every light reads; the light grid's part per light.
  mmv::SweptTransmittanceInputs inputs;
  std::copy(this->Grid.Dimensions, this->Grid.Dimensions + 3, inputs.Dimensions);
  inputs.Scalars = this->Scalars.data();
  inputs.ShadowTable = this->ShadowTable.data();
  inputs.TableSize = this->TableSize;
  inputs.StepLength = static_cast<float>(this->StepLength);
  inputs.WorldToIndex = glm::mat3(this->Grid.PhysicalToIndexMatrix());
  inputs.Classes = this->Classes.data();
  inputs.Needed = this->CopiedLightGridNeeded.data();
  inputs.SkipEmpty = skipEmpty;
  std::array<mmv::IndexBox, 2> covered;
  std::array<int, 2> strides = { 1, 1 };
  mmv::RunOnAllCores(
    [&]()
    {
      for (const auto& light : onCPU)
      {
        const mmv::LightSource& source = this->Lights[light.first];
        const int stride = source.GridStride;
        const int t = stride > 1 ? 1 : 0;
        strides[t] = stride;
        this->LightGridDimensions(stride, inputs.TargetDimensions);
        const int* d = inputs.TargetDimensions;
        std::vector<float>& buffer = this->SweptOnCPU[t];
        buffer.resize(static_cast<size_t>(channels[t]) * d[0] * d[1] * d[2]);
        double ratio[3];
        this->LightGridRatio(stride, ratio);
        for (int a = 0; a < 3; ++a)
        {
          // As SetLightGridUniforms gives the shader.
          inputs.TargetToIndex[a] = static_cast<float>(1.0 / ratio[a]);
        }
        inputs.Strided = stride > 1;
        const mmv::ShadowSweep& sweep = light.second[0];
        const std::vector<mmv::IndexBox> boxes = this->SweepBoxes(light.first, sweep, skipEmpty);
        this->EstimatedVoxels += mmv::SweepTransmittanceOnCPU(inputs, glm::vec3(source.ToLight),
          sweep, boxes, buffer.data(), channels[t], light.first % LightsPerTexture);
        for (const mmv::IndexBox& box : boxes)
        {
          covered[t] = covered[t].United(box);
        }
        lightDone();
      }
    });
  this->SweptChannels = channels;
  static const GLenum formats[] = { GL_RED, GL_RG, GL_RGB, GL_RGBA };
  for (int t = 0; upload && t < 2; ++t)
  {
    if (!covered[t].IsEmpty())
    {
      mmv::UploadTextureBox(this->LightGridTarget(strides[t]), covered[t].Bounds,
        formats[channels[t] - 1], GL_FLOAT, this->SweptOnCPU[t].data());
    }
  }
  return static_cast<int>(onCPU.size());
}

//------------------------------------------------------------------------------
bool vtkIrradianceEstimator::vtkInternals::WritesOnCPU(int group, int mask,
  const std::vector<std::pair<int, std::vector<mmv::ShadowSweep>>>& swept, bool diffusion) const
{
  const int lights = this->LightsInTexture(group);
  const bool scene =
    static_cast<size_t>(group) < this->SceneTransmittance.size() && this->SceneTransmittance[group];
  return this->SweepsOnCPU && (!diffusion || this->DiffusesOnCPU()) && !scene &&
    mask == (1 << lights) - 1 && static_cast<int>(swept.size()) == lights &&
    this->CopiedClassesStamp == this->Classifications &&
    std::all_of(swept.begin(), swept.end(),
      [this](const std::pair<int, std::vector<mmv::ShadowSweep>>& light)
      { return this->SweepsLightOnCPU(light.first, light.second); });
}

//------------------------------------------------------------------------------
mmv::IrradianceTexelInputs vtkIrradianceEstimator::vtkInternals::SweptTexelInputs(int group) const
{
  const int first = group * LightsPerTexture;
  mmv::IrradianceTexelInputs inputs;
  std::copy(this->Grid.Dimensions, this->Grid.Dimensions + 3, inputs.Dimensions);
  inputs.Classes = this->Classes.data();
  inputs.Lights = this->LightsInTexture(group);
  for (int l = 0; l < inputs.Lights; ++l)
  {
    inputs.StridedMask |= this->Lights[first + l].GridStride > 1 ? 1 << l : 0;
  }
  inputs.Fine = this->SweptOnCPU[0].data();
  inputs.FineChannels = this->SweptChannels[0];
  if (inputs.StridedMask != 0)
  {
    inputs.LightGrid = this->SweptOnCPU[1].data();
    inputs.LightGridChannels = this->SweptChannels[1];
    // The strided lights' grid, as UpsamplePass reads it.
    const int stride = this->MaxLightGridStride();
    this->LightGridDimensions(stride, inputs.LightGridDimensions);
    double ratio[3];
    this->LightGridRatio(stride, ratio);
    // As UpsamplePass gives the shader.
    inputs.IndexToLightGrid = glm::vec3(ratio[0], ratio[1], ratio[2]);
  }
  return inputs;
}

//------------------------------------------------------------------------------
void vtkIrradianceEstimator::vtkInternals::GatherOnCPU(int group, bool skipEmpty)
{
  const int* d = this->Grid.Dimensions;
  this->FineOnCPU.resize(4 * static_cast<size_t>(d[0]) * d[1] * d[2]);
  // The box UpsamplePass draws: the non-empty voxels the diffusion reads.
  const mmv::IndexBox box =
    skipEmpty ? this->OccupiedBox(this->Plan.Estimated, 1) : this->Plan.Estimated;
  const mmv::IrradianceTexelInputs inputs = this->SweptTexelInputs(group);
  mmv::RunOnAllCores(
    [&]() { mmv::GatherIrradianceValues(inputs, box, 4, this->FineOnCPU.data()); });
}

//------------------------------------------------------------------------------
void vtkIrradianceEstimator::vtkInternals::WriteOnCPU(int group, bool skipEmpty, bool diffused)
{
  mmv::IrradianceTexelInputs inputs = this->SweptTexelInputs(group);
  if (diffused)
  {
    // Every light's values diffused in FineOnCPU, on the irradiance grid.
    inputs.Fine = this->FineOnCPU.data();
    inputs.FineChannels = 4;
    inputs.StridedMask = 0;
  }
  vtkTextureObject* texture = this->Irradiance[group];
  const int channels = texture->GetComponents();
  const size_t size = static_cast<size_t>(channels) * this->Grid.GetNumberOfVoxels();
  if (this->WrittenOnCPU.size() < size)
  {
    this->WrittenOnCPU.resize(size);
  }
  const mmv::IndexBox box = this->FillBox(group, skipEmpty);
  mmv::RunOnAllCores(
    [&]() { mmv::WriteIrradianceTexels(inputs, box, channels, this->WrittenOnCPU.data()); });
  if (!box.IsEmpty())
  {
    // In the texture's own format; rows of 2-byte texels: aligned to 2.
    mmv::UploadTextureBox(texture, box.Bounds,
      texture->GetFormat(VTK_UNSIGNED_SHORT, channels, false), GL_UNSIGNED_SHORT,
      this->WrittenOnCPU.data(), 2);
  }
}
