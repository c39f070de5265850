#include "vtkMultiMaterialLightUniforms.h"

#include "vtkShaderProgram.h"

#include <vector>

namespace mmv
{

std::string LightUniformDeclarations(const std::string& slots)
{
  std::string s;
  for (const LightUniformInfo& field : LightUniformLayout)
  {
    s += std::string("uniform ") + field.GLSLType + " " + field.Name + "[" + slots + "]; // " +
      field.Meaning + "\n";
  }
  return s;
}

void SetLightUniforms(vtkShaderProgram* program, const LightSource* lights,
  const glm::dvec3* radiance, int count, int slots)
{
  if (slots <= 0)
  {
    return;
  }
  count = count < slots ? count : slots;
  std::vector<int> kind(slots, DirectionalLight);
  std::vector<float> cosCone(slots, -1.0f);
  std::vector<float> spotExponent(slots, 0.0f);
  std::vector<float> radius(slots, 0.0f);
  // Five vec3 fields, in the order of LightUniform.
  const LightUniform vectorFields[5] = { LightPositionUniform, LightToLightUniform,
    LightSpotAxisUniform, LightAttenuationUniform, LightRadianceUniform };
  std::vector<float> vectors[5];
  for (auto& v : vectors)
  {
    v.assign(3 * static_cast<size_t>(slots), 0.0f);
  }
  for (int l = 0; l < count; ++l)
  {
    const LightSource& light = lights[l];
    kind[l] = light.Kind;
    cosCone[l] = static_cast<float>(light.CosCone);
    spotExponent[l] = static_cast<float>(light.SpotExponent);
    radius[l] = static_cast<float>(light.Radius);
    const glm::dvec3 values[5] = { light.Position, light.ToLight, light.SpotAxis, light.Attenuation,
      radiance ? radiance[l] : glm::dvec3(0.0) };
    for (int f = 0; f < 5; ++f)
    {
      for (int a = 0; a < 3; ++a)
      {
        vectors[f][3 * l + a] = static_cast<float>(values[f][a]);
      }
    }
  }
  program->SetUniform1iv(LightUniformLayout[LightKindUniform].Name, slots, kind.data());
  program->SetUniform1fv(LightUniformLayout[LightCosConeUniform].Name, slots, cosCone.data());
  program->SetUniform1fv(
    LightUniformLayout[LightSpotExponentUniform].Name, slots, spotExponent.data());
  program->SetUniform1fv(LightUniformLayout[LightRadiusUniform].Name, slots, radius.data());
  for (int f = 0; f < 5; ++f)
  {
    program->SetUniform3fv(LightUniformLayout[vectorFields[f]].Name, slots,
      reinterpret_cast<const float(*)[3]>(vectors[f].data()));
  }
}

} // namespace mmv
