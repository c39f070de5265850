// Memory and time against the volume's size (docs/scaling.md, "Large volumes on one machine"):
// a generated N^3 float volume (nested shells and a plate, so that shadows
// and materials have work to do) rendered by the multi-material mapper at
// the default irradiance budget, one scene light, a 512 x 512 window.
//
//   mmvVolumeSizeBenchmark --size N [--reps R] [--csv FILE]
//
// Prints and appends to FILE (CSV, header when new): the size, the data's
// bytes, the irradiance grid, our GPU textures' bytes, the process's peak
// resident memory after the first frame, the first frame (uploads, gradient,
// pre-filter, irradiance, ray cast), the irradiance update after a light
// move (glFinish-timed), a still frame whose light moved (update + ray cast)
// and a frame with nothing changed (ray cast only), medians over R.
// Not a test: it asserts nothing.
#include "mmvTestWindow.h"

#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMultiMaterialVolumeMapper.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSMPTools.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

namespace
{
double Seconds(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double PeakResidentMB()
{
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0; // kB on Linux
}

double Median(std::vector<double> v)
{
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

vtkSmartPointer<vtkImageData> MakeVolume(int n)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(n, n, n);
  image->SetSpacing(256.0 / (n - 1), 256.0 / (n - 1), 256.0 / (n - 1));
  vtkNew<vtkFloatArray> values;
  values->SetNumberOfTuples(static_cast<vtkIdType>(n) * n * n);
  float* out = values->GetPointer(0);
  vtkSMPTools::For(0, n,
    [&](vtkIdType k0, vtkIdType k1)
    {
      for (vtkIdType k = k0; k < k1; ++k)
      {
        for (int j = 0; j < n; ++j)
        {
          for (int i = 0; i < n; ++i)
          {
            // Unit cube coordinates: shells around the centre, a plate above.
            const double x = double(i) / (n - 1) - 0.5;
            const double y = double(j) / (n - 1) - 0.5;
            const double z = double(k) / (n - 1) - 0.5;
            const double r = std::sqrt(x * x + y * y + z * z);
            double v = 0.0;
            v += (std::abs(r - 0.3) < 0.03) ? 60.0 : 0.0;
            v += (r < 0.15) ? 100.0 : 0.0;
            v += (y > 0.38 && y < 0.43 && std::abs(x) < 0.3 && std::abs(z) < 0.3) ? 100.0 : 0.0;
            out[i + static_cast<vtkIdType>(n) * (j + static_cast<vtkIdType>(n) * k)] =
              static_cast<float>(v);
          }
        }
      }
    });
  values->SetName("density");
  image->GetPointData()->SetScalars(values);
  return image;
}
} // namespace

int main(int argc, char* argv[])
{
  int n = 128;
  int reps = 3;
  std::string csv;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    if (arg == "--size" && i + 1 < argc)
    {
      n = std::atoi(argv[++i]);
    }
    else if (arg == "--reps" && i + 1 < argc)
    {
      reps = std::atoi(argv[++i]);
    }
    else if (arg == "--csv" && i + 1 < argc)
    {
      csv = argv[++i];
    }
  }
  const double baseMB = PeakResidentMB();
  auto image = MakeVolume(n);

  vtkSmartPointer<vtkRenderWindow> window = mmvtest::NewRenderWindow();
  window->SetOffScreenRendering(1);
  window->SetSize(512, 512);
  window->SetMultiSamples(0);
  vtkNew<vtkRenderer> renderer;
  renderer->AutomaticLightCreationOff();
  window->AddRenderer(renderer);
  vtkNew<vtkColorTransferFunction> color;
  color->AddRGBPoint(0.0, 0.9, 0.8, 0.7);
  color->AddRGBPoint(160.0, 0.9, 0.8, 0.7);
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0.0, 0.0);
  opacity->AddPoint(50.0, 0.0);
  opacity->AddPoint(60.0, 0.05);
  opacity->AddPoint(100.0, 0.6);
  vtkNew<vtkVolumeProperty> property;
  property->SetColor(color);
  property->SetScalarOpacity(opacity);
  property->SetInterpolationTypeToLinear();
  vtkNew<vtkMaterialTransferFunction> materials;
  materials->AddNode(60.0, 0.2, 0.7, 0.3, 20.0, 1.0, 0.5, 0.0);
  materials->AddNode(100.0, 0.2, 0.8, 0.2, 10.0, 1.0, 0.0, 0.0);
  vtkNew<vtkMultiMaterialVolumeMapper> mapper;
  mapper->SetInputData(image);
  mapper->SetMaterialTransferFunction(materials);
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  volume->SetProperty(property);
  renderer->AddVolume(volume);
  vtkNew<vtkLight> light;
  light->SetLightTypeToSceneLight();
  light->PositionalOff();
  light->SetFocalPoint(128.0, 128.0, 128.0);
  light->SetPosition(200.0, 600.0, 300.0);
  renderer->AddLight(light);
  renderer->ResetCamera();
  renderer->GetActiveCamera()->Azimuth(30.0);
  renderer->GetActiveCamera()->Elevation(20.0);
  renderer->ResetCameraClippingRange();

  auto start = std::chrono::steady_clock::now();
  window->Render();
  const double first = Seconds(start);
  const double peakMB = PeakResidentMB() - baseMB;
  if (!mapper->GetMultiMaterialActive())
  {
    std::cerr << "multi-material shading not active at size " << n << std::endl;
  }
  mapper->TimeStagesOn();
  std::vector<double> irradiance, lightFrame, still;
  for (int r = 0; r < reps; ++r)
  {
    light->SetPosition(200.0 + 40.0 * (r + 1), 600.0, 300.0);
    start = std::chrono::steady_clock::now();
    window->Render();
    lightFrame.push_back(Seconds(start));
    irradiance.push_back(mapper->GetLastIrradianceSeconds());
    start = std::chrono::steady_clock::now();
    window->Render();
    still.push_back(Seconds(start));
  }
  int dims[3];
  mapper->GetIrradianceDimensions(dims);
  const double dataMB = double(n) * n * n * sizeof(float) / (1024.0 * 1024.0);
  const double texturesMB = mapper->GetMultiMaterialMemoryBytes() / (1024.0 * 1024.0);
  char line[512];
  std::snprintf(line, sizeof(line), "%d,%.1f,%dx%dx%d,%.1f,%.0f,%.2f,%.3f,%.2f,%.2f", n, dataMB,
    dims[0], dims[1], dims[2], texturesMB, peakMB, first, Median(irradiance), Median(lightFrame),
    Median(still));
  const char* header = "size,data_MB,irradiance_grid,mmv_textures_MB,peak_rss_MB,first_frame_s,"
                       "irradiance_update_s,light_move_frame_s,still_frame_s";
  std::cout << header << "\n" << line << std::endl;
  std::cout << "irradiance: " << mapper->GetIrradianceResolutionReason() << std::endl;
  if (!csv.empty())
  {
    const bool fresh = !std::ifstream(csv).good();
    std::ofstream out(csv, std::ios::app);
    if (fresh)
    {
      out << header << "\n";
    }
    out << line << "\n";
  }
  return mapper->GetMultiMaterialActive() ? 0 : 1;
}
