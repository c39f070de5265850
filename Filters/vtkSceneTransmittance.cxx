#include "vtkSceneTransmittance.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mmv
{
namespace
{
/// Trilinear value of `values` (on a grid of `n`) at continuous index `p`,
/// inside the box of voxel centres.
double Trilinear(const std::vector<float>& values, const int n[3], const glm::dvec3& p)
{
  int i0[3];
  double w[3];
  for (int a = 0; a < 3; ++a)
  {
    const double c = std::min(std::max(p[a], 0.0), static_cast<double>(n[a] - 1));
    i0[a] = std::min(static_cast<int>(c), std::max(n[a] - 2, 0));
    w[a] = n[a] > 1 ? c - i0[a] : 0.0;
  }
  const size_t nx = static_cast<size_t>(n[0]);
  const size_t nxy = nx * n[1];
  const size_t dx = n[0] > 1 ? 1 : 0;
  const size_t dy = n[1] > 1 ? nx : 0;
  const size_t dz = n[2] > 1 ? nxy : 0;
  const size_t base = i0[0] + i0[1] * nx + i0[2] * nxy;
  auto lerp = [](double a, double b, double t) { return a + (b - a) * t; };
  const double c00 = lerp(values[base], values[base + dx], w[0]);
  const double c10 = lerp(values[base + dy], values[base + dy + dx], w[0]);
  const double c01 = lerp(values[base + dz], values[base + dz + dx], w[0]);
  const double c11 = lerp(values[base + dz + dy], values[base + dz + dy + dx], w[0]);
  return lerp(lerp(c00, c10, w[1]), lerp(c01, c11, w[1]), w[2]);
}

/// The parameters [t0, t1] where p + t d lies in the box [0, n - 1] (slab
/// test); false when it misses.
bool ClipToBox(const glm::dvec3& p, const glm::dvec3& d, const int n[3], double& t0, double& t1)
{
  for (int a = 0; a < 3; ++a)
  {
    const double high = static_cast<double>(n[a] - 1);
    if (d[a] == 0.0)
    {
      if (p[a] < 0.0 || p[a] > high)
      {
        return false;
      }
      continue;
    }
    double tNear = (0.0 - p[a]) / d[a];
    double tFar = (high - p[a]) / d[a];
    if (tNear > tFar)
    {
      std::swap(tNear, tFar);
    }
    t0 = std::max(t0, tNear);
    t1 = std::min(t1, tFar);
  }
  return t1 > t0;
}
}

double OccluderTransmittance(
  const Occluder& occluder, const glm::dvec3& x, const glm::dvec3& direction, double distance)
{
  const IrradianceGrid& grid = *occluder.Grid;
  const std::vector<float>& extinction = *occluder.Extinction;
  if (grid.GetNumberOfVoxels() <= 0 ||
    extinction.size() != static_cast<size_t>(grid.GetNumberOfVoxels()))
  {
    return 1.0;
  }
  // The ray in the occluder's object space, then in its grid's index space;
  // t stays the receiver's ray parameter throughout.
  const glm::dvec3 objectStart = glm::dvec3(occluder.ReceiverToOccluder * glm::dvec4(x, 1.0));
  const glm::dvec3 objectDir = glm::dmat3(occluder.ReceiverToOccluder) * direction;
  const glm::dmat3 toIndex = grid.PhysicalToIndexMatrix();
  const glm::dvec3 p = toIndex * (objectStart - grid.Origin);
  const glm::dvec3 d = toIndex * objectDir;
  double t0 = 0.0;
  double t1 = distance >= 0.0 ? distance : std::numeric_limits<double>::infinity();
  const double longest = std::max({ std::abs(d.x), std::abs(d.y), std::abs(d.z) });
  if (!(longest > 0.0) || !ClipToBox(p, d, grid.Dimensions, t0, t1))
  {
    return 1.0;
  }
  // Half an occluder voxel per step along the ray's dominant axis.
  const int steps = std::max(1, static_cast<int>(std::ceil((t1 - t0) * longest * 2.0)));
  const double dt = (t1 - t0) / steps;
  const double unitsPerT = glm::length(objectDir); // occluder object units per t
  double depth = 0.0;
  for (int s = 0; s < steps; ++s)
  {
    depth += Trilinear(extinction, grid.Dimensions, p + (t0 + (s + 0.5) * dt) * d);
  }
  return std::exp(-depth * dt * unitsPerT);
}

void ComputeSceneTransmittance(const IrradianceGrid& grid, const std::vector<LightSource>& lights,
  const std::vector<Occluder>& occluders, std::vector<std::vector<float>>& groups)
{
  const int perGroup = IrradianceLightsPerTexture;
  const size_t count = lights.size();
  const vtkIdType voxels = grid.GetNumberOfVoxels();
  groups.assign((count + perGroup - 1) / perGroup,
    std::vector<float>(static_cast<size_t>(std::max<vtkIdType>(voxels, 0)) * 4, 1.0f));
  vtkSMPTools::For(0, voxels,
    [&](vtkIdType first, vtkIdType last)
    {
      for (vtkIdType v = first; v < last; ++v)
      {
        const glm::dvec3 x = grid.IndexToPhysical(grid.IndexOfVoxel(v));
        for (size_t k = 0; k < count; ++k)
        {
          double distance = -1.0;
          const glm::dvec3 toLight = mmvDirectionToLight(lights[k], x, distance);
          double transmittance = 1.0;
          for (const Occluder& occluder : occluders)
          {
            transmittance *= OccluderTransmittance(occluder, x, toLight, distance);
          }
          groups[k / perGroup][static_cast<size_t>(v) * 4 + k % perGroup] =
            static_cast<float>(transmittance);
        }
      }
    });
}

} // namespace mmv
