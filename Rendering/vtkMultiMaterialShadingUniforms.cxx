#include "vtkMultiMaterialShadingUniforms.h"

#include "vtkGlobalPrefilteredVolume.h"
#include "vtkImageData.h"
#include "vtkIrradianceEstimator.h"
#include "vtkMatrix4x4.h"
#include "vtkMultiMaterialLightUniforms.h"
#include "vtkMultiMaterialParameters.h"
#include "vtkMultiMaterialReflection.h"
#include "vtkMultiMaterialTextures.h"
#include "vtkMultiMaterialVolumeGeometry.h"
#include "vtkMultiMaterialVolumeSampling.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"

#include <algorithm>
#include <cmath>
#include <vector>

void vtkMultiMaterialShadingUniforms::SetGradientMap(
  const int dataDims[3], const int gradientTexels[3])
{
  for (int a = 0; a < 3; ++a)
  {
    this->GradientScale[a] = static_cast<float>(dataDims[a]);
    mmv::SamePointsMap(
      dataDims[a], gradientTexels[a], this->GradientTexScale[a], this->GradientTexBias[a]);
  }
}

void vtkMultiMaterialShadingUniforms::SetGeometry(
  vtkImageData* image, const int irradianceDims[3], vtkGlobalPrefilteredVolume* global)
{
  int dims[3];
  image->GetDimensions(dims);
  mmv::WholeVolumeMaps(image, this->PhysicalToWholeIndex, this->GradientToObject,
    this->WholeDimensions, this->DataSpacing);
  if (global)
  {
    // The input is a piece of the global pre-filtered volume.
    const glm::dvec3 offset = global->PieceOffset(image);
    const double o[3] = { offset[0], offset[1], offset[2] };
    mmv::PieceToGlobalIrradianceMap(
      global->GetGrid(), o, dims, this->IrradianceScale, this->IrradianceBias);
  }
  else
  {
    for (int a = 0; a < 3; ++a)
    {
      // Data point i sits at texture coordinate (i + 0.5) / N, irradiance
      // voxel j at (j + 0.5) / M, and both grids span the same points.
      mmv::SamePointsMap(dims[a], irradianceDims[a] > 0 ? irradianceDims[a] : 1,
        this->IrradianceScale[a], this->IrradianceBias[a]);
    }
  }
  const double* spacing = image->GetSpacing();
  const double smallestSpacing =
    std::min({ std::abs(spacing[0]), std::abs(spacing[1]), std::abs(spacing[2]) });
  this->SurfaceEqualShare =
    static_cast<float>(mmv::SurfaceEqualShareGradientPerVoxel / smallestSpacing);
}

void vtkMultiMaterialShadingUniforms::Apply(vtkShaderProgram* program,
  vtkMultiMaterialTextures* textures, int tableSize, vtkIrradianceEstimator* irradiance) const
{
  program->SetUniformi("mmv_preintColor", textures->GetSegmentColorTexture()->GetTextureUnit());
  program->SetUniformi("mmv_preintBeta", textures->GetSegmentPositionTexture()->GetTextureUnit());
  program->SetUniformi("mmv_material", textures->GetMaterialTexture()->GetTextureUnit());
  program->SetUniformf("mmv_tableSize", static_cast<float>(tableSize));
  program->SetUniformf("mmv_tableStep", this->TableStep);
  program->SetUniformf("mmv_surfaceEqualShare", this->SurfaceEqualShare);
  program->SetUniformi("mmv_gradient", textures->GetGradientTexture()->GetTextureUnit());
  program->SetUniform3f("mmv_gradientScale", this->GradientScale);
  program->SetUniform3f("mmv_gradientTexScale", this->GradientTexScale);
  program->SetUniform3f("mmv_gradientTexBias", this->GradientTexBias);
  program->SetUniform3f("mmv_irradianceScale", this->IrradianceScale);
  program->SetUniform3f("mmv_irradianceBias", this->IrradianceBias);
  // VTK 9.2 takes the matrices as non-const (it only reads them).
  program->SetUniformMatrix4x4(
    "mmv_physicalToWholeIndex", const_cast<float*>(this->PhysicalToWholeIndex));
  program->SetUniformMatrix3x3("mmv_gradientToObject", const_cast<float*>(this->GradientToObject));
  program->SetUniform3f("mmv_wholeDimensions", this->WholeDimensions);
  program->SetUniform3f("mmv_dataSpacing", this->DataSpacing);
  program->SetUniformi("mmv_cellData", this->CellData);

  const int count = this->Variant.NumberOfLights;
  if (count > 0)
  {
    program->SetUniformi("mmv_irradiance0", irradiance->GetIrradianceTexture(0)->GetTextureUnit());
    if (count > 4)
    {
      program->SetUniformi(
        "mmv_irradiance1", irradiance->GetIrradianceTexture(1)->GetTextureUnit());
    }
    std::vector<mmv::LightSource> sources(count);
    std::vector<glm::dvec3> radiance(count);
    for (int k = 0; k < count; ++k)
    {
      sources[k] = this->Lights[k].Source;
      radiance[k] = this->Lights[k].Radiance;
    }
    mmv::SetLightUniforms(program, sources.data(), radiance.data(), count, count);
    if (this->Variant.RGBIrradiance)
    {
      // The tint grid spans the irradiance grid's points (every second one).
      vtkTextureObject* grey = irradiance->GetIrradianceTexture(0);
      vtkTextureObject* tint = irradiance->GetTintTexture(0);
      const unsigned int m[3] = { grey->GetWidth(), grey->GetHeight(), grey->GetDepth() };
      const unsigned int t[3] = { tint->GetWidth(), tint->GetHeight(), tint->GetDepth() };
      float scale[3], bias[3];
      for (int a = 0; a < 3; ++a)
      {
        mmv::SamePointsMap(m[a], t[a], scale[a], bias[a]);
      }
      program->SetUniform3f("mmv_tintScale", scale);
      program->SetUniform3f("mmv_tintBias", bias);
      std::vector<int> units(count);
      for (int k = 0; k < count; ++k)
      {
        units[k] = irradiance->GetTintTexture(k)->GetTextureUnit();
      }
      program->SetUniform1iv("mmv_tint", count, units.data());
    }
  }
  if (this->Variant.Reflection && this->Reflection)
  {
    this->Reflection->SetUniforms(program);
  }
}

void vtkMultiMaterialShadingUniforms::ActivateTextures(
  bool on, vtkMultiMaterialTextures* textures, vtkIrradianceEstimator* irradiance) const
{
  const int count =
    this->Variant.NumberOfLights > 0 ? std::min(irradiance->GetNumberOfIrradianceTextures(), 2) : 0;
  if (on)
  {
    textures->Activate();
  }
  else
  {
    textures->Deactivate();
  }
  if (this->Variant.Reflection && this->Reflection)
  {
    on ? this->Reflection->Activate() : this->Reflection->Deactivate();
  }
  for (int i = 0; i < count; ++i)
  {
    vtkTextureObject* texture = irradiance->GetIrradianceTexture(i);
    if (on)
    {
      texture->Activate();
    }
    else
    {
      texture->Deactivate();
    }
  }
  for (int k = 0; this->Variant.RGBIrradiance && k < this->Variant.NumberOfLights; ++k)
  {
    vtkTextureObject* tint = irradiance->GetTintTexture(k);
    on ? tint->Activate() : tint->Deactivate();
  }
}
