// Renders an image volume (the sample MR head by default) with a skin + bone
// transfer function and two lights, and writes a PNG.
//
//   MultiMaterialVolumeDemo input.vti output.png [azimuth elevation]
//
// vtkMultiMaterialVolumeMapper shades skin and bone with their own materials,
// shadows from both lights and multiple scattering in the skin.
#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMultiMaterialVolumeMapper.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include "vtkWindowToImageFilter.h"
#include "vtkXMLImageDataReader.h"

#include <chrono>
#include <cstdlib>
#include <iostream>

int main(int argc, char* argv[])
{
  if (argc < 3)
  {
    std::cerr << "usage: " << argv[0] << " input.vti output.png [azimuth elevation]\n";
    return 2;
  }

  vtkNew<vtkXMLImageDataReader> reader;
  reader->SetFileName(argv[1]);
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  if (!image || !image->GetPointData()->GetScalars())
  {
    std::cerr << "could not read point scalars from " << argv[1] << "\n";
    return 1;
  }
  double range[2];
  image->GetPointData()->GetScalars()->GetRange(range);

  // Skin around 25 % of the range, bone above 35 % (MR head: 0..3926).
  const double r0 = range[0];
  const double dr = range[1] - range[0];
  vtkNew<vtkColorTransferFunction> color;
  color->AddRGBPoint(r0, 0.0, 0.0, 0.0);
  color->AddRGBPoint(r0 + 0.15 * dr, 0.90, 0.60, 0.50);
  color->AddRGBPoint(r0 + 0.28 * dr, 0.90, 0.65, 0.55);
  color->AddRGBPoint(r0 + 0.35 * dr, 1.00, 0.98, 0.90);
  color->AddRGBPoint(range[1], 1.00, 1.00, 0.95);
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(r0, 0.0);
  opacity->AddPoint(r0 + 0.12 * dr, 0.0);
  opacity->AddPoint(r0 + 0.18 * dr, 0.25);
  opacity->AddPoint(r0 + 0.28 * dr, 0.25);
  opacity->AddPoint(r0 + 0.33 * dr, 0.6);
  opacity->AddPoint(range[1], 0.8);

  vtkNew<vtkMaterialTransferFunction> materials;
  materials->AddNode(r0 + 0.20 * dr, 0.35, 0.7, 0.3, 15, 0.5, 8, 0); // skin
  materials->AddNode(r0 + 0.35 * dr, 0.2, 0.8, 0.2, 25, 1.0, 1, 0);  // bone

  vtkNew<vtkVolumeProperty> property;
  property->SetColor(color);
  property->SetScalarOpacity(opacity);
  property->SetInterpolationTypeToLinear();
  property->SetScalarOpacityUnitDistance(image->GetSpacing()[0]);

  vtkNew<vtkMultiMaterialVolumeMapper> mapper;
  mapper->SetInputData(image);
  mapper->SetMaterialTransferFunction(materials);
  // The head's skin is a thin shell sampled every 3.2 mm in x and y: a
  // smoothed shading normal keeps its voxel rows from showing as stripes
  // (docs/stability.md, "Stripes on thin shells").
  mapper->SetGradientSmoothing(1.0);
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  volume->SetProperty(property);

  vtkNew<vtkRenderer> renderer;
  renderer->AddVolume(volume);
  renderer->SetBackground(0.08, 0.09, 0.12);
  renderer->SetBackground2(0.35, 0.38, 0.45);
  renderer->GradientBackgroundOn();
  renderer->ResetCamera();
  vtkCamera* camera = renderer->GetActiveCamera();
  const double azimuth = argc > 3 ? std::atof(argv[3]) : 20.0;
  const double elevation = argc > 4 ? std::atof(argv[4]) : 80.0;
  camera->Elevation(elevation);
  camera->OrthogonalizeViewUp();
  camera->Azimuth(azimuth);
  renderer->ResetCamera();
  camera->Zoom(1.3);

  // A warm key light above left of the camera (it follows the camera) and a
  // cool spot light from the side of the head.
  double center[3];
  image->GetCenter(center);
  vtkNew<vtkLight> key;
  key->SetLightTypeToCameraLight();
  key->SetPosition(-0.6, 0.8, 1.0);
  key->SetFocalPoint(0.0, 0.0, 0.0);
  key->SetColor(1.0, 0.95, 0.85);
  vtkNew<vtkLight> spot;
  spot->SetLightTypeToSceneLight();
  spot->PositionalOn();
  spot->SetConeAngle(25.0);
  spot->SetPosition(center[0] + 300, center[1] - 150, center[2] + 50);
  spot->SetFocalPoint(center);
  spot->SetColor(0.7, 0.8, 1.0);
  spot->SetIntensity(0.8);
  renderer->AddLight(key);
  renderer->AddLight(spot);

  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetSize(640, 640);
  window->AddRenderer(renderer);
  const auto start = std::chrono::steady_clock::now();
  window->Render();
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  int dims[3];
  mapper->GetIrradianceDimensions(dims);
  std::cout << "first frame " << seconds << " s: irradiance volume " << dims[0] << "x" << dims[1]
            << "x" << dims[2] << " for " << mapper->GetNumberOfShadedLights() << " lights in "
            << mapper->GetLastIrradianceSeconds() << " s\n";

  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->ReadFrontBufferOff();
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(argv[2]);
  writer->SetInputConnection(grab->GetOutputPort());
  writer->Write();
  return 0;
}
