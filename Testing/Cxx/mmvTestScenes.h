/**
 * Small scenes shared by the rendering tests: an offscreen window with a
 * parallel camera looking down -z at a volume, and readers of its pixels.
 */
#ifndef mmvTestScenes_h
#define mmvTestScenes_h

#include "mmvTestWindow.h"
#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

namespace mmvtest
{

/// PSNR of two 8-bit images in dB: infinity when identical, -1 when their
/// sizes differ or they are empty.
inline double PSNR(const std::vector<unsigned char>& a, const std::vector<unsigned char>& b)
{
  if (a.size() != b.size() || a.empty())
  {
    return -1.0;
  }
  double sum = 0.0;
  for (size_t i = 0; i < a.size(); ++i)
  {
    const double d = static_cast<double>(a[i]) - static_cast<double>(b[i]);
    sum += d * d;
  }
  const double mse = sum / a.size();
  return mse == 0.0 ? std::numeric_limits<double>::infinity()
                    : 10.0 * std::log10(255.0 * 255.0 / mse);
}

/// dims^3 points, spacing 1, origin 0, values from f(i, j, k).
inline vtkSmartPointer<vtkImageData> MakeVolume(
  int dims, const std::function<float(int, int, int)>& f)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(dims, dims, dims);
  vtkNew<vtkFloatArray> values;
  values->SetName("values");
  values->SetNumberOfTuples(static_cast<vtkIdType>(dims) * dims * dims);
  vtkIdType id = 0;
  for (int k = 0; k < dims; ++k)
  {
    for (int j = 0; j < dims; ++j)
    {
      for (int i = 0; i < dims; ++i)
      {
        values->SetValue(id++, f(i, j, k));
      }
    }
  }
  image->GetPointData()->SetScalars(values);
  return image;
}

/// `window` off screen at size x size with `renderer`: black background, no
/// automatic light, no multisampling.
inline void SetUpWindow(vtkRenderWindow* window, vtkRenderer* renderer, int size)
{
  window->SetOffScreenRendering(1);
  window->SetSize(size, size);
  window->SetMultiSamples(0);
  window->AddRenderer(renderer);
  renderer->SetBackground(0.0, 0.0, 0.0);
  renderer->AutomaticLightCreationOff();
}

/// `mapper` (a vtkMultiMaterialVolumeMapper; a template, so that tests of the
/// CPU side need not link the mapper) on `image` with `materials`, drawn by
/// `volume`: the irradiance on the data's own grid (scale 1), a sample every
/// half voxel.
template <typename Mapper>
void SetUpFullGridMapper(
  Mapper* mapper, vtkImageData* image, vtkMaterialTransferFunction* materials, vtkVolume* volume)
{
  mapper->SetInputData(image);
  mapper->SetMaterialTransferFunction(materials);
  mapper->SetIrradianceScale(1.0);
  mapper->AutoAdjustSampleDistancesOff();
  mapper->SetSampleDistance(0.5);
  volume->SetMapper(mapper);
}

/// A window of size x size, black background, parallel camera on +z looking
/// at the centre of `bounds` and framing it.
struct Scene
{
  vtkSmartPointer<vtkRenderWindow> Window = mmvtest::NewRenderWindow();
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkVolume> Volume;
  vtkNew<vtkVolumeProperty> Property;
  vtkNew<vtkColorTransferFunction> Color;
  vtkNew<vtkPiecewiseFunction> Opacity;

  explicit Scene(int size = 64)
  {
    SetUpWindow(this->Window, this->Renderer, size);
    this->Property->SetColor(this->Color);
    this->Property->SetScalarOpacity(this->Opacity);
    this->Property->SetInterpolationTypeToLinear();
    this->Volume->SetProperty(this->Property);
    this->Renderer->AddVolume(this->Volume);
  }

  void FrameBounds(const double bounds[6], double margin = 1.5)
  {
    vtkCamera* camera = this->Renderer->GetActiveCamera();
    const double c[3] = { 0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3]),
      0.5 * (bounds[4] + bounds[5]) };
    camera->ParallelProjectionOn();
    camera->SetFocalPoint(c);
    camera->SetPosition(c[0], c[1], c[2] + 10.0 * (bounds[5] - bounds[4] + 1.0));
    camera->SetViewUp(0.0, 1.0, 0.0);
    camera->SetParallelScale(margin * 0.5 * (bounds[3] - bounds[2]));
    this->Renderer->ResetCameraClippingRange(bounds);
  }

  /// A white directional light of intensity 1 shining from `from` toward `to`.
  vtkLight* AddDirectionalLight(const double from[3], const double to[3])
  {
    vtkNew<vtkLight> light;
    light->SetLightTypeToSceneLight();
    light->PositionalOff();
    light->SetPosition(from[0], from[1], from[2]);
    light->SetFocalPoint(to[0], to[1], to[2]);
    light->SetColor(1.0, 1.0, 1.0);
    light->SetIntensity(1.0);
    this->Renderer->AddLight(light);
    return light;
  }

  /// RGB of the pixel (x, y) of the last render, in [0, 1].
  std::vector<double> Pixel(int x, int y)
  {
    vtkNew<vtkUnsignedCharArray> rgb;
    this->Window->GetPixelData(x, y, x, y, /*front*/ 0, rgb);
    return { rgb->GetValue(0) / 255.0, rgb->GetValue(1) / 255.0, rgb->GetValue(2) / 255.0 };
  }

  /// All pixels of the last render as RGB bytes, bottom row first.
  std::vector<unsigned char> Pixels()
  {
    int* size = this->Window->GetSize();
    vtkNew<vtkUnsignedCharArray> rgb;
    this->Window->GetPixelData(0, 0, size[0] - 1, size[1] - 1, 0, rgb);
    return std::vector<unsigned char>(
      rgb->GetPointer(0), rgb->GetPointer(0) + rgb->GetNumberOfValues());
  }
};

/// A ball of dims^3 points (spacing 1) whose value falls from 1 at the
/// centre to 0 at the faces' centres: an orange shell of opacity
/// `shellOpacity` around a blue core of 0.5, set on `scene`. Returns the
/// volume.
inline vtkSmartPointer<vtkImageData> ShellAndCoreBall(Scene& scene, int dims, double shellOpacity)
{
  const double c = 0.5 * (dims - 1);
  auto image = MakeVolume(dims,
    [c](int i, int j, int k)
    {
      const double r = std::sqrt((i - c) * (i - c) + (j - c) * (j - c) + (k - c) * (k - c));
      return static_cast<float>(std::max(0.0, 1.0 - r / c));
    });
  scene.Color->AddRGBPoint(0.0, 1.0, 0.6, 0.3);
  scene.Color->AddRGBPoint(0.4, 1.0, 0.6, 0.3);
  scene.Color->AddRGBPoint(0.6, 0.7, 0.8, 1.0);
  scene.Color->AddRGBPoint(1.0, 0.7, 0.8, 1.0);
  scene.Opacity->AddPoint(0.0, 0.0);
  scene.Opacity->AddPoint(0.2, 0.0);
  scene.Opacity->AddPoint(0.3, shellOpacity);
  scene.Opacity->AddPoint(0.5, shellOpacity);
  scene.Opacity->AddPoint(0.6, 0.5);
  scene.Opacity->AddPoint(1.0, 0.5);
  return image;
}

/// A lit two-material ball of dims^3 points: a translucent diffuse shell
/// around a glossy core (ShellAndCoreBall), the unit distance scaled so that
/// it looks alike at any dims, its materials set on `materials`.
inline vtkSmartPointer<vtkImageData> TwoMaterialBall(
  Scene& scene, vtkMaterialTransferFunction* materials, int dims)
{
  auto image = ShellAndCoreBall(scene, dims, 0.05);
  scene.Property->SetScalarOpacityUnitDistance(32.0 / (dims - 1));
  materials->AddNode(0.3, 0.2, 0.7, 0.2, 20.0, 1.0, 0.0, 0.0);
  materials->AddNode(0.6, 0.1, 0.6, 0.8, 40.0, 1.0, 0.0, 0.0);
  return image;
}

} // namespace mmvtest

#endif
