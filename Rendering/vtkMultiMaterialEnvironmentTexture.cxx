#include "vtkMultiMaterialEnvironmentTexture.h"

#include "vtkMultiMaterialEnvironment.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLTexture.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"

vtkStandardNewMacro(vtkMultiMaterialEnvironmentTexture);

vtkMultiMaterialEnvironmentTexture::vtkMultiMaterialEnvironmentTexture() = default;
vtkMultiMaterialEnvironmentTexture::~vtkMultiMaterialEnvironmentTexture() = default;

vtkMultiMaterialEnvironment* vtkMultiMaterialEnvironmentTexture::GetEnvironment()
{
  return this->Environment;
}

void vtkMultiMaterialEnvironmentTexture::Update(
  vtkRenderer* ren, vtkMatrix4x4* objectToWorld, int source, std::vector<std::string>* problems)
{
  this->Renderer = ren;
  this->Environment->Update(ren, objectToWorld, source, problems);
}

void vtkMultiMaterialEnvironmentTexture::Activate()
{
  auto* texture = vtkOpenGLTexture::SafeDownCast(this->Environment->GetTexture());
  if (this->Environment->GetKind() == mmv::BackgroundEnvironment || !texture || !this->Renderer)
  {
    return;
  }
  // Uploads when the images changed, and binds a free texture unit.
  texture->Load(this->Renderer);
  this->Active = texture->GetTextureObject() != nullptr;
}

void vtkMultiMaterialEnvironmentTexture::Deactivate()
{
  if (this->Active)
  {
    vtkOpenGLTexture::SafeDownCast(this->Environment->GetTexture())->PostRender(this->Renderer);
    this->Active = false;
  }
}

void vtkMultiMaterialEnvironmentTexture::SetUniforms(vtkShaderProgram* program) const
{
  auto uniform = [program](const char* name, const glm::dvec3& v)
  {
    const float f[3] = { static_cast<float>(v.x), static_cast<float>(v.y),
      static_cast<float>(v.z) };
    program->SetUniform3f(name, f);
  };
  const vtkMultiMaterialEnvironment* environment = this->Environment;
  uniform("mmv_environmentUp", environment->GetViewUp());
  uniform("mmv_environmentBottom", environment->GetBackgroundBottom());
  uniform("mmv_environmentTop", environment->GetBackgroundTop());
  if (environment->GetKind() == mmv::BackgroundEnvironment)
  {
    return;
  }
  uniform("mmv_environmentFrameRight", environment->GetFrameRight());
  uniform("mmv_environmentFrameUp", environment->GetFrameUp());
  uniform("mmv_environmentFrameFront", environment->GetFrameFront());
  program->SetUniformi("mmv_environmentGrey", environment->GetGrey() ? 1 : 0);
  auto* texture = vtkOpenGLTexture::SafeDownCast(environment->GetTexture());
  if (this->Active && texture)
  {
    program->SetUniformi("mmv_environmentTexture", texture->GetTextureObject()->GetTextureUnit());
  }
}

void vtkMultiMaterialEnvironmentTexture::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Active: " << this->Active << "\n";
  this->Environment->PrintSelf(os, indent.GetNextIndent());
}
