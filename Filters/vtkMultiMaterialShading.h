/**
 * @file   vtkMultiMaterialShading.h
 * @brief  Segment shading on the CPU: Zhang & Ma eq. 16, the environment
 *         term of eq. 17 and the emission of Yang et al. eq. 27. Mirrors
 *         Shaders/mmvShading.glsl and Shaders/mmvEmission.glsl function for
 *         function; TestShaderMirror runs both. The reference renderer
 *         shades its segments with mmvShadeSample, as the ray cast does.
 */
#ifndef vtkMultiMaterialShading_h
#define vtkMultiMaterialShading_h

#include "vtkMultiMaterialLightModel.h"    // mmvDirectionToLight
#include "vtkMultiMaterialPhaseFunction.h" // mmvHenyeyGreensteinRelative

#include <glm/glm.hpp>

namespace mmv
{

/// material: (ka, kd, ks, shininess); segment: (I_c rgb, I_alpha); n, v, l unit
/// vectors (n facing the viewer or zero); directional in [0, 1]: the weight
/// of the normal-based terms (the surface share).
inline glm::dvec3 mmvBlinnPhong(const glm::dvec4& material, const glm::dvec4& segment,
  const glm::dvec3& n, const glm::dvec3& v, const glm::dvec3& l, double directional)
{
  const double ndotl = glm::max(glm::dot(n, l), 0.0);
  const glm::dvec3 h = v + l;
  const double hlen = glm::length(h);
  const double ndoth = hlen > 0.0 ? glm::max(glm::dot(n, h / hlen), 0.0) : 0.0;
  const double highlight = material.w > 0.0 ? glm::pow(ndoth, material.w) : 1.0;
  const glm::dvec3 ambientDiffuse =
    (material.x + directional * material.y * ndotl) * glm::dvec3(segment);
  return ambientDiffuse + glm::dvec3(directional * material.z * highlight * segment.w);
}

/// The surface elements' share of a segment's extinction in the hybrid
/// surface/particle model (Yang et al. eqs. 5-8; mmvSurfaceShare in
/// Shaders/mmvShading.glsl, which says why): gradientLength |grad| and
/// equalShare > 0 in normalised value per object unit.
inline double mmvSurfaceShare(double gradientLength, double equalShare)
{
  return gradientLength / (gradientLength + equalShare);
}

/// Emission of a segment (Shaders/mmvEmission.glsl): e * I_c, the integral of
/// e * colour * sigma_t with the segment's own attenuation.
inline glm::dvec3 mmvEmission(double emission, const glm::dvec4& segment)
{
  return emission * glm::dvec3(segment);
}

/// Vertical gradient environment around `up` (unit vectors).
inline glm::dvec3 mmvEnvironment(
  const glm::dvec3& d, const glm::dvec3& up, const glm::dvec3& bottom, const glm::dvec3& top)
{
  return glm::mix(bottom, top, glm::clamp(0.5 + 0.5 * glm::dot(d, up), 0.0, 1.0));
}

/// The radiance of one segment (mmvShadeSample in Shaders/mmvShading.glsl,
/// the arithmetic of the ray cast's mmvShadeSegment once it has read its
/// textures): eq. 16 summed over the lights, eq. 17's environment term and
/// emission. The hybrid model mixes the surface's Blinn-Phong BRDF and the
/// particles' phase function by the surface share w (mmvSurfaceShare): per
/// light w (ka + kd n.l) I_c + w ks h I_a + (1 - w) ka 4 pi HG(g) I_c.
/// material: (ka, kd, ks, ke); position: the shading point (object space);
/// n, v: as mmvBlinnPhong; surface: the surface share w; for k < count, light k's
/// geometry lights[k], its colour * intensity radiance[k] and its irradiance
/// irradiance[k]; environment: the environment's radiance along the mirrored
/// view direction. The GPU compiles the phase function, the reflection and
/// the emission out when no material uses them; at g = 0, r = 0 and e = 0
/// they change nothing here either. sky: the environment light is on (its
/// mmvSkyRadiance is added apart), so no light means no ambient fallback.
inline glm::dvec3 mmvShadeSample(const glm::dvec4& material, double anisotropy, double reflection,
  double emission, const glm::dvec4& segment, const glm::dvec3& position, const glm::dvec3& n,
  const glm::dvec3& v, double surface, const LightSource* lights, const glm::dvec3* radiance,
  const double* irradiance, int count, const glm::dvec3& environment, bool sky = false)
{
  glm::dvec3 result(0.0);
  if (count == 0 && !sky)
  {
    // No active light: ambient emission only, so the volume stays visible.
    result = material.x * glm::dvec3(segment);
  }
  for (int k = 0; k < count; ++k)
  {
    if (irradiance[k] <= 0.0)
    {
      continue;
    }
    double lightDistance = 0.0;
    const glm::dvec3 l = mmvDirectionToLight(lights[k], position, lightDistance);
    // The particles' share in-scatters by the phase function; the surface's
    // ambient is the BRDF's.
    glm::dvec4 lit = material;
    lit.x *= glm::mix(mmvHenyeyGreensteinRelative(anisotropy, -glm::dot(v, l)), 1.0, surface);
    result += irradiance[k] * radiance[k] * mmvBlinnPhong(lit, segment, n, v, l, surface);
  }
  if (reflection > 0.0)
  {
    result += surface * reflection * segment.w * environment;
  }
  return result + mmvEmission(emission, segment);
}

/// The sky's radiance of one segment (mmvSkyRadiance in Shaders/mmvShading.glsl):
/// physical, as the path tracer's sky, with albedo = the segment's colour:
/// ((1 - w) F0 / (4 pi) + w (1 - ks) E(n) / pi) I_c, F0 = mean S0 + slope S1,
/// E(n) ~ F0 / 4 + F1.n / 2, F1.n = mean (S1.n) + (slope n) S0 / 3; sky =
/// (S0, S1) of vtkSkyVisibility.h, the sky's radiance L(w) = mean + slope w.
inline glm::dvec3 mmvSkyRadiance(const glm::dvec4& material, const glm::dvec4& segment,
  const glm::dvec3& n, double surface, const glm::dvec4& sky, const glm::dvec3& mean,
  const glm::dmat3& slope)
{
  const glm::dvec3 s1(sky.y, sky.z, sky.w);
  const glm::dvec3 f0 = mean * sky.x + slope * s1;
  const glm::dvec3 f1n = mean * glm::dot(s1, n) + (slope * n) * (sky.x / 3.0);
  const glm::dvec3 e = glm::max(0.25 * f0 + 0.5 * f1n, glm::dvec3(0.0));
  const double diffuse = 1.0 - glm::clamp(material.z, 0.0, 1.0);
  return ((1.0 - surface) * f0 / (4.0 * M_PI) + surface * diffuse * e / M_PI) * glm::dvec3(segment);
}

} // namespace mmv

#endif
