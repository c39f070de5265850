#include "vtkIrradianceStepCache.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkIrradianceEstimator.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkTextureCopy.h"
#include "vtkTextureObject.h"

#include <algorithm>

//------------------------------------------------------------------------------
bool vtkIrradianceStepCache::Key::operator==(const Key& o) const
{
  return this->Volume == o.Volume && this->MaterialsTime == o.MaterialsTime &&
    this->Data == o.Data &&
    std::equal(this->DataDimensions, this->DataDimensions + 3, o.DataDimensions) &&
    std::equal(this->Origin, this->Origin + 3, o.Origin) &&
    std::equal(this->Spacing, this->Spacing + 3, o.Spacing) &&
    std::equal(
      this->IrradianceDimensions, this->IrradianceDimensions + 3, o.IrradianceDimensions) &&
    this->Lights == o.Lights;
}

bool vtkIrradianceStepCache::Key::SameLighting(const Key& o) const
{
  // The range is the step's own (its finite data range).
  vtkIrradianceInputCache::VolumeKey a = this->Volume;
  vtkIrradianceInputCache::VolumeKey b = o.Volume;
  a.Range[0] = a.Range[1] = b.Range[0] = b.Range[1] = 0.0;
  return a == b && this->MaterialsTime == o.MaterialsTime &&
    std::equal(
      this->IrradianceDimensions, this->IrradianceDimensions + 3, o.IrradianceDimensions) &&
    this->Lights == o.Lights;
}

vtkIrradianceStepCache::Key vtkIrradianceStepCache::MakeKey(
  const vtkIrradianceInputCache::VolumeKey& volume, vtkMTimeType materialsTime, vtkImageData* image,
  vtkDataArray* scalars, const std::vector<mmv::LightSource>& lights, const int dims[3])
{
  Key key;
  key.Volume = volume;
  key.Volume.DataTime = 0;
  // The version counts samplings, which a new step's range also bumps.
  key.Volume.MaterialVersion = 0;
  key.MaterialsTime = materialsTime;
  key.Data = mmv::KeptStepData(scalars, scalars ? scalars->GetMTime() : 0);
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
std::vector<vtkTextureObject*> vtkIrradianceStepCache::PassTextures(vtkIrradianceEstimator* pass)
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
  vtkIrradianceEstimator* pass, std::vector<mmv::LightSource>& computed)
{
  auto entry = std::find_if(this->Entries.begin(), this->Entries.end(),
    [&key](const Entry& e) { return e.EntryKey == key; });
  if (entry == this->Entries.end() || !context)
  {
    return false;
  }
  const std::vector<vtkTextureObject*> targets = PassTextures(pass);
  bool fits = targets.size() == entry->Textures.size();
  for (size_t t = 0; fits && t < targets.size(); ++t)
  {
    fits = targets[t] && mmv::SameTextureSize(targets[t], entry->Textures[t]);
  }
  if (!fits)
  {
    return false; // the estimator's textures are of another grid or layout
  }
  // Shown as they are: nothing is copied.
  const auto irradianceEnd = entry->Textures.begin() + pass->GetNumberOfIrradianceTextures();
  pass->ShowKeptTextures(std::vector<vtkTextureObject*>(entry->Textures.begin(), irradianceEnd),
    std::vector<vtkTextureObject*>(irradianceEnd, entry->Textures.end()));
  computed = entry->ComputedLights;
  this->Entries.splice(this->Entries.begin(), this->Entries, entry);
  return true;
}

//------------------------------------------------------------------------------
bool vtkIrradianceStepCache::Store(vtkOpenGLRenderWindow* context, const Key& key,
  vtkIrradianceEstimator* pass, const std::vector<mmv::LightSource>& computed, size_t budgetBytes)
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
    bytes += mmv::TextureBytes(texture);
  }
  if (!context || !mmv::CanCopyTextures() || sources.empty() ||
    !mmv::MakeRoomForStep(this->Entries, this->Bytes, bytes, budgetBytes,
      [this](std::list<Entry>::iterator entry) { this->Drop(entry); }))
  {
    return false;
  }
  Entry entry;
  entry.EntryKey = key;
  entry.ComputedLights = computed;
  entry.Bytes = bytes;
  for (vtkTextureObject* texture : sources)
  {
    vtkSmartPointer<vtkTextureObject> copy = mmv::NewTextureLike(context, texture);
    if (!copy)
    {
      for (auto& made : entry.Textures)
      {
        made->ReleaseGraphicsResources(context);
      }
      return false;
    }
    mmv::CopyTexture3D(texture, copy);
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
  // The context is current wherever entries are dropped (a render, or
  // ReleaseGraphicsResources).
  for (auto& texture : entry->Textures)
  {
    mmv::ReleaseUnlessShown(texture);
  }
  this->Bytes -= entry->Bytes;
  this->Entries.erase(entry);
}

void vtkIrradianceStepCache::ReleaseGraphicsResources(vtkWindow*)
{
  this->Trim(0);
}
