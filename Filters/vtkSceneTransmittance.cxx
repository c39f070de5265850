#include "vtkSceneTransmittance.h"

#include "vtkMultiMaterialThreads.h" // mmv::For
#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mmv
{
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
  if (!(longest > 0.0) || !ClipToIndexBox(p, d, grid.Dimensions, t0, t1))
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
    depth += SampleTrilinear(grid, extinction.data(), p + (t0 + (s + 0.5) * dt) * d);
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
  mmv::For(0, voxels,
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
