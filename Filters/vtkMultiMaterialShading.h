/**
 * @file   vtkMultiMaterialShading.h
 * @brief  Segment shading on the CPU: Zhang & Ma eq. 16, the environment
 *         term of eq. 17 and the emission of Yang et al. eq. 27. Mirrors
 *         Shaders/mmvShading.glsl and Shaders/mmvEmission.glsl function for
 *         function; TestShaderMirror runs both.
 */
#ifndef vtkMultiMaterialShading_h
#define vtkMultiMaterialShading_h

#include <glm/glm.hpp>

namespace mmv
{

/// material: (ka, kd, ks, shininess); segment: (I_c rgb, I_alpha); n, v, l unit
/// vectors (n facing the viewer or zero); directional in [0, 1].
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

/// Emission of a segment (Shaders/mmvEmission.glsl): e * I_c, the integral of
/// e * colour * sigma_t with the segment's own attenuation.
inline glm::dvec3 mmvEmission(double emission, const glm::dvec4& segment)
{
  return emission * glm::dvec3(segment);
}

/// Vertical gradient environment around `up` (unit vectors).
inline glm::dvec3 mmvEnvironment(const glm::dvec3& d, const glm::dvec3& up,
  const glm::dvec3& bottom, const glm::dvec3& top)
{
  return glm::mix(bottom, top, glm::clamp(0.5 + 0.5 * glm::dot(d, up), 0.0, 1.0));
}

} // namespace mmv

#endif
