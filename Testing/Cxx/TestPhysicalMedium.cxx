// Tests of mmv::PhysicalMediumToMaterial: the formula against the fitted
// table it was derived from (docs/medium_calibration.csv, written by
// mmvMediumCalibration), its limits, the domain checks, and the physically
// derived presets of the material library.
#include "mmvTestUtilities.h"
#include "vtkMaterialLibrary.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMultiMaterialParameters.h"
#include "vtkMultiMaterialPhysicalMedium.h"
#include "vtkNew.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace
{
constexpr int P = mmv::MaterialParameterCount;

// The residual docs/performance.md ("Physical media") states: on the medium's pixels the mapped
// parameters err at most this factor times the best fit of the grid, plus
// this much (0-255).
constexpr double MappedErrorFactor = 3.0;
constexpr double MappedErrorSlack = 5.0;

std::vector<double> Map(double albedo, double g, double extinction)
{
  std::vector<double> p(P, -1.0);
  std::string why;
  EXPECT_TRUE(mmv::PhysicalMediumToMaterial(albedo, g, extinction, p.data(), &why)) << why;
  return p;
}

// The rows of a CSV file as column -> text maps.
std::vector<std::map<std::string, std::string>> ReadCSV(const std::string& path)
{
  std::ifstream file(path);
  std::vector<std::map<std::string, std::string>> rows;
  std::string line;
  std::vector<std::string> header;
  auto split = [](const std::string& text)
  {
    std::vector<std::string> items;
    std::stringstream list(text);
    for (std::string item; std::getline(list, item, ',');)
    {
      items.push_back(item);
    }
    return items;
  };
  if (std::getline(file, line))
  {
    header = split(line);
  }
  while (std::getline(file, line))
  {
    const std::vector<std::string> items = split(line);
    std::map<std::string, std::string> row;
    for (size_t i = 0; i < header.size() && i < items.size(); ++i)
    {
      row[header[i]] = items[i];
    }
    rows.push_back(row);
  }
  return rows;
}

double Number(const std::map<std::string, std::string>& row, const std::string& key)
{
  const auto it = row.find(key);
  return it == row.end() ? std::numeric_limits<double>::quiet_NaN()
                         : std::strtod(it->second.c_str(), nullptr);
}
}

// FORMULA-SPECIFIC TESTS FOLLOW
TEST(PhysicalMedium, LimitsOfTheFormula)
{
  // No scattering: single scattering with full shadows, no diffusion.
  for (double tau : { 0.05, 0.25, 1.0 })
  {
    const std::vector<double> p = Map(0.0, 0.5, tau);
    EXPECT_DOUBLE_EQ(p[mmv::Ambient],
      1.0 / (4.0 * M_PI * (1.0 + mmv::PhysicalMediumCoefficients.DenseDimming * tau)));
    EXPECT_DOUBLE_EQ(p[mmv::Attenuation], 1.0);
    EXPECT_DOUBLE_EQ(p[mmv::Scattering], 0.0);
  }
  // Isotropic scattering keeps the full attenuation at any albedo.
  for (double a : { 0.3, 0.9, 0.999 })
  {
    EXPECT_DOUBLE_EQ(Map(a, 0.0, 0.25)[mmv::Attenuation], 1.0);
  }
  // Similarity: c_t = (1 - a g)^AttenuationPower.
  EXPECT_NEAR(Map(0.9, 0.6, 0.25)[mmv::Attenuation],
    std::pow(0.46, mmv::PhysicalMediumCoefficients.AttenuationPower), 1e-12);
  // More albedo: more light (ka) and farther diffusion (s); more g: lighter
  // shadows; denser voxels: shorter diffusion in voxels.
  double previous[3] = { 0.0, 0.0, 2.0 };
  for (double a : { 0.1, 0.3, 0.6, 0.9, 0.99, 0.999 })
  {
    const std::vector<double> p = Map(a, 0.6, 0.25);
    EXPECT_GT(p[mmv::Ambient], previous[0]) << a;
    EXPECT_GT(p[mmv::Scattering], previous[1]) << a;
    EXPECT_LT(p[mmv::Attenuation], previous[2]) << a;
    previous[0] = p[mmv::Ambient];
    previous[1] = p[mmv::Scattering];
    previous[2] = p[mmv::Attenuation];
  }
  EXPECT_LT(Map(0.9, 0.9, 0.25)[mmv::Attenuation], Map(0.9, 0.3, 0.25)[mmv::Attenuation]);
  EXPECT_GT(Map(0.9, 0.3, 0.05)[mmv::Scattering], Map(0.9, 0.3, 0.5)[mmv::Scattering]);
  // Every output is a valid material over the whole domain, edges included
  // (a vanishing extinction drives s to its cap).
  for (double a : { 0.0, 0.5, 0.999 })
  {
    for (double g : { 0.0, 0.45, 0.9 })
    {
      for (double tau : { 1e-9, 0.25, 13.8 })
      {
        const std::vector<double> p = Map(a, g, tau);
        for (int i = 0; i < P; ++i)
        {
          std::string why;
          EXPECT_TRUE(mmv::IsValidMaterialValue(i, p[i], &why)) << why;
        }
        EXPECT_DOUBLE_EQ(p[mmv::Anisotropy], g);
        EXPECT_EQ(p[mmv::Diffuse], 0.0);
        EXPECT_EQ(p[mmv::Specular], 0.0);
        EXPECT_EQ(p[mmv::Reflection], 0.0);
        EXPECT_EQ(p[mmv::Emission], 0.0);
      }
    }
  }
  EXPECT_EQ(
    Map(0.5, 0.3, 1e-9)[mmv::Scattering], mmv::MaterialParameterTable[mmv::Scattering].HardMax);
}

TEST(PhysicalMedium, RejectsInputOutsideTheDomain)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  struct Case
  {
    double Albedo, G, Extinction;
    const char* Word; // the explanation names the offending input
  };
  const Case cases[] = { { -0.1, 0.0, 0.25, "albedo" }, { 1.0, 0.0, 0.25, "albedo" },
    { nan, 0.0, 0.25, "albedo" }, { 0.5, -0.3, 0.25, "anisotropy" },
    { 0.5, 0.95, 0.25, "anisotropy" }, { 0.5, inf, 0.25, "anisotropy" },
    { 0.5, 0.3, 0.0, "extinction" }, { 0.5, 0.3, -1.0, "extinction" },
    { 0.5, 0.3, nan, "extinction" }, { 0.5, 0.3, inf, "extinction" } };
  for (const Case& c : cases)
  {
    std::vector<double> p(P, -7.0);
    std::string why;
    EXPECT_FALSE(mmv::PhysicalMediumToMaterial(c.Albedo, c.G, c.Extinction, p.data(), &why));
    EXPECT_NE(why.find(c.Word), std::string::npos) << why;
    EXPECT_EQ(p, std::vector<double>(P, -7.0)) << "parameters touched on rejection";
    // Without a `why` it still answers false.
    EXPECT_FALSE(mmv::PhysicalMediumToMaterial(c.Albedo, c.G, c.Extinction, p.data()));
  }
}

// The entry point for C++ and Python users (physical_medium_node in the
// package): the node holds the formula's parameters; outside the domain it
// adds nothing and reports the formula's reason.
TEST(PhysicalMedium, TransferFunctionNodeIsTheFormulasOutput)
{
  vtkNew<vtkMaterialTransferFunction> function;
  mmvtest::ErrorCounter errors(function);
  EXPECT_EQ(function->AddPhysicalMediumNode(1300.0, 0.3, 0.6, 0.5), 0);
  EXPECT_EQ(function->AddPhysicalMediumNode(600.0, 0.9, 0.8, 0.25), 0); // index in value order
  EXPECT_EQ(errors.Errors(), 0) << errors.LastMessage();
  ASSERT_EQ(function->GetSize(), 2);
  double node[vtkMaterialTransferFunction::NodeStride];
  ASSERT_TRUE(function->GetNode(0, node));
  EXPECT_EQ(node[0], 600.0);
  const std::vector<double> expected = Map(0.9, 0.8, 0.25);
  for (int i = 0; i < P; ++i)
  {
    EXPECT_EQ(node[i + 1], expected[i]) << mmv::MaterialParameterTable[i].Key;
  }
  EXPECT_EQ(vtkMaterialTransferFunction::PhysicalMediumDomainError(0.9, 0.8, 0.25), "");

  EXPECT_EQ(function->AddPhysicalMediumNode(900.0, 0.5, 0.95, 0.25), -1);
  EXPECT_EQ(errors.Errors(), 1);
  EXPECT_NE(errors.LastMessage().find("anisotropy"), std::string::npos) << errors.LastMessage();
  EXPECT_EQ(function->GetSize(), 2);
  const std::string why = vtkMaterialTransferFunction::PhysicalMediumDomainError(1.0, 0.0, 0.25);
  EXPECT_NE(why.find("albedo"), std::string::npos) << why;
}

TEST(PhysicalMedium, PresetsAreTheFormulasOutput)
{
  vtkNew<vtkMaterialLibrary> library;
  for (const mmv::PhysicalPreset& preset : mmv::PhysicalPresets)
  {
    SCOPED_TRACE(preset.Name);
    std::vector<double> stored(P, -1.0);
    ASSERT_TRUE(library->GetPreset(preset.Name, stored.data()));
    const std::vector<double> expected =
      Map(preset.Albedo, preset.Anisotropy, preset.ExtinctionPerVoxel);
    for (int i = 0; i < P; ++i)
    {
      // The JSON files carry 6 significant digits.
      EXPECT_NEAR(stored[i], expected[i], 1e-5 * std::abs(expected[i]))
        << mmv::MaterialParameterTable[i].Key;
    }
  }
}

TEST(PhysicalMedium, PublishedTableWasMeasuredWithThisFormula)
{
  // docs/medium_calibration.csv (mmvMediumCalibration) holds, per medium, the
  // mapped parameters it rendered and their error against the path tracer:
  // they must be this formula's output (a coefficient changed without a new
  // measurement fails here), and the mapped error must stay within the
  // residual docs/performance.md ("Physical media") states against the best
  // fit of the grid.
  const auto rows = ReadCSV(std::string(MMV_SOURCE_DIR) + "/docs/medium_calibration.csv");
  std::map<std::string, double> fitError;
  for (const auto& row : rows)
  {
    if (row.at("family") == "ours-fit")
    {
      fitError[row.at("albedo") + "/" + row.at("anisotropy") + "/" + row.at("depth")] =
        Number(row, "volume_rmse");
    }
  }
  int mapped = 0;
  for (const auto& row : rows)
  {
    if (row.at("family") != "ours-mapped")
    {
      continue;
    }
    ++mapped;
    const std::string key = row.at("albedo") + "/" + row.at("anisotropy") + "/" + row.at("depth");
    SCOPED_TRACE(key);
    const std::vector<double> p =
      Map(Number(row, "albedo"), Number(row, "anisotropy"), Number(row, "extinction_per_voxel"));
    // The CSV has 6 significant digits.
    EXPECT_NEAR(Number(row, "ka"), p[mmv::Ambient], 1e-5 * p[mmv::Ambient]);
    EXPECT_NEAR(Number(row, "attenuation"), p[mmv::Attenuation], 1e-5 * p[mmv::Attenuation]);
    EXPECT_NEAR(Number(row, "scattering"), p[mmv::Scattering], 1e-5 * p[mmv::Scattering] + 1e-9);
    ASSERT_TRUE(fitError.count(key));
    EXPECT_LE(Number(row, "volume_rmse"), MappedErrorFactor * fitError[key] + MappedErrorSlack);
  }
  EXPECT_EQ(mapped, 48); // 4 albedos x 4 g x 3 depths
}
