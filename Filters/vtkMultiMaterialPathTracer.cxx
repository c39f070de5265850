#include "vtkMultiMaterialPathTracer.h"

#include "vtkAbstractVolumeMapper.h"
#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkImageData.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMatrix4x4.h"
#include "vtkMultiMaterialLights.h"
#include "vtkMultiMaterialParameters.h"
#include "vtkMultiMaterialPhaseFunction.h"
#include "vtkMultiMaterialShading.h"
#include "vtkIrradianceGrid.h" // ClipToIndexBox
#include "vtkMultiMaterialVolumeSampling.h"
#include "vtkObjectFactory.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkRenderer.h"
#include "vtkSMPTools.h"
#include "vtkUnsignedCharArray.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <climits>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkMultiMaterialPathTracer);

namespace
{
using glm::dvec3;

// Transfer-function resolution, as in the reference renderer.
constexpr int TableSize = 65536;
// Cells per majorant brick along each axis.
constexpr int BrickCells = 8;
// Scattering events after which Russian roulette may end a path.
constexpr int RouletteAfter = 3;

// PCG32 (O'Neill): small, fast and statistically sound for Monte Carlo.
class Random
{
public:
  Random(std::uint64_t seed, std::uint64_t stream)
    : Increment((stream << 1u) | 1u)
  {
    this->Next();
    this->State += seed;
    this->Next();
  }
  // Uniform in [0, 1).
  double Uniform() { return (this->Next() >> 5) * (1.0 / 134217728.0); }

private:
  std::uint32_t Next()
  {
    const std::uint64_t old = this->State;
    this->State = old * 6364136223846793005ULL + this->Increment;
    const std::uint32_t shifted = static_cast<std::uint32_t>(((old >> 18u) ^ old) >> 27u);
    const std::uint32_t rot = static_cast<std::uint32_t>(old >> 59u);
    return (shifted >> rot) | (shifted << ((32u - rot) & 31u));
  }
  std::uint64_t State = 0;
  std::uint64_t Increment;
};

// Transfer functions tabulated over the scalar range.
struct MediumTables
{
  double Min = 0.0;
  double Scale = 1.0;           // entry per data unit
  std::vector<double> Albedo;   // rgb: the colour TF
  std::vector<double> Sigma;    // extinction per object unit
  std::vector<double> Material; // MaterialParameterCount per entry

  void Locate(double s, int& i, double& w) const
  {
    const double x = std::min(std::max((s - this->Min) * this->Scale, 0.0), TableSize - 1.0);
    i = std::min(static_cast<int>(x), TableSize - 2);
    w = x - i;
  }
  double Extinction(double s) const
  {
    int i;
    double w;
    this->Locate(s, i, w);
    return (1.0 - w) * this->Sigma[i] + w * this->Sigma[i + 1];
  }
  double Lerp(const std::vector<double>& t, int stride, int c, int i, double w) const
  {
    return (1.0 - w) * t[i * stride + c] + w * t[(i + 1) * stride + c];
  }
  // Largest extinction over the entries for data values in [lo, hi]: bounds
  // the interpolated extinction of any value in between.
  double MaxExtinction(double lo, double hi) const
  {
    int i0, i1;
    double w;
    this->Locate(lo, i0, w);
    this->Locate(hi, i1, w);
    return *std::max_element(this->Sigma.begin() + i0, this->Sigma.begin() + i1 + 2);
  }
};

// Largest extinction per brick of BrickCells^3 cells.
struct MajorantGrid
{
  int Bricks[3] = { 1, 1, 1 };
  std::vector<double> Max;

  void Build(const mmv::ScalarField& field, const MediumTables& tables)
  {
    const int* dims = field.Dims;
    for (int a = 0; a < 3; ++a)
    {
      this->Bricks[a] = std::max(1, (dims[a] - 2) / BrickCells + 1);
    }
    const vtkIdType count =
      static_cast<vtkIdType>(this->Bricks[0]) * this->Bricks[1] * this->Bricks[2];
    this->Max.assign(count, 0.0);
    vtkSMPTools::For(0, count,
      [&](vtkIdType first, vtkIdType last)
      {
        for (vtkIdType b = first; b < last; ++b)
        {
          const int bi[3] = { static_cast<int>(b % this->Bricks[0]),
            static_cast<int>((b / this->Bricks[0]) % this->Bricks[1]),
            static_cast<int>(b / (static_cast<vtkIdType>(this->Bricks[0]) * this->Bricks[1])) };
          int lo[3], hi[3];
          for (int a = 0; a < 3; ++a)
          {
            lo[a] = bi[a] * BrickCells;
            hi[a] = std::min(lo[a] + BrickCells, dims[a] - 1);
          }
          double smin = std::numeric_limits<double>::max();
          double smax = -smin;
          for (int k = lo[2]; k <= hi[2]; ++k)
          {
            for (int j = lo[1]; j <= hi[1]; ++j)
            {
              const double* row =
                field.Values + (static_cast<vtkIdType>(k) * dims[1] + j) * dims[0];
              for (int i = lo[0]; i <= hi[0]; ++i)
              {
                smin = std::min(smin, row[i]);
                smax = std::max(smax, row[i]);
              }
            }
          }
          this->Max[b] = tables.MaxExtinction(smin, smax);
        }
      });
  }
};

struct Event
{
  double T = 0.0;
  dvec3 P{ 0.0 }; // index coordinates
};

// The scene as the paths see it, shared read-only by the threads.
struct Medium
{
  mmv::ScalarField Data;
  MediumTables Tables;
  MajorantGrid Majorant;
  dvec3 Origin{ 0.0 };
  glm::dmat3 ObjectToIndex{ 1.0 };
  glm::dmat3 GradientToObject{ 1.0 };
  double InverseRange = 1.0;
  double SmallestSpacing = 1.0;
  std::vector<mmv::ShadingLight> Lights;
  dvec3 EnvironmentUp{ 0.0, 1.0, 0.0 };
  dvec3 EnvironmentBottom{ 0.0 };
  dvec3 EnvironmentTop{ 0.0 };
  int MaxBounces = 64;
  bool SurfaceScattering = true;

  dvec3 ToIndex(const dvec3& x) const { return this->ObjectToIndex * (x - this->Origin); }

  // Calls visit(t0, t1, majorant) for the bricks the ray x + t d crosses
  // inside the data box, in order, until it returns false.
  template <typename Visit>
  void Traverse(const dvec3& x, const dvec3& d, double tMax, Visit&& visit) const
  {
    const dvec3 p = this->ToIndex(x);
    const dvec3 q = this->ObjectToIndex * d;
    double t0 = 0.0;
    double t1 = tMax;
    if (!mmv::ClipToIndexBox(p, q, this->Data.Dims, t0, t1))
    {
      return;
    }
    // Amanatides-Woo over the brick grid (index units, BrickCells a brick).
    const dvec3 start = p + t0 * q;
    int brick[3], step[3];
    double tNext[3], tDelta[3];
    for (int a = 0; a < 3; ++a)
    {
      brick[a] = std::min(
        std::max(static_cast<int>(start[a] / BrickCells), 0), this->Majorant.Bricks[a] - 1);
      if (q[a] > 0.0)
      {
        step[a] = 1;
        tNext[a] = t0 + ((brick[a] + 1) * BrickCells - start[a]) / q[a];
        tDelta[a] = BrickCells / q[a];
      }
      else if (q[a] < 0.0)
      {
        step[a] = -1;
        tNext[a] = t0 + (brick[a] * BrickCells - start[a]) / q[a];
        tDelta[a] = -BrickCells / q[a];
      }
      else
      {
        step[a] = 0;
        tNext[a] = std::numeric_limits<double>::infinity();
        tDelta[a] = 0.0;
      }
    }
    double t = t0;
    while (t < t1)
    {
      const int a =
        tNext[0] < tNext[1] ? (tNext[0] < tNext[2] ? 0 : 2) : (tNext[1] < tNext[2] ? 1 : 2);
      const double tEnd = std::min(tNext[a], t1);
      const vtkIdType b = brick[0] +
        this->Majorant.Bricks[0] *
          (brick[1] + static_cast<vtkIdType>(this->Majorant.Bricks[1]) * brick[2]);
      if (tEnd > t && !visit(t, tEnd, this->Majorant.Max[b]))
      {
        return;
      }
      t = tEnd;
      brick[a] += step[a];
      tNext[a] += tDelta[a];
      if (brick[a] < 0 || brick[a] >= this->Majorant.Bricks[a])
      {
        return;
      }
    }
  }

  // Delta tracking: the first real collision along x + t d before tMax.
  bool SampleCollision(const dvec3& x, const dvec3& d, double tMax, Random& rng, Event& event) const
  {
    bool hit = false;
    const dvec3 p = this->ToIndex(x);
    const dvec3 q = this->ObjectToIndex * d;
    this->Traverse(x, d, tMax,
      [&](double t0, double t1, double majorant)
      {
        if (majorant <= 0.0)
        {
          return true;
        }
        double t = t0;
        for (;;)
        {
          t -= std::log1p(-rng.Uniform()) / majorant;
          if (t >= t1)
          {
            return true; // memoryless: start afresh in the next brick
          }
          const dvec3 pt = p + t * q;
          if (rng.Uniform() * majorant < this->Tables.Extinction(this->Data.Sample(pt)))
          {
            event.T = t;
            event.P = pt;
            hit = true;
            return false;
          }
        }
      });
    return hit;
  }

  // Ratio tracking: an unbiased estimate of the transmittance to tMax.
  double Transmittance(const dvec3& x, const dvec3& d, double tMax, Random& rng) const
  {
    double transmittance = 1.0;
    const dvec3 p = this->ToIndex(x);
    const dvec3 q = this->ObjectToIndex * d;
    this->Traverse(x, d, tMax,
      [&](double t0, double t1, double majorant)
      {
        if (majorant <= 0.0)
        {
          return true;
        }
        double t = t0;
        for (;;)
        {
          t -= std::log1p(-rng.Uniform()) / majorant;
          if (t >= t1)
          {
            return true;
          }
          transmittance *= 1.0 - this->Tables.Extinction(this->Data.Sample(p + t * q)) / majorant;
          if (transmittance < 0.1)
          {
            // Russian roulette keeps the estimate unbiased and the walk short.
            if (rng.Uniform() < 0.5)
            {
              transmittance = 0.0;
              return false;
            }
            transmittance *= 2.0;
          }
        }
      });
    return transmittance;
  }

  // Normalised-value gradient in object space, central differences of one
  // voxel like the reference renderer and the mapper.
  dvec3 Gradient(const dvec3& p) const
  {
    dvec3 g;
    for (int a = 0; a < 3; ++a)
    {
      dvec3 e(0.0);
      e[a] = 1.0;
      g[a] = 0.5 * (this->Data.Sample(p + e) - this->Data.Sample(p - e)) * this->InverseRange;
    }
    return this->GradientToObject * g;
  }

  dvec3 Environment(const dvec3& d) const
  {
    return mmv::mmvEnvironment(
      d, this->EnvironmentUp, this->EnvironmentBottom, this->EnvironmentTop);
  }

  dvec3 Trace(const dvec3& x0, const dvec3& d0, double tMax, const dvec3& background, Random& rng,
    long long& events) const;
};

// What scatters at one event: the phase function, or a surface BRDF.
struct Scatterer
{
  bool Surface = false;
  double G = 0.0;        // anisotropy
  dvec3 N{ 0.0 };        // surface: unit normal on the side of wo
  double Ks = 0.0;       // surface: specular weight
  double Exponent = 1.0; // surface: Blinn exponent

  // Scattered radiance per unit incident irradiance from wi toward wo
  // (both pointing away from the event), without the albedo.
  double Evaluate(const dvec3& wo, const dvec3& wi) const
  {
    if (!this->Surface)
    {
      return mmv::HenyeyGreenstein(this->G, -glm::dot(wo, wi));
    }
    const double cosI = glm::dot(this->N, wi);
    if (cosI <= 0.0)
    {
      return 0.0;
    }
    const dvec3 h = glm::normalize(wo + wi);
    const double cosH = std::max(0.0, glm::dot(this->N, h));
    const double f = (1.0 - this->Ks) / M_PI +
      this->Ks * (this->Exponent + 8.0) / (8.0 * M_PI) * std::pow(cosH, this->Exponent);
    return f * cosI;
  }

  // Samples wi; returns the weight Evaluate / pdf (0: path ends).
  double Sample(const dvec3& wo, Random& rng, dvec3& wi) const
  {
    const double u1 = rng.Uniform();
    const double u2 = rng.Uniform();
    const double u3 = rng.Uniform();
    if (!this->Surface)
    {
      wi =
        mmv::DirectionAround(-wo, mmv::SampleHenyeyGreensteinCosine(this->G, u1), 2.0 * M_PI * u2);
      return 1.0;
    }
    if (u3 < this->Ks)
    {
      const double cosH = std::pow(u1, 1.0 / (this->Exponent + 1.0));
      const dvec3 h = mmv::DirectionAround(this->N, cosH, 2.0 * M_PI * u2);
      wi = 2.0 * glm::dot(wo, h) * h - wo;
    }
    else
    {
      wi = mmv::DirectionAround(this->N, std::sqrt(u1), 2.0 * M_PI * u2);
    }
    const double cosI = glm::dot(this->N, wi);
    if (cosI <= 0.0)
    {
      return 0.0;
    }
    // One-sample mixture: the pdf of both strategies together.
    const dvec3 h = glm::normalize(wo + wi);
    const double cosH = std::max(0.0, glm::dot(this->N, h));
    const double oh = std::abs(glm::dot(wo, h));
    const double specularPdf = oh > 0.0
      ? (this->Exponent + 1.0) / (2.0 * M_PI) * std::pow(cosH, this->Exponent) / (4.0 * oh)
      : 0.0;
    const double pdf = (1.0 - this->Ks) * cosI / M_PI + this->Ks * specularPdf;
    return pdf > 0.0 ? this->Evaluate(wo, wi) / pdf : 0.0;
  }
};

dvec3 Medium::Trace(const dvec3& x0, const dvec3& d0, double tMax, const dvec3& background,
  Random& rng, long long& events) const
{
  dvec3 radiance(0.0);
  dvec3 throughput(1.0);
  dvec3 x = x0;
  dvec3 d = d0;
  double limit = tMax;
  for (int bounce = 0;; ++bounce)
  {
    Event event;
    if (!this->SampleCollision(x, d, limit, rng, event))
    {
      radiance += throughput * (bounce == 0 ? background : this->Environment(d));
      break;
    }
    constexpr int P = mmv::MaterialParameterCount;
    const double s = this->Data.Sample(event.P);
    int i;
    double w;
    this->Tables.Locate(s, i, w);
    const dvec3 albedo(this->Tables.Lerp(this->Tables.Albedo, 3, 0, i, w),
      this->Tables.Lerp(this->Tables.Albedo, 3, 1, i, w),
      this->Tables.Lerp(this->Tables.Albedo, 3, 2, i, w));
    // Emission, a source of e * colour * sigma_t per unit length: collisions
    // come at density sigma_t T, so each one scores e * colour (an absorbed
    // path's last collision too).
    const double emission = this->Tables.Lerp(this->Tables.Material, P, mmv::Emission, i, w);
    radiance += throughput * mmv::mmvEmission(emission, glm::dvec4(albedo, 1.0));
    if (bounce >= this->MaxBounces)
    {
      break; // absorbed: no more events allowed
    }
    ++events;
    x += event.T * d;
    limit = std::numeric_limits<double>::max();
    throughput *= albedo;
    if (throughput == dvec3(0.0))
    {
      break;
    }
    Scatterer scatterer;
    scatterer.G = this->Tables.Lerp(this->Tables.Material, P, mmv::Anisotropy, i, w);
    const dvec3 wo = -d;
    if (this->SurfaceScattering)
    {
      const dvec3 gradient = this->Gradient(event.P);
      const double length = glm::length(gradient);
      const double perVoxel =
        length * this->SmallestSpacing / vtkMultiMaterialPathTracer::SurfaceGradientPerVoxel;
      if (length > 0.0 && rng.Uniform() < -std::expm1(-perVoxel))
      {
        scatterer.Surface = true;
        scatterer.N = -gradient / length;
        scatterer.N = glm::dot(scatterer.N, wo) < 0.0 ? -scatterer.N : scatterer.N;
        scatterer.Ks = std::min(
          std::max(this->Tables.Lerp(this->Tables.Material, P, mmv::Specular, i, w), 0.0), 1.0);
        scatterer.Exponent =
          std::max(this->Tables.Lerp(this->Tables.Material, P, mmv::Shininess, i, w), 0.0);
      }
    }
    // Next-event estimation to every light.
    for (const mmv::ShadingLight& light : this->Lights)
    {
      const double geometry = mmv::mmvLightGeometryTerm(light.Source, x);
      if (geometry <= 0.0)
      {
        continue;
      }
      double distance = 0.0;
      const dvec3 l = mmv::mmvDirectionToLight(light.Source, x, distance);
      const double f = scatterer.Evaluate(wo, l);
      if (f <= 0.0)
      {
        continue;
      }
      const double transmittance = this->Transmittance(
        x, l, distance >= 0.0 ? distance : std::numeric_limits<double>::max(), rng);
      radiance += throughput * light.Radiance * (geometry * f * transmittance);
    }
    dvec3 wi;
    const double weight = scatterer.Sample(wo, rng, wi);
    if (weight <= 0.0)
    {
      break;
    }
    throughput *= weight;
    d = wi;
    if (bounce + 1 >= RouletteAfter)
    {
      const double survive = std::min(1.0, std::max({ throughput.x, throughput.y, throughput.z }));
      if (rng.Uniform() >= survive)
      {
        break;
      }
      throughput /= survive;
    }
  }
  return radiance;
}

double Seconds(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// A well-mixed 64-bit value of the seed and the pixel: its random stream.
std::uint64_t PixelSeed(unsigned int seed, vtkIdType pixel)
{
  std::uint64_t z = (static_cast<std::uint64_t>(seed) << 32) ^ static_cast<std::uint64_t>(pixel);
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

// The transfer functions tabulated over the scalar range: albedo, extinction
// and material parameters (the defaults where there are no materials).
void TabulateTransferFunctions(vtkVolumeProperty* property, vtkMaterialTransferFunction* materials,
  const double range[2], double unitDistance, MediumTables& tables)
{
  tables.Min = range[0];
  tables.Scale = (TableSize - 1) / (range[1] - range[0]);
  mmv::TabulateColor(property, range, TableSize, tables.Albedo);
  std::vector<double> alpha(TableSize);
  property->GetScalarOpacity(0)->GetTable(range[0], range[1], TableSize, alpha.data());
  constexpr int P = mmv::MaterialParameterCount;
  tables.Sigma.resize(TableSize);
  tables.Material.resize(static_cast<size_t>(P) * TableSize);
  for (int i = 0; i < TableSize; ++i)
  {
    const double s = range[0] + (range[1] - range[0]) * i / (TableSize - 1.0);
    double* m = &tables.Material[static_cast<size_t>(P) * i];
    if (materials)
    {
      materials->Evaluate(s, m);
    }
    else
    {
      for (int c = 0; c < P; ++c)
      {
        m[c] = mmv::MaterialParameterTable[c].Default;
      }
    }
    tables.Sigma[i] = mmv::ExtinctionFromOpacity(alpha[i], unitDistance);
  }
}

// Where TracePixels writes: 3 values per pixel each, row after row.
struct PixelOutput
{
  double* Radiance;
  double* Error;
  unsigned char* Colors;
};

// `samples` paths through every pixel's centre, rows in parallel, each pixel
// with its own random stream so the image does not depend on the threads.
// Returns the scattering events of all paths.
long long TracePixels(const Medium& medium, const vtkMatrix4x4* ndcToObject, int width, int height,
  int samples, unsigned int seed, const PixelOutput& output)
{
  double* out = output.Radiance;
  double* outError = output.Error;
  unsigned char* bytes = output.Colors;
  std::atomic<long long> events(0);
  vtkSMPTools::For(0, height, 1,
    [&](vtkIdType firstRow, vtkIdType lastRow)
    {
      long long localEvents = 0;
      for (vtkIdType j = firstRow; j < lastRow; ++j)
      {
        const double y = (j + 0.5) / height * 2.0 - 1.0;
        // VTK draws the gradient background bottom (Background) to top.
        const dvec3 background =
          glm::mix(medium.EnvironmentBottom, medium.EnvironmentTop, (j + 0.5) / height);
        for (int i = 0; i < width; ++i)
        {
          const vtkIdType id = j * width + i;
          const double x = (i + 0.5) / width * 2.0 - 1.0;
          dvec3 origin, direction;
          double length;
          mmv::PixelRay(ndcToObject, x, y, origin, direction, length);
          Random rng(PixelSeed(seed, id), static_cast<std::uint64_t>(id));
          // Welford's running mean and squared deviations: pixels whose paths
          // all agree get exactly zero error (sum-of-squares would round).
          dvec3 mean(0.0), squares(0.0);
          for (int k = 0; k < samples; ++k)
          {
            const dvec3 l = length > 0.0
              ? medium.Trace(origin, direction, length, background, rng, localEvents)
              : background;
            const dvec3 delta = l - mean;
            mean += delta / double(k + 1);
            squares += delta * (l - mean);
          }
          // Unbiased sample variance of one path, over samples for the mean's.
          const dvec3 variance = samples > 1 ? squares / double(samples - 1) : dvec3(0.0);
          for (int c = 0; c < 3; ++c)
          {
            out[3 * id + c] = mean[c];
            outError[3 * id + c] = std::sqrt(variance[c] / samples);
            bytes[3 * id + c] = static_cast<unsigned char>(
              std::lround(std::min(std::max(mean[c], 0.0), 1.0) * 255.0));
          }
        }
      }
      events += localEvents;
    });
  return events;
}
}

vtkMultiMaterialPathTracer::vtkMultiMaterialPathTracer() = default;
vtkMultiMaterialPathTracer::~vtkMultiMaterialPathTracer() = default;

vtkImageData* vtkMultiMaterialPathTracer::RenderToImage(vtkRenderer* ren, vtkVolume* volume)
{
  if (!ren)
  {
    vtkErrorMacro("RenderToImage needs a renderer and a volume with a mapper");
    return nullptr;
  }
  std::optional<mmv::MapperSettings> mmvMapper;
  if (!this->AdoptVolume(volume, mmvMapper))
  {
    return nullptr;
  }
  if (mmvMapper)
  {
    this->SetPointLightRadius(mmvMapper->Illumination.PointLightRadius);
  }
  const int* size = ren->GetSize();
  return this->Render(ren, size[0], size[1]);
}

vtkImageData* vtkMultiMaterialPathTracer::Render(vtkRenderer* ren, int width, int height)
{
  const auto start = std::chrono::steady_clock::now();
  vtkImageData* image = this->Input;
  vtkVolumeProperty* property = this->Property;
  if (!this->CheckRenderInputs(ren, width, height))
  {
    return nullptr;
  }
  if (this->SamplesPerPixel < 1 || this->MaxBounces < 0)
  {
    vtkErrorMacro("Render needs SamplesPerPixel >= 1 and MaxBounces >= 0 (got "
      << this->SamplesPerPixel << " and " << this->MaxBounces << ")");
    return nullptr;
  }
  const double unitDistance = property->GetScalarOpacityUnitDistance(0);
  if (!(unitDistance > 0.0) || !std::isfinite(unitDistance))
  {
    vtkErrorMacro("the scalar opacity unit distance must be positive (got " << unitDistance << ")");
    return nullptr;
  }
  Medium medium;
  std::vector<double> values;
  double range[2];
  glm::dmat3 indexToObject(1.0);
  const std::string why =
    mmv::LoadScalarField(image, values, medium.Data, range, medium.Origin, indexToObject);
  if (!why.empty())
  {
    vtkErrorMacro(<< why);
    return nullptr;
  }
  medium.InverseRange = 1.0 / (range[1] - range[0]);
  medium.ObjectToIndex = glm::inverse(indexToObject);
  medium.GradientToObject = glm::transpose(medium.ObjectToIndex);
  const double* spacing = image->GetSpacing();
  medium.SmallestSpacing =
    std::min({ std::abs(spacing[0]), std::abs(spacing[1]), std::abs(spacing[2]) });
  medium.MaxBounces = this->MaxBounces;
  medium.SurfaceScattering = this->SurfaceScattering;

  // Transfer functions.
  TabulateTransferFunctions(property, this->Materials, range, unitDistance, medium.Tables);
  medium.Majorant.Build(medium.Data, medium.Tables);

  // Lights and environment in object space.
  vtkNew<vtkMatrix4x4> objectToWorld;
  if (this->Matrix)
  {
    objectToWorld->DeepCopy(this->Matrix);
  }
  vtkNew<vtkMatrix4x4> worldToObject;
  vtkMatrix4x4::Invert(objectToWorld, worldToObject);
  const double radius =
    this->PointLightRadius > 0.0 ? this->PointLightRadius : medium.SmallestSpacing;
  medium.Lights = mmv::CollectLights(ren->GetLights(), worldToObject, radius, INT_MAX);
  vtkCamera* camera = ren->GetActiveCamera();
  medium.EnvironmentUp = mmv::ViewUpInObject(camera, worldToObject);
  const double* bg1 = ren->GetBackground();
  const double* bg2 = ren->GetGradientBackground() ? ren->GetBackground2() : bg1;
  medium.EnvironmentBottom = dvec3(bg1[0], bg1[1], bg1[2]);
  medium.EnvironmentTop = dvec3(bg2[0], bg2[1], bg2[2]);

  // Camera: pixel-centre rays from the near to the far plane.
  vtkNew<vtkMatrix4x4> ndcToObject;
  mmv::NDCToObject(camera, width, height, worldToObject, ndcToObject);

  const vtkIdType pixels = static_cast<vtkIdType>(width) * height;
  auto makeArray = [pixels](const char* name, auto array)
  {
    array->SetName(name);
    array->SetNumberOfComponents(3);
    array->SetNumberOfTuples(pixels);
    return array;
  };
  vtkSmartPointer<vtkDoubleArray> radiance =
    makeArray("Radiance", vtkSmartPointer<vtkDoubleArray>::New());
  vtkSmartPointer<vtkDoubleArray> error =
    makeArray("StandardError", vtkSmartPointer<vtkDoubleArray>::New());
  vtkSmartPointer<vtkUnsignedCharArray> colors =
    makeArray("Colors", vtkSmartPointer<vtkUnsignedCharArray>::New());
  const int samples = this->SamplesPerPixel;
  const PixelOutput pixelOutput{ radiance->GetPointer(0), error->GetPointer(0),
    colors->GetPointer(0) };
  const long long events =
    TracePixels(medium, ndcToObject, width, height, samples, this->Seed, pixelOutput);

  this->Output = vtkSmartPointer<vtkImageData>::New();
  this->Output->SetDimensions(width, height, 1);
  this->Output->GetPointData()->SetScalars(colors);
  this->Output->GetPointData()->AddArray(radiance);
  this->Output->GetPointData()->AddArray(error);
  this->NumberOfPaths = static_cast<long long>(pixels) * samples;
  this->NumberOfEvents = events;
  this->LastRenderSeconds = Seconds(start);
  return this->Output;
}

void vtkMultiMaterialPathTracer::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SamplesPerPixel: " << this->SamplesPerPixel << "\n";
  os << indent << "MaxBounces: " << this->MaxBounces << "\n";
  os << indent << "SurfaceScattering: " << this->SurfaceScattering << "\n";
  os << indent << "PointLightRadius: " << this->PointLightRadius << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "LastRenderSeconds: " << this->LastRenderSeconds << "\n";
  os << indent << "NumberOfPaths: " << this->NumberOfPaths << "\n";
  os << indent << "NumberOfEvents: " << this->NumberOfEvents << "\n";
}
