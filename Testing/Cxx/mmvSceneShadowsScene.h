/**
 * The plate-above-floor scene of the shadows between volumes
 * (TestSceneShadows, mmvSceneShadowsBenchmark): a floor volume and a plate
 * volume on its own, finer grid, each with its own mapper, under one slanted
 * directional light and a parallel camera from above, and the same scene
 * resampled into one volume. The fields are products of trapezoids whose
 * corners lie on every grid's points, so trilinear interpolation reproduces
 * them on each grid exactly; the extinction is low enough (0.2 per unit)
 * that each volume looks alike on either grid.
 */
#ifndef mmvSceneShadowsScene_h
#define mmvSceneShadowsScene_h

#include "mmvTestScenes.h"

#include "vtkLightCollection.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMatrix4x4.h"
#include "vtkMultiMaterialVolumeMapper.h"
#include "vtkTransform.h"
#include "vtkUnsignedCharArray.h"

#include <functional>
#include <memory>
#include <vector>

namespace mmvtest
{
namespace sceneshadows
{
using Field = std::function<double(double, double, double)>;

constexpr int Size = 128; // the tests' images
const double SceneBounds[6] = { 0.0, 32.0, 0.0, 32.0, 0.0, 20.0 };

/// 0 at a and d, 1 from b to c, linear in between: with a..d on the grid
/// points, trilinear interpolation reproduces it exactly on any grid
/// holding them.
inline double Trapezoid(double x, double a, double b, double c, double d)
{
  if (x <= a || x >= d)
  {
    return 0.0;
  }
  return x < b ? (x - a) / (b - a) : (x > c ? (d - x) / (d - c) : 1.0);
}

/// The floor: a slab 6 units thick (ramps of 2 included) over the whole
/// scene.
inline double Floor(double x, double y, double z)
{
  return Trapezoid(x, 0.0, 2.0, 30.0, 32.0) * Trapezoid(y, 0.0, 2.0, 30.0, 32.0) *
    Trapezoid(z, 0.0, 2.0, 4.0, 6.0);
}

/// The plate: 16 x 16 x 8 units (ramps of 2 included), 5 above the floor.
inline double Plate(double x, double y, double z)
{
  return Trapezoid(x, 8.0, 10.0, 22.0, 24.0) * Trapezoid(y, 8.0, 10.0, 22.0, 24.0) *
    Trapezoid(z, 11.0, 13.0, 17.0, 19.0);
}

/// `f` sampled on a grid of `dims` points from `origin` by `spacing`.
inline vtkSmartPointer<vtkImageData> Sample(
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

inline vtkSmartPointer<vtkImageData> FloorImage()
{
  const int dims[3] = { 33, 33, 7 };
  const double origin[3] = { 0.0, 0.0, 0.0 };
  return Sample(dims, origin, 1.0, Floor);
}

/// The plate on its own, finer grid.
inline vtkSmartPointer<vtkImageData> PlateImage()
{
  const int dims[3] = { 33, 33, 21 };
  const double origin[3] = { 8.0, 8.0, 10.0 };
  return Sample(dims, origin, 0.5, Plate);
}

/// `f` on one grid over the whole scene, as fine as the plate's.
inline vtkSmartPointer<vtkImageData> WholeSceneImage(const Field& f)
{
  const int dims[3] = { 65, 65, 41 };
  const double origin[3] = { 0.0, 0.0, 0.0 };
  return Sample(dims, origin, 0.5, f);
}

/// The plate's user matrix of the moved-plate case: turned 25 degrees
/// about its vertical axis and shifted.
inline vtkSmartPointer<vtkMatrix4x4> MovedPlateMatrix()
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
    SetUpFullGridMapper(this->Mapper.Get(), image, this->Materials, this->Volume);
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

  explicit ShadowScene(int size = Size)
  {
    SetUpWindow(this->Window, this->Renderer, size);
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

  /// The light positional at `position`, aimed at the floor's centre: a
  /// point light, or with a cone of `coneAngle` degrees (<= 90) a spot light.
  void MakeLightPositional(const double position[3], double coneAngle = 180.0)
  {
    vtkLight* light = vtkLight::SafeDownCast(this->Renderer->GetLights()->GetItemAsObject(0));
    light->PositionalOn();
    light->SetPosition(position[0], position[1], position[2]);
    light->SetFocalPoint(16.0, 16.0, 0.0);
    light->SetConeAngle(coneAngle);
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

/// The same scene as one volume, resampled from `f`; with `lightPosition`
/// a positional light there (MakeLightPositional).
inline std::vector<unsigned char> RenderAsOneVolume(
  const Field& f, const double* lightPosition = nullptr, double coneAngle = 180.0)
{
  ShadowScene one;
  one.Add(WholeSceneImage(f));
  if (lightPosition)
  {
    one.MakeLightPositional(lightPosition, coneAngle);
  }
  return one.Render();
}

/// The floor alone.
inline std::vector<unsigned char> RenderFloorAlone()
{
  ShadowScene alone;
  alone.Add(FloorImage());
  return alone.Render();
}

} // namespace sceneshadows
} // namespace mmvtest

#endif
