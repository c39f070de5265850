/**
 * @class   vtkMultiMaterialShadingUniforms
 * @brief   The ray cast's per-frame shading uniforms (Shaders/mmvRayCastDec.glsl,
 *          Shaders/mmvShading.glsl) and the textures they name.
 *
 * The mapper fills it once per frame (the lights, the segment tables' step,
 * the maps from a block's texture coordinates into the whole volume's
 * gradient and irradiance textures, the environment); the render pass calls
 * Apply() whenever VTK binds the ray-cast program. Lights go through the one
 * light layout of vtkMultiMaterialLightUniforms.h. Not a vtkObject: it is
 * plain state owned by the mapper.
 */
#ifndef vtkMultiMaterialShadingUniforms_h
#define vtkMultiMaterialShadingUniforms_h

#include "vtkMultiMaterialLights.h"         // ShadingLight
#include "vtkMultiMaterialShaderAssembly.h" // ShaderVariant
#include "vtkMultiMaterialVolumeModule.h"   // export macro

#include <vector>

class vtkGlobalPrefilteredVolume;
class vtkImageData;
class vtkIrradianceEstimator;
class vtkMatrix4x4;
class vtkMultiMaterialReflection;
class vtkMultiMaterialTextures;
class vtkRenderer;
class vtkShaderProgram;

class VTKMULTIMATERIALVOLUME_EXPORT vtkMultiMaterialShadingUniforms
{
public:
  /// The shader variant the uniforms are for (the number of lights included).
  void SetVariant(const mmv::ShaderVariant& variant) { this->Variant = variant; }
  const mmv::ShaderVariant& GetVariant() const { return this->Variant; }

  /// The lights, in object space, with their colour * intensity.
  void SetLights(const std::vector<mmv::ShadingLight>& lights) { this->Lights = lights; }
  const std::vector<mmv::ShadingLight>& GetLights() const { return this->Lights; }

  /// The segment length the pre-integrated tables were built for.
  void SetTableStep(double step) { this->TableStep = static_cast<float>(step); }

  /// The gradient texture's texels per axis, for data of `dataDims` points.
  void SetGradientMap(const int dataDims[3], const int gradientTexels[3]);

  /// Maps of the input `image` into the whole volume's index space, its
  /// irradiance texture (`irradianceDims`, or the global grid of `global`
  /// when the input is a piece of it) and the gradient fade.
  void SetGeometry(
    vtkImageData* image, const int irradianceDims[3], vtkGlobalPrefilteredVolume* global);

  /// Whether the data are cell scalars: the ray caster's texture coordinate
  /// then spans the cells (texel centres at the cell centres) and the
  /// gradient and irradiance grids are those of the cell centres.
  void SetCellData(bool cellData) { this->CellData = cellData ? 1 : 0; }

  /// The environment of the reflection term: the renderer's background
  /// colours around the camera's view-up, in object space.
  /// Eq. 17's environment and visibility (null: no reflection this frame).
  void SetReflection(vtkMultiMaterialReflection* reflection) { this->Reflection = reflection; }

  /// Sets every uniform of the variant on `program`.
  void Apply(vtkShaderProgram* program, vtkMultiMaterialTextures* textures, int tableSize,
    vtkIrradianceEstimator* irradiance) const;

  /// Binds (on) or releases (off) the textures the uniforms name.
  void ActivateTextures(
    bool on, vtkMultiMaterialTextures* textures, vtkIrradianceEstimator* irradiance) const;

private:
  mmv::ShaderVariant Variant;
  std::vector<mmv::ShadingLight> Lights;
  float IrradianceScale[3] = { 1.0f, 1.0f, 1.0f };
  float IrradianceBias[3] = { 0.0f, 0.0f, 0.0f };
  float PhysicalToWholeIndex[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
  float GradientToObject[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  float WholeDimensions[3] = { 1.0f, 1.0f, 1.0f };
  float DataSpacing[3] = { 1.0f, 1.0f, 1.0f };
  float SurfaceEqualShare = 1.0f; // mmv::SurfaceEqualShareGradientPerVoxel per object unit
  float GradientScale[3] = { 1.0f, 1.0f, 1.0f };
  float GradientTexScale[3] = { 1.0f, 1.0f, 1.0f };
  float GradientTexBias[3] = { 0.0f, 0.0f, 0.0f };
  float TableStep = 1.0f;
  int CellData = 0;
  vtkMultiMaterialReflection* Reflection = nullptr; // owned by the mapper
};

#endif
