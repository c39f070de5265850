#include "vtkPVMultiMaterialInformation.h"

#include "vtkClientServerStream.h"
#include "vtkDoubleArray.h"
#include "vtkObjectFactory.h"
#include "vtkPVMultiMaterialVolumeRepresentation.h"

#include <algorithm>

vtkStandardNewMacro(vtkPVMultiMaterialInformation);

namespace
{
// Names of the information properties (Plugin/MultiMaterialVolume.xml.in).
using Representation = vtkPVMultiMaterialVolumeRepresentation;
struct NumberGetter
{
  const char* Name;
  double (*Get)(Representation*);
};
const NumberGetter NumberGetters[] = {
  { "IrradianceUpdateCount",
    [](Representation* r) { return double(r->GetIrradianceUpdateCount()); } },
  { "SkyUpdateCount", [](Representation* r) { return double(r->GetSkyUpdateCount()); } },
  { "IrradianceCacheHitCount",
    [](Representation* r) { return double(r->GetIrradianceCacheHitCount()); } },
  { "DiffusionPassCount", [](Representation* r) { return double(r->GetDiffusionPassCount()); } },
  { "PreIntegrationCount", [](Representation* r) { return double(r->GetPreIntegrationCount()); } },
  { "RayCastCount", [](Representation* r) { return double(r->GetRayCastCount()); } },
  { "NumberOfShadedLights",
    [](Representation* r) { return double(r->GetNumberOfShadedLights()); } },
  { "DeferredIrradianceCount",
    [](Representation* r) { return double(r->GetDeferredIrradianceCount()); } },
  { "IrradianceProbeCount",
    [](Representation* r) { return double(r->GetIrradianceProbeCount()); } },
  { "MultiMaterialActive", [](Representation* r) { return double(r->GetMultiMaterialActive()); } },
  { "NumberOfFields", [](Representation* r) { return double(r->GetNumberOfFields()); } },
  { "LastIrradianceSeconds", [](Representation* r) { return r->GetLastIrradianceSeconds(); } },
  { "LastSkySeconds", [](Representation* r) { return r->GetLastSkySeconds(); } },
  { "LastEstimatedIrradianceVoxels",
    [](Representation* r) { return r->GetLastEstimatedIrradianceVoxels(); } },
};
struct TextGetter
{
  const char* Name;
  const char* (*Get)(Representation*);
};
const TextGetter TextGetters[] = {
  { "IrradianceResolutionInfo",
    [](Representation* r) { return r->GetIrradianceResolutionInfo(); } },
  { "LastIrradianceStages", [](Representation* r) { return r->GetLastIrradianceStages(); } },
  { "GlobalIrradianceInfo", [](Representation* r) { return r->GetGlobalIrradianceInfo(); } },
  { "ResampleInfo", [](Representation* r) { return r->GetResampleInfo(); } },
};
constexpr const char* AppliedNodes = "AppliedMaterialNodes";
}

//------------------------------------------------------------------------------
vtkPVMultiMaterialInformation::vtkPVMultiMaterialInformation()
{
  // Every rank renders its piece, so every rank answers.
  this->RootOnly = 0;
}

//------------------------------------------------------------------------------
vtkPVMultiMaterialInformation::~vtkPVMultiMaterialInformation() = default;

//------------------------------------------------------------------------------
void vtkPVMultiMaterialInformation::CopyFromObject(vtkObject* object)
{
  this->Numbers.clear();
  this->Texts.clear();
  auto* representation = vtkPVMultiMaterialVolumeRepresentation::SafeDownCast(object);
  if (!representation)
  {
    return;
  }
  for (const NumberGetter& getter : NumberGetters)
  {
    this->Numbers[getter.Name] = { getter.Get(representation) };
  }
  for (const TextGetter& getter : TextGetters)
  {
    const char* text = getter.Get(representation);
    this->Texts[getter.Name] = text ? text : "";
  }
  vtkDoubleArray* nodes = representation->GetAppliedMaterialNodes();
  std::vector<double>& values = this->Numbers[AppliedNodes];
  values.assign(nodes->GetPointer(0), nodes->GetPointer(0) + nodes->GetNumberOfValues());
}

//------------------------------------------------------------------------------
void vtkPVMultiMaterialInformation::AddInformation(vtkPVInformation* other)
{
  auto* info = vtkPVMultiMaterialInformation::SafeDownCast(other);
  if (!info || !info->HasValues())
  {
    return;
  }
  if (!this->HasValues())
  {
    this->Numbers = info->Numbers;
    this->Texts = info->Texts;
    return;
  }
  for (const auto& entry : info->Numbers)
  {
    std::vector<double>& mine = this->Numbers[entry.first];
    if (entry.first == AppliedNodes)
    {
      if (mine.empty())
      {
        mine = entry.second;
      }
    }
    else if (mine.size() == 1 && entry.second.size() == 1)
    {
      mine[0] = std::max(mine[0], entry.second[0]);
    }
  }
  for (const auto& entry : info->Texts)
  {
    std::string& mine = this->Texts[entry.first];
    if (mine.empty())
    {
      mine = entry.second;
    }
  }
}

//------------------------------------------------------------------------------
void vtkPVMultiMaterialInformation::CopyToStream(vtkClientServerStream* stream)
{
  stream->Reset();
  *stream << vtkClientServerStream::Reply << static_cast<int>(this->Numbers.size());
  for (const auto& entry : this->Numbers)
  {
    *stream << entry.first.c_str() << static_cast<int>(entry.second.size());
    if (!entry.second.empty())
    {
      *stream << vtkClientServerStream::InsertArray(
        entry.second.data(), static_cast<int>(entry.second.size()));
    }
  }
  *stream << static_cast<int>(this->Texts.size());
  for (const auto& entry : this->Texts)
  {
    *stream << entry.first.c_str() << entry.second.c_str();
  }
  *stream << vtkClientServerStream::End;
}

//------------------------------------------------------------------------------
void vtkPVMultiMaterialInformation::CopyFromStream(const vtkClientServerStream* stream)
{
  this->Numbers.clear();
  this->Texts.clear();
  int arg = 0;
  int count = 0;
  if (!stream->GetArgument(0, arg++, &count))
  {
    vtkErrorMacro("Error parsing the number count from the message.");
    return;
  }
  for (int i = 0; i < count; ++i)
  {
    const char* name = nullptr;
    int size = 0;
    if (!stream->GetArgument(0, arg++, &name) || !stream->GetArgument(0, arg++, &size) || !name ||
      size < 0)
    {
      vtkErrorMacro("Error parsing the numbers from the message.");
      return;
    }
    std::vector<double>& values = this->Numbers[name];
    values.resize(size);
    if (size > 0 && !stream->GetArgument(0, arg++, values.data(), size))
    {
      vtkErrorMacro("Error parsing the values of " << name << " from the message.");
      return;
    }
  }
  if (!stream->GetArgument(0, arg++, &count))
  {
    vtkErrorMacro("Error parsing the text count from the message.");
    return;
  }
  for (int i = 0; i < count; ++i)
  {
    const char* name = nullptr;
    const char* text = nullptr;
    if (!stream->GetArgument(0, arg++, &name) || !stream->GetArgument(0, arg++, &text) || !name)
    {
      vtkErrorMacro("Error parsing the texts from the message.");
      return;
    }
    this->Texts[name] = text ? text : "";
  }
}

//------------------------------------------------------------------------------
bool vtkPVMultiMaterialInformation::GetNumbers(
  const std::string& name, std::vector<double>& values) const
{
  auto it = this->Numbers.find(name);
  if (it == this->Numbers.end())
  {
    return false;
  }
  values = it->second;
  return true;
}

//------------------------------------------------------------------------------
bool vtkPVMultiMaterialInformation::GetText(const std::string& name, std::string& text) const
{
  auto it = this->Texts.find(name);
  if (it == this->Texts.end())
  {
    return false;
  }
  text = it->second;
  return true;
}

//------------------------------------------------------------------------------
void vtkPVMultiMaterialInformation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  for (const auto& entry : this->Numbers)
  {
    os << indent << entry.first << ": " << entry.second.size() << " value(s)"
       << (entry.second.size() == 1 ? " = " + std::to_string(entry.second[0]) : std::string())
       << "\n";
  }
  for (const auto& entry : this->Texts)
  {
    os << indent << entry.first << ": " << entry.second << "\n";
  }
}
