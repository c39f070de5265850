/**
 * @file   vtkMultiMaterialLightUniforms.h
 * @brief  The one layout of the light uniforms on the GPU.
 *
 * The ray cast (Shaders/mmvShading.glsl) and the irradiance pass
 * (Shaders/mmvIrradianceFS.glsl) both declare the lights with
 * LightUniformDeclarations() and receive them from SetLightUniforms(), so
 * the two shaders and the C++ that feeds them share one set of names and
 * types: arrays indexed by light, one per field of mmv::LightSource plus the
 * radiance the ray cast multiplies by. Light kinds are the prelude's
 * MMV_DIRECTIONAL_LIGHT, MMV_POINT_LIGHT and MMV_SPOT_LIGHT
 * (vtkMultiMaterialParameters.h).
 */
#ifndef vtkMultiMaterialLightUniforms_h
#define vtkMultiMaterialLightUniforms_h

#include "vtkMultiMaterialLightModel.h"   // LightSource
#include "vtkMultiMaterialVolumeModule.h" // export macro

#include <string>

class vtkShaderProgram;

namespace mmv
{

enum LightUniform : int
{
  LightKindUniform = 0,
  LightPositionUniform,
  LightToLightUniform,
  LightSpotAxisUniform,
  LightCosConeUniform,
  LightSpotExponentUniform,
  LightAttenuationUniform,
  LightRadiusUniform,
  LightRadianceUniform,
  LightUniformCount
};

struct LightUniformInfo
{
  const char* GLSLType;
  const char* Name;
  const char* Meaning;
};

constexpr LightUniformInfo LightUniformLayout[LightUniformCount] = {
  { "int", "mmv_lightKind", "MMV_DIRECTIONAL_LIGHT, MMV_POINT_LIGHT or MMV_SPOT_LIGHT" },
  { "vec3", "mmv_lightPosition", "point/spot: where the light is (object space)" },
  { "vec3", "mmv_lightToLight", "directional: unit vector toward the light" },
  { "vec3", "mmv_lightSpotAxis", "spot: unit axis of the cone" },
  { "float", "mmv_lightCosCone", "spot: cos of the cone half-angle" },
  { "float", "mmv_lightSpotExponent", "spot: vtkLight::Exponent" },
  { "vec3", "mmv_lightAttenuation", "point/spot: VTK's (c0, c1, c2), used when radius == 0" },
  { "float", "mmv_lightRadius", "point/spot: epsilon of eq. 12" },
  { "vec3", "mmv_lightRadiance", "colour * intensity (the irradiance pass does not read it)" },
};

/// The GLSL declarations of the light uniforms, arrays of `slots` entries
/// (a number or a macro, e.g. "MMV_NUMBER_OF_LIGHTS").
VTKMULTIMATERIALVOLUME_EXPORT std::string LightUniformDeclarations(const std::string& slots);

/// Sets the light uniforms of `program`: lights[0..count) in the first
/// slots, the rest of the `slots` (count <= slots) inert (directional, no
/// cone). `radiance` (count entries) may be null: then black.
VTKMULTIMATERIALVOLUME_EXPORT void SetLightUniforms(vtkShaderProgram* program,
  const LightSource* lights, const glm::dvec3* radiance, int count, int slots);

} // namespace mmv

#endif
