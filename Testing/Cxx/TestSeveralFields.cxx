// Several fields on one grid: the 2-4 independent components of one array,
// each with its own colour, opacity and materials. Light sees one medium:
// a plate of one field shadows a floor of another as the closed form of
// its transmittance says, and as the same scene made of one field does;
// each field keeps its own colour and materials in the image.
#include "mmvPlateScene.h"
#include "mmvTestScenes.h"
#include "mmvTestUtilities.h"

#include "vtkCombinedFieldExtinction.h"
#include "vtkFloatArray.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMultiMaterialVolumeMapper.h"
#include "vtkPointData.h"
#include "vtkVolumesToFields.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <vector>

namespace
{
constexpr int N = 32;         // points per axis
constexpr double Alpha = 0.5; // each field's opacity at value 1 (linear from 0 at 0)

// The plate (above, lit first) and the floor of mmvPlateScene's shadow tests.
bool InPlate(int i, int j, int k)
{
  return k >= 19 && k <= 22 && i >= 9 && i <= 22 && j >= 9 && j <= 22;
}
bool InFloor(int i, int j, int k)
{
  return k >= 3 && k <= 6 && i >= 3 && i <= 28 && j >= 3 && j <= 28;
}

vtkSmartPointer<vtkImageData> MakeImage(
  int components, const std::function<void(int, int, int, float*)>& f)
{
  vtkNew<vtkFloatArray> values;
  values->SetName("fields");
  values->SetNumberOfComponents(components);
  values->SetNumberOfTuples(static_cast<vtkIdType>(N) * N * N);
  vtkIdType id = 0;
  for (int k = 0; k < N; ++k)
  {
    for (int j = 0; j < N; ++j)
    {
      for (int i = 0; i < N; ++i, ++id)
      {
        f(i, j, k, values->GetPointer(id * components));
      }
    }
  }
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(N, N, N);
  image->GetPointData()->SetScalars(values);
  return image;
}

// Field 0 the plate, field 1 the floor.
vtkSmartPointer<vtkImageData> TwoFields()
{
  return MakeImage(2,
    [](int i, int j, int k, float* v)
    {
      v[0] = InPlate(i, j, k) ? 1.0f : 0.0f;
      v[1] = InFloor(i, j, k) ? 1.0f : 0.0f;
    });
}

// The same scene as one field.
vtkSmartPointer<vtkImageData> OneField()
{
  return MakeImage(1,
    [](int i, int j, int k, float* v) { *v = InPlate(i, j, k) || InFloor(i, j, k) ? 1.0f : 0.0f; });
}

/// The plate scene with a linear opacity ramp (0 at 0, Alpha at 1) for each
/// field, one colour and one material; Colors / Opacities / Materials[f]
/// are field f's.
struct FieldsScene : mmvtest::PlateScene
{
  vtkNew<vtkColorTransferFunction> Colors[2];
  vtkNew<vtkPiecewiseFunction> Opacities[2];
  vtkNew<vtkMaterialTransferFunction> FieldMaterials[2];

  explicit FieldsScene(vtkImageData* image)
    : mmvtest::PlateScene(image, 0.2)
  {
    this->Mapper->MultipleScatteringOff();
    const int fields = image->GetPointData()->GetScalars()->GetNumberOfComponents();
    for (int f = 0; f < fields; ++f)
    {
      this->Colors[f]->AddRGBPoint(0.0, 1.0, 0.9, 0.8);
      this->Colors[f]->AddRGBPoint(1.0, 1.0, 0.9, 0.8);
      this->Opacities[f]->AddPoint(0.0, 0.0);
      this->Opacities[f]->AddPoint(1.0, Alpha);
      this->FieldMaterials[f]->AddNode(1.0, 0.6, 0.4, 0.2, 10.0, 1.0, 0.0, 0.0);
      this->Property->SetColor(f, this->Colors[f]);
      this->Property->SetScalarOpacity(f, this->Opacities[f]);
      this->Property->SetScalarOpacityUnitDistance(f, 1.0);
      this->Mapper->SetFieldMaterialTransferFunction(f, this->FieldMaterials[f]);
    }
  }

  std::vector<float> Irradiance()
  {
    std::vector<float> values;
    EXPECT_TRUE(this->Mapper->ReadIrradiance(this->Window, 0, values));
    return values;
  }
};

float At(const std::vector<float>& irradiance, int i, int j, int k)
{
  return irradiance[(static_cast<size_t>(k) * N + j) * N + i];
}

// The optical depth of a ramp of the value from 0 to 1 over one unit with
// opacity Alpha * v: int_0^1 -ln(1 - Alpha s) ds.
double RampDepth()
{
  return ((1.0 - Alpha) * std::log(1.0 - Alpha) + Alpha) / Alpha;
}

mmv::FieldOptics Optics(double alphaAtOne, double attenuation, double scattering, double unit)
{
  mmv::FieldOptics o;
  o.Opacity = { 0.0f, static_cast<float>(alphaAtOne) };
  o.Attenuation = { static_cast<float>(attenuation), static_cast<float>(attenuation) };
  o.Scattering = { static_cast<float>(scattering), static_cast<float>(scattering) };
  o.UnitDistance = unit;
  return o;
}
} // namespace

TEST(SeveralFields, CombinedOpacityIsTheOpacityOfTheSummedExtinction)
{
  // D = 1 - prod (1 - alpha_f)^(c_t,f / u_f).
  const std::vector<mmv::FieldOptics> optics = { Optics(0.5, 1.0, 2.0, 1.0),
    Optics(0.25, 2.0, 6.0, 2.0) };
  const double both[2] = { 1.0, 1.0 };
  EXPECT_NEAR(mmv::CombinedOpacity(both, optics), 1.0 - 0.5 * 0.75, 1e-6);
  // Between table entries the shadow extinction is interpolated: half way
  // up field 0's two-entry table, half its depth -ln(0.5).
  const double half[2] = { 0.5, 0.0 };
  EXPECT_NEAR(mmv::CombinedOpacity(half, optics), 1.0 - std::sqrt(0.5), 1e-6);
  const double none[2] = { 0.0, 0.0 };
  EXPECT_EQ(mmv::CombinedOpacity(none, optics), 0.0f);
  // An opaque field lets nothing through; a visible field that casts no
  // shadow (c_t = 0) stays non-empty with a shadow no image shows.
  const std::vector<mmv::FieldOptics> opaque = { Optics(1.0, 1.0, 0.0, 1.0),
    Optics(0.5, 0.0, 0.0, 1.0) };
  const double first[2] = { 1.0, 0.0 };
  EXPECT_EQ(mmv::CombinedOpacity(first, opaque), 1.0f);
  const double second[2] = { 0.0, 1.0 };
  const float unshadowed = mmv::CombinedOpacity(second, opaque);
  EXPECT_GT(unshadowed, 0.0f);
  EXPECT_LT(unshadowed, 1e-6f);

  // The array and the binned scattering: the floor's voxels scatter with
  // field 0's s alone, those of both fields at equal opacity with the mean.
  vtkNew<vtkFloatArray> values;
  values->SetNumberOfComponents(2);
  const float tuples[3][2] = { { 1.0f, 0.0f }, { 1.0f, 1.0f }, { 0.0f, 0.0f } };
  for (const auto& t : tuples)
  {
    values->InsertNextTuple2(t[0], t[1]);
  }
  const std::vector<mmv::FieldOptics> equal = { Optics(0.5, 1.0, 2.0, 1.0),
    Optics(0.5, 1.0, 6.0, 1.0) };
  vtkNew<vtkFloatArray> out;
  std::vector<float> scattering;
  std::string error;
  ASSERT_TRUE(mmv::CombineFieldExtinction(values, equal, 1001, out, scattering, &error)) << error;
  ASSERT_EQ(out->GetNumberOfTuples(), 3);
  EXPECT_NEAR(out->GetValue(0), 0.5, 1e-6);
  EXPECT_NEAR(out->GetValue(1), 0.75, 1e-6);
  EXPECT_EQ(out->GetValue(2), 0.0f);
  ASSERT_EQ(scattering.size(), 1001u);
  EXPECT_NEAR(scattering[500], 2.0, 1e-5);
  EXPECT_NEAR(scattering[750], 4.0, 1e-5);
  // A bin between them that no voxel fell into interpolates them.
  EXPECT_NEAR(scattering[625], 3.0, 1e-5);

  // More than 4 fields, or optics for a different number: refused.
  vtkNew<vtkFloatArray> five;
  five->SetNumberOfComponents(5);
  five->SetNumberOfTuples(1);
  EXPECT_FALSE(mmv::CombineFieldExtinction(
    five, std::vector<mmv::FieldOptics>(5, equal[0]), 16, out, scattering, &error));
  EXPECT_NE(error.find("at most 4"), std::string::npos) << error;
  EXPECT_FALSE(mmv::CombineFieldExtinction(values, { equal[0] }, 16, out, scattering, &error));
}

TEST(SeveralFields, PlateOfOneFieldShadowsTheFloorOfAnother)
{
  FieldsScene two(TwoFields());
  two.Render();
  ASSERT_TRUE(two.Mapper->GetMultiMaterialActive());
  EXPECT_EQ(two.Mapper->GetNumberOfFields(), 2);
  const std::vector<float> fields = two.Irradiance();
  FieldsScene one(OneField());
  one.Render();
  ASSERT_TRUE(one.Mapper->GetMultiMaterialActive());
  EXPECT_EQ(one.Mapper->GetNumberOfFields(), 1);
  const std::vector<float> single = one.Irradiance();
  ASSERT_EQ(fields.size(), single.size());
  ASSERT_EQ(fields.size(), static_cast<size_t>(N) * N * N);

  // The floor's top voxel under the plate's centre: the light crosses the
  // floor's own upper ramp, then the plate (two ramps and three unit
  // segments at Alpha), slightly slanted (the light's direction).
  const double slant = std::sqrt(4.0 * 4.0 + 2.0 * 2.0 + 100.0 * 100.0) / 100.0;
  const double shadowed = std::exp(-slant * (3.0 * RampDepth() - 3.0 * std::log(1.0 - Alpha)));
  const double open = std::exp(-slant * RampDepth());
  double worst = 0.0;
  for (size_t v = 0; v < fields.size(); ++v)
  {
    worst = std::max(worst, std::abs(double(fields[v]) - single[v]));
  }
  std::printf("floor under the plate: two fields %.4f, one field %.4f, closed form %.4f; in the "
              "open: %.4f, %.4f, %.4f; max |two - one| over the grid %.2g\n",
    At(fields, 15, 15, 6), At(single, 15, 15, 6), shadowed, At(fields, 4, 27, 6),
    At(single, 4, 27, 6), open, worst);
  EXPECT_NEAR(At(fields, 15, 15, 6), shadowed, 0.005);
  EXPECT_NEAR(At(fields, 4, 27, 6), open, 0.01);
  EXPECT_LE(worst, 0.01);
}

TEST(SeveralFields, LightScatteredByOneFieldReachesTheOther)
{
  // Both fields scatter alike (s = 4 voxels^2): the diffused irradiance of
  // two fields equals that of the same scene as one field, and differs
  // from the unscattered one.
  const auto scatter = [](FieldsScene& scene, int fields)
  {
    for (int f = 0; f < fields; ++f)
    {
      scene.FieldMaterials[f]->RemoveAllNodes();
      scene.FieldMaterials[f]->AddNode(1.0, 0.6, 0.4, 0.2, 10.0, 1.0, 4.0, 0.0);
    }
    scene.Mapper->MultipleScatteringOn();
  };
  FieldsScene two(TwoFields());
  scatter(two, 2);
  two.Render();
  const std::vector<float> fields = two.Irradiance();
  FieldsScene one(OneField());
  scatter(one, 1);
  one.Render();
  const std::vector<float> single = one.Irradiance();
  EXPECT_GT(two.Mapper->GetDiffusionPassCount(), 0);
  FieldsScene direct(TwoFields());
  direct.Render();
  const std::vector<float> unscattered = direct.Irradiance();
  ASSERT_EQ(fields.size(), single.size());
  double worst = 0.0;
  double change = 0.0;
  for (size_t v = 0; v < fields.size(); ++v)
  {
    worst = std::max(worst, std::abs(double(fields[v]) - single[v]));
    change = std::max(change, std::abs(double(fields[v]) - unscattered[v]));
  }
  std::printf("scattered irradiance, two fields against one: max |difference| %.2g; the "
              "scattering changes it by up to %.3f; floor under the plate %.4f (direct %.4f)\n",
    worst, change, At(fields, 15, 15, 6), At(unscattered, 15, 15, 6));
  EXPECT_LE(worst, 0.01);
  EXPECT_GE(change, 0.05);
}

TEST(SeveralFields, TheImageMatchesOneFieldAndEachFieldKeepsItsColour)
{
  FieldsScene two(TwoFields());
  const std::vector<unsigned char> fields = two.Render();
  FieldsScene one(OneField());
  const std::vector<unsigned char> single = one.Render();
  // The same normals (the gradient of the summed fields is the one field's),
  // shadows and tables: equal up to rounding.
  const double psnr = mmvtest::PSNR(fields, single);
  std::printf("two fields against one field, same optics: %.1f dB\n", psnr);
  EXPECT_GE(psnr, 60.0);

  // The plate red, the floor blue: the centre (the plate) is red, a pixel
  // outside the plate's shadow and outline (the floor) blue.
  two.Colors[0]->RemoveAllPoints();
  two.Colors[0]->AddRGBPoint(0.0, 1.0, 0.1, 0.1);
  two.Colors[1]->RemoveAllPoints();
  two.Colors[1]->AddRGBPoint(0.0, 0.1, 0.1, 1.0);
  two.Render();
  const std::vector<double> plate = two.Pixel(32, 32);
  const std::vector<double> floor = two.Pixel(10, 10);
  std::printf("plate pixel %.2f %.2f %.2f, floor pixel %.2f %.2f %.2f\n", plate[0], plate[1],
    plate[2], floor[0], floor[1], floor[2]);
  EXPECT_GT(plate[0], 0.2);
  EXPECT_GT(plate[0], 3.0 * plate[2]);
  EXPECT_GT(floor[2], 0.2);
  EXPECT_GT(floor[2], 3.0 * floor[0]);

  // Field 1's materials alone go dark: the floor turns black, the plate
  // keeps its colour.
  two.FieldMaterials[1]->RemoveAllNodes();
  two.FieldMaterials[1]->AddNode(1.0, 0.0, 0.0, 0.0, 10.0, 1.0, 0.0, 0.0);
  two.Render();
  const std::vector<double> darkFloor = two.Pixel(10, 10);
  const std::vector<double> samePlate = two.Pixel(32, 32);
  EXPECT_LT(darkFloor[2], 0.02);
  EXPECT_NEAR(samePlate[0], plate[0], 0.02);
}

TEST(SeveralFields, EachFieldIsReadOverItsOwnRange)
{
  // Field 1 in units ten times larger (and its functions alike) renders and
  // lights as before: every field is normalised over its own range.
  FieldsScene reference(TwoFields());
  const std::vector<unsigned char> expected = reference.Render();
  const std::vector<float> expectedLight = reference.Irradiance();
  FieldsScene scaled(MakeImage(2,
    [](int i, int j, int k, float* v)
    {
      v[0] = InPlate(i, j, k) ? 1.0f : 0.0f;
      v[1] = InFloor(i, j, k) ? 10.0f : 0.0f;
    }));
  scaled.Opacities[1]->RemoveAllPoints();
  scaled.Opacities[1]->AddPoint(0.0, 0.0);
  scaled.Opacities[1]->AddPoint(10.0, Alpha);
  scaled.Colors[1]->RemoveAllPoints();
  scaled.Colors[1]->AddRGBPoint(0.0, 1.0, 0.9, 0.8);
  scaled.Colors[1]->AddRGBPoint(10.0, 1.0, 0.9, 0.8);
  scaled.FieldMaterials[1]->RemoveAllNodes();
  scaled.FieldMaterials[1]->AddNode(10.0, 0.6, 0.4, 0.2, 10.0, 1.0, 0.0, 0.0);
  const std::vector<unsigned char> image = scaled.Render();
  const std::vector<float> light = scaled.Irradiance();
  double worst = 0.0;
  for (size_t v = 0; v < light.size(); ++v)
  {
    worst = std::max(worst, std::abs(double(light[v]) - expectedLight[v]));
  }
  const double psnr = mmvtest::PSNR(image, expected);
  std::printf(
    "field 1 in units 10x larger: %.1f dB, max |irradiance difference| %.2g\n", psnr, worst);
  EXPECT_GE(psnr, 45.0);
  EXPECT_LE(worst, 1e-3);
}

TEST(SeveralFields, AnOpacityEditOfOneFieldRelightsTheOther)
{
  FieldsScene two(TwoFields());
  two.Render();
  const float before = At(two.Irradiance(), 15, 15, 6);
  const int updates = two.Mapper->GetIrradianceUpdateCount();
  // The plate's field turns invisible: the floor under it is in the open.
  two.Opacities[0]->RemoveAllPoints();
  two.Opacities[0]->AddPoint(0.0, 0.0);
  two.Opacities[0]->AddPoint(1.0, 0.0);
  two.Render();
  const float after = At(two.Irradiance(), 15, 15, 6);
  std::printf(
    "floor under the plate: %.4f, then %.4f with the plate's field invisible\n", before, after);
  EXPECT_GT(two.Mapper->GetIrradianceUpdateCount(), updates);
  EXPECT_LT(before, 0.06);
  EXPECT_NEAR(after, std::exp(-RampDepth()), 0.01);
}

namespace
{
// The two fields as two one-component arrays, "plate" the scalars.
vtkSmartPointer<vtkImageData> TwoArrays()
{
  vtkSmartPointer<vtkImageData> image = TwoFields();
  auto* both = vtkFloatArray::SafeDownCast(image->GetPointData()->GetScalars());
  vtkNew<vtkFloatArray> plate;
  vtkNew<vtkFloatArray> floor;
  plate->SetName("plate");
  floor->SetName("floor");
  plate->SetNumberOfTuples(both->GetNumberOfTuples());
  floor->SetNumberOfTuples(both->GetNumberOfTuples());
  for (vtkIdType i = 0; i < both->GetNumberOfTuples(); ++i)
  {
    plate->SetValue(i, both->GetTypedComponent(i, 0));
    floor->SetValue(i, both->GetTypedComponent(i, 1));
  }
  auto arrays = vtkSmartPointer<vtkImageData>::New();
  arrays->SetDimensions(N, N, N);
  arrays->GetPointData()->SetScalars(plate);
  arrays->GetPointData()->AddArray(floor);
  vtkNew<vtkFloatArray> vector;
  vector->SetName("vector");
  vector->SetNumberOfComponents(3);
  vector->SetNumberOfTuples(both->GetNumberOfTuples());
  vector->FillValue(0.0f);
  arrays->GetPointData()->AddArray(vector);
  return arrays;
}
}

TEST(SeveralFields, FurtherArraysAreFieldsAsComponentsAre)
{
  FieldsScene components(TwoFields());
  const std::vector<unsigned char> expected = components.Render();
  const std::vector<float> expectedLight = components.Irradiance();

  vtkSmartPointer<vtkImageData> image = TwoArrays();
  FieldsScene arrays(image);
  FieldsScene reference(TwoFields()); // the optics of two fields, for the property
  arrays.Volume->SetProperty(reference.Property);
  arrays.Mapper->SetFieldMaterialTransferFunction(1, reference.FieldMaterials[1]);
  arrays.Mapper->AddFieldArray("floor");
  EXPECT_EQ(arrays.Mapper->GetNumberOfFieldArrays(), 1);
  EXPECT_STREQ(arrays.Mapper->GetFieldArray(0), "floor");
  mmvtest::ErrorCounter errors(arrays.Mapper);
  const std::vector<unsigned char> pixels = arrays.Render();
  EXPECT_EQ(errors.Errors(), 0) << errors.LastMessage();
  EXPECT_EQ(arrays.Mapper->GetNumberOfFields(), 2);
  EXPECT_TRUE(arrays.Mapper->GetMultiMaterialActive());
  EXPECT_EQ(pixels, expected);
  EXPECT_EQ(arrays.Irradiance(), expectedLight);
  // The input itself is untouched: the combined array is in the ray
  // caster's copy.
  EXPECT_EQ(image->GetPointData()->GetScalars()->GetNumberOfComponents(), 1);

  // A missing array, or one with three components: an error, and the
  // scalars (the plate) are shaded alone.
  for (const char* bad : { "nothing", "vector" })
  {
    errors.Reset();
    arrays.Mapper->RemoveAllFieldArrays();
    arrays.Mapper->AddFieldArray(bad);
    arrays.Render();
    EXPECT_EQ(errors.Errors(), 1) << bad;
    EXPECT_NE(errors.LastMessage().find("field"), std::string::npos) << errors.LastMessage();
    EXPECT_EQ(arrays.Mapper->GetNumberOfFields(), 1) << bad;
    EXPECT_TRUE(arrays.Mapper->GetMultiMaterialActive()) << bad;
  }
  // Back to none: one field, no error.
  errors.Reset();
  arrays.Mapper->RemoveAllFieldArrays();
  arrays.Render();
  EXPECT_EQ(errors.Errors(), 0);
  EXPECT_EQ(arrays.Mapper->GetNumberOfFields(), 1);
}

TEST(SeveralFields, BadFieldCountsAndIndicesAreReported)
{
  // A field index out of [0, 3]: an error, nothing set.
  vtkNew<vtkMultiMaterialVolumeMapper> mapper;
  vtkNew<vtkMaterialTransferFunction> materials;
  mmvtest::ErrorCounter errors(mapper);
  mapper->SetFieldMaterialTransferFunction(4, materials);
  mapper->SetFieldMaterialTransferFunction(-1, materials);
  EXPECT_EQ(errors.Errors(), 2);
  mapper->SetFieldMaterialTransferFunction(3, materials);
  EXPECT_EQ(mapper->GetFieldMaterialTransferFunction(3), materials.Get());
  EXPECT_EQ(errors.Errors(), 2);

  // Dependent components (direct colour) are not fields: VTK's shading,
  // with the reason.
  FieldsScene dependent(TwoFields());
  dependent.Property->IndependentComponentsOff();
  mmvtest::ErrorCounter warnings(dependent.Mapper);
  dependent.Render();
  EXPECT_FALSE(dependent.Mapper->GetMultiMaterialActive());
  EXPECT_NE(warnings.LastMessage().find("independent components"), std::string::npos)
    << warnings.LastMessage();
}

namespace
{
// `array` of `image` on the points of `extent` alone, as an image of its own
// on the same lattice.
vtkSmartPointer<vtkImageData> SubVolume(vtkImageData* image, const char* array, const int extent[6])
{
  vtkDataArray* values = image->GetPointData()->GetArray(array);
  vtkNew<vtkFloatArray> part;
  part->SetName(array);
  auto sub = vtkSmartPointer<vtkImageData>::New();
  sub->SetExtent(const_cast<int*>(extent));
  part->SetNumberOfTuples(sub->GetNumberOfPoints());
  vtkIdType id = 0;
  for (int k = extent[4]; k <= extent[5]; ++k)
  {
    for (int j = extent[2]; j <= extent[3]; ++j)
    {
      for (int i = extent[0]; i <= extent[1]; ++i)
      {
        part->SetValue(id++, values->GetTuple1((static_cast<vtkIdType>(k) * N + j) * N + i));
      }
    }
  }
  sub->GetPointData()->SetScalars(part);
  return sub;
}
}

// Two volumes, the plate's box inside the floor's, merged into one image
// whose fields one ray integrates: the image of the same arrays made on one
// grid, pixel for pixel.
TEST(SeveralFields, OverlappingVolumesMergedAreOneRaysFields)
{
  FieldsScene components(TwoFields());
  const std::vector<unsigned char> expected = components.Render();

  vtkSmartPointer<vtkImageData> arrays = TwoArrays();
  const int plateBox[6] = { 6, 25, 6, 25, 16, 25 };
  const int floorBox[6] = { 0, N - 1, 0, N - 1, 0, N - 1 };
  vtkNew<vtkVolumesToFields> merge;
  merge->AddInputData(SubVolume(arrays, "plate", plateBox));
  merge->AddInputData(SubVolume(arrays, "floor", floorBox));
  merge->Update();
  vtkImageData* merged = merge->GetOutput();
  int dims[3];
  merged->GetDimensions(dims);
  EXPECT_EQ(dims[0] * dims[1] * dims[2], N * N * N);

  FieldsScene one(merged);
  FieldsScene reference(TwoFields()); // the optics of two fields, for the property
  one.Volume->SetProperty(reference.Property);
  one.Mapper->SetFieldMaterialTransferFunction(1, reference.FieldMaterials[1]);
  one.Mapper->AddFieldArray("floor");
  const std::vector<unsigned char> pixels = one.Render();
  EXPECT_EQ(one.Mapper->GetNumberOfFields(), 2);
  EXPECT_EQ(pixels, expected);
}
