// The error of storing the tint of a non-white transmission colour at half
// the irradiance resolution per axis (mmv::TintResolutionDivisor;
// docs/performance.md, "Material terms: cost"), on the benchmark scenes with every node's T = (1,
// 0.6, 0.3): the CPU irradiance filter's RGB irradiance E * K with the tint on the irradiance grid
// itself (divisor 1, uncompressed) against the stored one (divisor 2), over the voxels that hold
// irradiance (E > 0), per channel: PSNR (peak 1, the unshadowed light) and the largest absolute
// error; and the filter's seconds for each.
//
//   mmvTintBenchmark [--out FILE.csv] [--scenes synthetic,headsq] [--scale S]
//                    [--head FILE.vti]
//
// Not a test: it asserts nothing.
#include "mmvBenchmarkScenes.h"

#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkIrradianceVolumeFilter.h"
#include "vtkLight.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMultiMaterialParameters.h"
#include "vtkNew.h"
#include "vtkPointData.h"

#include <chrono>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <string>
#include <vector>

namespace
{
const double Tint[3] = { 1.0, 0.6, 0.3 };

vtkSmartPointer<vtkMaterialTransferFunction> Tinted(vtkMaterialTransferFunction* materials)
{
  constexpr int Stride = vtkMaterialTransferFunction::NodeStride;
  std::vector<double> nodes(static_cast<size_t>(materials->GetSize()) * Stride);
  materials->GetNodes(nodes.data());
  for (size_t i = 0; i < nodes.size(); i += Stride)
  {
    for (int c = 0; c < 3; ++c)
    {
      nodes[i + 1 + mmv::TransmissionR + c] = Tint[c];
    }
  }
  auto out = vtkSmartPointer<vtkMaterialTransferFunction>::New();
  out->SetNodes(static_cast<int>(nodes.size()), nodes.data());
  return out;
}

struct Result
{
  std::vector<float> Grey, Tint; // E, and K (3 per voxel)
  double Seconds = 0.0;
  int Dims[3] = { 0, 0, 0 };
};

Result Run(const mmvbench::SceneSpec& scene, vtkMaterialTransferFunction* materials, int divisor,
  double scale)
{
  vtkNew<vtkIrradianceVolumeFilter> filter;
  filter->SetInputData(scene.Image);
  filter->SetScalarOpacity(scene.Opacity);
  filter->SetScalarOpacityUnitDistance(scene.UnitDistance);
  filter->SetMaterialTransferFunction(materials);
  filter->SetIrradianceScale(scale);
  filter->SetTintResolutionDivisor(divisor);
  filter->MultipleScatteringOff(); // the tint is not diffused; keep E the same in both
  vtkNew<vtkLight> light;
  light->SetPositional(false);
  light->SetFocalPoint(0.0, 0.0, 0.0);
  light->SetPosition(scene.ToLight[0], scene.ToLight[1], scene.ToLight[2]);
  filter->AddLight(light);
  const auto start = std::chrono::steady_clock::now();
  filter->Update();
  Result r;
  r.Seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  filter->GetOutput()->GetDimensions(r.Dims);
  auto* grey =
    vtkFloatArray::SafeDownCast(filter->GetOutput()->GetPointData()->GetArray("Irradiance_0"));
  auto* tint =
    vtkFloatArray::SafeDownCast(filter->GetOutput()->GetPointData()->GetArray("IrradianceTint_0"));
  if (grey && tint)
  {
    r.Grey.assign(grey->GetPointer(0), grey->GetPointer(0) + grey->GetNumberOfValues());
    r.Tint.assign(tint->GetPointer(0), tint->GetPointer(0) + tint->GetNumberOfValues());
  }
  return r;
}
}

int main(int argc, char* argv[])
{
  std::string out = "tint.csv";
  std::string head = MMV_HEADSQ_PATH;
  std::vector<std::string> scenes = { "synthetic", "headsq" };
  double scale = 1.0;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    const std::string value = i + 1 < argc ? argv[i + 1] : "";
    if (a == "--out")
    {
      out = value;
    }
    else if (a == "--scenes")
    {
      scenes = mmvbench::SplitList(value);
    }
    else if (a == "--scale")
    {
      scale = std::atof(value.c_str());
    }
    else if (a == "--head")
    {
      head = value;
    }
    else
    {
      std::cerr << "usage: " << argv[0]
                << " [--out FILE.csv] [--scenes a,b] [--scale S] [--head FILE.vti]\n";
      return 2;
    }
    ++i;
  }
  std::ofstream csv(out);
  csv << "scene,irradiance_dims,tint_dims,channel,psnr_db,max_abs_error,voxels,"
         "seconds_full_tint,seconds_half_tint,seconds_grey\n";
  for (const std::string& name : scenes)
  {
    const mmvbench::SceneSpec scene = mmvbench::MakeScene(name, head);
    if (!scene.Image)
    {
      std::cerr << "unknown or unreadable scene " << name << "\n";
      return 1;
    }
    auto materials = Tinted(scene.Materials);
    const Result grey = Run(scene, scene.Materials, 2, scale);
    const Result full = Run(scene, materials, 1, scale);
    const Result half = Run(scene, materials, 2, scale);
    if (full.Tint.empty() || half.Tint.empty())
    {
      std::cerr << name << ": no tint arrays\n";
      return 1;
    }
    const std::string dims = std::to_string(full.Dims[0]) + "x" + std::to_string(full.Dims[1]) +
      "x" + std::to_string(full.Dims[2]);
    const std::string tintDims = std::to_string(mmv::TintDimension(full.Dims[0])) + "x" +
      std::to_string(mmv::TintDimension(full.Dims[1])) + "x" +
      std::to_string(mmv::TintDimension(full.Dims[2]));
    for (int c = 0; c < 3; ++c)
    {
      double sum = 0.0, worst = 0.0;
      size_t voxels = 0;
      for (size_t v = 0; v < full.Grey.size(); ++v)
      {
        if (!(full.Grey[v] > 0.0f))
        {
          continue;
        }
        const double a = static_cast<double>(full.Grey[v]) * full.Tint[3 * v + c];
        const double b = static_cast<double>(half.Grey[v]) * half.Tint[3 * v + c];
        sum += (a - b) * (a - b);
        worst = std::max(worst, std::abs(a - b));
        ++voxels;
      }
      const double mse = voxels ? sum / voxels : 0.0;
      const double psnr = mse > 0.0 ? 10.0 * std::log10(1.0 / mse) : INFINITY;
      std::cout << std::setw(10) << name << " " << dims << " (tint " << tintDims << ") channel "
                << "rgb"[c] << ": PSNR " << std::fixed << std::setprecision(1) << psnr
                << " dB, max error " << std::setprecision(4) << worst << " over " << voxels
                << " voxels; filter " << std::setprecision(2) << full.Seconds << " s (full tint), "
                << half.Seconds << " s (half), " << grey.Seconds << " s (grey)\n";
      csv << name << "," << dims << "," << tintDims << ","
          << "rgb"[c] << "," << psnr << "," << worst << "," << voxels << "," << full.Seconds << ","
          << half.Seconds << "," << grey.Seconds << "\n";
    }
  }
  return 0;
}
