/**
 * @file   vtkMultiMaterialPhaseFunction.h
 * @brief  The Henyey-Greenstein phase function: value, sampling, and a frame
 *         to turn a sampled cosine into a direction.
 *
 * The angle is the one between the direction the light travelled before the
 * event and after it: cos = 1 is straight on. Its mean cosine is g, the
 * material's anisotropy (mmv::Anisotropy).
 *
 * Our convention, stated once: HG(g, cos) = (1 - g^2) / (4 pi (1 + g^2 -
 * 2 g cos)^1.5) per steradian, pbrt's sign (g > 0 scatters forward) and
 * normalised to 1 over the sphere. The ray caster and the reference renderer
 * use it relative to isotropic scattering, 4 pi HG (mmvHenyeyGreensteinRelative,
 * mirrored line for line by Shaders/mmvPhaseFunction.glsl): that is exactly 1
 * at g = 0, so their former isotropic particle term is the g = 0 case.
 */
#ifndef vtkMultiMaterialPhaseFunction_h
#define vtkMultiMaterialPhaseFunction_h

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>

namespace mmv
{

/// Below this |g| the phase function is sampled as isotropic: the inverse
/// CDF divides by g.
constexpr double IsotropicAnisotropy = 1.0e-4;

/// 4 pi HG(g, cos): the phase function relative to isotropic scattering
/// (mean 1 over the sphere; 1 everywhere at g = 0, also in float).
/// cosTheta: between the light's travel direction and the scattered one,
/// -dot(v, l) for v toward the viewer and l toward the light.
inline double mmvHenyeyGreensteinRelative(double g, double cosTheta)
{
  // |g| <= 0.99 (the parameter's hard limits) keeps the denominator >= 1e-4.
  const double denominator = 1.0 + g * g - 2.0 * g * cosTheta;
  return (1.0 - g * g) / (denominator * std::sqrt(denominator));
}

/// p(cos) per steradian: (1 - g^2) / (4 pi (1 + g^2 - 2 g cos)^1.5).
inline double HenyeyGreenstein(double g, double cosTheta)
{
  return mmvHenyeyGreensteinRelative(g, cosTheta) / (4.0 * M_PI);
}

/// The cosine whose CDF is u in [0, 1): inverse-transform sampling.
inline double SampleHenyeyGreensteinCosine(double g, double u)
{
  if (std::abs(g) < IsotropicAnisotropy)
  {
    return 1.0 - 2.0 * u;
  }
  const double s = (1.0 - g * g) / (1.0 - g + 2.0 * g * u);
  return std::min(1.0, std::max(-1.0, (1.0 + g * g - s * s) / (2.0 * g)));
}

/// The unit vector at `cosTheta` from unit `axis`, turned by `phi` about it.
inline glm::dvec3 DirectionAround(const glm::dvec3& axis, double cosTheta, double phi)
{
  // Duff et al. 2017: an orthonormal basis without a branch on the axis.
  const double sign = std::copysign(1.0, axis.z);
  const double a = -1.0 / (sign + axis.z);
  const double b = axis.x * axis.y * a;
  const glm::dvec3 t(1.0 + sign * axis.x * axis.x * a, sign * b, -sign * axis.x);
  const glm::dvec3 bt(b, sign + axis.y * axis.y * a, -axis.y);
  const double sinTheta = std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta));
  return glm::normalize(
    sinTheta * std::cos(phi) * t + sinTheta * std::sin(phi) * bt + cosTheta * axis);
}

} // namespace mmv

#endif
