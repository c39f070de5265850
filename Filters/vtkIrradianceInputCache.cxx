#include "vtkIrradianceInputCache.h"

#include "vtkGlobalPrefilteredVolume.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMultiMaterialLiveObjects.h"
#include "vtkMultiMaterialParameters.h"
#include "vtkMultiMaterialThreads.h" // mmv::For
#include "vtkObjectFactory.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>

vtkStandardNewMacro(vtkIrradianceInputCache);

vtkIrradianceInputCache::vtkIrradianceInputCache()
{
  vtkMultiMaterialLiveObjects::Constructed("vtkIrradianceInputCache");
}

vtkIrradianceInputCache::~vtkIrradianceInputCache()
{
  vtkMultiMaterialLiveObjects::Destroyed("vtkIrradianceInputCache");
}

bool vtkIrradianceInputCache::MaterialKey::operator==(const MaterialKey& o) const
{
  return this->MaterialTime == o.MaterialTime && this->Range[0] == o.Range[0] &&
    this->Range[1] == o.Range[1] && this->TableSize == o.TableSize;
}

bool vtkIrradianceInputCache::PrefilterKey::operator==(const PrefilterKey& o) const
{
  return std::equal(this->Dimensions, this->Dimensions + 3, o.Dimensions) &&
    this->DataTime == o.DataTime && this->Range[0] == o.Range[0] && this->Range[1] == o.Range[1];
}

//------------------------------------------------------------------------------
void vtkIrradianceInputCache::SampleMaterials(
  vtkMaterialTransferFunction* materials, const double range[2], int n)
{
  MaterialKey key;
  key.MaterialTime = materials ? materials->GetMTime() : 0;
  key.Range[0] = range[0];
  key.Range[1] = range[1];
  key.TableSize = n;
  if (this->HasMaterials && key == this->Materials)
  {
    return;
  }
  // What the shadows' extinction reads: the attenuation, then the
  // transmission colour (the tint), n values each.
  std::vector<float> extinction(4 * static_cast<size_t>(n), 1.0f);
  std::vector<float> scattering(n, 0.0f);
  for (int i = 0; materials && i < n; ++i)
  {
    const double t = range[0] + (range[1] - range[0]) * i / (n - 1);
    extinction[i] = static_cast<float>(materials->EvaluateParameter(t, mmv::Attenuation));
    scattering[i] = static_cast<float>(materials->EvaluateParameter(t, mmv::Scattering));
    for (int c = 0; c < 3; ++c)
    {
      extinction[(c + 1) * static_cast<size_t>(n) + i] =
        static_cast<float>(materials->EvaluateParameter(t, mmv::TransmissionR + c));
    }
  }
  if (extinction != this->Extinction || scattering != this->Scattering)
  {
    this->Extinction = extinction;
    this->Scattering = scattering;
    ++this->MaterialVersion;
  }
  this->Materials = key;
  this->HasMaterials = true;
}

//------------------------------------------------------------------------------
bool vtkIrradianceInputCache::UpdatePrefiltered(vtkImageData* image, vtkDataArray* scalars,
  vtkGlobalPrefilteredVolume* global, const int dims[3], vtkMTimeType dataTime,
  const double range[2])
{
  PrefilterKey key;
  std::copy(dims, dims + 3, key.Dimensions);
  key.DataTime = dataTime;
  key.Range[0] = range[0];
  key.Range[1] = range[1];
  if (this->HasPrefiltered && key == this->PrefilteredFrom)
  {
    return false;
  }
  mmv::IrradianceGrid grid;
  // Into the buffer the step before last used: no new memory per step.
  std::vector<float> values;
  values.swap(this->SpareValues);
  if (global)
  {
    grid = global->GetGrid();
    values = global->GetValues();
  }
  else
  {
    grid = mmv::MakeIrradianceGrid(image, dims);
    mmv::PrefilterScalars(image, scalars, 0, grid, values, &this->Scratch);
  }
  const double scale = 1.0 / (range[1] - range[0]);
  mmv::For(0, static_cast<vtkIdType>(values.size()),
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType i = begin; i < end; ++i)
      {
        values[i] = static_cast<float>((values[i] - range[0]) * scale);
      }
    });
  // Normalised, the finite range is [0, 1].
  const bool nonFinite = mmv::ReplaceNonFinite(values, 0.0f, 1.0f);
  // The only comparison of the values: a new data time whose values are
  // the same (a pipeline that executed again) keeps the version, so the
  // irradiance pass, which trusts it, keeps every light.
  if (!this->HasPrefiltered || !grid.IsSameGrid(this->Grid) || values != this->Prefiltered)
  {
    ++this->PrefilteredVersion;
  }
  this->Grid = grid;
  this->Prefiltered.swap(values);
  this->SpareValues.swap(values);
  this->PrefilteredFrom = key;
  this->HasPrefiltered = true;
  return nonFinite;
}

//------------------------------------------------------------------------------
vtkIrradianceUpdatePlan vtkIrradianceInputCache::Plan(
  const vtkIrradianceUpdatePlan::Inputs& now, double toleranceRadians) const
{
  return vtkIrradianceUpdatePlan::Make(
    this->HasVolume ? &this->Held : nullptr, now, toleranceRadians, this->Grid.Center());
}

bool vtkIrradianceInputCache::IsCurrent(const VolumeKey& volume,
  const std::vector<mmv::LightSource>& lights, const int dims[3], double toleranceRadians) const
{
  vtkIrradianceUpdatePlan::Inputs now;
  now.Volume = volume;
  std::copy(dims, dims + 3, now.Dimensions);
  now.Lights = lights;
  return this->Plan(now, toleranceRadians).IsCurrent();
}

bool vtkIrradianceInputCache::SameVolume(const VolumeKey& volume) const
{
  vtkIrradianceUpdatePlan::Inputs now = this->Held;
  now.Volume = volume;
  return this->Plan(now, 0.0).KeepsVolume();
}

void vtkIrradianceInputCache::Store(
  const VolumeKey& volume, const std::vector<mmv::LightSource>& lights, const int dims[3])
{
  this->Held.Volume = volume;
  this->Held.Lights = lights;
  std::copy(dims, dims + 3, this->Held.Dimensions);
  this->HasVolume = true;
}

//------------------------------------------------------------------------------
void vtkIrradianceInputCache::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "MaterialVersion: " << this->MaterialVersion << "\n";
  os << indent << "PrefilteredVersion: " << this->PrefilteredVersion << "\n";
  os << indent << "Prefiltered voxels: " << this->Prefiltered.size() << "\n";
  os << indent << "Irradiance stored: " << (this->HasVolume ? "yes" : "no") << ", "
     << this->Held.Lights.size() << " lights, " << this->Held.Dimensions[0] << " x "
     << this->Held.Dimensions[1] << " x " << this->Held.Dimensions[2] << "\n";
}
