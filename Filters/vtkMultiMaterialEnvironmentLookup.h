/**
 * @file   vtkMultiMaterialEnvironmentLookup.h
 * @brief  Where a direction lands in an environment image: the cube-map face
 *         and the equirectangular coordinates of VTK 9.2's skybox, on the CPU.
 *
 * Mirrors mmvEnvironmentFrame() and mmvEquirectangularCoord() of
 * Shaders/mmvReflection.glsl, and the OpenGL cube-map face selection
 * (OpenGL 4.5 spec., table 8.19) that samplerCube does in hardware, so the
 * reference renderer reflects the same texel the GPU does. The environment's
 * frame is vtkRenderer's EnvironmentRight / EnvironmentUp, front = up x right,
 * as vtkOpenGLSkybox uses them (with the default frame, front is -z).
 */
#ifndef vtkMultiMaterialEnvironmentLookup_h
#define vtkMultiMaterialEnvironmentLookup_h

#include "vtkMultiMaterialReflectionModes.h" // ReflectionSource, ReflectionVisibility

#include <glm/glm.hpp>

#include <cmath>

namespace mmv
{

/// Where the per-sample march and the view-dependent pass cost the same, in
/// view pixels per irradiance voxel. The march costs per shaded pixel, the
/// pass per voxel, whatever the view; 0.15 lies inside the measured
/// crossover (docs/performance.md, "Material terms: cost").
constexpr double PerSampleMarchPixelsPerVoxel = 0.15;

/// The visibility march starts this many voxels (of the grid it marches:
/// the irradiance grid on the GPU, the data in the reference) off the
/// sample along the shading normal, so that a surface does not occlude its
/// own reflection.
constexpr double ReflectionVisibilityOffsetVoxels = 2.0;

/// What the environment term samples (the shader variant's MMV_ENVIRONMENT).
enum EnvironmentKind
{
  BackgroundEnvironment = 0,     // vertical gradient of the background colours
  CubeMapEnvironment = 1,        // samplerCube
  EquirectangularEnvironment = 2 // sampler2D, longitude x latitude
};

/// Direction d in the environment's frame (right, up, front components).
inline glm::dvec3 EnvironmentFrame(
  const glm::dvec3& d, const glm::dvec3& right, const glm::dvec3& up, const glm::dvec3& front)
{
  return glm::dvec3(glm::dot(d, right), glm::dot(d, up), glm::dot(d, front));
}

/// Texture coordinates (u, v) of frame direction e in an equirectangular
/// image, as vtkOpenGLSkybox's "Sphere" projection computes them.
inline glm::dvec2 EquirectangularCoord(const glm::dvec3& e)
{
  const double pi = 3.14159265358979323846;
  const double horizontal = std::sqrt(e.x * e.x + e.z * e.z);
  return glm::dvec2(0.5 * std::atan2(e.x, e.z) / pi + 0.5, std::atan2(e.y, horizontal) / pi + 0.5);
}

/// The cube-map face (0..5: +x, -x, +y, -y, +z, -z, VTK's input order) and
/// its (s, t) in [0, 1] for frame direction e (not zero).
inline int CubeMapFaceCoord(const glm::dvec3& e, glm::dvec2& st)
{
  const glm::dvec3 a = glm::abs(e);
  int face;
  double sc, tc, ma;
  if (a.x >= a.y && a.x >= a.z)
  {
    face = e.x >= 0.0 ? 0 : 1;
    ma = a.x;
    sc = e.x >= 0.0 ? -e.z : e.z;
    tc = -e.y;
  }
  else if (a.y >= a.z)
  {
    face = e.y >= 0.0 ? 2 : 3;
    ma = a.y;
    sc = e.x;
    tc = e.y >= 0.0 ? e.z : -e.z;
  }
  else
  {
    face = e.z >= 0.0 ? 4 : 5;
    ma = a.z;
    sc = e.z >= 0.0 ? e.x : -e.x;
    tc = -e.y;
  }
  st = glm::dvec2(0.5 * (sc / ma + 1.0), 0.5 * (tc / ma + 1.0));
  return face;
}

/// sRGB-encoded value -> linear (what the GPU does on sampling an sRGB texture).
inline double SRGBToLinear(double c)
{
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

} // namespace mmv

#endif
