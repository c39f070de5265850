#include "vtkIrradianceUpdatePlan.h"

#include "vtkIrradianceGrid.h"
#include "vtkMultiMaterialLightTolerance.h"

#include <algorithm>

namespace
{
/// The irradiance textures' layout for `lights` lights: how many textures,
/// and how many channels the last one has (mmv::IrradianceTextureChannels).
std::pair<int, int> TextureLayout(size_t lights)
{
  const int n = static_cast<int>(lights);
  const int perTexture = mmv::IrradianceLightsPerTexture;
  const int textures = (n + perTexture - 1) / perTexture;
  const int last = n - (textures - 1) * perTexture;
  return { textures, textures > 0 ? mmv::IrradianceTextureChannels(last) : 0 };
}
}

//------------------------------------------------------------------------------
unsigned int vtkIrradianceUpdatePlan::VolumeChanges(const VolumeKey& held, const VolumeKey& now)
{
  // != rather than !(==): a NaN never matches, so it is recomputed every
  // frame rather than kept on a meaningless value.
  unsigned int changes = NoChange;
  if (held.DataTime != now.DataTime || held.Range[0] != now.Range[0] ||
    held.Range[1] != now.Range[1])
  {
    changes |= Data;
  }
  if (held.OpacityTime != now.OpacityTime || held.MaterialVersion != now.MaterialVersion ||
    held.UnitDistance != now.UnitDistance || held.TableSize != now.TableSize)
  {
    changes |= Extinction;
  }
  if (held.MultipleScattering != now.MultipleScattering ||
    held.ExponentialDiffusion != now.ExponentialDiffusion)
  {
    changes |= Scattering;
  }
  if (held.ShadowEstimation != now.ShadowEstimation ||
    held.PiecewiseShadowSlices != now.PiecewiseShadowSlices)
  {
    changes |= Shadows;
  }
  if (held.Cut != now.Cut || !std::equal(held.Region, held.Region + 6, now.Region))
  {
    changes |= Cutaway;
  }
  if (held.NumberOfLights != now.NumberOfLights)
  {
    changes |= LightCount;
  }
  if (held.Occluders != now.Occluders)
  {
    changes |= Occluders;
  }
  return changes;
}

//------------------------------------------------------------------------------
std::vector<bool> vtkIrradianceUpdatePlan::MarkLights(const std::vector<mmv::LightSource>& held,
  const std::vector<mmv::LightSource>& now, bool all, double toleranceRadians,
  const glm::dvec3& centre)
{
  std::vector<bool> marked(now.size(), all);
  for (size_t k = 0; !all && k < now.size(); ++k)
  {
    marked[k] =
      k >= held.size() || !mmv::LightWithinTolerance(held[k], now[k], toleranceRadians, centre);
  }
  return marked;
}

//------------------------------------------------------------------------------
vtkIrradianceUpdatePlan vtkIrradianceUpdatePlan::Make(
  const Inputs* held, const Inputs& now, double toleranceRadians, const glm::dvec3& centre)
{
  vtkIrradianceUpdatePlan plan;
  if (!held)
  {
    plan.MarkedLights.assign(now.Lights.size(), true);
    plan.MovedLights = plan.MarkedLights;
    return plan; // NothingHeld: everything is computed
  }
  plan.Changes = VolumeChanges(held->Volume, now.Volume);
  if (!std::equal(held->Dimensions, held->Dimensions + 3, now.Dimensions))
  {
    plan.Changes |= Grid;
  }
  if (held->Lights.size() != now.Lights.size())
  {
    plan.Changes |= LightCount;
  }
  plan.TextureLayoutChanged =
    TextureLayout(held->Lights.size()) != TextureLayout(now.Lights.size());
  // The lights are compared even when all of them are recomputed: Lights
  // says whether one moved, whatever else changed.
  plan.MovedLights = MarkLights(held->Lights, now.Lights, false, toleranceRadians, centre);
  if (std::find(plan.MovedLights.begin(), plan.MovedLights.end(), true) != plan.MovedLights.end())
  {
    plan.Changes |= Lights;
  }
  plan.MarkedLights =
    plan.RecomputesAllLights() ? std::vector<bool>(now.Lights.size(), true) : plan.MovedLights;
  return plan;
}

//------------------------------------------------------------------------------
bool vtkIrradianceUpdatePlan::KeepsVolume() const
{
  return (this->Changes & ~(Grid | Lights | Occluders)) == 0;
}

bool vtkIrradianceUpdatePlan::Prefilters() const
{
  return (this->Changes & (NothingHeld | Data | Grid)) != 0;
}

bool vtkIrradianceUpdatePlan::Reallocates() const
{
  return (this->Changes & (NothingHeld | Grid)) != 0 || this->TextureLayoutChanged;
}

bool vtkIrradianceUpdatePlan::RecomputesAllLights() const
{
  return (this->Changes & ~(Lights | LightCount)) != 0 || this->Reallocates();
}

int vtkIrradianceUpdatePlan::GetNumberOfLights() const
{
  return static_cast<int>(std::count(this->MarkedLights.begin(), this->MarkedLights.end(), true));
}
