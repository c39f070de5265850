#include "vtkMultiMaterialFields.h"

#include "vtkColorTransferFunction.h"
#include "vtkDataArray.h"
#include "vtkDataSetAttributes.h"
#include "vtkMultiMaterialParameters.h"
#include "vtkMultiMaterialThreads.h" // mmv::For
#include "vtkPiecewiseFunction.h"
#include "vtkPreIntegrationTable.h"
#include "vtkSMPTools.h"
#include "vtkVolumeInputScalars.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace
{
/// `function` at n values over `range`.
std::vector<float> Sample(vtkPiecewiseFunction* function, const double range[2], int n)
{
  std::vector<float> table(n);
  for (int i = 0; i < n; ++i)
  {
    table[i] =
      static_cast<float>(function->GetValue(range[0] + (range[1] - range[0]) * i / (n - 1)));
  }
  return table;
}

std::vector<float> Sample(
  vtkMaterialTransferFunction* materials, int parameter, const double range[2], int n)
{
  std::vector<float> table(n, static_cast<float>(mmv::MaterialParameterTable[parameter].Default));
  for (int i = 0; materials && materials->GetSize() > 0 && i < n; ++i)
  {
    table[i] = static_cast<float>(
      materials->EvaluateParameter(range[0] + (range[1] - range[0]) * i / (n - 1), parameter));
  }
  return table;
}
}

vtkMultiMaterialFields::vtkMultiMaterialFields()
{
  // Further fields' tables are made when there are further fields.
  this->Tables[0] = vtkSmartPointer<vtkPreIntegrationTable>::New();
  for (auto& range : this->Ranges)
  {
    range = { 0.0, 1.0 };
  }
  this->Combined->SetName("CombinedShadowOpacity");
  this->Summed->SetName("SummedFields");
  // The combined field is an opacity over one object unit: read as it is,
  // its extinction is the sum of the fields'.
  vtkNew<vtkPiecewiseFunction> identity;
  identity->AddPoint(0.0, 0.0);
  identity->AddPoint(1.0, 1.0);
  this->CombinedProperty->SetScalarOpacity(identity);
  this->CombinedProperty->SetScalarOpacityUnitDistance(1.0);
}

vtkMultiMaterialFields::~vtkMultiMaterialFields() = default;

void vtkMultiMaterialFields::SetMaterials(int field, vtkMaterialTransferFunction* materials)
{
  if (field >= 0 && field < mmv::MaxFields)
  {
    this->Materials[field] = materials;
  }
}

vtkMaterialTransferFunction* vtkMultiMaterialFields::GetMaterials(int field) const
{
  return field >= 0 && field < mmv::MaxFields ? this->Materials[field].Get() : nullptr;
}

vtkMTimeType vtkMultiMaterialFields::GetMaterialsMTime() const
{
  vtkMTimeType t = 0;
  for (const auto& m : this->Materials)
  {
    t = m ? std::max(t, m->GetMTime()) : t;
  }
  return t;
}

bool vtkMultiMaterialFields::SetScalars(vtkDataArray* scalars)
{
  const int count = scalars->GetNumberOfComponents();
  if (count < 1 || count > mmv::MaxFields)
  {
    return false;
  }
  this->Count = count;
  for (int f = 0; f < count; ++f)
  {
    double range[2];
    mmv::LightingRange(scalars, f, range);
    this->Ranges[f] = { range[0], range[1] };
  }
  return true;
}

vtkColorTransferFunction* vtkMultiMaterialFields::ColorOf(vtkVolumeProperty* property, int field)
{
  if (property->GetColorChannels(field) != 1)
  {
    return property->GetRGBTransferFunction(field);
  }
  vtkPiecewiseFunction* gray = property->GetGrayTransferFunction(field);
  vtkSmartPointer<vtkColorTransferFunction>& rgb = this->GrayAsColor[field];
  if (!rgb)
  {
    rgb = vtkSmartPointer<vtkColorTransferFunction>::New();
  }
  if (gray && gray->GetMTime() != this->GrayTime[field])
  {
    rgb->RemoveAllPoints();
    double node[4];
    for (int i = 0; i < gray->GetSize(); ++i)
    {
      gray->GetNodeValue(i, node);
      rgb->AddRGBPoint(node[0], node[1], node[1], node[1]);
    }
    this->GrayTime[field] = gray->GetMTime();
  }
  return rgb;
}

bool vtkMultiMaterialFields::UpdateSegmentTables(
  vtkVolumeProperty* property, double step, int tableSize, int* rebuilt, double* seconds)
{
  for (int f = 0; f < this->Count; ++f)
  {
    if (!this->Tables[f])
    {
      this->Tables[f] = vtkSmartPointer<vtkPreIntegrationTable>::New();
    }
    vtkPreIntegrationTable* table = this->Tables[f];
    table->SetColorTransferFunction(this->ColorOf(property, f));
    table->SetScalarOpacity(property->GetScalarOpacity(f));
    table->SetScalarOpacityUnitDistance(property->GetScalarOpacityUnitDistance(f));
    table->SetTableSize(tableSize);
    table->SetScalarRange(this->Ranges[f].data());
    table->SetStepLength(step);
    const int builds = table->GetBuildCount();
    if (!table->Update())
    {
      return false;
    }
    if (table->GetBuildCount() != builds)
    {
      if (rebuilt)
      {
        ++*rebuilt;
      }
      if (seconds)
      {
        *seconds += table->GetLastBuildSeconds();
      }
    }
  }
  return true;
}

std::vector<vtkPreIntegrationTable*> vtkMultiMaterialFields::GetSegmentTables() const
{
  std::vector<vtkPreIntegrationTable*> tables;
  for (int f = 0; f < this->Count; ++f)
  {
    tables.push_back(this->Tables[f]);
  }
  return tables;
}

std::vector<vtkMaterialTransferFunction*> vtkMultiMaterialFields::GetMaterialsOfFields() const
{
  std::vector<vtkMaterialTransferFunction*> materials;
  for (int f = 0; f < this->Count; ++f)
  {
    materials.push_back(this->Materials[f]);
  }
  return materials;
}

std::vector<double> vtkMultiMaterialFields::GetRanges() const
{
  std::vector<double> ranges;
  for (int f = 0; f < this->Count; ++f)
  {
    ranges.push_back(this->Ranges[f][0]);
    ranges.push_back(this->Ranges[f][1]);
  }
  return ranges;
}

int vtkMultiMaterialFields::GetTableSize() const
{
  return this->Tables[0]->GetTableSize();
}

bool vtkMultiMaterialFields::AnyNonZero(int parameter) const
{
  for (int f = 0; f < this->Count; ++f)
  {
    if (this->Materials[f] && this->Materials[f]->HasNonZero(parameter))
    {
      return true;
    }
  }
  return false;
}

bool vtkMultiMaterialFields::AnyReflection() const
{
  for (int f = 0; f < this->Count; ++f)
  {
    vtkMaterialTransferFunction* m = this->Materials[f];
    if (m && m->GetSize() > 0 && m->GetMaximum(mmv::Reflection) > 0.0)
    {
      return true;
    }
  }
  return false;
}

bool vtkMultiMaterialFields::AnyChromaticTransmission() const
{
  for (int f = 0; f < this->Count; ++f)
  {
    if (this->Materials[f] && this->Materials[f]->HasChromaticTransmission())
    {
      return true;
    }
  }
  return false;
}

bool vtkMultiMaterialFields::UpdateLighting(
  vtkDataArray* scalars, vtkVolumeProperty* property, int tableSize, std::string* error)
{
  if (this->Count < 2)
  {
    return true;
  }
  // What D depends on: the data, each field's range, opacity, unit distance
  // and materials, and the table size.
  std::vector<double> key = { static_cast<double>(scalars->GetMTime()),
    static_cast<double>(reinterpret_cast<uintptr_t>(scalars)), static_cast<double>(tableSize) };
  for (int f = 0; f < this->Count; ++f)
  {
    vtkMaterialTransferFunction* m = this->Materials[f];
    key.insert(key.end(),
      { this->Ranges[f][0], this->Ranges[f][1],
        static_cast<double>(property->GetScalarOpacity(f)->GetMTime()),
        property->GetScalarOpacityUnitDistance(f), static_cast<double>(m ? m->GetMTime() : 0) });
  }
  if (key == this->CombinedKey)
  {
    return true;
  }
  std::vector<mmv::FieldOptics> optics(this->Count);
  for (int f = 0; f < this->Count; ++f)
  {
    mmv::FieldOptics& o = optics[f];
    const double* range = this->Ranges[f].data();
    o.Range[0] = range[0];
    o.Range[1] = range[1];
    o.Opacity = Sample(property->GetScalarOpacity(f), range, tableSize);
    o.Attenuation = Sample(this->Materials[f], mmv::Attenuation, range, tableSize);
    o.Scattering = Sample(this->Materials[f], mmv::Scattering, range, tableSize);
    o.UnitDistance = property->GetScalarOpacityUnitDistance(f);
  }
  std::vector<float> scattering;
  if (!mmv::CombineFieldExtinction(scalars, optics, tableSize, this->Combined, scattering, error))
  {
    return false;
  }
  // The lighting reads attenuation 1 and the mixed scattering per value of D
  // (remade only when that changes: the materials' time keys the lighting).
  this->CombinedKey = key;
  if (this->CombinedMaterials->GetSize() > 0 && scattering == this->CombinedScattering)
  {
    return true;
  }
  this->CombinedScattering = scattering;
  this->CombinedMaterials->RemoveAllNodes();
  const size_t nodes = std::max<size_t>(scattering.size(), 1);
  for (size_t i = 0; i < nodes; ++i)
  {
    const double t = nodes > 1 ? static_cast<double>(i) / (nodes - 1) : 0.0;
    const double s = scattering.empty() ? 0.0 : scattering[i];
    this->CombinedMaterials->AddNode(t, 1.0, 0.0, 0.0, 1.0, 1.0, s, 0.0);
  }
  return true;
}

vtkDataArray* vtkMultiMaterialFields::GetLightingScalars(vtkDataArray* scalars) const
{
  return this->Count > 1 ? static_cast<vtkDataArray*>(this->Combined.Get()) : scalars;
}

const double* vtkMultiMaterialFields::GetLightingRange(const double* dataRange) const
{
  // D is an opacity: its tables span [0, 1] whatever the data.
  static constexpr double UnitRange[2] = { 0.0, 1.0 };
  return this->Count > 1 ? UnitRange : dataRange;
}

vtkVolumeProperty* vtkMultiMaterialFields::GetLightingProperty(vtkVolumeProperty* property) const
{
  return this->Count > 1 ? this->CombinedProperty.Get() : property;
}

vtkMaterialTransferFunction* vtkMultiMaterialFields::GetLightingMaterials() const
{
  return this->Count > 1 ? this->CombinedMaterials.Get() : this->Materials[0].Get();
}

vtkDataArray* vtkMultiMaterialFields::GetGradientScalars(vtkDataArray* scalars)
{
  if (this->Count < 2)
  {
    return scalars;
  }
  std::vector<double> key = { static_cast<double>(scalars->GetMTime()),
    static_cast<double>(reinterpret_cast<uintptr_t>(scalars)) };
  for (int f = 0; f < this->Count; ++f)
  {
    key.insert(key.end(), { this->Ranges[f][0], this->Ranges[f][1] });
  }
  if (key == this->SummedKey)
  {
    return this->Summed;
  }
  const vtkIdType tuples = scalars->GetNumberOfTuples();
  this->Summed->SetNumberOfTuples(tuples);
  float* out = this->Summed->GetPointer(0);
  const int count = this->Count;
  std::array<double, mmv::MaxFields> offset{};
  std::array<double, mmv::MaxFields> scale{};
  for (int f = 0; f < count; ++f)
  {
    offset[f] = this->Ranges[f][0];
    scale[f] = 1.0 / (this->Ranges[f][1] - this->Ranges[f][0]);
  }
  mmv::For(0, tuples,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType i = begin; i < end; ++i)
      {
        double sum = 0.0;
        for (int f = 0; f < count; ++f)
        {
          const double v = scalars->GetComponent(i, f);
          sum += std::isfinite(v) ? (v - offset[f]) * scale[f] : 0.0;
        }
        out[i] = static_cast<float>(sum);
      }
    });
  this->Summed->Modified();
  this->Summed->GetFiniteRange(this->SummedRange, 0);
  if (!(this->SummedRange[1] > this->SummedRange[0]))
  {
    this->SummedRange[1] = this->SummedRange[0] + 1.0;
  }
  this->SummedKey = key;
  return this->Summed;
}

const double* vtkMultiMaterialFields::GetGradientRange(const double* dataRange) const
{
  return this->Count > 1 ? this->SummedRange : dataRange;
}

vtkDataArray* vtkMultiMaterialFields::WithArrays(vtkDataArray* scalars,
  vtkDataSetAttributes* attributes, const std::vector<std::string>& names, std::string* error)
{
  std::vector<vtkDataArray*> others;
  std::vector<std::pair<vtkDataArray*, vtkMTimeType>> from = { { scalars, scalars->GetMTime() } };
  for (const std::string& name : names)
  {
    vtkDataArray* array = attributes->GetArray(name.c_str());
    others.push_back(array);
    from.emplace_back(array, array ? array->GetMTime() : 0);
  }
  if (this->WithArraysArray && from == this->WithArraysFrom)
  {
    return this->WithArraysArray;
  }
  vtkSmartPointer<vtkDataArray> combined = mmv::MakeFieldArray(scalars, others, error);
  if (!combined)
  {
    return nullptr;
  }
  this->WithArraysArray = combined;
  this->WithArraysFrom = from;
  return combined;
}
