#include "vtkMultiMaterialRenderPass.h"

#include "vtkInformation.h"
#include "vtkInformationObjectBaseVectorKey.h"
#include "vtkObjectFactory.h"
#include "vtkShaderProgram.h"
#include "vtkSmartPointer.h"

#include <vector>

vtkStandardNewMacro(vtkMultiMaterialRenderPass);

vtkMultiMaterialRenderPass::vtkMultiMaterialRenderPass()
{
  // The base mapper sizes its image-sample draw buffers from a pass's count.
  this->SetActiveDrawBuffers(1);
  this->ReplacementTime.Modified();
}

vtkMultiMaterialRenderPass::~vtkMultiMaterialRenderPass() = default;

void vtkMultiMaterialRenderPass::SetFragmentReplacements(const Replacements& replacements)
{
  if (replacements != this->FragmentReplacements)
  {
    this->FragmentReplacements = replacements;
    this->ReplacementTime.Modified();
    this->Modified();
  }
}

void vtkMultiMaterialRenderPass::InstallInto(vtkInformation* keys)
{
  vtkInformationObjectBaseVectorKey* key = vtkOpenGLRenderPass::RenderPasses();
  const int count = key->Length(keys);
  std::vector<vtkSmartPointer<vtkObjectBase>> others;
  for (int i = 0; i < count; ++i)
  {
    vtkObjectBase* pass = key->Get(keys, i);
    if (pass == this)
    {
      return;
    }
    others.emplace_back(pass);
  }
  key->Clear(keys);
  key->Append(keys, this);
  for (auto& pass : others)
  {
    key->Append(keys, pass);
  }
}

void vtkMultiMaterialRenderPass::RemoveFrom(vtkInformation* keys)
{
  vtkInformationObjectBaseVectorKey* key = vtkOpenGLRenderPass::RenderPasses();
  if (keys && keys->Has(key))
  {
    key->Remove(keys, this);
    if (key->Length(keys) == 0)
    {
      keys->Remove(key);
    }
  }
}

bool vtkMultiMaterialRenderPass::PreReplaceShaderValues(std::string&, std::string&,
  std::string& fragmentShader, vtkAbstractMapper* mapper, vtkProp*)
{
  if (mapper != this->Owner)
  {
    return true;
  }
  for (const auto& replacement : this->FragmentReplacements)
  {
    vtkShaderProgram::Substitute(fragmentShader, replacement.first, replacement.second, false);
  }
  return true;
}

bool vtkMultiMaterialRenderPass::PostReplaceShaderValues(std::string&, std::string&,
  std::string& fragmentShader, vtkAbstractMapper* mapper, vtkProp*)
{
  if (mapper == this->Owner)
  {
    this->LastFragmentSource = fragmentShader;
  }
  return true;
}

bool vtkMultiMaterialRenderPass::SetShaderParameters(
  vtkShaderProgram* program, vtkAbstractMapper* mapper, vtkProp*, vtkOpenGLVertexArrayObject*)
{
  if (mapper == this->Owner && this->Callback && !this->FragmentReplacements.empty())
  {
    this->Callback(program);
  }
  return true;
}

vtkMTimeType vtkMultiMaterialRenderPass::GetShaderStageMTime()
{
  return this->ReplacementTime.GetMTime();
}

void vtkMultiMaterialRenderPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Owner: " << this->Owner << "\n";
  os << indent << "FragmentReplacements: " << this->FragmentReplacements.size() << "\n";
}
