// The data ParaView users volume-render, beyond one-component point scalars:
// cell scalars (lit on the grid of the cell centres) and vectors (their
// magnitude or one component, vtkMultiMaterialVolumeMapper::VectorMode).
// Each is shaded with materials (MultiMaterialActive) and renders as its
// one-component point-data equivalent does; the CPU filter lights cell
// scalars as the GPU does.
#include "mmvPlateScene.h"
#include "mmvTestScenes.h"
#include "mmvTestUtilities.h"

#include "vtkCellData.h"
#include "vtkFloatArray.h"
#include "vtkIrradianceVolumeFilter.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMultiMaterialVolumeMapper.h"
#include "vtkVectorScalarsCache.h"
#include "vtkVolumeInputScalars.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <string>

namespace
{
constexpr int Cells = 32; // per axis; the cell image has 33 points per axis

// A plate above a floor, by cell (or point) index in [0, Cells): the plate
// shadows the floor under a light from above, so misplaced irradiance shows.
// Neither touches the volume's sides: cell data reach half a cell further out
// than their point equivalent, and that rim must stay empty.
float PlateAndFloor(int i, int j, int k)
{
  const bool inside = i >= 3 && i <= 28 && j >= 3 && j <= 28;
  if (inside && k >= 3 && k <= 6)
  {
    return 1.0f;
  }
  if (k >= 19 && k <= 22 && i >= 9 && i <= 22 && j >= 9 && j <= 22)
  {
    return 1.0f;
  }
  return 0.0f;
}

vtkSmartPointer<vtkFloatArray> Values(
  const char* name, int components, const std::function<void(int, int, int, float*)>& f)
{
  auto values = vtkSmartPointer<vtkFloatArray>::New();
  values->SetName(name);
  values->SetNumberOfComponents(components);
  values->SetNumberOfTuples(static_cast<vtkIdType>(Cells) * Cells * Cells);
  vtkIdType id = 0;
  for (int k = 0; k < Cells; ++k)
  {
    for (int j = 0; j < Cells; ++j)
    {
      for (int i = 0; i < Cells; ++i)
      {
        f(i, j, k, values->GetPointer(id * components));
        ++id;
      }
    }
  }
  return values;
}

// The field as cell data on 33^3 points (origin 0, spacing 1)...
vtkSmartPointer<vtkImageData> AsCellData(vtkFloatArray* values)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(Cells + 1, Cells + 1, Cells + 1);
  image->GetCellData()->AddArray(values);
  image->GetCellData()->SetActiveScalars(values->GetName());
  return image;
}

// ... and as point data on the cell centres: 32^3 points from 0.5.
vtkSmartPointer<vtkImageData> AsPointDataOnCentres(vtkFloatArray* values)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(Cells, Cells, Cells);
  image->SetOrigin(0.5, 0.5, 0.5);
  image->GetPointData()->AddArray(values);
  image->GetPointData()->SetActiveScalars(values->GetName());
  return image;
}

/// The plate and floor of mmvPlateScene.h, framed on the cells' bounds so
/// that cell data and their point data on the cell centres look alike.
struct PlateScene : mmvtest::PlateScene
{
  explicit PlateScene(vtkImageData* image)
    : mmvtest::PlateScene(image, 0.2, CellBounds)
  {
  }
  static constexpr double CellBounds[6] = { 0, Cells, 0, Cells, 0, Cells };
};

using mmvtest::PSNR;

int Brightest(const std::vector<unsigned char>& pixels)
{
  int brightest = 0;
  for (unsigned char p : pixels)
  {
    brightest = std::max(brightest, int(p));
  }
  return brightest;
}

vtkSmartPointer<vtkFloatArray> PlateValues(const char* name = "values")
{
  return Values(name, 1, [](int i, int j, int k, float* v) { *v = PlateAndFloor(i, j, k); });
}
} // namespace

TEST(DataInputs, CellCentreImageSitsHalfASpacingIn)
{
  auto values = PlateValues();
  auto cells = AsCellData(values);
  cells->SetSpacing(2.0, 1.0, 0.5);
  cells->SetOrigin(-1.0, 4.0, 10.0);
  vtkSmartPointer<vtkImageData> centres = mmv::MakeCellCentreImage(cells, values);
  ASSERT_NE(centres, nullptr);
  int dims[3];
  centres->GetDimensions(dims);
  EXPECT_EQ(dims[0], Cells);
  EXPECT_EQ(dims[2], Cells);
  EXPECT_DOUBLE_EQ(centres->GetOrigin()[0], 0.0); // -1 + 2 / 2
  EXPECT_DOUBLE_EQ(centres->GetOrigin()[1], 4.5);
  EXPECT_DOUBLE_EQ(centres->GetOrigin()[2], 10.25);
  EXPECT_EQ(centres->GetPointData()->GetScalars(), values.Get());
  // No cells along an axis, or too few values: nothing to light.
  auto flat = vtkSmartPointer<vtkImageData>::New();
  flat->SetDimensions(4, 4, 1);
  EXPECT_EQ(mmv::MakeCellCentreImage(flat, values), nullptr);
  auto small = vtkSmartPointer<vtkImageData>::New();
  small->SetDimensions(Cells + 2, Cells + 1, Cells + 1);
  EXPECT_EQ(mmv::MakeCellCentreImage(small, values), nullptr);
}

// Threshold 40 dB: both renders shade the same field on the same grid with
// the same irradiance (checked equal below); what differs is where VTK's rays
// start (the cell image's box is half a cell larger each side), which moves
// the sample positions along each ray by a fraction of the 0.5 step. The
// same scene with the field moved by one cell scores far lower.
TEST(DataInputs, CellDataRenderAsTheirPointDataOnTheCellCentres)
{
  auto values = PlateValues();
  PlateScene cellScene(AsCellData(values));
  cellScene.Mapper->SetScalarModeToUseCellData();
  mmvtest::ErrorCounter cellErrors(cellScene.Mapper);
  const auto cellImage = cellScene.Render();
  PlateScene pointScene(AsPointDataOnCentres(values));
  const auto pointImage = pointScene.Render();
  EXPECT_TRUE(cellScene.Mapper->GetMultiMaterialActive());
  EXPECT_TRUE(pointScene.Mapper->GetMultiMaterialActive());
  EXPECT_EQ(cellErrors.Warnings() + cellErrors.Errors(), 0) << cellErrors.LastMessage();
  const double psnr = PSNR(cellImage, pointImage);

  // A field moved by one cell along x: what a misplaced grid would look like.
  auto moved = Values("values", 1,
    [](int i, int j, int k, float* v) { *v = i > 0 ? PlateAndFloor(i - 1, j, k) : 0.0f; });
  PlateScene movedScene(AsPointDataOnCentres(moved));
  const double movedPsnr = PSNR(movedScene.Render(), pointImage);
  std::printf("cell data vs point data on the cell centres: PSNR %.1f dB (moved one cell: "
              "%.1f dB); brightest %d\n",
    psnr, movedPsnr, Brightest(cellImage));
  EXPECT_GE(psnr, 40.0);
  EXPECT_LT(movedPsnr, 35.0);
  EXPECT_GT(Brightest(cellImage), 100); // lit, not an empty frame

  // The irradiance is estimated on the same grid: equal voxel for voxel.
  const int* cellGrid = cellScene.Mapper->GetIrradianceDimensions();
  const int* pointGrid = pointScene.Mapper->GetIrradianceDimensions();
  for (int a = 0; a < 3; ++a)
  {
    EXPECT_EQ(cellGrid[a], Cells);
    EXPECT_EQ(pointGrid[a], Cells);
  }
  std::vector<float> fromCells, fromPoints;
  ASSERT_TRUE(cellScene.Mapper->ReadIrradiance(cellScene.Window, 0, fromCells));
  ASSERT_TRUE(pointScene.Mapper->ReadIrradiance(pointScene.Window, 0, fromPoints));
  ASSERT_EQ(fromCells.size(), fromPoints.size());
  double worst = 0.0;
  for (size_t v = 0; v < fromCells.size(); ++v)
  {
    worst = std::max(worst, std::abs(double(fromCells[v]) - fromPoints[v]));
  }
  std::printf("irradiance, cell vs point data: max |difference| %.3g\n", worst);
  EXPECT_LE(worst, 1e-3);
}

TEST(DataInputs, CpuFilterLightsCellDataAsTheGpu)
{
  auto values = PlateValues();
  auto image = AsCellData(values);
  PlateScene scene(image);
  scene.Mapper->SetScalarModeToUseCellData();
  scene.Mapper->MultipleScatteringOff();
  scene.Render();
  ASSERT_TRUE(scene.Mapper->GetMultiMaterialActive());
  std::vector<float> gpu;
  ASSERT_TRUE(scene.Mapper->ReadIrradiance(scene.Window, 0, gpu));

  vtkNew<vtkIrradianceVolumeFilter> cpu;
  cpu->SetInputData(image);
  cpu->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_CELLS, "values");
  cpu->SetScalarOpacity(scene.Opacity);
  cpu->SetScalarOpacityUnitDistance(1.0);
  cpu->SetMaterialTransferFunction(scene.Materials);
  cpu->SetIrradianceScale(1.0);
  cpu->MultipleScatteringOff();
  cpu->SetLights(scene.Renderer->GetLights());
  cpu->Update();
  vtkImageData* output = cpu->GetOutput();
  EXPECT_DOUBLE_EQ(output->GetOrigin()[0], 0.5); // the cell centres' grid
  auto* reference = vtkFloatArray::SafeDownCast(output->GetPointData()->GetArray("Irradiance_0"));
  ASSERT_NE(reference, nullptr);
  ASSERT_EQ(static_cast<vtkIdType>(gpu.size()), reference->GetNumberOfTuples());
  double worst = 0.0;
  for (vtkIdType v = 0; v < reference->GetNumberOfTuples(); ++v)
  {
    worst = std::max(worst, std::abs(double(gpu[v]) - reference->GetValue(v)));
  }
  // The floor's top cell under the plate's centre lies in its shadow; one
  // at the floor's corner is lit.
  const auto at = [&](int i, int j, int k)
  { return reference->GetValue((static_cast<vtkIdType>(k) * Cells + j) * Cells + i); };
  std::printf("cell data irradiance, GPU vs CPU: max |difference| %.3g; floor under the plate "
              "%.3f, in the open %.3f\n",
    worst, at(15, 15, 6), at(4, 27, 6));
  EXPECT_LE(worst, 0.01);
  EXPECT_LT(at(15, 15, 6), 0.2 * at(4, 27, 6));
}

namespace
{
// A smooth vector field whose magnitude and components are all non-trivial,
// on the plate scene's grid as point data.
void Vector(int i, int j, int k, float* v)
{
  const float s = PlateAndFloor(i, j, k);
  v[0] = 0.6f * s;
  v[1] = -0.8f * s * (0.5f + 0.5f * i / Cells);
  v[2] = 0.3f * s * j / Cells;
}

struct VectorRender
{
  std::vector<unsigned char> Pixels;
  bool Active = false;
  int Errors = 0;
  int Warnings = 0;
  std::string Message;
};

VectorRender RenderArray(vtkImageData* image, const char* name, bool cells,
  const std::function<void(vtkMultiMaterialVolumeMapper*)>& setup = nullptr)
{
  PlateScene scene(image);
  // Magnitudes reach 1: the same ramp shows every field.
  mmvtest::ErrorCounter counter(scene.Mapper);
  cells ? scene.Mapper->SetScalarModeToUseCellFieldData()
        : scene.Mapper->SetScalarModeToUsePointFieldData();
  scene.Mapper->SelectScalarArray(name);
  if (setup)
  {
    setup(scene.Mapper);
  }
  VectorRender result;
  result.Pixels = scene.Render();
  result.Active = scene.Mapper->GetMultiMaterialActive();
  result.Errors = counter.Errors();
  result.Warnings = counter.Warnings();
  result.Message = counter.LastMessage();
  return result;
}

// The vector, its magnitude and its components as separate arrays.
vtkSmartPointer<vtkImageData> VectorImage(bool cells)
{
  auto vectors = Values("velocity", 3, Vector);
  auto magnitude = Values("speed", 1,
    [](int i, int j, int k, float* m)
    {
      float v[3];
      Vector(i, j, k, v);
      *m = static_cast<float>(
        std::sqrt(double(v[0]) * v[0] + double(v[1]) * v[1] + double(v[2]) * v[2]));
    });
  auto second = Values("velocity_Y", 1,
    [](int i, int j, int k, float* c)
    {
      float v[3];
      Vector(i, j, k, v);
      *c = -v[1]; // positive: the opacity ramp starts at 0
    });
  auto image = cells ? AsCellData(vectors) : AsPointDataOnCentres(vectors);
  vtkDataSetAttributes* attributes = cells
    ? static_cast<vtkDataSetAttributes*>(image->GetCellData())
    : static_cast<vtkDataSetAttributes*>(image->GetPointData());
  attributes->AddArray(magnitude);
  attributes->AddArray(second);
  return image;
}
} // namespace

TEST(DataInputs, VectorMagnitudeRendersAsAPrecomputedMagnitude)
{
  for (const bool cells : { false, true })
  {
    auto image = VectorImage(cells);
    const VectorRender reference = RenderArray(image, "speed", cells);
    const VectorRender magnitude = RenderArray(image, "velocity", cells,
      [](vtkMultiMaterialVolumeMapper* m) { m->SetVectorModeToMagnitude(); });
    const double psnr = PSNR(magnitude.Pixels, reference.Pixels);
    std::printf("%s data: |velocity| vs speed PSNR %.1f dB; brightest %d\n",
      cells ? "cell" : "point", psnr, Brightest(magnitude.Pixels));
    EXPECT_TRUE(reference.Active);
    EXPECT_TRUE(magnitude.Active) << magnitude.Message;
    EXPECT_EQ(magnitude.Errors + magnitude.Warnings, 0) << magnitude.Message;
    EXPECT_GE(psnr, 50.0);
    EXPECT_GT(Brightest(magnitude.Pixels), 100);
  }
}

TEST(DataInputs, VectorComponentRendersAsThatComponent)
{
  auto image = VectorImage(false);
  const VectorRender reference = RenderArray(image, "velocity_Y", false);
  // Component 1 is negative where there is material, and the opacity ramp
  // starts at 0: negate it in the vector itself, so both fields are the same.
  auto* vectors = vtkFloatArray::SafeDownCast(image->GetPointData()->GetArray("velocity"));
  for (vtkIdType t = 0; t < vectors->GetNumberOfTuples(); ++t)
  {
    vectors->SetComponent(t, 1, -vectors->GetComponent(t, 1));
  }
  vectors->Modified();
  const VectorRender component = RenderArray(image, "velocity", false,
    [](vtkMultiMaterialVolumeMapper* m)
    {
      m->SetVectorModeToComponent();
      m->SetVectorComponent(1);
    });
  const VectorRender otherComponent = RenderArray(image, "velocity", false,
    [](vtkMultiMaterialVolumeMapper* m)
    {
      m->SetVectorModeToComponent();
      m->SetVectorComponent(2);
    });
  const double psnr = PSNR(component.Pixels, reference.Pixels);
  const double otherPsnr = PSNR(otherComponent.Pixels, reference.Pixels);
  std::printf("velocity[1] vs velocity_Y PSNR %.1f dB (velocity[2]: %.1f dB)\n", psnr, otherPsnr);
  EXPECT_TRUE(component.Active) << component.Message;
  EXPECT_GE(psnr, 50.0);
  EXPECT_LT(otherPsnr, 30.0); // a different component is a different image
}

TEST(DataInputs, BadVectorComponentIsAnErrorAndDrawsNothing)
{
  auto image = VectorImage(false);
  const VectorRender bad = RenderArray(image, "velocity", false,
    [](vtkMultiMaterialVolumeMapper* m)
    {
      m->SetVectorModeToComponent();
      m->SetVectorComponent(3);
    });
  EXPECT_FALSE(bad.Active);
  EXPECT_EQ(bad.Errors, 1);
  EXPECT_NE(bad.Message.find("has 3 component(s)"), std::string::npos) << bad.Message;
  EXPECT_EQ(Brightest(bad.Pixels), 0);

  vtkNew<vtkMultiMaterialVolumeMapper> mapper;
  mmvtest::ErrorCounter counter(mapper);
  mapper->SetVectorComponent(2);
  mapper->SetVectorComponent(-1);
  EXPECT_EQ(counter.Errors(), 1);
  EXPECT_EQ(mapper->GetVectorComponent(), 2);
  mapper->SetVectorMode(7); // clamped, as vtkSmartVolumeMapper's
  EXPECT_EQ(mapper->GetVectorMode(), mmv::VectorModeComponent);
}

TEST(DataInputs, VectorModeOffGivesTheVectorBackToVTK)
{
  // One mapper: magnitude first, then VectorMode off: the ray caster's copy
  // must hold the 3-component array again, whose independent components are
  // three fields.
  auto image = VectorImage(false);
  PlateScene scene(image);
  mmvtest::ErrorCounter counter(scene.Mapper);
  scene.Mapper->SetScalarModeToUsePointFieldData();
  scene.Mapper->SelectScalarArray("velocity");
  scene.Mapper->SetVectorModeToMagnitude();
  scene.Render();
  EXPECT_TRUE(scene.Mapper->GetMultiMaterialActive());
  EXPECT_EQ(scene.Mapper->GetNumberOfFields(), 1);
  scene.Mapper->SetVectorModeToDisabled();
  scene.Render();
  EXPECT_TRUE(scene.Mapper->GetMultiMaterialActive());
  EXPECT_EQ(scene.Mapper->GetNumberOfFields(), 3);
  EXPECT_EQ(counter.Errors(), 0) << counter.LastMessage();
  vtkDataArray* drawn = scene.Mapper->GetTransformedInput(0)->GetPointData()->GetArray("velocity");
  ASSERT_NE(drawn, nullptr);
  EXPECT_EQ(drawn->GetNumberOfComponents(), 3);
}

TEST(DataInputs, OneCellThickSlabIsLit)
{
  // Cell data on 2 points along z: a slab one cell thick, which VTK draws
  // with its thickness (point data there would be a zero-thickness slice).
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(Cells + 1, Cells + 1, 2);
  image->SetSpacing(1.0, 1.0, 4.0);
  auto values = vtkSmartPointer<vtkFloatArray>::New();
  values->SetName("values");
  values->SetNumberOfTuples(static_cast<vtkIdType>(Cells) * Cells);
  for (vtkIdType c = 0; c < values->GetNumberOfTuples(); ++c)
  {
    const int i = static_cast<int>(c % Cells), j = static_cast<int>(c / Cells);
    values->SetValue(c, i >= 4 && i < 28 && j >= 4 && j < 28 ? 1.0f : 0.0f);
  }
  image->GetCellData()->SetScalars(values);
  PlateScene scene(image);
  mmvtest::ErrorCounter counter(scene.Mapper);
  scene.Mapper->SetScalarModeToUseCellData();
  const auto pixels = scene.Render();
  std::printf("one-cell slab: active %d, brightest %d, %s\n",
    scene.Mapper->GetMultiMaterialActive(), Brightest(pixels), counter.LastMessage().c_str());
  EXPECT_TRUE(scene.Mapper->GetMultiMaterialActive());
  EXPECT_EQ(counter.Errors(), 0) << counter.LastMessage();
  EXPECT_GT(Brightest(pixels), 60);
}
// VTK 9.2's own ray caster crashes (in vtkVolumeInputHelper::
// RefreshTransferFunction) when the scalars it draws on one input go from one
// component to three; the mapper starts its GPU resources afresh then.
TEST(DataInputs, SwitchingFromAScalarToAVectorArrayDoesNotCrash)
{
  auto image = VectorImage(false);
  PlateScene scene(image);
  scene.Mapper->SetScalarModeToUsePointFieldData();
  scene.Mapper->SelectScalarArray("speed");
  scene.Render();
  EXPECT_TRUE(scene.Mapper->GetMultiMaterialActive());
  scene.Mapper->SelectScalarArray("velocity");
  mmvtest::ErrorCounter counter(scene.Mapper);
  const auto pixels = scene.Render();
  // Three independent components: three fields.
  EXPECT_TRUE(scene.Mapper->GetMultiMaterialActive());
  EXPECT_EQ(scene.Mapper->GetNumberOfFields(), 3);
  EXPECT_EQ(counter.Errors(), 0) << counter.LastMessage();
  // As a fresh mapper draws it.
  PlateScene fresh(image);
  fresh.Mapper->SetScalarModeToUsePointFieldData();
  fresh.Mapper->SelectScalarArray("velocity");
  const double psnr = PSNR(pixels, fresh.Render());
  std::printf("vector after a scalar vs a fresh mapper: PSNR %.1f dB, brightest %d\n", psnr,
    Brightest(pixels));
  EXPECT_GE(psnr, 50.0);
  scene.Mapper->SetVectorModeToMagnitude();
  scene.Render();
  EXPECT_TRUE(scene.Mapper->GetMultiMaterialActive());
}

namespace
{
// One kind of input of a time series: how a step is made and how the mapper
// is told to read it.
struct SeriesKind
{
  const char* Name;
  bool Cells;
  int Components;
  std::function<void(vtkMultiMaterialVolumeMapper*)> Setup;
};

// Step `step` of a series: the plate and floor moved `step` cells along x,
// as a scalar or as the vector of Vector(), each step its own data object.
vtkSmartPointer<vtkImageData> SeriesStep(const SeriesKind& kind, int step)
{
  auto values = Values("values", kind.Components,
    [&kind, step](int i, int j, int k, float* v)
    {
      if (i < step)
      {
        std::fill(v, v + kind.Components, 0.0f);
      }
      else if (kind.Components == 1)
      {
        *v = PlateAndFloor(i - step, j, k);
      }
      else
      {
        Vector(i - step, j, k, v);
      }
    });
  return kind.Cells ? AsCellData(values) : AsPointDataOnCentres(values);
}
} // namespace

// ParaView's animation cache hands the mapper each step's data object again
// on the second loop: vectors (by magnitude or a component) and cell data
// must find their kept irradiance and gradient volume as point scalars do,
// so the reduced array of a vector has to stay the same array.
TEST(DataInputs, KeptStepsOfVectorsAndCellDataComeBackWithoutAnUpdate)
{
  const SeriesKind kinds[] = {
    { "point vector, magnitude", false, 3,
      [](vtkMultiMaterialVolumeMapper* m) { m->SetVectorModeToMagnitude(); } },
    { "point vector, component 0", false, 3,
      [](vtkMultiMaterialVolumeMapper* m)
      {
        m->SetVectorModeToComponent();
        m->SetVectorComponent(0);
      } },
    { "cell scalars", true, 1, nullptr },
    { "cell vector, magnitude", true, 3,
      [](vtkMultiMaterialVolumeMapper* m) { m->SetVectorModeToMagnitude(); } },
  };
  constexpr int Steps = 3;
  for (const SeriesKind& kind : kinds)
  {
    SCOPED_TRACE(kind.Name);
    std::vector<vtkSmartPointer<vtkImageData>> steps;
    for (int s = 0; s < Steps; ++s)
    {
      steps.push_back(SeriesStep(kind, 2 * s));
    }
    const auto configure = [&kind](vtkMultiMaterialVolumeMapper* m)
    {
      kind.Cells ? m->SetScalarModeToUseCellFieldData() : m->SetScalarModeToUsePointFieldData();
      m->SelectScalarArray("values");
      if (kind.Setup)
      {
        kind.Setup(m);
      }
    };
    PlateScene scene(steps[0]);
    configure(scene.Mapper);
    scene.Mapper->SetIrradianceCacheMB(64.0);
    mmvtest::ErrorCounter counter(scene.Mapper);
    std::vector<std::vector<unsigned char>> first;
    for (int s = 0; s < Steps; ++s)
    {
      const int updates = scene.Mapper->GetIrradianceUpdateCount();
      scene.Mapper->SetInputData(steps[s]);
      first.push_back(scene.Render());
      EXPECT_TRUE(scene.Mapper->GetMultiMaterialActive()) << "step " << s;
      EXPECT_EQ(scene.Mapper->GetIrradianceUpdateCount(), updates + 1) << "first loop, step " << s;
      EXPECT_GT(Brightest(first.back()), 100) << "step " << s;
    }
    EXPECT_EQ(scene.Mapper->GetIrradianceCacheHitCount(), 0);
    // The steps differ visibly, so a wrong step's irradiance would show.
    EXPECT_LT(PSNR(first[0], first[1]), 35.0);

    // The second loop: copies of the irradiance and the gradient volume,
    // the very same images, and each equal to a fresh mapper's render.
    const int updates = scene.Mapper->GetIrradianceUpdateCount();
    const int gradients = scene.Mapper->GetGradientUploadCount();
    for (int s = 0; s < Steps; ++s)
    {
      scene.Mapper->SetInputData(steps[s]);
      const auto again = scene.Render();
      EXPECT_EQ(scene.Mapper->GetIrradianceCacheHitCount(), s + 1) << "second loop, step " << s;
      const double kept = PSNR(again, first[s]);
      PlateScene fresh(steps[s]);
      configure(fresh.Mapper);
      const double vsFresh = PSNR(again, fresh.Render());
      std::printf("%s, step %d again: PSNR %.1f dB vs the first loop, %.1f dB vs a fresh "
                  "render\n",
        kind.Name, s, kept, vsFresh);
      EXPECT_EQ(kept, INFINITY) << "second loop, step " << s;
      EXPECT_GE(vsFresh, 40.0) << "second loop, step " << s;
    }
    EXPECT_EQ(scene.Mapper->GetIrradianceUpdateCount(), updates);
    EXPECT_EQ(scene.Mapper->GetGradientUploadCount(), gradients);
    EXPECT_EQ(counter.Errors() + counter.Warnings(), 0) << counter.LastMessage();
  }
}

TEST(DataInputs, VectorScalarsCacheGivesTheSameArrayForTheSameVector)
{
  auto a = Values("a", 3, Vector);
  auto b = Values("b", 3, Vector);
  vtkVectorScalarsCache cache;
  cache.SetKeepAll(true);
  vtkDataArray* magA = cache.Get(a, mmv::VectorModeMagnitude, 0, nullptr);
  vtkDataArray* magB = cache.Get(b, mmv::VectorModeMagnitude, 0, nullptr);
  ASSERT_NE(magA, nullptr);
  ASSERT_NE(magB, nullptr);
  EXPECT_NE(magA, magB);
  EXPECT_EQ(cache.Get(a, mmv::VectorModeMagnitude, 0, nullptr), magA);
  EXPECT_EQ(cache.Get(b, mmv::VectorModeMagnitude, 0, nullptr), magB);
  EXPECT_EQ(cache.GetNumberOfReductions(), 2);
  // 32^3 floats each.
  EXPECT_EQ(cache.GetBytes(), 2u * 4u * Cells * Cells * Cells);

  // New values in the vector: a new array of them, the old one dropped.
  a->SetComponent(0, 0, 3.0f);
  a->SetComponent(0, 1, 4.0f);
  a->Modified();
  vtkDataArray* again = cache.Get(a, mmv::VectorModeMagnitude, 0, nullptr);
  ASSERT_NE(again, nullptr);
  EXPECT_FLOAT_EQ(static_cast<float>(again->GetComponent(0, 0)), 5.0f);
  EXPECT_EQ(cache.GetNumberOfReductions(), 3);
  EXPECT_EQ(cache.GetNumberOfEntries(), 2);

  // A deleted vector's array goes at the next look-up.
  b = nullptr;
  cache.Get(a, mmv::VectorModeComponent, 2, nullptr);
  EXPECT_EQ(cache.GetNumberOfEntries(), 2); // a's magnitude and component 2

  // Only the latest without KeepAll; a bad component is an error.
  cache.SetKeepAll(false);
  cache.Get(a, mmv::VectorModeMagnitude, 0, nullptr);
  EXPECT_EQ(cache.GetNumberOfEntries(), 1);
  std::string error;
  EXPECT_EQ(cache.Get(a, mmv::VectorModeComponent, 3, &error), nullptr);
  EXPECT_NE(error.find("has 3 component(s)"), std::string::npos) << error;
  EXPECT_EQ(cache.Get(nullptr, mmv::VectorModeMagnitude, 0, &error), nullptr);
}
