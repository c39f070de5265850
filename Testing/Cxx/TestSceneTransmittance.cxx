// The transmittance through other volumes (Filters/vtkSceneTransmittance.h)
// against Beer-Lambert, the coarse extinction it marches
// (Filters/vtkCoarseExtinction.h), and the update plan's Occluders change.
#include "vtkCoarseExtinction.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkIrradianceUpdatePlan.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkSceneTransmittance.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <cmath>

namespace
{
/// A homogeneous occluder: the box [0, 10]^3 (11^3 voxel centres) of
/// extinction `mu` per unit.
struct Box
{
  mmv::IrradianceGrid Grid;
  std::vector<float> Extinction;
  explicit Box(float mu)
  {
    std::fill(this->Grid.Dimensions, this->Grid.Dimensions + 3, 11);
    this->Extinction.assign(11 * 11 * 11, mu);
  }
  mmv::Occluder At(const glm::dmat4& receiverToOccluder = glm::dmat4(1.0)) const
  {
    mmv::Occluder occluder;
    occluder.Grid = &this->Grid;
    occluder.Extinction = &this->Extinction;
    occluder.ReceiverToOccluder = receiverToOccluder;
    return occluder;
  }
};
}

TEST(SceneTransmittance, BeerLambertThroughABox)
{
  const Box box(0.1f);
  const glm::dvec3 up(0.0, 0.0, 1.0);
  // Straight up through 10 units, and diagonally through 10 sqrt(2).
  EXPECT_NEAR(
    mmv::OccluderTransmittance(box.At(), { 5.0, 5.0, -5.0 }, up, -1.0), std::exp(-1.0), 1e-6);
  const glm::dvec3 slanted = glm::normalize(glm::dvec3(1.0, 0.0, 1.0));
  EXPECT_NEAR(mmv::OccluderTransmittance(box.At(), { 0.0, 5.0, 0.0 }, slanted, -1.0),
    std::exp(-std::sqrt(2.0)), 1e-6);
  // Beside it, away from it, and a point light below it: nothing in the way.
  EXPECT_EQ(mmv::OccluderTransmittance(box.At(), { 20.0, 5.0, -5.0 }, up, -1.0), 1.0);
  EXPECT_EQ(mmv::OccluderTransmittance(box.At(), { 5.0, 5.0, -5.0 }, -up, -1.0), 1.0);
  EXPECT_EQ(mmv::OccluderTransmittance(box.At(), { 5.0, 5.0, -5.0 }, up, 4.0), 1.0);
  // A point light inside it: only the way to the light counts.
  EXPECT_NEAR(
    mmv::OccluderTransmittance(box.At(), { 5.0, 5.0, -5.0 }, up, 9.0), std::exp(-0.4), 1e-6);
}

TEST(SceneTransmittance, PlacementMovesAndScalesThePath)
{
  const Box box(0.1f);
  const glm::dvec3 up(0.0, 0.0, 1.0);
  // The occluder shifted by 20 along x in the receiver's space: the
  // receiver's point at x = 25 is under it.
  const glm::dmat4 shifted = glm::translate(glm::dmat4(1.0), glm::dvec3(-20.0, 0.0, 0.0));
  EXPECT_NEAR(mmv::OccluderTransmittance(box.At(shifted), { 25.0, 5.0, -5.0 }, up, -1.0),
    std::exp(-1.0), 1e-6);
  EXPECT_EQ(mmv::OccluderTransmittance(box.At(shifted), { 5.0, 5.0, -5.0 }, up, -1.0), 1.0);
  // Twice the occluder's units per receiver unit: its extinction is per
  // its own unit, so the same box is crossed in half the receiver's length
  // with the same optical depth.
  const glm::dmat4 scaled = glm::scale(glm::dmat4(1.0), glm::dvec3(2.0));
  EXPECT_NEAR(
    mmv::OccluderTransmittance(box.At(scaled), { 2.5, 2.5, -1.0 }, up, -1.0), std::exp(-1.0), 1e-6);
}

TEST(SceneTransmittance, GroupsLightsAsTheIrradianceTextures)
{
  const Box box(0.1f);
  mmv::IrradianceGrid grid; // two voxels below the box, one beside it
  grid.Dimensions[0] = 3;
  grid.Dimensions[1] = 1;
  grid.Dimensions[2] = 1;
  grid.Origin = glm::dvec3(0.0, 5.0, -5.0);
  grid.Spacing = glm::dvec3(10.0, 1.0, 1.0);
  std::vector<mmv::LightSource> lights(5); // directional, from +z
  lights[4].ToLight = glm::dvec3(0.0, 0.0, -1.0);
  std::vector<std::vector<float>> groups;
  mmv::ComputeSceneTransmittance(grid, lights, { box.At() }, groups);
  ASSERT_EQ(groups.size(), 2u);
  ASSERT_EQ(groups[0].size(), 12u);
  EXPECT_NEAR(groups[0][0], std::exp(-1.0), 1e-6); // voxel 0, light 0
  EXPECT_NEAR(groups[0][7], std::exp(-1.0), 1e-6); // voxel 1, light 3
  EXPECT_EQ(groups[0][8], 1.0f);                   // voxel 2: beside it
  EXPECT_EQ(groups[1][0], 1.0f);                   // light 4: from below
  EXPECT_EQ(groups[1][1], 1.0f);                   // no light 5
  // No occluder: all ones.
  mmv::ComputeSceneTransmittance(grid, lights, {}, groups);
  EXPECT_EQ(groups[0][0], 1.0f);
}

TEST(SceneTransmittance, CoarseExtinctionKeepsTheOpticalDepth)
{
  // A 1-voxel-thick sheet of value 1 in a 65^3 volume: on a 17^3 grid its
  // optical depth across is kept (the mean of the extinction, not of the
  // values).
  vtkNew<vtkImageData> image;
  image->SetDimensions(65, 65, 65);
  vtkNew<vtkFloatArray> values;
  values->SetNumberOfTuples(image->GetNumberOfPoints());
  for (vtkIdType i = 0; i < values->GetNumberOfTuples(); ++i)
  {
    values->SetValue(i, (i / (65 * 65)) == 30 ? 1.0f : 0.0f);
  }
  image->GetPointData()->SetScalars(values);
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0.0, 0.0);
  opacity->AddPoint(1.0, 0.5);
  const double range[2] = { 0.0, 1.0 };
  const std::vector<float> table = mmv::SampleExtinction(opacity, 1.0, nullptr, range, 256);
  EXPECT_NEAR(table.back(), std::log(2.0), 1e-6);
  mmv::CoarseExtinction coarse;
  EXPECT_TRUE(coarse.Update(image, values, range, table, 17));
  const unsigned long version = coarse.GetVersion();
  EXPECT_FALSE(coarse.Update(image, values, range, table, 17)); // nothing changed
  EXPECT_EQ(coarse.GetVersion(), version);
  const mmv::IrradianceGrid& grid = coarse.GetGrid();
  EXPECT_EQ(grid.Dimensions[2], 17);
  double depth = 0.0; // through the middle column, sum of mu * length
  for (int k = 0; k < grid.Dimensions[2]; ++k)
  {
    depth += coarse.GetValues()[(static_cast<size_t>(k) * 17 + 8) * 17 + 8] * grid.Spacing[2];
  }
  EXPECT_NEAR(depth, std::log(2.0), 0.02);
  values->Modified();
  EXPECT_TRUE(coarse.Update(image, values, range, table, 17));
  EXPECT_NE(coarse.GetVersion(), version);
}

TEST(SceneTransmittance, OccludersChangeIsPlanned)
{
  vtkIrradianceUpdatePlan::Inputs held;
  held.Volume.Occluders = { 1.0, 2.0 };
  std::fill(held.Dimensions, held.Dimensions + 3, 8);
  held.Lights.resize(1);
  vtkIrradianceUpdatePlan::Inputs now = held;
  EXPECT_TRUE(vtkIrradianceUpdatePlan::Make(&held, now, 0.0, glm::dvec3(0.0)).IsCurrent());
  now.Volume.Occluders.clear(); // another volume hidden or removed
  const vtkIrradianceUpdatePlan plan =
    vtkIrradianceUpdatePlan::Make(&held, now, 0.0, glm::dvec3(0.0));
  EXPECT_EQ(plan.GetChanges(), static_cast<unsigned int>(vtkIrradianceUpdatePlan::Occluders));
  EXPECT_TRUE(plan.RecomputesAllLights());
  EXPECT_TRUE(plan.KeepsVolume()); // an interactive frame may wait for the still one
  EXPECT_FALSE(plan.Prefilters());
}
