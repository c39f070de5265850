/**
 * The benchmark scenes (data, colour/opacity, materials, the light and the
 * start of the camera path) and how every benchmark program shows them: the
 * camera and key light (FrameScene), the volume property (SetUpProperty),
 * the renderer (SetUpRenderer), VTK's shading at our default material
 * (ShadeWithDefaultMaterial) and one offscreen window per mapper (View).
 *
 *  - "synthetic": 64^3 voxels, three objects of three materials: a polished
 *    metal ball (reflective), a strongly scattering translucent blob (s = 15)
 *    and a glossy plastic slab.
 *  - "headsq": Testing/Data/headsq.vti (64 x 64 x 93 MR head), skin
 *    (scattering 8) and bone, the transfer functions of the demo program.
 *  - "ct": the head resampled to 256 x 256 x 128, a CT-sized volume for the
 *    irradiance-update benchmark (mmvIrradianceBenchmark).
 *  - "orbital": 64^3 samples of the hydrogen 3d_z2 orbital density
 *    |psi_320|^2 (fourth root, normalised), three materials by density:
 *    a scattering haze, a diffuse shell and a glossy core.
 */
#ifndef mmvBenchmarkScenes_h
#define mmvBenchmarkScenes_h

#include "mmvTestScenes.h" // MakeVolume, shared with the tests
#include "mmvTestWindow.h" // NewRenderWindow

#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkImageResample.h"
#include "vtkLight.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMultiMaterialParameters.h"
#include "vtkMultiMaterialVolumeMapper.h"
#include "vtkNew.h"
#include "vtkOpenGLGPUVolumeRayCastMapper.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkVolume.h"
#include "vtkVolumeMapper.h"
#include "vtkVolumeProperty.h"
#include "vtkXMLImageDataReader.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

namespace mmvbench
{
/// The items of a comma-separated command-line list ("synthetic,headsq").
inline std::vector<std::string> SplitList(const std::string& text)
{
  std::vector<std::string> items;
  std::stringstream list(text);
  for (std::string item; std::getline(list, item, ',');)
  {
    items.push_back(item);
  }
  return items;
}

/// One volume in its own window, drawn by VTK's GPU ray caster or by ours
/// (`Ours`, the same object as `Mapper`, or nullptr).
struct VolumeWindow
{
  vtkSmartPointer<vtkRenderWindow> Window = mmvtest::NewRenderWindow();
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkVolume> Volume;
  vtkNew<vtkVolumeProperty> Property;
  vtkNew<vtkMaterialTransferFunction> Materials;
  vtkSmartPointer<vtkOpenGLGPUVolumeRayCastMapper> Mapper;
  vtkMultiMaterialVolumeMapper* Ours = nullptr;
};

struct SceneSpec
{
  std::string Name;
  vtkSmartPointer<vtkImageData> Image;
  vtkSmartPointer<vtkColorTransferFunction> Color;
  vtkSmartPointer<vtkPiecewiseFunction> Opacity;
  vtkSmartPointer<vtkMaterialTransferFunction> Materials;
  double UnitDistance = 1.0;
  double Background[3] = { 0.1, 0.1, 0.12 };
  double Background2[3] = { 0.4, 0.42, 0.5 };
  // Camera start: direction from the centre toward the eye, and view-up.
  double ViewDirection[3] = { 0.0, -1.0, 0.35 };
  double ViewUp[3] = { 0.0, 0.0, 1.0 };
  // Direction toward the key light (world space).
  double ToLight[3] = { -0.5, -0.6, 0.8 };
};

// Material node pairs spanning a value band [lo, hi].
inline void AddBand(vtkMaterialTransferFunction* m, double lo, double hi, double ka, double kd,
  double ks, double ke, double ct, double s, double r)
{
  m->AddNode(lo, ka, kd, ks, ke, ct, s, r);
  m->AddNode(hi, ka, kd, ks, ke, ct, s, r);
}

inline SceneSpec MakeSynthetic()
{
  SceneSpec s;
  s.Name = "synthetic";
  // value_i * (soft inside-ness over ~1 voxel), the largest object wins.
  // Values grow with opacity (blob 0.2, slab 0.5, metal 0.85) so the thin
  // shells an object's edge passes through belong to fainter materials.
  auto ramp = [](double distance) { return std::min(std::max(0.5 - distance, 0.0), 1.0); };
  s.Image = mmvtest::MakeVolume(64,
    [&](double x, double y, double z)
    {
      const double metal =
        std::sqrt((x - 20) * (x - 20) + (y - 34) * (y - 34) + (z - 30) * (z - 30)) - 11.0;
      const double blob =
        std::sqrt((x - 44) * (x - 44) + 0.6 * (y - 30) * (y - 30) + (z - 32) * (z - 32)) - 13.0;
      const double slab =
        std::max({ std::abs(x - 32) - 27.0, std::abs(y - 32) - 27.0, std::abs(z - 9) - 4.0 });
      return std::max({ 0.85 * ramp(metal), 0.2 * ramp(blob), 0.5 * ramp(slab) });
    });
  s.Color = vtkSmartPointer<vtkColorTransferFunction>::New();
  s.Color->AddRGBPoint(0.0, 0.95, 0.7, 0.35);
  s.Color->AddRGBPoint(0.3, 0.95, 0.7, 0.35); // scattering blob: amber
  s.Color->AddRGBPoint(0.4, 0.3, 0.5, 0.9);
  s.Color->AddRGBPoint(0.6, 0.3, 0.5, 0.9); // plastic: blue
  s.Color->AddRGBPoint(0.7, 0.85, 0.85, 0.88);
  s.Color->AddRGBPoint(1.0, 0.85, 0.85, 0.88); // metal
  s.Opacity = vtkSmartPointer<vtkPiecewiseFunction>::New();
  s.Opacity->AddPoint(0.0, 0.0);
  s.Opacity->AddPoint(0.1, 0.0);
  s.Opacity->AddPoint(0.15, 0.06);
  s.Opacity->AddPoint(0.27, 0.06);
  s.Opacity->AddPoint(0.32, 0.0);
  s.Opacity->AddPoint(0.4, 0.0);
  s.Opacity->AddPoint(0.45, 0.5);
  s.Opacity->AddPoint(0.56, 0.5);
  s.Opacity->AddPoint(0.6, 0.0);
  s.Opacity->AddPoint(0.7, 0.0);
  s.Opacity->AddPoint(0.75, 0.9);
  s.Opacity->AddPoint(1.0, 0.9);
  s.Materials = vtkSmartPointer<vtkMaterialTransferFunction>::New();
  AddBand(s.Materials, 0.12, 0.3, 0.3, 0.6, 0.1, 10, 0.5, 15.0, 0.0); // scattering
  AddBand(s.Materials, 0.42, 0.58, 0.2, 0.8, 0.3, 30, 1.0, 0.0, 0.0); // plastic
  AddBand(s.Materials, 0.72, 1.0, 0.1, 0.3, 0.9, 120, 1.0, 0.0, 0.6); // metal
  return s;
}

inline SceneSpec MakeHead(const std::string& path)
{
  SceneSpec s;
  s.Name = "headsq";
  vtkNew<vtkXMLImageDataReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  s.Image = reader->GetOutput();
  if (!s.Image || !s.Image->GetPointData()->GetScalars())
  {
    s.Image = nullptr;
    return s;
  }
  double range[2];
  s.Image->GetPointData()->GetScalars()->GetRange(range);
  const double r0 = range[0];
  const double dr = range[1] - range[0];
  s.Color = vtkSmartPointer<vtkColorTransferFunction>::New();
  s.Color->AddRGBPoint(r0, 0.0, 0.0, 0.0);
  s.Color->AddRGBPoint(r0 + 0.15 * dr, 0.90, 0.60, 0.50);
  s.Color->AddRGBPoint(r0 + 0.28 * dr, 0.90, 0.65, 0.55);
  s.Color->AddRGBPoint(r0 + 0.35 * dr, 1.00, 0.98, 0.90);
  s.Color->AddRGBPoint(range[1], 1.00, 1.00, 0.95);
  s.Opacity = vtkSmartPointer<vtkPiecewiseFunction>::New();
  s.Opacity->AddPoint(r0, 0.0);
  s.Opacity->AddPoint(r0 + 0.12 * dr, 0.0);
  s.Opacity->AddPoint(r0 + 0.18 * dr, 0.25);
  s.Opacity->AddPoint(r0 + 0.28 * dr, 0.25);
  s.Opacity->AddPoint(r0 + 0.33 * dr, 0.6);
  s.Opacity->AddPoint(range[1], 0.8);
  s.Materials = vtkSmartPointer<vtkMaterialTransferFunction>::New();
  s.Materials->AddNode(r0 + 0.20 * dr, 0.35, 0.7, 0.3, 15, 0.5, 8, 0); // skin
  s.Materials->AddNode(r0 + 0.35 * dr, 0.2, 0.8, 0.2, 25, 1.0, 1, 0);  // bone
  s.UnitDistance = s.Image->GetSpacing()[0];
  s.ViewDirection[0] = 0.3;
  s.ViewDirection[1] = -1.0;
  s.ViewDirection[2] = 0.25;
  return s;
}

/**
 * "ct": a CT-sized volume, the MR head resampled (trilinear) to 256 x 256 x
 * 128 points over the same bounds, with the head scene's transfer functions
 * and materials (skin s = 8).
 */
inline SceneSpec MakeCTSized(const std::string& headPath)
{
  SceneSpec s = MakeHead(headPath);
  if (!s.Image)
  {
    return s;
  }
  s.Name = "ct";
  int dims[3];
  s.Image->GetDimensions(dims);
  const int target[3] = { 256, 256, 128 };
  vtkNew<vtkImageResample> resample;
  resample->SetInputData(s.Image);
  resample->SetInterpolationModeToLinear();
  for (int a = 0; a < 3; ++a)
  {
    resample->SetAxisMagnificationFactor(a, (target[a] - 1.0) / (dims[a] - 1.0));
  }
  resample->Update();
  s.Image = resample->GetOutput();
  s.UnitDistance = s.Image->GetSpacing()[0];
  return s;
}

inline SceneSpec MakeOrbital()
{
  SceneSpec s;
  s.Name = "orbital";
  // psi_320 ~ r^2 exp(-r/3) (3 cos^2 theta - 1), r in Bohr radii over
  // [-24, 24]^3; the fourth root of the density spreads its range.
  double peak = 0.0;
  auto density = [](double x, double y, double z)
  {
    const double r2 = x * x + y * y + z * z;
    const double psi = (3.0 * z * z - r2) * std::exp(-std::sqrt(r2) / 3.0);
    return psi * psi;
  };
  const double h = 48.0 / 63.0;
  for (int k = 0; k < 64; ++k)
  {
    for (int j = 0; j < 64; ++j)
    {
      for (int i = 0; i < 64; ++i)
      {
        peak = std::max(peak, density(i * h - 24, j * h - 24, k * h - 24));
      }
    }
  }
  s.Image = mmvtest::MakeVolume(64,
    [&](double i, double j, double k)
    { return std::pow(density(i * h - 24, j * h - 24, k * h - 24) / peak, 0.25); });
  s.Color = vtkSmartPointer<vtkColorTransferFunction>::New();
  s.Color->AddRGBPoint(0.0, 0.35, 0.55, 1.0);
  s.Color->AddRGBPoint(0.3, 0.35, 0.55, 1.0); // haze: blue
  s.Color->AddRGBPoint(0.5, 0.4, 0.9, 0.5);
  s.Color->AddRGBPoint(0.65, 0.4, 0.9, 0.5); // shell: green
  s.Color->AddRGBPoint(0.8, 1.0, 0.85, 0.4);
  s.Color->AddRGBPoint(1.0, 1.0, 0.85, 0.4); // core: gold
  s.Opacity = vtkSmartPointer<vtkPiecewiseFunction>::New();
  s.Opacity->AddPoint(0.0, 0.0);
  s.Opacity->AddPoint(0.15, 0.0);
  s.Opacity->AddPoint(0.25, 0.03);
  s.Opacity->AddPoint(0.45, 0.03);
  s.Opacity->AddPoint(0.55, 0.25);
  s.Opacity->AddPoint(0.7, 0.25);
  s.Opacity->AddPoint(0.8, 0.8);
  s.Opacity->AddPoint(1.0, 0.8);
  s.Materials = vtkSmartPointer<vtkMaterialTransferFunction>::New();
  AddBand(s.Materials, 0.15, 0.42, 0.4, 0.5, 0.0, 1, 0.5, 10.0, 0.0); // haze
  AddBand(s.Materials, 0.5, 0.68, 0.2, 0.8, 0.3, 20, 1.0, 1.0, 0.0);  // shell
  AddBand(s.Materials, 0.78, 1.0, 0.15, 0.5, 0.9, 60, 1.0, 0.0, 0.2); // core
  s.ViewDirection[0] = 1.0;
  s.ViewDirection[1] = -0.8;
  s.ViewDirection[2] = 0.3;
  return s;
}

/// A scene by name (synthetic, headsq, orbital, ct); no image if unknown.
inline SceneSpec MakeScene(const std::string& name, const std::string& headPath)
{
  if (name == "synthetic")
  {
    return MakeSynthetic();
  }
  if (name == "headsq")
  {
    return MakeHead(headPath);
  }
  if (name == "orbital")
  {
    return MakeOrbital();
  }
  if (name == "ct")
  {
    return MakeCTSized(headPath);
  }
  return {};
}

/**
 * The benchmark's view of a scene: a perspective camera (30 degrees) on
 * ViewDirection framing the data's bounding sphere, with a fixed clipping
 * range so that every method casts the same rays, and a white directional
 * key light of intensity 1 along ToLight. Returns the camera distance; fills
 * the sphere's radius.
 */
inline double FrameScene(const SceneSpec& scene, vtkCamera* camera, vtkLight* light, double& radius)
{
  double bounds[6];
  scene.Image->GetBounds(bounds);
  const double center[3] = { 0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3]),
    0.5 * (bounds[4] + bounds[5]) };
  radius = 0.5 *
    std::sqrt((bounds[1] - bounds[0]) * (bounds[1] - bounds[0]) +
      (bounds[3] - bounds[2]) * (bounds[3] - bounds[2]) +
      (bounds[5] - bounds[4]) * (bounds[5] - bounds[4]));
  auto unit = [](const double v[3], double out[3])
  {
    const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int i = 0; i < 3; ++i)
    {
      out[i] = v[i] / n;
    }
  };
  double view[3];
  unit(scene.ViewDirection, view);
  const double distance = 0.95 * radius / std::sin(15.0 * M_PI / 180.0);
  camera->SetViewAngle(30.0);
  camera->SetFocalPoint(const_cast<double*>(center));
  camera->SetPosition(
    center[0] + distance * view[0], center[1] + distance * view[1], center[2] + distance * view[2]);
  camera->SetViewUp(const_cast<double*>(scene.ViewUp));
  camera->OrthogonalizeViewUp();
  camera->SetClippingRange(distance - 1.05 * radius, distance + 1.05 * radius);
  double toLight[3];
  unit(scene.ToLight, toLight);
  light->SetLightTypeToSceneLight();
  light->PositionalOff();
  light->SetFocalPoint(const_cast<double*>(center));
  light->SetPosition(center[0] + toLight[0], center[1] + toLight[1], center[2] + toLight[2]);
  light->SetColor(1.0, 1.0, 1.0);
  light->SetIntensity(1.0);
  return distance;
}

/// The scene's colour, opacity and unit distance, trilinear: the volume
/// property every method renders with.
inline void SetUpProperty(const SceneSpec& scene, vtkVolumeProperty* property)
{
  property->SetColor(scene.Color);
  property->SetScalarOpacity(scene.Opacity);
  property->SetScalarOpacityUnitDistance(scene.UnitDistance);
  property->SetInterpolationTypeToLinear();
}

/// VTK's own shading with the mmv default material: VTK has one material
/// per volume, so its methods are compared at our defaults.
inline void ShadeWithDefaultMaterial(vtkVolumeProperty* property)
{
  property->ShadeOn();
  property->SetAmbient(mmv::MaterialParameterTable[mmv::Ambient].Default);
  property->SetDiffuse(mmv::MaterialParameterTable[mmv::Diffuse].Default);
  property->SetSpecular(mmv::MaterialParameterTable[mmv::Specular].Default);
  property->SetSpecularPower(mmv::MaterialParameterTable[mmv::Shininess].Default);
}

/// The scene's background (its gradient unless `gradient` is false), only
/// `light`, and `camera`: every method and the references see the same.
inline void SetUpRenderer(const SceneSpec& scene, vtkRenderer* renderer, vtkCamera* camera,
  vtkLight* light, bool gradient = true)
{
  renderer->SetBackground(const_cast<double*>(scene.Background));
  if (gradient)
  {
    renderer->SetBackground2(const_cast<double*>(scene.Background2));
    renderer->GradientBackgroundOn();
  }
  renderer->AutomaticLightCreationOff();
  renderer->AddLight(light);
  renderer->SetActiveCamera(camera);
}

/**
 * One offscreen window showing the scene through one mapper: size x size,
 * no multisampling (a method's cost and image are its own), the renderer of
 * SetUpRenderer and the property of SetUpProperty. Sample distances are the
 * caller's.
 */
struct View
{
  vtkSmartPointer<vtkRenderWindow> RenderWindow = mmvtest::NewRenderWindow();
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkVolume> Volume;
  vtkNew<vtkVolumeProperty> Property;

  void SetUp(const SceneSpec& scene, vtkCamera* camera, vtkLight* light, int size,
    vtkVolumeMapper* mapper, bool gradient = true)
  {
    this->RenderWindow->SetOffScreenRendering(1);
    this->RenderWindow->SetSize(size, size);
    this->RenderWindow->SetMultiSamples(0);
    this->RenderWindow->AddRenderer(this->Renderer);
    SetUpRenderer(scene, this->Renderer, camera, light, gradient);
    SetUpProperty(scene, this->Property);
    mapper->SetInputData(scene.Image);
    this->Volume->SetMapper(mapper);
    this->Volume->SetProperty(this->Property);
    this->Renderer->AddVolume(this->Volume);
  }
};

} // namespace mmvbench

#endif
