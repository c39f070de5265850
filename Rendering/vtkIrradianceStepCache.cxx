#include "vtkIrradianceStepCache.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkIrradianceVolumePass.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include <algorithm>

namespace
{
/// Bytes of one texel: the irradiance is 16-bit normalised and the tint half
/// float, whatever VTK type they were allocated with.
size_t TexelBytes(vtkTextureObject* texture)
{
  const int type = texture->GetVTKDataType();
  const unsigned int internal = texture->GetInternalFormat(type, texture->GetComponents(), false);
  switch (internal)
  {
    case GL_R16:
    case GL_RG16:
    case GL_RGBA16:
    case GL_R16F:
    case GL_RG16F:
    case GL_RGBA16F:
      return 2 * static_cast<size_t>(texture->GetComponents());
    default:
      return 4 * static_cast<size_t>(texture->GetComponents());
  }
}

size_t TextureBytes(vtkTextureObject* texture)
{
  return TexelBytes(texture) * texture->GetWidth() * texture->GetHeight() * texture->GetDepth();
}

bool SameSize(vtkTextureObject* a, vtkTextureObject* b)
{
  return a->GetWidth() == b->GetWidth() && a->GetHeight() == b->GetHeight() &&
    a->GetDepth() == b->GetDepth() && a->GetComponents() == b->GetComponents() &&
    a->GetVTKDataType() == b->GetVTKDataType();
}

void CopyTexture(vtkTextureObject* from, vtkTextureObject* to)
{
  glCopyImageSubData(from->GetHandle(), GL_TEXTURE_3D, 0, 0, 0, 0, to->GetHandle(),
    GL_TEXTURE_3D, 0, 0, 0, 0, static_cast<GLsizei>(from->GetWidth()),
    static_cast<GLsizei>(from->GetHeight()), static_cast<GLsizei>(from->GetDepth()));
}

/// An uninitialised texture of `like`'s size and format (storage only: the
/// copies are never sampled).
vtkSmartPointer<vtkTextureObject> NewLike(vtkOpenGLRenderWindow* context, vtkTextureObject* like)
{
  const int type = like->GetVTKDataType();
  const int components = like->GetComponents();
  auto texture = vtkSmartPointer<vtkTextureObject>::New();
  texture->SetContext(context);
  texture->SetInternalFormat(like->GetInternalFormat(type, components, false));
  texture->SetFormat(like->GetFormat(type, components, false));
  texture->SetDataType(like->GetDataType(type));
  if (!texture->Allocate3D(like->GetWidth(), like->GetHeight(), like->GetDepth(), components, type))
  {
    return nullptr;
  }
  return texture;
}
}

//------------------------------------------------------------------------------
bool vtkIrradianceStepCache::Key::operator==(const Key& o) const
{
  return this->Volume == o.Volume && this->MaterialsTime == o.MaterialsTime &&
    this->Scalars == o.Scalars &&
    this->ScalarsTime == o.ScalarsTime &&
    std::equal(this->DataDimensions, this->DataDimensions + 3, o.DataDimensions) &&
    std::equal(this->Origin, this->Origin + 3, o.Origin) &&
    std::equal(this->Spacing, this->Spacing + 3, o.Spacing) &&
    std::equal(this->IrradianceDimensions, this->IrradianceDimensions + 3,
      o.IrradianceDimensions) &&
    this->Lights == o.Lights;
}

bool vtkIrradianceStepCache::Key::SameLighting(const Key& o) const
{
  // The range is the step's own (its finite data range).
  vtkIrradianceInputCache::VolumeKey a = this->Volume;
  vtkIrradianceInputCache::VolumeKey b = o.Volume;
  a.Range[0] = a.Range[1] = b.Range[0] = b.Range[1] = 0.0;
  return a == b && this->MaterialsTime == o.MaterialsTime &&
    std::equal(this->IrradianceDimensions, this->IrradianceDimensions + 3,
      o.IrradianceDimensions) &&
    this->Lights == o.Lights;
}

vtkIrradianceStepCache::Key vtkIrradianceStepCache::MakeKey(
  const vtkIrradianceInputCache::VolumeKey& volume, vtkMTimeType materialsTime,
  vtkImageData* image, vtkDataArray* scalars, const std::vector<mmv::LightSource>& lights,
  const int dims[3])
{
  Key key;
  key.Volume = volume;
  key.Volume.DataTime = 0;
  // The version counts samplings, which a new step's range also bumps.
  key.Volume.MaterialVersion = 0;
  key.MaterialsTime = materialsTime;
  key.Scalars = scalars;
  key.ScalarsTime = scalars ? scalars->GetMTime() : 0;
  if (image)
  {
    image->GetDimensions(key.DataDimensions);
    image->GetOrigin(key.Origin);
    image->GetSpacing(key.Spacing);
  }
  std::copy(dims, dims + 3, key.IrradianceDimensions);
  key.Lights = lights;
  return key;
}

//------------------------------------------------------------------------------
bool vtkIrradianceStepCache::CanCopy()
{
  return glCopyImageSubData != nullptr;
}

std::vector<vtkTextureObject*> vtkIrradianceStepCache::PassTextures(vtkIrradianceVolumePass* pass)
{
  std::vector<vtkTextureObject*> textures;
  for (int t = 0; t < pass->GetNumberOfIrradianceTextures(); ++t)
  {
    textures.push_back(pass->GetIrradianceTexture(t));
  }
  for (int light = 0; pass->GetTintTexture(light); ++light)
  {
    textures.push_back(pass->GetTintTexture(light));
  }
  return textures;
}

//------------------------------------------------------------------------------
bool vtkIrradianceStepCache::Restore(vtkOpenGLRenderWindow* context, const Key& key,
  vtkIrradianceVolumePass* pass, std::vector<mmv::LightSource>& computed)
{
  auto entry = std::find_if(this->Entries.begin(), this->Entries.end(),
    [&key](const Entry& e) { return e.EntryKey == key; });
  if (entry == this->Entries.end() || !context || !CanCopy())
  {
    return false;
  }
  const std::vector<vtkTextureObject*> targets = PassTextures(pass);
  bool fits = targets.size() == entry->Textures.size();
  for (size_t t = 0; fits && t < targets.size(); ++t)
  {
    fits = targets[t] && SameSize(targets[t], entry->Textures[t]);
  }
  if (!fits)
  {
    return false; // the pass's textures were allocated for another grid
  }
  for (size_t t = 0; t < targets.size(); ++t)
  {
    CopyTexture(entry->Textures[t], targets[t]);
  }
  // The pass's record of what its textures hold is no longer true.
  pass->InvalidateComputedLights();
  computed = entry->ComputedLights;
  this->Entries.splice(this->Entries.begin(), this->Entries, entry);
  return true;
}

//------------------------------------------------------------------------------
bool vtkIrradianceStepCache::Contains(const Key& key) const
{
  return std::any_of(this->Entries.begin(), this->Entries.end(),
    [&key](const Entry& e) { return e.EntryKey == key; });
}

bool vtkIrradianceStepCache::Store(vtkOpenGLRenderWindow* context, const Key& key,
  vtkIrradianceVolumePass* pass, const std::vector<mmv::LightSource>& computed,
  size_t budgetBytes)
{
  for (auto entry = this->Entries.begin(); entry != this->Entries.end();)
  {
    auto next = std::next(entry);
    if (entry->EntryKey == key || !entry->EntryKey.SameLighting(key))
    {
      this->Drop(entry);
    }
    entry = next;
  }
  const std::vector<vtkTextureObject*> sources = PassTextures(pass);
  size_t bytes = 0;
  for (vtkTextureObject* texture : sources)
  {
    bytes += TextureBytes(texture);
  }
  if (!context || !CanCopy() || sources.empty() || bytes > budgetBytes)
  {
    this->Trim(budgetBytes);
    return false;
  }
  this->Trim(budgetBytes - bytes);
  Entry entry;
  entry.EntryKey = key;
  entry.ComputedLights = computed;
  entry.Bytes = bytes;
  for (vtkTextureObject* texture : sources)
  {
    vtkSmartPointer<vtkTextureObject> copy = NewLike(context, texture);
    if (!copy)
    {
      for (auto& made : entry.Textures)
      {
        made->ReleaseGraphicsResources(context);
      }
      return false;
    }
    CopyTexture(texture, copy);
    entry.Textures.push_back(copy);
  }
  this->Entries.push_front(std::move(entry));
  this->Bytes += bytes;
  return true;
}

//------------------------------------------------------------------------------
void vtkIrradianceStepCache::Trim(size_t budgetBytes)
{
  while (!this->Entries.empty() && this->Bytes > budgetBytes)
  {
    this->Drop(std::prev(this->Entries.end()));
  }
}

void vtkIrradianceStepCache::Drop(std::list<Entry>::iterator entry)
{
  for (auto& texture : entry->Textures)
  {
    // The context is current wherever entries are dropped (a render, or
    // ReleaseGraphicsResources).
    texture->ReleaseGraphicsResources(texture->GetContext());
  }
  this->Bytes -= entry->Bytes;
  this->Entries.erase(entry);
}

void vtkIrradianceStepCache::ReleaseGraphicsResources(vtkWindow*)
{
  this->Trim(0);
}
