#include "vtkTextureCopy.h"

#include "vtkOpenGLRenderWindow.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

namespace
{
/// Bytes of one texel: 16-bit formats (the irradiance, tint and gradient)
/// whatever VTK type they were allocated with.
size_t TexelBytes(vtkTextureObject* texture)
{
  const int type = texture->GetVTKDataType();
  const unsigned int internal = texture->GetInternalFormat(type, texture->GetComponents(), false);
  switch (internal)
  {
    case GL_R16:
    case GL_RG16:
    case GL_RGBA16:
    case GL_R16F:
    case GL_RG16F:
    case GL_RGB16F:
    case GL_RGBA16F:
      return 2 * static_cast<size_t>(texture->GetComponents());
    default:
      return 4 * static_cast<size_t>(texture->GetComponents());
  }
}
}

namespace mmv
{
bool CanCopyTextures()
{
  return glCopyImageSubData != nullptr;
}

size_t TextureBytes(vtkTextureObject* texture)
{
  return TexelBytes(texture) * texture->GetWidth() * texture->GetHeight() * texture->GetDepth();
}

bool SameTextureSize(vtkTextureObject* a, vtkTextureObject* b)
{
  return a->GetWidth() == b->GetWidth() && a->GetHeight() == b->GetHeight() &&
    a->GetDepth() == b->GetDepth() && a->GetComponents() == b->GetComponents() &&
    a->GetVTKDataType() == b->GetVTKDataType();
}

void CopyTexture3D(vtkTextureObject* from, vtkTextureObject* to)
{
  glCopyImageSubData(from->GetHandle(), GL_TEXTURE_3D, 0, 0, 0, 0, to->GetHandle(), GL_TEXTURE_3D,
    0, 0, 0, 0, static_cast<GLsizei>(from->GetWidth()), static_cast<GLsizei>(from->GetHeight()),
    static_cast<GLsizei>(from->GetDepth()));
}

void ReleaseUnlessShown(vtkTextureObject* texture)
{
  // The caller's reference is the kept list's own.
  if (texture->GetReferenceCount() == 1)
  {
    texture->ReleaseGraphicsResources(texture->GetContext());
  }
}

vtkSmartPointer<vtkTextureObject> NewTextureLike(
  vtkOpenGLRenderWindow* context, vtkTextureObject* like)
{
  const int type = like->GetVTKDataType();
  const int components = like->GetComponents();
  auto texture = vtkSmartPointer<vtkTextureObject>::New();
  texture->SetContext(context);
  texture->SetInternalFormat(like->GetInternalFormat(type, components, false));
  texture->SetFormat(like->GetFormat(type, components, false));
  texture->SetDataType(like->GetDataType(type));
  // Sampled as the original (a kept copy is shown in its place).
  texture->SetMinificationFilter(like->GetMinificationFilter());
  texture->SetMagnificationFilter(like->GetMagnificationFilter());
  texture->SetWrapS(like->GetWrapS());
  texture->SetWrapT(like->GetWrapT());
  texture->SetWrapR(like->GetWrapR());
  if (!texture->Allocate3D(like->GetWidth(), like->GetHeight(), like->GetDepth(), components, type))
  {
    return nullptr;
  }
  return texture;
}

void UseLinearClamped(vtkTextureObject* texture)
{
  texture->SetMinificationFilter(vtkTextureObject::Linear);
  texture->SetMagnificationFilter(vtkTextureObject::Linear);
  texture->SetWrapS(vtkTextureObject::ClampToEdge);
  texture->SetWrapT(vtkTextureObject::ClampToEdge);
  texture->SetWrapR(vtkTextureObject::ClampToEdge);
}
}
