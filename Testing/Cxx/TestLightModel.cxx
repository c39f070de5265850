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

mmv::LightSource MakeSpot(const glm::dvec3& position, const glm::dvec3& axis, double cosCone, double radius)
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

TEST(LightModel, ZeroRadiusIsTheLimitOfEquation12)
{
  // Radius 0: 1 at the light itself (not 0/0), 0 everywhere else, which is
  // where eq. 12 goes as the radius shrinks.
  EXPECT_EQ(mmv::mmvPointFalloff(0.0, 0.0), 1.0);
  EXPECT_EQ(mmv::mmvPointFalloff(0.0, 1.0e-12), 0.0);
  EXPECT_EQ(mmv::mmvPointFalloff(0.0, 4.0), 0.0);
  EXPECT_LT(mmv::mmvPointFalloff(1.0e-3, 4.0), 1.0e-6);
  mmv::LightSource light;
  light.Kind = mmv::PointLight;
  light.Position = { 1.0, 2.0, 3.0 };
  light.Radius = 0.0;
  EXPECT_EQ(mmv::mmvLightGeometryTerm(light, light.Position), 1.0);
  EXPECT_EQ(mmv::mmvLightGeometryTerm(light, glm::dvec3(0.0)), 0.0);
}

TEST(LightModel, SpotVisibilityInsideOutsideAndOnTheEdge)
{
  const glm::dvec3 axis(0.0, 0.0, -1.0);
  // (4, 0, -3)/5 makes an exact cosine of 0.6 with the axis.
  EXPECT_EQ(mmv::mmvSpotVisibility(glm::dvec3(4.0, 0.0, -3.0), axis, 0.6), 0.0);
  EXPECT_EQ(mmv::mmvSpotVisibility(glm::dvec3(3.9, 0.0, -3.0), axis, 0.6), 1.0);
  EXPECT_EQ(mmv::mmvSpotVisibility(glm::dvec3(4.1, 0.0, -3.0), axis, 0.6), 0.0);
  EXPECT_EQ(mmv::mmvSpotVisibility(glm::dvec3(0.0, 0.0, -7.0), axis, 0.6), 1.0);
  EXPECT_EQ(mmv::mmvSpotVisibility(glm::dvec3(0.0, 0.0, 7.0), axis, 0.6), 0.0); // behind
  // A 90-degree half-angle: perpendicular points lie exactly on the edge.
  EXPECT_EQ(mmv::mmvSpotVisibility(glm::dvec3(1.0, 0.0, 0.0), axis, 0.0), 0.0);
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
  const glm::dvec3 inside(3.0, 0.0, 0.0);  // cos = 10/sqrt(109) = 0.958
  const glm::dvec3 edge(4.0, 0.0, 7.0);    // cos = 0.6 exactly
  const glm::dvec3 outside(20.0, 0.0, 0.0);
  EXPECT_DOUBLE_EQ(mmv::mmvLightGeometryTerm(spot, inside), mmv::mmvLightGeometryTerm(point, inside));
  EXPECT_DOUBLE_EQ(mmv::mmvLightGeometryTerm(spot, inside), 1.0 / 109.0);
  EXPECT_EQ(mmv::mmvLightGeometryTerm(spot, edge), 0.0);
  EXPECT_EQ(mmv::mmvLightGeometryTerm(spot, outside), 0.0);
  EXPECT_GT(mmv::mmvLightGeometryTerm(point, outside), 0.0);
  const double atApex = mmv::mmvLightGeometryTerm(spot, position);
  EXPECT_TRUE(std::isfinite(atApex));
  EXPECT_DOUBLE_EQ(atApex, 1.0);
}
