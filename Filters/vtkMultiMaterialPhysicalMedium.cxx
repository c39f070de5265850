#include "vtkMultiMaterialPhysicalMedium.h"

#include <algorithm>
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
    return Reject(why,
      "albedo must be in [0, " + std::to_string(PhysicalMediumMaxAlbedo) + "], got " +
        std::to_string(albedo));
  }
  if (!std::isfinite(g) || g < 0.0 || g > PhysicalMediumMaxAnisotropy)
  {
    return Reject(why,
      "anisotropy g must be in [0, " + std::to_string(PhysicalMediumMaxAnisotropy) +
        "] (backward scattering was not calibrated), got " + std::to_string(g));
  }
  if (!std::isfinite(extinctionPerVoxel) || !(extinctionPerVoxel > 0.0))
  {
    return Reject(why,
      "extinction per voxel must be a positive number, got " + std::to_string(extinctionPerVoxel));
  }
  // Fitted to the path tracer (docs/how-it-works.md, "Physical media"); a =
  // albedo, tau = extinction per voxel.
  const double a = albedo;
  const double tau = extinctionPerVoxel;
  const PhysicalMediumFit& f = PhysicalMediumCoefficients;
  // Multiple scattering adds light: the gain over single scattering grows
  // with the albedo (steeply near 1, as the diffusion albedo does with
  // sqrt(1 - a)) and saturates with the density; dense voxels render a
  // little darker in our ray cast, the 1 / (1 + k tau). Our particle term
  // weights all of it by the phase function HG(g), but light scattered many
  // times has forgotten its direction: strong forward scattering needs more
  // (the g^ForwardPower term, fitted at one scattering angle, about 85 deg).
  const double gain = 1.0 +
    f.GainScale * std::pow(a, f.GainAlbedoPower) / (f.GainOffset + std::sqrt(1.0 - a)) *
      (1.0 - std::exp(-tau / f.GainDepth)) * (1.0 + f.ForwardGain * std::pow(g, f.ForwardPower));
  parameters[Ambient] = gain / (4.0 * M_PI * (1.0 + f.DenseDimming * tau));
  parameters[Diffuse] = 0.0;
  parameters[Specular] = 0.0;
  parameters[Shininess] = 1.0;
  // Forward scattering lets light through: the similarity relation's reduced
  // extinction 1 - a g, to a fitted power.
  parameters[Attenuation] = std::pow(1.0 - a * g, f.AttenuationPower);
  // The diffusion reaches farther the more is scattered and the thinner the
  // medium (s in voxel^2); capped at the parameter's largest accepted value.
  parameters[Scattering] = std::min(f.ScatteringScale * std::pow(a, f.ScatteringAlbedoPower) /
      std::pow(tau, f.ScatteringDepthPower),
    MaterialParameterTable[Scattering].HardMax);
  parameters[Reflection] = 0.0;
  parameters[Anisotropy] = g;
  parameters[Emission] = 0.0;
  // A grey medium: its albedo is one number.
  parameters[TransmissionR] = parameters[TransmissionG] = parameters[TransmissionB] = 1.0;
  return true;
}

} // namespace mmv
