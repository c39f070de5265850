// The environment colour c_r of eq. 17 on the CPU (vtkMultiMaterialEnvironment,
// MultiMaterialVolume::Filters): read from a renderer with no OpenGL (this
// test links the CPU module only), looked up against closed forms. The GPU
// side and bad textures: TestReflection.
#include "vtkCamera.h"
#include "vtkMatrix4x4.h"
#include "vtkMultiMaterialEnvironment.h"
#include "vtkMultiMaterialEnvironmentLookup.h"
#include "vtkNew.h"
#include "vtkRenderer.h"

#include "mmvTestEnvironments.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace
{
// A colour that changes with every component of the unit frame direction.
glm::dvec3 DirectionColour(const glm::dvec3& e)
{
  return 0.5 + 0.5 * glm::normalize(e);
}

// Object -> world: a quarter turn about z (object x is world y).
void QuarterTurn(vtkMatrix4x4* m)
{
  m->Zero();
  m->SetElement(0, 1, -1.0);
  m->SetElement(1, 0, 1.0);
  m->SetElement(2, 2, 1.0);
  m->SetElement(3, 3, 1.0);
}

glm::dvec3 Apply(vtkMatrix4x4* m, const glm::dvec3& d)
{
  glm::dvec3 w(0.0);
  for (int i = 0; i < 3; ++i)
  {
    w[i] = m->GetElement(i, 0) * d.x + m->GetElement(i, 1) * d.y + m->GetElement(i, 2) * d.z;
  }
  return w;
}

std::vector<glm::dvec3> RandomDirections(int count)
{
  std::mt19937 random(13);
  std::normal_distribution<double> normal;
  std::vector<glm::dvec3> directions;
  while (static_cast<int>(directions.size()) < count)
  {
    const glm::dvec3 d(normal(random), normal(random), normal(random));
    if (glm::length(d) > 0.1)
    {
      directions.push_back(glm::normalize(d));
    }
  }
  return directions;
}

// The largest colour difference between Lookup(d) and DirectionColour of d's
// frame direction, for a renderer whose environment up is world +z and
// right world +x (front = up x right = world +y): e = (w.x, w.z, w.y) for the
// world direction w of the object direction d. The texture must give `kind`.
double LargestLookupError(vtkTexture* texture, int kind)
{
  vtkNew<vtkRenderer> renderer;
  renderer->SetEnvironmentTexture(texture);
  renderer->SetEnvironmentUp(0.0, 0.0, 1.0);
  renderer->SetEnvironmentRight(1.0, 0.0, 0.0);
  vtkNew<vtkMatrix4x4> objectToWorld;
  QuarterTurn(objectToWorld);
  vtkNew<vtkMultiMaterialEnvironment> environment;
  std::vector<std::string> problems;
  environment->Update(renderer, objectToWorld, mmv::ReflectEnvironmentTexture, &problems);
  EXPECT_TRUE(problems.empty()) << problems.front();
  EXPECT_EQ(environment->GetTexture(), texture);
  EXPECT_EQ(environment->GetKind(), kind);
  EXPECT_FALSE(environment->GetGrey());
  double largest = 0.0;
  for (const glm::dvec3& d : RandomDirections(2000))
  {
    const glm::dvec3 w = Apply(objectToWorld, d);
    const glm::dvec3 expected = DirectionColour(glm::dvec3(w.x, w.z, w.y));
    // Any length but zero.
    const glm::dvec3 c = environment->Lookup(3.0 * d);
    largest = std::max(largest, glm::length(c - expected));
  }
  return largest;
}
}

TEST(Environment, CubeMapLookupIsTheColourOfTheDirectionInTheRenderersFrame)
{
  constexpr int size = 64;
  auto texture = mmvtest::MakeCubeMap(DirectionColour, size);

  // Nearest texel: the direction is off by at most half a texel diagonal,
  // about sqrt(2) / size, and the colour by half of that, plus 8-bit
  // rounding (0.5 / 255 per channel).
  const double largest = LargestLookupError(texture, mmv::CubeMapEnvironment);
  std::cout << "cube map " << size << "^2: largest colour error " << largest << "\n";
  EXPECT_LT(largest, 0.5 * std::sqrt(2.0) / size + std::sqrt(3.0) * 0.5 / 255.0);
}

TEST(Environment, EquirectangularLookupIsTheColourOfTheDirectionInTheRenderersFrame)
{
  constexpr int width = 128;
  auto texture = mmvtest::MakeEquirectangular(DirectionColour, width);

  // A texel spans 2 pi / width in longitude and latitude: the direction is
  // off by at most pi / width * sqrt(2), the colour by half of that, plus
  // 8-bit rounding.
  const double pi = 3.14159265358979323846;
  const double largest = LargestLookupError(texture, mmv::EquirectangularEnvironment);
  std::cout << "equirectangular " << width << " x " << width / 2 << ": largest colour error "
            << largest << "\n";
  EXPECT_LT(largest, 0.5 * std::sqrt(2.0) * pi / width + std::sqrt(3.0) * 0.5 / 255.0);
}

TEST(Environment, BackgroundIsTheGradientAroundTheCamerasViewUp)
{
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(0.1, 0.2, 0.3);
  renderer->SetBackground2(0.9, 0.8, 0.7);
  renderer->GradientBackgroundOn();
  renderer->GetActiveCamera()->SetViewUp(0.0, 1.0, 0.0);
  // A texture the background source ignores.
  renderer->SetEnvironmentTexture(mmvtest::MakeCubeMap(DirectionColour));
  vtkNew<vtkMatrix4x4> objectToWorld;
  QuarterTurn(objectToWorld);
  vtkNew<vtkMultiMaterialEnvironment> environment;
  environment->Update(renderer, objectToWorld, mmv::ReflectBackground, nullptr);
  EXPECT_EQ(environment->GetKind(), mmv::BackgroundEnvironment);
  EXPECT_EQ(environment->GetTexture(), nullptr);

  const glm::dvec3 bottom(0.1, 0.2, 0.3), top(0.9, 0.8, 0.7);
  // Object +x is world +y, the view-up: the top colour; object +y is world
  // -x, across: halfway; 60 degrees below the view-up: a quarter of the way.
  EXPECT_LT(glm::length(environment->Lookup(glm::dvec3(2.0, 0.0, 0.0)) - top), 1e-12);
  EXPECT_LT(glm::length(environment->Lookup(glm::dvec3(-1.0, 0.0, 0.0)) - bottom), 1e-12);
  EXPECT_LT(
    glm::length(environment->Lookup(glm::dvec3(0.0, 1.0, 0.0)) - 0.5 * (bottom + top)), 1e-12);
  const glm::dvec3 below(-0.5, 0.0, std::sqrt(0.75));
  EXPECT_LT(glm::length(environment->Lookup(below) - (0.75 * bottom + 0.25 * top)), 1e-12);

  // Without the gradient, Background everywhere.
  renderer->GradientBackgroundOff();
  environment->Update(renderer, objectToWorld, mmv::ReflectEnvironmentTexture, nullptr);
  EXPECT_EQ(environment->GetKind(), mmv::CubeMapEnvironment);
  renderer->SetEnvironmentTexture(nullptr);
  environment->Update(renderer, objectToWorld, mmv::ReflectEnvironmentTexture, nullptr);
  EXPECT_EQ(environment->GetKind(), mmv::BackgroundEnvironment);
  EXPECT_LT(glm::length(environment->Lookup(glm::dvec3(1.0, 0.0, 0.0)) - bottom), 1e-12);
}

TEST(Environment, SRGBTexturesAreDecodedAsTheGPUDecodesThem)
{
  // A uniform grey of 128 / 255, encoded sRGB: linear ((c + 0.055) / 1.055)^2.4.
  const double encoded = 128.0 / 255.0;
  const double linear = std::pow((encoded + 0.055) / 1.055, 2.4);
  auto texture =
    mmvtest::MakeEquirectangular([encoded](const glm::dvec3&) { return glm::dvec3(encoded); }, 8);
  vtkNew<vtkRenderer> renderer;
  renderer->SetEnvironmentTexture(texture);
  vtkNew<vtkMatrix4x4> identity;
  vtkNew<vtkMultiMaterialEnvironment> environment;

  environment->Update(renderer, identity, mmv::ReflectEnvironmentTexture, nullptr);
  EXPECT_LT(
    glm::length(environment->Lookup(glm::dvec3(0.3, -0.2, 1.0)) - glm::dvec3(encoded)), 1e-12);
  texture->UseSRGBColorSpaceOn();
  environment->Update(renderer, identity, mmv::ReflectEnvironmentTexture, nullptr);
  EXPECT_LT(
    glm::length(environment->Lookup(glm::dvec3(0.3, -0.2, 1.0)) - glm::dvec3(linear)), 1e-12);
  EXPECT_NEAR(linear, 0.2158605, 1e-6);
}

TEST(Environment, PinnedBackgroundOverridesTheRenderersUntilCleared)
{
  // ParaView clears the renderer's background to black while parallel ranks
  // draw; the representation pins the view's background before the render.
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(0.0, 0.0, 0.0);
  vtkNew<vtkMatrix4x4> objectToWorld;
  vtkNew<vtkMultiMaterialEnvironment> environment;
  const double bottom[3] = { 0.1, 0.1, 0.15 };
  const double top[3] = { 0.3, 0.4, 0.5 };
  environment->SetBackgroundOverride(bottom, top);
  environment->Update(renderer, objectToWorld, mmv::ReflectBackground, nullptr);
  EXPECT_EQ(environment->GetBackgroundBottom(), glm::dvec3(0.1, 0.1, 0.15));
  EXPECT_EQ(environment->GetBackgroundTop(), glm::dvec3(0.3, 0.4, 0.5));
  environment->ClearBackgroundOverride();
  environment->Update(renderer, objectToWorld, mmv::ReflectBackground, nullptr);
  EXPECT_EQ(environment->GetBackgroundBottom(), glm::dvec3(0.0));
  EXPECT_EQ(environment->GetBackgroundTop(), glm::dvec3(0.0));
}
