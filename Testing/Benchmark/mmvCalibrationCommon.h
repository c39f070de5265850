/**
 * What the calibration programs against the physical reference share
 * (mmvPhysicalCalibration, mmvMediumCalibration): an offscreen window that
 * renders a benchmark scene with one mapper and times it, the path tracer's
 * image as the truth, the scaling of a scene's materials, and the error
 * after the best brightness factor.
 */
#ifndef mmvCalibrationCommon_h
#define mmvCalibrationCommon_h

#include "mmvBenchmarkScenes.h"
#include "mmvTestWindow.h"

#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMultiMaterialParameters.h"
#include "vtkNew.h"
#include "vtkOpenGLGPUVolumeRayCastMapper.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace mmvcal
{
using Clock = std::chrono::steady_clock;

/// The numbers of a comma-separated command-line list ("1,0.5,2").
inline std::vector<double> Numbers(const std::string& text)
{
  std::vector<double> values;
  for (const std::string& item : mmvbench::SplitList(text))
  {
    values.push_back(std::atof(item.c_str()));
  }
  return values;
}

inline double Median(std::vector<double> v)
{
  if (v.empty())
  {
    return 0.0;
  }
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// The scene's materials with every node's s and c_t scaled, and g set
// (NaN: kept).
inline void ScaleMaterials(vtkMaterialTransferFunction* source, double scattering,
  double attenuation, vtkMaterialTransferFunction* target, double anisotropy = std::nan(""))
{
  const int stride = vtkMaterialTransferFunction::NodeStride;
  std::vector<double> nodes(static_cast<size_t>(source->GetSize()) * stride);
  source->GetNodes(nodes.data());
  for (size_t n = 0; n < nodes.size(); n += stride)
  {
    nodes[n + 1 + mmv::Scattering] *= scattering;
    nodes[n + 1 + mmv::Attenuation] *= attenuation;
    if (!std::isnan(anisotropy))
    {
      nodes[n + 1 + mmv::Anisotropy] = anisotropy;
    }
  }
  target->SetNodes(static_cast<int>(nodes.size()), nodes.data());
}

// One offscreen window rendering the scene with one mapper, sampled at the
// smallest spacing.
struct Window : mmvbench::View
{
  Window(const mmvbench::SceneSpec& scene, vtkCamera* camera, vtkLight* light, int size,
    vtkOpenGLGPUVolumeRayCastMapper* mapper)
  {
    this->SetUp(scene, camera, light, size, mapper);
    const double* spacing = scene.Image->GetSpacing();
    mapper->AutoAdjustSampleDistancesOff();
    mapper->LockSampleDistanceToInputSpacingOff();
    mapper->SetSampleDistance(static_cast<float>(std::min({ spacing[0], spacing[1], spacing[2] })));
  }

  // Median frame time after one untimed frame (0 with frames = 0); the image
  // of the last one.
  double Frames(int frames, vtkImageData* image)
  {
    this->RenderWindow->Render();
    std::vector<double> times;
    for (int f = 0; f < frames; ++f)
    {
      const auto start = Clock::now();
      this->RenderWindow->Render();
      this->RenderWindow->WaitForCompletion();
      times.push_back(std::chrono::duration<double>(Clock::now() - start).count());
    }
    const int* size = this->RenderWindow->GetSize();
    vtkNew<vtkUnsignedCharArray> rgb;
    this->RenderWindow->GetPixelData(0, 0, size[0] - 1, size[1] - 1, 0, rgb);
    image->SetDimensions(size[0], size[1], 1);
    image->GetPointData()->SetScalars(rgb);
    return Median(times);
  }
};

// The path tracer's image as the methods are compared with it: its 8-bit
// colours, the pixels where its paths met the medium (some standard error),
// and its noise floor (the RMS standard error, 0-255).
struct Truth
{
  vtkNew<vtkImageData> Image;
  std::vector<bool> Mask;
  double FloorRMSE = 0.0;

  Truth(vtkImageData* traced, int size)
  {
    this->Image->SetDimensions(size, size, 1);
    this->Image->GetPointData()->SetScalars(traced->GetPointData()->GetArray("Colors"));
    vtkDataArray* se = traced->GetPointData()->GetArray("StandardError");
    double floor2 = 0.0;
    this->Mask.assign(se->GetNumberOfTuples(), false);
    for (vtkIdType i = 0; i < se->GetNumberOfValues(); ++i)
    {
      const double e = se->GetComponent(i / 3, i % 3);
      floor2 += e * e;
      this->Mask[i / 3] = this->Mask[i / 3] || e > 0.0;
    }
    this->FloorRMSE = 255.0 * std::sqrt(floor2 / se->GetNumberOfValues());
  }
};

// Over the volume's pixels (`mask`: the truth's paths met the medium there),
// the RMSE (0-255) of test against truth as is (`raw`), and after the
// least-squares brightness factor k (returned).
inline double GainCompensated(
  vtkImageData* test, vtkImageData* truth, const std::vector<bool>& mask, double& k, double& raw)
{
  vtkDataArray* a = test->GetPointData()->GetScalars();
  vtkDataArray* b = truth->GetPointData()->GetScalars();
  const vtkIdType n = std::min(a->GetNumberOfTuples(), b->GetNumberOfTuples());
  double ab = 0.0, aa = 0.0, e0 = 0.0;
  long long count = 0;
  for (vtkIdType i = 0; i < n; ++i)
  {
    for (int c = 0; mask[i] && c < 3; ++c)
    {
      const double x = a->GetComponent(i, c);
      const double y = b->GetComponent(i, c);
      ab += x * y;
      aa += x * x;
      e0 += (x - y) * (x - y);
      ++count;
    }
  }
  k = aa > 0.0 ? ab / aa : 1.0;
  double e = 0.0;
  for (vtkIdType i = 0; i < n; ++i)
  {
    for (int c = 0; mask[i] && c < 3; ++c)
    {
      const double d = k * a->GetComponent(i, c) - b->GetComponent(i, c);
      e += d * d;
    }
  }
  raw = count ? std::sqrt(e0 / count) : 0.0;
  return count ? std::sqrt(e / count) : 0.0;
}

// The largest channel value of an image.
inline double Brightest(vtkImageData* image)
{
  vtkDataArray* x = image->GetPointData()->GetScalars();
  double largest = 0.0;
  for (int c = 0; c < x->GetNumberOfComponents(); ++c)
  {
    largest = std::max(largest, x->GetRange(c)[1]);
  }
  return largest;
}

// The (x, y) >= 0 minimising |x (A - Z) + y (B - Z) - (T - Z)|^2 over all
// pixels and channels; Z (`offset`, optional: 0) is what every image holds
// whatever x and y (the background, terms not fitted).
inline void NonNegativeLeastSquares(vtkImageData* a, vtkImageData* b, vtkImageData* t, double& x,
  double& y, vtkImageData* offset = nullptr)
{
  vtkDataArray* A = a->GetPointData()->GetScalars();
  vtkDataArray* B = b->GetPointData()->GetScalars();
  vtkDataArray* T = t->GetPointData()->GetScalars();
  vtkDataArray* Z = offset ? offset->GetPointData()->GetScalars() : nullptr;
  double aa = 0, ab = 0, bb = 0, at = 0, bt = 0, tt = 0;
  for (vtkIdType i = 0; i < A->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      const double z = Z ? Z->GetComponent(i, c) : 0.0;
      const double u = A->GetComponent(i, c) - z, v = B->GetComponent(i, c) - z,
                   w = T->GetComponent(i, c) - z;
      aa += u * u;
      ab += u * v;
      bb += v * v;
      at += u * w;
      bt += v * w;
      tt += w * w;
    }
  }
  auto error = [&](double p, double q)
  { return p * p * aa + q * q * bb + 2 * p * q * ab - 2 * p * at - 2 * q * bt + tt; };
  const double det = aa * bb - ab * ab;
  x = y = 0.0;
  if (det > 1e-12 * aa * bb)
  {
    x = (at * bb - bt * ab) / det;
    y = (bt * aa - at * ab) / det;
  }
  if (!(x >= 0.0 && y >= 0.0))
  {
    const double xa = aa > 0 ? std::max(at / aa, 0.0) : 0.0; // y = 0
    const double yb = bb > 0 ? std::max(bt / bb, 0.0) : 0.0; // x = 0
    if (error(xa, 0.0) <= error(0.0, yb))
    {
      x = xa, y = 0.0;
    }
    else
    {
      x = 0.0, y = yb;
    }
  }
}

// The (a, b) >= 0 with which `render(a, b, image)` best fits `truth`, the
// image being linear in a and b: basis renders at (k0, 0) and (0, k0), k0
// halved from `k0` until neither saturates, then least squares; with
// `offset`, less the (0, 0) render (what a and b do not scale: background,
// terms not fitted).
inline void FitTwoScales(const std::function<void(double, double, vtkImageData*)>& render,
  vtkImageData* truth, double k0, bool offset, double& a, double& b)
{
  vtkNew<vtkImageData> zero, basisA, basisB;
  if (offset)
  {
    render(0.0, 0.0, zero);
  }
  for (int tries = 0; tries < 6; ++tries)
  {
    render(k0, 0.0, basisA);
    render(0.0, k0, basisB);
    if (std::max(Brightest(basisA), Brightest(basisB)) < 255.0 || tries == 5)
    {
      break; // k0 is the basis renders' scale
    }
    k0 *= 0.5;
  }
  double x = 0.0, y = 0.0;
  NonNegativeLeastSquares(basisA, basisB, truth, x, y, offset ? zero.Get() : nullptr);
  a = k0 * x;
  b = k0 * y;
}

// Every node's ka and kd of `materials` multiplied (in place), within their
// hard limits.
inline void ScaleAmbientDiffuse(
  vtkMaterialTransferFunction* materials, double ambient, double diffuse)
{
  const int stride = vtkMaterialTransferFunction::NodeStride;
  std::vector<double> nodes(static_cast<size_t>(materials->GetSize()) * stride);
  materials->GetNodes(nodes.data());
  for (size_t n = 0; n < nodes.size(); n += stride)
  {
    double& ka = nodes[n + 1 + mmv::Ambient];
    double& kd = nodes[n + 1 + mmv::Diffuse];
    ka = std::min(ka * ambient, mmv::MaterialParameterTable[mmv::Ambient].HardMax);
    kd = std::min(kd * diffuse, mmv::MaterialParameterTable[mmv::Diffuse].HardMax);
  }
  materials->SetNodes(static_cast<int>(nodes.size()), nodes.data());
}

inline std::string Setting(const std::vector<std::pair<std::string, double>>& values)
{
  std::ostringstream s;
  for (size_t i = 0; i < values.size(); ++i)
  {
    s << (i ? " " : "") << values[i].first << "=" << values[i].second;
  }
  return s.str();
}
} // namespace mmvcal

#endif
