/**
 * @file   vtkMultiMaterialShaderAssembly.h
 * @brief  Which GLSL file of Shaders/ goes to which tag of VTK's ray caster
 *         (raycasterfs.glsl), and the defines that select the variant.
 *
 * The only place that knows the tag table. Variants are chosen by defines,
 * so a scene gets no code it does not need: no light loop without lights, no
 * environment lookup when every reflection coefficient is 0, no segment
 * tables' second fetch without pre-integration, no Henyey-Greenstein code
 * when every anisotropy g is 0, no emission term when every emission is 0
 * and no RGB irradiance (tints) when every transmission colour is white (at
 * those values the terms would leave the image unchanged).
 */
#ifndef vtkMultiMaterialShaderAssembly_h
#define vtkMultiMaterialShaderAssembly_h

#include "vtkMultiMaterialVolumeModule.h" // export macro

#include <string>
#include <utility>
#include <vector>

namespace mmv
{

struct ShaderVariant
{
  int NumberOfLights = 0;  // 0..MaxLights
  int Fields = 1;          // 1..MaxFields: components shaded as fields
  bool Reflection = false; // some material has r > 0
  bool PreIntegration = true;
  bool Anisotropy = false; // some material has g != 0 (and there is a light)
  bool Emission = false;   // some material has e != 0
  bool Sky = false;        // the environment lights the volume (vtkMultiMaterialSky.h)
  // Some material's transmission colour is not white (and there is a light):
  // per-light tints (mmvTint.glsl, MMV_USE_RGB_IRRADIANCE).
  bool RGBIrradiance = false;
  // With Reflection: mmv::EnvironmentKind and mmv::ReflectionVisibility.
  int Environment = 0;
  int ReflectionVisibility = 0;
  // With a visibility march: the irradiance pass's cutaway is not empty, and
  // the march treats what it removes as empty (MMV_CUTAWAY).
  bool ReflectionCutaway = false;

  bool operator==(const ShaderVariant& o) const
  {
    return this->NumberOfLights == o.NumberOfLights && this->Fields == o.Fields &&
      this->Reflection == o.Reflection && this->PreIntegration == o.PreIntegration &&
      this->Anisotropy == o.Anisotropy && this->Emission == o.Emission && this->Sky == o.Sky &&
      this->RGBIrradiance == o.RGBIrradiance && this->Environment == o.Environment &&
      this->ReflectionVisibility == o.ReflectionVisibility &&
      this->ReflectionCutaway == o.ReflectionCutaway;
  }
  bool operator!=(const ShaderVariant& o) const { return !(*this == o); }
};

/// The `#define` lines of a variant (the material layout prelude included).
VTKMULTIMATERIALVOLUME_EXPORT std::string VariantDefines(const ShaderVariant& variant);

/// The `#define` lines the reflections' visibility march needs (the shadow
/// rays' constants, the cutaway's, MMV_CUTAWAY with `cutaway`): in the ray
/// cast (mmv::MarchedReflectionVisibility) and in vtkReflectionVisibilityPass.
VTKMULTIMATERIALVOLUME_EXPORT std::string ReflectionMarchDefines(bool cutaway);

/// Fragment-shader replacements (tag, text) for composite ray casting.
VTKMULTIMATERIALVOLUME_EXPORT std::vector<std::pair<std::string, std::string>> RayCastReplacements(
  const ShaderVariant& variant);

} // namespace mmv

#endif
