// The GLSL in Shaders/ against its C++ mirror: each shader function is run on
// the GPU (llvmpipe under Xvfb in CI) over a grid of inputs, read back from a
// float framebuffer and compared with the CPU function of the same name.
#include "mmvEmission.h"
#include "mmvLightModel.h"
#include "mmvPhaseFunction.h"
#include "mmvShading.h"
#include "mmvTestWindow.h"
#include "mmvTint.h"
#include "vtkIrradianceDiffusion.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMultiMaterialLightModel.h"
#include "vtkMultiMaterialLightUniforms.h"
#include "vtkMultiMaterialParameters.h"
#include "vtkMultiMaterialPhaseFunction.h"
#include "vtkMultiMaterialShaderAssembly.h"
#include "vtkMultiMaterialShading.h"
#include "vtkMultiMaterialTextures.h"
#include "vtkTextureObject.h"

#include "vtkNew.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkRenderWindow.h"
#include "vtkShaderProgram.h"
#include "vtk_glew.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

namespace
{
constexpr int Size = 48;

mmv::ShaderVariant FullVariant(int lights = mmv::MaxLights)
{
  mmv::ShaderVariant variant;
  variant.NumberOfLights = lights;
  variant.Reflection = true;
  variant.Anisotropy = lights > 0;
  variant.Emission = true;
  variant.RGBIrradiance = lights > 0;
  return variant;
}

/// Draws a full-screen quad with `body` as the fragment shader's main() into a
/// Size x Size RGBA32F target and returns the pixels.
class ShaderRunner
{
public:
  ShaderRunner()
  {
    this->Window->SetOffScreenRendering(1);
    this->Window->SetSize(Size, Size);
    this->GL = vtkOpenGLRenderWindow::SafeDownCast(this->Window);
    if (this->GL)
    {
      this->GL->Initialize();
    }
  }

  /// The shaders are composed as the ray cast composes them
  /// (vtkMultiMaterialShaderAssembly.cxx), for `variant`: by default every
  /// optional term and MaxLights lights in two irradiance textures.
  bool Run(const std::string& body, const std::function<void(vtkShaderProgram*)>& setUniforms,
    std::vector<float>& pixels, const mmv::ShaderVariant& variant = FullVariant())
  {
    if (!this->GL)
    {
      return false;
    }
    this->GL->MakeCurrent();
    std::string fs = std::string("//VTK::System::Dec\n") + mmv::VariantDefines(variant);
    if (variant.NumberOfLights > 0)
    {
      fs += mmv::LightUniformDeclarations("MMV_NUMBER_OF_LIGHTS");
    }
    fs += std::string(mmvLightModel) + mmvPhaseFunction + mmvEmission +
      (variant.RGBIrradiance && variant.NumberOfLights > 0 ? mmvTint : "") + mmvShading +
      "\nin vec2 texCoord;\n//VTK::Output::Dec\n" + body;
    vtkNew<vtkOpenGLFramebufferObject> fbo;
    fbo->SetContext(this->GL);
    this->GL->GetState()->PushFramebufferBindings();
    fbo->PopulateFramebuffer(Size, Size, true, 1, VTK_FLOAT, false, 0, 0);
    fbo->Bind();
    fbo->ActivateDrawBuffer(0);
    this->GL->GetState()->vtkglViewport(0, 0, Size, Size);
    this->GL->GetState()->vtkglDisable(GL_BLEND);
    this->GL->GetState()->vtkglDisable(GL_DEPTH_TEST);
    this->GL->GetState()->vtkglDisable(GL_SCISSOR_TEST);
    // -1 marks pixels the quad did not write.
    this->GL->GetState()->vtkglClearColor(-1.0, -1.0, -1.0, -1.0);
    this->GL->GetState()->vtkglClear(GL_COLOR_BUFFER_BIT);
    bool ok = false;
    {
      vtkOpenGLQuadHelper quad(this->GL, nullptr, fs.c_str(), "");
      if (quad.Program && this->GL->GetShaderCache()->ReadyShaderProgram(quad.Program))
      {
        setUniforms(quad.Program);
        quad.Render();
        pixels.assign(4 * Size * Size, -1.0f);
        fbo->ActivateReadBuffer(0);
        glReadPixels(0, 0, Size, Size, GL_RGBA, GL_FLOAT, pixels.data());
        ok = true;
      }
      quad.ReleaseGraphicsResources(this->GL);
    }
    this->GL->GetState()->PopFramebufferBindings();
    return ok;
  }

  vtkSmartPointer<vtkRenderWindow> Window = mmvtest::NewRenderWindow();
  vtkOpenGLRenderWindow* GL = nullptr;
};

// Pixel (i, j) samples the point x = (u, v, 0) with u, v in [-2, 2].
glm::dvec3 PixelPoint(int i, int j)
{
  const double u = -2.0 + 4.0 * (i + 0.5) / Size;
  const double v = -2.0 + 4.0 * (j + 0.5) / Size;
  return { u, v, 0.0 };
}

// The light of the tests below: above the grid's plane, its spot cone
// cutting through the grid. Falloff variant 0: eq. 12 (radius 0.5); 1: VTK
// attenuation (1, 0.5, 2) with exponent 7.5; 2: VTK attenuation (0, 0, 1),
// exponent 0 (hard cone); 3: the vtkLight defaults, (1, 0, 0) and exponent 1.
mmv::LightSource TestLight(int kind, int falloff = 0)
{
  mmv::LightSource light;
  light.Kind = static_cast<mmv::LightKind>(kind);
  light.Position = { 0.3, -0.2, 1.0 };
  light.ToLight = glm::normalize(glm::dvec3(-0.4, 0.5, 1.0));
  light.SpotAxis = glm::normalize(glm::dvec3(0.2, 0.1, -1.0));
  light.CosCone = std::cos(30.0 * M_PI / 180.0);
  light.Radius = falloff == 0 ? 0.5 : 0.0;
  const glm::dvec3 attenuation[4] = { { 1.0, 0.0, 0.0 }, { 1.0, 0.5, 2.0 }, { 0.0, 0.0, 1.0 },
    { 1.0, 0.0, 0.0 } };
  const double exponent[4] = { 0.0, 7.5, 0.0, 1.0 };
  light.Attenuation = attenuation[falloff];
  light.SpotExponent = exponent[falloff];
  return light;
}

const char* LightGeometryBody = R"(
uniform int kind;
uniform vec3 lightPosition;
uniform vec3 spotAxis;
uniform float cosCone;
uniform float spotExponent;
uniform vec3 attenuation;
uniform float radius;
void main()
{
  vec3 x = vec3(-2.0 + 4.0 * texCoord, 0.0);
  gl_FragData[0] = vec4(mmvLightGeometryTerm(kind, lightPosition, spotAxis, cosCone,
    spotExponent, attenuation, radius, x),
    mmvSpotFactor(x - lightPosition, spotAxis, cosCone, spotExponent),
    float(4 * MMV_ANISOTROPY_ROW + MMV_ANISOTROPY_CHANNEL), float(MMV_SPOT_LIGHT));
}
)";
}

TEST(ShaderMirror, LightGeometryTermMatchesCPU)
{
  ShaderRunner runner;
  ASSERT_NE(runner.GL, nullptr);

  for (int falloff = 0; falloff < 4; ++falloff)
    for (int kind : { mmv::DirectionalLight, mmv::PointLight, mmv::SpotLight })
    {
      const mmv::LightSource light = TestLight(kind, falloff);

      std::vector<float> pixels;
      ASSERT_TRUE(runner.Run(
        LightGeometryBody,
        [&](vtkShaderProgram* p)
        {
          p->SetUniformi("kind", kind);
          const float pos[3] = { 0.3f, -0.2f, 1.0f };
          const float axis[3] = { float(light.SpotAxis.x), float(light.SpotAxis.y),
            float(light.SpotAxis.z) };
          const glm::vec3 attenuation(light.Attenuation);
          p->SetUniform3f("lightPosition", pos);
          p->SetUniform3f("spotAxis", axis);
          p->SetUniformf("cosCone", float(light.CosCone));
          p->SetUniformf("spotExponent", float(light.SpotExponent));
          p->SetUniform3f("attenuation", &attenuation.x);
          p->SetUniformf("radius", float(light.Radius));
        },
        pixels));

      int compared = 0;
      for (int j = 0; j < Size; ++j)
      {
        for (int i = 0; i < Size; ++i)
        {
          const float* px = &pixels[4 * (j * Size + i)];
          const glm::dvec3 x = PixelPoint(i, j);
          const glm::dvec3 toPoint = x - light.Position;
          // float and double disagree right on the cone edge; skip a thin band.
          if (std::abs(glm::dot(glm::normalize(toPoint), light.SpotAxis) - light.CosCone) < 1e-4)
          {
            continue;
          }
          const double cpu = mmv::mmvLightGeometryTerm(light, x);
          ASSERT_NEAR(px[0], cpu, 1e-5 * std::max(1.0, cpu))
            << "kind " << kind << " falloff " << falloff << " pixel " << i << "," << j;
          ASSERT_NEAR(px[1],
            mmv::mmvSpotFactor(toPoint, light.SpotAxis, light.CosCone, light.SpotExponent), 1e-5);
          // The prelude's generated names carry the C++ contract's values.
          const mmv::MaterialTexel texel = mmv::MaterialTexelLayout[mmv::Anisotropy];
          ASSERT_EQ(px[2], float(4 * texel.Row + texel.Channel));
          ASSERT_EQ(px[3], float(mmv::SpotLight));
          ++compared;
        }
      }
      EXPECT_GT(compared, Size * Size * 9 / 10);
    }
}

namespace
{
const char* DirectionToLightBody = R"(
uniform int kind;
uniform vec3 lightPosition;
uniform vec3 toLight;
void main()
{
  vec3 x = vec3(-2.0 + 4.0 * texCoord, 0.0);
  float lightDistance;
  vec3 dir = mmvDirectionToLight(kind, lightPosition, toLight, x, lightDistance);
  gl_FragData[0] = vec4(dir, lightDistance);
}
)";
}

TEST(ShaderMirror, DirectionToLightMatchesCPU)
{
  ShaderRunner runner;
  ASSERT_NE(runner.GL, nullptr);

  for (int kind : { mmv::DirectionalLight, mmv::PointLight, mmv::SpotLight })
  {
    const mmv::LightSource light = TestLight(kind);

    std::vector<float> pixels;
    ASSERT_TRUE(runner.Run(
      DirectionToLightBody,
      [&](vtkShaderProgram* p)
      {
        p->SetUniformi("kind", kind);
        const glm::vec3 position(light.Position);
        const glm::vec3 toLight(light.ToLight);
        p->SetUniform3f("lightPosition", &position.x);
        p->SetUniform3f("toLight", &toLight.x);
      },
      pixels));

    for (int j = 0; j < Size; ++j)
    {
      for (int i = 0; i < Size; ++i)
      {
        const float* px = &pixels[4 * (j * Size + i)];
        double distance = 0.0;
        const glm::dvec3 dir = mmv::mmvDirectionToLight(light, PixelPoint(i, j), distance);
        for (int a = 0; a < 3; ++a)
        {
          ASSERT_NEAR(px[a], dir[a], 1e-5) << "kind " << kind << " pixel " << i << "," << j;
        }
        if (kind == mmv::DirectionalLight)
        {
          ASSERT_EQ(distance, -1.0);
          ASSERT_EQ(px[3], -1.0f);
        }
        else
        {
          ASSERT_NEAR(px[3], distance, 1e-5 * std::max(1.0, distance))
            << "kind " << kind << " pixel " << i << "," << j;
        }
      }
    }
  }
}

namespace
{
// Column block -> radius 0, 0.25, 0.5, 0.75; row j -> squared distance
// 0.02 j (row 0 is the light's own position: 0/0 without the guard).
const char* PointFalloffBody = R"(
void main()
{
  float radius = floor(texCoord.x * 4.0) * 0.25;
  float distance2 = floor(texCoord.y * float(SIZE)) * 0.02;
  gl_FragData[0] = vec4(mmvPointFalloff(radius, distance2), radius, distance2, 0.0);
}
)";
}

TEST(ShaderMirror, PointFalloffMatchesCPUIncludingZeroRadius)
{
  ShaderRunner runner;
  ASSERT_NE(runner.GL, nullptr);
  std::vector<float> pixels;
  const std::string body = "#define SIZE " + std::to_string(Size) + "\n" + PointFalloffBody;
  ASSERT_TRUE(runner.Run(
    body, [](vtkShaderProgram*) {}, pixels));
  for (int j = 0; j < Size; ++j)
  {
    for (int i = 0; i < Size; ++i)
    {
      const float* px = &pixels[4 * (j * Size + i)];
      const double radius = std::floor((i + 0.5) / Size * 4.0) * 0.25;
      const double distance2 = j * 0.02;
      ASSERT_EQ(px[1], float(radius)) << i << "," << j;
      ASSERT_NEAR(px[2], distance2, 1e-6) << i << "," << j;
      const double cpu = mmv::mmvPointFalloff(radius, distance2);
      ASSERT_FALSE(std::isnan(px[0])) << i << "," << j;
      ASSERT_NEAR(px[0], cpu, 1e-6) << "radius " << radius << " d2 " << distance2;
    }
  }
}

namespace
{
// Column block -> attenuation (1, 0, 0), (1, 0.5, 2), (0, 1, 0), (0, 0, 1);
// row j -> squared distance 0.02 j (row 0: the light's own position, where
// the polynomials without a constant term vanish and the clamp holds).
const char* AttenuationFalloffBody = R"(
void main()
{
  int block = int(floor(texCoord.x * 4.0));
  vec3 attenuation = block == 0 ? vec3(1.0, 0.0, 0.0) : block == 1 ? vec3(1.0, 0.5, 2.0)
    : block == 2 ? vec3(0.0, 1.0, 0.0) : vec3(0.0, 0.0, 1.0);
  float distance2 = floor(texCoord.y * float(SIZE)) * 0.02;
  gl_FragData[0] = vec4(mmvDistanceFalloff(0.0, attenuation, distance2), float(block),
    distance2, 0.0);
}
)";
}

TEST(ShaderMirror, AttenuationFalloffMatchesCPUIncludingTheLightItself)
{
  ShaderRunner runner;
  ASSERT_NE(runner.GL, nullptr);
  std::vector<float> pixels;
  const std::string body = "#define SIZE " + std::to_string(Size) + "\n" + AttenuationFalloffBody;
  ASSERT_TRUE(runner.Run(
    body, [](vtkShaderProgram*) {}, pixels));
  const glm::dvec3 attenuation[4] = { { 1.0, 0.0, 0.0 }, { 1.0, 0.5, 2.0 }, { 0.0, 1.0, 0.0 },
    { 0.0, 0.0, 1.0 } };
  for (int j = 0; j < Size; ++j)
  {
    for (int i = 0; i < Size; ++i)
    {
      const float* px = &pixels[4 * (j * Size + i)];
      const int block = static_cast<int>(std::floor((i + 0.5) / Size * 4.0));
      ASSERT_EQ(px[1], float(block));
      const double cpu = mmv::mmvDistanceFalloff(0.0, attenuation[block], j * 0.02);
      ASSERT_TRUE(std::isfinite(px[0])) << i << "," << j;
      ASSERT_NEAR(px[0], cpu, 1e-5 * std::max(1.0, cpu)) << "block " << block << " row " << j;
    }
  }
}

TEST(ShaderMirror, SpotLightHasLitAndUnlitPixels)
{
  // Guards the comparison above against a degenerate scene: the spot must
  // light some of the grid and leave some of it dark.
  const mmv::LightSource light = TestLight(mmv::SpotLight);
  int lit = 0;
  for (int j = 0; j < Size; ++j)
  {
    for (int i = 0; i < Size; ++i)
    {
      lit += mmv::mmvLightGeometryTerm(light, PixelPoint(i, j)) > 0.0 ? 1 : 0;
    }
  }
  EXPECT_GT(lit, Size * Size / 20);
  EXPECT_LT(lit, Size * Size * 19 / 20);
}

namespace
{
// Pixel (i, j) -> a light direction sweeping the sphere around n = +z, and
// a shininess growing along i (0 included: the pow(0, 0) guard).
glm::dvec3 SweepLight(int i, int j)
{
  const double theta = M_PI * (j + 0.5) / Size;
  const double phi = 2.0 * M_PI * (i + 0.5) / Size;
  return { std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta) };
}

const char* BlinnPhongBody = R"(
void main()
{
  float theta = 3.14159265358979 * texCoord.y;
  float phi = 6.28318530717959 * texCoord.x;
  vec3 l = vec3(sin(theta) * cos(phi), sin(theta) * sin(phi), cos(theta));
  vec3 n = vec3(0.0, 0.0, 1.0);
  vec3 v = normalize(vec3(0.3, -0.2, 1.0));
  float shininess = floor(texCoord.x * 4.0) * 25.0;
  vec4 material = vec4(0.2, 0.7, 0.5, shininess);
  vec4 segment = vec4(0.3, 0.2, 0.1, 0.6);
  vec3 c = mmvBlinnPhong(material, segment, n, v, l, texCoord.y);
  vec3 e = mmvEnvironment(l, vec3(0.0, 1.0, 0.0), vec3(0.1, 0.2, 0.3), vec3(0.9, 0.8, 0.7));
  gl_FragData[0] = vec4(c.x, c.y + c.z, e.x, e.z);
}
)";
}

TEST(ShaderMirror, BlinnPhongAndEnvironmentMatchCPU)
{
  ShaderRunner runner;
  ASSERT_NE(runner.GL, nullptr);
  std::vector<float> pixels;
  ASSERT_TRUE(runner.Run(
    BlinnPhongBody, [](vtkShaderProgram*) {}, pixels));
  const glm::dvec3 n(0.0, 0.0, 1.0);
  const glm::dvec3 v = glm::normalize(glm::dvec3(0.3, -0.2, 1.0));
  int highlights = 0;
  for (int j = 0; j < Size; ++j)
  {
    for (int i = 0; i < Size; ++i)
    {
      const float* px = &pixels[4 * (j * Size + i)];
      const glm::dvec3 l = SweepLight(i, j);
      const double shininess = std::floor((i + 0.5) / Size * 4.0) * 25.0;
      const glm::dvec4 material(0.2, 0.7, 0.5, shininess);
      const glm::dvec4 segment(0.3, 0.2, 0.1, 0.6);
      const double directional = (j + 0.5) / Size;
      const glm::dvec3 c = mmv::mmvBlinnPhong(material, segment, n, v, l, directional);
      const glm::dvec3 e = mmv::mmvEnvironment(
        l, glm::dvec3(0.0, 1.0, 0.0), glm::dvec3(0.1, 0.2, 0.3), glm::dvec3(0.9, 0.8, 0.7));
      // float vs double; pow() of a large exponent amplifies the rounding.
      ASSERT_NEAR(px[0], c.x, 1e-4) << i << "," << j;
      ASSERT_NEAR(px[1], c.y + c.z, 1e-4) << i << "," << j;
      ASSERT_NEAR(px[2], e.x, 1e-5);
      ASSERT_NEAR(px[3], e.z, 1e-5);
      highlights += c.y - 0.2 * 0.2 > 0.05 ? 1 : 0;
    }
  }
  // The sweep must reach lit, unlit and highlighted configurations.
  EXPECT_GT(highlights, 10);
}

const char* SkyBody = R"(
void main()
{
  float theta = 3.14159265358979 * texCoord.y;
  float phi = 6.28318530717959 * texCoord.x;
  vec3 n = vec3(sin(theta) * cos(phi), sin(theta) * sin(phi), cos(theta));
  // Visibility moments from a mostly occluded sky to an open one.
  vec4 sky = vec4(12.566 * (0.05 + 0.95 * texCoord.x), 6.0 * (texCoord.y - 0.5), -5.0 * texCoord.x,
    2.0);
  mat3 slope = mat3(0.1, 0.0, 0.05, 0.2, 0.1, 0.0, 0.3, 0.2, 0.1);
  vec4 material = vec4(0.08, 0.6, 0.3, 20.0);
  vec4 segment = vec4(0.3, 0.2, 0.1, 0.6);
  vec3 c = mmvSkyRadiance(material, segment, n, texCoord.y, sky, vec3(0.5, 0.4, 0.3), slope);
  gl_FragData[0] = vec4(c, 0.0);
}
)";

TEST(ShaderMirror, SkyRadianceMatchesCPU)
{
  ShaderRunner runner;
  ASSERT_NE(runner.GL, nullptr);
  std::vector<float> pixels;
  ASSERT_TRUE(runner.Run(
    SkyBody, [](vtkShaderProgram*) {}, pixels));
  // GLSL's mat3 takes columns: the same numbers as glm's constructor.
  const glm::dmat3 slope(0.1, 0.0, 0.05, 0.2, 0.1, 0.0, 0.3, 0.2, 0.1);
  int clamped = 0;
  for (int j = 0; j < Size; ++j)
  {
    for (int i = 0; i < Size; ++i)
    {
      const double x = (i + 0.5) / Size;
      const double y = (j + 0.5) / Size;
      const glm::dvec3 n = SweepLight(i, j);
      const glm::dvec4 sky(12.566 * (0.05 + 0.95 * x), 6.0 * (y - 0.5), -5.0 * x, 2.0);
      const glm::dvec3 c = mmv::mmvSkyRadiance(glm::dvec4(0.08, 0.6, 0.3, 20.0),
        glm::dvec4(0.3, 0.2, 0.1, 0.6), n, y, sky, glm::dvec3(0.5, 0.4, 0.3), slope);
      for (int k = 0; k < 3; ++k)
      {
        ASSERT_NEAR(pixels[4 * (j * Size + i) + k], c[k], 1e-5) << i << "," << j << " " << k;
      }
      // The cosine fit's clamp must be reached too: the diffuse share at 0.
      const glm::dvec3 s1(sky.y, sky.z, sky.w);
      const glm::dvec3 mean(0.5, 0.4, 0.3);
      const glm::dvec3 f0 = mean * sky.x + slope * s1;
      const glm::dvec3 f1n = mean * glm::dot(s1, n) + (slope * n) * (sky.x / 3.0);
      clamped += 0.25 * f0.x + 0.5 * f1n.x < 0.0 ? 1 : 0;
    }
  }
  EXPECT_GT(clamped, 0);
}

const char* PhaseAndEmissionBody = R"(
void main()
{
  // x: g over [-0.99, 0.99]; y: the cosine over [-1, 1].
  float g = mix(-0.99, 0.99, texCoord.x);
  float cosTheta = mix(-1.0, 1.0, texCoord.y);
  vec3 glow = mmvEmission(3.0 * texCoord.x, vec4(0.3, 0.2, 0.1, 0.6));
  gl_FragData[0] = vec4(mmvHenyeyGreensteinRelative(g, cosTheta),
    mmvHenyeyGreensteinRelative(0.0, cosTheta), glow.x, glow.z);
}
)";

TEST(ShaderMirror, HenyeyGreensteinAndEmissionMatchCPU)
{
  ShaderRunner runner;
  ASSERT_NE(runner.GL, nullptr);
  std::vector<float> pixels;
  ASSERT_TRUE(runner.Run(
    PhaseAndEmissionBody, [](vtkShaderProgram*) {}, pixels));
  double largest = 0.0;
  for (int j = 0; j < Size; ++j)
  {
    for (int i = 0; i < Size; ++i)
    {
      const float* px = &pixels[4 * (j * Size + i)];
      const double u = (i + 0.5) / Size;
      const double g = -0.99 + 1.98 * u;
      const double cosTheta = -1.0 + 2.0 * (j + 0.5) / Size;
      const double phase = mmv::mmvHenyeyGreensteinRelative(g, cosTheta);
      largest = std::max(largest, phase);
      // float vs double: 1 + g^2 - 2 g cos cancels near the forward peak.
      ASSERT_NEAR(px[0], phase, 1e-4 * phase + 1e-6) << "g " << g << " cos " << cosTheta;
      // g = 0 is exactly isotropic on the GPU too: the isotropic model's images.
      ASSERT_EQ(px[1], 1.0f) << "cos " << cosTheta;
      const glm::dvec3 glow = mmv::mmvEmission(3.0 * u, glm::dvec4(0.3, 0.2, 0.1, 0.6));
      ASSERT_NEAR(px[2], glow.x, 1e-6);
      ASSERT_NEAR(px[3], glow.z, 1e-6);
    }
  }
  // The sweep reaches the forward peak (7.1 at g = 0.969, cos = 0.979).
  EXPECT_GT(largest, 5.0);
}

const char* SurfaceShareBody = R"(
void main()
{
  // x: |grad| over [0, 1] (squared, to dwell near 0); y: equalShare over (0, 0.1].
  float gradientLength = texCoord.x * texCoord.x;
  float equalShare = 0.1 * texCoord.y;
  gl_FragData[0] = vec4(mmvSurfaceShare(gradientLength, equalShare),
    mmvSurfaceShare(0.0, equalShare), mmvSurfaceShare(equalShare, equalShare), 0.0);
}
)";

TEST(ShaderMirror, HybridSurfaceShareMatchesCPU)
{
  ShaderRunner runner;
  ASSERT_NE(runner.GL, nullptr);
  std::vector<float> pixels;
  ASSERT_TRUE(runner.Run(
    SurfaceShareBody, [](vtkShaderProgram*) {}, pixels));
  for (int j = 0; j < Size; ++j)
  {
    for (int i = 0; i < Size; ++i)
    {
      const float* px = &pixels[4 * (j * Size + i)];
      const double u = (i + 0.5) / Size;
      const double equalShare = 0.1 * (j + 0.5) / Size;
      ASSERT_NEAR(px[0], mmv::mmvSurfaceShare(u * u, equalShare), 1e-6) << i << ", " << j;
      // No gradient, no surface: exactly 0; at equalShare, exactly half.
      ASSERT_EQ(px[1], 0.0f);
      ASSERT_NEAR(px[2], 0.5, 1e-7);
    }
  }
}

namespace
{
// Lights of every kind and falloff, given to the shaders through the one
// light layout (mmv::SetLightUniforms) as the ray cast and the irradiance
// pass give them.
std::vector<mmv::LightSource> EveryKindOfLight()
{
  std::vector<mmv::LightSource> lights;
  mmv::LightSource directional = TestLight(mmv::DirectionalLight);
  lights.push_back(directional);
  mmv::LightSource point = TestLight(mmv::PointLight, 1); // attenuation (1, 0.5, 2)
  lights.push_back(point);
  mmv::LightSource spot = TestLight(mmv::SpotLight, 1); // cone 30 deg, exponent 7.5
  lights.push_back(spot);
  mmv::LightSource paperPoint = TestLight(mmv::PointLight, 0); // eq. 12, radius 0.5
  paperPoint.Position = { -0.6, 0.4, 0.3 };
  lights.push_back(paperPoint);
  mmv::LightSource paperSpot = TestLight(mmv::SpotLight, 0); // eq. 12, hard cone
  paperSpot.SpotExponent = 2.0;
  paperSpot.CosCone = std::cos(45.0 * M_PI / 180.0);
  lights.push_back(paperSpot);
  mmv::LightSource hardSpot = TestLight(mmv::SpotLight, 2); // (0, 0, 1), hard cone
  hardSpot.Position = { -0.5, -0.5, 0.8 };
  hardSpot.CosCone = std::cos(50.0 * M_PI / 180.0);
  hardSpot.SpotAxis = glm::normalize(glm::dvec3(0.3, 0.4, -1.0));
  lights.push_back(hardSpot);
  mmv::LightSource linearPoint = TestLight(mmv::PointLight, 2); // (0, 0, 1) at the plane
  linearPoint.Attenuation = { 0.0, 1.0, 0.0 };
  linearPoint.Position = { 0.9, 0.9, 0.05 };
  lights.push_back(linearPoint);
  mmv::LightSource skew = TestLight(mmv::DirectionalLight);
  skew.ToLight = glm::normalize(glm::dvec3(0.7, -0.1, 0.2));
  lights.push_back(skew);
  return lights;
}

// Light `LIGHT`'s geometry term and direction at x, read from the uniforms.
const char* LightUniformsBody = R"(
void main()
{
  vec3 x = vec3(-2.0 + 4.0 * texCoord, 0.0);
  float geometry = mmvLightGeometryTerm(mmv_lightKind[LIGHT], mmv_lightPosition[LIGHT],
    mmv_lightSpotAxis[LIGHT], mmv_lightCosCone[LIGHT], mmv_lightSpotExponent[LIGHT],
    mmv_lightAttenuation[LIGHT], mmv_lightRadius[LIGHT], x);
  float lightDistance;
  vec3 l = mmvDirectionToLight(mmv_lightKind[LIGHT], mmv_lightPosition[LIGHT],
    mmv_lightToLight[LIGHT], x, lightDistance);
  gl_FragData[0] = vec4(geometry, dot(l, vec3(0.3, 0.5, 0.8)), lightDistance,
    float(mmv_lightKind[LIGHT]));
}
)";
}

TEST(ShaderMirror, LightModelOfEveryLightTypeThroughTheLightUniforms)
{
  ShaderRunner runner;
  ASSERT_NE(runner.GL, nullptr);
  const std::vector<mmv::LightSource> lights = EveryKindOfLight();
  ASSERT_EQ(static_cast<int>(lights.size()), mmv::MaxLights);
  int kinds[3] = { 0, 0, 0 };
  double worst = 0.0;
  for (int k = 0; k < mmv::MaxLights; ++k)
  {
    const mmv::LightSource& light = lights[k];
    ++kinds[light.Kind];
    std::vector<float> pixels;
    const std::string body = "#define LIGHT " + std::to_string(k) + "\n" + LightUniformsBody;
    ASSERT_TRUE(runner.Run(
      body,
      [&](vtkShaderProgram* p)
      { mmv::SetLightUniforms(p, lights.data(), nullptr, mmv::MaxLights, mmv::MaxLights); },
      pixels));
    int lit = 0;
    int unlit = 0;
    for (int j = 0; j < Size; ++j)
    {
      for (int i = 0; i < Size; ++i)
      {
        const float* px = &pixels[4 * (j * Size + i)];
        const glm::dvec3 x = PixelPoint(i, j);
        ASSERT_EQ(px[3], float(light.Kind)) << "light " << k;
        // float and double disagree right on a cone's edge; skip a thin band.
        const glm::dvec3 toPoint = x - light.Position;
        if (light.Kind == mmv::SpotLight &&
          std::abs(glm::dot(glm::normalize(toPoint), light.SpotAxis) - light.CosCone) < 1e-4)
        {
          continue;
        }
        const double cpu = mmv::mmvLightGeometryTerm(light, x);
        // float against double: relative rounding of the falloff and the
        // spot's pow(cos, exponent) (exponent 7.5: ~1e-6), far below any
        // change of the model (a different kind, falloff or cone).
        ASSERT_NEAR(px[0], cpu, 1e-5 * std::max(1.0, cpu))
          << "light " << k << " at " << i << "," << j;
        worst = std::max(worst, std::abs(px[0] - cpu) / std::max(1.0, cpu));
        double distance = 0.0;
        const glm::dvec3 l = mmv::mmvDirectionToLight(light, x, distance);
        ASSERT_NEAR(px[1], glm::dot(l, glm::dvec3(0.3, 0.5, 0.8)), 1e-5) << "light " << k;
        ASSERT_NEAR(px[2], distance, 1e-5 * std::max(1.0, distance)) << "light " << k;
        (cpu > 0.0 ? lit : unlit) += 1;
      }
    }
    EXPECT_GT(lit, Size * Size / 20) << "light " << k;
    if (light.Kind == mmv::SpotLight)
    {
      EXPECT_GT(unlit, Size * Size / 20) << "spot light " << k << " lights everything";
    }
  }
  std::cout << "largest |GPU - CPU| / max(1, CPU) of the geometry term: " << worst << "\n";
  EXPECT_GT(kinds[mmv::DirectionalLight], 0);
  EXPECT_GT(kinds[mmv::PointLight], 0);
  EXPECT_GT(kinds[mmv::SpotLight], 0);
}

namespace
{
// Materials of the segment-shading test: (ka, kd, ks, ke) and (g, r, e).
const glm::dvec4 Phong[6] = { { 0.2, 0.7, 0.2, 20.0 }, { 0.0, 0.5, 0.9, 120.0 },
  { 1.0, 0.0, 0.0, 0.0 }, { 0.3, 0.3, 0.6, 5.0 }, { 0.1, 0.9, 0.4, 60.0 }, { 0.5, 0.2, 0.0, 1.0 } };
const glm::dvec3 Optics[6] = { { 0.0, 0.0, 0.0 }, { 0.6, 0.5, 0.0 }, { -0.5, 0.0, 2.0 },
  { 0.9, 1.0, 0.3 }, { -0.9, 0.2, 0.0 }, { 0.3, 0.0, 0.7 } };

// The inputs of pixel (i, j), as the shader below derives them: material
// i % 6, a normal sweeping the sphere (none in every seventh row), the
// directional weight, a position in the lights' plane, each light's
// irradiance (0 for some) and an environment colour.
struct SegmentInputs
{
  int Material;
  glm::dvec4 Segment;
  glm::dvec3 Position, N, V, Environment;
  double Directional;
  double Irradiance[mmv::MaxLights];
  glm::dvec3 Tint[mmv::MaxLights]; // each light's tint (mmvTint.glsl)
};

SegmentInputs PixelInputs(int i, int j)
{
  SegmentInputs in;
  in.Material = i % 6;
  const double theta = M_PI * (j + 0.5) / Size;
  const double phi = 2.0 * M_PI * (i + 0.5) / Size;
  in.N = j % 7 == 0
    ? glm::dvec3(0.0)
    : glm::dvec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
  in.V = glm::normalize(glm::dvec3(0.3, -0.2, 1.0));
  in.Directional = (j % 5) / 4.0;
  in.Position = PixelPoint(i, j);
  in.Segment = glm::dvec4(0.3 + 0.1 * (i % 3), 0.2, 0.1 + 0.05 * (j % 4), 0.6);
  for (int k = 0; k < mmv::MaxLights; ++k)
  {
    in.Irradiance[k] = (i + j + k) % 4 == 0 ? 0.0 : ((i * 7 + j * 3 + k * 5) % 11) / 10.0;
    in.Tint[k] = glm::dvec3(1.0, ((i + k) % 5) / 4.0, ((j + 2 * k) % 3) / 2.0);
  }
  in.Environment = glm::dvec3(0.2, 0.5, 0.9) * (1.0 + (j % 2));
  return in;
}

const char* SegmentShadingBody = R"(
uniform vec4 phong[6];
uniform vec3 optics[6];
void main()
{
  int i = int(gl_FragCoord.x);
  int j = int(gl_FragCoord.y);
  int m = i % 6;
  float theta = 3.14159265358979 * (float(j) + 0.5) / float(SIZE);
  float phi = 6.28318530717959 * (float(i) + 0.5) / float(SIZE);
  vec3 n = j % 7 == 0 ? vec3(0.0)
                      : vec3(sin(theta) * cos(phi), sin(theta) * sin(phi), cos(theta));
  vec3 v = normalize(vec3(0.3, -0.2, 1.0));
  float directional = float(j % 5) / 4.0;
  vec3 position = vec3(-2.0 + 4.0 * texCoord, 0.0);
  vec4 segment = vec4(0.3 + 0.1 * float(i % 3), 0.2, 0.1 + 0.05 * float(j % 4), 0.6);
  float irradiance[8];
  for (int k = 0; k < 8; ++k)
  {
    irradiance[k] = (i + j + k) % 4 == 0 ? 0.0 : float((i * 7 + j * 3 + k * 5) % 11) / 10.0;
  }
  vec3 environment = vec3(0.2, 0.5, 0.9) * (1.0 + float(j % 2));
#if MMV_USE_RGB_IRRADIANCE
  // Each light's tint, as mmvFetchTints would have read it.
  for (int k = 0; k < MMV_NUMBER_OF_LIGHTS; ++k)
  {
    mmvSetLightTint(k, vec3(1.0, float((i + k) % 5) / 4.0, float((j + 2 * k) % 3) / 2.0));
  }
#endif
  vec3 c = mmvShadeSample(phong[m], optics[m].x, optics[m].y, optics[m].z, segment, position,
    n, v, directional, vec4(irradiance[0], irradiance[1], irradiance[2], irradiance[3]),
    vec4(irradiance[4], irradiance[5], irradiance[6], irradiance[7]), environment);
  gl_FragData[0] = vec4(c, texCoord.x);
}
)";
}

TEST(ShaderMirror, SegmentShadingMatchesTheReferenceRenderersFunction)
{
  // mmvShadeSample (what the ray cast's mmvShadeSegment computes once it has
  // read its textures) against the CPU function the reference renderer
  // shades with: six materials (ambient only, sharp highlights, g = +-0.9,
  // reflection, emission), the lights of every kind through the light
  // uniforms, each tinted (RGB irradiance, mmvTint.glsl), with no light
  // (ambient only), three lights (one irradiance texture) and MaxLights (two).
  ShaderRunner runner;
  ASSERT_NE(runner.GL, nullptr);
  std::vector<mmv::LightSource> lights = EveryKindOfLight();
  std::vector<glm::dvec3> radiance;
  for (int k = 0; k < mmv::MaxLights; ++k)
  {
    radiance.emplace_back(1.0 - 0.1 * k, 0.5 + 0.05 * k, 0.8);
  }
  float phong[6][4];
  float optics[6][3];
  for (int m = 0; m < 6; ++m)
  {
    for (int c = 0; c < 4; ++c)
    {
      phong[m][c] = static_cast<float>(Phong[m][c]);
    }
    for (int c = 0; c < 3; ++c)
    {
      optics[m][c] = static_cast<float>(Optics[m][c]);
    }
  }
  const std::string body = "#define SIZE " + std::to_string(Size) + "\n" + SegmentShadingBody;
  for (int count : { 0, 3, mmv::MaxLights })
  {
    std::vector<float> pixels;
    ASSERT_TRUE(runner.Run(
      body,
      [&](vtkShaderProgram* p)
      {
        p->SetUniform4fv("phong", 6, phong);
        p->SetUniform3fv("optics", 6, optics);
        mmv::SetLightUniforms(p, lights.data(), radiance.data(), count, count);
      },
      pixels, FullVariant(count)))
      << count << " lights";
    double largest = 0.0;
    double worst = 0.0;
    int reflecting = 0;
    for (int j = 0; j < Size; ++j)
    {
      for (int i = 0; i < Size; ++i)
      {
        const float* px = &pixels[4 * (j * Size + i)];
        // The quad's coordinate: the pixel was drawn, where PixelPoint says.
        ASSERT_NEAR(px[3], (i + 0.5) / Size, 1e-6) << "pixel " << i << "," << j;
        const SegmentInputs in = PixelInputs(i, j);
        const glm::dvec3& optic = Optics[in.Material];
        // A tinted light arrives with its radiance times its tint.
        glm::dvec3 arriving[mmv::MaxLights];
        for (int k = 0; k < count; ++k)
        {
          arriving[k] = radiance[k] * in.Tint[k];
        }
        const glm::dvec3 cpu = mmv::mmvShadeSample(Phong[in.Material], optic.x, optic.y, optic.z,
          in.Segment, in.Position, in.N, in.V, in.Directional, lights.data(), arriving,
          in.Irradiance, count, in.Environment);
        for (int c = 0; c < 3; ++c)
        {
          // float against double: the inputs' own rounding (~1e-7), pow() of
          // shininess up to 120 and the phase function at g = 0.9 (up to 19x
          // its value at g = 0) amplify it to ~1e-5 relative; a change of the
          // model (a term, a light, a sign) moves the result by > 1e-2.
          ASSERT_NEAR(px[c], cpu[c], 1e-4 * std::max(1.0, std::abs(cpu[c])))
            << count << " lights, material " << in.Material << ", pixel " << i << "," << j
            << ", channel " << c;
          largest = std::max(largest, cpu[c]);
          worst = std::max(worst, std::abs(px[c] - cpu[c]) / std::max(1.0, std::abs(cpu[c])));
        }
        reflecting +=
          Optics[in.Material].y > 0.0 && in.Directional > 0.0 && glm::length(in.N) > 0.0 ? 1 : 0;
      }
    }
    std::cout << count << " lights: largest |GPU - CPU| / max(1, CPU) " << worst << "\n";
    EXPECT_GT(largest, 0.5) << count << " lights";
    EXPECT_GT(reflecting, Size * Size / 10);
  }
}

namespace
{
// Parameter PARAMETER of table entry i (pixel column i), read as the ray
// cast reads it: the generated texel macros of its name.
const char* MaterialTexelBody = R"(
uniform sampler2D material;
void main()
{
  float row = (float(PARAMETER_ROW) + 0.5) / float(MMV_MATERIAL_ROWS);
  gl_FragData[0] = vec4(texture(material, vec2(texCoord.x, row))[PARAMETER_CHANNEL], 0.0, 0.0, 1.0);
}
)";
}

TEST(ShaderMirror, MaterialTexturePackingMatchesTheGeneratedTexelNames)
{
  // The C++ packing (vtkMultiMaterialTextures, mmv::PackMaterialTexels) and
  // the GLSL reading (MMV_<NAME>_ROW / _CHANNEL) of every parameter agree:
  // each entry's texel centre holds the parameter.
  ShaderRunner runner;
  ASSERT_NE(runner.GL, nullptr);
  vtkNew<vtkMaterialTransferFunction> materials;
  materials->AddNode(0.0, 0.1, 0.2, 0.3, 10.0, 0.5, 1.0, 0.25, -0.5, 2.0);
  materials->AddNode(1.0, 0.9, 0.8, 0.7, 90.0, 1.5, 7.0, 0.75, 0.5, 6.0);
  const double range[2] = { 0.0, 1.0 };
  vtkNew<vtkMultiMaterialTextures> textures;
  runner.GL->MakeCurrent();
  textures->UpdateMaterialTable(runner.GL, materials, range, Size);
  std::vector<float> table(static_cast<size_t>(Size) * mmv::MaterialParameterCount);
  materials->GetTable(range[0], range[1], Size, table.data());
  int read = 0;
  for (int p = 0; p < mmv::MaterialParameterCount; ++p)
  {
    const std::string name = mmv::MaterialParameterTable[p].GLSLName;
    const mmv::MaterialTexel texel = mmv::MaterialTexelLayout[p];
    if (texel.Row < 0)
    {
      continue; // in no texel: no shader reads it
    }
    // (ka, kd, ks, ke) are read as one texel, the vec4 mmvBlinnPhong takes.
    const std::string row = texel.Row == mmv::BlinnPhongRow ? "MMV_BLINN_PHONG_ROW" : name + "_ROW";
    const std::string channel =
      texel.Row == mmv::BlinnPhongRow ? std::to_string(p - mmv::Ambient) : name + "_CHANNEL";
    const std::string body = "#define PARAMETER_ROW " + row + "\n#define PARAMETER_CHANNEL " +
      channel + "\n" + MaterialTexelBody;
    ++read;
    std::vector<float> pixels;
    ASSERT_TRUE(runner.Run(
      body,
      [&](vtkShaderProgram* program)
      {
        textures->GetMaterialTexture()->Activate();
        program->SetUniformi("material", textures->GetMaterialTexture()->GetTextureUnit());
      },
      pixels));
    textures->GetMaterialTexture()->Deactivate();
    for (int i = 0; i < Size; ++i)
    {
      const float expected = table[static_cast<size_t>(i) * mmv::MaterialParameterCount + p];
      // At the texel's centre the linear filter's weight is 1 up to float
      // rounding of the coordinate (neighbouring entries differ by < 2).
      ASSERT_NEAR(pixels[4 * (7 * Size + i)], expected, 1e-4 * std::max(1.0f, std::abs(expected)))
        << name << " entry " << i;
    }
    // The parameter varies over the table: a wrong texel would show.
    EXPECT_NE(table[p], table[static_cast<size_t>(Size - 1) * mmv::MaterialParameterCount + p])
      << name;
  }
  EXPECT_EQ(read, 7); // all but c_t and s
  textures->ReleaseGraphicsResources(runner.Window);
}
