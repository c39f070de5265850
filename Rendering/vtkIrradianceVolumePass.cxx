#include "vtkIrradianceVolumePass.h"

#include "vtkIrradianceComputeProgram.h"
#include "vtkIrradianceDiffusion.h"
#include "vtkIrradianceRegion.h"
#include "vtkMultiMaterialLightTolerance.h"
#include "vtkMultiMaterialLightUniforms.h"
#include "vtkMultiMaterialParameters.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkOpenGLVertexArrayObject.h"
#include "vtkShaderProgram.h"
#include "vtkShadowSweep.h"
#include "vtkSmartPointer.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include "mmvDiffusionFS.h"
#include "mmvDiffusionGridFS.h"
#include "mmvIrradianceFS.h"
#include "mmvIrradianceTintFS.h"
#include "mmvLayerGS.h"
#include "mmvLayerVS.h"
#include "mmvCutaway.h"
#include "mmvLightModel.h"
#include "mmvPiecewiseShadowFS.h"
#include "mmvShadowRay.h"
#include "mmvVoxelPassDec.h"
#include "mmvVoxelPassMain.h"

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <initializer_list>
#include <memory>
#include <string>

namespace
{

constexpr int LightsPerTexture = mmv::IrradianceLightsPerTexture;

/// Residual checks of a diffusion sub-step: each costs about a sweep and
/// waits for the GPU, so only sub-steps whose error bound asks for at least
/// this many sweeps are checked, four times at most. (Checking short
/// sub-steps too saves sweeps but costs more in waiting than it saves.)
constexpr int ResidualCheckMinimumSweeps = 12;

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

/// A voxel pass: system declarations, `defines`, optionally the light
/// model, the voxel-pass declarations, `body`, then main(); as a fragment
/// shader (VTK's tags) or as a compute shader.
std::string ComposeShader(
  const std::string& body, const std::string& defines, bool lightModel, bool compute)
{
  std::string source = compute ? "#version 430 core\n#define MMV_COMPUTE\n" : "//VTK::System::Dec\n";
  source += mmv::MaterialGLSLPrelude();
  source += mmv::CutawayGLSLPrelude();
  source += defines;
  source += mmvCutaway;
  source += "\n";
  if (lightModel)
  {
    source += mmv::LightUniformDeclarations(std::to_string(LightsPerTexture));
    source += mmvLightModel;
    source += "\n";
  }
  if (!compute)
  {
    source += "//VTK::Output::Dec\n";
  }
  source += mmvVoxelPassDec;
  source += body;
  source += mmvVoxelPassMain;
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

bool HasSize(vtkTextureObject* t, const int d[3])
{
  return t && t->GetHandle() && static_cast<int>(t->GetWidth()) == d[0] &&
    static_cast<int>(t->GetHeight()) == d[1] && static_cast<int>(t->GetDepth()) == d[2];
}

/// A float RGBA 3D texture of size d, kept when it already has that size.
bool EnsureFloatTexture(
  vtkOpenGLRenderWindow* context, vtkSmartPointer<vtkTextureObject>& texture, const int d[3])
{
  if (HasSize(texture, d))
  {
    return true;
  }
  // Linear: the prolongation interpolates the diffusion grid; the other
  // passes read with texelFetch, which ignores filtering.
  texture = NewTexture(context, GL_RGBA32F, GL_RGBA, GL_FLOAT, true);
  return texture->Allocate3D(d[0], d[1], d[2], 4, VTK_FLOAT);
}

/// The pass's lights first .. first + 3 (one output texture's channels)
/// through the ray cast's light layout, and which of them to compute.
void SetLightUniforms(
  vtkShaderProgram* program, const std::vector<mmv::LightSource>& lights, int first, int mask)
{
  const int count = std::min(LightsPerTexture, static_cast<int>(lights.size()) - first);
  program->SetUniformi("numberOfLights", count);
  program->SetUniformi("lightMask", mask);
  mmv::SetLightUniforms(program, lights.data() + first, nullptr, count, LightsPerTexture);
}

/// The uniforms of Shaders/mmvCutaway.glsl.
void SetCutawayUniforms(vtkShaderProgram* program, const mmv::IndexCutaway& cut)
{
  float planes[mmv::MaxCutPlanes][4] = {};
  for (int p = 0; p < cut.NumberOfPlanes; ++p)
  {
    for (int c = 0; c < 4; ++c)
    {
      planes[p][c] = static_cast<float>(cut.Planes[p][c]);
    }
  }
  float axes[3][4] = {};
  float bounds[6] = {};
  for (int a = 0; a < 3; ++a)
  {
    for (int c = 0; c < 4; ++c)
    {
      axes[a][c] = static_cast<float>(cut.CropAxes[a][c]);
    }
    bounds[2 * a] = static_cast<float>(cut.CropBounds[2 * a]);
    bounds[2 * a + 1] = static_cast<float>(cut.CropBounds[2 * a + 1]);
  }
  program->SetUniformi("cutPlaneCount", cut.NumberOfPlanes);
  program->SetUniform4fv("cutPlanes", mmv::MaxCutPlanes, planes);
  program->SetUniformi("cropping", cut.Cropping ? 1 : 0);
  program->SetUniform4fv("cropAxes", 3, axes);
  program->SetUniform1fv("cropBounds", 6, bounds);
  program->SetUniformi("cropFlags", cut.CropFlags);
}

/// A draw's box (i0, i1, j0, j1, k0, k1) that holds no voxel; null is the
/// whole target.
bool IsEmptyBox(const int* box)
{
  return box && (box[0] > box[1] || box[2] > box[3] || box[4] > box[5]);
}

bool SameGrid(const mmv::IrradianceGrid& a, const mmv::IrradianceGrid& b)
{
  return std::equal(a.Dimensions, a.Dimensions + 3, b.Dimensions) && a.Origin == b.Origin &&
    a.Spacing == b.Spacing && a.Direction == b.Direction;
}

/// Activates textures for one draw and deactivates them when it ends.
class ScopedTextures
{
public:
  ScopedTextures(std::initializer_list<vtkTextureObject*> textures)
  {
    for (vtkTextureObject* t : textures)
    {
      if (std::find(this->Textures.begin(), this->Textures.end(), t) == this->Textures.end())
      {
        this->Textures.push_back(t);
      }
    }
    for (vtkTextureObject* t : this->Textures)
    {
      t->Activate();
    }
  }
  ~ScopedTextures()
  {
    for (vtkTextureObject* t : this->Textures)
    {
      t->Deactivate();
    }
  }

private:
  std::vector<vtkTextureObject*> Textures;
};

/// One voxel pass's programs: the layered fragment draw (built on first use)
/// and the compute dispatch (where OpenGL 4.3 is there and asked for).
struct VoxelPass
{
  std::unique_ptr<vtkOpenGLQuadHelper> Quad;
  vtkSmartPointer<vtkIrradianceComputeProgram> Compute;
  // The sources they were built from: a pass whose defines change (a
  // cutaway appears) is rebuilt.
  std::string QuadSource;
  std::string ComputeSource;

  /// The compute program is not the shader cache's own: when it was bound
  /// last, the cache must forget it, or a new program that happens to get
  /// its address would be taken for bound and dispatched unbound (seen with
  /// passes released and created again in one context).
  void ReleaseCompute(vtkWindow* window)
  {
    if (!this->Compute)
    {
      return;
    }
    auto* context = vtkOpenGLRenderWindow::SafeDownCast(window);
    if (context && context->GetShaderCache()->GetLastShaderBound() == this->Compute)
    {
      context->GetShaderCache()->ReleaseCurrentShader();
    }
    this->Compute->ReleaseGraphicsResources(window);
    this->Compute = nullptr;
  }
  void Release(vtkWindow* window)
  {
    if (this->Quad)
    {
      this->Quad->ReleaseGraphicsResources(window);
      this->Quad.reset();
    }
    this->ReleaseCompute(window);
  }
};

} // namespace

class vtkIrradianceVolumePass::vtkInternals
{
public:
  // Inputs, copied by SetInputs().
  mmv::IrradianceGrid Grid;
  std::vector<float> Scalars;
  unsigned long ScalarsVersion = 0; // the caller's, 0: compare the values
  int TableSize = 0;
  std::vector<float> ShadowTable;
  double StepLength = 0.0;
  std::vector<float> OpacityTable;
  std::vector<float> ScatteringTable;
  std::vector<mmv::LightSource> Lights;
  mmv::Cutaway Cut;
  bool HasInputs = false;
  bool Uploaded = false;
  vtkIdType VolumeUploads = 0;
  // The lights the irradiance textures hold, and whether the volume they
  // were computed from is still the current one.
  std::vector<mmv::LightSource> ComputedLights;
  bool VolumeChanged = true;
  bool MultipleScatteringUsed = true;
  bool WarnedNoBarrier = false;
  int ShadowEstimationUsed = -1; // with PiecewiseSlicesUsed: how the held lights were estimated
  int PiecewiseSlicesUsed = 0;

  // Derived on the CPU: s per voxel (-1 where empty), and the diffusion
  // grid (vtkIrradianceDiffusion.h) with its strength and capacity per block
  // (interleaved) and solve lengths.
  std::vector<float> Classes;
  vtkIdType NonEmptyVoxels = 0;
  mmv::DiffusionSettings Diffusion;
  mmv::DiffusionGrid Coarse;
  std::vector<float> CoarseStrength;
  double CoarseMaxRate = 0.0;
  int SubSteps = 0;
  int SweepsPerStep = 0;
  std::vector<double> ExponentialSeries; // c_k of the exponential integrator
  double SpectralRadius = 0.0; // of the Jacobi iteration, for the Chebyshev weights
  mmv::IndexBox ScatteringBox; // diffusion-grid blocks with s > 0
  unsigned int ResidualQuery = 0; // occlusion query counting unconverged blocks

  // The caller's region (SetRegion; every voxel until then or after
  // ResetRegion), the one the textures hold, and what this Render() draws.
  mmv::IndexBox RequestedRegion = mmv::IndexBox::Everything();
  mmv::IndexBox RegionUsed;
  mmv::IrradianceRegionPlan Plan;
  vtkIdType EstimatedVoxels = 0; // of this Render(), all lights
  mmv::IndexBox Region() const
  {
    return this->RequestedRegion.Intersected(mmv::IndexBox::Whole(this->Grid.Dimensions));
  }
  /// `box` for a draw into a grid of `dims`: nullptr when it is the whole
  /// grid (the draws without a scissor, as before regions).
  static const int* DrawBox(const mmv::IndexBox& box, const int dims[3])
  {
    return box == mmv::IndexBox::Whole(dims) ? nullptr : box.Bounds;
  }
  void PlanRegion(bool diffusion);

  // GPU resources.
  vtkSmartPointer<vtkTextureObject> ScalarTexture;
  vtkSmartPointer<vtkTextureObject> ClassTexture;
  vtkSmartPointer<vtkTextureObject> TableTexture;
  vtkSmartPointer<vtkTextureObject> CoarseStrengthTexture;
  std::vector<vtkSmartPointer<vtkTextureObject>> Irradiance;
  // The tint of a non-white transmission colour: its table (4 floats per
  // entry; empty when grey), and one RGBA16F texture per light on the tint
  // grid (mmv::TintDimension).
  std::vector<float> TintTable;
  vtkSmartPointer<vtkTextureObject> TintTableTexture;
  std::vector<vtkSmartPointer<vtkTextureObject>> Tint;
  VoxelPass TintQuad;
  void TintDimensions(int dims[3]) const
  {
    for (int a = 0; a < 3; ++a)
    {
      dims[a] = mmv::TintDimension(this->Grid.Dimensions[a]);
    }
  }
  bool TintPass(vtkOpenGLRenderWindow* context, int light, bool layered);
  // Irradiance grid: [0] shadow rays, [1] after the diffusion. Diffusion
  // grid: [0] restricted, [1..4] rotate through the sweeps (right-hand side,
  // previous, current and next iterate).
  std::array<vtkSmartPointer<vtkTextureObject>, 2> FineScratch;
  std::array<vtkSmartPointer<vtkTextureObject>, 5> CoarseScratch;
  vtkSmartPointer<vtkOpenGLFramebufferObject> Framebuffer;
  VoxelPass ShadowQuad;
  VoxelPass PiecewiseQuad;
  VoxelPass RestrictQuad;
  VoxelPass SweepQuad;
  VoxelPass ExponentialQuad;
  VoxelPass ProlongQuad;
  VoxelPass FillQuad;
  // Compute dispatches instead of fragment draws (this update), and the
  // atomic counter that stands in for the occlusion query there.
  bool Compute = false;
  unsigned int WriteCounter = 0;

  void Classify(const std::vector<float>& opacity, const std::vector<float>& scattering);
  void PlanDiffusion(double time, bool exponential);

  bool Upload(vtkOpenGLRenderWindow* context);
  bool AllocateTargets(vtkOpenGLRenderWindow* context, bool diffusion, bool& reallocated);
  vtkShaderProgram* Ready(vtkOpenGLRenderWindow* context, VoxelPass& pass,
    const std::string& body, const std::string& defines, bool lightModel);
  void DrawLayers(vtkOpenGLRenderWindow* context, VoxelPass& pass, vtkTextureObject* target,
    bool layered, const int* box = nullptr, int writeMask = 0xF);
  void Dispatch(vtkOpenGLRenderWindow* context, VoxelPass& pass, vtkTextureObject* target,
    const int* box, int writeMask, bool countWrites);
  unsigned int CountWrites(vtkOpenGLRenderWindow* context, VoxelPass& pass,
    vtkTextureObject* target, bool layered, const int* box);
  void SetTransferUniforms(vtkShaderProgram* program) const;
  std::string ShadowRayDefines() const;
  void SetShadowRayUniforms(vtkShaderProgram* program) const;

  bool ShadowPass(vtkOpenGLRenderWindow* context, int group, int mask, bool skipEmpty, bool layered);
  bool PiecewiseShadowPass(vtkOpenGLRenderWindow* context, int light, int slicesPerChunk,
    bool skipEmpty, bool layered);
  int Diffuse(vtkOpenGLRenderWindow* context, bool layered, int mask);
  void SetDiffusionGridUniforms(vtkShaderProgram* program);
  int BackwardEulerSweeps(
    vtkOpenGLRenderWindow* context, vtkShaderProgram* sweep, bool layered, int mask, int& current);
  int ExponentialSweeps(
    vtkOpenGLRenderWindow* context, vtkShaderProgram* sweep, bool layered, int& current);
  bool FillPass(vtkOpenGLRenderWindow* context, vtkTextureObject* source, int group, int mask,
    bool layered);
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
// The diffusion grid and how long its solve runs, exactly as the CPU's
// mmv::DiffuseIrradianceOnDiffusionGrid plans them.
void vtkIrradianceVolumePass::vtkInternals::PlanDiffusion(double time, bool exponential)
{
  this->Diffusion.Exponential = exponential;
  this->Diffusion.Time = time;
  std::vector<float> strength(this->Classes.size());
  float maxStrength = 0.0f;
  for (size_t v = 0; v < strength.size(); ++v)
  {
    strength[v] = std::max(0.0f, this->Classes[v]);
    maxStrength = std::max(maxStrength, strength[v]);
  }
  const double spacing[3] = { this->Grid.DataVoxelsPerVoxel[0], this->Grid.DataVoxelsPerVoxel[1],
    this->Grid.DataVoxelsPerVoxel[2] };
  this->Coarse = mmv::PlanDiffusionGrid(this->Grid.Dimensions, spacing, maxStrength, this->Diffusion);
  std::vector<float> coarseStrength;
  std::vector<float> capacity;
  mmv::RestrictToDiffusionGrid(this->Grid.Dimensions, this->Coarse, strength.data(), nullptr,
    &coarseStrength, nullptr, &capacity);
  this->CoarseMaxRate = time > 0.0 ? mmv::MaxDiffusionRate(this->Coarse.Dimensions,
                                       this->Coarse.Spacing, coarseStrength.data(), capacity.data())
                                   : 0.0;
  // One RG texel per block: strength, capacity; and the box of the blocks
  // that scatter, the only ones the sweeps change.
  this->CoarseStrength.resize(2 * coarseStrength.size());
  const int* cd = this->Coarse.Dimensions;
  int* box = this->ScatteringBox.Bounds;
  for (int a = 0; a < 3; ++a)
  {
    box[2 * a] = cd[a] - 1;
    box[2 * a + 1] = 0;
  }
  for (size_t c = 0; c < coarseStrength.size(); ++c)
  {
    this->CoarseStrength[2 * c] = coarseStrength[c];
    this->CoarseStrength[2 * c + 1] = capacity[c];
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
// What this Render() draws for the region; the diffusion's passes each read
// their input's neighbours (every sweep of every sub-step for backward
// Euler, which may stop earlier).
void vtkIrradianceVolumePass::vtkInternals::PlanRegion(bool diffusion)
{
  const int passes = this->ExponentialSeries.empty()
    ? this->SubSteps * this->SweepsPerStep
    : static_cast<int>(this->ExponentialSeries.size());
  this->Plan = mmv::PlanIrradianceRegion(
    this->Region(), this->Grid.Dimensions, diffusion ? &this->Coarse : nullptr, passes);
}

//------------------------------------------------------------------------------
bool vtkIrradianceVolumePass::vtkInternals::Upload(vtkOpenGLRenderWindow* context)
{
  if (this->Uploaded && this->ScalarTexture)
  {
    return true;
  }
  const int* d = this->Grid.Dimensions;
  const int* c = this->Coarse.Dimensions;
  this->ScalarTexture = NewTexture(context, GL_R32F, GL_RED, GL_FLOAT, true);
  this->ClassTexture = NewTexture(context, GL_R32F, GL_RED, GL_FLOAT, false);
  this->TableTexture = NewTexture(context, GL_R32F, GL_RED, GL_FLOAT, true);
  this->CoarseStrengthTexture = NewTexture(context, GL_RG32F, GL_RG, GL_FLOAT, false);
  ++this->VolumeUploads;
  this->Uploaded = this->ScalarTexture->Create3DFromRaw(d[0], d[1], d[2], 1, VTK_FLOAT,
                     this->Scalars.data()) &&
    this->ClassTexture->Create3DFromRaw(d[0], d[1], d[2], 1, VTK_FLOAT, this->Classes.data()) &&
    this->TableTexture->Create2DFromRaw(
      this->TableSize, this->TableSize, 1, VTK_FLOAT, this->ShadowTable.data()) &&
    this->CoarseStrengthTexture->Create3DFromRaw(
      c[0], c[1], c[2], 2, VTK_FLOAT, this->CoarseStrength.data());
  this->TintTableTexture = nullptr;
  if (this->Uploaded && !this->TintTable.empty())
  {
    this->TintTableTexture = NewTexture(context, GL_RGBA32F, GL_RGBA, GL_FLOAT, true);
    this->Uploaded = this->TintTableTexture->Create2DFromRaw(
      this->TableSize, this->TableSize, 4, VTK_FLOAT, this->TintTable.data());
  }
  return this->Uploaded;
}

//------------------------------------------------------------------------------
bool vtkIrradianceVolumePass::vtkInternals::AllocateTargets(
  vtkOpenGLRenderWindow* context, bool diffusion, bool& reallocated)
{
  const int* d = this->Grid.Dimensions;
  const size_t textures = (this->Lights.size() + LightsPerTexture - 1) / LightsPerTexture;
  reallocated = this->Irradiance.size() != textures;
  this->Irradiance.resize(textures);
  bool ok = true;
  for (size_t t = 0; t < textures; ++t)
  {
    // As many channels as lights (the last texture may hold fewer than 4),
    // so the memory is what mmv::IrradianceBytesPerVoxel counts.
    const int lights = std::min(LightsPerTexture,
      static_cast<int>(this->Lights.size()) - static_cast<int>(t) * LightsPerTexture);
    const int channels = mmv::IrradianceTextureChannels(lights);
    vtkSmartPointer<vtkTextureObject>& texture = this->Irradiance[t];
    if (!HasSize(texture, d) || texture->GetComponents() != channels)
    {
      // 16-bit unsigned normalised: values are fractions in [0, 1]. Zeroed:
      // channels without a light are never written, and an NVIDIA driver
      // hands out garbage (NaN after the conversion) where llvmpipe zeroes.
      static const GLenum internal[] = { GL_R16, GL_RG16, GL_RGBA16, GL_RGBA16 };
      static const GLenum format[] = { GL_RED, GL_RG, GL_RGBA, GL_RGBA };
      texture = NewTexture(
        context, internal[channels - 1], format[channels - 1], GL_UNSIGNED_SHORT, true);
      std::vector<unsigned short> zeros(channels * static_cast<size_t>(d[0]) * d[1] * d[2], 0);
      ok = ok &&
        texture->Create3DFromRaw(d[0], d[1], d[2], channels, VTK_UNSIGNED_SHORT, zeros.data());
      reallocated = true;
    }
  }
  // The tint: one texture per light, only while some colour is not white.
  const size_t tints = this->TintTable.empty() ? 0 : this->Lights.size();
  for (size_t t = tints; t < this->Tint.size(); ++t)
  {
    this->Tint[t]->ReleaseGraphicsResources(context);
  }
  reallocated = reallocated || this->Tint.size() != tints;
  this->Tint.resize(tints);
  int tintDims[3];
  this->TintDimensions(tintDims);
  for (auto& texture : this->Tint)
  {
    if (!HasSize(texture, tintDims))
    {
      // Half floats: K in [0, 1] with 11 bits of mantissa also where it is
      // small (deep tinted shadow), linear for the ray cast's lookups.
      texture = NewTexture(context, GL_RGBA16F, GL_RGBA, GL_FLOAT, true);
      ok = ok && texture->Allocate3D(tintDims[0], tintDims[1], tintDims[2], 4, VTK_FLOAT);
      reallocated = true;
    }
  }
  for (size_t i = 0; i < this->FineScratch.size(); ++i)
  {
    // Kept scratch the diffusion no longer needs goes.
    if (i == 0 || diffusion)
    {
      ok = ok && EnsureFloatTexture(context, this->FineScratch[i], d);
    }
    else if (this->FineScratch[i])
    {
      this->FineScratch[i]->ReleaseGraphicsResources(context);
      this->FineScratch[i] = nullptr;
    }
  }
  for (size_t i = 0; i < this->CoarseScratch.size(); ++i)
  {
    if (diffusion)
    {
      ok = ok && EnsureFloatTexture(context, this->CoarseScratch[i], this->Coarse.Dimensions);
    }
    else if (this->CoarseScratch[i])
    {
      this->CoarseScratch[i]->ReleaseGraphicsResources(context);
      this->CoarseScratch[i] = nullptr;
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
  VoxelPass& pass, const std::string& body, const std::string& defines, bool lightModel)
{
  const std::string source = ComposeShader(body, defines, lightModel, this->Compute);
  if (this->Compute)
  {
    if (!pass.Compute || pass.ComputeSource != source)
    {
      pass.ReleaseCompute(context);
      pass.ComputeSource = source;
      auto program = vtkSmartPointer<vtkIrradianceComputeProgram>::New();
      if (!program->Build(source))
      {
        vtkGenericWarningMacro("Irradiance pass: " << program->GetError());
        return nullptr;
      }
      pass.Compute = program;
    }
    return context->GetShaderCache()->ReadyShaderProgram(pass.Compute);
  }
  std::unique_ptr<vtkOpenGLQuadHelper>& quad = pass.Quad;
  if (!quad || pass.QuadSource != source)
  {
    if (quad)
    {
      quad->ReleaseGraphicsResources(context);
    }
    pass.QuadSource = source;
    quad = std::make_unique<vtkOpenGLQuadHelper>(context, mmvLayerVS, source.c_str(), mmvLayerGS);
  }
  if (!quad->Program || !context->GetShaderCache()->ReadyShaderProgram(quad->Program))
  {
    return nullptr;
  }
  return quad->Program;
}

//------------------------------------------------------------------------------
// Every slice of `target` in one instanced draw into the whole 3D texture
// (layered rendering), or, with `layered` off, one draw per slice.
void vtkIrradianceVolumePass::vtkInternals::DrawLayers(vtkOpenGLRenderWindow* context,
  VoxelPass& pass, vtkTextureObject* target, bool layered, const int* box, int writeMask)
{
  if (IsEmptyBox(box))
  {
    return; // nothing of the region's depends on this draw
  }
  if (this->Compute)
  {
    this->Dispatch(context, pass, target, box, writeMask, false);
    return;
  }
  vtkOpenGLQuadHelper& quad = *pass.Quad;
  // `box` (i0, i1, j0, j1, k0, k1, inclusive) limits the draw to the voxels
  // that can change: a scissor in x and y, a range of layers in z.
  vtkOpenGLState* state = context->GetState();
  state->vtkglColorMask((writeMask & 1) != 0, (writeMask & 2) != 0, (writeMask & 4) != 0,
    (writeMask & 8) != 0);
  const int first = box ? box[4] : 0;
  const int last = box ? box[5] : static_cast<int>(target->GetDepth()) - 1;
  state->vtkglViewport(0, 0, target->GetWidth(), target->GetHeight());
  if (box)
  {
    state->vtkglEnable(GL_SCISSOR_TEST);
    state->vtkglScissor(box[0], box[2], box[1] - box[0] + 1, box[3] - box[2] + 1);
  }
  this->Framebuffer->Bind();
  if (layered)
  {
    glFramebufferTexture(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, target->GetHandle(), 0);
    this->Framebuffer->ActivateDrawBuffers(1);
    quad.Program->SetUniformi("firstLayer", first);
    quad.VAO->Bind();
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, last - first + 1);
    quad.VAO->Release();
    glFramebufferTexture(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, 0, 0);
  }
  for (int z = first; !layered && z <= last; ++z)
  {
    // Removed first: re-adding the same texture keeps the old slice.
    this->Framebuffer->RemoveColorAttachment(0);
    this->Framebuffer->AddColorAttachment(0, target, z);
    this->Framebuffer->ActivateDrawBuffers(1);
    quad.Program->SetUniformi("firstLayer", z);
    quad.Render();
  }
  if (!layered)
  {
    this->Framebuffer->RemoveColorAttachment(0);
  }
  if (box)
  {
    state->vtkglDisable(GL_SCISSOR_TEST);
  }
  state->vtkglColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

//------------------------------------------------------------------------------
// The compute form of DrawLayers: one invocation per voxel of `box` (all of
// `target` without one) stores into `target` as an image; the channels off
// in `writeMask` keep what `target` held. With `countWrites`, the atomic
// counter counts the voxels written. The stores are made visible to the
// texture fetches, image accesses and draws that follow.
void vtkIrradianceVolumePass::vtkInternals::Dispatch(vtkOpenGLRenderWindow* context,
  VoxelPass& pass, vtkTextureObject* target, const int* box, int writeMask, bool countWrites)
{
  vtkShaderProgram* program = pass.Compute;
  context->GetShaderCache()->ReadyShaderProgram(program);
  const int whole[6] = { 0, static_cast<int>(target->GetWidth()) - 1, 0,
    static_cast<int>(target->GetHeight()) - 1, 0, static_cast<int>(target->GetDepth()) - 1 };
  const int* b = box ? box : whole;
  const int boxMin[3] = { b[0], b[2], b[4] };
  const int boxMax[3] = { b[1], b[3], b[5] };
  const int size[2] = { whole[1] + 1, whole[3] + 1 };
  const int mask[4] = { (writeMask & 1) != 0, (writeMask & 2) != 0, (writeMask & 4) != 0,
    (writeMask & 8) != 0 };
  // (vtkShaderProgram has no ivec3/bvec4 setters.)
  glUniform3iv(program->FindUniform("mmvBoxMin"), 1, boxMin);
  glUniform3iv(program->FindUniform("mmvBoxMax"), 1, boxMax);
  glUniform2iv(program->FindUniform("mmvTargetSize"), 1, size);
  glUniform4iv(program->FindUniform("mmvWriteMask"), 1, mask);
  program->SetUniformi("mmvCountWrites", countWrites ? 1 : 0);
  if (!this->WriteCounter)
  {
    glGenBuffers(1, &this->WriteCounter);
    glBindBuffer(GL_ATOMIC_COUNTER_BUFFER, this->WriteCounter);
    glBufferData(GL_ATOMIC_COUNTER_BUFFER, sizeof(GLuint), nullptr, GL_DYNAMIC_READ);
  }
  const GLuint zero = 0;
  glBindBufferBase(GL_ATOMIC_COUNTER_BUFFER, 0, this->WriteCounter);
  if (countWrites)
  {
    glBufferSubData(GL_ATOMIC_COUNTER_BUFFER, 0, sizeof(GLuint), &zero);
  }
  // The masked channels are read back from the target itself (already bound
  // where the pass samples its own target, as the piecewise rays do).
  const bool wasActive = target->GetTextureUnit() >= 0;
  if (!wasActive)
  {
    target->Activate();
  }
  program->SetUniformi("mmvTargetBefore", target->GetTextureUnit());
  glBindImageTexture(0, target->GetHandle(), 0, GL_TRUE, 0, GL_READ_WRITE,
    static_cast<GLenum>(target->GetInternalFormat(VTK_FLOAT, 4, false)));
  program->SetUniformi("mmvTarget", 0);
  // 8 x 8 x 4 invocations per group (mmvVoxelPassMain.glsl).
  glDispatchCompute(static_cast<GLuint>((boxMax[0] - boxMin[0] + 8) / 8),
    static_cast<GLuint>((boxMax[1] - boxMin[1] + 8) / 8),
    static_cast<GLuint>((boxMax[2] - boxMin[2] + 4) / 4));
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT |
    GL_FRAMEBUFFER_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT | GL_ATOMIC_COUNTER_BARRIER_BIT);
  glBindImageTexture(0, 0, 0, GL_TRUE, 0, GL_READ_WRITE, GL_RGBA32F);
  if (!wasActive)
  {
    target->Deactivate();
  }
}

//------------------------------------------------------------------------------
// DrawLayers that returns the number of voxels written (the others returned
// without writing: discarded fragments): an occlusion query, or the atomic
// counter of a compute dispatch. Waits for the GPU.
unsigned int vtkIrradianceVolumePass::vtkInternals::CountWrites(vtkOpenGLRenderWindow* context,
  VoxelPass& pass, vtkTextureObject* target, bool layered, const int* box)
{
  GLuint written = 0;
  if (IsEmptyBox(box))
  {
    return written;
  }
  if (this->Compute)
  {
    this->Dispatch(context, pass, target, box, 0xF, true);
    glBindBuffer(GL_ATOMIC_COUNTER_BUFFER, this->WriteCounter);
    glGetBufferSubData(GL_ATOMIC_COUNTER_BUFFER, 0, sizeof(GLuint), &written);
    return written;
  }
  if (!this->ResidualQuery)
  {
    glGenQueries(1, &this->ResidualQuery);
  }
  glBeginQuery(GL_SAMPLES_PASSED, this->ResidualQuery);
  this->DrawLayers(context, pass, target, layered, box);
  glEndQuery(GL_SAMPLES_PASSED);
  glGetQueryObjectuiv(this->ResidualQuery, GL_QUERY_RESULT, &written);
  return written;
}

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

//------------------------------------------------------------------------------
// Multiple scattering of FineScratch[0] into FineScratch[1]: restriction to
// the diffusion grid, the exponential's Chebyshev series (the default) or
// backward-Euler sub-steps each solved by Chebyshev-accelerated Jacobi sweeps
// (their number from the error bound, mmv::ChebyshevSweeps), then the
// prolongation of the change. Returns the passes drawn, or -1 on failure.
int vtkIrradianceVolumePass::vtkInternals::Diffuse(
  vtkOpenGLRenderWindow* context, bool layered, int mask)
{
  const bool exponential = !this->ExponentialSeries.empty();
  vtkShaderProgram* restriction =
    this->Ready(context, this->RestrictQuad, mmvDiffusionGridFS, "#define MMV_RESTRICT\n", false);
  vtkShaderProgram* sweep = exponential
    ? this->Ready(context, this->ExponentialQuad, mmvDiffusionFS, "#define MMV_EXPONENTIAL\n", false)
    : this->Ready(context, this->SweepQuad, mmvDiffusionFS, "", false);
  vtkShaderProgram* prolong = this->Ready(context, this->ProlongQuad, mmvDiffusionGridFS, "", false);
  if (!restriction || !sweep || !prolong)
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
    this->DrawLayers(context, this->RestrictQuad, coarse[0], layered,
      DrawBox(this->Plan.Coarse, this->Coarse.Dimensions));
  }

  int current = 0;
  const int sweeps = exponential ? this->ExponentialSweeps(context, sweep, layered, current)
                                 : this->BackwardEulerSweeps(context, sweep, layered, mask, current);

  context->GetShaderCache()->ReadyShaderProgram(prolong);
  ScopedTextures bound{ this->FineScratch[0], this->ClassTexture, coarse[current],
    this->CoarseStrengthTexture, coarse[0] };
  prolong->SetUniformi("before", coarse[0]->GetTextureUnit());
  prolong->SetUniformi("coarseStrength", this->CoarseStrengthTexture->GetTextureUnit());
  prolong->SetUniformi("fine", this->FineScratch[0]->GetTextureUnit());
  prolong->SetUniformi("classes", this->ClassTexture->GetTextureUnit());
  prolong->SetUniformi("after", coarse[current]->GetTextureUnit());
  this->SetTransferUniforms(prolong);
  this->DrawLayers(context, this->ProlongQuad, this->FineScratch[1], layered,
    DrawBox(this->Plan.Source, this->Grid.Dimensions));
  return sweeps;
}

//------------------------------------------------------------------------------
// The diffusion grid's strength texture (activated here, deactivated by the
// caller), dimensions and 1 / h^2, for the sweeps and the exponential's steps.
void vtkIrradianceVolumePass::vtkInternals::SetDiffusionGridUniforms(vtkShaderProgram* program)
{
  const glm::vec3 invH2(1.0 / (this->Coarse.Spacing[0] * this->Coarse.Spacing[0]),
    1.0 / (this->Coarse.Spacing[1] * this->Coarse.Spacing[1]),
    1.0 / (this->Coarse.Spacing[2] * this->Coarse.Spacing[2]));
  this->CoarseStrengthTexture->Activate();
  program->SetUniformi("classes", this->CoarseStrengthTexture->GetTextureUnit());
  program->SetUniform1iv("dims", 3, this->Coarse.Dimensions);
  program->SetUniform3f("invH2", glm::value_ptr(invH2));
}

//------------------------------------------------------------------------------
// Backward-Euler sub-steps on the diffusion grid, each solved by Chebyshev-
// accelerated Jacobi sweeps; `current` receives the texture of the result.
int vtkIrradianceVolumePass::vtkInternals::BackwardEulerSweeps(vtkOpenGLRenderWindow* context,
  vtkShaderProgram* sweep, bool layered, int mask, int& current)
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
        this->DrawLayers(context, this->SweepQuad, coarse[next], layered, box.Bounds);
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
  this->CoarseStrengthTexture->Deactivate();
  return sweeps;
}

//------------------------------------------------------------------------------
// The exponential's Chebyshev series on the diffusion grid by the Clenshaw
// recurrence (Shaders/mmvDiffusionFS.glsl, MMV_EXPONENTIAL): b_k = c_k u0 +
// 2 B b_k+1 - b_k+2 from k = n down to 1, then c_0 u0 + B b_1 - b_2; u0 is
// the restricted irradiance (texture 0). `current` receives the result.
int vtkIrradianceVolumePass::vtkInternals::ExponentialSweeps(vtkOpenGLRenderWindow* context,
  vtkShaderProgram* sweep, bool layered, int& current)
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
    this->DrawLayers(context, this->ExponentialQuad, coarse[next], layered, box.Bounds);
    ++passes;
    previous = current;
    current = next;
  }
  this->CoarseStrengthTexture->Deactivate();
  return passes;
}

//------------------------------------------------------------------------------
// The final write of the lights in `mask`: the other channels of the
// irradiance texture keep what they hold.
bool vtkIrradianceVolumePass::vtkInternals::FillPass(vtkOpenGLRenderWindow* context,
  vtkTextureObject* source, int group, int mask, bool layered)
{
  vtkShaderProgram* program =
    this->Ready(context, this->FillQuad, mmvDiffusionFS, "#define MMV_FILL_PASS\n", false);
  if (!program)
  {
    return false;
  }
  ScopedTextures bound{ this->ClassTexture, source };
  program->SetUniformi("classes", this->ClassTexture->GetTextureUnit());
  program->SetUniformi("current", source->GetTextureUnit());
  program->SetUniform1iv("dims", 3, this->Grid.Dimensions);
  this->DrawLayers(context, this->FillQuad, this->Irradiance[group], layered,
    DrawBox(this->Plan.Region, this->Grid.Dimensions), mask);
  return true;
}

//------------------------------------------------------------------------------
void vtkIrradianceVolumePass::vtkInternals::ReleaseScratch(vtkWindow* window)
{
  // The float scratch is 8x the result per texture: not worth keeping.
  for (auto* scratch : { this->FineScratch.data(), this->CoarseScratch.data() })
  {
    const size_t count = scratch == this->FineScratch.data() ? this->FineScratch.size()
                                                             : this->CoarseScratch.size();
    for (size_t i = 0; i < count; ++i)
    {
      if (scratch[i])
      {
        scratch[i]->ReleaseGraphicsResources(window);
        scratch[i] = nullptr;
      }
    }
  }
}

//------------------------------------------------------------------------------
void vtkIrradianceVolumePass::vtkInternals::Release(vtkWindow* window)
{
  this->ReleaseScratch(window);
  for (auto* texture : { &this->ScalarTexture, &this->ClassTexture, &this->TableTexture,
         &this->CoarseStrengthTexture })
  {
    if (*texture)
    {
      (*texture)->ReleaseGraphicsResources(window);
      *texture = nullptr;
    }
  }
  for (auto& texture : this->Irradiance)
  {
    texture->ReleaseGraphicsResources(window);
  }
  this->Irradiance.clear();
  for (auto& texture : this->Tint)
  {
    texture->ReleaseGraphicsResources(window);
  }
  this->Tint.clear();
  if (this->TintTableTexture)
  {
    this->TintTableTexture->ReleaseGraphicsResources(window);
    this->TintTableTexture = nullptr;
  }
  this->ComputedLights.clear();
  if (this->ResidualQuery)
  {
    glDeleteQueries(1, &this->ResidualQuery);
    this->ResidualQuery = 0;
  }
  if (this->Framebuffer)
  {
    this->Framebuffer->ReleaseGraphicsResources(window);
    this->Framebuffer = nullptr;
  }
  if (this->WriteCounter)
  {
    glDeleteBuffers(1, &this->WriteCounter);
    this->WriteCounter = 0;
  }
  for (VoxelPass* pass : { &this->ShadowQuad, &this->PiecewiseQuad, &this->RestrictQuad,
         &this->SweepQuad, &this->ExponentialQuad, &this->ProlongQuad, &this->FillQuad,
         &this->TintQuad })
  {
    pass->Release(window);
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
  // A caller's version number saves comparing the scalars (27 MB on the
  // CT-sized head).
  const bool sameScalars = (scalarsVersion != 0 && scalarsVersion == internals.ScalarsVersion) ||
    internals.Scalars == normalizedScalars;
  const bool sameVolume = internals.HasInputs && SameGrid(internals.Grid, grid) &&
    internals.StepLength == stepLength && sameScalars &&
    internals.ShadowTable == shadow && internals.OpacityTable == opacity &&
    internals.ScatteringTable == scattering;
  if (!sameVolume)
  {
    internals.Grid = grid;
    if (!sameScalars)
    {
      internals.Scalars = normalizedScalars;
    }
    internals.TableSize = tableSize;
    internals.ShadowTable = shadow;
    internals.StepLength = stepLength;
    internals.OpacityTable = opacity;
    internals.ScatteringTable = scattering;
    internals.Classify(opacity, scattering);
    internals.PlanDiffusion(this->DiffusionTime, this->ExponentialDiffusion);
    internals.Uploaded = false;
    internals.VolumeChanged = true;
  }
  internals.HasInputs = true;
  internals.ScalarsVersion = scalarsVersion;
}

//------------------------------------------------------------------------------
void vtkIrradianceVolumePass::SetCutaway(const mmv::Cutaway& cutaway)
{
  vtkInternals& internals = *this->Internals;
  if (cutaway.Key() != internals.Cut.Key())
  {
    internals.Cut = cutaway;
    internals.VolumeChanged = true;
    this->Modified();
  }
}

const mmv::Cutaway& vtkIrradianceVolumePass::GetCutaway() const
{
  return this->Internals->Cut;
}

void vtkIrradianceVolumePass::SetCutawayUniforms(vtkShaderProgram* program) const
{
  if (!this->Internals->Cut.IsEmpty())
  {
    ::SetCutawayUniforms(program, mmv::ToIndexSpace(this->Internals->Cut, this->Internals->Grid));
  }
}

//------------------------------------------------------------------------------
void vtkIrradianceVolumePass::SetRegion(const int bounds[6])
{
  mmv::IndexBox region;
  std::copy(bounds, bounds + 6, region.Bounds);
  if (region != this->Internals->RequestedRegion)
  {
    this->Internals->RequestedRegion = region;
    this->Modified();
  }
}

void vtkIrradianceVolumePass::ResetRegion()
{
  this->SetRegion(mmv::IndexBox::Everything().Bounds);
}

void vtkIrradianceVolumePass::GetRegion(int bounds[6]) const
{
  const mmv::IndexBox region = this->Internals->Region();
  std::copy(region.Bounds, region.Bounds + 6, bounds);
}

//------------------------------------------------------------------------------
bool vtkIrradianceVolumePass::Render(vtkOpenGLRenderWindow* context)
{
  vtkInternals& internals = *this->Internals;
  this->NumberOfComputedVoxels = 0;
  this->DiffusionPasses = 0;
  this->NumberOfUpdatedLights = 0;
  this->LastEstimatedVoxels = 0;
  this->LastEstimationSeconds = 0.0;
  this->LastDiffusionSeconds = 0.0;
  this->LastSetupSeconds = 0.0;
  this->LastWriteSeconds = 0.0;
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
  if (internals.Diffusion.Time != this->DiffusionTime ||
    internals.Diffusion.Exponential != this->ExponentialDiffusion)
  {
    internals.PlanDiffusion(this->DiffusionTime, this->ExponentialDiffusion);
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
  const bool diffusion = this->MultipleScattering && this->DiffusionTime > 0.0 &&
    internals.CoarseMaxRate > 0.0;
  const mmv::IndexBox region = internals.Region();
  if (region != internals.RegionUsed)
  {
    internals.RegionUsed = region;
    internals.VolumeChanged = true;
  }
  internals.PlanRegion(diffusion);
  internals.EstimatedVoxels = 0;
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
    // The diffusion sweeps scissor to their blocks: the renderer's own
    // scissor box must come back for the ray cast.
    vtkOpenGLState::ScopedglScissor scissorBox(state);
    state->vtkglDisable(GL_BLEND); // blending would garble the float outputs
    state->vtkglDisable(GL_DEPTH_TEST);
    state->vtkglDisable(GL_SCISSOR_TEST);
    state->vtkglColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    internals.Compute = this->ComputeShaders != FragmentDraws &&
      vtkIrradianceComputeProgram::IsSupported() &&
      (this->ComputeShaders == ComputeDispatches ||
        !vtkIrradianceComputeProgram::IsSoftwareRenderer());
    this->ComputeShadersUsed = internals.Compute;
    bool reallocated = false;
    ok = internals.Upload(context) && internals.AllocateTargets(context, diffusion, reallocated);
    glFinish();
    this->LastSetupSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    // Only the lights that moved (or all, when the volume changed) are
    // recomputed: each light keeps its own channel.
    const bool all = internals.VolumeChanged || reallocated;
    std::vector<bool> updated(internals.Lights.size(), false);
    const double tolerance = mmv::LightToleranceRadians(this->LightDirectionTolerance);
    const glm::dvec3 centre = internals.Grid.Center();
    // A new light, or one beyond the tolerance of what its channel holds;
    // the others keep the placement they were computed for.
    std::vector<mmv::LightSource>& held = internals.ComputedLights;
    held.resize(std::min(held.size(), internals.Lights.size()));
    for (size_t k = 0; k < internals.Lights.size(); ++k)
    {
      if (all || k >= held.size() ||
        !mmv::LightWithinTolerance(held[k], internals.Lights[k], tolerance, centre))
      {
        updated[k] = true;
        if (k < held.size())
        {
          held[k] = internals.Lights[k];
        }
        else
        {
          held.push_back(internals.Lights[k]);
        }
      }
    }
    for (int group = 0; ok && group < this->GetNumberOfIrradianceTextures(); ++group)
    {
      int mask = 0;
      for (int l = 0; l < LightsPerTexture; ++l)
      {
        const size_t k = static_cast<size_t>(group * LightsPerTexture + l);
        if (k < internals.Lights.size() && updated[k])
        {
          mask |= 1 << l;
          ++this->NumberOfUpdatedLights;
        }
      }
      if (mask == 0)
      {
        continue;
      }
      // Directional lights by piecewise rays (unless full rays are asked
      // for), the others by full rays, each light into its own channel.
      int fullMask = 0;
      std::vector<int> swept;
      for (int l = 0; l < LightsPerTexture; ++l)
      {
        const int k = group * LightsPerTexture + l;
        if ((mask & (1 << l)) != 0)
        {
          if (mmv::UsesPiecewiseShadowRays(estimation, internals.Lights[k]))
          {
            swept.push_back(k);
          }
          else
          {
            fullMask |= 1 << l;
          }
        }
      }
      auto stage = std::chrono::steady_clock::now();
      auto elapsed = [&stage]() {
        glFinish();
        const auto now = std::chrono::steady_clock::now();
        const double seconds = std::chrono::duration<double>(now - stage).count();
        stage = now;
        return seconds;
      };
      ok = fullMask == 0 ||
        internals.ShadowPass(
          context, group, fullMask, this->SkipEmptyVoxels, this->LayeredRendering);
      for (const int k : swept)
      {
        ok = ok &&
          internals.PiecewiseShadowPass(context, k, this->PiecewiseShadowSlices,
            this->SkipEmptyVoxels, this->LayeredRendering);
      }
      this->LastEstimationSeconds += elapsed();
      vtkTextureObject* result = internals.FineScratch[0];
      if (ok && diffusion)
      {
        const int sweeps = internals.Diffuse(context, this->LayeredRendering, mask);
        ok = sweeps >= 0;
        this->DiffusionPasses += std::max(0, sweeps);
        result = internals.FineScratch[1];
        this->LastDiffusionSeconds += elapsed();
      }
      ok = ok && internals.FillPass(context, result, group, mask, this->LayeredRendering);
      this->LastWriteSeconds += elapsed();
      for (int l = 0; ok && !internals.Tint.empty() && l < LightsPerTexture; ++l)
      {
        if ((mask & (1 << l)) != 0)
        {
          ok = internals.TintPass(context, group * LightsPerTexture + l, this->LayeredRendering);
        }
      }
      if (!internals.Tint.empty())
      {
        this->LastEstimationSeconds += elapsed();
      }
    }
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
void vtkIrradianceVolumePass::GetDiffusionGridDimensions(int dims[3]) const
{
  for (int a = 0; a < 3; ++a)
  {
    dims[a] = this->Internals->Coarse.Dimensions[a];
  }
}

int vtkIrradianceVolumePass::GetDiffusionSubSteps() const
{
  return this->Internals->SubSteps;
}

int vtkIrradianceVolumePass::GetDiffusionSweepsPerStep() const
{
  return this->Internals->SweepsPerStep;
}

double vtkIrradianceVolumePass::GetDiffusionLength() const
{
  return this->Internals->Coarse.DiffusionLength;
}

//------------------------------------------------------------------------------
vtkTextureObject* vtkIrradianceVolumePass::GetIrradianceTexture(int i) const
{
  const auto& textures = this->Internals->Irradiance;
  return i >= 0 && i < static_cast<int>(textures.size()) ? textures[i].Get() : nullptr;
}

vtkTextureObject* vtkIrradianceVolumePass::GetScalarTexture() const
{
  return this->Internals->Uploaded ? this->Internals->ScalarTexture.Get() : nullptr;
}

vtkTextureObject* vtkIrradianceVolumePass::GetShadowTableTexture() const
{
  return this->Internals->Uploaded ? this->Internals->TableTexture.Get() : nullptr;
}

int vtkIrradianceVolumePass::GetNumberOfIrradianceTextures() const
{
  return static_cast<int>(this->Internals->Irradiance.size());
}

const std::vector<mmv::LightSource>& vtkIrradianceVolumePass::GetComputedLights() const
{
  return this->Internals->ComputedLights;
}

//------------------------------------------------------------------------------
bool vtkIrradianceVolumePass::ReadBack(
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

bool vtkIrradianceVolumePass::ReadBackLights(vtkOpenGLRenderWindow* context, int first, int last,
  std::vector<std::vector<float>>& values)
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
  vtkOpenGLState* state = context->GetState();
  state->PushFramebufferBindings();
  internals.Framebuffer->Bind();
  // Each texture is read once for all the lights it holds.
  for (int t = first / LightsPerTexture; t * LightsPerTexture < last; ++t)
  {
    vtkTextureObject* texture = this->GetIrradianceTexture(t);
    for (int z = 0; texture && z < d[2]; ++z)
    {
      internals.Framebuffer->RemoveColorAttachment(0);
      internals.Framebuffer->AddColorAttachment(0, texture, z);
      internals.Framebuffer->ActivateReadBuffer(0);
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

vtkIdType vtkIrradianceVolumePass::GetScratchMemoryBytes() const
{
  vtkIdType bytes = 0;
  auto add = [&bytes](const vtkSmartPointer<vtkTextureObject>& texture) {
    // RGBA32F: 4 channels of 4 bytes.
    bytes += texture ? static_cast<vtkIdType>(texture->GetWidth()) * texture->GetHeight() *
        texture->GetDepth() * 16
                     : 0;
  };
  std::for_each(this->Internals->FineScratch.begin(), this->Internals->FineScratch.end(), add);
  std::for_each(this->Internals->CoarseScratch.begin(), this->Internals->CoarseScratch.end(), add);
  return bytes;
}

//------------------------------------------------------------------------------
void vtkIrradianceVolumePass::SetTintTable(const float* tintTable)
{
  vtkInternals& internals = *this->Internals;
  std::vector<float> table;
  if (tintTable && internals.TableSize > 0)
  {
    table.assign(tintTable, tintTable + 4 * static_cast<size_t>(internals.TableSize) * internals.TableSize);
  }
  if (table != internals.TintTable)
  {
    internals.TintTable.swap(table);
    internals.Uploaded = false;
    internals.VolumeChanged = true;
  }
}

bool vtkIrradianceVolumePass::IsTinted() const
{
  return !this->Internals->TintTable.empty();
}

vtkTextureObject* vtkIrradianceVolumePass::GetTintTexture(int light) const
{
  const auto& tint = this->Internals->Tint;
  return light >= 0 && light < static_cast<int>(tint.size()) ? tint[light].Get() : nullptr;
}

void vtkIrradianceVolumePass::GetTintDimensions(int dims[3]) const
{
  this->Internals->TintDimensions(dims);
}

bool vtkIrradianceVolumePass::ReadBackTint(
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
      for (int c = 0; c < 3; ++c)
      {
        rgb[3 * (z * sliceSize + p) + c] = rgba[4 * p + c];
      }
    }
  }
  internals.Framebuffer->RemoveColorAttachment(0);
  state->PopFramebufferBindings();
  return true;
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
  os << indent << "LayeredRendering: " << this->LayeredRendering << "\n";
  os << indent << "ComputeShaders: " << this->ComputeShaders
     << " (last update: " << (this->ComputeShadersUsed ? "compute" : "fragment") << ")\n";
  os << indent << "SkipEmptyVoxels: " << this->SkipEmptyVoxels << "\n";
  os << indent << "ShadowEstimation: " << this->ShadowEstimation << "\n";
  os << indent << "PiecewiseShadowSlices: " << this->PiecewiseShadowSlices << "\n";
  os << indent << "DiffusionGrid: " << internals.Coarse.Dimensions[0] << " "
     << internals.Coarse.Dimensions[1] << " " << internals.Coarse.Dimensions[2] << " ("
     << internals.SubSteps << " sub-steps x " << internals.SweepsPerStep << " sweeps)\n";
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
  os << indent << "KeepScratch: " << this->KeepScratch << "\n";
  os << indent << "ScratchMemoryBytes: " << this->GetScratchMemoryBytes() << "\n";
}
