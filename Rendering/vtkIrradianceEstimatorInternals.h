/**
 * @file   vtkIrradianceEstimatorInternals.h
 * @brief  The state vtkIrradianceEstimator keeps between updates and the
 *         helpers its voxel passes share; private to the estimator's sources:
 *         vtkIrradianceEstimator.cxx (inputs, the update's order, results),
 *         vtkIrradianceEstimatorRunner.cxx (programs, draws, dispatches,
 *         textures), vtkIrradianceEstimatorShadows.cxx (shadow rays and
 *         tints) and vtkIrradianceEstimatorDiffusion.cxx (multiple
 *         scattering).
 */
#ifndef vtkIrradianceEstimatorInternals_h
#define vtkIrradianceEstimatorInternals_h

#include "vtkIrradianceEstimator.h"

#include "vtkBlockDiffusionSeries.h"
#include "vtkDiffusionGridTransfer.h"
#include "vtkIrradianceComputeProgram.h"
#include "vtkIrradianceDiffusion.h"
#include "vtkIrradianceRegion.h"
#include "vtkIrradianceTexels.h"
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
#include "vtkTableLookup.h"
#include "vtkTextureObject.h"
#include "vtkVoxelOccupancy.h"
#include "vtk_glew.h"

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <initializer_list>
#include <memory>
#include <string>

#include "mmvCutaway.h"
#include "mmvLightModel.h"
#include "mmvVoxelPassDec.h"
#include "mmvVoxelPassMain.h"

namespace mmv
{
namespace voxelpass
{

constexpr int LightsPerTexture = mmv::IrradianceLightsPerTexture;

/// Residual checks of a diffusion sub-step: each costs about a sweep and
/// waits for the GPU, so only sub-steps whose error bound asks for at least
/// this many sweeps are checked, four times at most. (Checking short
/// sub-steps too saves sweeps but costs more in waiting than it saves.)
constexpr int ResidualCheckMinimumSweeps = 12;

using mmv::EmptyVoxelClass; // vtkIrradianceTexels.h
using mmv::LookupTable;     // vtkTableLookup.h

/// A voxel pass: system declarations, `defines`, optionally the light
/// model, the voxel-pass declarations, `body`, then main(); as a fragment
/// shader (VTK's tags) or as a compute shader.
inline std::string ComposeShader(
  const std::string& body, const std::string& defines, bool lightModel, bool compute)
{
  std::string source =
    compute ? "#version 430 core\n#define MMV_COMPUTE\n" : "//VTK::System::Dec\n";
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
inline vtkSmartPointer<vtkTextureObject> NewTexture(vtkOpenGLRenderWindow* context,
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

inline bool HasSize(vtkTextureObject* t, const int d[3])
{
  return t && t->GetHandle() && static_cast<int>(t->GetWidth()) == d[0] &&
    static_cast<int>(t->GetHeight()) == d[1] && static_cast<int>(t->GetDepth()) == d[2];
}

/// A float texture of `d` with 1, 2 or 4 `components` (R32F, RG32F,
/// RGBA32F), kept while it has them.
inline bool EnsureFloatTexture(vtkOpenGLRenderWindow* context,
  vtkSmartPointer<vtkTextureObject>& texture, const int d[3], int components = 4)
{
  if (HasSize(texture, d) && texture->GetComponents() == components)
  {
    return true;
  }
  static const GLenum internal[] = { GL_R32F, GL_RG32F, GL_RGBA32F, GL_RGBA32F };
  static const GLenum format[] = { GL_RED, GL_RG, GL_RGBA, GL_RGBA };
  // Linear: the prolongation interpolates the diffusion grid; the other
  // passes read with texelFetch, which ignores filtering.
  texture = NewTexture(context, internal[components - 1], format[components - 1], GL_FLOAT, true);
  return texture->Allocate3D(d[0], d[1], d[2], components, VTK_FLOAT);
}

/// The estimator's lights first .. first + 3 (one output texture's channels)
/// through the ray cast's light layout, and which of them to compute.
inline void SetLightUniforms(
  vtkShaderProgram* program, const std::vector<mmv::LightSource>& lights, int first, int mask)
{
  const int count = std::min(LightsPerTexture, static_cast<int>(lights.size()) - first);
  program->SetUniformi("numberOfLights", count);
  program->SetUniformi("lightMask", mask);
  mmv::SetLightUniforms(program, lights.data() + first, nullptr, count, LightsPerTexture);
}

/// The uniforms of Shaders/mmvCutaway.glsl.
inline void SetCutawayUniforms(vtkShaderProgram* program, const mmv::IndexCutaway& cut)
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
  const mmv::CutawayUniformInfo* u = mmv::CutawayUniformLayout;
  program->SetUniformi(u[mmv::CutPlaneCountUniform].Name, cut.NumberOfPlanes);
  program->SetUniform4fv(u[mmv::CutPlanesUniform].Name, mmv::MaxCutPlanes, planes);
  program->SetUniformi(u[mmv::CroppingUniform].Name, cut.Cropping ? 1 : 0);
  program->SetUniform4fv(u[mmv::CropAxesUniform].Name, 3, axes);
  program->SetUniform1fv(u[mmv::CropBoundsUniform].Name, 6, bounds);
  program->SetUniformi(u[mmv::CropFlagsUniform].Name, cut.CropFlags);
}

/// A draw's box (i0, i1, j0, j1, k0, k1) that holds no voxel; null is the
/// whole target.
inline bool IsEmptyBox(const int* box)
{
  return box && (box[0] > box[1] || box[2] > box[3] || box[4] > box[5]);
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
struct VoxelPrograms
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

} // namespace voxelpass
} // namespace mmv

class vtkIrradianceEstimator::vtkInternals
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
  // The scalar texture alone: an opacity edit re-uploads the classes, not it.
  bool ScalarsUploaded = false;
  vtkIdType VolumeUploads = 0;
  // The lights the irradiance textures hold, and whether the volume they
  // were computed from is still the current one.
  std::vector<mmv::LightSource> ComputedLights;
  bool VolumeChanged = true;
  bool MultipleScatteringUsed = true;
  bool WarnedNoBarrier = false;
  int ShadowEstimationUsed = -1; // with PiecewiseSlicesUsed: how the held lights were estimated
  int PiecewiseSlicesUsed = 0;

  // s per voxel (-1 where empty): ClassTexture holds it, made at the upload
  // on the GPU (ClassifyOnGPU) or on the CPU and copied (CopyClasses). The
  // CPU's classes (Classes) hold the current inputs' only where the
  // diffusion plan needs the strengths: multiple scattering on, a positive
  // diffusion time and some s > 0 in the scattering table (NeedsCPUClasses;
  // ClassesOnCPU). Otherwise Classes is CopyClasses' buffer, and
  // NonEmptyVoxels is counted on the CPU from ValueHistogram, without the
  // voxels (CountNonEmptyVoxels). Classes and ClassifyValues' scratch are
  // kept between updates: fresh memory at every time step costs page faults
  // (about 4 ms per MB on the development VM).
  std::vector<float> Classes;
  std::vector<unsigned char> NonEmptyScratch;
  bool ClassesOnCPU = false; // Classes and NonEmptyVoxels hold the current inputs'
  vtkIdType NonEmptyVoxels = 0;
  // Where the voxels' values fall in a table of ValueHistogramSize entries,
  // with LookupTable's arithmetic: [2 e] at entry e exactly, [2 e + 1]
  // strictly between entries e and e + 1; [2 n - 1] NaN or a weight that
  // could underflow (those are counted voxel by voxel). Made once per
  // scalars (cleared when they change) and table size.
  std::vector<vtkIdType> ValueHistogram;
  int ValueHistogramSize = 0;
  void CountNonEmptyVoxels();
  /// ValueHistogram for the current scalars and table size, where the
  /// opacity table allows it (no negative, non-finite or tiny entry);
  /// returns whether it does.
  bool BuildValueHistogram();
  // The tables the classes (ClassTexture, and Classes where the CPU made
  // them) were made from; ClassTexture is made again at the next upload
  // while ClassesStale. Classifications counts the GPU's.
  std::vector<float> ClassifiedOpacity;
  std::vector<float> ClassifiedScattering;
  bool ClassesStale = true;
  vtkIdType Classifications = 0;
  /// Whether the classes made from the Classified tables (of the current
  /// scalars) are the current tables' too: an opacity edit that keeps which
  /// entries are positive (a point's value dragged within the support) and
  /// the scattering keeps every class.
  bool ClassesHold() const;
  // The bricks that may hold non-empty voxels (value ranges once per
  // scalars, marked at every upload): the shadow draws shrink to them.
  mmv::VoxelOccupancy Occupancy;
  /// The part of `box` (a box of the light grid of `stride`) whose voxels a
  /// later pass reads: around the non-empty irradiance voxels, or the
  /// strided points their interpolation reads.
  mmv::IndexBox OccupiedBox(const mmv::IndexBox& box, int stride) const;
  // One diffusion grid (vtkIrradianceDiffusion.h) with its blocks' texels
  // (mmv::DiffusionBlockTexels: face coefficients, capacity, whether they
  // exchange light) and solve lengths, planned on the CPU, the blocks this
  // Render() draws, and its textures.
  struct DiffusionPlan
  {
    bool Planned = false; // for the current classes and settings
    mmv::DiffusionGrid Coarse;
    std::array<std::vector<float>, 2> CoarseFaces;
    std::vector<float> CoarseExchanges; // 1 where a block exchanges light: ExchangeMask's depths
    double CoarseMaxRate = 0.0;
    double FilledShare = 0.0; // mmv::FilledBlockShare of its blocks
    int SubSteps = 0;
    int SweepsPerStep = 0;
    std::vector<double> ExponentialSeries; // c_k of the exponential integrator
    double SpectralRadius = 0.0;           // of the Jacobi iteration, for the Chebyshev weights
    mmv::IndexBox ScatteringBox;           // diffusion-grid blocks with s > 0
    mmv::IndexBox Blocks; // what the restriction and the sweeps draw (the region's plan)
    // The blocks changed since CoarseFacesTextures were made.
    bool CoarseFacesChanged = true;
    // RGBA32F, of CoarseFaces; the second one linear: its alpha, the blocks
    // that scatter, weighs the prolongation's corners.
    std::array<vtkSmartPointer<vtkTextureObject>, 2> CoarseFacesTextures;
    // [0] restricted, [1..4] rotate through the sweeps (right-hand side,
    // previous, current and next iterate).
    std::array<vtkSmartPointer<vtkTextureObject>, 5> CoarseScratch;
    // The diffusion on the CPU (DiffusesOnCPU): the restricted irradiance,
    // the series' iterates and its change.
    mmv::BlockDiffusionSeries Series;
    std::vector<float> Restricted;
    std::vector<float> Change;
    // A GL_TEXTURE_2D_ARRAY of depths, CoarseExchanges (ExchangeMaskHolds:
    // the current ones). The layered draws of the restriction and the
    // sweeps test their quad's depth (0.5) against it, so a software
    // rasterizer runs no shader for blocks the diffusion leaves alone;
    // compute dispatches and per-slice draws return early in the shader
    // instead.
    unsigned int ExchangeMask = 0;
    int ExchangeMaskDimensions[3] = { 0, 0, 0 };
    bool ExchangeMaskHolds = false;
    /// The passes each reading their neighbours: the series' terms, or
    /// every Jacobi sweep of every sub-step.
    int Passes() const
    {
      return this->ExponentialSeries.empty() ? this->SubSteps * this->SweepsPerStep
                                             : static_cast<int>(this->ExponentialSeries.size());
    }
    bool UploadExchangeMask();
    /// The scratch: textures and the CPU's buffers.
    void ReleaseScratch(vtkWindow* window);
    void ReleaseScratchTextures(vtkWindow* window);
    /// Every texture (scratch, blocks, exchange mask); the CPU's buffers stay.
    void ReleaseTextures(vtkWindow* window);
    void Release(vtkWindow* window);
    /// Bytes of the CPU's buffers.
    size_t CPUScratchBytes() const
    {
      return 4 * (this->Restricted.size() + this->Change.size()) + this->Series.GetBytes();
    }
  };
  mmv::DiffusionSettings Diffusion;
  // [0]: the lights on the irradiance grid. [1]: those on a strided light
  // grid (mmv::LightGridDiffusionSettings), planned while one is strided and
  // used where DiffusionOf picks it.
  std::array<DiffusionPlan, 2> Diffusions;
  /// The plan that diffuses lights of grid stride `stride` (an index of
  /// Diffusions): the strided lights' own where it is coarser than the
  /// others', the scattering fills its blocks (mmv::MinimumFilledBlockShare)
  /// and some exchange light on it.
  int DiffusionOf(int stride) const;
  /// The channels each plan's scratch needs: up to the highest channel of a
  /// light it diffuses, 1, 2 or 4 (a software rasterizer sweeps one-channel
  /// float texels in about three quarters of an RGBA grid's time); 4 for
  /// compute dispatches, which store RGBA images.
  std::array<int, 2> ScratchChannels() const;
  /// Plans Diffusions[1] for the current classes where a light is strided
  /// (`strength` and `maxStrength`: DiffusionStrengths, made here if null).
  void PlanStridedDiffusion(const std::vector<float>* strength = nullptr, float maxStrength = 0.0f);
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
  // TableSize x 1 RG32F: (opacity, scattering) per entry, what the class
  // pass reads.
  vtkSmartPointer<vtkTextureObject> ClassTableTexture;
  vtkSmartPointer<vtkTextureObject> TableTexture;
  std::vector<vtkSmartPointer<vtkTextureObject>> Irradiance;
  // A kept step's irradiance and tint textures shown instead of the own
  // (ShowKeptTextures) until the next Render(): held here, as the step
  // cache may drop them meanwhile.
  std::vector<vtkSmartPointer<vtkTextureObject>> ShownIrradiance;
  std::vector<vtkSmartPointer<vtkTextureObject>> ShownTint;
  // Per irradiance texture, the voxels that may hold non-zero values: zero
  // when it is made, and what the last final write covered.
  std::vector<mmv::IndexBox> FilledBoxes;
  // The tint of a non-white transmission colour: its table (4 floats per
  // entry; empty when grey), and one RGBA16F texture per light on the tint
  // grid (mmv::TintDimension).
  std::vector<float> TintTable;
  vtkSmartPointer<vtkTextureObject> TintTableTexture;
  std::vector<vtkSmartPointer<vtkTextureObject>> Tint;
  // The transmittance through the other volumes, per irradiance texture
  // (the scene's, not ours: never released here), and its version.
  std::vector<vtkSmartPointer<vtkTextureObject>> SceneTransmittance;
  unsigned long SceneTransmittanceVersion = 0;
  mmv::voxelpass::VoxelPrograms TintQuad;
  void TintDimensions(int dims[3]) const
  {
    for (int a = 0; a < 3; ++a)
    {
      dims[a] = mmv::TintDimension(this->Grid.Dimensions[a]);
    }
  }
  bool TintPass(vtkOpenGLRenderWindow* context, int light, bool layered);
  // Irradiance grid: [0] shadow rays, [1] after the diffusion.
  std::array<vtkSmartPointer<vtkTextureObject>, 2> FineScratch;
  // The dim lights' transmittance on their strided grid (LightGridStride),
  // before it is interpolated into FineScratch[0]; only while one is dim.
  vtkSmartPointer<vtkTextureObject> LightGridScratch;
  // Which strided points a non-empty irradiance voxel needs (1) or not (0),
  // for the volume upload and stride it was made for.
  vtkSmartPointer<vtkTextureObject> LightGridClassTexture;
  vtkIdType LightGridClassUpload = -1; // the Classifications it was marked from
  int LightGridClassStride = 0;
  // Per axis (rows 0..2), the first and last irradiance index whose
  // interpolation reads each light grid point (RG32F, width the largest
  // light grid dimension).
  vtkSmartPointer<vtkTextureObject> LightGridRangeTexture;
  /// LightGridClassTexture, marked on the GPU from ClassTexture.
  bool MarkLightGridNeeded(vtkOpenGLRenderWindow* context, int stride, bool layered);
  /// Whether LightGridClassTexture holds the marks of the current classes
  /// for `stride`.
  bool LightGridNeededHold(int stride) const;
  /// LightGridClassTexture of the light grid's size for `stride`, its
  /// contents undefined.
  bool EnsureLightGridClassTexture(vtkOpenGLRenderWindow* context, int stride);
  /// Per axis a, range[a][2 p] .. range[a][2 p + 1]: the irradiance indices
  /// whose interpolation reads light grid point p (first > last: none).
  void LightGridNeededRanges(int stride, std::array<std::vector<int>, 3>& range) const;
  /// The CPU's marks (255 where needed, 0 elsewhere) from `classes`, x fastest.
  std::vector<unsigned char> LightGridNeededOnCPU(
    const std::vector<float>& classes, int stride) const;
  // The classes and the strided marks as CopyClasses made and copied them,
  // with the classification they belong to (Classifications then): the
  // shadow rays on the CPU read them where they are the current ones.
  vtkIdType CopiedClassesStamp = -1;
  std::vector<unsigned char> CopiedLightGridNeeded;
  vtkIdType CopiedLightGridNeededStamp = -1;
  int CopiedLightGridNeededStride = 0;
  vtkSmartPointer<vtkOpenGLFramebufferObject> Framebuffer;
  mmv::voxelpass::VoxelPrograms ShadowQuad;
  mmv::voxelpass::VoxelPrograms PiecewiseQuad;
  mmv::voxelpass::VoxelPrograms PointSweepQuad;   // point and spot lights' piecewise rays
  mmv::voxelpass::VoxelPrograms PyramidSweepQuad; // ... around one inside the grid
  mmv::voxelpass::VoxelPrograms RestrictQuad;
  mmv::voxelpass::VoxelPrograms SweepQuad;
  mmv::voxelpass::VoxelPrograms ExponentialQuad;
  mmv::voxelpass::VoxelPrograms ChangeQuad;
  mmv::voxelpass::VoxelPrograms ProlongQuad;
  mmv::voxelpass::VoxelPrograms FillQuad;
  mmv::voxelpass::VoxelPrograms UpsampleQuad;
  mmv::voxelpass::VoxelPrograms ClassifyQuad;
  mmv::voxelpass::VoxelPrograms NeededQuad;
  // Compute dispatches instead of fragment draws (this update), and the
  // atomic counter that stands in for the occlusion query there.
  bool Compute = false;
  // The diffusion on the CPU where it can (this update; DiffusionPlace), and
  // whether one ran there.
  bool DiffusionOnCPU = false;
  bool DiffusionRanOnCPU = false;
  // The irradiance before the diffusion (FineScratch[0], RGBA), read back
  // for a diffusion on the CPU, and diffused in place in the lights'
  // channels before it goes to FineScratch[1].
  std::vector<float> FineOnCPU;
  /// Whether this update diffuses on the CPU: asked to, with the
  /// exponential integrator and the classes the transfers read.
  bool DiffusesOnCPU() const
  {
    return this->DiffusionOnCPU && this->Diffusion.Exponential && this->ClassesOnCPU;
  }
  /// FineScratch[0] into FineOnCPU, and FineOnCPU into FineScratch[1].
  bool ReadFineScratch();
  bool UploadDiffusedFine();
  unsigned int WriteCounter = 0;
  bool ExchangeMaskRefused = false; // the framebuffer would not take a plan's mask

  /// The CPU's classification of the current inputs into Classes and
  /// NonEmptyVoxels.
  void Classify();
  /// The classes of `scalars` on a grid of `dims` from the tables: s where
  /// the voxel is non-empty, EmptyVoxelClass where it is empty. Returns the
  /// non-empty voxels. `nonEmpty` is scratch (one byte per voxel).
  static vtkIdType ClassifyValues(const std::vector<float>& scalars, const int dims[3],
    const std::vector<float>& opacity, const std::vector<float>& scattering,
    std::vector<float>& classes, std::vector<unsigned char>& nonEmpty);
  /// Whether the diffusion plan needs the classes on the CPU.
  bool NeedsCPUClasses(bool multipleScattering, double time) const;
  /// Plans the diffusion; classifies on the CPU first where NeedsCPUClasses,
  /// else (no strength anywhere the diffusion would use) plans for none.
  void PlanDiffusion(double time, bool exponential, bool multipleScattering);
  /// The diffusion's strength per irradiance voxel from the CPU's classes
  /// (0 where empty) and its largest value; empty without CPU classes.
  /// Made into StrengthScratch, which it returns.
  const std::vector<float>& DiffusionStrengths(float& maxStrength);
  // Kept between plans: a new one at every time step would be fresh memory.
  std::vector<float> StrengthScratch;
  /// One diffusion grid of `settings` for `strength` (DiffusionStrengths).
  void PlanDiffusionBlocks(DiffusionPlan& plan, const mmv::DiffusionSettings& settings,
    const std::vector<float>& strength, float maxStrength);

  /// The scalars, tables and, where they are stale, the classes: made on
  /// the CPU and copied where `cpuClasses` (sets `copied`), else on the GPU.
  bool Upload(vtkOpenGLRenderWindow* context, bool layered, bool cpuClasses, bool& copied);
  /// ClassTexture from ScalarTexture and the tables.
  bool ClassifyOnGPU(vtkOpenGLRenderWindow* context, bool layered);
  /// ClassTexture from the CPU's classes (Classes, or made here where the
  /// diffusion did not need them), and the strided lights' needed points
  /// from the same classes.
  bool CopyClasses(vtkOpenGLRenderWindow* context);
  void EnsureFramebuffer(vtkOpenGLRenderWindow* context);
  /// `plan`'s block textures and exchange mask, where they changed.
  bool UploadDiffusionBlocks(vtkOpenGLRenderWindow* context, DiffusionPlan& plan, bool layered);
  bool AllocateTargets(
    vtkOpenGLRenderWindow* context, bool diffusion, bool layered, bool& reallocated);
  vtkShaderProgram* Ready(vtkOpenGLRenderWindow* context, mmv::voxelpass::VoxelPrograms& pass,
    const std::string& body, const std::string& defines, bool lightModel);
  /// With `exchanging`, a layered fragment draw on its diffusion grid skips
  /// the blocks its ExchangeMask marks 0.
  void DrawLayers(vtkOpenGLRenderWindow* context, mmv::voxelpass::VoxelPrograms& pass,
    vtkTextureObject* target, bool layered, const int* box = nullptr, int writeMask = 0xF,
    DiffusionPlan* exchanging = nullptr);
  void Dispatch(vtkOpenGLRenderWindow* context, mmv::voxelpass::VoxelPrograms& pass,
    vtkTextureObject* target, const int* box, int writeMask, bool countWrites);
  unsigned int CountWrites(vtkOpenGLRenderWindow* context, mmv::voxelpass::VoxelPrograms& pass,
    vtkTextureObject* target, bool layered, const int* box);
  void SetTransferUniforms(vtkShaderProgram* program, const DiffusionPlan& plan) const;
  std::string ShadowRayDefines() const;
  void SetShadowRayUniforms(vtkShaderProgram* program) const;

  /// The grid the shadow rays of lights of grid stride `stride` start from
  /// (mmv::LightGridDimension per axis; the irradiance grid for 1), the
  /// texture they write, and the uniforms of Shaders/mmvLightGrid.glsl.
  void LightGridDimensions(int stride, int dims[3]) const;
  /// Light grid coordinate per irradiance index, per axis ((m - 1) / (n - 1)
  /// for m light grid and n irradiance points; 1 where an axis has one point).
  void LightGridRatio(int stride, double ratio[3]) const;
  vtkTextureObject* LightGridTarget(int stride) const;
  vtkTextureObject* LightGridClasses(int stride) const;
  /// Physical point p's index on the light grid of `stride` is this matrix
  /// times (p - the grid's origin).
  glm::dmat3 LightGridPhysicalToIndex(int stride) const;
  void SetLightGridUniforms(vtkShaderProgram* program, int stride) const;
  /// The largest grid stride of the lights (1: every light on the
  /// irradiance grid).
  int MaxLightGridStride() const;
  /// The lights irradiance texture `group` holds (the last may hold fewer
  /// than LightsPerTexture).
  int LightsInTexture(int group) const
  {
    return std::min(mmv::IrradianceLightsPerTexture,
      static_cast<int>(this->Lights.size()) - group * mmv::IrradianceLightsPerTexture);
  }

  bool ShadowPass(
    vtkOpenGLRenderWindow* context, int group, int mask, int stride, bool skipEmpty, bool layered);
  /// Its sweeps (mmv::PlanLightSweeps on its light grid); none: full rays.
  std::vector<mmv::ShadowSweep> LightSweeps(int light, int estimation, int slicesPerChunk) const;
  bool PiecewiseShadowPass(vtkOpenGLRenderWindow* context, int light,
    const std::vector<mmv::ShadowSweep>& sweeps, bool skipEmpty, bool layered);
  /// The region's estimated box on the light grid of `stride`.
  mmv::IndexBox EstimatedOnLightGrid(int stride) const;
  /// Each chunk's box of light `light`'s `sweep` (mmv::PlanSweepBoxes): what
  /// the pass draws, and the CPU computes.
  std::vector<mmv::IndexBox> SweepBoxes(
    int light, const mmv::ShadowSweep& sweep, bool skipEmpty) const;
  // Where a directional light's piecewise rays run (this update;
  // ShadowRaysPlace), and the light grid targets' contents they make there,
  // kept between updates (fresh memory costs page faults): [0] the
  // irradiance grid's (FineScratch[0]), [1] the strided grid's.
  bool SweepsOnCPU = false;
  std::array<std::vector<float>, 2> SweptOnCPU;
  std::array<int, 2> SweptChannels = { 0, 0 }; // floats per point of each, this update
  // The final write on the CPU (WriteOnCPU): an irradiance texture's
  // texels, the whole grid, kept like SweptOnCPU.
  std::vector<unsigned short> WrittenOnCPU;
  /// Whether light `light`'s sweeps run on the CPU in this update: a
  /// directional light's, nothing cut, the CPU's classes (and strided marks)
  /// current.
  bool SweepsLightOnCPU(int light, const std::vector<mmv::ShadowSweep>& sweeps) const;
  /// The lights of `swept` that run on the CPU (SweepsLightOnCPU), swept
  /// into SweptOnCPU and uploaded into their targets; they leave `swept`,
  /// whose other lights the passes draw after. Before any pass of the
  /// group: an upload sets every channel of the box it covers. Calls
  /// `lightDone` after each light's sweep; returns how many it swept.
  int SweepOnCPU(std::vector<std::pair<int, std::vector<mmv::ShadowSweep>>>& swept, bool skipEmpty,
    bool upload, const std::function<void()>& lightDone);
  /// The passes' float scratch (FineScratch, the strided light grid's),
  /// made when a group first goes to the passes: an update whose textures
  /// the CPU writes needs none.
  bool EnsurePassScratch(vtkOpenGLRenderWindow* context, bool diffusion);
  /// Whether group `group`'s final write runs on the CPU (WriteOnCPU) in
  /// this update: every light of the group updated (`mask`) and swept on
  /// the CPU (`swept`, none left to passes), no diffusion or one on the CPU,
  /// no other volume's transmittance, the CPU's classes current.
  bool WritesOnCPU(int group, int mask,
    const std::vector<std::pair<int, std::vector<mmv::ShadowSweep>>>& swept, bool diffusion) const;
  /// What the final write of group `group` reads from the CPU's sweeps.
  mmv::IrradianceTexelInputs SweptTexelInputs(int group) const;
  /// Group `group`'s values from the CPU's sweeps into FineOnCPU for the
  /// diffusion on the CPU (mmv::GatherIrradianceValues): what the sweeps'
  /// upload, the upsampling pass and ReadFineScratch give it.
  void GatherOnCPU(int group, bool skipEmpty);
  /// The final write of group `group` (mmv::WriteIrradianceTexels) from
  /// SweptOnCPU, or from FineOnCPU once `diffused`, uploaded over the box
  /// the fill pass would draw.
  void WriteOnCPU(int group, bool skipEmpty, bool diffused);
  /// The box the final write of group `group` covers in this update, which
  /// it records: the region's occupied voxels and their neighbours, and
  /// what an earlier write reached there.
  mmv::IndexBox FillBox(int group, bool skipEmpty);
  /// The lights of `mask` of a strided light grid, interpolated into their
  /// channels of FineScratch[0] over the estimated box.
  bool UpsamplePass(
    vtkOpenGLRenderWindow* context, int mask, int stride, bool skipEmpty, bool layered);
  int Diffuse(
    vtkOpenGLRenderWindow* context, DiffusionPlan& plan, bool layered, int mask, bool skipEmpty);
  static void SetDiffusionGridUniforms(vtkShaderProgram* program, const DiffusionPlan& plan);
  static void ReleaseDiffusionGridTextures(const DiffusionPlan& plan);
  int BackwardEulerSweeps(vtkOpenGLRenderWindow* context, DiffusionPlan& plan,
    vtkShaderProgram* sweep, bool layered, int mask, int& current);
  int ExponentialSweeps(vtkOpenGLRenderWindow* context, DiffusionPlan& plan,
    vtkShaderProgram* sweep, bool layered, int& current);
  /// Diffuse() on the CPU: restriction, series and prolongation of
  /// FineOnCPU's channels of `mask`, in place; the passes the series stands
  /// for.
  int DiffuseOnCPU(DiffusionPlan& plan, int mask, bool skipEmpty);
  bool FillPass(vtkOpenGLRenderWindow* context, vtkTextureObject* source, int group, int mask,
    bool skipEmpty, bool layered);
  /// Which lights this update recomputes: all of them (`all`), or those
  /// the caller marked (SetLightsToUpdate), or else the new ones and those
  /// beyond `toleranceRadians` of the placement their channel holds;
  /// records the placements they get.
  std::vector<bool> MarkLightsToUpdate(
    bool all, double toleranceRadians, const std::vector<bool>& given);
  std::vector<bool> GivenMarks; // the caller's (SetLightsToUpdate), for one Render()
  void ReleaseScratch(vtkWindow* window);
  void Release(vtkWindow* window);
};

// The updated lights of one irradiance texture, by how their shadows are
// estimated (bit l: the texture's light l).
struct vtkIrradianceEstimator::GroupLights
{
  int Mask = 0;            // every updated light
  int FullMask = 0;        // full rays on the irradiance grid
  int StridedFullMask = 0; // full rays on the strided light grid
  int StridedMask = 0;     // every light on the strided grid
  std::vector<std::pair<int, std::vector<mmv::ShadowSweep>>> Swept; // piecewise
};

#endif
