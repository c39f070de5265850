#include "vtkMultiMaterialShaderAssembly.h"

#include "vtkMultiMaterialLightUniforms.h"
#include "vtkMultiMaterialParameters.h"

#include "vtkMultiMaterialCutaway.h"
#include "vtkMultiMaterialEnvironmentLookup.h"

#include "mmvCutaway.h"
#include "mmvEmission.h"
#include "mmvLightModel.h"
#include "mmvPhaseFunction.h"
#include "mmvRayCastDec.h"
#include "mmvRayCastExit.h"
#include "mmvRayCastImpl.h"
#include "mmvRayCastInit.h"
#include "mmvReflection.h"
#include "mmvReflectionMarch.h"
#include "mmvShading.h"
#include "mmvShadowRay.h"
#include "mmvTint.h"

namespace mmv
{

std::string VariantDefines(const ShaderVariant& variant)
{
  const int textures = (variant.NumberOfLights + 3) / 4;
  std::string s = MaterialGLSLPrelude();
  s += "#define MMV_NUMBER_OF_LIGHTS " + std::to_string(variant.NumberOfLights) + "\n";
  s += "#define MMV_FIELDS " + std::to_string(variant.Fields) + "\n";
  s += "#define MMV_IRRADIANCE_TEXTURES " + std::to_string(textures) + "\n";
  s += "#define MMV_USE_REFLECTION " + std::string(variant.Reflection ? "1" : "0") + "\n";
  s += "#define MMV_USE_PREINTEGRATION " + std::string(variant.PreIntegration ? "1" : "0") + "\n";
  s += "#define MMV_USE_ANISOTROPY " + std::string(variant.Anisotropy ? "1" : "0") + "\n";
  s += "#define MMV_USE_EMISSION " + std::string(variant.Emission ? "1" : "0") + "\n";
  s += "#define MMV_USE_SKY " + std::string(variant.Sky ? "1" : "0") + "\n";
  s += "#define MMV_USE_RGB_IRRADIANCE " + std::string(variant.RGBIrradiance ? "1" : "0") + "\n";
  s += "#define MMV_ENVIRONMENT " + std::to_string(variant.Environment) + "\n";
  s += "#define MMV_REFLECTION_VISIBILITY " + std::to_string(variant.ReflectionVisibility) + "\n";
  return s;
}

std::string ReflectionMarchDefines(bool cutaway)
{
  return ShadowRayGLSLPrelude() + CutawayGLSLPrelude() + (cutaway ? CutawayGLSLDefine : "");
}

std::vector<std::pair<std::string, std::string>> RayCastReplacements(const ShaderVariant& variant)
{
  // Declarations and the per-ray init/exit keep VTK's own code after ours
  // (the tag is re-emitted); the per-sample shading replaces VTK's. The
  // optional terms' functions are left out of the source, not only compiled
  // out, when no material uses them.
  std::string declarations = VariantDefines(variant);
  if (variant.NumberOfLights > 0)
  {
    declarations += LightUniformDeclarations("MMV_NUMBER_OF_LIGHTS");
  }
  declarations += mmvLightModel;
  if (variant.Anisotropy)
  {
    declarations += mmvPhaseFunction;
  }
  if (variant.Emission)
  {
    declarations += mmvEmission;
  }
  if (variant.RGBIrradiance && variant.NumberOfLights > 0)
  {
    declarations += mmvTint;
  }
  // Before the reflection: mmvReflection.glsl draws the background gradient
  // with mmvShading.glsl's mmvEnvironment.
  declarations += mmvShading;
  if (variant.Reflection)
  {
    if (variant.ReflectionVisibility == MarchedReflectionVisibility)
    {
      // The irradiance pass's shadow-ray march, with its cutaway.
      declarations += ReflectionMarchDefines(variant.ReflectionCutaway) + mmvCutaway +
        mmvShadowRay + mmvReflectionMarch;
    }
    declarations += mmvReflection;
  }
  return {
    { "//VTK::Shading::Dec", declarations + mmvRayCastDec + "\n//VTK::Shading::Dec" },
    { "//VTK::Shading::Init", std::string(mmvRayCastInit) + "\n//VTK::Shading::Init" },
    { "//VTK::Shading::Impl", mmvRayCastImpl },
    { "//VTK::Shading::Exit", std::string(mmvRayCastExit) + "\n//VTK::Shading::Exit" },
  };
}

} // namespace mmv
