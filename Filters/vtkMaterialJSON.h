/**
 * @file   vtkMaterialJSON.h
 * @brief  JSON helpers shared by vtkMaterialTransferFunction and vtkMaterialLibrary.
 *
 * Internal header, included only by the module's .cxx files. Both classes read
 * and write the material parameters with the same keys and the same
 * validation, so that code lives here once. Functions report problems through
 * `why` and leave the reporting (vtkErrorMacro) to the calling object.
 */
#ifndef vtkMaterialJSON_h
#define vtkMaterialJSON_h

#include "vtkMultiMaterialParameters.h"

// clang-format off
#include "vtk_nlohmannjson.h"
#include VTK_NLOHMANN_JSON(json.hpp)
// clang-format on

#include <cmath>
#include <fstream>
#include <initializer_list>
#include <sstream>
#include <string>

namespace mmv
{

// Ordered so written files keep the key order a person expects (name first,
// parameters in table order) instead of alphabetical order.
using Json = nlohmann::ordered_json;

/// Parses `text`; json::parse throws on syntax errors and number overflow.
inline bool ParseJSON(const std::string& text, Json& out, std::string& why)
{
  try
  {
    out = Json::parse(text);
  }
  catch (const Json::exception& e)
  {
    why = std::string("malformed JSON: ") + e.what();
    return false;
  }
  return true;
}

/// Reads a finite number; `what` names it in the message.
inline bool ReadFiniteNumber(
  const Json& value, const std::string& what, double& out, std::string& why)
{
  if (!value.is_number())
  {
    why = what + " must be a number, not " + value.dump();
    return false;
  }
  out = value.get<double>();
  if (!std::isfinite(out))
  {
    why = what + " is not a finite number";
    return false;
  }
  return true;
}

/**
 * Reads the material parameters of a JSON object. Missing keys take their
 * defaults; keys listed in `otherKeys` belong to the caller and are skipped;
 * any other key is an error.
 */
inline bool ReadMaterialParameters(const Json& object, std::initializer_list<const char*> otherKeys,
  double parameters[MaterialParameterCount], std::string& why)
{
  if (!object.is_object())
  {
    why = "expected a JSON object, got " + object.dump();
    return false;
  }
  for (int p = 0; p < MaterialParameterCount; ++p)
  {
    parameters[p] = MaterialParameterTable[p].Default;
  }
  for (auto it = object.begin(); it != object.end(); ++it)
  {
    const std::string& key = it.key();
    int parameter = -1;
    for (int p = 0; p < MaterialParameterCount; ++p)
    {
      if (key == MaterialParameterTable[p].Key)
      {
        parameter = p;
        break;
      }
    }
    if (parameter < 0)
    {
      bool known = false;
      for (const char* other : otherKeys)
      {
        known = known || key == other;
      }
      if (!known)
      {
        why = "unknown key \"" + key + "\"";
        return false;
      }
      continue;
    }
    if (!ReadFiniteNumber(it.value(), "\"" + key + "\"", parameters[parameter], why) ||
      !IsValidMaterialValue(parameter, parameters[parameter], &why))
    {
      return false;
    }
  }
  return true;
}

/// Adds every material parameter to a JSON object under its table key; the
/// transmission colour only when it is not white, so a grey material writes
/// the same JSON as before the colour existed (absent keys read as white).
inline void WriteMaterialParameters(const double parameters[MaterialParameterCount], Json& object)
{
  const bool chromatic = IsChromaticTransmission(
    parameters[TransmissionR], parameters[TransmissionG], parameters[TransmissionB]);
  for (int p = 0; p < MaterialParameterCount; ++p)
  {
    if (chromatic || p < TransmissionR || p > TransmissionB)
    {
      object[MaterialParameterTable[p].Key] = parameters[p];
    }
  }
}

inline bool ReadTextFile(const char* path, std::string& text, std::string& why)
{
  if (!path || !*path)
  {
    why = "no file name given";
    return false;
  }
  std::ifstream file(path, std::ios::in | std::ios::binary);
  if (!file)
  {
    why = std::string("cannot open \"") + path + "\" for reading";
    return false;
  }
  std::ostringstream contents;
  contents << file.rdbuf();
  if (file.bad())
  {
    why = std::string("error while reading \"") + path + "\"";
    return false;
  }
  text = contents.str();
  return true;
}

inline bool WriteTextFile(const char* path, const std::string& text, std::string& why)
{
  if (!path || !*path)
  {
    why = "no file name given";
    return false;
  }
  std::ofstream file(path, std::ios::out | std::ios::binary | std::ios::trunc);
  if (!file)
  {
    why = std::string("cannot open \"") + path + "\" for writing";
    return false;
  }
  file << text << '\n';
  file.close();
  if (file.fail())
  {
    why = std::string("error while writing \"") + path + "\"";
    return false;
  }
  return true;
}

} // namespace mmv

#endif
