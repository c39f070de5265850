// Tests of vtkMaterialTransferFunction: interpolation, node editing,
// validation (rejected edits change nothing and raise exactly one error),
// MTime, GPU tables, JSON and presets.
#include "mmvTestUtilities.h"
#include "vtkMaterialLibrary.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMultiMaterialParameters.h"
#include "vtkNew.h"
#include "vtkSmartPointer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace
{
constexpr int P = mmv::MaterialParameterCount;
constexpr int Stride = vtkMaterialTransferFunction::NodeStride;
const double NaN = std::numeric_limits<double>::quiet_NaN();
const double Inf = std::numeric_limits<double>::infinity();

std::vector<double> AllNodes(vtkMaterialTransferFunction* tf)
{
  std::vector<double> nodes(static_cast<std::size_t>(tf->GetSize()) * Stride);
  tf->GetNodes(nodes.data());
  return nodes;
}

std::vector<double> Evaluated(vtkMaterialTransferFunction* tf, double x)
{
  std::vector<double> parameters(P);
  tf->Evaluate(x, parameters.data());
  return parameters;
}

/// Two nodes whose parameters differ by exactly representable steps, so
/// interpolated values can be compared exactly.
void AddTwoNodes(vtkMaterialTransferFunction* tf)
{
  ASSERT_EQ(tf->AddNode(0.0, 0.0, 0.5, 1.0, 10.0, 0.0, 2.0, 0.25, -0.5, 1.0, 1.0, 0.5, 0.25), 0);
  ASSERT_EQ(tf->AddNode(10.0, 1.0, 0.25, 0.0, 50.0, 2.0, 6.0, 0.75, 0.5, 3.0, 0.5, 1.0, 0.75), 1);
}

std::string TempPath(const std::string& name)
{
  return ::testing::TempDir() + "mmv_" + name;
}
}

TEST(MaterialTransferFunction, EmptyFunctionReturnsDefaults)
{
  vtkNew<vtkMaterialTransferFunction> tf;
  EXPECT_EQ(tf->GetSize(), 0);
  for (double x : { -1.0e9, 0.0, 3.5, 1.0e9 })
  {
    const std::vector<double> parameters = Evaluated(tf, x);
    for (int p = 0; p < P; ++p)
    {
      EXPECT_EQ(parameters[p], mmv::MaterialParameterTable[p].Default) << "x=" << x << " p=" << p;
      EXPECT_EQ(tf->EvaluateParameter(x, p), mmv::MaterialParameterTable[p].Default);
    }
  }
  EXPECT_EQ(Evaluated(tf, 0)[mmv::Shininess], 20.0);
  EXPECT_EQ(Evaluated(tf, 0)[mmv::Diffuse], 0.7);
  double range[2] = { -1, -1 };
  tf->GetRange(range);
  EXPECT_EQ(range[0], 0.0);
  EXPECT_EQ(range[1], 0.0);
}

TEST(MaterialTransferFunction, InterpolatesLinearlyBetweenNodes)
{
  vtkNew<vtkMaterialTransferFunction> tf;
  AddTwoNodes(tf);
  const std::vector<double> mid = Evaluated(tf, 5.0);
  const std::vector<double> expectedMid = { 0.5, 0.375, 0.5, 30.0, 1.0, 4.0, 0.5, 0.0, 2.0, 0.75,
    0.75, 0.5 };
  for (int p = 0; p < P; ++p)
  {
    EXPECT_EQ(mid[p], expectedMid[p]) << "parameter " << mmv::MaterialParameterTable[p].Key;
  }
  const std::vector<double> quarter = Evaluated(tf, 2.5);
  const std::vector<double> expectedQuarter = { 0.25, 0.4375, 0.75, 20.0, 0.5, 3.0, 0.375, -0.25,
    1.5, 0.875, 0.625, 0.375 };
  for (int p = 0; p < P; ++p)
  {
    EXPECT_EQ(quarter[p], expectedQuarter[p]) << "parameter " << mmv::MaterialParameterTable[p].Key;
  }
  EXPECT_EQ(tf->EvaluateParameter(7.5, mmv::Shininess), 40.0);
  EXPECT_EQ(tf->EvaluateParameter(7.5, mmv::Scattering), 5.0);
  // At a node the node's own values come back.
  EXPECT_EQ(tf->EvaluateParameter(10.0, mmv::Attenuation), 2.0);
  EXPECT_EQ(tf->EvaluateParameter(0.0, mmv::Specular), 1.0);
}

TEST(MaterialTransferFunction, InterpolatesWithinTheRightInterval)
{
  vtkNew<vtkMaterialTransferFunction> tf;
  tf->AddNode(0.0, 0, 0, 0, 0, 0, 0, 0);
  tf->AddNode(1.0, 0, 0, 0, 100, 0, 0, 0);
  tf->AddNode(3.0, 0, 0, 0, 0, 0, 0, 0);
  EXPECT_EQ(tf->EvaluateParameter(0.5, mmv::Shininess), 50.0);
  EXPECT_EQ(tf->EvaluateParameter(1.0, mmv::Shininess), 100.0);
  EXPECT_EQ(tf->EvaluateParameter(2.0, mmv::Shininess), 50.0);
  EXPECT_EQ(tf->EvaluateParameter(2.5, mmv::Shininess), 25.0);
}

TEST(MaterialTransferFunction, ClampsOutsideTheNodes)
{
  vtkNew<vtkMaterialTransferFunction> tf;
  AddTwoNodes(tf);
  const std::vector<double> first = { 0.0, 0.5, 1.0, 10.0, 0.0, 2.0, 0.25, -0.5, 1.0, 1.0, 0.5,
    0.25 };
  const std::vector<double> last = { 1.0, 0.25, 0.0, 50.0, 2.0, 6.0, 0.75, 0.5, 3.0, 0.5, 1.0,
    0.75 };
  EXPECT_EQ(Evaluated(tf, -0.001), first);
  EXPECT_EQ(Evaluated(tf, -1.0e30), first);
  EXPECT_EQ(Evaluated(tf, -Inf), first);
  EXPECT_EQ(Evaluated(tf, 10.001), last);
  EXPECT_EQ(Evaluated(tf, 1.0e30), last);
  EXPECT_EQ(Evaluated(tf, Inf), last);
  // NaN data must not produce NaN parameters.
  EXPECT_EQ(Evaluated(tf, NaN), first);
}

TEST(MaterialTransferFunction, SingleNodeIsConstant)
{
  vtkNew<vtkMaterialTransferFunction> tf;
  tf->AddNode(4.0, 0.1, 0.2, 0.3, 40.0, 0.5, 6.0, 0.7);
  // The 8-argument AddNode scatters isotropically, does not glow and casts
  // grey shadows: g = e = 0, T = (1, 1, 1).
  const std::vector<double> node = { 0.1, 0.2, 0.3, 40.0, 0.5, 6.0, 0.7, 0.0, 0.0, 1.0, 1.0, 1.0 };
  EXPECT_EQ(Evaluated(tf, -100.0), node);
  EXPECT_EQ(Evaluated(tf, 4.0), node);
  EXPECT_EQ(Evaluated(tf, 100.0), node);
}

TEST(MaterialTransferFunction, AddNodeAtExistingValueReplaces)
{
  vtkNew<vtkMaterialTransferFunction> tf;
  AddTwoNodes(tf);
  const double replacement[P] = { 0.9, 0.8, 0.7, 60.0, 1.5, 3.0, 0.1, 0.3 };
  EXPECT_EQ(tf->AddNode(10.0, replacement), 1);
  EXPECT_EQ(tf->GetSize(), 2);
  double node[Stride];
  ASSERT_TRUE(tf->GetNode(1, node));
  EXPECT_EQ(node[0], 10.0);
  for (int p = 0; p < P; ++p)
  {
    EXPECT_EQ(node[1 + p], replacement[p]);
  }
  // The other node is untouched.
  ASSERT_TRUE(tf->GetNode(0, node));
  EXPECT_EQ(node[0], 0.0);
  EXPECT_EQ(node[1 + mmv::Shininess], 10.0);
}

TEST(MaterialTransferFunction, NodesAreSortedWhenAddedOutOfOrder)
{
  vtkNew<vtkMaterialTransferFunction> tf;
  EXPECT_EQ(tf->AddNode(5.0, 0.5, 0, 0, 0, 0, 0, 0), 0);
  EXPECT_EQ(tf->AddNode(-1.0, 0.1, 0, 0, 0, 0, 0, 0), 0);
  EXPECT_EQ(tf->AddNode(3.0, 0.3, 0, 0, 0, 0, 0, 0), 1);
  EXPECT_EQ(tf->AddNode(9.0, 0.9, 0, 0, 0, 0, 0, 0), 3);
  ASSERT_EQ(tf->GetSize(), 4);
  const double expectedValues[] = { -1.0, 3.0, 5.0, 9.0 };
  const double expectedAmbient[] = { 0.1, 0.3, 0.5, 0.9 };
  for (int i = 0; i < 4; ++i)
  {
    double node[Stride];
    ASSERT_TRUE(tf->GetNode(i, node));
    EXPECT_EQ(node[0], expectedValues[i]);
    EXPECT_EQ(node[1], expectedAmbient[i]);
  }
  double node[Stride];
  EXPECT_FALSE(tf->GetNode(-1, node));
  EXPECT_FALSE(tf->GetNode(4, node));
  double range[2];
  tf->GetRange(range);
  EXPECT_EQ(range[0], -1.0);
  EXPECT_EQ(range[1], 9.0);
  EXPECT_DOUBLE_EQ(tf->EvaluateParameter(4.0, mmv::Ambient), 0.4);
}

TEST(MaterialTransferFunction, RemoveNode)
{
  vtkNew<vtkMaterialTransferFunction> tf;
  tf->AddNode(1.0, 0.1, 0, 0, 0, 0, 0, 0);
  tf->AddNode(2.0, 0.2, 0, 0, 0, 0, 0, 0);
  tf->AddNode(3.0, 0.3, 0, 0, 0, 0, 0, 0);
  mmvtest::ErrorCounter errors(tf);
  EXPECT_EQ(tf->RemoveNode(2.0), 1);
  EXPECT_EQ(tf->GetSize(), 2);
  EXPECT_EQ(tf->RemoveNode(2.0), -1);
  EXPECT_EQ(tf->RemoveNode(2.5), -1);
  EXPECT_EQ(tf->GetSize(), 2);
  EXPECT_DOUBLE_EQ(tf->EvaluateParameter(2.0, mmv::Ambient), 0.2); // now between 0.1 and 0.3
  EXPECT_EQ(tf->RemoveNode(3.0), 1);
  EXPECT_EQ(tf->RemoveNode(1.0), 0);
  EXPECT_EQ(tf->GetSize(), 0);
  EXPECT_EQ(errors.Errors(), 0);
  tf->AddNode(1.0, 0.1, 0, 0, 0, 0, 0, 0);
  tf->RemoveAllNodes();
  EXPECT_EQ(tf->GetSize(), 0);
}

TEST(MaterialTransferFunction, SetNodesGetNodesRoundTrip)
{
  vtkNew<vtkMaterialTransferFunction> tf;
  // Out of order on purpose: SetNodes sorts.
  const std::vector<double> input = {
    7.0, 0.7, 0.6, 0.5, 70.0, 1.7, 7.0, 0.07, 0.7, 7.5, 0.9, 0.8, 0.7,  //
    -2.0, 0.2, 0.3, 0.4, 2.0, 0.2, 0.5, 0.02, -0.2, 0.0, 1.0, 1.0, 1.0, //
    3.0, 0.3, 0.4, 0.6, 30.0, 1.3, 3.0, 0.03, 0.3, 0.25, 0.0, 0.5, 1.0, //
  };
  ASSERT_TRUE(tf->SetNodes(static_cast<int>(input.size()), input.data()));
  ASSERT_EQ(tf->GetSize(), 3);
  const std::vector<double> expected = {
    -2.0, 0.2, 0.3, 0.4, 2.0, 0.2, 0.5, 0.02, -0.2, 0.0, 1.0, 1.0, 1.0, //
    3.0, 0.3, 0.4, 0.6, 30.0, 1.3, 3.0, 0.03, 0.3, 0.25, 0.0, 0.5, 1.0, //
    7.0, 0.7, 0.6, 0.5, 70.0, 1.7, 7.0, 0.07, 0.7, 7.5, 0.9, 0.8, 0.7,  //
  };
  EXPECT_EQ(AllNodes(tf), expected);
  for (int i = 0; i < 3; ++i)
  {
    double node[Stride];
    ASSERT_TRUE(tf->GetNode(i, node));
    EXPECT_EQ(std::vector<double>(node, node + Stride),
      std::vector<double>(expected.begin() + i * Stride, expected.begin() + (i + 1) * Stride));
  }
  // Feeding GetNodes back gives the same function.
  vtkNew<vtkMaterialTransferFunction> copy;
  const std::vector<double> flat = AllNodes(tf);
  ASSERT_TRUE(copy->SetNodes(static_cast<int>(flat.size()), flat.data()));
  EXPECT_EQ(AllNodes(copy), expected);
  // An empty array clears.
  EXPECT_TRUE(tf->SetNodes(0, nullptr));
  EXPECT_EQ(tf->GetSize(), 0);
}

TEST(MaterialTransferFunction, SetNodesDuplicateValuesLastWins)
{
  vtkNew<vtkMaterialTransferFunction> tf;
  const std::vector<double> input = {
    1.0, 0.1, 0.1, 0.1, 1.0, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1, //
    1.0, 0.9, 0.9, 0.9, 9.0, 0.9, 0.9, 0.9, 0.9, 0.9, 0.9, 0.9, 0.9, //
  };
  ASSERT_TRUE(tf->SetNodes(static_cast<int>(input.size()), input.data()));
  EXPECT_EQ(AllNodes(tf), std::vector<double>(input.begin() + Stride, input.end()));
}

TEST(MaterialTransferFunction, SetNodesRejectsInvalidInput)
{
  std::vector<std::pair<std::string, std::vector<double>>> cases = {
    { "7 numbers", { 1, 0.1, 0.1, 0.1, 1, 0.1, 0.1 } },
    { "11 numbers", { 1, 0.1, 0.1, 0.1, 1, 0.1, 0.1, 0.1, 0.1, 2, 3 } },
    { "negative emission", { 1, 0.1, 0.1, 0.1, 1, 0.1, 0.1, 0.1, 0.1, -0.5 } },
    { "NaN emission", { 1, 0.1, 0.1, 0.1, 1, 0.1, 0.1, 0.1, 0.1, NaN } },
    { "anisotropy -1", { 1, 0.1, 0.1, 0.1, 1, 0.1, 0.1, 0.1, -1.0 } },
    { "anisotropy below HardMin",
      { 1, 0.1, 0.1, 0.1, 1, 0.1, 0.1, 0.1,
        std::nextafter(mmv::MaterialParameterTable[mmv::Anisotropy].HardMin, -Inf) } },
    { "NaN value", { NaN, 0.1, 0.1, 0.1, 1, 0.1, 0.1, 0.1 } },
    { "infinite value", { Inf, 0.1, 0.1, 0.1, 1, 0.1, 0.1, 0.1 } },
    { "NaN ambient", { 1, NaN, 0.1, 0.1, 1, 0.1, 0.1, 0.1 } },
    { "infinite scattering", { 1, 0.1, 0.1, 0.1, 1, 0.1, Inf, 0.1 } },
    { "negative diffuse", { 1, 0.1, -0.1, 0.1, 1, 0.1, 0.1, 0.1 } },
    { "negative reflection in second node",
      { 1, 0.1, 0.1, 0.1, 1, 0.1, 0.1, 0.1, 2, 0.1, 0.1, 0.1, 1, 0.1, 0.1, -1e-9 } },
  };
  for (int p = 0; p < P; ++p)
  {
    std::vector<double> node = { 1, 0.1, 0.1, 0.1, 1, 0.1, 0.1, 0.1, 0.1, 0.1, 0.5, 0.5, 0.5 };
    node[1 + p] = std::nextafter(mmv::MaterialParameterTable[p].HardMax, Inf);
    cases.emplace_back(std::string(mmv::MaterialParameterTable[p].Key) + " above HardMax", node);
  }

  for (const auto& c : cases)
  {
    SCOPED_TRACE(c.first);
    vtkNew<vtkMaterialTransferFunction> tf;
    AddTwoNodes(tf);
    const std::vector<double> before = AllNodes(tf);
    const vtkMTimeType mtime = tf->GetMTime();
    mmvtest::ErrorCounter errors(tf);
    EXPECT_FALSE(tf->SetNodes(static_cast<int>(c.second.size()), c.second.data()));
    EXPECT_EQ(AllNodes(tf), before);
    EXPECT_EQ(errors.Errors(), 1);
    EXPECT_EQ(tf->GetMTime(), mtime);
  }
}

TEST(MaterialTransferFunction, HardMaxItselfIsAccepted)
{
  vtkNew<vtkMaterialTransferFunction> tf;
  mmvtest::ErrorCounter errors(tf);
  std::vector<double> node = { 0.0 };
  for (int p = 0; p < P; ++p)
  {
    node.push_back(mmv::MaterialParameterTable[p].HardMax);
  }
  EXPECT_TRUE(tf->SetNodes(Stride, node.data()));
  EXPECT_EQ(AllNodes(tf), node);
  EXPECT_EQ(errors.Errors(), 0);
}

TEST(MaterialTransferFunction, AddNodeRejectsInvalidInput)
{
  const std::vector<std::pair<std::string, std::vector<double>>> cases = {
    { "NaN value", { NaN, 0.1, 0.1, 0.1, 1, 0.1, 0.1, 0.1, 0.0 } },
    { "-inf value", { -Inf, 0.1, 0.1, 0.1, 1, 0.1, 0.1, 0.1, 0.0 } },
    { "NaN specular", { 1, 0.1, 0.1, NaN, 1, 0.1, 0.1, 0.1, 0.0 } },
    { "negative attenuation", { 1, 0.1, 0.1, 0.1, 1, -0.5, 0.1, 0.1, 0.0 } },
    { "shininess above limit", { 1, 0.1, 0.1, 0.1, 1.0e4 + 1, 0.1, 0.1, 0.1, 0.0 } },
    { "anisotropy 1", { 1, 0.1, 0.1, 0.1, 1, 0.1, 0.1, 0.1, 1.0 } },
  };
  for (const auto& c : cases)
  {
    SCOPED_TRACE(c.first);
    vtkNew<vtkMaterialTransferFunction> tf;
    AddTwoNodes(tf);
    const std::vector<double> before = AllNodes(tf);
    const vtkMTimeType mtime = tf->GetMTime();
    mmvtest::ErrorCounter errors(tf);
    const std::vector<double>& n = c.second;
    EXPECT_EQ(tf->AddNode(n[0], n[1], n[2], n[3], n[4], n[5], n[6], n[7], n[8]), -1);
    // The array form reads every parameter (emission included): pad the
    // legacy-sized case with the default 0.
    std::vector<double> full = n;
    full.resize(vtkMaterialTransferFunction::NodeStride, 0.0);
    EXPECT_EQ(tf->AddNode(full[0], full.data() + 1), -1);
    EXPECT_EQ(AllNodes(tf), before);
    EXPECT_EQ(errors.Errors(), 2);
    EXPECT_EQ(tf->GetMTime(), mtime);
  }
}

TEST(MaterialTransferFunction, ErrorMessageNamesTheParameter)
{
  vtkNew<vtkMaterialTransferFunction> tf;
  mmvtest::ErrorCounter errors(tf);
  EXPECT_EQ(tf->AddNode(0.0, 0.1, 0.1, 0.1, 1.0, 0.1, -3.0, 0.1), -1);
  ASSERT_EQ(errors.Errors(), 1);
  EXPECT_NE(errors.LastMessage().find("scattering"), std::string::npos) << errors.LastMessage();
  EXPECT_FALSE(tf->FromJSON(R"({"nodes": [{"value": 0, "glossiness": 1}]})"));
  ASSERT_EQ(errors.Errors(), 2);
  EXPECT_NE(errors.LastMessage().find("glossiness"), std::string::npos) << errors.LastMessage();
}

TEST(MaterialTransferFunction, MTimeIncreasesOnEverySuccessfulEdit)
{
  vtkNew<vtkMaterialTransferFunction> tf;
  vtkNew<vtkMaterialTransferFunction> other;
  other->AddNode(1.0, 0.1, 0.2, 0.3, 4.0, 0.5, 0.6, 0.7);
  const std::string path = TempPath("mtime_tf.json");
  ASSERT_TRUE(other->WriteJSONFile(path.c_str()));
  const double flat[Stride] = { 2.0, 0.1, 0.2, 0.3, 4.0, 0.5, 0.6, 0.7 };
  const double parameters[P] = { 0.1, 0.2, 0.3, 4.0, 0.5, 0.6, 0.7 };

  const std::vector<std::pair<std::string, std::function<bool()>>> edits = {
    { "AddNode", [&] { return tf->AddNode(0.0, 0.1, 0.2, 0.3, 4.0, 0.5, 0.6, 0.7) == 0; } },
    { "AddNode replacing", [&] { return tf->AddNode(0.0, parameters) == 0; } },
    { "AddNode second", [&] { return tf->AddNode(5.0, parameters) == 1; } },
    { "RemoveNode", [&] { return tf->RemoveNode(5.0) == 1; } },
    { "SetNodes", [&] { return tf->SetNodes(Stride, flat); } },
    { "FromJSON", [&] { return tf->FromJSON(R"({"nodes": [{"value": 3}]})"); } },
    { "ApplyPreset", [&] { return tf->ApplyPreset("metal", 0.0, 1.0); } },
    { "ReadJSONFile", [&] { return tf->ReadJSONFile(path.c_str()); } },
    { "DeepCopy",
      [&]
      {
        tf->DeepCopy(other);
        return true;
      } },
    { "RemoveAllNodes",
      [&]
      {
        tf->RemoveAllNodes();
        return true;
      } },
  };
  for (const auto& edit : edits)
  {
    const vtkMTimeType before = tf->GetMTime();
    EXPECT_TRUE(edit.second()) << edit.first;
    EXPECT_GT(tf->GetMTime(), before) << edit.first;
  }
  std::remove(path.c_str());
}

TEST(MaterialTransferFunction, MTimeUnchangedByRejectedEditsAndQueries)
{
  vtkNew<vtkMaterialTransferFunction> tf;
  AddTwoNodes(tf);
  mmvtest::ErrorCounter errors(tf);
  const vtkMTimeType mtime = tf->GetMTime();
  const double bad[Stride] = { 2.0, -0.1, 0.2, 0.3, 4.0, 0.5, 0.6, 0.7 };
  EXPECT_EQ(tf->AddNode(NaN, 0.1, 0.2, 0.3, 4.0, 0.5, 0.6, 0.7), -1);
  EXPECT_FALSE(tf->SetNodes(Stride, bad));
  EXPECT_FALSE(tf->SetNodes(Stride - 1, bad));
  EXPECT_FALSE(tf->FromJSON("{"));
  EXPECT_FALSE(tf->ApplyPreset("no-such-material", 0.0, 1.0));
  EXPECT_FALSE(tf->ReadJSONFile(TempPath("does_not_exist.json").c_str()));
  EXPECT_EQ(tf->RemoveNode(123.0), -1);
  EXPECT_EQ(errors.Errors(), 6);
  // Queries do not count as edits either.
  double parameters[P];
  tf->Evaluate(3.0, parameters);
  float table[P * 4];
  tf->GetTable(0.0, 1.0, 4, table);
  tf->ToJSON();
  EXPECT_EQ(tf->GetMTime(), mtime);
}

TEST(MaterialTransferFunction, GetTableMatchesEvaluate)
{
  vtkNew<vtkMaterialTransferFunction> tf;
  AddTwoNodes(tf);
  tf->AddNode(4.0, 0.3, 0.9, 0.2, 100.0, 1.0, 12.0, 0.5);
  const int size = 17;
  const double xStart = -2.0;
  const double xEnd = 14.0; // step 1: samples at -2, -1, ..., 14
  std::vector<float> table(size * P, -1.0f);
  tf->GetTable(xStart, xEnd, size, table.data());
  for (int i = 0; i < size; ++i)
  {
    const double x = xStart + i;
    const std::vector<double> expected = Evaluated(tf, x);
    for (int p = 0; p < P; ++p)
    {
      EXPECT_EQ(table[i * P + p], static_cast<float>(expected[p])) << "x=" << x << " p=" << p;
    }
  }
  // Spot checks against hand-computed values: clamped, at a node, interpolated.
  EXPECT_EQ(table[0 * P + mmv::Shininess], 10.0f);  // x = -2
  EXPECT_EQ(table[6 * P + mmv::Shininess], 100.0f); // x = 4, node
  EXPECT_EQ(table[9 * P + mmv::Shininess], 75.0f);  // x = 7, between 100 and 50
  EXPECT_EQ(table[16 * P + mmv::Scattering], 6.0f); // x = 14, clamped
  EXPECT_EQ(table[4 * P + mmv::Scattering], 7.0f);  // x = 2, between 2 and 12

  // size 1 samples xStart.
  float one[P];
  tf->GetTable(4.0, 10.0, 1, one);
  EXPECT_EQ(one[mmv::Shininess], 100.0f);
}

TEST(MaterialTransferFunction, GetTableRejectsBadArguments)
{
  vtkNew<vtkMaterialTransferFunction> tf;
  mmvtest::ErrorCounter errors(tf);
  float table[P] = { -7.0f };
  tf->GetTable(0.0, 1.0, 0, table);
  tf->GetTable(0.0, 1.0, -3, table);
  tf->GetTable(0.0, 1.0, 4, nullptr);
  tf->GetTable(NaN, 1.0, 1, table);
  EXPECT_EQ(errors.Errors(), 4);
  EXPECT_EQ(table[0], -7.0f);
}

// The value interval outside which a parameter is 0, in closed form:
// linear between nodes, so it reaches from the node before the first
// non-zero one to the node after the last; clamped outside the nodes, so an
// end node that is non-zero reaches infinity.
TEST(MaterialTransferFunction, GetNonZeroRangeSpansTheNeighbouringNodes)
{
  const double infinity = std::numeric_limits<double>::infinity();
  vtkNew<vtkMaterialTransferFunction> tf;
  double range[2] = { -7.0, -7.0 };
  EXPECT_FALSE(tf->GetNonZeroRange(mmv::Reflection, range)); // default r = 0
  EXPECT_TRUE(tf->GetNonZeroRange(mmv::Diffuse, range));     // default kd > 0
  EXPECT_EQ(range[0], -infinity);
  EXPECT_EQ(range[1], infinity);
  for (double value : { 0.0, 10.0, 20.0, 30.0, 40.0 })
  {
    const double r = value == 20.0 || value == 30.0 ? 0.5 : 0.0;
    tf->AddNode(value, 0.1, 0.7, 0.2, 20.0, 1.0, 0.0, r);
  }
  ASSERT_TRUE(tf->GetNonZeroRange(mmv::Reflection, range));
  EXPECT_EQ(range[0], 10.0);
  EXPECT_EQ(range[1], 40.0);
  EXPECT_EQ(tf->EvaluateParameter(10.0, mmv::Reflection), 0.0); // the interval is tight
  EXPECT_GT(tf->EvaluateParameter(10.5, mmv::Reflection), 0.0);
  EXPECT_GT(tf->EvaluateParameter(39.5, mmv::Reflection), 0.0);
  EXPECT_EQ(tf->EvaluateParameter(40.0, mmv::Reflection), 0.0);
  tf->AddNode(0.0, 0.1, 0.7, 0.2, 20.0, 1.0, 0.0, 0.3); // the first node reflects
  ASSERT_TRUE(tf->GetNonZeroRange(mmv::Reflection, range));
  EXPECT_EQ(range[0], -infinity);
  EXPECT_EQ(range[1], 40.0);
  EXPECT_FALSE(tf->GetNonZeroRange(mmv::Scattering, range)); // s = 0 everywhere
  EXPECT_EQ(range[0], -infinity);                            // untouched
  mmvtest::ErrorCounter errors(tf);
  EXPECT_FALSE(tf->GetNonZeroRange(P, range));
  EXPECT_EQ(errors.Errors(), 1);
}

TEST(MaterialTransferFunction, GetMaximum)
{
  vtkNew<vtkMaterialTransferFunction> tf;
  for (int p = 0; p < P; ++p)
  {
    EXPECT_EQ(tf->GetMaximum(p), mmv::MaterialParameterTable[p].Default);
  }
  AddTwoNodes(tf);
  tf->AddNode(4.0, 0.3, 0.9, 0.2, 100.0, 1.0, 12.0, 0.5);
  const double expected[P] = { 1.0, 0.9, 1.0, 100.0, 2.0, 12.0, 0.75, 0.5, 3.0, 1.0, 1.0, 1.0 };
  for (int p = 0; p < P; ++p)
  {
    EXPECT_EQ(tf->GetMaximum(p), expected[p]) << mmv::MaterialParameterTable[p].Key;
  }
  tf->RemoveNode(4.0);
  EXPECT_EQ(tf->GetMaximum(mmv::Scattering), 6.0);
  // All-zero scattering gives 0, the hint that lets renderers skip diffusion.
  tf->ApplyPreset("metal", 0.0, 1.0);
  EXPECT_EQ(tf->GetMaximum(mmv::Scattering), 0.0);

  mmvtest::ErrorCounter errors(tf);
  EXPECT_EQ(tf->GetMaximum(-1), 0.0);
  EXPECT_EQ(tf->GetMaximum(P), 0.0);
  EXPECT_EQ(errors.Errors(), 2);
}

TEST(MaterialTransferFunction, JSONRoundTripIsExact)
{
  vtkNew<vtkMaterialTransferFunction> tf;
  // Values without short decimal forms: the round trip must not round them.
  tf->AddNode(0.1, 1.0 / 3.0, 0.7, 0.2, 20.0 / 7.0, 1.0, 0.0, 1.0e-300);
  tf->AddNode(-1234.5678, 0.0, 1.0 / 7.0, 999.9999999999, 1.0e4, 2.0 / 3.0, 0.1 + 0.2, 0.0);
  tf->AddNode(1.0e12, 5e-324, 0.5, 0.5, 0.0, 1.0e3, 1.0e4, 0.125, 0.0, 0.0, 1.0 / 3.0, 0.1, 1.0);
  const std::string json = tf->ToJSON();
  for (int p = 0; p < P; ++p)
  {
    EXPECT_NE(
      json.find(std::string("\"") + mmv::MaterialParameterTable[p].Key + "\""), std::string::npos);
  }
  vtkNew<vtkMaterialTransferFunction> back;
  mmvtest::ErrorCounter errors(back);
  ASSERT_TRUE(back->FromJSON(json)) << json;
  EXPECT_EQ(errors.Errors(), 0);
  EXPECT_EQ(AllNodes(back), AllNodes(tf)); // bitwise equal doubles
  EXPECT_EQ(back->ToJSON(), json);

  // An empty function round-trips too.
  vtkNew<vtkMaterialTransferFunction> empty;
  ASSERT_TRUE(back->FromJSON(empty->ToJSON()));
  EXPECT_EQ(back->GetSize(), 0);
}

TEST(MaterialTransferFunction, JSONMissingParametersTakeDefaultsAndNodesAreSorted)
{
  vtkNew<vtkMaterialTransferFunction> tf;
  ASSERT_TRUE(tf->FromJSON(R"({"nodes": [
      {"value": 5, "scattering": 3},
      {"value": -1, "shininess": 80, "ambient": 0}
    ]})"));
  ASSERT_EQ(tf->GetSize(), 2);
  const std::vector<double> expected = {
    -1.0, 0.0, 0.7, 0.2, 80.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, //
    5.0, 0.2, 0.7, 0.2, 20.0, 1.0, 3.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0,  //
  };
  EXPECT_EQ(AllNodes(tf), expected);
  // Integers are accepted as numbers.
  ASSERT_TRUE(tf->FromJSON(R"({"nodes": [{"value": 2, "shininess": 7}]})"));
  EXPECT_EQ(tf->EvaluateParameter(0.0, mmv::Shininess), 7.0);
}

TEST(MaterialTransferFunction, MalformedJSONIsRejectedAndChangesNothing)
{
  const std::vector<std::pair<std::string, std::string>> cases = {
    { "empty text", "" },
    { "syntax error", R"({"nodes": [)" },
    { "trailing garbage", R"({"nodes": []} x)" },
    { "top level array", R"([{"value": 0}])" },
    { "top level string", R"("nodes")" },
    { "top level null", "null" },
    { "missing nodes", "{}" },
    { "nodes not an array", R"({"nodes": {"value": 0}})" },
    { "nodes a number", R"({"nodes": 3})" },
    { "unknown top-level key", R"({"nodes": [], "version": 2})" },
    { "node not an object", R"({"nodes": [1]})" },
    { "node missing value", R"({"nodes": [{"ambient": 0.1}]})" },
    { "unknown node key", R"({"nodes": [{"value": 0, "glossiness": 1}]})" },
    { "string instead of number", R"({"nodes": [{"value": 0, "diffuse": "0.5"}]})" },
    { "string value", R"({"nodes": [{"value": "0"}]})" },
    { "boolean parameter", R"({"nodes": [{"value": 0, "ambient": true}]})" },
    { "null parameter", R"({"nodes": [{"value": 0, "ambient": null}]})" },
    { "negative", R"({"nodes": [{"value": 0, "specular": -0.1}]})" },
    { "1e400 parameter", R"({"nodes": [{"value": 0, "scattering": 1e400}]})" },
    { "1e400 value", R"({"nodes": [{"value": 1e400}]})" },
    { "NaN literal", R"({"nodes": [{"value": NaN}]})" },
    { "shininess above limit", R"({"nodes": [{"value": 0, "shininess": 10000.5}]})" },
    { "second node bad", R"({"nodes": [{"value": 0}, {"value": 1, "reflection": -1}]})" },
  };
  for (const auto& c : cases)
  {
    SCOPED_TRACE(c.first);
    vtkNew<vtkMaterialTransferFunction> tf;
    AddTwoNodes(tf);
    const std::vector<double> before = AllNodes(tf);
    const vtkMTimeType mtime = tf->GetMTime();
    mmvtest::ErrorCounter errors(tf);
    EXPECT_FALSE(tf->FromJSON(c.second));
    EXPECT_EQ(AllNodes(tf), before);
    EXPECT_EQ(errors.Errors(), 1);
    EXPECT_EQ(tf->GetMTime(), mtime);
  }
}

TEST(MaterialTransferFunction, FileRoundTrip)
{
  vtkNew<vtkMaterialTransferFunction> tf;
  AddTwoNodes(tf);
  tf->AddNode(1.0 / 3.0, 0.3, 0.9, 0.2, 100.0, 1.0, 12.0, 0.5);
  const std::string path = TempPath("tf_round_trip.json");
  ASSERT_TRUE(tf->WriteJSONFile(path.c_str()));
  vtkNew<vtkMaterialTransferFunction> back;
  mmvtest::ErrorCounter errors(back);
  ASSERT_TRUE(back->ReadJSONFile(path.c_str()));
  EXPECT_EQ(AllNodes(back), AllNodes(tf));
  EXPECT_EQ(errors.Errors(), 0);
  std::remove(path.c_str());
}

TEST(MaterialTransferFunction, FileErrors)
{
  vtkNew<vtkMaterialTransferFunction> tf;
  AddTwoNodes(tf);
  const std::vector<double> before = AllNodes(tf);
  mmvtest::ErrorCounter errors(tf);

  EXPECT_FALSE(tf->ReadJSONFile(TempPath("no_such_file.json").c_str()));
  EXPECT_EQ(errors.Errors(), 1);
  EXPECT_NE(errors.LastMessage().find("no_such_file.json"), std::string::npos)
    << errors.LastMessage();
  EXPECT_FALSE(tf->ReadJSONFile(nullptr));
  EXPECT_EQ(errors.Errors(), 2);

  const std::string bad = TempPath("tf_bad.json");
  {
    FILE* f = std::fopen(bad.c_str(), "w");
    ASSERT_NE(f, nullptr);
    std::fputs(R"({"nodes": [{"value": 0, "ambient": -1}]})", f);
    std::fclose(f);
  }
  EXPECT_FALSE(tf->ReadJSONFile(bad.c_str()));
  EXPECT_EQ(errors.Errors(), 3);
  std::remove(bad.c_str());

  EXPECT_FALSE(tf->WriteJSONFile(TempPath("no_such_dir/out.json").c_str()));
  EXPECT_EQ(errors.Errors(), 4);
  EXPECT_EQ(AllNodes(tf), before);
}

TEST(MaterialTransferFunction, ApplyPresetMatchesLibrary)
{
  vtkNew<vtkMaterialLibrary> library;
  ASSERT_GE(library->GetNumberOfPresets(), 7);
  for (int i = 0; i < library->GetNumberOfPresets(); ++i)
  {
    const char* name = library->GetPresetName(i);
    SCOPED_TRACE(name);
    std::vector<double> preset(P);
    ASSERT_TRUE(library->GetPreset(name, preset.data()));
    vtkNew<vtkMaterialTransferFunction> tf;
    mmvtest::ErrorCounter errors(tf);
    ASSERT_TRUE(tf->ApplyPreset(name, 10.0, 20.0));
    EXPECT_EQ(tf->GetSize(), 2);
    double range[2];
    tf->GetRange(range);
    EXPECT_EQ(range[0], 10.0);
    EXPECT_EQ(range[1], 20.0);
    for (double x : { -5.0, 10.0, 13.3, 20.0, 1.0e6 })
    {
      EXPECT_EQ(Evaluated(tf, x), preset) << "x=" << x;
    }
    EXPECT_EQ(errors.Errors(), 0);
  }
  // A concrete number from Filters/Materials/metal.json.
  vtkNew<vtkMaterialTransferFunction> tf;
  tf->ApplyPreset("metal", 0.0, 1.0);
  EXPECT_EQ(tf->EvaluateParameter(0.5, mmv::Shininess), 120.0);
  EXPECT_EQ(tf->EvaluateParameter(0.5, mmv::Reflection), 0.6);
}

TEST(MaterialTransferFunction, ApplyPresetWithEqualRangeUsesOneNode)
{
  vtkNew<vtkMaterialTransferFunction> tf;
  ASSERT_TRUE(tf->ApplyPreset("skin", 3.0, 3.0));
  ASSERT_EQ(tf->GetSize(), 1);
  double node[Stride];
  ASSERT_TRUE(tf->GetNode(0, node));
  EXPECT_EQ(node[0], 3.0);
  EXPECT_EQ(node[1 + mmv::Scattering], 8.0);
  EXPECT_EQ(node[1 + mmv::Attenuation], 0.5);
}

TEST(MaterialTransferFunction, ApplyPresetRejectsUnknownNamesAndBadRanges)
{
  vtkNew<vtkMaterialTransferFunction> tf;
  AddTwoNodes(tf);
  const std::vector<double> before = AllNodes(tf);
  const vtkMTimeType mtime = tf->GetMTime();
  mmvtest::ErrorCounter errors(tf);
  EXPECT_FALSE(tf->ApplyPreset("unobtainium", 0.0, 1.0));
  EXPECT_EQ(errors.Errors(), 1);
  EXPECT_NE(errors.LastMessage().find("unobtainium"), std::string::npos) << errors.LastMessage();
  EXPECT_FALSE(tf->ApplyPreset(nullptr, 0.0, 1.0));
  EXPECT_FALSE(tf->ApplyPreset("metal", 1.0, 0.0));
  EXPECT_FALSE(tf->ApplyPreset("metal", NaN, 1.0));
  EXPECT_FALSE(tf->ApplyPreset("metal", 0.0, Inf));
  EXPECT_EQ(errors.Errors(), 5);
  EXPECT_EQ(AllNodes(tf), before);
  EXPECT_EQ(tf->GetMTime(), mtime);
}

TEST(MaterialTransferFunction, DeepCopy)
{
  vtkNew<vtkMaterialTransferFunction> tf;
  AddTwoNodes(tf);
  vtkNew<vtkMaterialTransferFunction> copy;
  copy->AddNode(100.0, 0, 0, 0, 0, 0, 0, 0);
  copy->DeepCopy(tf);
  EXPECT_EQ(AllNodes(copy), AllNodes(tf));
  // The copy is independent.
  tf->RemoveAllNodes();
  EXPECT_EQ(copy->GetSize(), 2);
}

TEST(MaterialTransferFunction, PrintSelfListsNodes)
{
  vtkNew<vtkMaterialTransferFunction> tf;
  AddTwoNodes(tf);
  std::ostringstream os;
  tf->Print(os);
  const std::string text = os.str();
  EXPECT_NE(text.find("Nodes: 2"), std::string::npos) << text;
  EXPECT_NE(text.find("shininess=50"), std::string::npos) << text;
  EXPECT_NE(text.find("scattering=2"), std::string::npos) << text;
}

TEST(MaterialTransferFunction, LegacyEightNumberNodesLoadWithIsotropicScattering)
{
  // The MaterialNodes layout before anisotropy: value + 7 parameters.
  const std::vector<double> legacy = {
    -2.0, 0.2, 0.3, 0.4, 2.0, 0.2, 0.5, 0.02, //
    3.0, 0.3, 0.4, 0.6, 30.0, 1.3, 3.0, 0.03, //
  };
  EXPECT_EQ(vtkMaterialTransferFunction::DetectNodeStride(16, legacy.data()),
    vtkMaterialTransferFunction::LegacyNodeStride);
  vtkNew<vtkMaterialTransferFunction> tf;
  mmvtest::ErrorCounter errors(tf);
  ASSERT_TRUE(tf->SetNodes(static_cast<int>(legacy.size()), legacy.data()));
  const std::vector<double> expected = {
    -2.0, 0.2, 0.3, 0.4, 2.0, 0.2, 0.5, 0.02, 0.0, 0.0, 1.0, 1.0, 1.0, //
    3.0, 0.3, 0.4, 0.6, 30.0, 1.3, 3.0, 0.03, 0.0, 0.0, 1.0, 1.0, 1.0, //
  };
  EXPECT_EQ(AllNodes(tf), expected);
  EXPECT_EQ(errors.Errors(), 0);
}

TEST(MaterialTransferFunction, DetectNodeStrideOnCountsOfBothLayouts)
{
  // 72 numbers: 8 nodes of 9 (before emission) or 9 nodes of 8. Sorted
  // valid 9-number nodes (what GetNodes wrote then) are read as such...
  std::vector<double> current;
  for (int i = 0; i < 8; ++i)
  {
    const std::vector<double> node = { double(i), 0.2, 0.7, 0.2, 20.0, 1.0, 0.0, 0.0, 0.5 };
    current.insert(current.end(), node.begin(), node.end());
  }
  EXPECT_EQ(vtkMaterialTransferFunction::DetectNodeStride(72, current.data()),
    vtkMaterialTransferFunction::AnisotropyNodeStride);
  // ...while 9 legacy nodes (a data value where g would be, shininess 20
  // where g would be further on) are not valid 9-number nodes.
  std::vector<double> legacy;
  for (int i = 0; i < 9; ++i)
  {
    const std::vector<double> node = { 10.0 * i, 0.2, 0.7, 0.2, 20.0, 1.0, 0.0, 0.0 };
    legacy.insert(legacy.end(), node.begin(), node.end());
  }
  EXPECT_EQ(vtkMaterialTransferFunction::DetectNodeStride(72, legacy.data()),
    vtkMaterialTransferFunction::LegacyNodeStride);
  vtkNew<vtkMaterialTransferFunction> tf;
  ASSERT_TRUE(tf->SetNodes(72, legacy.data()));
  EXPECT_EQ(tf->GetSize(), 9);
  EXPECT_EQ(tf->EvaluateParameter(45.0, mmv::Shininess), 20.0);
  EXPECT_EQ(tf->EvaluateParameter(45.0, mmv::Anisotropy), 0.0);
  EXPECT_EQ(vtkMaterialTransferFunction::DetectNodeStride(7, legacy.data()), 0);
}

TEST(MaterialTransferFunction, OldJSONWithoutAnisotropyLoads)
{
  vtkNew<vtkMaterialTransferFunction> tf;
  ASSERT_TRUE(tf->FromJSON(R"({"nodes": [{"value": 1, "ambient": 0.3, "reflection": 0.2}]})"));
  EXPECT_EQ(tf->EvaluateParameter(1.0, mmv::Anisotropy), 0.0);
  EXPECT_EQ(tf->EvaluateParameter(1.0, mmv::Ambient), 0.3);
  ASSERT_TRUE(tf->FromJSON(R"({"nodes": [{"value": 1, "anisotropy": -0.4}]})"));
  EXPECT_EQ(tf->EvaluateParameter(1.0, mmv::Anisotropy), -0.4);
  EXPECT_NE(tf->ToJSON().find("\"anisotropy\""), std::string::npos);
  // Likewise emission (0 when missing).
  EXPECT_EQ(tf->EvaluateParameter(1.0, mmv::Emission), 0.0);
  ASSERT_TRUE(tf->FromJSON(R"({"nodes": [{"value": 1, "emission": 2.5}]})"));
  EXPECT_EQ(tf->EvaluateParameter(1.0, mmv::Emission), 2.5);
  EXPECT_NE(tf->ToJSON().find("\"emission\""), std::string::npos);
}
