#include "vtkMultiMaterialReferenceRenderer.h"

#include "vtkMultiMaterialEnvironment.h"
#include "vtkSkyVisibility.h"

#include "vtkAbstractVolumeMapper.h"
#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkImageData.h"
#include "vtkIrradianceDiffusion.h"
#include "vtkLightCollection.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMatrix3x3.h"
#include "vtkMatrix4x4.h"
#include "vtkMultiMaterialCutaway.h"
#include "vtkMultiMaterialLights.h"
#include "vtkMultiMaterialParameters.h"
#include "vtkMultiMaterialPhaseFunction.h"
#include "vtkMultiMaterialShading.h"
#include "vtkMultiMaterialVolumeSampling.h"
#include "vtkObjectFactory.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkRenderer.h"
#include "vtkSMPTools.h"
#include "vtkUnsignedCharArray.h"
#include "vtkVolume.h"
#include "vtkVolumeMapper.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkMultiMaterialReferenceRenderer);

namespace
{
using glm::dvec3;
using glm::dvec4;

// Fine enough that linear interpolation between entries is indistinguishable
// from evaluating the piecewise-linear functions directly.
constexpr int TableSize = 65536;

// Every transfer function, tabulated over the scalar range.
struct TransferTables
{
  double Min = 0.0;
  double Scale = 1.0;        // table index per data unit
  std::vector<double> Color; // rgb
  std::vector<double> Mu;    // extinction per object unit
  std::vector<double> Sigma; // shadow extinction, attenuation * mu
  // The selective extinction c_t mu (-ln T) per channel, 3 per value; empty
  // when every transmission colour is white (grey shadows).
  std::vector<double> SigmaTint;
  std::vector<double> Material; // the material parameters

  // Entry index and weight of data value s.
  void Locate(double s, int& i, double& w) const
  {
    const double x = std::min(std::max((s - this->Min) * this->Scale, 0.0), TableSize - 1.0);
    i = std::min(static_cast<int>(x), TableSize - 2);
    w = x - i;
  }
  static double Lerp(const std::vector<double>& t, int stride, int c, int i, double w)
  {
    return (1.0 - w) * t[i * stride + c] + w * t[(i + 1) * stride + c];
  }
};

using Field = mmv::ScalarField;

// Everything a ray needs, shared read-only by the threads.
struct Scene
{
  Field Data;
  TransferTables Tables;
  double RangeMin = 0.0;
  double InverseRange = 1.0; // normalised value per data unit
  dvec3 Origin{ 0.0 };
  glm::dmat3 IndexToObject{ 1.0 };
  glm::dmat3 ObjectToIndex{ 1.0 };
  glm::dmat3 GradientToObject{ 1.0 }; // (ObjectToIndex)^T: gradients are covectors
  double PrimaryStep = 1.0;
  double ShadowStep = 1.0;
  double MaxOpticalDepth = 13.8;
  double SurfaceEqualShare = 1.0; // mmv::SurfaceEqualShareGradientPerVoxel per object unit
  std::vector<mmv::ShadingLight> Lights;
  // The same lights as mmvShadeSample takes them.
  std::vector<mmv::LightSource> Sources;
  std::vector<dvec3> Radiances;
  mmv::IndexCutaway Cut; // in data index space: removed, as VTK's ray caster does
  // Per light: diffused minus direct irradiance at the voxels (empty: none).
  std::vector<std::vector<float>> ScatteringDelta;
  bool Reflection = false;
  const vtkMultiMaterialEnvironment* Environment = nullptr; // c_r
  bool ReflectionVisibility = false;                        // I(x, w_r) by a shadow ray along w_r
  // The environment light: S0 and S1 at the data points, one array each,
  // and the sky's radiance mean + slope w (empty arrays: off).
  std::vector<double> SkyMoments[mmv::SkyMomentsPerVoxel];
  dvec3 SkyMean{ 0.0 };
  glm::dmat3 SkySlope{ 0.0 };
  double ReflectionOffset = 0.0; // object units along n (self-occlusion)

  dvec3 ToIndex(const dvec3& x) const { return this->ObjectToIndex * (x - this->Origin); }

  // Object-space distances [t0, t1] where the line x + t d (d in object
  // space) is inside the data box; false when it misses.
  bool Clip(const dvec3& x, const dvec3& d, double& t0, double& t1) const
  {
    return mmv::ClipToIndexBox(this->ToIndex(x), this->ObjectToIndex * d, this->Data.Dims, t0, t1);
  }

  double Extinction(double s, int& i, double& w) const
  {
    this->Tables.Locate(s, i, w);
    return TransferTables::Lerp(this->Tables.Mu, 1, 0, i, w);
  }

  // Light k's transmittance from object point x (eqs. 9-10 by midpoint rule),
  // times its geometry term; 0 outside a spot cone.
  // With `tint`: also the tint K per channel of a non-white transmission
  // colour (vtkMultiMaterialParameters.h), per sample like the grey part,
  // at full resolution (the GPU stores it at half: the compression the
  // comparisons measure); (1, 1, 1) when grey.
  double DirectIrradiance(
    const mmv::LightSource& light, const dvec3& x, dvec3* tint = nullptr) const
  {
    if (tint)
    {
      *tint = dvec3(1.0);
    }
    const double geometry = mmv::mmvLightGeometryTerm(light, x);
    if (geometry <= 0.0)
    {
      return 0.0;
    }
    double distance = 0.0;
    const dvec3 dir = mmv::mmvDirectionToLight(light, x, distance);
    double t0 = 0.0;
    double t1 = std::numeric_limits<double>::max();
    if (distance >= 0.0)
    {
      t1 = distance;
    }
    if (!this->Clip(x, dir, t0, t1))
    {
      return geometry; // already on the boundary, heading out
    }
    const int n = std::max(1, static_cast<int>(std::ceil((t1 - t0) / this->ShadowStep - 1e-9)));
    const double h = (t1 - t0) / n;
    const dvec3 p0 = this->ToIndex(x);
    const dvec3 q = this->ObjectToIndex * dir;
    double depth = 0.0;
    dvec3 tintDepth(0.0);
    const bool tinted = tint && !this->Tables.SigmaTint.empty();
    for (int m = 0; m < n && depth < this->MaxOpticalDepth; ++m)
    {
      const dvec3 pm = p0 + (t0 + (m + 0.5) * h) * q;
      if (mmv::mmvIsCut(this->Cut, pm))
      {
        continue; // cut away: casts no shadow
      }
      const double s = this->Data.Sample(pm);
      int i;
      double w;
      this->Tables.Locate(s, i, w);
      depth += h * TransferTables::Lerp(this->Tables.Sigma, 1, 0, i, w);
      for (int c = 0; tinted && c < 3; ++c)
      {
        tintDepth[c] += h * TransferTables::Lerp(this->Tables.SigmaTint, 3, c, i, w);
      }
    }
    if (tinted)
    {
      *tint = glm::exp(-tintDepth);
    }
    return geometry * std::exp(-depth);
  }

  // Normalised-value gradient in object space at continuous index p,
  // central differences of one voxel like mmvGradient().
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

  // mmvShadeSegment(): radiance of one segment at object point x.
  dvec3 Shade(const dvec3& x, const dvec3& p, double s, const dvec4& segment, const dvec3& v,
    vtkIdType& shadowRays) const
  {
    int i;
    double w;
    this->Tables.Locate(s, i, w);
    double m[mmv::MaterialParameterCount];
    for (int c = 0; c < mmv::MaterialParameterCount; ++c)
    {
      m[c] = TransferTables::Lerp(this->Tables.Material, mmv::MaterialParameterCount, c, i, w);
    }
    const dvec4 material(m[mmv::Ambient], m[mmv::Diffuse], m[mmv::Specular], m[mmv::Shininess]);
    const dvec3 gradient = this->Gradient(p);
    const double gradientLength = glm::length(gradient);
    dvec3 n = gradientLength > 0.0 ? -gradient / gradientLength : dvec3(0.0);
    n = glm::dot(n, v) < 0.0 ? -n : n; // two-sided
    const double surface = mmv::mmvSurfaceShare(gradientLength, this->SurfaceEqualShare);

    const int count = static_cast<int>(this->Lights.size());
    double irradiance[mmv::MaxLights] = {};
    dvec3 tint[mmv::MaxLights];
    for (int k = 0; k < count; ++k)
    {
      irradiance[k] = this->DirectIrradiance(this->Sources[k], x, &tint[k]);
      ++shadowRays;
      if (!this->ScatteringDelta.empty())
      {
        irradiance[k] =
          std::max(0.0, irradiance[k] + this->Data.SampleArray(this->ScatteringDelta[k].data(), p));
      }
    }
    const double reflection = this->Reflection ? m[mmv::Reflection] : 0.0;
    const dvec3 environment = reflection > 0.0 ? this->Reflected(x, n, v) : dvec3(0.0);
    // A tinted light arrives with its radiance times its tint, as the ray
    // cast's mmvFetchTints makes it (Shaders/mmvTint.glsl).
    dvec3 arriving[mmv::MaxLights];
    const bool tinted = !this->Tables.SigmaTint.empty();
    for (int k = 0; tinted && k < count; ++k)
    {
      arriving[k] = this->Radiances[k] * tint[k];
    }
    const dvec3* radiances = tinted ? arriving : this->Radiances.data();
    const bool sky = !this->SkyMoments[0].empty();
    dvec3 radiance =
      mmv::mmvShadeSample(material, m[mmv::Anisotropy], reflection, m[mmv::Emission], segment, x, n,
        v, surface, this->Sources.data(), radiances, irradiance, count, environment, sky);
    if (sky)
    {
      dvec4 moments;
      for (int c = 0; c < mmv::SkyMomentsPerVoxel; ++c)
      {
        moments[c] = this->Data.SampleArray(this->SkyMoments[c].data(), p);
      }
      radiance +=
        mmv::mmvSkyRadiance(material, segment, n, surface, moments, this->SkyMean, this->SkySlope);
    }
    return radiance;
  }

  // Eq. 17's I(x, w_r) c_r(w_r) (Shaders/mmvReflection.glsl): the
  // visibility is a shadow ray toward a directional light along w_r,
  // started off the surface along n.
  dvec3 Reflected(const dvec3& x, const dvec3& n, const dvec3& v) const
  {
    const dvec3 mirrored = glm::reflect(-v, n);
    dvec3 c = this->Environment->Lookup(mirrored);
    if (this->ReflectionVisibility)
    {
      mmv::LightSource along;
      along.Kind = mmv::DirectionalLight;
      along.ToLight = mirrored;
      c *= this->DirectIrradiance(along, x + this->ReflectionOffset * n);
    }
    return c;
  }

  // Front-to-back composite of the ray x + t d, t in [tNear, tFar]; rgb and
  // alpha of the volume (premultiplied).
  dvec4 Trace(const dvec3& x, const dvec3& d, double tNear, double tFar, double minTransmittance,
    vtkIdType& samples, vtkIdType& shadowRays) const
  {
    dvec4 result(0.0);
    double t0 = tNear;
    double t1 = tFar;
    if (!this->Clip(x, d, t0, t1))
    {
      return result;
    }
    const int n = std::max(1, static_cast<int>(std::ceil((t1 - t0) / this->PrimaryStep - 1e-9)));
    const double h = (t1 - t0) / n;
    const dvec3 v = -d;
    double transmittance = 1.0;
    dvec3 color(0.0);
    for (int m = 0; m < n && transmittance >= minTransmittance; ++m)
    {
      const dvec3 xm = x + (t0 + (m + 0.5) * h) * d;
      const dvec3 p = this->ToIndex(xm);
      if (mmv::mmvIsCut(this->Cut, p))
      {
        continue;
      }
      const double s = this->Data.Sample(p);
      ++samples;
      int i;
      double w;
      this->Tables.Locate(s, i, w);
      const double mu = TransferTables::Lerp(this->Tables.Mu, 1, 0, i, w);
      if (mu <= 0.0)
      {
        continue;
      }
      const double alpha = -std::expm1(-mu * h);
      const dvec3 c(TransferTables::Lerp(this->Tables.Color, 3, 0, i, w),
        TransferTables::Lerp(this->Tables.Color, 3, 1, i, w),
        TransferTables::Lerp(this->Tables.Color, 3, 2, i, w));
      const dvec4 segment(c * alpha, alpha);
      color += transmittance * this->Shade(xm, p, s, segment, v, shadowRays);
      transmittance *= 1.0 - alpha;
    }
    return dvec4(color, 1.0 - transmittance);
  }
};

double Seconds(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}
}

vtkMultiMaterialReferenceRenderer::vtkMultiMaterialReferenceRenderer() = default;
vtkMultiMaterialReferenceRenderer::~vtkMultiMaterialReferenceRenderer() = default;

void vtkMultiMaterialReferenceRenderer::SetCutawayMapper(vtkVolumeMapper* mapper)
{
  if (this->CutawayMapper != mapper)
  {
    this->CutawayMapper = mapper;
    this->Modified();
  }
}

vtkVolumeMapper* vtkMultiMaterialReferenceRenderer::GetCutawayMapper()
{
  return this->CutawayMapper;
}

vtkImageData* vtkMultiMaterialReferenceRenderer::RenderToImage(vtkRenderer* ren, vtkVolume* volume)
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
  this->SetCutawayMapper(vtkVolumeMapper::SafeDownCast(volume->GetMapper()));
  if (mmvMapper)
  {
    this->SetMultipleScattering(mmvMapper->Illumination.MultipleScattering);
    this->SetPointLightRadius(mmvMapper->Illumination.PointLightRadius);
    this->SetReflectionSource(mmvMapper->Illumination.ReflectionSource);
    this->SetReflectionVisibility(mmvMapper->Illumination.ReflectionVisibility);
    this->SetEnvironmentLighting(mmvMapper->Illumination.EnvironmentLighting);
  }
  const int* size = ren->GetSize();
  return this->Render(ren, size[0], size[1]);
}

namespace
{
/// The transfer functions at TableSize values over `range`: colour,
/// extinction, attenuated extinction and every material parameter.
void TabulateTransferFunctions(vtkVolumeProperty* property, vtkMaterialTransferFunction* materials,
  const double range[2], TransferTables& tables)
{
  tables.Min = range[0];
  tables.Scale = (TableSize - 1) / (range[1] - range[0]);
  mmv::TabulateColor(property, range, TableSize, tables.Color);
  std::vector<double> alpha(TableSize);
  property->GetScalarOpacity(0)->GetTable(range[0], range[1], TableSize, alpha.data());
  const double unitDistance = property->GetScalarOpacityUnitDistance(0);
  tables.Mu.resize(TableSize);
  tables.Sigma.resize(TableSize);
  const bool tinted = materials && materials->HasChromaticTransmission();
  tables.SigmaTint.assign(tinted ? 3 * TableSize : 0, 0.0);
  tables.Material.resize(static_cast<size_t>(mmv::MaterialParameterCount) * TableSize);
  for (int i = 0; i < TableSize; ++i)
  {
    const double s = range[0] + (range[1] - range[0]) * i / (TableSize - 1.0);
    double* m = &tables.Material[static_cast<size_t>(mmv::MaterialParameterCount) * i];
    if (materials)
    {
      materials->Evaluate(s, m);
    }
    else
    {
      for (int c = 0; c < mmv::MaterialParameterCount; ++c)
      {
        m[c] = mmv::MaterialParameterTable[c].Default;
      }
    }
    tables.Mu[i] = mmv::ExtinctionFromOpacity(alpha[i], unitDistance);
    tables.Sigma[i] = m[mmv::Attenuation] * tables.Mu[i];
    for (int c = 0; tinted && c < 3; ++c)
    {
      tables.SigmaTint[3 * i + c] =
        tables.Sigma[i] * mmv::SelectiveAbsorption(m[mmv::TransmissionR + c]);
    }
  }
}

/// Sampling steps and ray-termination depth, from the data's spacing.
void SetUpSampling(Scene& scene, const double range[2], const double spacing[3],
  double sampleDistance, double shadowSampleDistance, double minTransmittance)
{
  scene.RangeMin = range[0];
  scene.InverseRange = 1.0 / (range[1] - range[0]);
  scene.ObjectToIndex = glm::inverse(scene.IndexToObject);
  scene.GradientToObject = glm::transpose(scene.ObjectToIndex);
  const double smallestSpacing =
    std::min({ std::abs(spacing[0]), std::abs(spacing[1]), std::abs(spacing[2]) });
  scene.PrimaryStep = sampleDistance > 0.0 ? sampleDistance : smallestSpacing / 8.0;
  scene.ShadowStep = shadowSampleDistance > 0.0 ? shadowSampleDistance : smallestSpacing / 8.0;
  scene.SurfaceEqualShare = mmv::SurfaceEqualShareGradientPerVoxel / smallestSpacing;
  scene.MaxOpticalDepth =
    minTransmittance > 0.0 ? -std::log(minTransmittance) : std::numeric_limits<double>::infinity();
  scene.ReflectionOffset = mmv::ReflectionVisibilityOffsetVoxels * smallestSpacing;
}

/// The renderer's lights and the mapper's cut in object space; what had to
/// be replaced goes to `problems`.
void PlaceLights(Scene& scene, vtkRenderer* ren, vtkMatrix4x4* worldToObject, vtkImageData* input,
  vtkVolumeMapper* cutawayMapper, double radius, std::vector<std::string>& problems)
{
  int dims[3];
  input->GetDimensions(dims);
  scene.Cut = mmv::ToIndexSpace(
    mmv::MakeCutaway(cutawayMapper, worldToObject), mmv::MakeIrradianceGrid(input, dims));
  scene.Lights =
    mmv::CollectLights(ren->GetLights(), worldToObject, radius, mmv::MaxLights, nullptr, &problems);
  for (const mmv::ShadingLight& light : scene.Lights)
  {
    scene.Sources.push_back(light.Source);
    scene.Radiances.push_back(light.Radiance);
  }
}

/// c_r of eq. 17 from the renderer's environment, and whether I(x, w_r) is
/// estimated: as the GPU, per sample or per irradiance voxel alike (the same
/// transmittance along w_r), and only with a light (the GPU marches the
/// irradiance pass's pre-filtered volume).
void PlaceEnvironment(Scene& scene, vtkRenderer* ren, vtkMatrix4x4* objectToWorld,
  vtkMultiMaterialEnvironment* environment, int source, int visibility,
  std::vector<std::string>& problems)
{
  environment->Update(ren, objectToWorld, source, &problems);
  scene.Environment = environment;
  scene.ReflectionVisibility = visibility != mmv::UnoccludedReflections && !scene.Lights.empty();
}

/// The diffusion strength of every data voxel: the material's s where the
/// opacity is > 0, else 0 (as the irradiance filter). False: nothing
/// scatters.
bool ScatteringStrengths(
  const Scene& scene, const std::vector<double>& values, std::vector<float>& strength)
{
  strength.assign(values.size(), 0.0f);
  bool any = false;
  for (size_t v = 0; v < values.size(); ++v)
  {
    int i;
    double w;
    if (scene.Extinction(values[v], i, w) > 0.0)
    {
      strength[v] = static_cast<float>(TransferTables::Lerp(
        scene.Tables.Material, mmv::MaterialParameterCount, mmv::Scattering, i, w));
      any = any || strength[v] > 0.0f;
    }
  }
  return any;
}

/// Multiple scattering: per light, the diffused minus the direct irradiance
/// of every voxel (the reference renderer adds it back). False: nothing
/// scatters.
bool ComputeScatteringDeltas(Scene& scene, const std::vector<double>& values, bool exponential,
  std::atomic<vtkIdType>& shadowRays)
{
  const vtkIdType count = static_cast<vtkIdType>(values.size());
  std::vector<float> strength;
  if (!ScatteringStrengths(scene, values, strength))
  {
    return false;
  }
  const int* dims = scene.Data.Dims;
  const double voxel[3] = { 1.0, 1.0, 1.0 };
  for (const mmv::ShadingLight& light : scene.Lights)
  {
    std::vector<float> direct(count);
    vtkSMPTools::For(0, count,
      [&](vtkIdType first, vtkIdType last)
      {
        for (vtkIdType v = first; v < last; ++v)
        {
          const dvec3 p(v % dims[0], (v / dims[0]) % dims[1], v / (vtkIdType(dims[0]) * dims[1]));
          direct[v] = static_cast<float>(
            scene.DirectIrradiance(light.Source, scene.Origin + scene.IndexToObject * p));
        }
        shadowRays += last - first;
      });
    std::vector<float> diffused = direct;
    mmv::DiffusionSettings settings;
    settings.Exponential = exponential;
    mmv::DiffuseIrradiance(dims, voxel, strength.data(), diffused.data(), settings);
    for (vtkIdType v = 0; v < count; ++v)
    {
      diffused[v] -= direct[v];
    }
    scene.ScatteringDelta.push_back(std::move(diffused));
  }
  return true;
}

/// One ray per pixel centre (rows in parallel): radiance over the
/// renderer's background (gradient bottom to top, as VTK draws it) into
/// `out` (RGB doubles) and `bytes` (clamped RGB bytes).
void TracePixels(const Scene& scene, vtkRenderer* ren, vtkMatrix4x4* ndcToObject, int width,
  int height, double minTransmittance, double* out, unsigned char* bytes,
  std::atomic<vtkIdType>& samples, std::atomic<vtkIdType>& shadowRays)
{
  const double* bg1 = ren->GetBackground();
  const double* bg2 = ren->GetGradientBackground() ? ren->GetBackground2() : bg1;
  const dvec3 background1(bg1[0], bg1[1], bg1[2]);
  const dvec3 background2(bg2[0], bg2[1], bg2[2]);
  vtkSMPTools::For(0, height, 1,
    [&](vtkIdType firstRow, vtkIdType lastRow)
    {
      vtkIdType localSamples = 0;
      vtkIdType localShadowRays = 0;
      for (vtkIdType j = firstRow; j < lastRow; ++j)
      {
        const double y = (j + 0.5) / height * 2.0 - 1.0;
        const dvec3 background = glm::mix(background1, background2, (j + 0.5) / height);
        for (int i = 0; i < width; ++i)
        {
          const double x = (i + 0.5) / width * 2.0 - 1.0;
          dvec3 nearPoint, direction;
          double length;
          mmv::PixelRay(ndcToObject, x, y, nearPoint, direction, length);
          dvec4 c(0.0);
          if (length > 0.0)
          {
            c = scene.Trace(
              nearPoint, direction, 0.0, length, minTransmittance, localSamples, localShadowRays);
          }
          const dvec3 rgb = dvec3(c) + (1.0 - c.w) * background;
          const vtkIdType id = j * width + i;
          for (int k = 0; k < 3; ++k)
          {
            out[3 * id + k] = rgb[k];
            bytes[3 * id + k] =
              static_cast<unsigned char>(std::lround(std::min(std::max(rgb[k], 0.0), 1.0) * 255.0));
          }
        }
      }
      samples += localSamples;
      shadowRays += localShadowRays;
    });
}
}

namespace
{
/// The environment light (vtkMultiMaterialSky's model): the sky's radiance
/// fitted as mean + slope w, and its visibility moments at every data point
/// from the shadows' extinction there.
void PlaceSky(Scene& scene, vtkRenderer* ren, vtkMatrix4x4* objectToWorld,
  vtkMultiMaterialEnvironment* environment, vtkImageData* image, const std::vector<double>& values,
  double strength, int source, const mmv::DiffusionSettings* diffusion,
  std::vector<std::string>& problems)
{
  problems.emplace_back();
  strength = mmv::ValidEnvironmentLighting(strength, &problems.back());
  if (strength == 0.0)
  {
    return;
  }
  environment->Update(ren, objectToWorld, source, &problems);
  environment->FitLinear(scene.SkyMean, scene.SkySlope);
  scene.SkyMean *= strength;
  scene.SkySlope *= strength;
  if (glm::length(scene.SkyMean) <= 0.0)
  {
    return; // a black sky lights nothing
  }
  const mmv::IrradianceGrid grid = mmv::MakeIrradianceGrid(image, scene.Data.Dims);
  std::vector<float> sigma(values.size());
  for (size_t v = 0; v < values.size(); ++v)
  {
    int i;
    double w;
    scene.Tables.Locate(values[v], i, w);
    sigma[v] = static_cast<float>(TransferTables::Lerp(scene.Tables.Sigma, 1, 0, i, w));
  }
  std::vector<float> moments;
  mmv::ComputeSkyVisibility(
    grid, sigma.data(), mmv::SkyDirections(mmv::SkyDirectionCount), moments);
  // Multiple scattering spreads the sky's light as the lights': each moment
  // is diffused (the diffusion is linear, so any sky colour still shades).
  std::vector<float> scattering;
  if (diffusion && ScatteringStrengths(scene, values, scattering))
  {
    const double voxel[3] = { 1.0, 1.0, 1.0 };
    mmv::DiffuseSkyMoments(scene.Data.Dims, voxel, scattering.data(), moments, *diffusion);
  }
  for (int c = 0; c < mmv::SkyMomentsPerVoxel; ++c)
  {
    scene.SkyMoments[c].resize(values.size());
    for (size_t v = 0; v < values.size(); ++v)
    {
      scene.SkyMoments[c][v] = moments[v * mmv::SkyMomentsPerVoxel + c];
    }
  }
}
}

vtkImageData* vtkMultiMaterialReferenceRenderer::Render(vtkRenderer* ren, int width, int height)
{
  const auto start = std::chrono::steady_clock::now();
  vtkImageData* image = this->Input;
  if (!this->CheckRenderInputs(ren, width, height))
  {
    return nullptr;
  }
  Scene scene;
  std::vector<double> values;
  double range[2];
  const std::string why =
    mmv::LoadScalarField(image, values, scene.Data, range, scene.Origin, scene.IndexToObject);
  if (!why.empty())
  {
    vtkErrorMacro(<< why);
    return nullptr;
  }
  SetUpSampling(scene, range, image->GetSpacing(), this->SampleDistance, this->ShadowSampleDistance,
    this->MinimumTransmittance);
  vtkMaterialTransferFunction* materials = this->Materials;
  TabulateTransferFunctions(this->Property, materials, range, scene.Tables);

  // Lights, cut and environment in object space.
  vtkNew<vtkMatrix4x4> objectToWorld;
  if (this->Matrix)
  {
    objectToWorld->DeepCopy(this->Matrix);
  }
  vtkNew<vtkMatrix4x4> worldToObject;
  vtkMatrix4x4::Invert(objectToWorld, worldToObject);
  std::vector<std::string> problems;
  problems.emplace_back(); // the radius's, if any
  const double radius = mmv::ValidPointLightRadius(this->PointLightRadius, &problems.back());
  PlaceLights(scene, ren, worldToObject, image, this->CutawayMapper, radius, problems);
  vtkNew<vtkMultiMaterialEnvironment> environment;
  scene.Reflection =
    materials && materials->GetSize() > 0 && materials->GetMaximum(mmv::Reflection) > 0.0;
  if (scene.Reflection)
  {
    PlaceEnvironment(scene, ren, objectToWorld, environment, this->ReflectionSource,
      this->ReflectionVisibility, problems);
  }
  vtkNew<vtkMultiMaterialEnvironment> sky;
  mmv::DiffusionSettings skyDiffusion;
  skyDiffusion.Exponential = this->ExponentialDiffusion;
  PlaceSky(scene, ren, objectToWorld, sky, image, values, this->EnvironmentLighting,
    this->ReflectionSource, this->MultipleScattering ? &skyDiffusion : nullptr, problems);
  for (const std::string& problem : problems)
  {
    if (!problem.empty())
    {
      vtkWarningMacro(<< problem);
    }
  }

  // Multiple scattering: diffuse the direct irradiance of every voxel.
  this->ScatteringApplied = false;
  this->LastScatteringSeconds = 0.0;
  std::atomic<vtkIdType> shadowRays(0);
  if (this->MultipleScattering && materials && materials->GetMaximum(mmv::Scattering) > 0.0 &&
    !scene.Lights.empty())
  {
    const auto scatterStart = std::chrono::steady_clock::now();
    this->ScatteringApplied =
      ComputeScatteringDeltas(scene, values, this->ExponentialDiffusion, shadowRays);
    this->LastScatteringSeconds = Seconds(scatterStart);
  }

  // Camera: unproject each pixel centre from the near to the far plane.
  vtkNew<vtkMatrix4x4> ndcToObject;
  mmv::NDCToObject(ren->GetActiveCamera(), width, height, worldToObject, ndcToObject);
  const vtkIdType pixels = static_cast<vtkIdType>(width) * height;
  vtkNew<vtkDoubleArray> radiance;
  radiance->SetName("Radiance");
  radiance->SetNumberOfComponents(3);
  radiance->SetNumberOfTuples(pixels);
  vtkNew<vtkUnsignedCharArray> colors;
  colors->SetName("Colors");
  colors->SetNumberOfComponents(3);
  colors->SetNumberOfTuples(pixels);
  std::atomic<vtkIdType> samples(0);
  TracePixels(scene, ren, ndcToObject, width, height, this->MinimumTransmittance,
    radiance->GetPointer(0), colors->GetPointer(0), samples, shadowRays);

  this->Output = vtkSmartPointer<vtkImageData>::New();
  this->Output->SetDimensions(width, height, 1);
  this->Output->GetPointData()->SetScalars(colors);
  this->Output->GetPointData()->AddArray(radiance);
  this->NumberOfSamples = samples;
  this->NumberOfShadowRays = shadowRays;
  this->LastRenderSeconds = Seconds(start);
  return this->Output;
}

void vtkMultiMaterialReferenceRenderer::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SampleDistance: " << this->SampleDistance << "\n";
  os << indent << "ShadowSampleDistance: " << this->ShadowSampleDistance << "\n";
  os << indent << "PointLightRadius: " << this->PointLightRadius << "\n";
  os << indent << "MultipleScattering: " << this->MultipleScattering << "\n";
  os << indent << "ExponentialDiffusion: " << this->ExponentialDiffusion << "\n";
  os << indent << "MinimumTransmittance: " << this->MinimumTransmittance << "\n";
  os << indent << "ReflectionSource: " << this->ReflectionSource << "\n";
  os << indent << "ReflectionVisibility: " << this->ReflectionVisibility << "\n";
  os << indent << "EnvironmentLighting: " << this->EnvironmentLighting << "\n";
  os << indent << "LastRenderSeconds: " << this->LastRenderSeconds << "\n";
  os << indent << "NumberOfSamples: " << this->NumberOfSamples << "\n";
  os << indent << "NumberOfShadowRays: " << this->NumberOfShadowRays << "\n";
}
