// Shadows between several volumes of one renderer
// (Rendering/vtkMultiMaterialSceneShadows.h): a plate volume above a floor
// volume, each on its own grid, against the same scene resampled into one
// volume; the plate moved by a user matrix; hidden, removed, empty,
// overlapping volumes and volumes of other scalar types.
#include "mmvTestScenes.h"
#include "mmvTestUtilities.h"

#include "vtkMaterialTransferFunction.h"
#include "vtkMatrix4x4.h"
#include "vtkMultiMaterialVolumeMapper.h"
#include "vtkTransform.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnsignedShortArray.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <iostream>
#include <memory>

namespace
{
using Field = std::function<double(double, double, double)>;

constexpr int Size = 128;
const double SceneBounds[6] = { 0.0, 32.0, 0.0, 32.0, 0.0, 20.0 };

/// 0 at a and d, 1 from b to c, linear in between: with a..d on the grid
/// points, trilinear interpolation reproduces it exactly on any grid
/// holding them.
double Trapezoid(double x, double a, double b, double c, double d)
{
  if (x <= a || x >= d)
  {
    return 0.0;
  }
  return x < b ? (x - a) / (b - a) : (x > c ? (d - x) / (d - c) : 1.0);
}

/// The floor: a slab 6 units thick (ramps of 2 included) over the whole
/// scene.
double Floor(double x, double y, double z)
{
  return Trapezoid(x, 0.0, 2.0, 30.0, 32.0) * Trapezoid(y, 0.0, 2.0, 30.0, 32.0) *
    Trapezoid(z, 0.0, 2.0, 4.0, 6.0);
}

/// The plate: 16 x 16 x 8 units (ramps of 2 included), 5 above the floor.
double Plate(double x, double y, double z)
{
  return Trapezoid(x, 8.0, 10.0, 22.0, 24.0) * Trapezoid(y, 8.0, 10.0, 22.0, 24.0) *
    Trapezoid(z, 11.0, 13.0, 17.0, 19.0);
}

/// `f` sampled on a grid of `dims` points from `origin` by `spacing`.
vtkSmartPointer<vtkImageData> Sample(
  const int dims[3], const double origin[3], double spacing, const Field& f)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(dims[0], dims[1], dims[2]);
  image->SetOrigin(origin[0], origin[1], origin[2]);
  image->SetSpacing(spacing, spacing, spacing);
  vtkNew<vtkFloatArray> values;
  values->SetName("values");
  values->SetNumberOfTuples(image->GetNumberOfPoints());
  vtkIdType id = 0;
  for (int k = 0; k < dims[2]; ++k)
  {
    for (int j = 0; j < dims[1]; ++j)
    {
      for (int i = 0; i < dims[0]; ++i)
      {
        values->SetValue(id++,
          static_cast<float>(
            f(origin[0] + i * spacing, origin[1] + j * spacing, origin[2] + k * spacing)));
      }
    }
  }
  image->GetPointData()->SetScalars(values);
  return image;
}

vtkSmartPointer<vtkImageData> FloorImage()
{
  const int dims[3] = { 33, 33, 7 };
  const double origin[3] = { 0.0, 0.0, 0.0 };
  return Sample(dims, origin, 1.0, Floor);
}

/// The plate on its own, finer grid.
vtkSmartPointer<vtkImageData> PlateImage()
{
  const int dims[3] = { 33, 33, 21 };
  const double origin[3] = { 8.0, 8.0, 10.0 };
  return Sample(dims, origin, 0.5, Plate);
}

/// `f` on one grid over the whole scene, as fine as the plate's.
vtkSmartPointer<vtkImageData> WholeSceneImage(const Field& f)
{
  const int dims[3] = { 65, 65, 41 };
  const double origin[3] = { 0.0, 0.0, 0.0 };
  return Sample(dims, origin, 0.5, f);
}

/// The plate's user matrix of the moved-plate case: turned 25 degrees
/// about its vertical axis and shifted.
vtkSmartPointer<vtkMatrix4x4> MovedPlateMatrix()
{
  vtkNew<vtkTransform> transform;
  transform->PostMultiply();
  transform->Translate(-16.0, -16.0, 0.0);
  transform->RotateZ(25.0);
  transform->Translate(16.0 + 2.0, 16.0 - 1.5, 1.0);
  auto matrix = vtkSmartPointer<vtkMatrix4x4>::New();
  matrix->DeepCopy(transform->GetMatrix());
  return matrix;
}

/// One volume of the scene: its own property (the same transfer functions
/// for all) and mapper.
struct SceneVolume
{
  vtkNew<vtkVolume> Volume;
  vtkNew<vtkVolumeProperty> Property;
  vtkNew<vtkColorTransferFunction> Color;
  vtkNew<vtkPiecewiseFunction> Opacity;
  vtkNew<vtkMaterialTransferFunction> Materials;
  vtkNew<vtkMultiMaterialVolumeMapper> Mapper;

  /// Data values [low, high] play the part of [0, 1].
  SceneVolume(vtkImageData* image, double low = 0.0, double high = 1.0)
  {
    const double w = high - low;
    this->Color->AddRGBPoint(low, 1.0, 0.9, 0.8);
    this->Color->AddRGBPoint(high, 1.0, 0.9, 0.8);
    this->Opacity->AddPoint(low, 0.0);
    this->Opacity->AddPoint(low + 0.5 * w, 0.18);
    this->Opacity->AddPoint(high, 0.18);
    this->Property->SetColor(this->Color);
    this->Property->SetScalarOpacity(this->Opacity);
    this->Property->SetScalarOpacityUnitDistance(1.0);
    this->Property->SetInterpolationTypeToLinear();
    this->Materials->AddNode(high, 1.0, 0.0, 0.0, 10.0, 1.0, 0.0, 0.0);
    this->Mapper->SetInputData(image);
    this->Mapper->SetMaterialTransferFunction(this->Materials);
    this->Mapper->SetIrradianceScale(1.0);
    this->Mapper->AutoAdjustSampleDistancesOff();
    this->Mapper->SetSampleDistance(0.5);
    this->Volume->SetMapper(this->Mapper);
    this->Volume->SetProperty(this->Property);
  }
};

/// A window with one slanted directional light and a parallel camera
/// above the scene; volumes are drawn in the order they are added (the
/// floor first: seen from above, the plate composites over it).
struct ShadowScene
{
  vtkSmartPointer<vtkRenderWindow> Window = mmvtest::NewRenderWindow();
  vtkNew<vtkRenderer> Renderer;
  std::vector<std::unique_ptr<SceneVolume>> Volumes;

  ShadowScene()
  {
    this->Window->SetOffScreenRendering(1);
    this->Window->SetSize(Size, Size);
    this->Window->SetMultiSamples(0);
    this->Window->AddRenderer(this->Renderer);
    this->Renderer->SetBackground(0.0, 0.0, 0.0);
    this->Renderer->AutomaticLightCreationOff();
    vtkCamera* camera = this->Renderer->GetActiveCamera();
    camera->ParallelProjectionOn();
    camera->SetFocalPoint(16.0, 16.0, 9.0);
    camera->SetPosition(16.0, 16.0, 200.0);
    camera->SetViewUp(0.0, 1.0, 0.0);
    camera->SetParallelScale(1.1 * 16.0);
    this->Renderer->ResetCameraClippingRange(SceneBounds);
    vtkNew<vtkLight> light;
    light->SetLightTypeToSceneLight();
    light->PositionalOff();
    light->SetPosition(60.0, 40.0, 100.0);
    light->SetFocalPoint(16.0, 16.0, 0.0);
    this->Renderer->AddLight(light);
  }

  SceneVolume* Add(vtkImageData* image, double low = 0.0, double high = 1.0)
  {
    this->Volumes.push_back(std::make_unique<SceneVolume>(image, low, high));
    this->Renderer->AddVolume(this->Volumes.back()->Volume);
    return this->Volumes.back().get();
  }

  std::vector<unsigned char> Render()
  {
    this->Renderer->ResetCameraClippingRange(-50.0, 80.0, -50.0, 80.0, -20.0, 40.0);
    this->Window->Render();
    int* size = this->Window->GetSize();
    vtkNew<vtkUnsignedCharArray> rgb;
    this->Window->GetPixelData(0, 0, size[0] - 1, size[1] - 1, 0, rgb);
    return std::vector<unsigned char>(
      rgb->GetPointer(0), rgb->GetPointer(0) + rgb->GetNumberOfValues());
  }
};

/// The same scene as one volume, resampled from `f`.
std::vector<unsigned char> RenderAsOneVolume(const Field& f)
{
  ShadowScene one;
  one.Add(WholeSceneImage(f));
  return one.Render();
}

/// The floor alone.
std::vector<unsigned char> RenderFloorAlone()
{
  ShadowScene alone;
  alone.Add(FloorImage());
  return alone.Render();
}

/// Lit pixels (any channel above 0), to check that images show something.
int LitPixels(const std::vector<unsigned char>& rgb)
{
  int lit = 0;
  for (size_t i = 0; i + 2 < rgb.size(); i += 3)
  {
    lit += (rgb[i] | rgb[i + 1] | rgb[i + 2]) != 0 ? 1 : 0;
  }
  return lit;
}
}

TEST(SceneShadows, PlateShadowsTheFloorAsInOneVolume)
{
  ShadowScene two;
  SceneVolume* floor = two.Add(FloorImage());
  SceneVolume* plate = two.Add(PlateImage());
  const std::vector<unsigned char> image = two.Render();
  EXPECT_TRUE(floor->Mapper->GetMultiMaterialActive());
  EXPECT_TRUE(plate->Mapper->GetMultiMaterialActive());
  EXPECT_EQ(floor->Mapper->GetNumberOfSceneOccluders(), 1);
  EXPECT_EQ(plate->Mapper->GetNumberOfSceneOccluders(), 1);
  const std::vector<unsigned char> reference = RenderAsOneVolume(
    [](double x, double y, double z) { return std::max(Floor(x, y, z), Plate(x, y, z)); });
  const double psnr = mmvtest::PSNR(image, reference);
  std::cout << "two volumes against one: PSNR " << psnr << " dB" << std::endl;
  EXPECT_GT(LitPixels(image), Size * Size / 2);
  EXPECT_GE(psnr, 35.0);
}

TEST(SceneShadows, MovedPlateShadowsAsItsResampledCopy)
{
  vtkSmartPointer<vtkMatrix4x4> matrix = MovedPlateMatrix();
  ShadowScene two;
  two.Add(FloorImage());
  SceneVolume* plate = two.Add(PlateImage());
  plate->Volume->SetUserMatrix(matrix);
  const std::vector<unsigned char> image = two.Render();
  vtkNew<vtkMatrix4x4> inverse;
  vtkMatrix4x4::Invert(matrix, inverse);
  const std::vector<unsigned char> reference = RenderAsOneVolume(
    [&inverse](double x, double y, double z)
    {
      const double world[4] = { x, y, z, 1.0 };
      double p[4];
      inverse->MultiplyPoint(world, p);
      return std::max(Floor(x, y, z), Plate(p[0], p[1], p[2]));
    });
  const double psnr = mmvtest::PSNR(image, reference);
  std::cout << "moved plate against its resampled copy: PSNR " << psnr << " dB" << std::endl;
  EXPECT_GE(psnr, 35.0);
}

TEST(SceneShadows, HiddenVolumeCastsNoShadow)
{
  const std::vector<unsigned char> alone = RenderFloorAlone();
  ShadowScene two;
  SceneVolume* floor = two.Add(FloorImage());
  SceneVolume* plate = two.Add(PlateImage());
  const std::vector<unsigned char> shadowed = two.Render();
  plate->Volume->VisibilityOff();
  const std::vector<unsigned char> hidden = two.Render();
  EXPECT_EQ(floor->Mapper->GetNumberOfSceneOccluders(), 0);
  EXPECT_GE(mmvtest::PSNR(hidden, alone), 60.0);
  EXPECT_LT(mmvtest::PSNR(shadowed, alone), 40.0); // the shadow was there
  plate->Volume->VisibilityOn();
  EXPECT_GE(mmvtest::PSNR(two.Render(), shadowed), 60.0);
}

TEST(SceneShadows, RemovedVolumeTakesItsShadowAlong)
{
  const std::vector<unsigned char> alone = RenderFloorAlone();
  ShadowScene two;
  SceneVolume* floor = two.Add(FloorImage());
  SceneVolume* plate = two.Add(PlateImage());
  two.Render();
  const int updates = floor->Mapper->GetIrradianceUpdateCount();
  two.Renderer->RemoveVolume(plate->Volume);
  EXPECT_GE(mmvtest::PSNR(two.Render(), alone), 60.0);
  EXPECT_EQ(floor->Mapper->GetIrradianceUpdateCount(), updates + 1);
  EXPECT_EQ(floor->Mapper->GetNumberOfSceneOccluders(), 0);
}

TEST(SceneShadows, OnlyChangesRelight)
{
  ShadowScene two;
  SceneVolume* floor = two.Add(FloorImage());
  SceneVolume* plate = two.Add(PlateImage());
  const std::vector<unsigned char> first = two.Render();
  const int updates = floor->Mapper->GetIrradianceUpdateCount();
  const int transmittances = floor->Mapper->GetSceneShadowUpdateCount();
  const int plateUpdates = plate->Mapper->GetIrradianceUpdateCount();
  // A still frame: nothing recomputed.
  two.Render();
  EXPECT_EQ(floor->Mapper->GetIrradianceUpdateCount(), updates);
  EXPECT_EQ(floor->Mapper->GetSceneShadowUpdateCount(), transmittances);
  // Moving the plate relights the floor (and the plate, which the floor
  // shadows from below no more than before, but whose placement changed).
  plate->Volume->SetPosition(-6.0, 0.0, 0.0);
  const std::vector<unsigned char> moved = two.Render();
  EXPECT_EQ(floor->Mapper->GetIrradianceUpdateCount(), updates + 1);
  EXPECT_EQ(floor->Mapper->GetSceneShadowUpdateCount(), transmittances + 1);
  EXPECT_EQ(plate->Mapper->GetIrradianceUpdateCount(), plateUpdates + 1);
  EXPECT_LT(mmvtest::PSNR(moved, first), 40.0);
  // An opacity edit of the plate relights the floor too.
  plate->Opacity->AddPoint(1.0, 0.1);
  two.Render();
  EXPECT_EQ(floor->Mapper->GetIrradianceUpdateCount(), updates + 2);
  // Back where it was: the first image again.
  plate->Opacity->AddPoint(1.0, 0.18);
  plate->Volume->SetPosition(0.0, 0.0, 0.0);
  EXPECT_GE(mmvtest::PSNR(two.Render(), first), 60.0);
}

TEST(SceneShadows, OtherScalarTypesAndRangesShadowAlike)
{
  ShadowScene floats;
  floats.Add(FloorImage());
  floats.Add(PlateImage());
  const std::vector<unsigned char> reference = floats.Render();
  // The floor as unsigned char over [0, 200], the plate as unsigned short
  // over [0, 1000], each with its transfer functions over its range.
  auto convert = [](vtkImageData* image, vtkDataArray* out, double high)
  {
    vtkDataArray* in = image->GetPointData()->GetScalars();
    out->SetNumberOfTuples(in->GetNumberOfTuples());
    for (vtkIdType i = 0; i < in->GetNumberOfTuples(); ++i)
    {
      out->SetTuple1(i, std::round(in->GetTuple1(i) * high));
    }
    auto copy = vtkSmartPointer<vtkImageData>::New();
    copy->CopyStructure(image);
    copy->GetPointData()->SetScalars(out);
    return copy;
  };
  vtkNew<vtkUnsignedCharArray> bytes;
  vtkNew<vtkUnsignedShortArray> shorts;
  ShadowScene mixed;
  SceneVolume* floor = mixed.Add(convert(FloorImage(), bytes, 200.0), 0.0, 200.0);
  SceneVolume* plate = mixed.Add(convert(PlateImage(), shorts, 1000.0), 0.0, 1000.0);
  const std::vector<unsigned char> image = mixed.Render();
  EXPECT_EQ(floor->Mapper->GetNumberOfSceneOccluders(), 1);
  EXPECT_EQ(plate->Mapper->GetNumberOfSceneOccluders(), 1);
  const double psnr = mmvtest::PSNR(image, reference);
  std::cout << "unsigned char floor, unsigned short plate against floats: PSNR " << psnr << " dB"
            << std::endl;
  EXPECT_GE(psnr, 35.0);
}

TEST(SceneShadows, EmptyVolumeChangesNothing)
{
  ShadowScene two;
  two.Add(FloorImage());
  two.Add(PlateImage());
  const std::vector<unsigned char> reference = two.Render();
  // A third volume without points: VTK's mapper reports it and draws
  // nothing; it casts no shadow.
  vtkNew<vtkImageData> empty;
  ShadowScene three;
  SceneVolume* floor = three.Add(FloorImage());
  three.Add(PlateImage());
  SceneVolume* nothing = three.Add(empty);
  mmvtest::ErrorCounter errors(nothing->Mapper);
  const std::vector<unsigned char> image = three.Render();
  EXPECT_EQ(floor->Mapper->GetNumberOfSceneOccluders(), 1);
  EXPECT_GE(mmvtest::PSNR(image, reference), 60.0);
}

TEST(SceneShadows, VolumeInsideAnotherRenders)
{
  // The plate inside a box of thin fog that holds it: each dims the other's
  // lights (the fog counts the plate's extinction on its way up and the
  // plate the fog's above it); the two are blended, not composited in one
  // ray.
  const int dims[3] = { 17, 17, 10 };
  const double origin[3] = { 0.0, 0.0, 0.0 };
  ShadowScene nested;
  SceneVolume* fog =
    nested.Add(Sample(dims, origin, 2.0, [](double, double, double) { return 0.55; }));
  SceneVolume* plate = nested.Add(PlateImage());
  const std::vector<unsigned char> image = nested.Render();
  EXPECT_EQ(fog->Mapper->GetNumberOfSceneOccluders(), 1);
  EXPECT_EQ(plate->Mapper->GetNumberOfSceneOccluders(), 1);
  EXPECT_TRUE(fog->Mapper->GetMultiMaterialActive());
  EXPECT_TRUE(plate->Mapper->GetMultiMaterialActive());
  EXPECT_GT(LitPixels(image), Size * Size / 2);
}

TEST(SceneShadows, VolumeAloneComputesNoTransmittance)
{
  ShadowScene alone;
  SceneVolume* floor = alone.Add(FloorImage());
  alone.Render();
  EXPECT_EQ(floor->Mapper->GetNumberOfSceneOccluders(), 0);
  EXPECT_EQ(floor->Mapper->GetSceneShadowUpdateCount(), 0);
}
