#include "vtkMultiMaterialShaderHook.h"

#include "vtkInformation.h"
#include "vtkInformationObjectBaseVectorKey.h"
#include "vtkMultiMaterialLiveObjects.h"
#include "vtkObjectFactory.h"
#include "vtkShaderProgram.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <vector>

vtkStandardNewMacro(vtkMultiMaterialShaderHook);

vtkMultiMaterialShaderHook::vtkMultiMaterialShaderHook()
{
  vtkMultiMaterialLiveObjects::Constructed("vtkMultiMaterialShaderHook");
  // The base mapper sizes its image-sample draw buffers from a pass's count.
  this->SetActiveDrawBuffers(1);
  this->ReplacementTime.Modified();
}

vtkMultiMaterialShaderHook::~vtkMultiMaterialShaderHook()
{
  vtkMultiMaterialLiveObjects::Destroyed("vtkMultiMaterialShaderHook");
}

void vtkMultiMaterialShaderHook::SetFragmentReplacements(const Replacements& replacements)
{
  if (replacements != this->FragmentReplacements)
  {
    this->FragmentReplacements = replacements;
    this->ReplacementTime.Modified();
    this->Modified();
  }
}

namespace
{
// VTK 9.2's vtkInformationObjectBaseVectorKey::Append() registers its value
// twice (an explicit Register() besides the smart pointer of its vector) and
// only Remove(info, value) gives both back: Clear(), Resize() and the death of
// the information give back one. So a pass appended to a volume's keys and
// still there when the volume died leaked, once per mapper, and so did every
// other pass that a Clear() took out and Append() put back. Set() and
// Resize() touch only the smart pointers; rewriting the list with them keeps
// every object's count as its owner left it, whoever empties the list later.
using PassList = std::vector<vtkSmartPointer<vtkObjectBase>>;

PassList GetPasses(vtkInformation* keys)
{
  vtkInformationObjectBaseVectorKey* key = vtkOpenGLRenderPass::RenderPasses();
  PassList passes;
  const int count = keys->Has(key) ? key->Length(keys) : 0;
  for (int i = 0; i < count; ++i)
  {
    passes.emplace_back(key->Get(keys, i));
  }
  return passes;
}

void SetPasses(vtkInformation* keys, const PassList& passes)
{
  vtkInformationObjectBaseVectorKey* key = vtkOpenGLRenderPass::RenderPasses();
  if (passes.empty())
  {
    keys->Remove(key);
    return;
  }
  key->Resize(keys, static_cast<int>(passes.size()));
  for (size_t i = 0; i < passes.size(); ++i)
  {
    key->Set(keys, passes[i], static_cast<int>(i));
  }
}
}

void vtkMultiMaterialShaderHook::InstallInto(vtkInformation* keys)
{
  PassList passes = GetPasses(keys);
  if (std::find(passes.begin(), passes.end(), this) == passes.end())
  {
    passes.insert(passes.begin(), this);
    SetPasses(keys, passes);
  }
}

void vtkMultiMaterialShaderHook::RemoveFrom(vtkInformation* keys)
{
  if (!keys)
  {
    return;
  }
  PassList passes = GetPasses(keys);
  const auto end = std::remove(passes.begin(), passes.end(), this);
  if (end != passes.end())
  {
    passes.erase(end, passes.end());
    SetPasses(keys, passes);
  }
}

bool vtkMultiMaterialShaderHook::PreReplaceShaderValues(
  std::string&, std::string&, std::string& fragmentShader, vtkAbstractMapper* mapper, vtkProp*)
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

bool vtkMultiMaterialShaderHook::PostReplaceShaderValues(
  std::string&, std::string&, std::string& fragmentShader, vtkAbstractMapper* mapper, vtkProp*)
{
  if (mapper == this->Owner)
  {
    this->LastFragmentSource = fragmentShader;
  }
  return true;
}

bool vtkMultiMaterialShaderHook::SetShaderParameters(
  vtkShaderProgram* program, vtkAbstractMapper* mapper, vtkProp*, vtkOpenGLVertexArrayObject*)
{
  if (mapper == this->Owner && this->Callback && !this->FragmentReplacements.empty())
  {
    this->Callback(program);
  }
  return true;
}

vtkMTimeType vtkMultiMaterialShaderHook::GetShaderStageMTime()
{
  return this->ReplacementTime.GetMTime();
}

void vtkMultiMaterialShaderHook::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Owner: " << this->Owner << "\n";
  os << indent << "FragmentReplacements: " << this->FragmentReplacements.size() << "\n";
}
