#include "vtkMultiMaterialLights.h"

#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMatrix4x4.h"

#include <algorithm>
#include <cmath>

namespace mmv
{
namespace
{
glm::dvec3 TransformPoint(const vtkMatrix4x4* m, const double p[3])
{
  if (!m)
  {
    return { p[0], p[1], p[2] };
  }
  const double in[4] = { p[0], p[1], p[2], 1.0 };
  double out[4];
  const_cast<vtkMatrix4x4*>(m)->MultiplyPoint(in, out);
  const double w = out[3] != 0.0 ? out[3] : 1.0;
  return { out[0] / w, out[1] / w, out[2] / w };
}

glm::dvec3 SafeNormalize(const glm::dvec3& v, const glm::dvec3& fallback)
{
  const double len = glm::length(v);
  return len > 0.0 && std::isfinite(len) ? v / len : fallback;
}

/// Mean linear scale of a matrix's 3x3 part (cube root of |det|), 1 when
/// there is no matrix or it is degenerate.
double MeanScale(const vtkMatrix4x4* m)
{
  if (!m)
  {
    return 1.0;
  }
  double a[3][3];
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      a[i][j] = m->GetElement(i, j);
    }
  }
  const double det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
    a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
    a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
  const double s = std::cbrt(std::abs(det));
  return s > 0.0 && std::isfinite(s) ? s : 1.0;
}

std::string Describe(vtkLight* light, int index)
{
  return "light " + std::to_string(index) + " (" + light->GetClassName() + ")";
}

void Report(std::vector<std::string>* problems, const std::string& what)
{
  if (problems)
  {
    problems->push_back(what);
  }
}

/// vtkLight::AttenuationValues, or (1, 0, 0) when VTK's Phong would divide
/// by a negative, NaN or zero polynomial.
glm::dvec3 ValidAttenuation(vtkLight* light, int index, std::vector<std::string>* problems)
{
  const double* a = light->GetAttenuationValues();
  const glm::dvec3 att(a[0], a[1], a[2]);
  const bool finite = std::isfinite(att.x) && std::isfinite(att.y) && std::isfinite(att.z);
  if (!finite || att.x < 0.0 || att.y < 0.0 || att.z < 0.0 || (att.x + att.y + att.z) <= 0.0)
  {
    Report(problems,
      Describe(light, index) + ": AttenuationValues (" + std::to_string(att.x) + ", " +
        std::to_string(att.y) + ", " + std::to_string(att.z) +
        ") must be finite, >= 0 and not all 0; using (1, 0, 0), no falloff");
    return glm::dvec3(1.0, 0.0, 0.0);
  }
  return att;
}

double Strength(vtkLight* light)
{
  const double* c = light->GetDiffuseColor();
  return light->GetIntensity() * std::max({ c[0], c[1], c[2] });
}
}

bool IsLightActive(vtkLight* light)
{
  return light && light->GetSwitch() && light->GetIntensity() > 0.0 && Strength(light) > 0.0;
}

namespace
{
/// MakeLightSource for the light at `index` of its collection (for messages).
LightSource MakeIndexedLightSource(vtkLight* light, const vtkMatrix4x4* worldToObject,
  double radius, int index, std::vector<std::string>* problems)
{
  double position[3];
  double focal[3];
  light->GetTransformedPosition(position);
  light->GetTransformedFocalPoint(focal);
  const glm::dvec3 p = TransformPoint(worldToObject, position);
  const glm::dvec3 f = TransformPoint(worldToObject, focal);

  LightSource source;
  source.Radius = radius;
  if (!light->GetPositional())
  {
    source.Kind = DirectionalLight;
    // A light whose position equals its focal point has no direction; VTK
    // shines such lights along -z, so do the same.
    source.ToLight = SafeNormalize(p - f, glm::dvec3(0.0, 0.0, 1.0));
    return source;
  }
  source.Position = p;
  // VTK measures attenuation distances in eye space, a rigid image of world
  // space; object distances are world distances times the mean scale.
  const double s = MeanScale(worldToObject);
  const glm::dvec3 att = ValidAttenuation(light, index, problems);
  source.Attenuation = glm::dvec3(att.x, att.y / s, att.z / (s * s));
  const double cone = light->GetConeAngle();
  if (!(cone > 0.0 && cone < 180.0))
  {
    Report(problems,
      Describe(light, index) + ": ConeAngle " + std::to_string(cone) +
        " is not in (0, 180) degrees; it shines as a point light (no cone)");
    source.Kind = PointLight;
    return source;
  }
  // VTK's Phong: a cone (half-)angle above 90 degrees means no spot effect.
  if (cone > 90.0)
  {
    source.Kind = PointLight;
    return source;
  }
  source.Kind = SpotLight;
  source.SpotAxis = SafeNormalize(f - p, glm::dvec3(0.0, 0.0, -1.0));
  source.CosCone = std::cos(cone * M_PI / 180.0);
  source.SpotExponent = light->GetExponent();
  if (!(source.SpotExponent >= 0.0) || !std::isfinite(source.SpotExponent))
  {
    Report(problems,
      Describe(light, index) + ": Exponent " + std::to_string(source.SpotExponent) +
        " must be finite and >= 0; using 1");
    source.SpotExponent = 1.0;
  }
  return source;
}
}

LightSource MakeLightSource(vtkLight* light, const vtkMatrix4x4* worldToObject, double radius,
  std::vector<std::string>* problems)
{
  return MakeIndexedLightSource(light, worldToObject, radius, 0, problems);
}

double ValidPointLightRadius(double radius, std::string* why)
{
  if (std::isfinite(radius) && radius >= 0.0)
  {
    return radius;
  }
  if (why)
  {
    *why = "PointLightRadius " + std::to_string(radius) +
      " must be finite and >= 0; using 0 (the lights' AttenuationValues)";
  }
  return 0.0;
}

std::vector<ShadingLight> CollectLights(vtkLightCollection* lights,
  const vtkMatrix4x4* worldToObject, double radius, int maxLights, int* dropped,
  std::vector<std::string>* problems)
{
  std::vector<ShadingLight> result;
  std::vector<double> strength;
  if (lights)
  {
    vtkCollectionSimpleIterator it;
    lights->InitTraversal(it);
    int index = 0;
    while (vtkLight* light = lights->GetNextLight(it))
    {
      if (IsLightActive(light))
      {
        ShadingLight sl;
        sl.Source = MakeIndexedLightSource(light, worldToObject, radius, index, problems);
        const double* c = light->GetDiffuseColor();
        sl.Radiance = glm::dvec3(c[0], c[1], c[2]) * light->GetIntensity();
        sl.Index = index;
        result.push_back(sl);
        strength.push_back(Strength(light));
      }
      ++index;
    }
  }
  const int count = static_cast<int>(result.size());
  if (dropped)
  {
    *dropped = std::max(0, count - maxLights);
  }
  if (count <= maxLights)
  {
    return result;
  }
  // Keep the strongest, but in their original order so shading is stable.
  std::vector<int> order(count);
  for (int i = 0; i < count; ++i)
  {
    order[i] = i;
  }
  std::stable_sort(
    order.begin(), order.end(), [&](int a, int b) { return strength[a] > strength[b]; });
  order.resize(maxLights);
  std::sort(order.begin(), order.end());
  std::vector<ShadingLight> kept;
  for (int i : order)
  {
    kept.push_back(result[i]);
  }
  return kept;
}

//------------------------------------------------------------------------------
void OrderForIrradianceTextures(std::vector<ShadingLight>& lights, std::vector<int>& order)
{
  std::vector<int> now;
  for (const ShadingLight& light : lights)
  {
    now.push_back(light.Index);
  }
  std::vector<int> held = order;
  std::sort(held.begin(), held.end());
  std::sort(now.begin(), now.end());
  if (held == now)
  {
    std::vector<ShadingLight> kept;
    for (const int index : order)
    {
      kept.push_back(*std::find_if(lights.begin(), lights.end(),
        [index](const ShadingLight& light) { return light.Index == index; }));
    }
    lights.swap(kept);
  }
  else
  {
    const auto brightest = [](const ShadingLight& light) {
      return std::max({ light.Radiance.x, light.Radiance.y, light.Radiance.z });
    };
    std::stable_sort(lights.begin(), lights.end(),
      [&](const ShadingLight& a, const ShadingLight& b) { return brightest(a) < brightest(b); });
  }
  order.clear();
  for (const ShadingLight& light : lights)
  {
    order.push_back(light.Index);
  }
}

//------------------------------------------------------------------------------
std::vector<LightSource> IrradianceLightSources(
  const std::vector<ShadingLight>& lights, const int dims[3], bool strideDimLights)
{
  auto brightness = [](const ShadingLight& light)
  { return std::max(light.Radiance.x, std::max(light.Radiance.y, light.Radiance.z)); };
  double brightest = 0.0;
  for (const ShadingLight& light : lights)
  {
    brightest = std::max(brightest, brightness(light));
  }
  std::vector<LightSource> sources;
  for (const ShadingLight& light : lights)
  {
    sources.push_back(light.Source);
    sources.back().GridStride =
      strideDimLights ? LightGridStride(brightness(light), brightest, dims) : 1;
  }
  return sources;
}

} // namespace mmv
