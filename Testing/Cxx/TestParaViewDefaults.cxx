// The ParaView proxies (Plugin/MultiMaterialVolume.xml.in) repeat the C++
// defaults as text; this keeps every copy equal to the one table,
// vtkMultiMaterialSettings.h (a default written in several places drifts).
#include "vtkMultiMaterialParameters.h"
#include "vtkMultiMaterialSettings.h"

#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace
{
std::string ReadPluginXML()
{
  std::ifstream in(MMV_SOURCE_DIR "/Plugin/MultiMaterialVolume.xml.in");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

/// default_values of every property called `name`, in file order.
std::vector<double> Defaults(const std::string& xml, const std::string& name)
{
  const std::regex property("name=\"" + name + "\"[^>]*default_values=\"([^\"]*)\"");
  std::vector<double> values;
  for (auto it = std::sregex_iterator(xml.begin(), xml.end(), property);
       it != std::sregex_iterator(); ++it)
  {
    values.push_back(std::stod((*it)[1].str()));
  }
  return values;
}
} // namespace

TEST(ParaViewDefaults, ProxyDefaultsAreTheCppConstants)
{
  const std::string xml = ReadPluginXML();
  ASSERT_FALSE(xml.empty());
  // The representation and the Irradiance Volume filter.
  const std::vector<double> budget = Defaults(xml, "IrradianceMemoryMB");
  ASSERT_EQ(budget.size(), 2u);
  for (const double value : budget)
  {
    EXPECT_EQ(value, mmv::DefaultIrradianceBudgetMB);
  }
  const std::vector<double> slices = Defaults(xml, "PiecewiseShadowSlices");
  ASSERT_EQ(slices.size(), 2u);
  for (const double value : slices)
  {
    EXPECT_EQ(value, mmv::DefaultPiecewiseShadowSlices);
  }
  const std::vector<double> tolerance = Defaults(xml, "LightDirectionTolerance");
  ASSERT_EQ(tolerance.size(), 1u);
  EXPECT_EQ(tolerance[0], mmv::DefaultLightDirectionToleranceDegrees);
  const std::vector<double> exponential = Defaults(xml, "ExponentialDiffusion");
  ASSERT_EQ(exponential.size(), 1u);
  EXPECT_EQ(exponential[0], mmv::DefaultExponentialDiffusion ? 1.0 : 0.0);
  const std::vector<double> bound = Defaults(xml, "IrradianceErrorBound");
  ASSERT_EQ(bound.size(), 1u);
  EXPECT_EQ(bound[0], mmv::DefaultIrradianceErrorBoundDB);
}

TEST(ParaViewDefaults, EverySettingsPropertyDefaultsToItsRow)
{
  const std::string xml = ReadPluginXML();
  ASSERT_FALSE(xml.empty());
  int found = 0;
  for (const mmv::SettingDescription& row : mmv::IlluminationSettingDescriptions)
  {
    const std::string name = row.Name;
    const std::vector<double> values = Defaults(xml, name);
    if (name == "IrradianceCacheMB")
    {
      // The mapper keeps no earlier steps unless asked (0); the representation
      // asks for this much whenever the view caches its animation.
      ASSERT_EQ(values.size(), 1u);
      EXPECT_GT(values[0], row.Default);
      ++found;
      continue;
    }
    for (const double value : values)
    {
      EXPECT_EQ(value, row.Default) << name;
      EXPECT_GE(value, row.Min) << name;
      EXPECT_LE(value, row.Max) << name;
    }
    found += values.empty() ? 0 : 1;
  }
  // The panel's settings (sampling and data selection are VTK's own).
  EXPECT_GE(found, 16);
}
