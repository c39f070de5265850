// CPU light-source terms of Zhang & Ma eqs. 11-14 (vtkMultiMaterialLightModel.h)
// against closed-form values.
#include "vtkMultiMaterialLightModel.h"

#include <gtest/gtest.h>

#include <cmath>

namespace
{

mmv::LightSource MakePoint(const glm::dvec3& position, double radius)
{
  mmv::LightSource light;
  light.Kind = mmv::PointLight;
  light.Position = position;
  light.Radius = radius;
  return light;
}

mmv::LightSource MakeSpot(
  const glm::dvec3& position, const glm::dvec3& axis, double cosCone, double radius)
{
  mmv::LightSource light = MakePoint(position, radius);
  light.Kind = mmv::SpotLight;
  light.SpotAxis = axis;
  light.CosCone = cosCone;
  return light;
}

} // namespace

TEST(LightModel, PointFalloffIsInverseSquareOutsideTheRadius)
{
  EXPECT_DOUBLE_EQ(mmv::mmvPointFalloff(2.0, 16.0), 0.25);
  EXPECT_DOUBLE_EQ(mmv::mmvPointFalloff(0.5, 100.0), 0.0025);
  EXPECT_DOUBLE_EQ(mmv::mmvPointFalloff(2.0, 4.0), 1.0); // on the sphere
  EXPECT_DOUBLE_EQ(mmv::mmvPointFalloff(2.0, 1.0), 1.0); // inside: clamped
}

TEST(LightModel, PointFalloffIsFiniteAtTheLight)
{
  const double f = mmv::mmvPointFalloff(0.1, 0.0);
  EXPECT_TRUE(std::isfinite(f));
  EXPECT_DOUBLE_EQ(f, 1.0);
}

TEST(LightModel, ZeroRadiusSelectsVTKAttenuation)
{
  // Radius 0: VTK's 1 / (c0 + c1 d + c2 d^2); the vtkLight default (1, 0, 0)
  // means no falloff at any distance.
  mmv::LightSource light;
  light.Kind = mmv::PointLight;
  light.Position = { 1.0, 2.0, 3.0 };
  light.Radius = 0.0;
  EXPECT_EQ(mmv::mmvLightGeometryTerm(light, light.Position), 1.0);
  EXPECT_EQ(mmv::mmvLightGeometryTerm(light, glm::dvec3(601.0, 2.0, 3.0)), 1.0);
  // (0.5, 0.25, 0.125) at distance 4 (a 0-0-4 offset): 1 / (0.5 + 1 + 2).
  light.Attenuation = { 0.5, 0.25, 0.125 };
  EXPECT_DOUBLE_EQ(mmv::mmvLightGeometryTerm(light, glm::dvec3(1.0, 2.0, 7.0)), 1.0 / 3.5);
  // Distance 5 along a 3-4-5 triangle.
  EXPECT_DOUBLE_EQ(
    mmv::mmvLightGeometryTerm(light, glm::dvec3(4.0, 6.0, 3.0)), 1.0 / (0.5 + 1.25 + 3.125));
  // A radius > 0 selects eq. 12 whatever the attenuation.
  light.Radius = 2.0;
  EXPECT_DOUBLE_EQ(mmv::mmvLightGeometryTerm(light, glm::dvec3(4.0, 6.0, 3.0)), 4.0 / 25.0);
}

TEST(LightModel, AttenuationWithoutConstantTermStaysFiniteAtTheLight)
{
  // (0, 0, 1) is the physical inverse square law: 1/d^2, clamped at the light.
  const glm::dvec3 inverseSquare(0.0, 0.0, 1.0);
  EXPECT_DOUBLE_EQ(mmv::mmvAttenuationFalloff(inverseSquare, 16.0), 1.0 / 16.0);
  EXPECT_DOUBLE_EQ(
    mmv::mmvAttenuationFalloff(inverseSquare, 0.0), 1.0 / mmv::MinAttenuationDenominator);
  EXPECT_DOUBLE_EQ(mmv::mmvAttenuationFalloff(glm::dvec3(0.0, 1.0, 0.0), 1.0e-12),
    1.0 / mmv::MinAttenuationDenominator);
}

TEST(LightModel, SpotExponentIsVTKsAngularFalloff)
{
  const glm::dvec3 axis(0.0, 0.0, -1.0);
  // (3, 0, -4)/5: cos 0.8 to the axis, inside a cone of cos 0.6.
  EXPECT_DOUBLE_EQ(mmv::mmvSpotFactor(glm::dvec3(3.0, 0.0, -4.0), axis, 0.6, 1.0), 0.8);
  EXPECT_DOUBLE_EQ(
    mmv::mmvSpotFactor(glm::dvec3(3.0, 0.0, -4.0), axis, 0.6, 2.5), std::pow(0.8, 2.5));
  // Exponent 0: the hard cone of eq. 14.
  EXPECT_EQ(mmv::mmvSpotFactor(glm::dvec3(3.0, 0.0, -4.0), axis, 0.6, 0.0), 1.0);
  // Outside stays 0 whatever the exponent.
  EXPECT_EQ(mmv::mmvSpotFactor(glm::dvec3(4.1, 0.0, -3.0), axis, 0.6, 2.5), 0.0);
  // A 90-degree half-angle (cos 0) with exponent > 0: 0 on the edge, no NaN.
  EXPECT_EQ(mmv::mmvSpotFactor(glm::dvec3(1.0, 0.0, 0.0), axis, 0.0, 3.0), 0.0);
}

TEST(LightModel, SpotVisibilityInsideOutsideAndOnTheEdge)
{
  const glm::dvec3 axis(0.0, 0.0, -1.0);
  // (4, 0, -3)/5 makes an exact cosine of 0.6 with the axis.
  // On the edge: lit, as VTK's Phong (coneDot >= cos).
  EXPECT_EQ(mmv::mmvSpotVisibility(glm::dvec3(4.0, 0.0, -3.0), axis, 0.6), 1.0);
  EXPECT_EQ(mmv::mmvSpotVisibility(glm::dvec3(3.9, 0.0, -3.0), axis, 0.6), 1.0);
  EXPECT_EQ(mmv::mmvSpotVisibility(glm::dvec3(4.1, 0.0, -3.0), axis, 0.6), 0.0);
  EXPECT_EQ(mmv::mmvSpotVisibility(glm::dvec3(0.0, 0.0, -7.0), axis, 0.6), 1.0);
  EXPECT_EQ(mmv::mmvSpotVisibility(glm::dvec3(0.0, 0.0, 7.0), axis, 0.6), 0.0); // behind
  // A 90-degree half-angle: perpendicular points lie exactly on the edge.
  EXPECT_EQ(mmv::mmvSpotVisibility(glm::dvec3(1.0, 0.0, 0.0), axis, 0.0), 1.0);
  // The length of the vector does not matter.
  EXPECT_EQ(mmv::mmvSpotVisibility(glm::dvec3(3.9e-3, 0.0, -3.0e-3), axis, 0.6), 1.0);
}

TEST(LightModel, SpotVisibilityAtTheApexIsFinite)
{
  EXPECT_EQ(mmv::mmvSpotVisibility(glm::dvec3(0.0), glm::dvec3(0.0, 0.0, -1.0), 0.9), 1.0);
}

TEST(LightModel, DirectionalGeometryTermIsOne)
{
  mmv::LightSource light;
  light.Kind = mmv::DirectionalLight;
  light.ToLight = glm::dvec3(0.0, 1.0, 0.0);
  EXPECT_EQ(mmv::mmvLightGeometryTerm(light, glm::dvec3(1e6, -3.0, 2.0)), 1.0);
  double distance = 0.0;
  const glm::dvec3 dir = mmv::mmvDirectionToLight(light, glm::dvec3(5.0), distance);
  EXPECT_LT(distance, 0.0);
  EXPECT_EQ(dir, light.ToLight);
}

TEST(LightModel, PointGeometryTermMatchesEquation12)
{
  const mmv::LightSource light = MakePoint(glm::dvec3(1.0, 2.0, 3.0), 1.5);
  // Distance 3 -> 1.5^2 / 9.
  EXPECT_DOUBLE_EQ(mmv::mmvLightGeometryTerm(light, glm::dvec3(1.0, 2.0, 6.0)), 0.25);
  // Distance 5 along a 3-4-5 triangle.
  EXPECT_DOUBLE_EQ(mmv::mmvLightGeometryTerm(light, glm::dvec3(4.0, 6.0, 3.0)), 2.25 / 25.0);
  // Inside the radius and at the light itself: 1, finite.
  EXPECT_DOUBLE_EQ(mmv::mmvLightGeometryTerm(light, glm::dvec3(1.0, 2.0, 4.0)), 1.0);
  const double atLight = mmv::mmvLightGeometryTerm(light, light.Position);
  EXPECT_TRUE(std::isfinite(atLight));
  EXPECT_DOUBLE_EQ(atLight, 1.0);

  double distance = 0.0;
  const glm::dvec3 dir = mmv::mmvDirectionToLight(light, glm::dvec3(4.0, 6.0, 3.0), distance);
  EXPECT_DOUBLE_EQ(distance, 5.0);
  EXPECT_NEAR(dir.x, -0.6, 1e-15);
  EXPECT_NEAR(dir.y, -0.8, 1e-15);
  EXPECT_NEAR(dir.z, 0.0, 1e-15);
  const glm::dvec3 atDir = mmv::mmvDirectionToLight(light, light.Position, distance);
  EXPECT_EQ(distance, 0.0);
  EXPECT_TRUE(std::isfinite(atDir.x) && std::isfinite(atDir.y) && std::isfinite(atDir.z));
}

TEST(LightModel, SpotGeometryTermIsPointTermInsideTheConeAndZeroOutside)
{
  const glm::dvec3 position(0.0, 0.0, 10.0);
  const mmv::LightSource point = MakePoint(position, 1.0);
  const mmv::LightSource spot = MakeSpot(position, glm::dvec3(0.0, 0.0, -1.0), 0.6, 1.0);
  const glm::dvec3 inside(3.0, 0.0, 0.0); // cos = 10/sqrt(109) = 0.958
  const glm::dvec3 edge(4.0, 0.0, 7.0);   // cos = 0.6 exactly
  const glm::dvec3 outside(20.0, 0.0, 0.0);
  EXPECT_DOUBLE_EQ(
    mmv::mmvLightGeometryTerm(spot, inside), mmv::mmvLightGeometryTerm(point, inside));
  EXPECT_DOUBLE_EQ(mmv::mmvLightGeometryTerm(spot, inside), 1.0 / 109.0);
  EXPECT_DOUBLE_EQ(mmv::mmvLightGeometryTerm(spot, edge), 1.0 / 25.0); // edge: lit, as VTK
  EXPECT_EQ(mmv::mmvLightGeometryTerm(spot, outside), 0.0);
  EXPECT_GT(mmv::mmvLightGeometryTerm(point, outside), 0.0);
  const double atApex = mmv::mmvLightGeometryTerm(spot, position);
  EXPECT_TRUE(std::isfinite(atApex));
  EXPECT_DOUBLE_EQ(atApex, 1.0);
}
