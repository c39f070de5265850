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

void UploadTextureBox(vtkTextureObject* texture, const int* box, unsigned int format,
  unsigned int type, const void* volume, int alignment)
{
  const int dims[3] = { static_cast<int>(texture->GetWidth()),
    static_cast<int>(texture->GetHeight()), static_cast<int>(texture->GetDepth()) };
  const int whole[6] = { 0, dims[0] - 1, 0, dims[1] - 1, 0, dims[2] - 1 };
  const int* b = box ? box : whole;
  const size_t components = format == GL_RED ? 1 : format == GL_RG ? 2 : format == GL_RGB ? 3 : 4;
  const size_t bytes = type == GL_FLOAT ? 4 : type == GL_UNSIGNED_SHORT ? 2 : 1;
  const size_t first =
    b[0] + static_cast<size_t>(dims[0]) * (b[2] + static_cast<size_t>(dims[1]) * b[4]);
  GLint rowLength = 0;
  GLint imageHeight = 0;
  GLint unpackAlignment = 4;
  glGetIntegerv(GL_UNPACK_ROW_LENGTH, &rowLength);
  glGetIntegerv(GL_UNPACK_IMAGE_HEIGHT, &imageHeight);
  glGetIntegerv(GL_UNPACK_ALIGNMENT, &unpackAlignment);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, dims[0]);
  glPixelStorei(GL_UNPACK_IMAGE_HEIGHT, dims[1]);
  glPixelStorei(GL_UNPACK_ALIGNMENT, alignment);
  texture->Activate();
  glTexSubImage3D(GL_TEXTURE_3D, 0, b[0], b[2], b[4], b[1] - b[0] + 1, b[3] - b[2] + 1,
    b[5] - b[4] + 1, format, type, static_cast<const char*>(volume) + first * components * bytes);
  texture->Deactivate();
  glPixelStorei(GL_UNPACK_ROW_LENGTH, rowLength);
  glPixelStorei(GL_UNPACK_IMAGE_HEIGHT, imageHeight);
  glPixelStorei(GL_UNPACK_ALIGNMENT, unpackAlignment);
}
}
