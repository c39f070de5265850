#include "vtkIrradianceVolumePass.h"

#include "vtkIrradianceDiffusion.h"
#include "vtkMultiMaterialParameters.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkShaderProgram.h"
#include "vtkSmartPointer.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include "mmvDiffusionFS.h"
#include "mmvIrradianceFS.h"
#include "mmvLightModel.h"

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <memory>
#include <string>

namespace
{

constexpr int LightsPerTexture = 4;

/// Linear interpolation of an n-entry table over the normalised range, as a
/// bilinear texture lookup at (x + 0.5) / n would do it.
float LookupTable(const std::vector<float>& table, float t)
{
  const int n = static_cast<int>(table.size());
  const float x = std::min(std::max(t, 0.0f), 1.0f) * static_cast<float>(n - 1);
  const int i0 = std::min(static_cast<int>(x), n - 2);
  const float f = x - static_cast<float>(i0);
  return (1.0f - f) * table[i0] + f * table[i0 + 1];
}

/// Face coefficient of the CPU diffusion (vtkIrradianceDiffusion.cxx).
double HarmonicMean(double a, double b)
{
  return (a > 0.0 && b > 0.0) ? 2.0 * a * b / (a + b) : 0.0;
}

/// 1/h^2 per axis of the diffusion operator, h in data voxels (the unit of
/// the scattering strength s), for both the CPU estimate and the shader.
glm::dvec3 InverseSquaredSpacing(const mmv::IrradianceGrid& grid)
{
  glm::dvec3 invH2;
  for (int a = 0; a < 3; ++a)
  {
    const double h = grid.DataVoxelsPerVoxel[a] > 0.0 ? grid.DataVoxelsPerVoxel[a] : 1.0;
    invH2[a] = 1.0 / (h * h);
  }
  return invH2;
}

/// The fragment shader: system declarations, `defines`, optionally the light
/// model, then `body`.
std::string ComposeShader(const char* body, const std::string& defines, bool lightModel)
{
  std::string source = "//VTK::System::Dec\n";
  source += mmv::MaterialGLSLPrelude();
  source += defines;
  if (lightModel)
  {
    source += mmvLightModel;
    source += "\n";
  }
  source += "//VTK::Output::Dec\n";
  source += body;
  return source;
}

/// An empty 3D/2D texture object with explicit GL formats, so that no
/// context-dependent default picks a different precision.
vtkSmartPointer<vtkTextureObject> NewTexture(vtkOpenGLRenderWindow* context,
  unsigned int internalFormat, unsigned int format, unsigned int type, bool linear)
{
  auto texture = vtkSmartPointer<vtkTextureObject>::New();
  texture->SetContext(context);
  texture->SetInternalFormat(internalFormat);
  texture->SetFormat(format);
  texture->SetDataType(type);
  const int filter = linear ? vtkTextureObject::Linear : vtkTextureObject::Nearest;
  texture->SetMinificationFilter(filter);
  texture->SetMagnificationFilter(filter);
  texture->SetWrapS(vtkTextureObject::ClampToEdge);
  texture->SetWrapT(vtkTextureObject::ClampToEdge);
  texture->SetWrapR(vtkTextureObject::ClampToEdge);
  return texture;
}

void SetLightUniforms(vtkShaderProgram* program, const std::vector<mmv::LightSource>& lights,
  int first)
{
  const int count = std::min(LightsPerTexture, static_cast<int>(lights.size()) - first);
  int kind[LightsPerTexture] = { 0, 0, 0, 0 };
  float position[LightsPerTexture][3] = {};
  float toLight[LightsPerTexture][3] = {};
  float spotAxis[LightsPerTexture][3] = {};
  float cosCone[LightsPerTexture] = { -1.0f, -1.0f, -1.0f, -1.0f };
  float radius[LightsPerTexture] = { 1.0f, 1.0f, 1.0f, 1.0f };
  for (int l = 0; l < count; ++l)
  {
    const mmv::LightSource& light = lights[first + l];
    kind[l] = light.Kind;
    for (int a = 0; a < 3; ++a)
    {
      position[l][a] = static_cast<float>(light.Position[a]);
      toLight[l][a] = static_cast<float>(light.ToLight[a]);
      spotAxis[l][a] = static_cast<float>(light.SpotAxis[a]);
    }
    cosCone[l] = static_cast<float>(light.CosCone);
    radius[l] = static_cast<float>(light.Radius);
  }
  program->SetUniformi("numberOfLights", count);
  program->SetUniform1iv("lightKind", LightsPerTexture, kind);
  program->SetUniform3fv("lightPosition", LightsPerTexture, position);
  program->SetUniform3fv("lightToLight", LightsPerTexture, toLight);
  program->SetUniform3fv("lightSpotAxis", LightsPerTexture, spotAxis);
  program->SetUniform1fv("lightCosCone", LightsPerTexture, cosCone);
  program->SetUniform1fv("lightRadius", LightsPerTexture, radius);
}

bool SameGrid(const mmv::IrradianceGrid& a, const mmv::IrradianceGrid& b)
{
  return std::equal(a.Dimensions, a.Dimensions + 3, b.Dimensions) && a.Origin == b.Origin &&
    a.Spacing == b.Spacing && a.Direction == b.Direction;
}

} // namespace

class vtkIrradianceVolumePass::vtkInternals
{
public:
  // Inputs, copied by SetInputs().
  mmv::IrradianceGrid Grid;
  std::vector<float> Scalars;
  int TableSize = 0;
  std::vector<float> ShadowTable;
  double StepLength = 0.0;
  std::vector<float> OpacityTable;
  std::vector<float> ScatteringTable;
  std::vector<mmv::LightSource> Lights;
  bool HasInputs = false;
  bool Uploaded = false;
  vtkIdType VolumeUploads = 0;

  // Derived on the CPU: s per voxel (-1 where empty), and what it implies.
  std::vector<float> Classes;
  vtkIdType NonEmptyVoxels = 0;
  double MaxDiffusionRate = 0.0; // largest row sum of the diffusion operator

  // GPU resources.
  vtkSmartPointer<vtkTextureObject> ScalarTexture;
  vtkSmartPointer<vtkTextureObject> ClassTexture;
  vtkSmartPointer<vtkTextureObject> TableTexture;
  std::vector<vtkSmartPointer<vtkTextureObject>> Irradiance;
  std::array<vtkSmartPointer<vtkTextureObject>, 3> Scratch;
  vtkSmartPointer<vtkOpenGLFramebufferObject> Framebuffer;
  std::unique_ptr<vtkOpenGLQuadHelper> ShadowQuad;
  std::unique_ptr<vtkOpenGLQuadHelper> SweepQuad;
  std::unique_ptr<vtkOpenGLQuadHelper> FillQuad;

  void Classify(const std::vector<float>& opacity, const std::vector<float>& scattering);
  void ComputeMaxDiffusionRate();
  int DiffusionSteps(double time) const;

  bool Upload(vtkOpenGLRenderWindow* context);
  bool AllocateTargets(vtkOpenGLRenderWindow* context, bool diffusion);
  vtkShaderProgram* Ready(vtkOpenGLRenderWindow* context, std::unique_ptr<vtkOpenGLQuadHelper>& quad,
    const char* body, const std::string& defines, bool lightModel);
  void DrawSlices(vtkOpenGLQuadHelper& quad, vtkTextureObject* target);
  void SetGridUniforms(vtkShaderProgram* program) const;

  bool ShadowPass(vtkOpenGLRenderWindow* context, int group);
  int Diffuse(vtkOpenGLRenderWindow* context, double time, int sweeps);
  bool FillPass(vtkOpenGLRenderWindow* context, int source, int group);
  void ReleaseScratch(vtkWindow* window);
  void Release(vtkWindow* window);
};

//------------------------------------------------------------------------------
void vtkIrradianceVolumePass::vtkInternals::Classify(
  const std::vector<float>& opacity, const std::vector<float>& scattering)
{
  this->Classes.resize(this->Scalars.size());
  this->NonEmptyVoxels = 0;
  for (size_t v = 0; v < this->Scalars.size(); ++v)
  {
    const bool nonEmpty = LookupTable(opacity, this->Scalars[v]) > 0.0f;
    this->Classes[v] = nonEmpty ? std::max(0.0f, LookupTable(scattering, this->Scalars[v])) : -1.0f;
    this->NonEmptyVoxels += nonEmpty ? 1 : 0;
  }
}

//------------------------------------------------------------------------------
// The CPU solver's stiffness estimate (Gershgorin bound of its operator),
// from which both pick the same number of backward-Euler steps.
void vtkIrradianceVolumePass::vtkInternals::ComputeMaxDiffusionRate()
{
  const int* dims = this->Grid.Dimensions;
  const vtkIdType stride[3] = { 1, dims[0], static_cast<vtkIdType>(dims[0]) * dims[1] };
  const glm::dvec3 invH2 = InverseSquaredSpacing(this->Grid);
  auto strength = [&](vtkIdType v) { return std::max(0.0, static_cast<double>(this->Classes[v])); };
  this->MaxDiffusionRate = 0.0;
  vtkIdType v = 0;
  for (int k = 0; k < dims[2]; ++k)
  {
    for (int j = 0; j < dims[1]; ++j)
    {
      for (int i = 0; i < dims[0]; ++i, ++v)
      {
        const int index[3] = { i, j, k };
        double sum = 0.0;
        for (int a = 0; a < 3; ++a)
        {
          if (index[a] > 0)
          {
            sum += static_cast<float>(HarmonicMean(strength(v), strength(v - stride[a])) * invH2[a]);
          }
          if (index[a] + 1 < dims[a])
          {
            sum += static_cast<float>(HarmonicMean(strength(v), strength(v + stride[a])) * invH2[a]);
          }
        }
        this->MaxDiffusionRate = std::max(this->MaxDiffusionRate, sum);
      }
    }
  }
}

//------------------------------------------------------------------------------
// As many backward-Euler steps as an explicit scheme would need, capped like
// the CPU solver.
int vtkIrradianceVolumePass::vtkInternals::DiffusionSteps(double time) const
{
  return static_cast<int>(std::min<double>(mmv::DiffusionSettings().MaxSubSteps,
    std::max(1.0, std::ceil(time * this->MaxDiffusionRate))));
}

//------------------------------------------------------------------------------
bool vtkIrradianceVolumePass::vtkInternals::Upload(vtkOpenGLRenderWindow* context)
{
  if (this->Uploaded && this->ScalarTexture)
  {
    return true;
  }
  const int* d = this->Grid.Dimensions;
  this->ScalarTexture = NewTexture(context, GL_R32F, GL_RED, GL_FLOAT, true);
  this->ClassTexture = NewTexture(context, GL_R32F, GL_RED, GL_FLOAT, false);
  this->TableTexture = NewTexture(context, GL_R32F, GL_RED, GL_FLOAT, true);
  ++this->VolumeUploads;
  this->Uploaded = this->ScalarTexture->Create3DFromRaw(d[0], d[1], d[2], 1, VTK_FLOAT,
                     this->Scalars.data()) &&
    this->ClassTexture->Create3DFromRaw(d[0], d[1], d[2], 1, VTK_FLOAT, this->Classes.data()) &&
    this->TableTexture->Create2DFromRaw(
      this->TableSize, this->TableSize, 1, VTK_FLOAT, this->ShadowTable.data());
  return this->Uploaded;
}

//------------------------------------------------------------------------------
bool vtkIrradianceVolumePass::vtkInternals::AllocateTargets(
  vtkOpenGLRenderWindow* context, bool diffusion)
{
  const int* d = this->Grid.Dimensions;
  const size_t textures = (this->Lights.size() + LightsPerTexture - 1) / LightsPerTexture;
  auto sameSize = [&](vtkTextureObject* t) {
    return t && t->GetHandle() && static_cast<int>(t->GetWidth()) == d[0] &&
      static_cast<int>(t->GetHeight()) == d[1] && static_cast<int>(t->GetDepth()) == d[2];
  };
  this->Irradiance.resize(textures);
  bool ok = true;
  for (auto& texture : this->Irradiance)
  {
    if (!sameSize(texture))
    {
      // 16-bit unsigned normalised: values are fractions in [0, 1].
      texture = NewTexture(context, GL_RGBA16, GL_RGBA, GL_UNSIGNED_SHORT, true);
      ok = ok && texture->Allocate3D(d[0], d[1], d[2], 4, VTK_UNSIGNED_SHORT);
    }
  }
  const size_t scratch = diffusion ? this->Scratch.size() : 1;
  for (size_t i = 0; i < scratch; ++i)
  {
    if (!sameSize(this->Scratch[i]))
    {
      this->Scratch[i] = NewTexture(context, GL_RGBA32F, GL_RGBA, GL_FLOAT, false);
      ok = ok && this->Scratch[i]->Allocate3D(d[0], d[1], d[2], 4, VTK_FLOAT);
    }
  }
  if (!this->Framebuffer)
  {
    this->Framebuffer = vtkSmartPointer<vtkOpenGLFramebufferObject>::New();
    this->Framebuffer->SetContext(context);
  }
  return ok;
}

//------------------------------------------------------------------------------
vtkShaderProgram* vtkIrradianceVolumePass::vtkInternals::Ready(vtkOpenGLRenderWindow* context,
  std::unique_ptr<vtkOpenGLQuadHelper>& quad, const char* body, const std::string& defines,
  bool lightModel)
{
  if (!quad)
  {
    const std::string source = ComposeShader(body, defines, lightModel);
    quad = std::make_unique<vtkOpenGLQuadHelper>(context, nullptr, source.c_str(), "");
  }
  if (!quad->Program || !context->GetShaderCache()->ReadyShaderProgram(quad->Program))
  {
    return nullptr;
  }
  return quad->Program;
}

//------------------------------------------------------------------------------
void vtkIrradianceVolumePass::vtkInternals::SetGridUniforms(vtkShaderProgram* program) const
{
  program->SetUniform1iv("dims", 3, this->Grid.Dimensions);
}

//------------------------------------------------------------------------------
// One draw per z slice: the framebuffer's attachment is switched to the
// slice (removed first: re-adding the same texture keeps the old slice).
void vtkIrradianceVolumePass::vtkInternals::DrawSlices(
  vtkOpenGLQuadHelper& quad, vtkTextureObject* target)
{
  this->Framebuffer->Bind();
  for (int z = 0; z < this->Grid.Dimensions[2]; ++z)
  {
    this->Framebuffer->RemoveColorAttachment(0);
    this->Framebuffer->AddColorAttachment(0, target, z);
    this->Framebuffer->ActivateDrawBuffers(1);
    quad.Program->SetUniformi("slice", z);
    quad.Render();
  }
  this->Framebuffer->RemoveColorAttachment(0);
}

//------------------------------------------------------------------------------
bool vtkIrradianceVolumePass::vtkInternals::ShadowPass(vtkOpenGLRenderWindow* context, int group)
{
  vtkShaderProgram* program =
    this->Ready(context, this->ShadowQuad, mmvIrradianceFS, mmv::ShadowRayGLSLPrelude(), true);
  if (!program)
  {
    return false;
  }
  glm::mat3 toWorld(this->Grid.IndexToPhysicalMatrix());
  glm::mat3 toIndex(this->Grid.PhysicalToIndexMatrix());
  const glm::vec3 origin(this->Grid.Origin);
  this->ScalarTexture->Activate();
  this->ClassTexture->Activate();
  this->TableTexture->Activate();
  program->SetUniformi("scalars", this->ScalarTexture->GetTextureUnit());
  program->SetUniformi("classes", this->ClassTexture->GetTextureUnit());
  program->SetUniformi("shadowTable", this->TableTexture->GetTextureUnit());
  program->SetUniformf("tableSize", static_cast<float>(this->TableSize));
  this->SetGridUniforms(program);
  program->SetUniform3f("origin", glm::value_ptr(origin));
  program->SetUniformMatrix3x3("indexToWorld", glm::value_ptr(toWorld));
  program->SetUniformMatrix3x3("worldToIndex", glm::value_ptr(toIndex));
  program->SetUniformf("stepLength", static_cast<float>(this->StepLength));
  SetLightUniforms(program, this->Lights, group * LightsPerTexture);
  this->DrawSlices(*this->ShadowQuad, this->Scratch[0]);
  this->ScalarTexture->Deactivate();
  this->ClassTexture->Deactivate();
  this->TableTexture->Deactivate();
  return true;
}

//------------------------------------------------------------------------------
// Backward-Euler steps from Scratch[0], each solved by `sweeps` Jacobi sweeps
// from the previous step's result, rotating over the three scratch textures.
// Returns the scratch index holding the result, or -1 on failure.
int vtkIrradianceVolumePass::vtkInternals::Diffuse(
  vtkOpenGLRenderWindow* context, double time, int sweeps)
{
  vtkShaderProgram* program = this->Ready(context, this->SweepQuad, mmvDiffusionFS, "", false);
  if (!program)
  {
    return -1;
  }
  const int steps = this->DiffusionSteps(time);
  const glm::vec3 invH2(InverseSquaredSpacing(this->Grid));
  this->ClassTexture->Activate();
  program->SetUniformi("classes", this->ClassTexture->GetTextureUnit());
  this->SetGridUniforms(program);
  program->SetUniform3f("invH2", glm::value_ptr(invH2));
  program->SetUniformf("dt", static_cast<float>(time / steps));
  int rhs = 0;
  int current = 0;
  for (int step = 0; step < steps; ++step)
  {
    for (int sweep = 0; sweep < sweeps; ++sweep)
    {
      const int target = (current + 1) % 3 == rhs ? (current + 2) % 3 : (current + 1) % 3;
      this->Scratch[rhs]->Activate();
      if (current != rhs)
      {
        this->Scratch[current]->Activate();
      }
      program->SetUniformi("rhs", this->Scratch[rhs]->GetTextureUnit());
      program->SetUniformi("current", this->Scratch[current]->GetTextureUnit());
      this->DrawSlices(*this->SweepQuad, this->Scratch[target]);
      this->Scratch[rhs]->Deactivate();
      if (current != rhs)
      {
        this->Scratch[current]->Deactivate();
      }
      current = target;
    }
    rhs = current;
  }
  this->ClassTexture->Deactivate();
  return current;
}

//------------------------------------------------------------------------------
bool vtkIrradianceVolumePass::vtkInternals::FillPass(
  vtkOpenGLRenderWindow* context, int source, int group)
{
  vtkShaderProgram* program =
    this->Ready(context, this->FillQuad, mmvDiffusionFS, "#define MMV_FILL_PASS\n", false);
  if (!program)
  {
    return false;
  }
  this->ClassTexture->Activate();
  this->Scratch[source]->Activate();
  program->SetUniformi("classes", this->ClassTexture->GetTextureUnit());
  program->SetUniformi("current", this->Scratch[source]->GetTextureUnit());
  this->SetGridUniforms(program);
  this->DrawSlices(*this->FillQuad, this->Irradiance[group]);
  this->ClassTexture->Deactivate();
  this->Scratch[source]->Deactivate();
  return true;
}

//------------------------------------------------------------------------------
void vtkIrradianceVolumePass::vtkInternals::ReleaseScratch(vtkWindow* window)
{
  // The float scratch is 8x the result per texture: not worth keeping.
  for (auto& texture : this->Scratch)
  {
    if (texture)
    {
      texture->ReleaseGraphicsResources(window);
      texture = nullptr;
    }
  }
}

//------------------------------------------------------------------------------
void vtkIrradianceVolumePass::vtkInternals::Release(vtkWindow* window)
{
  this->ReleaseScratch(window);
  for (vtkTextureObject* texture :
    { this->ScalarTexture.Get(), this->ClassTexture.Get(), this->TableTexture.Get() })
  {
    if (texture)
    {
      texture->ReleaseGraphicsResources(window);
    }
  }
  this->ScalarTexture = nullptr;
  this->ClassTexture = nullptr;
  this->TableTexture = nullptr;
  for (auto& texture : this->Irradiance)
  {
    texture->ReleaseGraphicsResources(window);
  }
  this->Irradiance.clear();
  if (this->Framebuffer)
  {
    this->Framebuffer->ReleaseGraphicsResources(window);
    this->Framebuffer = nullptr;
  }
  for (auto* quad : { &this->ShadowQuad, &this->SweepQuad, &this->FillQuad })
  {
    if (*quad)
    {
      (*quad)->ReleaseGraphicsResources(window);
      quad->reset();
    }
  }
  this->Uploaded = false;
}

//------------------------------------------------------------------------------
vtkStandardNewMacro(vtkIrradianceVolumePass);

vtkIrradianceVolumePass::vtkIrradianceVolumePass()
  : Internals(new vtkInternals)
{
}

vtkIrradianceVolumePass::~vtkIrradianceVolumePass()
{
  delete this->Internals;
}

//------------------------------------------------------------------------------
void vtkIrradianceVolumePass::SetInputs(const mmv::IrradianceGrid& grid,
  const std::vector<float>& normalizedScalars, int tableSize, const float* shadowTable,
  double stepLength, const float* opacityTable, const float* scatteringTable,
  const std::vector<mmv::LightSource>& lights)
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
    vtkWarningMacro("" << lights.size() << " lights given; only the first " << mmv::MaxLights
                       << " are used.");
  }
  internals.Lights.assign(
    lights.begin(), lights.begin() + std::min<size_t>(lights.size(), mmv::MaxLights));
  // A light move changes only the lights: keep the classified, uploaded
  // volume and tables unless one of them differs.
  const std::vector<float> shadow(shadowTable, shadowTable + tableSize * tableSize);
  const std::vector<float> opacity(opacityTable, opacityTable + tableSize);
  const std::vector<float> scattering(scatteringTable, scatteringTable + tableSize);
  const bool sameVolume = internals.HasInputs && SameGrid(internals.Grid, grid) &&
    internals.StepLength == stepLength && internals.Scalars == normalizedScalars &&
    internals.ShadowTable == shadow && internals.OpacityTable == opacity &&
    internals.ScatteringTable == scattering;
  if (!sameVolume)
  {
    internals.Grid = grid;
    internals.Scalars = normalizedScalars;
    internals.TableSize = tableSize;
    internals.ShadowTable = shadow;
    internals.StepLength = stepLength;
    internals.OpacityTable = opacity;
    internals.ScatteringTable = scattering;
    internals.Classify(opacity, scattering);
    internals.ComputeMaxDiffusionRate();
    internals.Uploaded = false;
  }
  internals.HasInputs = true;
}

//------------------------------------------------------------------------------
bool vtkIrradianceVolumePass::Render(vtkOpenGLRenderWindow* context)
{
  vtkInternals& internals = *this->Internals;
  this->NumberOfComputedVoxels = 0;
  this->DiffusionPasses = 0;
  if (!context || !internals.HasInputs)
  {
    vtkErrorMacro("Render() needs a context and valid inputs (SetInputs).");
    return false;
  }
  int major = 0;
  int minor = 0;
  context->GetOpenGLVersion(major, minor);
  if (major * 10 + minor < 32)
  {
    vtkErrorMacro("The irradiance volume needs OpenGL 3.2, the context has " << major << "."
                                                                             << minor << ".");
    return false;
  }
  const bool diffusion = this->MultipleScattering && this->DiffusionTime > 0.0 &&
    internals.MaxDiffusionRate > 0.0;
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
    state->vtkglDisable(GL_BLEND); // blending would garble the float outputs
    state->vtkglDisable(GL_DEPTH_TEST);
    state->vtkglDisable(GL_SCISSOR_TEST);
    state->vtkglColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    state->vtkglViewport(0, 0, internals.Grid.Dimensions[0], internals.Grid.Dimensions[1]);
    ok = internals.Upload(context) && internals.AllocateTargets(context, diffusion);
    for (int group = 0; ok && group < this->GetNumberOfIrradianceTextures(); ++group)
    {
      int result = internals.ShadowPass(context, group) ? 0 : -1;
      if (diffusion && result == 0)
      {
        result = internals.Diffuse(context, this->DiffusionTime, this->DiffusionSweeps);
      }
      ok = result >= 0 && internals.FillPass(context, result, group);
    }
    internals.ReleaseScratch(context);
  }
  state->PopFramebufferBindings();
  glFinish();
  this->LastRenderSeconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!ok)
  {
    vtkErrorMacro("The irradiance passes failed (shader or texture setup).");
    return false;
  }
  this->NumberOfComputedVoxels = internals.NonEmptyVoxels;
  if (diffusion)
  {
    this->DiffusionPasses = internals.DiffusionSteps(this->DiffusionTime) * this->DiffusionSweeps *
      this->GetNumberOfIrradianceTextures();
  }
  return true;
}

//------------------------------------------------------------------------------
vtkTextureObject* vtkIrradianceVolumePass::GetIrradianceTexture(int i) const
{
  const auto& textures = this->Internals->Irradiance;
  return i >= 0 && i < static_cast<int>(textures.size()) ? textures[i].Get() : nullptr;
}

int vtkIrradianceVolumePass::GetNumberOfIrradianceTextures() const
{
  return static_cast<int>(this->Internals->Irradiance.size());
}

//------------------------------------------------------------------------------
bool vtkIrradianceVolumePass::ReadBack(
  vtkOpenGLRenderWindow* context, int light, std::vector<float>& values)
{
  vtkInternals& internals = *this->Internals;
  vtkTextureObject* texture = this->GetIrradianceTexture(light / LightsPerTexture);
  if (!context || !texture || !internals.Framebuffer || light < 0 ||
    light >= static_cast<int>(internals.Lights.size()))
  {
    vtkErrorMacro("No irradiance of light " << light << " to read back.");
    return false;
  }
  const int* d = internals.Grid.Dimensions;
  const vtkIdType sliceSize = static_cast<vtkIdType>(d[0]) * d[1];
  std::vector<float> rgba(4 * sliceSize);
  values.resize(sliceSize * d[2]);
  vtkOpenGLState* state = context->GetState();
  state->PushFramebufferBindings();
  internals.Framebuffer->Bind();
  for (int z = 0; z < d[2]; ++z)
  {
    internals.Framebuffer->RemoveColorAttachment(0);
    internals.Framebuffer->AddColorAttachment(0, texture, z);
    internals.Framebuffer->ActivateReadBuffer(0);
    glReadPixels(0, 0, d[0], d[1], GL_RGBA, GL_FLOAT, rgba.data());
    for (vtkIdType p = 0; p < sliceSize; ++p)
    {
      values[z * sliceSize + p] = rgba[4 * p + light % LightsPerTexture];
    }
  }
  internals.Framebuffer->RemoveColorAttachment(0);
  state->PopFramebufferBindings();
  return true;
}

//------------------------------------------------------------------------------
vtkIdType vtkIrradianceVolumePass::GetNumberOfVolumeUploads() const
{
  return this->Internals->VolumeUploads;
}

vtkIdType vtkIrradianceVolumePass::GetTextureMemoryBytes() const
{
  const vtkIdType bytesPerVoxel = 4 * sizeof(unsigned short);
  vtkIdType bytes = 0;
  for (const auto& texture : this->Internals->Irradiance)
  {
    bytes += static_cast<vtkIdType>(texture->GetWidth()) * texture->GetHeight() *
      texture->GetDepth() * bytesPerVoxel;
  }
  return bytes;
}

//------------------------------------------------------------------------------
void vtkIrradianceVolumePass::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Internals->Release(window);
}

//------------------------------------------------------------------------------
void vtkIrradianceVolumePass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  const vtkInternals& internals = *this->Internals;
  os << indent << "Dimensions: " << internals.Grid.Dimensions[0] << " "
     << internals.Grid.Dimensions[1] << " " << internals.Grid.Dimensions[2] << "\n";
  os << indent << "Lights: " << internals.Lights.size() << "\n";
  os << indent << "MultipleScattering: " << this->MultipleScattering << "\n";
  os << indent << "DiffusionTime: " << this->DiffusionTime << "\n";
  os << indent << "DiffusionSweeps: " << this->DiffusionSweeps << "\n";
  os << indent << "NumberOfComputedVoxels: " << this->NumberOfComputedVoxels << "\n";
  os << indent << "DiffusionPasses: " << this->DiffusionPasses << "\n";
  os << indent << "LastRenderSeconds: " << this->LastRenderSeconds << "\n";
  os << indent << "TextureMemoryBytes: " << this->GetTextureMemoryBytes() << "\n";
}
