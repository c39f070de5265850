#include "vtkMultiMaterialTextures.h"

#include "vtkTextureCopy.h"

#include "vtkDataArray.h"
#include "vtkIrradianceComputeProgram.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMultiMaterialParameters.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPreIntegrationTable.h"
#include "vtkTextureObject.h"
#include "vtkValueGradient.h"
#include "vtk_glew.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

vtkStandardNewMacro(vtkMultiMaterialTextures);

namespace
{
}

vtkMultiMaterialTextures::vtkMultiMaterialTextures() = default;
vtkMultiMaterialTextures::~vtkMultiMaterialTextures() = default;

void vtkMultiMaterialTextures::UpdateSegmentTables(
  vtkOpenGLRenderWindow* context, const std::vector<vtkPreIntegrationTable*>& tables)
{
  // A colour-only build (vtkPreIntegrationTable::GetColorOnlyBuildCount)
  // leaves the shading positions as they were.
  std::vector<std::pair<vtkPreIntegrationTable*, int>> builds;
  std::vector<std::pair<vtkPreIntegrationTable*, int>> positionBuilds;
  for (vtkPreIntegrationTable* table : tables)
  {
    builds.emplace_back(table, table->GetBuildCount());
    positionBuilds.emplace_back(table, table->GetBuildCount() - table->GetColorOnlyBuildCount());
  }
  const bool colorCurrent = this->SegmentColor->GetHandle() != 0 && builds == this->UploadedTables;
  const bool positionCurrent =
    this->SegmentPosition->GetHandle() != 0 && positionBuilds == this->UploadedPositions;
  if (colorCurrent && positionCurrent)
  {
    return;
  }
  const int n = tables[0]->GetTableSize();
  const int rows = n * static_cast<int>(tables.size());
  if (!colorCurrent)
  {
    this->UploadTable(context, this->SegmentColor, tables, 4, n, rows,
      [](vtkPreIntegrationTable* t) { return t->GetColorOpacityTable(); });
  }
  if (!positionCurrent)
  {
    this->UploadTable(context, this->SegmentPosition, tables, 1, n, rows,
      [](vtkPreIntegrationTable* t) { return t->GetShadingPositionTable(); });
  }
  this->UploadedTables = builds;
  this->UploadedPositions = positionBuilds;
  this->TableSize = n;
  ++this->SegmentUploads;
}

// The tables' `components`-float entries stacked by rows into `texture`: in
// place when it has their size (an edit), else into new storage.
void vtkMultiMaterialTextures::UploadTable(vtkOpenGLRenderWindow* context,
  vtkTextureObject* texture, const std::vector<vtkPreIntegrationTable*>& tables, int components,
  int n, int rows, const std::function<const float*(vtkPreIntegrationTable*)>& entries)
{
  const size_t texels = static_cast<size_t>(n) * n;
  std::vector<float> stacked;
  const float* data = entries(tables[0]);
  if (tables.size() > 1)
  {
    stacked.reserve(components * texels * tables.size());
    for (vtkPreIntegrationTable* table : tables)
    {
      const float* values = entries(table);
      stacked.insert(stacked.end(), values, values + components * texels);
    }
    data = stacked.data();
  }
  if (texture->GetHandle() != 0 && static_cast<int>(texture->GetWidth()) == n &&
    static_cast<int>(texture->GetHeight()) == rows && texture->GetComponents() == components &&
    texture->GetContext() == context)
  {
    texture->Activate();
    glTexSubImage2D(
      GL_TEXTURE_2D, 0, 0, 0, n, rows, components == 4 ? GL_RGBA : GL_RED, GL_FLOAT, data);
    texture->Deactivate();
    return;
  }
  texture->SetContext(context);
  texture->Create2DFromRaw(n, rows, components, VTK_FLOAT, const_cast<float*>(data));
  mmv::UseLinearClamped(texture);
}

void vtkMultiMaterialTextures::UpdateMaterialTable(vtkOpenGLRenderWindow* context,
  const std::vector<vtkMaterialTransferFunction*>& materials, const std::vector<double>& ranges,
  int n)
{
  std::vector<std::pair<vtkMaterialTransferFunction*, vtkMTimeType>> sources;
  for (vtkMaterialTransferFunction* m : materials)
  {
    sources.emplace_back(m, m ? m->GetMTime() : 0);
  }
  if (this->Material->GetHandle() != 0 && sources == this->UploadedMaterials &&
    ranges == this->UploadedRanges && n == this->UploadedMaterialSize)
  {
    return;
  }
  constexpr int P = mmv::MaterialParameterCount;
  constexpr int Rows = mmv::MaterialTextureRows;
  // Laid out as mmv::MaterialTexelLayout, which the shaders read through the
  // prelude's MMV_<NAME>_ROW / _CHANNEL; unused channels hold 0.
  std::vector<float> texels(static_cast<size_t>(n) * Rows * 4 * materials.size(), 0.0f);
  std::vector<float> samples(static_cast<size_t>(n) * P);
  for (size_t f = 0; f < materials.size(); ++f)
  {
    if (materials[f])
    {
      materials[f]->GetTable(ranges[2 * f], ranges[2 * f + 1], n, samples.data());
    }
    else
    {
      for (int i = 0; i < n; ++i)
      {
        for (int p = 0; p < P; ++p)
        {
          samples[i * P + p] = static_cast<float>(mmv::MaterialParameterTable[p].Default);
        }
      }
    }
    float* field = texels.data() + f * static_cast<size_t>(n) * Rows * 4;
    for (int i = 0; i < n; ++i)
    {
      mmv::PackMaterialTexels(&samples[i * P], i, n, field);
    }
  }
  this->Material->SetContext(context);
  this->Material->Create2DFromRaw(
    n, Rows * static_cast<int>(materials.size()), 4, VTK_FLOAT, texels.data());
  mmv::UseLinearClamped(this->Material);
  this->UploadedMaterials = sources;
  this->UploadedRanges = ranges;
  this->UploadedMaterialSize = n;
  ++this->MaterialUploads;
}

bool vtkMultiMaterialTextures::UpdateGradientTexture(vtkOpenGLRenderWindow* context,
  vtkDataArray* scalars, const int dims[3], const double range[2], double maxTextureBytes,
  const double smoothing[3])
{
  const double none[3] = { 0.0, 0.0, 0.0 };
  const double* sigma = smoothing ? smoothing : none;
  const vtkMTimeType time = scalars->GetMTime();
  const bool current = this->Gradient->GetHandle() != 0 && scalars == this->UploadedScalars &&
    time == this->UploadedScalarsTime && range[0] == this->UploadedGradientRange[0] &&
    range[1] == this->UploadedGradientRange[1] &&
    std::equal(dims, dims + 3, this->GradientDimensions) &&
    std::equal(sigma, sigma + 3, this->UploadedGradientSmoothing);
  if (current)
  {
    // Shown before steps were kept (the step on screen when caching began).
    if (this->KeptBudget > 0 && !this->GradientKept)
    {
      this->KeepGradient(context);
    }
    return true;
  }
  if (this->RestoreKeptGradient(scalars, dims, range, sigma))
  {
    return true;
  }
  // A volume longer than the largest 3D texture (rendered in bricks) keeps
  // its gradient volume in one texture, resampled along the long axes.
  const int largest = vtkTextureObject::GetMaximumTextureSize3D(context);
  int textureDims[3];
  // Likewise a gradient volume over maxTextureBytes (6 B a texel) shrinks on
  // every axis.
  const double bytes = 6.0 * dims[0] * dims[1] * dims[2];
  const double shrink =
    maxTextureBytes > 0.0 && bytes > maxTextureBytes ? std::cbrt(maxTextureBytes / bytes) : 1.0;
  for (int a = 0; a < 3; ++a)
  {
    const int fit = std::max(std::min(dims[a], 2), static_cast<int>(dims[a] * shrink));
    textureDims[a] = largest > 1 ? std::min(fit, largest) : fit;
  }
  // From here on the own texture is written and shown.
  this->ShownGradient = nullptr;
  this->Gradient->SetContext(context);
  // Half floats: 6 bytes a voxel, and 11 bits of mantissa keep the faint
  // gradients of soft tissue that 8-bit normals would flatten.
  this->Gradient->SetInternalFormat(GL_RGB16F);
  this->Gradient->SetFormat(GL_RGB);
  this->Gradient->SetDataType(GL_HALF_FLOAT);
  const bool plain = std::equal(dims, dims + 3, textureDims) &&
    std::all_of(sigma, sigma + 3, [](double s) { return s == 0.0; });
  if (!(plain ? this->UploadGradientSlabs(scalars, dims, range)
              : this->UploadGradientVolume(scalars, dims, range, sigma, textureDims)))
  {
    this->UploadedScalars = nullptr;
    return false;
  }
  mmv::UseLinearClamped(this->Gradient);
  this->UploadedScalars = scalars;
  this->UploadedScalarsTime = time;
  this->UploadedGradientRange[0] = range[0];
  this->UploadedGradientRange[1] = range[1];
  std::copy(sigma, sigma + 3, this->UploadedGradientSmoothing);
  std::copy(dims, dims + 3, this->GradientDimensions);
  ++this->GradientUploads;
  this->GradientKept = false;
  this->KeepGradient(context);
  return true;
}

//------------------------------------------------------------------------------
// Gradients of the volume as it is, a slab of slices at a time into the
// texture, kept from the previous step where the size is the same: neither
// the gradients nor the texture's storage are allocated again for a new
// step (fresh memory costs more than computing them on some machines).
bool vtkMultiMaterialTextures::UploadGradientSlabs(
  vtkDataArray* scalars, const int dims[3], const double range[2])
{
  if (this->Gradient->GetHandle() == 0 ||
    !std::equal(dims, dims + 3, this->GradientTextureDimensions))
  {
    if (!this->Gradient->Allocate3D(dims[0], dims[1], dims[2], 3, VTK_UNSIGNED_SHORT))
    {
      return false;
    }
    std::copy(dims, dims + 3, this->GradientTextureDimensions);
  }
  // About a million voxels a slab: small scratch, few uploads.
  const vtkIdType sliceSize = static_cast<vtkIdType>(dims[0]) * dims[1];
  const int slab =
    static_cast<int>(std::max<vtkIdType>(1, (1 << 20) / std::max<vtkIdType>(1, sliceSize)));
  // On a GPU each slab's gradients are computed straight into a pixel
  // buffer that the driver copies into the texture on its own (DMA): from
  // client memory the copy waits on the CPU, about as long as computing
  // them on 16 cores. Orphaned per slab, so a slab never waits for the
  // last one's copy. A software renderer copies on the CPU either way, and
  // each orphaned buffer is fresh host memory (page faults: about 4 ms per
  // MB on the development VM): there, and where a buffer cannot be mapped,
  // the slabs go through client memory that is kept.
  const bool staged = !vtkIrradianceComputeProgram::IsSoftwareRenderer();
  if (staged)
  {
    if (!this->SlabBuffer)
    {
      this->SlabBuffer = vtkSmartPointer<vtkPixelBufferObject>::New();
    }
    this->SlabBuffer->SetContext(this->Gradient->GetContext());
  }
  this->Gradient->Activate();
  GLint alignment = 4;
  glGetIntegerv(GL_UNPACK_ALIGNMENT, &alignment);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1); // 6-byte texels
  for (int first = 0; first < dims[2]; first += slab)
  {
    const int last = std::min(dims[2] - 1, first + slab - 1);
    const size_t bytes = 3 * sizeof(unsigned short) * sliceSize * (last - first + 1);
    auto* mapped = staged ? static_cast<unsigned short*>(
                              this->SlabBuffer->MapUnpackedBuffer(static_cast<unsigned int>(bytes)))
                          : nullptr;
    if (mapped)
    {
      mmv::ComputeHalfValueGradients(
        scalars, 0, dims, range, first, last, this->SlabValues, mapped);
      this->SlabBuffer->UnmapUnpackedBuffer();
      this->SlabBuffer->BindToUnPackedBuffer();
      glTexSubImage3D(GL_TEXTURE_3D, 0, 0, 0, first, dims[0], dims[1], last - first + 1, GL_RGB,
        GL_HALF_FLOAT, nullptr);
      this->SlabBuffer->UnBind();
    }
    else
    {
      mmv::ComputeHalfValueGradients(
        scalars, 0, dims, range, first, last, this->SlabValues, this->SlabHalves);
      glTexSubImage3D(GL_TEXTURE_3D, 0, 0, 0, first, dims[0], dims[1], last - first + 1, GL_RGB,
        GL_HALF_FLOAT, this->SlabHalves.data());
    }
  }
  glPixelStorei(GL_UNPACK_ALIGNMENT, alignment);
  this->Gradient->Deactivate();
  return true;
}

// Smoothed, or resampled to fit: the whole volume's gradients first.
bool vtkMultiMaterialTextures::UploadGradientVolume(vtkDataArray* scalars, const int dims[3],
  const double range[2], const double sigma[3], const int textureDims[3])
{
  std::vector<float> gradients;
  mmv::ComputeValueGradients(scalars, 0, dims, range, gradients);
  mmv::SmoothVectors(gradients, 3, dims, sigma);
  if (!std::equal(dims, dims + 3, textureDims))
  {
    gradients = mmv::ResampleVectors(gradients, 3, dims, textureDims);
  }
  // Packed here, so the upload is a copy.
  std::vector<unsigned short> halves = mmv::PackHalfFloats(gradients);
  if (!this->Gradient->Create3DFromRaw(
        textureDims[0], textureDims[1], textureDims[2], 3, VTK_UNSIGNED_SHORT, halves.data()))
  {
    return false;
  }
  std::copy(textureDims, textureDims + 3, this->GradientTextureDimensions);
  return true;
}

//------------------------------------------------------------------------------
void vtkMultiMaterialTextures::SetKeptGradientBytes(size_t bytes)
{
  // Dropped at the next upload or restore, where the context is current.
  this->KeptBudget = bytes;
}

bool vtkMultiMaterialTextures::RestoreKeptGradient(
  vtkDataArray* scalars, const int dims[3], const double range[2], const double smoothing[3])
{
  this->TrimKeptGradients(this->KeptBudget);
  for (auto kept = this->Kept.begin(); kept != this->Kept.end(); ++kept)
  {
    if (kept->Data.Is(scalars) && kept->Range[0] == range[0] && kept->Range[1] == range[1] &&
      std::equal(dims, dims + 3, kept->Dimensions) &&
      std::equal(smoothing, smoothing + 3, kept->Smoothing))
    {
      // Only in place of a texture of its size (the grid's earlier steps'),
      // which GradientTextureDimensions describes; shown as it is.
      if (!this->Gradient->GetHandle() || !mmv::SameTextureSize(kept->Texture, this->Gradient))
      {
        return false;
      }
      this->ShownGradient = kept->Texture;
      this->UploadedScalars = scalars;
      this->UploadedScalarsTime = scalars->GetMTime();
      std::copy(range, range + 2, this->UploadedGradientRange);
      std::copy(smoothing, smoothing + 3, this->UploadedGradientSmoothing);
      std::copy(dims, dims + 3, this->GradientDimensions);
      this->Kept.splice(this->Kept.begin(), this->Kept, kept);
      this->GradientKept = true;
      ++this->KeptGradientHits;
      return true;
    }
  }
  return false;
}

void vtkMultiMaterialTextures::KeepGradient(vtkOpenGLRenderWindow* context)
{
  vtkTextureObject* shown = this->GetGradientTexture();
  const size_t bytes = mmv::TextureBytes(shown);
  this->TrimKeptGradients(this->KeptBudget);
  if (!mmv::CanCopyTextures() ||
    !mmv::MakeRoomForStep(this->Kept, this->KeptBytes, bytes, this->KeptBudget,
      [this](std::list<KeptGradient>::iterator kept) { this->DropKeptGradient(kept); }))
  {
    return;
  }
  KeptGradient kept;
  kept.Texture = mmv::NewTextureLike(context, shown);
  if (!kept.Texture)
  {
    return;
  }
  mmv::CopyTexture3D(shown, kept.Texture);
  kept.Data = mmv::KeptStepData(this->UploadedScalars, this->UploadedScalarsTime);
  std::copy(this->UploadedGradientRange, this->UploadedGradientRange + 2, kept.Range);
  std::copy(this->UploadedGradientSmoothing, this->UploadedGradientSmoothing + 3, kept.Smoothing);
  std::copy(this->GradientDimensions, this->GradientDimensions + 3, kept.Dimensions);
  kept.Bytes = bytes;
  this->KeptBytes += bytes;
  this->Kept.push_front(kept);
  this->GradientKept = true;
}

void vtkMultiMaterialTextures::TrimKeptGradients(size_t bytes)
{
  while (!this->Kept.empty() && this->KeptBytes > bytes)
  {
    this->DropKeptGradient(std::prev(this->Kept.end()));
  }
}

void vtkMultiMaterialTextures::DropKeptGradient(std::list<KeptGradient>::iterator kept)
{
  mmv::ReleaseUnlessShown(kept->Texture);
  this->KeptBytes -= kept->Bytes;
  this->Kept.erase(kept);
}

void vtkMultiMaterialTextures::Activate()
{
  this->SegmentColor->Activate();
  this->SegmentPosition->Activate();
  this->Material->Activate();
  this->GetGradientTexture()->Activate();
}

void vtkMultiMaterialTextures::Deactivate()
{
  this->SegmentColor->Deactivate();
  this->SegmentPosition->Deactivate();
  this->Material->Deactivate();
  this->GetGradientTexture()->Deactivate();
}

vtkIdType vtkMultiMaterialTextures::GetMemoryBytes() const
{
  const vtkIdType n = this->TableSize;
  // The texture's texels, fewer than the data's points when resampled to fit.
  const vtkIdType gradientBytes = static_cast<vtkIdType>(this->GradientTextureDimensions[0]) *
    this->GradientTextureDimensions[1] * this->GradientTextureDimensions[2] * 3 * 2;
  const vtkIdType fields = static_cast<vtkIdType>(this->UploadedTables.size());
  const vtkIdType materialBytes = static_cast<vtkIdType>(this->UploadedMaterialSize) *
    mmv::MaterialTextureRows * 4 * 4 * static_cast<vtkIdType>(this->UploadedMaterials.size());
  return n * n * (4 + 1) * 4 * fields + materialBytes + gradientBytes;
}

void vtkMultiMaterialTextures::ReleaseGraphicsResources(vtkWindow* window)
{
  this->SegmentColor->ReleaseGraphicsResources(window);
  this->SegmentPosition->ReleaseGraphicsResources(window);
  this->Material->ReleaseGraphicsResources(window);
  this->Gradient->ReleaseGraphicsResources(window);
  // Before the trim, which then releases every kept copy.
  this->ShownGradient = nullptr;
  if (this->SlabBuffer)
  {
    this->SlabBuffer->SetContext(nullptr); // deletes the buffer
    this->SlabBuffer = nullptr;
  }
  this->TrimKeptGradients(0);
  this->GradientKept = false;
  this->UploadedTables.clear();
  this->UploadedMaterials.clear();
  this->UploadedScalars = nullptr;
}

void vtkMultiMaterialTextures::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SegmentUploads: " << this->SegmentUploads << "\n";
  os << indent << "MaterialUploads: " << this->MaterialUploads << "\n";
  os << indent << "GradientUploads: " << this->GradientUploads << "\n";
}
