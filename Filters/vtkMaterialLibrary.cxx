#include "vtkMaterialLibrary.h"

#include "vtkMaterialJSON.h"
#include "vtkMaterialLibraryBuiltins.h"
#include "vtkMultiMaterialParameters.h"
#include "vtkObjectFactory.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

// The wrapped API spells the size out (VTK's wrappers read a literal).
static_assert(mmv::MaterialParameterCount == 12, "vtkMaterialLibrary.h: parameters[12]");

namespace
{
struct Preset
{
  std::string Name;
  std::string Description;
  std::array<double, mmv::MaterialParameterCount> Parameters;
  std::array<double, 3> Color{ { 1.0, 1.0, 1.0 } };
};

bool IsValidColor(const double rgb[3], std::string& why)
{
  for (int c = 0; c < 3; ++c)
  {
    if (!std::isfinite(rgb[c]) || rgb[c] < 0.0 || rgb[c] > 1.0)
    {
      why = "colour component " + std::to_string(c) + " = " + std::to_string(rgb[c]) +
        " is not a finite number in [0, 1]";
      return false;
    }
  }
  return true;
}

/// Everything but the name, which ParsePreset reads first so that messages
/// can name the preset.
bool ParsePresetFields(const mmv::Json& object, Preset& preset, std::string& why)
{
  if (!mmv::ReadMaterialParameters(
        object, { "name", "description", "color" }, preset.Parameters.data(), why))
  {
    return false;
  }
  const auto description = object.find("description");
  if (description != object.end())
  {
    if (!description->is_string())
    {
      why = "\"description\" must be a string";
      return false;
    }
    preset.Description = description->get<std::string>();
  }
  const auto color = object.find("color");
  if (color != object.end())
  {
    if (!color->is_array() || color->size() != 3)
    {
      why = "\"color\" must be an array of 3 numbers";
      return false;
    }
    for (int c = 0; c < 3; ++c)
    {
      if (!mmv::ReadFiniteNumber((*color)[c], "\"color\"", preset.Color[c], why))
      {
        return false;
      }
    }
    return IsValidColor(preset.Color.data(), why);
  }
  return true;
}

bool ParsePreset(const mmv::Json& object, Preset& preset, std::string& why)
{
  if (!object.is_object())
  {
    why = "expected a preset object, got " + object.dump();
    return false;
  }
  const auto name = object.find("name");
  if (name == object.end() || !name->is_string() || name->get<std::string>().empty())
  {
    why = "a preset needs a non-empty string \"name\"";
    return false;
  }
  preset.Name = name->get<std::string>();
  if (!ParsePresetFields(object, preset, why))
  {
    why = "preset \"" + preset.Name + "\": " + why;
    return false;
  }
  return true;
}

/// Parses one preset object or an array of them; nothing is applied here so
/// the caller can keep AddPresetsFromJSON all-or-nothing.
bool ParsePresets(const std::string& text, std::vector<Preset>& presets, std::string& why)
{
  mmv::Json root;
  if (!mmv::ParseJSON(text, root, why))
  {
    return false;
  }
  std::vector<Preset> parsed;
  if (root.is_object())
  {
    parsed.emplace_back();
    if (!ParsePreset(root, parsed.back(), why))
    {
      return false;
    }
  }
  else if (root.is_array())
  {
    for (std::size_t i = 0; i < root.size(); ++i)
    {
      parsed.emplace_back();
      if (!ParsePreset(root[i], parsed.back(), why))
      {
        why = "element " + std::to_string(i) + ": " + why;
        return false;
      }
    }
  }
  else
  {
    why = "expected a preset object or an array of presets";
    return false;
  }
  presets.swap(parsed);
  return true;
}
}

class vtkMaterialLibrary::vtkInternals
{
public:
  std::vector<Preset> Presets; // insertion order, unique names

  Preset* Find(const char* name)
  {
    auto it = std::find_if(this->Presets.begin(), this->Presets.end(),
      [name](const Preset& p) { return name && p.Name == name; });
    return it == this->Presets.end() ? nullptr : &*it;
  }

  /// Replaces a preset of the same name in place, or appends.
  void Add(const Preset& preset)
  {
    if (Preset* existing = this->Find(preset.Name.c_str()))
    {
      *existing = preset;
    }
    else
    {
      this->Presets.push_back(preset);
    }
  }
};

vtkStandardNewMacro(vtkMaterialLibrary);

vtkMaterialLibrary::vtkMaterialLibrary()
  : Internals(new vtkInternals)
{
  this->ResetToBuiltins();
}

vtkMaterialLibrary::~vtkMaterialLibrary()
{
  delete this->Internals;
}

int vtkMaterialLibrary::GetNumberOfPresets() const
{
  return static_cast<int>(this->Internals->Presets.size());
}

const char* vtkMaterialLibrary::GetPresetName(int i) const
{
  if (i < 0 || i >= this->GetNumberOfPresets())
  {
    return nullptr;
  }
  return this->Internals->Presets[i].Name.c_str();
}

bool vtkMaterialLibrary::HasPreset(const char* name) const
{
  return this->Internals->Find(name) != nullptr;
}

bool vtkMaterialLibrary::GetPreset(
  const char* name, double parameters[mmv::MaterialParameterCount]) const
{
  const Preset* preset = this->Internals->Find(name);
  if (!preset)
  {
    vtkErrorMacro("GetPreset: unknown material preset \"" << (name ? name : "(null)") << "\".");
    return false;
  }
  std::copy(preset->Parameters.begin(), preset->Parameters.end(), parameters);
  return true;
}

bool vtkMaterialLibrary::GetPresetColor(const char* name, double rgb[3]) const
{
  const Preset* preset = this->Internals->Find(name);
  if (!preset)
  {
    vtkErrorMacro(
      "GetPresetColor: unknown material preset \"" << (name ? name : "(null)") << "\".");
    return false;
  }
  std::copy(preset->Color.begin(), preset->Color.end(), rgb);
  return true;
}

bool vtkMaterialLibrary::AddPreset(
  const char* name, const double parameters[mmv::MaterialParameterCount], const double rgb[3])
{
  if (!name || !*name)
  {
    vtkErrorMacro("AddPreset: a preset needs a non-empty name.");
    return false;
  }
  if (!parameters)
  {
    vtkErrorMacro("AddPreset: no parameters given for \"" << name << "\".");
    return false;
  }
  std::string why;
  for (int p = 0; p < mmv::MaterialParameterCount; ++p)
  {
    if (!mmv::IsValidMaterialValue(p, parameters[p], &why))
    {
      vtkErrorMacro("AddPreset: \"" << name << "\": " << why << "; the library is unchanged.");
      return false;
    }
  }
  if (rgb && !IsValidColor(rgb, why))
  {
    vtkErrorMacro("AddPreset: \"" << name << "\": " << why << "; the library is unchanged.");
    return false;
  }
  // The preset is exactly what is given: a replaced preset loses its old
  // description, and its colour falls back to white without `rgb`.
  Preset preset;
  preset.Name = name;
  std::copy(parameters, parameters + mmv::MaterialParameterCount, preset.Parameters.begin());
  if (rgb)
  {
    std::copy(rgb, rgb + 3, preset.Color.begin());
  }
  this->Internals->Add(preset);
  this->Modified();
  return true;
}

bool vtkMaterialLibrary::RemovePreset(const char* name)
{
  std::vector<Preset>& presets = this->Internals->Presets;
  auto it = std::find_if(
    presets.begin(), presets.end(), [name](const Preset& p) { return name && p.Name == name; });
  if (it == presets.end())
  {
    return false;
  }
  presets.erase(it);
  this->Modified();
  return true;
}

void vtkMaterialLibrary::ResetToBuiltins()
{
  this->Internals->Presets.clear();
  for (const mmv::BuiltinMaterial* builtin = mmv::BuiltinMaterials; builtin->Name; ++builtin)
  {
    std::vector<Preset> presets;
    std::string why;
    // The builtins are checked like user files; a failure is a bug in
    // Filters/Materials/, so it is reported rather than hidden.
    if (!ParsePresets(builtin->JSON, presets, why))
    {
      vtkErrorMacro("Built-in material \"" << builtin->Name << "\" is invalid: " << why << ".");
      continue;
    }
    if (presets.size() != 1 || presets.front().Name != builtin->Name)
    {
      vtkErrorMacro("Built-in material file \"" << builtin->Name
                                                << ".json\" must hold one preset of that name.");
      continue;
    }
    this->Internals->Add(presets.front());
  }
  this->Modified();
}

bool vtkMaterialLibrary::AddPresetsFromJSON(const std::string& json)
{
  std::vector<Preset> presets;
  std::string why;
  if (!ParsePresets(json, presets, why))
  {
    vtkErrorMacro("AddPresetsFromJSON: " << why << "; the library is unchanged.");
    return false;
  }
  for (const Preset& preset : presets)
  {
    this->Internals->Add(preset);
  }
  if (!presets.empty())
  {
    this->Modified();
  }
  return true;
}

bool vtkMaterialLibrary::ReadJSONFile(const char* path)
{
  std::string text;
  std::vector<Preset> presets;
  std::string why;
  if (!mmv::ReadTextFile(path, text, why))
  {
    vtkErrorMacro("ReadJSONFile: " << why << "; the library is unchanged.");
    return false;
  }
  if (!ParsePresets(text, presets, why))
  {
    vtkErrorMacro("ReadJSONFile: \"" << path << "\": " << why << "; the library is unchanged.");
    return false;
  }
  for (const Preset& preset : presets)
  {
    this->Internals->Add(preset);
  }
  if (!presets.empty())
  {
    this->Modified();
  }
  return true;
}

std::string vtkMaterialLibrary::ToJSON() const
{
  mmv::Json root = mmv::Json::array();
  for (const Preset& preset : this->Internals->Presets)
  {
    mmv::Json object = mmv::Json::object();
    object["name"] = preset.Name;
    if (!preset.Description.empty())
    {
      object["description"] = preset.Description;
    }
    object["color"] = preset.Color;
    mmv::WriteMaterialParameters(preset.Parameters.data(), object);
    root.push_back(object);
  }
  return root.dump(2);
}

bool vtkMaterialLibrary::WriteJSONFile(const char* path) const
{
  std::string why;
  if (!mmv::WriteTextFile(path, this->ToJSON(), why))
  {
    vtkErrorMacro("WriteJSONFile: " << why << ".");
    return false;
  }
  return true;
}

void vtkMaterialLibrary::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Presets: " << this->Internals->Presets.size() << "\n";
  for (const Preset& preset : this->Internals->Presets)
  {
    os << indent.GetNextIndent() << preset.Name << ": color=(" << preset.Color[0] << ", "
       << preset.Color[1] << ", " << preset.Color[2] << ")";
    for (int p = 0; p < mmv::MaterialParameterCount; ++p)
    {
      os << " " << mmv::MaterialParameterTable[p].Key << "=" << preset.Parameters[p];
    }
    os << "\n";
  }
}
