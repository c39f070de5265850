// Overlapping volumes on one grid, one field each (vtkVolumesToFields): the
// image whose fields one ray integrates.
#include "vtkVolumesToFields.h"

#include "mmvTestUtilities.h"

#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkTrivialProducer.h"
#include "vtkUnsignedCharArray.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>

namespace
{
using Field = std::function<double(double, double, double)>;

// An image of `dims` points at `origin` with `spacing`, one point array
// `name` of `f` at each point's position (stored as `type`).
template <typename ArrayT = vtkFloatArray>
vtkSmartPointer<vtkImageData> Volume(const char* name, const int dims[3], const double origin[3],
  const double spacing[3], const Field& f)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(dims[0], dims[1], dims[2]);
  image->SetOrigin(origin[0], origin[1], origin[2]);
  image->SetSpacing(spacing[0], spacing[1], spacing[2]);
  vtkNew<ArrayT> values;
  values->SetName(name);
  values->SetNumberOfTuples(image->GetNumberOfPoints());
  for (vtkIdType p = 0; p < image->GetNumberOfPoints(); ++p)
  {
    double x[3];
    image->GetPoint(p, x);
    values->SetTuple1(p, f(x[0], x[1], x[2]));
  }
  image->GetPointData()->SetScalars(values);
  return image;
}

vtkImageData* Merge(vtkVolumesToFields* merge, std::initializer_list<vtkImageData*> volumes)
{
  merge->RemoveAllInputs();
  for (vtkImageData* volume : volumes)
  {
    merge->AddInputData(volume);
  }
  merge->Update();
  return merge->GetOutput();
}
} // namespace

TEST(VolumesToFields, UnionGridTakesTheFinestSpacingAndReachesTheUpperCorner)
{
  const double lower[6] = { 0, 0, 0, 2.5, -1, 4 };
  const double upper[6] = { 9, 9, 9, 12.1, 3, 6 };
  const double spacings[6] = { 1, 1, 1, 0.5, 2, 0.25 };
  double origin[3], spacing[3];
  int dims[3];
  vtkVolumesToFields::UnionGrid(2, lower, upper, spacings, origin, spacing, dims);
  EXPECT_DOUBLE_EQ(origin[0], 0.0);
  EXPECT_DOUBLE_EQ(origin[1], -1.0);
  EXPECT_DOUBLE_EQ(origin[2], 0.0);
  EXPECT_DOUBLE_EQ(spacing[0], 0.5);
  EXPECT_DOUBLE_EQ(spacing[1], 1.0);
  EXPECT_DOUBLE_EQ(spacing[2], 0.25);
  // x: [0, 12.1] in steps of 0.5 needs 26 points (the last at 12.5); y: [-1,
  // 9] ends on a sample (11 points); z: [0, 9] (37 points).
  EXPECT_EQ(dims[0], 26);
  EXPECT_EQ(dims[1], 11);
  EXPECT_EQ(dims[2], 37);
}

// Two volumes of one lattice, the second shifted by whole steps: every
// value is copied, and points outside a volume take its lowest value.
TEST(VolumesToFields, VolumesOfOneLatticeAreCopiedExactly)
{
  const int dimsA[3] = { 10, 8, 6 };
  const int dimsB[3] = { 7, 8, 9 };
  const double originA[3] = { 0, 0, 0 };
  const double originB[3] = { 1.5, -1.0, 2.0 }; // 3, -2, 4 steps
  const double spacing[3] = { 0.5, 0.5, 0.5 };
  auto a = Volume<vtkUnsignedCharArray>("ball", dimsA, originA, spacing,
    [](double x, double y, double z) { return 10 + 7 * x + 5 * y + 3 * z; });
  auto b = Volume("slab", dimsB, originB, spacing,
    [](double x, double y, double z) { return std::sin(x) * std::cos(2 * y) + z * z; });
  vtkNew<vtkVolumesToFields> merge;
  vtkImageData* out = Merge(merge, { a, b });
  int dims[3];
  out->GetDimensions(dims);
  EXPECT_EQ(dims[0], 10);
  EXPECT_EQ(dims[1], 10);
  EXPECT_EQ(dims[2], 13);
  EXPECT_DOUBLE_EQ(out->GetOrigin()[1], -1.0);
  EXPECT_STREQ(out->GetPointData()->GetScalars()->GetName(), "ball");
  vtkDataArray* ball = out->GetPointData()->GetArray("ball");
  vtkDataArray* slab = out->GetPointData()->GetArray("slab");
  ASSERT_TRUE(ball && slab);
  const double ballMin = a->GetPointData()->GetScalars()->GetRange()[0];
  const double slabMin = b->GetPointData()->GetScalars()->GetRange()[0];
  int inside[2] = { 0, 0 };
  int wrong[2] = { 0, 0 };
  for (vtkIdType p = 0; p < out->GetNumberOfPoints(); ++p)
  {
    double x[3];
    out->GetPoint(p, x);
    int ijk[3];
    double pc[3];
    const bool inA = a->ComputeStructuredCoordinates(x, ijk, pc) != 0;
    const bool inB = b->ComputeStructuredCoordinates(x, ijk, pc) != 0;
    const double expectA =
      inA ? a->GetPointData()->GetScalars()->GetTuple1(a->FindPoint(x)) : ballMin;
    const double expectB =
      inB ? b->GetPointData()->GetScalars()->GetTuple1(b->FindPoint(x)) : slabMin;
    inside[0] += inA;
    inside[1] += inB;
    wrong[0] += ball->GetTuple1(p) != static_cast<float>(expectA);
    wrong[1] += slab->GetTuple1(p) != static_cast<float>(expectB);
  }
  EXPECT_EQ(inside[0], 10 * 8 * 6);
  EXPECT_EQ(inside[1], 7 * 8 * 9);
  EXPECT_EQ(wrong[0], 0);
  EXPECT_EQ(wrong[1], 0);
}

// A coarse volume resampled at a finer volume's spacing: trilinear
// interpolation reproduces a trilinear field exactly (the closed form at
// every point), here at 2.5 output points per input step.
TEST(VolumesToFields, ACoarseVolumeIsInterpolatedTrilinearly)
{
  const int dimsA[3] = { 9, 7, 5 };
  const int dimsB[3] = { 11, 6, 9 };
  const double originA[3] = { -4, -3, -2 };
  const double originB[3] = { -1, -1, -1 };
  const double spacingA[3] = { 1, 1, 1 };
  const double spacingB[3] = { 0.4, 0.4, 0.25 };
  const Field trilinear = [](double x, double y, double z)
  { return 2 * x - 3 * y + 0.5 * z + 0.25 * x * y * z - y * z + 1; };
  auto a = Volume("coarse", dimsA, originA, spacingA, trilinear);
  auto b = Volume("coarse", dimsB, originB, spacingB, [](double, double, double) { return 1.0; });
  vtkNew<vtkVolumesToFields> merge;
  vtkImageData* out = Merge(merge, { a, b });
  EXPECT_DOUBLE_EQ(out->GetSpacing()[0], 0.4);
  EXPECT_DOUBLE_EQ(out->GetSpacing()[2], 0.25);
  // The second input's repeated name is made unique.
  vtkDataArray* coarse = out->GetPointData()->GetArray("coarse");
  ASSERT_NE(out->GetPointData()->GetArray("coarse_2"), nullptr);
  double worst = 0.0;
  int inside = 0;
  for (vtkIdType p = 0; p < out->GetNumberOfPoints(); ++p)
  {
    double x[3];
    out->GetPoint(p, x);
    if (x[0] > 4 + 1e-9 || x[1] > 3 + 1e-9 || x[2] > 2 + 1e-9)
    {
      continue;
    }
    ++inside;
    worst = std::max(worst, std::abs(coarse->GetTuple1(p) - trilinear(x[0], x[1], x[2])));
  }
  EXPECT_GT(inside, 1000);
  EXPECT_LT(worst, 1e-4);
}

TEST(VolumesToFields, ActiveScalarsArePickedOrTheFirstOneComponentArray)
{
  const int dims[3] = { 4, 4, 4 };
  const double origin[3] = { 0, 0, 0 };
  const double spacing[3] = { 1, 1, 1 };
  auto a = Volume("density", dims, origin, spacing, [](double x, double, double) { return x; });
  vtkNew<vtkDoubleArray> vectors;
  vectors->SetName("velocity");
  vectors->SetNumberOfComponents(3);
  vectors->SetNumberOfTuples(a->GetNumberOfPoints());
  vectors->Fill(0.0);
  a->GetPointData()->AddArray(vectors);
  EXPECT_STREQ(vtkVolumesToFields::FieldOf(a)->GetName(), "density");
  a->GetPointData()->SetActiveScalars("velocity");
  EXPECT_STREQ(vtkVolumesToFields::FieldOf(a)->GetName(), "density");
  a->GetPointData()->RemoveArray("density");
  EXPECT_EQ(vtkVolumesToFields::FieldOf(a), nullptr);
}

TEST(VolumesToFields, BadInputsAreErrorsWithAnEmptyOutput)
{
  const int dims[3] = { 4, 4, 4 };
  const double origin[3] = { 0, 0, 0 };
  const double spacing[3] = { 1, 1, 1 };
  auto ok = Volume("v", dims, origin, spacing, [](double x, double, double) { return x; });
  vtkNew<vtkVolumesToFields> merge;
  // The filter's messages, and apart from them the executive's report that
  // the filter failed.
  mmvtest::ErrorCounter errors(merge);
  mmvtest::ErrorCounter pipeline(merge->GetExecutive());
  vtkImageData* out = Merge(merge, { ok, ok });
  ASSERT_EQ(out->GetNumberOfPoints(), 64);

  // Each merge is refused with an error naming the cause, and leaves an
  // empty output (the last good one does not stay).
  const auto refused = [&](std::initializer_list<vtkImageData*> volumes, const char* cause)
  {
    errors.Reset();
    vtkImageData* output = Merge(merge, volumes);
    EXPECT_GE(errors.Errors(), 1) << cause;
    EXPECT_NE(errors.LastMessage().find(cause), std::string::npos) << errors.LastMessage();
    EXPECT_EQ(output->GetNumberOfPoints(), 0) << cause;
  };
  // Five volumes: one ray shades at most four fields.
  refused({ ok, ok, ok, ok, ok }, "5 inputs");
  // A rotated volume.
  auto rotated = Volume("r", dims, origin, spacing, [](double, double, double) { return 1.0; });
  rotated->SetDirectionMatrix(0, 1, 0, 1, 0, 0, 0, 0, 1);
  refused({ ok, rotated }, "direction");
  // No one-component point array.
  auto noField = vtkSmartPointer<vtkImageData>::New();
  noField->SetDimensions(4, 4, 4);
  refused({ ok, noField }, "input 1 has no one-component");
  // A fine volume over a large box asks for too many points.
  const double far[3] = { 1000, 0, 0 };
  const double fine[3] = { 0.01, 0.01, 0.01 };
  auto distant = Volume("d", dims, far, fine, [](double, double, double) { return 1.0; });
  merge->SetMaximumNumberOfPoints(1000000);
  refused({ ok, distant }, "MaximumNumberOfPoints");

  // Good inputs again: the filter recovers.
  errors.Reset();
  out = Merge(merge, { ok, ok });
  EXPECT_EQ(errors.Errors(), 0) << errors.LastMessage();
  EXPECT_EQ(out->GetNumberOfPoints(), 64);
}
