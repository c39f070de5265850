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

LightSource MakeLightSource(vtkLight* light, const vtkMatrix4x4* worldToObject, double radius)
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
  // VTK: a cone angle of 90 degrees or more means no spot effect.
  if (light->GetConeAngle() >= 90.0)
  {
    source.Kind = PointLight;
    return source;
  }
  source.Kind = SpotLight;
  source.SpotAxis = SafeNormalize(f - p, glm::dvec3(0.0, 0.0, -1.0));
  source.CosCone = std::cos(light->GetConeAngle() * M_PI / 180.0);
  return source;
}

std::vector<ShadingLight> CollectLights(vtkLightCollection* lights,
  const vtkMatrix4x4* worldToObject, double radius, int maxLights, int* dropped)
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
        sl.Source = MakeLightSource(light, worldToObject, radius);
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
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return strength[a] > strength[b]; });
  order.resize(maxLights);
  std::sort(order.begin(), order.end());
  std::vector<ShadingLight> kept;
  for (int i : order)
  {
    kept.push_back(result[i]);
  }
  return kept;
}

} // namespace mmv
