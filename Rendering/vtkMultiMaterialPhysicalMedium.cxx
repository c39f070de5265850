#include "vtkMultiMaterialPhysicalMedium.h"

#include <cmath>

namespace mmv
{

namespace
{
bool Reject(std::string* why, const std::string& reason)
{
  if (why)
  {
    *why = reason;
  }
  return false;
}
}

bool PhysicalMediumToMaterial(double albedo, double g, double extinctionPerVoxel,
  double parameters[MaterialParameterCount], std::string* why)
{
  if (!std::isfinite(albedo) || albedo < 0.0 || albedo > PhysicalMediumMaxAlbedo)
  {
    return Reject(why, "albedo must be in [0, " + std::to_string(PhysicalMediumMaxAlbedo) +
        "], got " + std::to_string(albedo));
  }
  if (!std::isfinite(g) || std::abs(g) > PhysicalMediumMaxAnisotropy)
  {
    return Reject(why, "anisotropy g must be in [-" + std::to_string(PhysicalMediumMaxAnisotropy) +
        ", " + std::to_string(PhysicalMediumMaxAnisotropy) + "], got " + std::to_string(g));
  }
  if (!std::isfinite(extinctionPerVoxel) || !(extinctionPerVoxel > 0.0))
  {
    return Reject(why, "extinction per voxel must be a positive number, got " +
        std::to_string(extinctionPerVoxel));
  }
  // PROVISIONAL (replaced by the fit): single scattering plus similarity.
  const double reduced = 1.0 - albedo * g;
  parameters[Ambient] = albedo / (4.0 * M_PI) / (1.0 - albedo + 1e-3);
  parameters[Diffuse] = 0.0;
  parameters[Specular] = 0.0;
  parameters[Shininess] = 1.0;
  parameters[Attenuation] = reduced;
  parameters[Scattering] = 1.0 / (3.0 * extinctionPerVoxel * reduced);
  parameters[Reflection] = 0.0;
  parameters[Anisotropy] = g;
  parameters[Emission] = 0.0;
  return true;
}

} // namespace mmv
