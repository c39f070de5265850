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

/// eq. 12: epsilon^2 / max(epsilon^2, d^2), i.e. 1 within the radius and
/// epsilon^2 / d^2 beyond it; the clamp keeps a light sitting on a voxel
/// centre finite. Radius 0 is the limit of eq. 12 (1 at the light's own
/// position, 0 elsewhere) rather than 0/0: the formula is normalised at
/// d = epsilon, so an unnormalised 1/d^2 would not be its limit. Written as a
/// branch so that no 0/0 can occur; for radius > 0 it equals the formula.
inline double mmvPointFalloff(double radius, double distance2)
{
  const double e2 = radius * radius;
  return distance2 <= e2 ? 1.0 : e2 / distance2;
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

/// Unit direction and distance from point x toward the light. Directional
/// lights are infinitely far: distance -1. A point on a positional light gets
/// +z (any unit vector would do: its shadow ray has length 0).
inline glm::dvec3 mmvDirectionToLight(
  int kind, const glm::dvec3& position, const glm::dvec3& toLight, const glm::dvec3& x, double& distance)
{
  if (kind == DirectionalLight)
  {
    distance = -1.0;
    return toLight;
  }
  const glm::dvec3 d = position - x;
  distance = glm::length(d);
  return distance > 0.0 ? d / distance : glm::dvec3(0.0, 0.0, 1.0);
}

inline glm::dvec3 mmvDirectionToLight(const LightSource& light, const glm::dvec3& x, double& distance)
{
  return mmvDirectionToLight(light.Kind, light.Position, light.ToLight, x, distance);
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
