// mmv::MaterialNodeModel, the Multi-Material Editor's nodes without Qt: the
// property layout, legacy strides, sanitising of numbers the renderer
// rejects, and every edit the editor offers, against closed forms and
// vtkMaterialTransferFunction / vtkMaterialLibrary. No Qt, no display.
#include "mmvMaterialNodeModel.h"

#include "vtkMaterialLibrary.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMultiMaterialParameters.h"
#include "vtkNew.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace mmvtest
{
namespace
{
using Model = mmv::MaterialNodeModel;
constexpr int S = Model::Stride;
constexpr int P = Model::ParameterCount;
const double NaN = std::numeric_limits<double>::quiet_NaN();

// A node at `value` whose parameters are the table defaults, with `diffuse`.
std::vector<double> NodeAt(double value, double diffuse)
{
  std::vector<double> node(S);
  node[0] = value;
  for (int p = 0; p < P; ++p)
  {
    node[p + 1] = mmv::MaterialParameterTable[p].Default;
  }
  node[1 + mmv::Diffuse] = diffuse;
  return node;
}

std::vector<double> Concat(std::initializer_list<std::vector<double>> nodes)
{
  std::vector<double> flat;
  for (const auto& n : nodes)
  {
    flat.insert(flat.end(), n.begin(), n.end());
  }
  return flat;
}

// Two nodes: value 0 with diffuse 0.2, value 10 with diffuse 0.8.
void TwoNodes(Model& model)
{
  model.SetFlat(Concat({ NodeAt(0.0, 0.2), NodeAt(10.0, 0.8) }));
}
}

TEST(MaterialNodeModel, FlatListRoundTripsAndSortsByValue)
{
  Model model;
  const std::vector<double> a = NodeAt(5.0, 0.3), b = NodeAt(-1.0, 0.9);
  model.SetFlat(Concat({ a, b }));
  ASSERT_EQ(model.GetNumberOfNodes(), 2);
  EXPECT_EQ(model.GetNodes()[0][0], -1.0);
  EXPECT_EQ(model.GetNodes()[1][0], 5.0);
  EXPECT_EQ(model.GetFlat(), Concat({ b, a }));
  EXPECT_TRUE(model.GetLoadProblems().empty());
  EXPECT_EQ(model.GetCurrent(), -1);
}

TEST(MaterialNodeModel, OlderLayoutsTakeTheTableDefaultsForTheMissingFields)
{
  // 9 numbers a node (before emission) and 8 (before anisotropy).
  for (const int stride : { vtkMaterialTransferFunction::AnisotropyNodeStride,
         vtkMaterialTransferFunction::LegacyNodeStride })
  {
    std::vector<double> flat;
    for (double value : { 0.0, 1.0 })
    {
      std::vector<double> node = NodeAt(value, 0.4);
      node.resize(stride);
      flat.insert(flat.end(), node.begin(), node.end());
    }
    Model model;
    model.SetFlat(flat);
    ASSERT_EQ(model.GetNumberOfNodes(), 2) << "stride " << stride;
    for (const auto& node : model.GetNodes())
    {
      EXPECT_EQ(node[1 + mmv::Diffuse], 0.4);
      for (int p = stride - 1; p < P; ++p)
      {
        EXPECT_EQ(node[1 + p], mmv::MaterialParameterTable[p].Default) << "parameter " << p;
      }
    }
    EXPECT_EQ(model.GetFlat().size(), 2u * S) << "written back in the current layout";
  }
}

TEST(MaterialNodeModel, NonFiniteValueLeavesTheNodeOutAndIsReported)
{
  Model model;
  model.SetFlat(Concat(
    { NodeAt(1.0, 0.5), NodeAt(NaN, 0.5), NodeAt(std::numeric_limits<double>::infinity(), 0.5) }));
  ASSERT_EQ(model.GetNumberOfNodes(), 1);
  EXPECT_EQ(model.GetNodes()[0][0], 1.0);
  ASSERT_EQ(model.GetLoadProblems().size(), 2u);
  EXPECT_EQ(model.GetLoadProblems()[0].Parameter, -1);
  EXPECT_EQ(model.GetLoadProblems()[0].Node, 1);
  EXPECT_TRUE(std::isnan(model.GetLoadProblems()[0].Value));
  EXPECT_EQ(model.GetLoadProblems()[1].Node, 2);
}

TEST(MaterialNodeModel, RejectedParametersShowStandInsAndAreReported)
{
  Model model;
  std::vector<double> bad = NodeAt(2.0, NaN); // NaN: the default
  bad[1 + mmv::Shininess] = 5.0e4;            // above HardMax
  bad[1 + mmv::Anisotropy] = -3.0;            // below HardMin
  model.SetFlat(Concat({ NodeAt(7.0, 0.5), bad }));
  ASSERT_EQ(model.GetNumberOfNodes(), 2);
  const auto& node = model.GetNodes()[0]; // sorted: the bad node (value 2) first
  EXPECT_EQ(node[1 + mmv::Diffuse], mmv::MaterialParameterTable[mmv::Diffuse].Default);
  EXPECT_EQ(node[1 + mmv::Shininess], mmv::MaterialParameterTable[mmv::Shininess].HardMax);
  EXPECT_EQ(node[1 + mmv::Anisotropy], mmv::MaterialParameterTable[mmv::Anisotropy].HardMin);
  ASSERT_EQ(model.GetLoadProblems().size(), 3u);
  EXPECT_TRUE(model.IsStandIn(0, mmv::Diffuse));
  EXPECT_TRUE(model.IsStandIn(0, mmv::Shininess));
  EXPECT_TRUE(model.IsStandIn(0, mmv::Anisotropy));
  EXPECT_FALSE(model.IsStandIn(0, mmv::Ambient));
  EXPECT_FALSE(model.IsStandIn(1, mmv::Diffuse));
  EXPECT_FALSE(model.GetLoadProblems()[0].Why.empty());
  // The stand-ins make a list the renderer accepts.
  vtkNew<vtkMaterialTransferFunction> function;
  const std::vector<double> flat = model.GetFlat();
  EXPECT_TRUE(function->SetNodes(static_cast<int>(flat.size()), flat.data()));
  model.ClearLoadProblems();
  EXPECT_FALSE(model.IsStandIn(0, mmv::Diffuse));
}

TEST(MaterialNodeModel, InsertInterpolatesLikeTheRendererAndSelects)
{
  Model model;
  TwoNodes(model);
  bool inserted = false;
  EXPECT_EQ(model.Insert(2.5, &inserted), 1);
  EXPECT_TRUE(inserted);
  EXPECT_EQ(model.GetCurrent(), 1);
  ASSERT_EQ(model.GetNumberOfNodes(), 3);
  // Linear between (0, 0.2) and (10, 0.8): 0.2 + 0.25 * 0.6.
  EXPECT_NEAR(model.GetNodes()[1][1 + mmv::Diffuse], 0.35, 1e-12);
  // The curve is unchanged by the new node.
  EXPECT_NEAR(model.EvaluateParameter(5.0, mmv::Diffuse), 0.5, 1e-12);
}

TEST(MaterialNodeModel, InsertAtAnExistingValueSelectsThatNode)
{
  Model model;
  TwoNodes(model);
  bool inserted = true;
  EXPECT_EQ(model.Insert(10.0, &inserted), 1);
  EXPECT_FALSE(inserted);
  EXPECT_EQ(model.GetNumberOfNodes(), 2);
  EXPECT_EQ(model.GetCurrent(), 1);
  EXPECT_EQ(model.Insert(NaN, &inserted), -1);
  EXPECT_FALSE(inserted);
  EXPECT_EQ(model.GetNumberOfNodes(), 2);
}

TEST(MaterialNodeModel, InsertIntoNoNodesTakesTheTableDefaults)
{
  Model model;
  EXPECT_EQ(model.Insert(3.0), 0);
  ASSERT_EQ(model.GetNumberOfNodes(), 1);
  for (int p = 0; p < P; ++p)
  {
    EXPECT_EQ(model.GetNodes()[0][1 + p], mmv::MaterialParameterTable[p].Default);
  }
}

TEST(MaterialNodeModel, MoveStopsShortOfTheNeighbours)
{
  Model model;
  TwoNodes(model);
  model.Insert(5.0);
  const double range[2] = { 0.0, 10.0 };
  const double gap = 10.0 * 1e-4;
  EXPECT_TRUE(model.Move(1, 20.0, range));
  EXPECT_DOUBLE_EQ(model.GetNodes()[1][0], 10.0 - gap);
  EXPECT_TRUE(model.Move(1, -20.0, range));
  EXPECT_DOUBLE_EQ(model.GetNodes()[1][0], 0.0 + gap);
  EXPECT_TRUE(model.Move(1, 4.0, range));
  EXPECT_EQ(model.GetNodes()[1][0], 4.0);
  // The end nodes move freely outwards.
  EXPECT_TRUE(model.Move(2, 30.0, range));
  EXPECT_EQ(model.GetNodes()[2][0], 30.0);
  EXPECT_FALSE(model.Move(1, NaN, range));
  EXPECT_FALSE(model.Move(3, 1.0, range));
  EXPECT_EQ(model.GetNodes()[1][0], 4.0);
}

TEST(MaterialNodeModel, RemoveSelectsTheNextNode)
{
  Model model;
  TwoNodes(model);
  model.Insert(5.0);
  model.SetCurrent(2);
  EXPECT_TRUE(model.RemoveCurrent());
  EXPECT_EQ(model.GetCurrent(), 1) << "the new last node";
  model.SetCurrent(0);
  EXPECT_TRUE(model.RemoveCurrent());
  EXPECT_EQ(model.GetCurrent(), 0);
  EXPECT_EQ(model.GetNodes()[0][0], 5.0);
  EXPECT_TRUE(model.RemoveCurrent());
  EXPECT_EQ(model.GetCurrent(), -1);
  EXPECT_FALSE(model.RemoveCurrent());
}

TEST(MaterialNodeModel, SelectionSurvivesAReloadOfTheSameCountOnly)
{
  Model model;
  TwoNodes(model);
  model.SetCurrent(1);
  model.SetFlat(Concat({ NodeAt(0.0, 0.2), NodeAt(9.0, 0.8) })); // undo of a drag
  EXPECT_EQ(model.GetCurrent(), 1);
  model.SetFlat(NodeAt(0.0, 0.2));
  EXPECT_EQ(model.GetCurrent(), -1);
  model.SetCurrent(5);
  EXPECT_EQ(model.GetCurrent(), -1);
}

TEST(MaterialNodeModel, ParametersAndPresetsOfTheSelectedNode)
{
  Model model;
  TwoNodes(model);
  EXPECT_TRUE(model.SetParameter(0, mmv::Shininess, 42.0));
  EXPECT_EQ(model.GetNodes()[0][1 + mmv::Shininess], 42.0);
  EXPECT_EQ(model.EvaluateParameter(0.0, mmv::Shininess), 42.0);
  EXPECT_FALSE(model.SetParameter(0, P, 1.0));
  EXPECT_FALSE(model.SetParameter(2, 0, 1.0));

  double bone[P];
  ASSERT_TRUE(model.GetLibrary()->GetPreset("bone", bone));
  EXPECT_FALSE(model.SetCurrentParameters(bone)) << "no node selected";
  model.SetCurrent(1);
  EXPECT_TRUE(model.SetCurrentParameters(bone));
  EXPECT_STREQ(model.PresetOf(model.GetNodes()[1]), "bone");
  EXPECT_EQ(model.PresetOf(model.GetNodes()[0]), nullptr);
}

TEST(MaterialNodeModel, UniformAndPresetNodesMatchApplyPreset)
{
  Model model;
  TwoNodes(model);
  model.Insert(3.0);
  ASSERT_TRUE(model.TakePreset("skin", -5.0, 50.0));
  EXPECT_EQ(model.GetCurrent(), -1);
  vtkNew<vtkMaterialTransferFunction> reference;
  ASSERT_TRUE(reference->ApplyPreset("skin", -5.0, 50.0));
  std::vector<double> expected(static_cast<size_t>(reference->GetSize()) * S);
  reference->GetNodes(expected.data());
  EXPECT_EQ(model.GetFlat(), expected);

  double skin[P];
  ASSERT_TRUE(model.GetLibrary()->GetPreset("skin", skin));
  const double range[2] = { -5.0, 50.0 };
  model.SetUniform(skin, range);
  EXPECT_EQ(model.GetFlat(), expected);

  const std::vector<double> before = model.GetFlat();
  EXPECT_FALSE(model.TakePreset("no such preset", 0.0, 1.0));
  EXPECT_FALSE(model.TakePreset(nullptr, 0.0, 1.0));
  EXPECT_EQ(model.GetFlat(), before);
}

TEST(MaterialNodeModel, TrackRangeCoversTheDataAndEveryNode)
{
  Model model;
  double range[2];
  model.TrackRange(nullptr, range);
  EXPECT_EQ(range[0], 0.0);
  EXPECT_EQ(range[1], 1.0);

  model.SetFlat(NodeAt(4.0, 0.5));
  model.TrackRange(nullptr, range); // one node: a window of +-max(0.5, |4| / 2)
  EXPECT_EQ(range[0], 2.0);
  EXPECT_EQ(range[1], 6.0);

  const double data[2] = { 0.0, 10.0 };
  model.SetFlat(Concat({ NodeAt(-2.0, 0.5), NodeAt(12.0, 0.5) }));
  model.TrackRange(data, range);
  EXPECT_EQ(range[0], -2.0);
  EXPECT_EQ(range[1], 12.0);
}
}

// Every refused or changed typed value gets a notice saying so; an edit that
// goes through as typed leaves none.
TEST(MaterialNodeModel, TypedTextIsRefusedOrMovedWithANotice)
{
  mmv::MaterialNodeModel model;
  std::vector<double> flat = { 0.38, 0.1, 0.7, 0.2, 10, 1, 0, 0, 0, 0, 1, 1, 1, 0.8, 0.1, 0.7, 0.2,
    10, 1, 0, 0, 0, 0, 1, 1, 1 };
  model.SetFlat(flat);
  const double range[2] = { 0.0, 1.0 };

  // "nan" is not a value: refused, nothing moves.
  EXPECT_FALSE(model.SetValueText(1, "nan", range));
  EXPECT_EQ(model.GetNodes()[1][0], 0.8);
  EXPECT_NE(model.GetNotice().find("\"nan\" refused"), std::string::npos) << model.GetNotice();

  // -5 for the second node stops next to the first (0.38 + 1e-4 of the range).
  EXPECT_TRUE(model.SetValueText(1, "-5", range));
  EXPECT_NEAR(model.GetNodes()[1][0], 0.3801, 1e-12);
  EXPECT_NE(model.GetNotice().find("-5 moved to 0.3801"), std::string::npos) << model.GetNotice();

  // A value between the neighbours goes through: no notice.
  EXPECT_TRUE(model.SetValueText(1, " 5e-1 ", range));
  EXPECT_EQ(model.GetNodes()[1][0], 0.5);
  EXPECT_EQ(model.GetNotice(), "");

  // Parameters: NaN and values past the limits are refused and keep the old value.
  const double diffuse = model.GetNodes()[0][1 + mmv::Diffuse];
  EXPECT_FALSE(model.SetParameterText(0, mmv::Diffuse, "nan"));
  EXPECT_NE(model.GetNotice().find("\"nan\" refused: diffuse"), std::string::npos)
    << model.GetNotice();
  EXPECT_FALSE(model.SetParameterText(0, mmv::Diffuse, "-5"));
  EXPECT_NE(model.GetNotice().find("\"-5\" refused"), std::string::npos) << model.GetNotice();
  EXPECT_NE(model.GetNotice().find("kept 0.7"), std::string::npos) << model.GetNotice();
  EXPECT_EQ(model.GetNodes()[0][1 + mmv::Diffuse], diffuse);
  EXPECT_TRUE(model.SetParameterText(0, mmv::Diffuse, "0.25"));
  EXPECT_EQ(model.GetNodes()[0][1 + mmv::Diffuse], 0.25);
  EXPECT_EQ(model.GetNotice(), "");

  // What an editor refusing keystrokes shows is the same notice.
  EXPECT_EQ(mmv::MaterialNodeModel::ParameterTextNotice(mmv::Diffuse, "0.5", 0.7), "");
  EXPECT_NE(mmv::MaterialNodeModel::ParameterTextNotice(mmv::Diffuse, "abc", 0.7), "");
}
