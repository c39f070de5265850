/**
 * @file   vtkMultiMaterialLights.h
 * @brief  vtkLight -> mmv::LightSource, shared by the CPU filter and the mapper.
 *
 * Positions come from vtkLight::GetTransformedPosition/FocalPoint (world
 * coordinates, headlights and camera lights included once the renderer has
 * placed them) and are mapped into the volume's object (data) space with
 * `worldToObject` (nullptr: identity).
 */
#ifndef vtkMultiMaterialLights_h
#define vtkMultiMaterialLights_h

#include "vtkMultiMaterialLightModel.h"
#include "vtkMultiMaterialVolumeFiltersModule.h" // export macro

#include <string>
#include <vector>

class vtkLight;
class vtkLightCollection;
class vtkMatrix4x4;

namespace mmv
{

/// A light for shading: its geometry plus colour * intensity.
struct ShadingLight
{
  LightSource Source;
  glm::dvec3 Radiance{ 1.0 };
  int Index = 0; // position in the collection it came from
};

/// True when the light contributes at all (switched on, intensity > 0,
/// non-black colour). Such lights cost nothing anywhere.
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT bool IsLightActive(vtkLight* light);

/**
 * The light's geometry in object space. `radius` is epsilon of eq. 12 (0:
 * the light's AttenuationValues). Attenuation distances are world distances,
 * as in VTK: a scaling worldToObject rescales the coefficients (by its mean
 * scale, the cube root of its determinant).
 *
 * Values VTK's Phong would turn into NaN, infinite or black light are
 * replaced, and each replacement is described in `problems` (if given):
 * negative, NaN or all-zero attenuation -> (1, 0, 0); a cone angle that is
 * NaN, <= 0 or >= 180 -> a point light (VTK: > 90 means no cone); a negative
 * or NaN Exponent -> 1 (vtkLight's default).
 */
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT LightSource MakeLightSource(vtkLight* light,
  const vtkMatrix4x4* worldToObject, double radius, std::vector<std::string>* problems = nullptr);

/**
 * The active lights of a collection, in collection order. With more than
 * `maxLights` of them, only the strongest (intensity times brightest colour
 * channel) are kept and `dropped` (if given) receives how many were left out.
 */
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT std::vector<ShadingLight> CollectLights(
  vtkLightCollection* lights, const vtkMatrix4x4* worldToObject, double radius, int maxLights,
  int* dropped = nullptr, std::vector<std::string>* problems = nullptr);

/**
 * Orders `lights` for the irradiance textures, four lights to a texture:
 * dimmest first, so that the dim lights of ParaView's light kit share one
 * texture and the one pass that interpolates their strided grid
 * (DimLightCoarsening). `order` carries the collection indices' order from
 * call to call: while the same lights come back they keep their places, so a
 * light whose intensity changes moves no other light's channel (nor its
 * irradiance).
 */
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT void OrderForIrradianceTextures(
  std::vector<ShadingLight>& lights, std::vector<int>& order);

/**
 * The lights' geometry for the irradiance volume on a grid of `dims`. With
 * `strideDimLights`, each light gets the grid stride its share of the image
 * allows (mmv::LightGridStride of its brightest colour channel against the
 * brightest light's); without, every light the irradiance grid.
 */
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT std::vector<LightSource> IrradianceLightSources(
  const std::vector<ShadingLight>& lights, const int dims[3], bool strideDimLights);

/// Checks a PointLightRadius (eq. 12's epsilon; 0 selects VTK's attenuation):
/// a negative or non-finite radius returns 0 and describes why in `why`.
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT double ValidPointLightRadius(double radius, std::string* why);

} // namespace mmv

#endif
