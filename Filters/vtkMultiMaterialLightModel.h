/**
 * @file   vtkMultiMaterialLightModel.h
 * @brief  Light-source terms (the unshadowed part of I_k(x), Zhang & Ma eqs.
 *         11-14, with VTK's light conventions), on the CPU.
 *
 * Each function mirrors the GLSL function of the same name in
 * Shaders/mmvLightModel.glsl line for line; TestShaderMirror runs both.
 * The irradiance pass, the CPU irradiance filter and the reference renderer
 * all evaluate lights only through these functions.
 *
 * Light kinds follow vtkLight and VTK 9.2's Phong (vtkVolumeShaderComposer,
 * lighting complexity 3): a non-positional light is directional (rays toward
 * the light run along position - focalPoint); a positional light with
 * ConeAngle > 90 degrees is a point light; up to 90 it is a spot light whose
 * ConeAngle is the half-angle of the cone (the paper's phi is the full angle,
 * so cos(phi/2) there is cos(ConeAngle) here).
 *
 * Distance falloff of point and spot lights:
 *  - Radius == 0 (default): VTK's AttenuationValues (c0, c1, c2):
 *    1 / (c0 + c1 d + c2 d^2); the vtkLight default (1, 0, 0) means none.
 *  - Radius > 0: the paper's eq. 12, epsilon^2 / max(epsilon^2, d^2).
 * Spot cone: 1 / 0 inside / outside the cone (VTK: inside includes the edge),
 * times VTK's angular falloff cos(angle to the axis)^Exponent inside; an
 * Exponent of 0 is the hard cone of eq. 14.
 */
#ifndef vtkMultiMaterialLightModel_h
#define vtkMultiMaterialLightModel_h

#include "vtkMultiMaterialParameters.h" // LightKind, MinAttenuationDenominator

#include <glm/glm.hpp>

#include <cmath>

namespace mmv
{

/// A light in object coordinates, as the irradiance estimation sees it.
/// Colour and intensity are not here: irradiance is stored without them.
/// The shaders get it through the light uniforms of
/// vtkMultiMaterialLightUniforms.h.
struct LightSource
{
  LightKind Kind = DirectionalLight;
  glm::dvec3 Position{ 0.0 };            // point/spot: where the light is
  glm::dvec3 ToLight{ 0.0, 0.0, 1.0 };   // directional: unit vector toward the light
  glm::dvec3 SpotAxis{ 0.0, 0.0, -1.0 }; // spot: unit axis of the cone
  double CosCone = -1.0;                 // spot: cos of the cone half-angle
  double SpotExponent = 0.0;             // spot: vtkLight::Exponent (0: hard cone)
  /// point/spot: vtkLight::AttenuationValues (constant, linear, quadratic),
  /// with distances in object units; used when Radius == 0.
  glm::dvec3 Attenuation{ 1.0, 0.0, 0.0 };
  double Radius = 0.0; // point/spot: epsilon of eq. 12; 0: Attenuation
  /// The GPU estimates the light's transmittance on every GridStride-th
  /// point of the irradiance grid (mmv::LightGridStride) and interpolates it.
  int GridStride = 1;

  bool operator==(const LightSource& o) const
  {
    return Kind == o.Kind && Position == o.Position && ToLight == o.ToLight &&
      SpotAxis == o.SpotAxis && CosCone == o.CosCone && SpotExponent == o.SpotExponent &&
      Attenuation == o.Attenuation && Radius == o.Radius && GridStride == o.GridStride;
  }
  bool operator!=(const LightSource& o) const { return !(*this == o); }
};

/// eq. 12: epsilon^2 / max(epsilon^2, d^2), i.e. 1 within the radius and
/// epsilon^2 / d^2 beyond it; the clamp keeps a light sitting on a voxel
/// centre finite. Written as a branch so that no 0/0 can occur.
inline double mmvPointFalloff(double radius, double distance2)
{
  const double e2 = radius * radius;
  return distance2 <= e2 ? 1.0 : e2 / distance2;
}

/// VTK's Phong: 1 / (c0 + c1 d + c2 d^2), the polynomial clamped below at
/// MinAttenuationDenominator (coefficients are >= 0, see MakeLightSource).
inline double mmvAttenuationFalloff(const glm::dvec3& attenuation, double distance2)
{
  const double d = std::sqrt(distance2);
  const double p = attenuation.x + attenuation.y * d + attenuation.z * distance2;
  return 1.0 / (p > MinAttenuationDenominator ? p : MinAttenuationDenominator);
}

/// The distance falloff of a point or spot light: eq. 12 when radius > 0,
/// else VTK's attenuation.
inline double mmvDistanceFalloff(double radius, const glm::dvec3& attenuation, double distance2)
{
  return radius > 0.0 ? mmvPointFalloff(radius, distance2)
                      : mmvAttenuationFalloff(attenuation, distance2);
}

/// Spot cone as VTK's Phong: cos^exponent of the angle to the axis inside the
/// cone (edge included), 0 outside; exponent 0 is the hard cone of eq. 14.
inline double mmvSpotFactor(
  const glm::dvec3& lightToPoint, const glm::dvec3& axis, double cosCone, double exponent)
{
  const double len = glm::length(lightToPoint);
  if (len <= 0.0)
  {
    return 1.0; // at the apex: treat as lit, the falloff handles the rest
  }
  const double c = glm::dot(lightToPoint / len, axis);
  if (!(c >= cosCone))
  {
    return 0.0;
  }
  // pow(0, 0) is undefined in GLSL: exponent 0 is the hard cone.
  return exponent > 0.0 ? std::pow(c > 0.0 ? c : 0.0, exponent) : 1.0;
}

/// eq. 14: the hard cone, 1 inside (edge included, as VTK) and 0 outside.
inline double mmvSpotVisibility(
  const glm::dvec3& lightToPoint, const glm::dvec3& axis, double cosCone)
{
  return mmvSpotFactor(lightToPoint, axis, cosCone, 0.0);
}

/// Unit direction and distance from point x toward the light. Directional
/// lights are infinitely far: distance -1. A point on a positional light gets
/// +z (any unit vector would do: its shadow ray has length 0).
inline glm::dvec3 mmvDirectionToLight(int kind, const glm::dvec3& position,
  const glm::dvec3& toLight, const glm::dvec3& x, double& distance)
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

inline glm::dvec3 mmvDirectionToLight(
  const LightSource& light, const glm::dvec3& x, double& distance)
{
  return mmvDirectionToLight(light.Kind, light.Position, light.ToLight, x, distance);
}

/// Unshadowed part of I_k(x) (eqs. 11-14 without the transmittance).
inline double mmvLightGeometryTerm(const LightSource& light, const glm::dvec3& x)
{
  if (light.Kind == DirectionalLight)
  {
    return 1.0;
  }
  const glm::dvec3 lightToPoint = x - light.Position;
  double term =
    mmvDistanceFalloff(light.Radius, light.Attenuation, glm::dot(lightToPoint, lightToPoint));
  if (light.Kind == SpotLight)
  {
    term *= mmvSpotFactor(lightToPoint, light.SpotAxis, light.CosCone, light.SpotExponent);
  }
  return term;
}

} // namespace mmv

#endif
