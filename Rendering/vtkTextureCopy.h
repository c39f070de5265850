/**
 * @file   vtkTextureCopy.h
 * @brief  GPU-side copies of 3D textures (what the irradiance and gradient
 *         volumes of earlier time steps are kept as), and the sampling the
 *         mapper's volume textures share.
 */
#ifndef vtkTextureCopy_h
#define vtkTextureCopy_h

#include "vtkSmartPointer.h" // return value

#include <cstddef>

class vtkOpenGLRenderWindow;
class vtkTextureObject;

namespace mmv
{
/// Whether this context can copy textures (glCopyImageSubData, OpenGL 4.3).
bool CanCopyTextures();
/// Bytes of `texture` on the GPU (16-bit formats counted as such).
size_t TextureBytes(vtkTextureObject* texture);
/// Same size, components and type: one can be copied into the other.
bool SameTextureSize(vtkTextureObject* a, vtkTextureObject* b);
/// Copies all of 3D texture `from` into `to` (SameTextureSize) on the GPU.
void CopyTexture3D(vtkTextureObject* from, vtkTextureObject* to);
/// Releases a kept copy's GPU memory now, unless something else still holds
/// it (a kept step shown in place of a texture of its own): that holder's
/// last reference releases it then. Needs the texture's context current.
void ReleaseUnlessShown(vtkTextureObject* texture);
/// An uninitialised 3D texture of `like`'s size, format and sampling (null:
/// failed).
vtkSmartPointer<vtkTextureObject> NewTextureLike(
  vtkOpenGLRenderWindow* context, vtkTextureObject* like);
/// Linear filtering, clamped to the edge along every axis.
void UseLinearClamped(vtkTextureObject* texture);
/// Writes box `box` (index bounds; null: all) of 3D texture `texture` from
/// `volume`, the whole texture's texels (x fastest, `format` and `type`),
/// in place (no new texture memory), rows aligned to `alignment` bytes.
/// The unpacking state comes back as it was.
void UploadTextureBox(vtkTextureObject* texture, const int* box, unsigned int format,
  unsigned int type, const void* volume, int alignment = 4);
}

#endif
