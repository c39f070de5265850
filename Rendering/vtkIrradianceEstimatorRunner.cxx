// vtkIrradianceEstimator: running its voxel passes (programs, layered draws
// or compute dispatches, the textures they read and write) and the final
// write into the irradiance textures.
#include "vtkIrradianceEstimatorInternals.h"
#include "vtkTextureCopy.h"

#include "vtkIrradianceUpdatePlan.h"
#include "vtkMultiMaterialVolumeGeometry.h" // SamePointsMap

#include "mmvClassifyFS.h"
#include "mmvDiffusionFS.h"
#include "mmvLayerGS.h"
#include "mmvLayerVS.h"
#include "mmvLightGridNeededFS.h"
#include "vtkMultiMaterialThreads.h" // mmv::For
#include "vtkSMPTools.h"

#include <atomic>
#include <mutex>

using namespace mmv::voxelpass;

//------------------------------------------------------------------------------
vtkIdType vtkIrradianceEstimator::vtkInternals::ClassifyValues(const std::vector<float>& scalars,
  const int dims[3], const std::vector<float>& opacity, const std::vector<float>& scattering,
  std::vector<float>& classes, std::vector<unsigned char>& nonEmptyVoxel)
{
  classes.resize(scalars.size());
  nonEmptyVoxel.resize(scalars.size());
  // On all cores: the whole grid at every opacity edit that needs it.
  std::atomic<vtkIdType> nonEmptyVoxels(0);
  mmv::For(0, static_cast<vtkIdType>(scalars.size()),
    [&](vtkIdType begin, vtkIdType end)
    {
      vtkIdType count = 0;
      for (vtkIdType v = begin; v < end; ++v)
      {
        const bool nonEmpty = LookupTable(opacity, scalars[v]) > 0.0f;
        classes[v] =
          nonEmpty ? std::max(0.0f, LookupTable(scattering, scalars[v])) : EmptyVoxelClass(0);
        nonEmptyVoxel[v] = nonEmpty ? 1 : 0;
        count += nonEmpty ? 1 : 0;
      }
      nonEmptyVoxels += count;
    });
  // Empty voxels name their non-empty face neighbours, which the final write averages.
  const vtkIdType nx = dims[0];
  const vtkIdType nxy = nx * dims[1];
  mmv::For(0, static_cast<vtkIdType>(scalars.size()),
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType v = begin; v < end; ++v)
      {
        if (nonEmptyVoxel[v])
        {
          continue;
        }
        const vtkIdType ijk[3] = { v % nx, (v / nx) % dims[1], v / nxy };
        const vtkIdType step[3] = { 1, nx, nxy };
        int neighbors = 0;
        for (int a = 0; a < 3; ++a)
        {
          neighbors |= (ijk[a] > 0 && nonEmptyVoxel[v - step[a]]) ? 1 << (2 * a) : 0;
          neighbors |= (ijk[a] + 1 < dims[a] && nonEmptyVoxel[v + step[a]]) ? 2 << (2 * a) : 0;
        }
        classes[v] = EmptyVoxelClass(neighbors);
      }
    });
  return nonEmptyVoxels;
}

void vtkIrradianceEstimator::vtkInternals::Classify()
{
  this->NonEmptyVoxels = ClassifyValues(this->Scalars, this->Grid.Dimensions, this->OpacityTable,
    this->ScatteringTable, this->Classes, this->NonEmptyScratch);
  this->ClassesOnCPU = true;
  this->BuildValueHistogram(); // for ClassesHold at the next edit
}

bool vtkIrradianceEstimator::vtkInternals::NeedsCPUClasses(
  bool multipleScattering, double time) const
{
  // Without an s > 0 in the table every class is -1 or 0: no strength, and
  // the plan for none is the plan.
  return multipleScattering && time > 0.0 &&
    std::any_of(
      this->ScatteringTable.begin(), this->ScatteringTable.end(), [](float s) { return s > 0.0f; });
}

//------------------------------------------------------------------------------
void vtkIrradianceEstimator::vtkInternals::EnsureFramebuffer(vtkOpenGLRenderWindow* context)
{
  if (!this->Framebuffer)
  {
    this->Framebuffer = vtkSmartPointer<vtkOpenGLFramebufferObject>::New();
    this->Framebuffer->SetContext(context);
  }
}

//------------------------------------------------------------------------------
// The non-empty voxels (LookupTable(opacity, t) > 0) without a pass over
// them at every edit: per table segment, the voxels at its first entry
// exactly (there the interpolation is that entry), and those strictly inside
// it (positive where either end is positive and neither negative). Exact
// for tables without negative entries and without positive ones below
// 1e-30 (where the product with the weight could underflow); the other
// tables, and NaN values and weights below 1e-20, are counted voxel by
// voxel.
void vtkIrradianceEstimator::vtkInternals::CountNonEmptyVoxels()
{
  const std::vector<float>& opacity = this->OpacityTable;
  const int n = static_cast<int>(opacity.size());
  const bool exact = this->BuildValueHistogram();
  if (!exact || this->ValueHistogram[2 * n - 1] > 0)
  {
    std::atomic<vtkIdType> count(0);
    mmv::For(0, static_cast<vtkIdType>(this->Scalars.size()),
      [&](vtkIdType begin, vtkIdType end)
      {
        vtkIdType local = 0;
        for (vtkIdType v = begin; v < end; ++v)
        {
          local += LookupTable(opacity, this->Scalars[v]) > 0.0f ? 1 : 0;
        }
        count += local;
      });
    this->NonEmptyVoxels = count;
    return;
  }
  vtkIdType count = 0;
  for (int e = 0; e < n; ++e)
  {
    count += opacity[e] > 0.0f ? this->ValueHistogram[2 * e] : 0;
    if (e + 1 < n && (opacity[e] > 0.0f || opacity[e + 1] > 0.0f))
    {
      count += this->ValueHistogram[2 * e + 1];
    }
  }
  this->NonEmptyVoxels = count;
}

bool vtkIrradianceEstimator::vtkInternals::BuildValueHistogram()
{
  const std::vector<float>& opacity = this->OpacityTable;
  const int n = static_cast<int>(opacity.size());
  const bool exact = std::none_of(opacity.begin(), opacity.end(),
    [](float a) { return a < 0.0f || (a > 0.0f && a < 1e-30f) || !std::isfinite(a); });
  if (exact && (this->ValueHistogramSize != n || this->ValueHistogram.empty()))
  {
    // Once per scalars and table size.
    std::vector<vtkIdType> histogram(2 * static_cast<size_t>(n), 0);
    std::mutex merge;
    mmv::For(0, static_cast<vtkIdType>(this->Scalars.size()),
      [&](vtkIdType begin, vtkIdType end)
      {
        std::vector<vtkIdType> local(histogram.size(), 0);
        for (vtkIdType v = begin; v < end; ++v)
        {
          const float t = this->Scalars[v];
          const mmv::TablePosition position = mmv::LocateInTable(n, t);
          const int i0 = position.Entry;
          const float f = position.Weight;
          // NaN, and weights so small that f * b could underflow: voxel by
          // voxel.
          const bool unusual = std::isnan(t) || (f > 0.0f && f < 1e-20f);
          ++local[unusual ? 2 * n - 1
                          : (f == 0.0f ? 2 * i0 : (f == 1.0f ? 2 * (n - 1) : 2 * i0 + 1))];
        }
        std::lock_guard<std::mutex> lock(merge);
        for (size_t b = 0; b < local.size(); ++b)
        {
          histogram[b] += local[b];
        }
      });
    this->ValueHistogram.swap(histogram);
    this->ValueHistogramSize = n;
  }
  return exact;
}

//------------------------------------------------------------------------------
// The classes on the GPU (Shaders/mmvClassifyFS.glsl): an opacity edit
// uploads the (opacity, scattering) table, not a class volume.
bool vtkIrradianceEstimator::vtkInternals::ClassifyOnGPU(
  vtkOpenGLRenderWindow* context, bool layered)
{
  const int n = this->TableSize;
  std::vector<float> tables(2 * static_cast<size_t>(n));
  for (int i = 0; i < n; ++i)
  {
    tables[2 * i] = this->OpacityTable[i];
    tables[2 * i + 1] = this->ScatteringTable[i];
  }
  // One texture object for every edit: only its contents change.
  if (!this->ClassTableTexture || this->ClassTableTexture->GetContext() != context)
  {
    this->ClassTableTexture = NewTexture(context, GL_RG32F, GL_RG, GL_FLOAT, false);
  }
  if (!this->ClassTableTexture->Create2DFromRaw(n, 1, 2, VTK_FLOAT, tables.data()))
  {
    return false;
  }
  this->EnsureFramebuffer(context);
  vtkShaderProgram* program = this->Ready(context, this->ClassifyQuad, mmvClassifyFS, "", false);
  if (!program)
  {
    return false;
  }
  ScopedTextures bound{ this->ScalarTexture, this->ClassTableTexture };
  program->SetUniformi("classifyScalars", this->ScalarTexture->GetTextureUnit());
  program->SetUniformi("classifyTables", this->ClassTableTexture->GetTextureUnit());
  program->SetUniformi("classifyTableSize", n);
  program->SetUniform1iv("dims", 3, this->Grid.Dimensions);
  this->DrawLayers(context, this->ClassifyQuad, this->ClassTexture, layered);
  return true;
}

//------------------------------------------------------------------------------
// In place: fresh texture memory costs more than the copy on a software
// rasterizer. The strided marks made here hold until the next
// classification (Classifications already counts this one).
bool vtkIrradianceEstimator::vtkInternals::CopyClasses(vtkOpenGLRenderWindow* context)
{
  if (!this->ClassesOnCPU)
  {
    // Made for the upload only: ClassesOnCPU stays off.
    ClassifyValues(this->Scalars, this->Grid.Dimensions, this->OpacityTable, this->ScatteringTable,
      this->Classes, this->NonEmptyScratch);
  }
  const std::vector<float>& classes = this->Classes;
  const int* d = this->Grid.Dimensions;
  this->ClassTexture->Activate();
  glTexSubImage3D(GL_TEXTURE_3D, 0, 0, 0, 0, d[0], d[1], d[2], GL_RED, GL_FLOAT, classes.data());
  this->ClassTexture->Deactivate();
  this->CopiedClassesStamp = this->Classifications;
  const int stride = this->MaxLightGridStride();
  if (stride <= 1)
  {
    return true;
  }
  if (!this->EnsureLightGridClassTexture(context, stride))
  {
    return false;
  }
  this->CopiedLightGridNeeded = this->LightGridNeededOnCPU(classes, stride);
  this->CopiedLightGridNeededStamp = this->Classifications;
  this->CopiedLightGridNeededStride = stride;
  // Rows of bytes: any length.
  mmv::UploadTextureBox(this->LightGridClassTexture, nullptr, GL_RED, GL_UNSIGNED_BYTE,
    this->CopiedLightGridNeeded.data(), 1);
  this->LightGridClassUpload = this->Classifications;
  this->LightGridClassStride = stride;
  return true;
}

//------------------------------------------------------------------------------
// What this Render() draws for the region; the diffusion's passes each read
// their input's neighbours (every sweep of every sub-step for backward
// Euler, which may stop earlier).
void vtkIrradianceEstimator::vtkInternals::PlanRegion(bool diffusion)
{
  DiffusionPlan& lights = this->Diffusions[0];
  this->Plan = mmv::PlanIrradianceRegion(
    this->Region(), this->Grid.Dimensions, diffusion ? &lights.Coarse : nullptr, lights.Passes());
  lights.Blocks = this->Plan.Coarse;
  DiffusionPlan& strided = this->Diffusions[this->DiffusionOf(this->MaxLightGridStride())];
  if (diffusion && &strided != &lights)
  {
    // The shadow rays feed both grids' restrictions.
    const mmv::IrradianceRegionPlan plan = mmv::PlanIrradianceRegion(
      this->Region(), this->Grid.Dimensions, &strided.Coarse, strided.Passes());
    strided.Blocks = plan.Coarse;
    this->Plan.Estimated = this->Plan.Estimated.United(plan.Estimated);
  }
}

//------------------------------------------------------------------------------
bool vtkIrradianceEstimator::vtkInternals::Upload(
  vtkOpenGLRenderWindow* context, bool layered, bool cpuClasses, bool& copied)
{
  if (this->Uploaded && this->ScalarTexture)
  {
    return true;
  }
  const int* d = this->Grid.Dimensions;
  const bool scalarsKept =
    this->ScalarsUploaded && this->ScalarTexture && this->ScalarTexture->GetHandle() != 0;
  if (!scalarsKept)
  {
    // New values on the same grid (a time step, several fields' opacity
    // edit) go into the texture in place: fresh memory costs more than the
    // copy (about 4 ms per MB on llvmpipe).
    if (HasSize(this->ScalarTexture, d))
    {
      this->ScalarTexture->Activate();
      glTexSubImage3D(
        GL_TEXTURE_3D, 0, 0, 0, 0, d[0], d[1], d[2], GL_RED, GL_FLOAT, this->Scalars.data());
      this->ScalarTexture->Deactivate();
      this->ScalarsUploaded = true;
    }
    else
    {
      this->ScalarTexture = NewTexture(context, GL_R32F, GL_RED, GL_FLOAT, true);
      this->ScalarsUploaded =
        this->ScalarTexture->Create3DFromRaw(d[0], d[1], d[2], 1, VTK_FLOAT, this->Scalars.data());
    }
    this->Occupancy.SetValues(this->Scalars, d);
  }
  bool classes = true;
  bool classesKept = scalarsKept;
  if (!HasSize(this->ClassTexture, d))
  {
    // Written by ClassifyOnGPU below.
    this->ClassTexture = NewTexture(context, GL_R32F, GL_RED, GL_FLOAT, false);
    classes = this->ClassTexture->Allocate3D(d[0], d[1], d[2], 1, VTK_FLOAT);
    classesKept = false;
  }
  this->TableTexture = NewTexture(context, GL_R32F, GL_RED, GL_FLOAT, true);
  ++this->VolumeUploads;
  this->Uploaded = this->ScalarsUploaded && classes &&
    this->TableTexture->Create2DFromRaw(
      this->TableSize, this->TableSize, 1, VTK_FLOAT, this->ShadowTable.data());
  this->TintTableTexture = nullptr;
  if (this->Uploaded && !this->TintTable.empty())
  {
    this->TintTableTexture = NewTexture(context, GL_RGBA32F, GL_RGBA, GL_FLOAT, true);
    this->Uploaded = this->TintTableTexture->Create2DFromRaw(
      this->TableSize, this->TableSize, 4, VTK_FLOAT, this->TintTable.data());
  }
  if (this->Uploaded && (!classesKept || this->ClassesStale))
  {
    // The occupied bricks follow the same classes.
    this->Occupancy.Classify(this->OpacityTable);
    ++this->Classifications;
    this->Uploaded =
      cpuClasses ? this->CopyClasses(context) : this->ClassifyOnGPU(context, layered);
    copied = cpuClasses;
    this->ClassesStale = !this->Uploaded;
  }
  return this->Uploaded;
}

//------------------------------------------------------------------------------
// A voxel is non-empty where (1 - f) a + f b > 0 (LookupTable: a, b the
// entries around its value, f its weight). With no negative or non-finite
// entry, every positive entry at least 1e-10, and no voxel whose weight
// lies in (0, 1e-20) (the value histogram's last bin), neither product
// underflows, so which entries are positive decides every voxel; its class
// is then that and the scattering.
bool vtkIrradianceEstimator::vtkInternals::ClassesHold() const
{
  const std::vector<float>& opacityThen = this->ClassifiedOpacity;
  const size_t n = this->OpacityTable.size();
  if (opacityThen.size() != n || this->ClassifiedScattering != this->ScatteringTable ||
    this->ValueHistogramSize != static_cast<int>(n) || this->ValueHistogram.size() != 2 * n ||
    this->ValueHistogram[2 * n - 1] != 0)
  {
    return false;
  }
  auto usual = [](float a) { return a == 0.0f || (std::isfinite(a) && a >= 1e-10f); };
  for (size_t e = 0; e < n; ++e)
  {
    const float before = opacityThen[e];
    const float now = this->OpacityTable[e];
    if (!usual(before) || !usual(now) || (before > 0.0f) != (now > 0.0f))
    {
      return false;
    }
  }
  return true;
}

//------------------------------------------------------------------------------
// `plan`'s block textures and exchange mask: they change with the plan, not
// at every edit, and in place while the grid keeps its size (fresh memory
// costs more).
bool vtkIrradianceEstimator::vtkInternals::UploadDiffusionBlocks(
  vtkOpenGLRenderWindow* context, DiffusionPlan& plan, bool layered)
{
  const int* c = plan.Coarse.Dimensions;
  bool ok = true;
  if (plan.CoarseFacesChanged || !HasSize(plan.CoarseFacesTextures[0], c))
  {
    for (size_t t = 0; t < plan.CoarseFacesTextures.size(); ++t)
    {
      auto& texture = plan.CoarseFacesTextures[t];
      if (HasSize(texture, c) && texture->GetContext() == context)
      {
        texture->Activate();
        glTexSubImage3D(GL_TEXTURE_3D, 0, 0, 0, 0, c[0], c[1], c[2], GL_RGBA, GL_FLOAT,
          plan.CoarseFaces[t].data());
        texture->Deactivate();
        continue;
      }
      texture = NewTexture(context, GL_RGBA32F, GL_RGBA, GL_FLOAT, t == 1);
      ok =
        ok && texture->Create3DFromRaw(c[0], c[1], c[2], 4, VTK_FLOAT, plan.CoarseFaces[t].data());
    }
    plan.CoarseFacesChanged = !ok;
    plan.ExchangeMaskHolds = false;
  }
  if (ok && !plan.ExchangeMaskHolds && !this->ExchangeMaskRefused && !this->Compute && layered)
  {
    plan.ExchangeMaskHolds = plan.UploadExchangeMask();
  }
  return ok;
}

//------------------------------------------------------------------------------
bool vtkIrradianceEstimator::vtkInternals::AllocateTargets(
  vtkOpenGLRenderWindow* context, bool diffusion, bool layered, bool& reallocated)
{
  const int* d = this->Grid.Dimensions;
  const size_t textures = (this->Lights.size() + LightsPerTexture - 1) / LightsPerTexture;
  reallocated = this->Irradiance.size() != textures;
  this->Irradiance.resize(textures);
  this->FilledBoxes.resize(textures, mmv::IndexBox::Whole(d));
  bool ok = true;
  for (size_t t = 0; t < textures; ++t)
  {
    // As many channels as lights (the last texture may hold fewer than 4),
    // so the memory is what mmv::IrradianceBytesPerVoxel counts.
    const int channels = mmv::IrradianceTextureChannels(this->LightsInTexture(static_cast<int>(t)));
    vtkSmartPointer<vtkTextureObject>& texture = this->Irradiance[t];
    if (!HasSize(texture, d) || texture->GetComponents() != channels)
    {
      // 16-bit unsigned normalised: values are fractions in [0, 1]. Zeroed:
      // channels without a light are never written, and an NVIDIA driver
      // hands out garbage (NaN after the conversion) where llvmpipe zeroes.
      static const GLenum internal[] = { GL_R16, GL_RG16, GL_RGBA16, GL_RGBA16 };
      static const GLenum format[] = { GL_RED, GL_RG, GL_RGBA, GL_RGBA };
      texture =
        NewTexture(context, internal[channels - 1], format[channels - 1], GL_UNSIGNED_SHORT, true);
      std::vector<unsigned short> zeros(channels * static_cast<size_t>(d[0]) * d[1] * d[2], 0);
      ok = ok &&
        texture->Create3DFromRaw(d[0], d[1], d[2], channels, VTK_UNSIGNED_SHORT, zeros.data());
      this->FilledBoxes[t] = mmv::IndexBox();
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
  // The passes make their float scratch when they run (EnsurePassScratch):
  // an update that writes every texture on the CPU needs none. Kept scratch
  // the diffusion no longer needs goes.
  if (!diffusion && this->FineScratch[1])
  {
    this->FineScratch[1]->ReleaseGraphicsResources(context);
    this->FineScratch[1] = nullptr;
  }
  const int stride = this->MaxLightGridStride();
  if (stride > 1)
  {
    ok = ok && this->MarkLightGridNeeded(context, stride, layered);
  }
  else
  {
    for (auto* texture :
      { &this->LightGridScratch, &this->LightGridClassTexture, &this->LightGridRangeTexture })
    {
      if (*texture)
      {
        (*texture)->ReleaseGraphicsResources(context);
        *texture = nullptr;
      }
    }
  }
  // The diffusion plans in use (the strided lights' where theirs is coarser)
  // get their blocks and scratch; kept scratch the diffusion no longer needs
  // goes.
  // A diffusion on the CPU reads the blocks' texels and keeps its buffers
  // on the CPU: the plans' textures go, and nothing is uploaded for them.
  const DiffusionPlan* strided = &this->Diffusions[this->DiffusionOf(stride)];
  const std::array<int, 2> channels = this->ScratchChannels();
  const bool onCPU = diffusion && this->DiffusesOnCPU();
  if (!onCPU)
  {
    std::vector<float>().swap(this->FineOnCPU);
  }
  for (DiffusionPlan& plan : this->Diffusions)
  {
    if (onCPU)
    {
      plan.ReleaseTextures(context);
    }
    else if (diffusion && (&plan == &this->Diffusions[0] || &plan == strided))
    {
      ok = ok && this->UploadDiffusionBlocks(context, plan, layered);
      const int components = channels[&plan - this->Diffusions.data()];
      for (auto& texture : plan.CoarseScratch)
      {
        ok = ok && EnsureFloatTexture(context, texture, plan.Coarse.Dimensions, components);
      }
    }
    else
    {
      plan.ReleaseScratch(context);
    }
  }
  this->EnsureFramebuffer(context);
  return ok;
}

//------------------------------------------------------------------------------
bool vtkIrradianceEstimator::vtkInternals::EnsurePassScratch(
  vtkOpenGLRenderWindow* context, bool diffusion)
{
  const int* d = this->Grid.Dimensions;
  bool ok = EnsureFloatTexture(context, this->FineScratch[0], d) &&
    (!diffusion || EnsureFloatTexture(context, this->FineScratch[1], d));
  const int stride = this->MaxLightGridStride();
  if (ok && stride > 1)
  {
    int lightDims[3];
    this->LightGridDimensions(stride, lightDims);
    ok = EnsureFloatTexture(context, this->LightGridScratch, lightDims);
  }
  return ok;
}

//------------------------------------------------------------------------------
// A strided point is needed where the trilinear interpolation to a
// non-empty irradiance voxel reads it: the two points around the voxel per
// axis (the point at or below it, floor(i * ratio), and the next, clamped).
// Marked once per volume upload, so a strided point's emptiness costs one
// fetch in the shadow passes. The voxels that read point p along an axis
// are those whose point below is p - 1 or p: one run of indices, as that
// point never decreases along the axis.
void vtkIrradianceEstimator::vtkInternals::LightGridNeededRanges(
  int stride, std::array<std::vector<int>, 3>& range) const
{
  const int* d = this->Grid.Dimensions;
  int c[3];
  this->LightGridDimensions(stride, c);
  double ratio[3];
  this->LightGridRatio(stride, ratio);
  for (int a = 0; a < 3; ++a)
  {
    range[a].assign(2 * static_cast<size_t>(c[a]), 0);
    for (int p = 0; p < c[a]; ++p)
    {
      range[a][2 * p] = d[a];
      range[a][2 * p + 1] = -1;
    }
    for (int i = 0; i < d[a]; ++i)
    {
      const int below = std::min(static_cast<int>(std::floor(i * ratio[a])), c[a] - 1);
      for (const int p : { below, std::min(below + 1, c[a] - 1) })
      {
        range[a][2 * p] = std::min(range[a][2 * p], i);
        range[a][2 * p + 1] = std::max(range[a][2 * p + 1], i);
      }
    }
  }
}

std::vector<unsigned char> vtkIrradianceEstimator::vtkInternals::LightGridNeededOnCPU(
  const std::vector<float>& classes, int stride) const
{
  const int* d = this->Grid.Dimensions;
  int c[3];
  this->LightGridDimensions(stride, c);
  double ratio[3];
  this->LightGridRatio(stride, ratio);
  std::array<std::vector<int>, 3> below; // per axis: the point at or below each voxel
  for (int a = 0; a < 3; ++a)
  {
    below[a].resize(d[a]);
    for (int i = 0; i < d[a]; ++i)
    {
      below[a][i] = std::min(static_cast<int>(std::floor(i * ratio[a])), c[a] - 1);
    }
  }
  std::vector<unsigned char> needed(static_cast<size_t>(c[0]) * c[1] * c[2], 0);
  // In parallel over the light grid's planes: each writes only its own.
  mmv::For(0, c[2],
    [&](vtkIdType zBegin, vtkIdType zEnd)
    {
      for (int z = static_cast<int>(zBegin); z < zEnd; ++z)
      {
        for (int k = 0; k < d[2]; ++k)
        {
          const bool reads = below[2][k] == z || std::min(below[2][k] + 1, c[2] - 1) == z;
          for (int j = 0; reads && j < d[1]; ++j)
          {
            const size_t rowOfVoxels = (static_cast<size_t>(k) * d[1] + j) * d[0];
            for (int i = 0; i < d[0]; ++i)
            {
              if (classes[rowOfVoxels + i] < 0.0f)
              {
                continue;
              }
              for (int dj = 0; dj < 2; ++dj)
              {
                const int y = std::min(below[1][j] + dj, c[1] - 1);
                const size_t row = (static_cast<size_t>(z) * c[1] + y) * c[0];
                needed[row + below[0][i]] = 255; // GL_R8 reads it as 1
                needed[row + std::min(below[0][i] + 1, c[0] - 1)] = 255;
              }
            }
          }
        }
      }
    });
  return needed;
}

// On the GPU (Shaders/mmvLightGridNeededFS.glsl): a pass over the light
// grid reads the classes of the voxels that interpolate from each point.
bool vtkIrradianceEstimator::vtkInternals::MarkLightGridNeeded(
  vtkOpenGLRenderWindow* context, int stride, bool layered)
{
  if (this->LightGridNeededHold(stride))
  {
    return true;
  }
  int c[3];
  this->LightGridDimensions(stride, c);
  std::array<std::vector<int>, 3> range;
  this->LightGridNeededRanges(stride, range);
  const int width = std::max({ c[0], c[1], c[2] });
  std::vector<float> ranges(2 * static_cast<size_t>(width) * 3, 0.0f);
  for (int a = 0; a < 3; ++a)
  {
    for (int p = 0; p < width; ++p)
    {
      // Indices below 2^24: exact in a float.
      ranges[2 * (static_cast<size_t>(a) * width + p)] =
        p < c[a] ? static_cast<float>(range[a][2 * p]) : 1.0f;
      ranges[2 * (static_cast<size_t>(a) * width + p) + 1] =
        p < c[a] ? static_cast<float>(range[a][2 * p + 1]) : 0.0f;
    }
  }
  this->LightGridRangeTexture = NewTexture(context, GL_RG32F, GL_RG, GL_FLOAT, false);
  bool ok = this->LightGridRangeTexture->Create2DFromRaw(width, 3, 2, VTK_FLOAT, ranges.data()) &&
    this->EnsureLightGridClassTexture(context, stride);
  vtkShaderProgram* program =
    ok ? this->Ready(context, this->NeededQuad, mmvLightGridNeededFS, "", false) : nullptr;
  if (!program)
  {
    return false;
  }
  this->EnsureFramebuffer(context);
  ScopedTextures bound{ this->ClassTexture, this->LightGridRangeTexture };
  program->SetUniformi("classes", this->ClassTexture->GetTextureUnit());
  program->SetUniformi("neededRanges", this->LightGridRangeTexture->GetTextureUnit());
  program->SetUniform1iv("lightDims", 3, c);
  this->DrawLayers(context, this->NeededQuad, this->LightGridClassTexture, layered);
  this->LightGridClassUpload = this->Classifications;
  this->LightGridClassStride = stride;
  return true;
}

bool vtkIrradianceEstimator::vtkInternals::LightGridNeededHold(int stride) const
{
  int c[3];
  this->LightGridDimensions(stride, c);
  return this->LightGridClassUpload == this->Classifications &&
    this->LightGridClassStride == stride && HasSize(this->LightGridClassTexture, c);
}

bool vtkIrradianceEstimator::vtkInternals::EnsureLightGridClassTexture(
  vtkOpenGLRenderWindow* context, int stride)
{
  int c[3];
  this->LightGridDimensions(stride, c);
  if (HasSize(this->LightGridClassTexture, c))
  {
    return true;
  }
  this->LightGridClassTexture = NewTexture(context, GL_R8, GL_RED, GL_UNSIGNED_BYTE, false);
  return this->LightGridClassTexture->Allocate3D(c[0], c[1], c[2], 1, VTK_UNSIGNED_CHAR);
}

//------------------------------------------------------------------------------
vtkShaderProgram* vtkIrradianceEstimator::vtkInternals::Ready(vtkOpenGLRenderWindow* context,
  VoxelPrograms& pass, const std::string& body, const std::string& defines, bool lightModel)
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
void vtkIrradianceEstimator::vtkInternals::DrawLayers(vtkOpenGLRenderWindow* context,
  VoxelPrograms& pass, vtkTextureObject* target, bool layered, const int* box, int writeMask,
  DiffusionPlan* exchanging)
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
  state->vtkglColorMask(
    (writeMask & 1) != 0, (writeMask & 2) != 0, (writeMask & 4) != 0, (writeMask & 8) != 0);
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
    bool masked = exchanging && exchanging->ExchangeMaskHolds;
    glFramebufferTexture(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, target->GetHandle(), 0);
    if (masked)
    {
      glFramebufferTexture(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, exchanging->ExchangeMask, 0);
      // A driver that will not pair a 3D colour target with a depth array
      // gets the unmasked draw: the shader leaves those blocks alone too,
      // only later.
      masked = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
      if (!masked)
      {
        glFramebufferTexture(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, 0, 0);
        exchanging->ExchangeMaskHolds = false;
        this->ExchangeMaskRefused = true;
      }
    }
    if (masked)
    {
      state->vtkglEnable(GL_DEPTH_TEST);
      state->vtkglDepthFunc(GL_LESS);
      state->vtkglDepthMask(GL_FALSE);
    }
    this->Framebuffer->ActivateDrawBuffers(1);
    quad.Program->SetUniformi("firstLayer", first);
    quad.VAO->Bind();
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, last - first + 1);
    quad.VAO->Release();
    glFramebufferTexture(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, 0, 0);
    if (masked)
    {
      glFramebufferTexture(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, 0, 0);
      state->vtkglDisable(GL_DEPTH_TEST);
    }
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
void vtkIrradianceEstimator::vtkInternals::Dispatch(vtkOpenGLRenderWindow* context,
  VoxelPrograms& pass, vtkTextureObject* target, const int* box, int writeMask, bool countWrites)
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
  // where the estimator samples its own target, as the piecewise rays do).
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
unsigned int vtkIrradianceEstimator::vtkInternals::CountWrites(vtkOpenGLRenderWindow* context,
  VoxelPrograms& pass, vtkTextureObject* target, bool layered, const int* box)
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
// The final write of the lights in `mask`: the other channels of the
// irradiance texture keep what they hold.
bool vtkIrradianceEstimator::vtkInternals::FillPass(vtkOpenGLRenderWindow* context,
  vtkTextureObject* source, int group, int mask, bool skipEmpty, bool layered)
{
  // The other volumes' transmittance, where there are other volumes.
  vtkTextureObject* scene = static_cast<size_t>(group) < this->SceneTransmittance.size()
    ? this->SceneTransmittance[group].Get()
    : nullptr;
  vtkShaderProgram* program = this->Ready(context, this->FillQuad, mmvDiffusionFS,
    scene ? "#define MMV_FILL_PASS\n#define MMV_SCENE_TRANSMITTANCE\n" : "#define MMV_FILL_PASS\n",
    false);
  if (!program)
  {
    return false;
  }
  ScopedTextures bound{ this->ClassTexture, source, scene ? scene : source };
  program->SetUniformi("classes", this->ClassTexture->GetTextureUnit());
  program->SetUniformi("current", source->GetTextureUnit());
  program->SetUniform1iv("dims", 3, this->Grid.Dimensions);
  if (scene)
  {
    const int sceneDims[3] = { static_cast<int>(scene->GetWidth()),
      static_cast<int>(scene->GetHeight()), static_cast<int>(scene->GetDepth()) };
    float scale[3];
    float bias[3];
    for (int a = 0; a < 3; ++a)
    {
      mmv::SamePointsMap(this->Grid.Dimensions[a], sceneDims[a], scale[a], bias[a]);
    }
    program->SetUniformi("sceneTransmittance", scene->GetTextureUnit());
    program->SetUniform3f("sceneScale", scale);
    program->SetUniform3f("sceneBias", bias);
  }
  const mmv::IndexBox drawn = this->FillBox(group, skipEmpty);
  if (!drawn.IsEmpty())
  {
    this->DrawLayers(context, this->FillQuad, this->Irradiance[group], layered,
      DrawBox(drawn, this->Grid.Dimensions), mask);
  }
  return true;
}

//------------------------------------------------------------------------------
mmv::IndexBox vtkIrradianceEstimator::vtkInternals::FillBox(int group, bool skipEmpty)
{
  // Beyond the occupied bricks and their neighbours every voxel is empty
  // with empty neighbours: the write gives it 0, which it holds already
  // unless an earlier write reached it (a support that shrank). The write
  // covers both, on the region.
  const mmv::IndexBox& region = this->Plan.Region;
  const mmv::IndexBox needed = skipEmpty
    ? this->OccupiedBox(region, 1).Grown(1, this->Grid.Dimensions).Intersected(region)
    : region;
  mmv::IndexBox& filled = this->FilledBoxes[group];
  const mmv::IndexBox drawn = needed.United(filled.Intersected(region));
  filled = filled.Intersected(region) == filled ? needed : needed.United(filled);
  return drawn;
}

//------------------------------------------------------------------------------
void vtkIrradianceEstimator::vtkInternals::ReleaseScratch(vtkWindow* window)
{
  std::vector<float>().swap(this->FineOnCPU);
  for (auto& buffer : this->SweptOnCPU)
  {
    std::vector<float>().swap(buffer);
  }
  std::vector<unsigned short>().swap(this->WrittenOnCPU);
  // The float scratch is 8x the result per texture: not worth keeping.
  if (this->LightGridScratch)
  {
    this->LightGridScratch->ReleaseGraphicsResources(window);
    this->LightGridScratch = nullptr;
  }
  for (auto& texture : this->FineScratch)
  {
    if (texture)
    {
      texture->ReleaseGraphicsResources(window);
      texture = nullptr;
    }
  }
  for (auto& plan : this->Diffusions)
  {
    plan.ReleaseScratch(window);
  }
}

//------------------------------------------------------------------------------
void vtkIrradianceEstimator::vtkInternals::Release(vtkWindow* window)
{
  // A kept step's textures are the step cache's.
  this->ShownIrradiance.clear();
  this->ShownTint.clear();
  this->ReleaseScratch(window);
  for (auto& plan : this->Diffusions)
  {
    plan.Release(window);
  }
  for (auto* texture : { &this->ScalarTexture, &this->ClassTexture, &this->TableTexture,
         &this->LightGridClassTexture, &this->ClassTableTexture, &this->LightGridRangeTexture })
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
  this->SceneTransmittance.clear(); // the scene's textures: released by it
  this->SceneTransmittanceVersion = 0;
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
  this->ExchangeMaskRefused = false; // another context may take it
  for (VoxelPrograms* pass : { &this->ShadowQuad, &this->PiecewiseQuad, &this->PointSweepQuad,
         &this->PyramidSweepQuad, &this->RestrictQuad, &this->SweepQuad, &this->ExponentialQuad,
         &this->ChangeQuad, &this->ProlongQuad, &this->FillQuad, &this->TintQuad,
         &this->UpsampleQuad, &this->ClassifyQuad, &this->NeededQuad })
  {
    pass->Release(window);
  }
  this->Uploaded = false;
  this->ScalarsUploaded = false;
}

//------------------------------------------------------------------------------
std::vector<bool> vtkIrradianceEstimator::vtkInternals::MarkLightsToUpdate(
  bool all, double toleranceRadians, const std::vector<bool>& given)
{
  // A new light, or one beyond the tolerance of what its channel holds;
  // the others keep the placement they were computed for.
  std::vector<mmv::LightSource>& held = this->ComputedLights;
  held.resize(std::min(held.size(), this->Lights.size()));
  std::vector<bool> updated;
  if (given.size() >= this->Lights.size())
  {
    updated.assign(given.begin(), given.begin() + this->Lights.size());
    std::replace(updated.begin(), updated.end(), false, all);
  }
  else
  {
    updated = vtkIrradianceUpdatePlan::MarkLights(
      held, this->Lights, all, toleranceRadians, this->Grid.Center());
  }
  held.resize(this->Lights.size());
  for (size_t k = 0; k < this->Lights.size(); ++k)
  {
    if (updated[k])
    {
      held[k] = this->Lights[k];
    }
  }
  return updated;
}
