#include "vtkMultiMaterialReflection.h"

#include "vtkIrradianceGrid.h"
#include "vtkIrradianceVolumePass.h"
#include "vtkMultiMaterialEnvironment.h"
#include "vtkObjectFactory.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"

#include <algorithm>

vtkStandardNewMacro(vtkMultiMaterialReflection);

vtkMultiMaterialReflection::vtkMultiMaterialReflection() = default;
vtkMultiMaterialReflection::~vtkMultiMaterialReflection() = default;

vtkMultiMaterialEnvironment* vtkMultiMaterialReflection::GetEnvironment()
{
  return this->Environment;
}

int vtkMultiMaterialReflection::GetEnvironmentKind() const
{
  return this->Environment->GetKind();
}

void vtkMultiMaterialReflection::Update(vtkRenderer* ren, vtkMatrix4x4* objectToWorld,
  int source, int visibility, vtkIrradianceVolumePass* pass, const mmv::IrradianceGrid& grid,
  int tableSize, double stepLength, std::vector<std::string>* problems)
{
  this->Environment->Update(ren, objectToWorld, source, problems);
  this->Visibility = mmv::UnoccludedReflections;
  this->Cutaway = false;
  this->Pass = nullptr;
  if (visibility != mmv::MarchedReflectionVisibility)
  {
    return;
  }
  if (!pass || !pass->GetScalarTexture() || !pass->GetShadowTableTexture())
  {
    if (problems)
    {
      problems->push_back("reflections are not occluded by the volume without a light (their "
                          "visibility marches the pre-filtered volume the irradiance pass builds)");
    }
    return;
  }
  this->Visibility = mmv::MarchedReflectionVisibility;
  this->Pass = pass;
  // The pass's cutaway is the mapper's of this frame (or, while its
  // irradiance is kept during interaction, of the irradiance shown).
  this->Cutaway = !pass->GetCutaway().IsEmpty();
  const glm::dmat3 toIndex = grid.PhysicalToIndexMatrix();
  for (int c = 0; c < 3; ++c)
  {
    for (int r = 0; r < 3; ++r)
    {
      this->ToIndex[3 * c + r] = static_cast<float>(toIndex[c][r]); // column-major, as GLSL
    }
    this->Origin[c] = static_cast<float>(grid.Origin[c]);
    this->Dimensions[c] = grid.Dimensions[c];
  }
  // Voxels of the grid marched: its smallest spacing is the march's step.
  this->Offset = static_cast<float>(mmv::ReflectionVisibilityOffsetVoxels * stepLength);
  this->TableSize = static_cast<float>(tableSize);
  this->StepLength = static_cast<float>(stepLength);
}

void vtkMultiMaterialReflection::Activate()
{
  this->Environment->Activate();
  if (this->Pass)
  {
    this->Pass->GetScalarTexture()->Activate();
    this->Pass->GetShadowTableTexture()->Activate();
  }
}

void vtkMultiMaterialReflection::Deactivate()
{
  this->Environment->Deactivate();
  if (this->Pass)
  {
    this->Pass->GetScalarTexture()->Deactivate();
    this->Pass->GetShadowTableTexture()->Deactivate();
  }
}

void vtkMultiMaterialReflection::SetUniforms(vtkShaderProgram* program) const
{
  this->Environment->SetUniforms(program);
  if (!this->Pass)
  {
    return;
  }
  // The uniforms of Shaders/mmvShadowRay.glsl, as the irradiance pass sets them.
  program->SetUniformi("scalars", this->Pass->GetScalarTexture()->GetTextureUnit());
  program->SetUniformi("shadowTable", this->Pass->GetShadowTableTexture()->GetTextureUnit());
  program->SetUniformf("tableSize", this->TableSize);
  program->SetUniform1iv("dims", 3, this->Dimensions);
  program->SetUniformf("stepLength", this->StepLength);
  program->SetUniformMatrix3x3("mmv_visibilityToIndex", const_cast<float*>(this->ToIndex));
  program->SetUniform3f("mmv_visibilityOrigin", this->Origin);
  program->SetUniformf("mmv_visibilityOffset", this->Offset);
  this->Pass->SetCutawayUniforms(program);
}

void vtkMultiMaterialReflection::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Visibility: " << this->Visibility << "\n";
  this->Environment->PrintSelf(os, indent.GetNextIndent());
}
