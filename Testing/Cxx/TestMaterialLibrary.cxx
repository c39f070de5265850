// Tests of vtkMaterialLibrary: the built-in presets against their JSON files,
// editing, validation (all-or-nothing, one error per rejected call), JSON and
// file round trips.
#include "mmvTestUtilities.h"
#include "vtkMaterialLibrary.h"
#include "vtkMultiMaterialParameters.h"
#include "vtkNew.h"
#include "vtkSmartPointer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <regex>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace
{
constexpr int P = mmv::MaterialParameterCount;
const char* const BuiltinNames[] = { "plastic", "metal", "skin", "bone", "glass", "leaf", "matte",
  "smoke", "glow", "fog", "tissue", "soot" };

std::vector<double> PresetOf(vtkMaterialLibrary* library, const char* name)
{
  std::vector<double> parameters(P, -1.0);
  EXPECT_TRUE(library->GetPreset(name, parameters.data())) << name;
  return parameters;
}

std::vector<double> ColorOf(vtkMaterialLibrary* library, const char* name)
{
  std::vector<double> rgb(3, -1.0);
  EXPECT_TRUE(library->GetPresetColor(name, rgb.data())) << name;
  return rgb;
}

std::vector<std::string> NamesOf(vtkMaterialLibrary* library)
{
  std::vector<std::string> names;
  for (int i = 0; i < library->GetNumberOfPresets(); ++i)
  {
    names.emplace_back(library->GetPresetName(i));
  }
  return names;
}

void RemoveAll(vtkMaterialLibrary* library)
{
  for (const std::string& name : NamesOf(library))
  {
    ASSERT_TRUE(library->RemovePreset(name.c_str()));
  }
  ASSERT_EQ(library->GetNumberOfPresets(), 0);
}

std::string ReadFile(const std::string& path)
{
  std::ifstream file(path);
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

void WriteFile(const std::string& path, const std::string& text)
{
  std::ofstream file(path);
  file << text;
}

std::string TempPath(const std::string& name)
{
  return ::testing::TempDir() + "mmv_" + name;
}

/// `"key": number` from a flat preset file, by regular expression so the
/// check does not share the JSON code under test. NaN when the key is absent.
double NumberInFile(const std::string& text, const std::string& key)
{
  std::smatch match;
  const std::regex pattern("\"" + key + "\"\\s*:\\s*([-+0-9.eE]+)");
  return std::regex_search(text, match, pattern) ? std::strtod(match[1].str().c_str(), nullptr)
                                                 : std::numeric_limits<double>::quiet_NaN();
}

std::vector<double> ColorInFile(const std::string& text)
{
  std::smatch match;
  const std::string number = "\\s*([-+0-9.eE]+)\\s*";
  const std::regex pattern("\"color\"\\s*:\\s*\\[" + number + "," + number + "," + number + "\\]");
  if (!std::regex_search(text, match, pattern))
  {
    return {};
  }
  return { std::strtod(match[1].str().c_str(), nullptr),
    std::strtod(match[2].str().c_str(), nullptr), std::strtod(match[3].str().c_str(), nullptr) };
}
}

TEST(MaterialLibrary, AllBuiltinsArePresent)
{
  vtkNew<vtkMaterialLibrary> library;
  EXPECT_EQ(library->GetNumberOfPresets(), 12);
  for (const char* name : BuiltinNames)
  {
    EXPECT_TRUE(library->HasPreset(name)) << name;
  }
  EXPECT_FALSE(library->HasPreset("unobtainium"));
  EXPECT_FALSE(library->HasPreset(""));
  EXPECT_FALSE(library->HasPreset(nullptr));
}

TEST(MaterialLibrary, BuiltinsMatchTheirJSONFiles)
{
  vtkNew<vtkMaterialLibrary> library;
  for (const char* name : BuiltinNames)
  {
    SCOPED_TRACE(name);
    const std::string text =
      ReadFile(std::string(MMV_SOURCE_DIR) + "/Filters/Materials/" + name + ".json");
    ASSERT_FALSE(text.empty());
    const std::vector<double> parameters = PresetOf(library, name);
    for (int p = 0; p < P; ++p)
    {
      const char* key = mmv::MaterialParameterTable[p].Key;
      double expected = NumberInFile(text, key);
      if (std::isnan(expected))
      {
        expected = mmv::MaterialParameterTable[p].Default;
      }
      EXPECT_EQ(parameters[p], expected) << key;
    }
    std::vector<double> color = ColorInFile(text);
    if (color.empty())
    {
      color = { 1.0, 1.0, 1.0 };
    }
    EXPECT_EQ(ColorOf(library, name), color);
  }
}

TEST(MaterialLibrary, BuiltinSpotValues)
{
  // Numbers copied from Filters/Materials/*.json: a change there is caught.
  vtkNew<vtkMaterialLibrary> library;
  EXPECT_EQ(PresetOf(library, "metal"),
    (std::vector<double>{ 0.1, 0.3, 0.9, 120.0, 1.0, 0.0, 0.6, 0.0, 0.0, 1.0, 1.0, 1.0 }));
  EXPECT_EQ(PresetOf(library, "skin"),
    (std::vector<double>{ 0.25, 0.7, 0.3, 15.0, 0.5, 8.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0 }));
  EXPECT_EQ(PresetOf(library, "smoke")[mmv::Anisotropy], 0.6);
  EXPECT_EQ(PresetOf(library, "glow")[mmv::Emission], 2.0);
  EXPECT_EQ(PresetOf(library, "glass")[mmv::Shininess], 200.0);
  EXPECT_EQ(PresetOf(library, "glass")[mmv::Attenuation], 0.2);
  // Glass casts shadows tinted by its transmission colour; the others grey.
  EXPECT_EQ(PresetOf(library, "glass")[mmv::TransmissionR], 0.6);
  EXPECT_EQ(PresetOf(library, "glass")[mmv::TransmissionB], 0.95);
  EXPECT_EQ(PresetOf(library, "metal")[mmv::TransmissionG], 1.0);
  EXPECT_EQ(PresetOf(library, "leaf")[mmv::Scattering], 4.0);
  EXPECT_EQ(PresetOf(library, "bone")[mmv::Scattering], 1.0);
  EXPECT_EQ(PresetOf(library, "matte")[mmv::Specular], 0.0);
  EXPECT_EQ(PresetOf(library, "plastic")[mmv::Reflection], 0.05);
  EXPECT_EQ(ColorOf(library, "plastic"), (std::vector<double>{ 0.8, 0.2, 0.2 }));
  EXPECT_EQ(ColorOf(library, "leaf"), (std::vector<double>{ 0.25, 0.6, 0.2 }));
}

TEST(MaterialLibrary, EveryBuiltinIsValidAndLoadsWithoutErrors)
{
  vtkNew<vtkMaterialLibrary> library;
  mmvtest::ErrorCounter errors(library);
  library->ResetToBuiltins(); // reloads with the observer in place
  EXPECT_EQ(errors.Errors(), 0) << errors.LastMessage();
  ASSERT_EQ(library->GetNumberOfPresets(), 12);
  for (int i = 0; i < library->GetNumberOfPresets(); ++i)
  {
    const char* name = library->GetPresetName(i);
    SCOPED_TRACE(name);
    const std::vector<double> parameters = PresetOf(library, name);
    for (int p = 0; p < P; ++p)
    {
      std::string why;
      EXPECT_TRUE(mmv::IsValidMaterialValue(p, parameters[p], &why)) << why;
      // Built-ins should sit inside the editor's range, not just the hard limit.
      EXPECT_GE(parameters[p], mmv::MaterialParameterTable[p].SoftMin);
      EXPECT_LE(parameters[p], mmv::MaterialParameterTable[p].SoftMax);
    }
    for (double c : ColorOf(library, name))
    {
      EXPECT_GE(c, 0.0);
      EXPECT_LE(c, 1.0);
    }
  }
}

TEST(MaterialLibrary, PresetNamesAndUnknownLookups)
{
  vtkNew<vtkMaterialLibrary> library;
  // Built-ins are embedded in file-name order.
  EXPECT_EQ(NamesOf(library),
    (std::vector<std::string>{ "bone", "fog", "glass", "glow", "leaf", "matte", "metal", "plastic",
      "skin", "smoke", "soot", "tissue" }));
  EXPECT_EQ(library->GetPresetName(-1), nullptr);
  EXPECT_EQ(library->GetPresetName(12), nullptr);

  mmvtest::ErrorCounter errors(library);
  double parameters[P] = { -5 };
  double rgb[3] = { -5 };
  EXPECT_FALSE(library->GetPreset("unobtainium", parameters));
  EXPECT_FALSE(library->GetPresetColor("unobtainium", rgb));
  EXPECT_FALSE(library->GetPreset(nullptr, parameters));
  EXPECT_EQ(errors.Errors(), 3);
  EXPECT_EQ(parameters[0], -5.0);
  EXPECT_EQ(rgb[0], -5.0);
}

TEST(MaterialLibrary, AddReplaceRemove)
{
  vtkNew<vtkMaterialLibrary> library;
  mmvtest::ErrorCounter errors(library);
  const double chrome[P] = { 0.05, 0.1, 1.0, 300.0, 1.0, 0.0, 0.9 };
  const double chromeColor[3] = { 0.9, 0.9, 0.95 };
  ASSERT_TRUE(library->AddPreset("chrome", chrome, chromeColor));
  EXPECT_EQ(library->GetNumberOfPresets(), 13);
  EXPECT_STREQ(library->GetPresetName(12), "chrome");
  EXPECT_EQ(PresetOf(library, "chrome"), std::vector<double>(chrome, chrome + P));
  EXPECT_EQ(ColorOf(library, "chrome"), std::vector<double>(chromeColor, chromeColor + 3));

  // Replacing keeps the position; without a colour the preset is white.
  const double softMetal[P] = { 0.2, 0.4, 0.5, 30.0, 1.0, 0.5, 0.2 };
  ASSERT_TRUE(library->AddPreset("metal", softMetal));
  EXPECT_EQ(library->GetNumberOfPresets(), 13);
  EXPECT_STREQ(library->GetPresetName(6), "metal");
  EXPECT_EQ(PresetOf(library, "metal"), std::vector<double>(softMetal, softMetal + P));
  EXPECT_EQ(ColorOf(library, "metal"), (std::vector<double>{ 1.0, 1.0, 1.0 }));

  EXPECT_TRUE(library->RemovePreset("glass"));
  EXPECT_FALSE(library->HasPreset("glass"));
  EXPECT_EQ(library->GetNumberOfPresets(), 12);
  EXPECT_EQ(NamesOf(library),
    (std::vector<std::string>{ "bone", "fog", "glow", "leaf", "matte", "metal", "plastic", "skin",
      "smoke", "soot", "tissue", "chrome" }));
  EXPECT_FALSE(library->RemovePreset("glass"));
  EXPECT_FALSE(library->RemovePreset(nullptr));
  EXPECT_EQ(errors.Errors(), 0);

  library->ResetToBuiltins();
  EXPECT_EQ(library->GetNumberOfPresets(), 12);
  EXPECT_FALSE(library->HasPreset("chrome"));
  EXPECT_TRUE(library->HasPreset("glass"));
  EXPECT_EQ(PresetOf(library, "metal")[mmv::Shininess], 120.0);
}

TEST(MaterialLibrary, MTimeChangesOnEditsOnly)
{
  vtkNew<vtkMaterialLibrary> library;
  mmvtest::ErrorCounter errors(library);
  const double parameters[P] = { 0.1, 0.2, 0.3, 4.0, 0.5, 0.6, 0.7 };
  vtkMTimeType mtime = library->GetMTime();
  ASSERT_TRUE(library->AddPreset("new", parameters));
  EXPECT_GT(library->GetMTime(), mtime);
  mtime = library->GetMTime();
  ASSERT_TRUE(library->AddPresetsFromJSON(R"({"name": "other"})"));
  EXPECT_GT(library->GetMTime(), mtime);
  mtime = library->GetMTime();
  ASSERT_TRUE(library->RemovePreset("new"));
  EXPECT_GT(library->GetMTime(), mtime);
  mtime = library->GetMTime();
  library->ResetToBuiltins();
  EXPECT_GT(library->GetMTime(), mtime);

  mtime = library->GetMTime();
  const double bad[P] = { -1, 0.2, 0.3, 4.0, 0.5, 0.6, 0.7 };
  EXPECT_FALSE(library->AddPreset("bad", bad));
  EXPECT_FALSE(library->AddPresetsFromJSON("{"));
  EXPECT_FALSE(library->RemovePreset("new"));
  double out[P];
  library->GetPreset("metal", out);
  library->ToJSON();
  EXPECT_EQ(library->GetMTime(), mtime);
  EXPECT_EQ(errors.Errors(), 2);
}

TEST(MaterialLibrary, AddPresetRejectsInvalidInput)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double good[P] = { 0.1, 0.2, 0.3, 4.0, 0.5, 0.6, 0.7 };
  struct Case
  {
    std::string What;
    std::string Name;
    std::vector<double> Parameters;
    std::vector<double> Color; // empty: none given
  };
  std::vector<Case> cases = {
    { "empty name", "", { good, good + P }, {} },
    { "NaN ambient", "x", { nan, 0.2, 0.3, 4.0, 0.5, 0.6, 0.7 }, {} },
    { "negative diffuse", "x", { 0.1, -0.2, 0.3, 4.0, 0.5, 0.6, 0.7 }, {} },
    { "infinite shininess", "x",
      { 0.1, 0.2, 0.3, std::numeric_limits<double>::infinity(), 0.5, 0.6, 0.7 }, {} },
    { "colour above 1", "x", { good, good + P }, { 0.5, 1.5, 0.5 } },
    { "negative colour", "x", { good, good + P }, { -0.1, 0.5, 0.5 } },
    { "NaN colour", "x", { good, good + P }, { 0.5, 0.5, nan } },
    { "replacing metal with a bad value", "metal", { 0.1, 0.2, 0.3, 4.0, 0.5, -0.6, 0.7 }, {} },
  };
  for (int p = 0; p < P; ++p)
  {
    std::vector<double> parameters(good, good + P);
    parameters[p] = 2.0 * mmv::MaterialParameterTable[p].HardMax;
    cases.push_back({ std::string(mmv::MaterialParameterTable[p].Key) + " above HardMax", "metal",
      parameters, {} });
  }
  for (const Case& c : cases)
  {
    SCOPED_TRACE(c.What);
    vtkNew<vtkMaterialLibrary> library;
    const std::string before = library->ToJSON();
    const vtkMTimeType mtime = library->GetMTime();
    mmvtest::ErrorCounter errors(library);
    EXPECT_FALSE(library->AddPreset(
      c.Name.c_str(), c.Parameters.data(), c.Color.empty() ? nullptr : c.Color.data()));
    EXPECT_EQ(errors.Errors(), 1);
    EXPECT_EQ(library->ToJSON(), before);
    EXPECT_EQ(library->GetMTime(), mtime);
  }
  vtkNew<vtkMaterialLibrary> library;
  mmvtest::ErrorCounter errors(library);
  EXPECT_FALSE(library->AddPreset(nullptr, good));
  EXPECT_FALSE(library->AddPreset("x", nullptr));
  EXPECT_EQ(errors.Errors(), 2);
  EXPECT_EQ(library->GetNumberOfPresets(), 12);
}

TEST(MaterialLibrary, JSONRoundTrip)
{
  vtkNew<vtkMaterialLibrary> library;
  // Values without short decimal forms and a preset without colour.
  const double odd[P] = { 1.0 / 3.0, 2.0 / 3.0, 0.1 + 0.2, 1.0e4, 1.0e-300, 9999.0 / 7.0, 1.0 };
  const double oddColor[3] = { 1.0 / 3.0, 0.0, 1.0 };
  ASSERT_TRUE(library->AddPreset("odd", odd, oddColor));
  const double plain[P] = { 0, 0, 0, 0, 0, 0, 0 };
  ASSERT_TRUE(library->AddPreset("plain", plain));
  const std::string json = library->ToJSON();

  vtkNew<vtkMaterialLibrary> back;
  RemoveAll(back);
  mmvtest::ErrorCounter errors(back);
  ASSERT_TRUE(back->AddPresetsFromJSON(json)) << json;
  EXPECT_EQ(errors.Errors(), 0);
  EXPECT_EQ(NamesOf(back), NamesOf(library));
  for (const std::string& name : NamesOf(library))
  {
    SCOPED_TRACE(name);
    EXPECT_EQ(PresetOf(back, name.c_str()), PresetOf(library, name.c_str())); // bitwise
    EXPECT_EQ(ColorOf(back, name.c_str()), ColorOf(library, name.c_str()));
  }
  EXPECT_EQ(back->ToJSON(), json);
  // Descriptions of the built-ins survive the trip.
  EXPECT_NE(json.find("Polished metal"), std::string::npos);
}

TEST(MaterialLibrary, FileRoundTrip)
{
  vtkNew<vtkMaterialLibrary> library;
  const double custom[P] = { 0.11, 0.22, 0.33, 44.0, 0.55, 6.6, 0.77 };
  const double customColor[3] = { 0.1, 0.2, 0.3 };
  ASSERT_TRUE(library->AddPreset("custom", custom, customColor));
  const std::string path = TempPath("library_round_trip.json");
  ASSERT_TRUE(library->WriteJSONFile(path.c_str()));

  vtkNew<vtkMaterialLibrary> back;
  RemoveAll(back);
  mmvtest::ErrorCounter errors(back);
  ASSERT_TRUE(back->ReadJSONFile(path.c_str()));
  EXPECT_EQ(errors.Errors(), 0);
  EXPECT_EQ(back->ToJSON(), library->ToJSON());
  EXPECT_EQ(PresetOf(back, "custom"), std::vector<double>(custom, custom + P));
  EXPECT_EQ(ColorOf(back, "custom"), std::vector<double>(customColor, customColor + 3));
  std::remove(path.c_str());
}

TEST(MaterialLibrary, ReadsASinglePresetFile)
{
  const std::string path = TempPath("single_preset.json");
  WriteFile(path, R"({"name": "wax", "description": "candle", "scattering": 12, "ambient": 0.4})");
  vtkNew<vtkMaterialLibrary> library;
  ASSERT_TRUE(library->ReadJSONFile(path.c_str()));
  EXPECT_EQ(library->GetNumberOfPresets(), 13);
  // Missing keys take the table defaults; a missing colour is white.
  EXPECT_EQ(PresetOf(library, "wax"),
    (std::vector<double>{ 0.4, 0.7, 0.2, 20.0, 1.0, 12.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0 }));
  EXPECT_EQ(ColorOf(library, "wax"), (std::vector<double>{ 1.0, 1.0, 1.0 }));
  std::remove(path.c_str());
}

TEST(MaterialLibrary, FileErrors)
{
  vtkNew<vtkMaterialLibrary> library;
  const std::string before = library->ToJSON();
  mmvtest::ErrorCounter errors(library);
  EXPECT_FALSE(library->ReadJSONFile(TempPath("no_such_library.json").c_str()));
  EXPECT_EQ(errors.Errors(), 1);
  EXPECT_NE(errors.LastMessage().find("no_such_library.json"), std::string::npos)
    << errors.LastMessage();
  EXPECT_FALSE(library->ReadJSONFile(nullptr));
  EXPECT_EQ(errors.Errors(), 2);

  const std::string bad = TempPath("bad_library.json");
  WriteFile(bad, R"([{"name": "ok"}, {"name": "bad", "specular": -1}])");
  EXPECT_FALSE(library->ReadJSONFile(bad.c_str()));
  EXPECT_EQ(errors.Errors(), 3);
  EXPECT_FALSE(library->HasPreset("ok"));
  std::remove(bad.c_str());

  EXPECT_FALSE(library->WriteJSONFile(TempPath("no_such_dir/library.json").c_str()));
  EXPECT_EQ(errors.Errors(), 4);
  EXPECT_EQ(library->ToJSON(), before);
}

TEST(MaterialLibrary, ArrayIsAllOrNothing)
{
  vtkNew<vtkMaterialLibrary> library;
  const std::string before = library->ToJSON();
  const vtkMTimeType mtime = library->GetMTime();
  mmvtest::ErrorCounter errors(library);
  // The first element is valid and the last replaces a built-in: neither may
  // be applied because the middle one is bad.
  EXPECT_FALSE(library->AddPresetsFromJSON(R"([
      {"name": "first", "ambient": 0.5},
      {"name": "second", "shininess": -3},
      {"name": "metal", "shininess": 1}
    ])"));
  EXPECT_EQ(errors.Errors(), 1);
  EXPECT_NE(errors.LastMessage().find("shininess"), std::string::npos) << errors.LastMessage();
  EXPECT_FALSE(library->HasPreset("first"));
  EXPECT_EQ(PresetOf(library, "metal")[mmv::Shininess], 120.0);
  EXPECT_EQ(library->ToJSON(), before);
  EXPECT_EQ(library->GetMTime(), mtime);

  // The same array without the bad element is applied in full.
  EXPECT_TRUE(library->AddPresetsFromJSON(R"([
      {"name": "first", "ambient": 0.5},
      {"name": "metal", "shininess": 1}
    ])"));
  EXPECT_EQ(library->GetNumberOfPresets(), 13);
  EXPECT_EQ(PresetOf(library, "first")[mmv::Ambient], 0.5);
  EXPECT_EQ(PresetOf(library, "metal")[mmv::Shininess], 1.0);
  EXPECT_STREQ(library->GetPresetName(6), "metal");
  EXPECT_EQ(errors.Errors(), 1);
}

TEST(MaterialLibrary, MalformedJSONIsRejected)
{
  const std::vector<std::pair<std::string, std::string>> cases = {
    { "syntax error", R"({"name": "x")" },
    { "empty text", "" },
    { "top level number", "3" },
    { "top level string", R"("metal")" },
    { "array of numbers", "[1, 2]" },
    { "missing name", R"({"ambient": 0.1})" },
    { "empty name", R"({"name": ""})" },
    { "name not a string", R"({"name": 3})" },
    { "description not a string", R"({"name": "x", "description": 1})" },
    { "unknown key", R"({"name": "x", "roughness": 0.5})" },
    { "misspelt parameter", R"({"name": "x", "shinyness": 5})" },
    { "string instead of number", R"({"name": "x", "diffuse": "0.5"})" },
    { "negative parameter", R"({"name": "x", "reflection": -0.5})" },
    { "1e400 parameter", R"({"name": "x", "attenuation": 1e400})" },
    { "shininess above limit", R"({"name": "x", "shininess": 20000})" },
    { "colour with 2 components", R"({"name": "x", "color": [0.5, 0.5]})" },
    { "colour with 4 components", R"({"name": "x", "color": [0.5, 0.5, 0.5, 1]})" },
    { "colour not an array", R"({"name": "x", "color": 0.5})" },
    { "colour component a string", R"({"name": "x", "color": [0.5, "0.5", 0.5]})" },
    { "colour above 1", R"({"name": "x", "color": [0.5, 1.01, 0.5]})" },
    { "negative colour", R"({"name": "x", "color": [-0.01, 0.5, 0.5]})" },
    { "colour 1e400", R"({"name": "x", "color": [1e400, 0.5, 0.5]})" },
  };
  for (const auto& c : cases)
  {
    SCOPED_TRACE(c.first);
    vtkNew<vtkMaterialLibrary> library;
    const std::string before = library->ToJSON();
    mmvtest::ErrorCounter errors(library);
    EXPECT_FALSE(library->AddPresetsFromJSON(c.second));
    EXPECT_EQ(errors.Errors(), 1);
    EXPECT_EQ(library->ToJSON(), before);
  }
}

TEST(MaterialLibrary, ColourBoundsAreInclusive)
{
  vtkNew<vtkMaterialLibrary> library;
  mmvtest::ErrorCounter errors(library);
  ASSERT_TRUE(library->AddPresetsFromJSON(R"({"name": "x", "color": [0, 1, 0.5]})"));
  EXPECT_EQ(ColorOf(library, "x"), (std::vector<double>{ 0.0, 1.0, 0.5 }));
  EXPECT_EQ(errors.Errors(), 0);
}

TEST(MaterialLibrary, EmptyArrayIsAcceptedAndChangesNothing)
{
  vtkNew<vtkMaterialLibrary> library;
  const vtkMTimeType mtime = library->GetMTime();
  EXPECT_TRUE(library->AddPresetsFromJSON("[]"));
  EXPECT_EQ(library->GetNumberOfPresets(), 12);
  EXPECT_EQ(library->GetMTime(), mtime);
}

TEST(MaterialLibrary, PrintSelfListsPresets)
{
  vtkNew<vtkMaterialLibrary> library;
  std::ostringstream os;
  library->Print(os);
  const std::string text = os.str();
  EXPECT_NE(text.find("Presets: 12"), std::string::npos) << text;
  EXPECT_NE(text.find("metal"), std::string::npos) << text;
  EXPECT_NE(text.find("shininess=120"), std::string::npos) << text;
}
