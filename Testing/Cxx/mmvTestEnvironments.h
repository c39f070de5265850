// Environment textures for tests, made on the CPU from a colour function of
// the direction in the environment's frame (right, up, front): a cube map
// whose faces VTK's skybox and samplerCube read in OpenGL's layout, or an
// equirectangular image in vtkOpenGLSkybox's "Sphere" projection.
#ifndef mmvTestEnvironments_h
#define mmvTestEnvironments_h

#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkTexture.h"
#include "vtkUnsignedCharArray.h"

#include <glm/glm.hpp>

#include <cmath>
#include <functional>

namespace mmvtest
{
/// A colour of a frame direction (unit vector).
using Colour = std::function<glm::dvec3(const glm::dvec3&)>;

/// An RGB (8-bit) image whose texel (i, j) is colour((i + 0.5) / width,
/// (j + 0.5) / height), clamped to [0, 1].
inline vtkSmartPointer<vtkImageData> MakeImage(
  int width, int height, const std::function<glm::dvec3(double, double)>& colour)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(width, height, 1);
  vtkNew<vtkUnsignedCharArray> rgb;
  rgb->SetNumberOfComponents(3);
  rgb->SetNumberOfTuples(static_cast<vtkIdType>(width) * height);
  for (int j = 0; j < height; ++j)
  {
    for (int i = 0; i < width; ++i)
    {
      const glm::dvec3 c = colour((i + 0.5) / width, (j + 0.5) / height);
      for (int k = 0; k < 3; ++k)
      {
        rgb->SetValue(3 * (static_cast<vtkIdType>(j) * width + i) + k,
          static_cast<unsigned char>(std::lround(255.0 * glm::clamp(c[k], 0.0, 1.0))));
      }
    }
  }
  image->GetPointData()->SetScalars(rgb);
  return image;
}

/// The frame direction of texel (s, t) of cube face `face` (OpenGL's table,
/// inverted): the faces a CPU would write for colour(direction).
inline glm::dvec3 CubeFaceDirection(int face, double s, double t)
{
  const double sc = 2.0 * s - 1.0;
  const double tc = 2.0 * t - 1.0;
  switch (face)
  {
    case 0:
      return glm::dvec3(1.0, -tc, -sc);
    case 1:
      return glm::dvec3(-1.0, -tc, sc);
    case 2:
      return glm::dvec3(sc, 1.0, tc);
    case 3:
      return glm::dvec3(sc, -1.0, -tc);
    case 4:
      return glm::dvec3(sc, -tc, 1.0);
    default:
      return glm::dvec3(-sc, -tc, -1.0);
  }
}

/// A cube map (nearest) of `colour` on six size x size faces, +x -x +y -y
/// +z -z, as VTK orders its inputs.
inline vtkSmartPointer<vtkTexture> MakeCubeMap(const Colour& colour, int size = 16)
{
  auto texture = vtkSmartPointer<vtkTexture>::New();
  texture->CubeMapOn();
  texture->InterpolateOff();
  for (int face = 0; face < 6; ++face)
  {
    texture->SetInputData(face,
      MakeImage(
        size, size, [&](double s, double t) { return colour(CubeFaceDirection(face, s, t)); }));
  }
  return texture;
}

/// An equirectangular image (nearest) of `colour`, width x width / 2.
inline vtkSmartPointer<vtkTexture> MakeEquirectangular(const Colour& colour, int width = 64)
{
  auto texture = vtkSmartPointer<vtkTexture>::New();
  texture->InterpolateOff();
  const double pi = 3.14159265358979323846;
  texture->SetInputData(MakeImage(width, width / 2,
    [&](double u, double v)
    {
      const double longitude = (u - 0.5) * 2.0 * pi;
      const double latitude = (v - 0.5) * pi;
      return colour(glm::dvec3(std::cos(latitude) * std::sin(longitude), std::sin(latitude),
        std::cos(latitude) * std::cos(longitude)));
    }));
  return texture;
}
}

#endif
