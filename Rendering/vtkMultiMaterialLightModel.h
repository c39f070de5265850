/**
 * @file   vtkMultiMaterialLightModel.h
 * @brief  Light-source terms of Zhang & Ma eqs. 11-14, on the CPU.
 *
 * Each function mirrors the GLSL function of the same name in
 * Shaders/mmvLightModel.glsl line for line; the tests run both.
 *
 * Light kinds follow vtkLight: a non-positional light is directional
 * (rays toward the light run along position - focalPoint); a positional light
 * with ConeAngle >= 90 degrees is a point light; below 90 it is a spot light
 * whose ConeAngle is the half-angle of the cone (VTK's meaning; the paper's
 * phi is the full angle, so cos(phi/2) there is cos(ConeAngle) here).
 */
#ifndef vtkMultiMaterialLightModel_h
#define vtkMultiMaterialLightModel_h

#include <glm/glm.hpp>

namespace mmv
{

enum LightKind : int
{
  DirectionalLight = 0,
  PointLight = 1,
  SpotLight = 2
};

/// A light in world coordinates, as the irradiance estimation sees it.
/// Colour and intensity are not here: irradiance is stored without them.
struct LightSource
{
  LightKind Kind = DirectionalLight;
  glm::dvec3 Position{ 0.0 };      // point/spot: where the light is
  glm::dvec3 ToLight{ 0.0, 0.0, 1.0 }; // directional: unit vector toward the light
  glm::dvec3 SpotAxis{ 0.0, 0.0, -1.0 }; // spot: unit axis of the cone
  double CosCone = -1.0;           // spot: cos of the cone half-angle
  double Radius = 1.0;             // point/spot: epsilon of eq. 12
};

/// eq. 12: epsilon^2 / max(epsilon^2, d^2). Equal to 1 inside the radius;
/// the clamp keeps a light sitting on a voxel centre finite.
inline double mmvPointFalloff(double radius, double distance2)
{
  const double e2 = radius * radius;
  return e2 / glm::max(e2, distance2);
}

/// eq. 14: 1 inside the open cone, 0 outside (and on its edge).
inline double mmvSpotVisibility(const glm::dvec3& lightToPoint, const glm::dvec3& axis, double cosCone)
{
  const double len = glm::length(lightToPoint);
  if (len <= 0.0)
  {
    return 1.0; // at the apex: treat as lit, the falloff handles the rest
  }
  return glm::dot(lightToPoint / len, axis) > cosCone ? 1.0 : 0.0;
}

/// Direction and distance from point x toward the light. For directional
/// lights the distance is infinite (returned as a negative number).
inline glm::dvec3 mmvDirectionToLight(const LightSource& light, const glm::dvec3& x, double& distance)
{
  if (light.Kind == DirectionalLight)
  {
    distance = -1.0;
    return light.ToLight;
  }
  const glm::dvec3 d = light.Position - x;
  distance = glm::length(d);
  return distance > 0.0 ? d / distance : glm::dvec3(0.0, 0.0, 1.0);
}

/// Unshadowed part of I_k(x) (eqs. 11-13 without the transmittance).
inline double mmvLightGeometryTerm(const LightSource& light, const glm::dvec3& x)
{
  if (light.Kind == DirectionalLight)
  {
    return 1.0;
  }
  const glm::dvec3 lightToPoint = x - light.Position;
  double term = mmvPointFalloff(light.Radius, glm::dot(lightToPoint, lightToPoint));
  if (light.Kind == SpotLight)
  {
    term *= mmvSpotVisibility(lightToPoint, light.SpotAxis, light.CosCone);
  }
  return term;
}

} // namespace mmv

#endif
