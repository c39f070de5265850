/**
 * @file   vtkMultiMaterialLightTolerance.h
 * @brief  When a light has moved so little that its irradiance is kept.
 *
 * ParaView's light kit follows the camera, so every rotation moves its five
 * lights. A light whose placement changed by less than a tolerance angle
 * keeps the irradiance computed for its old placement, so small nudges
 * cost only a ray cast; the shading terms of the ray cast still use the new
 * placement. The comparison is always against the placement the irradiance
 * was computed for, so small moves cannot add up unnoticed.
 *
 * What a tolerance costs in image error: docs/performance.md, "Light
 * tolerance".
 */
#ifndef vtkMultiMaterialLightTolerance_h
#define vtkMultiMaterialLightTolerance_h

#include "vtkMultiMaterialLightModel.h" // mmv::LightSource
#include "vtkMultiMaterialParameters.h" // MaxLightDirectionToleranceDegrees

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>

namespace mmv
{

/// The floor of every tolerance, in radians: the rounding of the camera's
/// transform. ParaView recomputes its kit from the camera at each render,
/// and its first two renders differ in the last bits (1e-16), which used to
/// run the whole irradiance twice. 1e-7 rad moves a light's shadow by 1e-7
/// of the distance it falls, far below a voxel.
constexpr double LightRoundingRadians = 1e-7;

/// Angle between two directions (any length but zero), robust near 0.
inline double AngleBetween(const glm::dvec3& a, const glm::dvec3& b)
{
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

/**
 * Whether `now` may keep the irradiance computed for `computed`: the same
 * kind, cone, exponent, attenuation and radius, and
 *  - directional: directions within `toleranceRadians`;
 *  - point and spot: a position moved by at most `toleranceRadians` times its
 *    distance from `centre` (the irradiance grid's centre: the angle the move
 *    subtends there), and a spot axis within the angle.
 * The tolerance never drops below LightRoundingRadians.
 */
inline bool LightWithinTolerance(const LightSource& computed, const LightSource& now,
  double toleranceRadians, const glm::dvec3& centre)
{
  if (computed.Kind != now.Kind || computed.CosCone != now.CosCone ||
    computed.SpotExponent != now.SpotExponent || computed.Attenuation != now.Attenuation ||
    computed.Radius != now.Radius || computed.GridStride != now.GridStride)
  {
    return false;
  }
  const double tolerance = std::isfinite(toleranceRadians)
    ? std::max(toleranceRadians, LightRoundingRadians)
    : LightRoundingRadians;
  if (now.Kind == DirectionalLight)
  {
    return AngleBetween(computed.ToLight, now.ToLight) <= tolerance;
  }
  const double distance = glm::length(computed.Position - centre);
  if (glm::length(now.Position - computed.Position) > tolerance * distance)
  {
    return false;
  }
  return now.Kind != SpotLight || AngleBetween(computed.SpotAxis, now.SpotAxis) <= tolerance;
}

/// A user's tolerance in degrees as radians: NaN or negative -> 0, above
/// MaxLightDirectionToleranceDegrees -> that maximum.
inline double LightToleranceRadians(double degrees)
{
  if (!(degrees > 0.0))
  {
    return 0.0;
  }
  return glm::radians(std::min(degrees, MaxLightDirectionToleranceDegrees));
}

} // namespace mmv

#endif
