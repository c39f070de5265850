// What an irradiance update recomputes (vtkIrradianceUpdatePlan.h), on the
// CPU: which lights and which steps each kind of edit marks.
#include "vtkIrradianceInputCache.h"
#include "vtkIrradianceUpdatePlan.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMultiMaterialLightTolerance.h"
#include "vtkMultiMaterialLights.h"
#include "vtkNew.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace
{
using Plan = vtkIrradianceUpdatePlan;

/// A directional light `degrees` from +z toward +x.
mmv::LightSource Turned(double degrees)
{
  mmv::LightSource light;
  const double a = glm::radians(degrees);
  light.ToLight = glm::dvec3(std::sin(a), 0.0, std::cos(a));
  return light;
}

/// Three directional lights on a 32^3 grid, everything else at its default.
Plan::Inputs ThreeLights()
{
  Plan::Inputs inputs;
  inputs.Volume.DataTime = 10;
  inputs.Volume.OpacityTime = 20;
  inputs.Volume.Range[1] = 1.0;
  inputs.Volume.TableSize = 256;
  inputs.Volume.NumberOfLights = 3;
  for (int a = 0; a < 3; ++a)
  {
    inputs.Dimensions[a] = 32;
  }
  inputs.Lights = { Turned(0.0), Turned(40.0), Turned(80.0) };
  return inputs;
}

const glm::dvec3 Centre(0.0);

Plan Make(const Plan::Inputs& held, const Plan::Inputs& now, double degrees = 0.0)
{
  return Plan::Make(&held, now, mmv::LightToleranceRadians(degrees), Centre);
}

std::vector<bool> Only(size_t lights, size_t k)
{
  std::vector<bool> marks(lights, false);
  marks[k] = true;
  return marks;
}
}

TEST(IrradianceUpdatePlan, NothingHeldComputesEverything)
{
  const Plan plan = Plan::Make(nullptr, ThreeLights(), 0.0, Centre);
  EXPECT_TRUE(plan.Changed(Plan::NothingHeld));
  EXPECT_FALSE(plan.IsCurrent());
  EXPECT_FALSE(plan.KeepsVolume());
  EXPECT_TRUE(plan.Prefilters());
  EXPECT_TRUE(plan.Reallocates());
  EXPECT_EQ(plan.GetNumberOfLights(), 3);
  EXPECT_TRUE(plan.Diffuses(true));
  EXPECT_FALSE(plan.Diffuses(false));
}

TEST(IrradianceUpdatePlan, TheSameInputsRecomputeNothing)
{
  const Plan plan = Make(ThreeLights(), ThreeLights());
  EXPECT_TRUE(plan.IsCurrent());
  EXPECT_TRUE(plan.KeepsVolume());
  EXPECT_FALSE(plan.Prefilters());
  EXPECT_FALSE(plan.Reallocates());
  EXPECT_EQ(plan.GetNumberOfLights(), 0);
  EXPECT_FALSE(plan.Diffuses(true));
}

TEST(IrradianceUpdatePlan, ALightTurnedWithinTheToleranceRecomputesNothing)
{
  Plan::Inputs now = ThreeLights();
  now.Lights[1] = Turned(40.5);
  const Plan plan = Make(ThreeLights(), now, 1.0);
  EXPECT_TRUE(plan.IsCurrent());
  EXPECT_EQ(plan.GetNumberOfLights(), 0);
  // Compared with the held placement, never the last one: a second half
  // degree in the same direction is beyond it.
  now.Lights[1] = Turned(41.2);
  EXPECT_EQ(Make(ThreeLights(), now, 1.0).GetLights(), Only(3, 1));
}

TEST(IrradianceUpdatePlan, ALightTurnedBeyondTheToleranceRecomputesOnlyThatLight)
{
  Plan::Inputs now = ThreeLights();
  now.Lights[2] = Turned(82.0);
  const Plan plan = Make(ThreeLights(), now, 1.0);
  EXPECT_EQ(plan.GetChanges(), static_cast<unsigned int>(Plan::Lights));
  EXPECT_EQ(plan.GetLights(), Only(3, 2));
  EXPECT_FALSE(plan.RecomputesAllLights());
  EXPECT_FALSE(plan.Prefilters());
  EXPECT_FALSE(plan.Reallocates());
  // Only the lights moved: an interactive frame may keep the irradiance.
  EXPECT_TRUE(plan.KeepsVolume());
  EXPECT_TRUE(plan.Diffuses(true)) << "the moved light's irradiance is diffused";
  // With the tolerance at 0 every move beyond the camera's rounding counts.
  EXPECT_EQ(Make(ThreeLights(), now, 0.0).GetLights(), Only(3, 2));
}

TEST(IrradianceUpdatePlan, ADimLightCrossingTheDimLightRatioRecomputesOnlyThatLight)
{
  // A key light and two others; light 2 dims below mmv::DimLightRatio of the
  // key light and moves to the strided light grid (mmv::DimLightStride).
  const int dims[3] = { 64, 64, 64 };
  std::vector<mmv::ShadingLight> lights(3);
  for (int k = 0; k < 3; ++k)
  {
    lights[k].Source = Turned(40.0 * k);
    lights[k].Radiance = glm::dvec3(k == 0 ? 1.0 : 0.8);
  }
  Plan::Inputs held = ThreeLights();
  std::copy(dims, dims + 3, held.Dimensions);
  held.Lights = mmv::IrradianceLightSources(lights, dims, true);
  ASSERT_EQ(held.Lights[2].GridStride, 1);
  lights[2].Radiance = glm::dvec3(0.9 * mmv::DimLightRatio);
  Plan::Inputs now = held;
  now.Lights = mmv::IrradianceLightSources(lights, dims, true);
  ASSERT_EQ(now.Lights[2].GridStride, mmv::DimLightStride);
  // Not even the largest tolerance keeps it: its irradiance is on another grid.
  const Plan plan = Make(held, now, mmv::MaxLightDirectionToleranceDegrees);
  EXPECT_EQ(plan.GetLights(), Only(3, 2));
  EXPECT_FALSE(plan.Reallocates());
}

TEST(IrradianceUpdatePlan, AnOpacityEditRecomputesEveryLightAndTheDiffusion)
{
  Plan::Inputs now = ThreeLights();
  now.Volume.OpacityTime = 21;
  const Plan plan = Make(ThreeLights(), now);
  EXPECT_EQ(plan.GetChanges(), static_cast<unsigned int>(Plan::Extinction));
  EXPECT_TRUE(plan.RecomputesAllLights());
  EXPECT_EQ(plan.GetNumberOfLights(), 3);
  EXPECT_TRUE(plan.Diffuses(true));
  EXPECT_FALSE(plan.KeepsVolume()) << "an interactive frame must not keep it";
  EXPECT_FALSE(plan.Prefilters()) << "the data are not pre-filtered again";
  EXPECT_FALSE(plan.Reallocates());
}

TEST(IrradianceUpdatePlan, AColourOnlyMaterialEditRecomputesNothing)
{
  // The volume key carries the materials' sampled attenuation, transmission
  // and scattering (vtkIrradianceInputCache's version), not their edit time.
  vtkNew<vtkMaterialTransferFunction> materials;
  materials->AddNode(0.2, 0.3, 0.7, 0.2, 20.0, 1.0, 4.0, 0.0);
  materials->AddNode(0.8, 0.3, 0.7, 0.2, 20.0, 2.0, 4.0, 0.0);
  vtkNew<vtkIrradianceInputCache> cache;
  const double range[2] = { 0.0, 1.0 };
  cache->SampleMaterials(materials, range, 64);
  Plan::Inputs held = ThreeLights();
  held.Volume.MaterialVersion = cache->GetMaterialVersion();
  // Ambient, diffuse, specular, shininess and reflection only colour the
  // ray cast.
  materials->AddNode(0.8, 0.9, 0.1, 0.9, 60.0, 2.0, 4.0, 0.5);
  cache->SampleMaterials(materials, range, 64);
  Plan::Inputs now = held;
  now.Volume.MaterialVersion = cache->GetMaterialVersion();
  EXPECT_TRUE(Make(held, now).IsCurrent());
  // The attenuation casts other shadows: every light.
  materials->AddNode(0.8, 0.9, 0.1, 0.9, 60.0, 3.0, 4.0, 0.5);
  cache->SampleMaterials(materials, range, 64);
  now.Volume.MaterialVersion = cache->GetMaterialVersion();
  const Plan plan = Make(held, now);
  EXPECT_TRUE(plan.Changed(Plan::Extinction));
  EXPECT_EQ(plan.GetNumberOfLights(), 3);
}

TEST(IrradianceUpdatePlan, ANewTimeStepOnTheSameGridRecomputesEveryLightOnTheSameGrid)
{
  Plan::Inputs now = ThreeLights();
  now.Volume.DataTime = 11;
  now.Volume.Range[1] = 1.5; // a step's own finite range
  const Plan plan = Make(ThreeLights(), now);
  EXPECT_EQ(plan.GetChanges(), static_cast<unsigned int>(Plan::Data));
  EXPECT_TRUE(plan.Prefilters());
  EXPECT_EQ(plan.GetNumberOfLights(), 3);
  // The grid (and so the probe's choice of it) is kept: no new textures.
  EXPECT_FALSE(plan.Changed(Plan::Grid));
  EXPECT_FALSE(plan.Reallocates());
  EXPECT_FALSE(plan.KeepsVolume());
}

TEST(IrradianceUpdatePlan, NewDimensionsReallocateAndRecomputeEverything)
{
  Plan::Inputs now = ThreeLights();
  now.Dimensions[0] = 48;
  const Plan plan = Make(ThreeLights(), now);
  EXPECT_EQ(plan.GetChanges(), static_cast<unsigned int>(Plan::Grid));
  EXPECT_TRUE(plan.Reallocates());
  EXPECT_TRUE(plan.Prefilters());
  EXPECT_EQ(plan.GetNumberOfLights(), 3);
  // The screen chose another grid: an interactive frame may keep the last one.
  EXPECT_TRUE(plan.KeepsVolume());
}

TEST(IrradianceUpdatePlan, AnAddedLightIsComputedAloneUnlessTheTexturesChange)
{
  // A fourth light fits the RGBA16 texture that three lights use.
  Plan::Inputs now = ThreeLights();
  now.Lights.push_back(Turned(120.0));
  now.Volume.NumberOfLights = 4;
  Plan plan = Make(ThreeLights(), now);
  EXPECT_TRUE(plan.Changed(Plan::LightCount));
  EXPECT_FALSE(plan.Reallocates());
  EXPECT_EQ(plan.GetLights(), Only(4, 3));
  EXPECT_FALSE(plan.KeepsVolume());
  // A fifth needs a second texture; a second light turns R16 into RG16.
  Plan::Inputs five = now;
  five.Lights.push_back(Turned(160.0));
  five.Volume.NumberOfLights = 5;
  plan = Make(now, five);
  EXPECT_TRUE(plan.Reallocates());
  EXPECT_EQ(plan.GetNumberOfLights(), 5);
  Plan::Inputs one = ThreeLights();
  one.Lights.resize(1);
  one.Volume.NumberOfLights = 1;
  Plan::Inputs two = one;
  two.Lights.push_back(Turned(40.0));
  two.Volume.NumberOfLights = 2;
  EXPECT_TRUE(Make(one, two).Reallocates());
}

TEST(IrradianceUpdatePlan, EveryFieldOfTheVolumeKeyIsAChange)
{
  using Key = Plan::VolumeKey;
  const Key held = ThreeLights().Volume;
  struct Case
  {
    void (*Edit)(Key&);
    Plan::Change Expected;
  };
  const Case cases[] = {
    { [](Key& k) { k.DataTime = 99; }, Plan::Data },
    { [](Key& k) { k.Range[0] = -1.0; }, Plan::Data },
    { [](Key& k) { k.OpacityTime = 99; }, Plan::Extinction },
    { [](Key& k) { k.MaterialVersion = 7; }, Plan::Extinction },
    { [](Key& k) { k.UnitDistance = 2.0; }, Plan::Extinction },
    { [](Key& k) { k.TableSize = 128; }, Plan::Extinction },
    { [](Key& k) { k.MultipleScattering = !k.MultipleScattering; }, Plan::Scattering },
    { [](Key& k) { k.ExponentialDiffusion = !k.ExponentialDiffusion; }, Plan::Scattering },
    { [](Key& k) { k.ShadowEstimation = 1 - k.ShadowEstimation; }, Plan::Shadows },
    { [](Key& k) { k.PiecewiseShadowSlices = 8; }, Plan::Shadows },
    { [](Key& k) { k.Cut = { 1.0 }; }, Plan::Cutaway },
    { [](Key& k) { k.Region[1] = 3; }, Plan::Cutaway },
    { [](Key& k) { k.NumberOfLights = 9; }, Plan::LightCount },
  };
  for (const Case& c : cases)
  {
    Key now = held;
    c.Edit(now);
    EXPECT_EQ(Plan::VolumeChanges(held, now), static_cast<unsigned int>(c.Expected));
    EXPECT_NE(held, now);
  }
  EXPECT_EQ(held, held);
  Key nan = held;
  nan.UnitDistance = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(nan, nan) << "a NaN never matches: recomputed every frame";
}

TEST(IrradianceUpdatePlan, MarkLightsComparesEachChannelWithWhatItHolds)
{
  const std::vector<mmv::LightSource> held = { Turned(0.0), Turned(40.0) };
  std::vector<mmv::LightSource> now = { Turned(0.0), Turned(45.0), Turned(90.0) };
  const double one = mmv::LightToleranceRadians(1.0);
  EXPECT_EQ(
    Plan::MarkLights(held, now, false, one, Centre), std::vector<bool>({ false, true, true }));
  EXPECT_EQ(Plan::MarkLights(held, now, true, one, Centre), std::vector<bool>(3, true));
  // Anything but the placement must match exactly, whatever the tolerance.
  now = held;
  now[0].Attenuation.y = 1e-9;
  EXPECT_EQ(Plan::MarkLights(held, now, false, mmv::LightToleranceRadians(45.0), Centre),
    std::vector<bool>({ true, false }));
}

TEST(IrradianceUpdatePlan, MovedLightsAreNamedWhateverElseChanged)
{
  // The pass recomputes every light only where the values behind the keys
  // changed; otherwise it takes the moved lights the plan names.
  Plan::Inputs now = ThreeLights();
  now.Volume.OpacityTime = 21;
  now.Lights[1] = Turned(45.0);
  const Plan plan = Make(ThreeLights(), now, 1.0);
  EXPECT_EQ(plan.GetNumberOfLights(), 3);
  EXPECT_EQ(plan.GetMovedLights(), Only(3, 1));
  EXPECT_TRUE(plan.Changed(Plan::Lights));
  // Nothing held: every light is new.
  EXPECT_EQ(Plan::Make(nullptr, now, 0.0, Centre).GetMovedLights(), std::vector<bool>(3, true));
}

namespace
{
/// ParaView's light kit as the mapper collects it: the key light first,
/// then fill, head and two back lights at a third to a quarter of it.
std::vector<mmv::ShadingLight> LightKit(double fill = 0.33)
{
  const double radiance[5] = { 1.0, fill, 0.3, 0.25, 0.25 };
  std::vector<mmv::ShadingLight> lights(5);
  for (int k = 0; k < 5; ++k)
  {
    lights[k].Radiance = glm::dvec3(radiance[k]);
    lights[k].Index = k;
  }
  return lights;
}

std::vector<int> Indices(const std::vector<mmv::ShadingLight>& lights)
{
  std::vector<int> indices;
  for (const mmv::ShadingLight& light : lights)
  {
    indices.push_back(light.Index);
  }
  return indices;
}
}

// Dimmest first: the kit's four dim lights fill the first irradiance
// texture and its one strided grid, the key light the second texture.
TEST(IrradianceUpdatePlan, TheLightKitsDimLightsShareOneTexture)
{
  std::vector<mmv::ShadingLight> lights = LightKit();
  std::vector<int> order;
  mmv::OrderForIrradianceTextures(lights, order);
  EXPECT_EQ(Indices(lights), (std::vector<int>{ 3, 4, 2, 1, 0 }));
  EXPECT_EQ(order, Indices(lights));
  const int dims[3] = { 64, 64, 64 };
  const std::vector<mmv::LightSource> sources = mmv::IrradianceLightSources(lights, dims, true);
  for (int k = 0; k < 4; ++k)
  {
    EXPECT_EQ(sources[k].GridStride, mmv::DimLightStride) << "light " << k;
  }
  EXPECT_EQ(sources[4].GridStride, 1);
}

// The same lights keep their places whatever their intensity does: a fill
// light raised to the key's brightness moves no other light's channel, so
// only its own irradiance is recomputed (what the mapper's
// DimLightsOnACoarserGridKeepTheImage counts). A new set of lights is
// ordered again.
TEST(IrradianceUpdatePlan, LightsKeepTheirChannelsWhileTheSameLightsComeBack)
{
  std::vector<mmv::ShadingLight> lights = LightKit();
  std::vector<int> order;
  mmv::OrderForIrradianceTextures(lights, order);
  const std::vector<int> first = order;
  std::vector<mmv::ShadingLight> brighter = LightKit(1.0);
  mmv::OrderForIrradianceTextures(brighter, order);
  EXPECT_EQ(Indices(brighter), first);
  EXPECT_EQ(brighter[3].Radiance.x, 1.0); // the fill light, with its new radiance
  std::vector<mmv::ShadingLight> fewer = LightKit(1.0);
  fewer.erase(fewer.begin() + 2); // the head light switched off
  mmv::OrderForIrradianceTextures(fewer, order);
  EXPECT_EQ(Indices(fewer), (std::vector<int>{ 3, 4, 0, 1 }));
}
