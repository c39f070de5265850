/**
 * @file   vtkKeptTexture.h
 * @brief  A copy of a 3D texture kept for a later frame (a time step's
 *         irradiance or gradient volume): a texture beside it on a GPU,
 *         host memory on a software renderer.
 *
 * On a software renderer (llvmpipe) a texture is host memory too, and every
 * new one is new pages: the kernel's fault and zeroing of each 4 KB page costs
 * more than copying the texture into it (on a virtual machine about 4 ms per
 * MB against 0.1). There the copy goes into memory mapped here and advised to
 * transparent huge pages, where one fault brings in 2 MB; the texture is
 * read back into it and written again from it, both plain copies.
 */
#ifndef vtkKeptTexture_h
#define vtkKeptTexture_h

#include "vtkMultiMaterialVolumeModule.h" // export macro
#include "vtkSmartPointer.h"              // the copy on the GPU

#include <cstddef>
#include <memory>

class vtkOpenGLRenderWindow;
class vtkTextureObject;

namespace mmv
{
class VTKMULTIMATERIALVOLUME_EXPORT KeptTexture
{
public:
  enum class Place
  {
    Automatic, // host memory on a software renderer, else the GPU
    GPU,
    Host
  };
  /// Where the copies made from now on go (every process-wide; tests pick).
  static void SetPlace(Place place);
  static Place GetPlace();

  /// A copy of 3D texture `texture` (null: no memory, or no way to copy).
  static std::unique_ptr<KeptTexture> Make(
    vtkOpenGLRenderWindow* context, vtkTextureObject* texture);
  ~KeptTexture();
  KeptTexture(const KeptTexture&) = delete;
  KeptTexture& operator=(const KeptTexture&) = delete;

  /// `texture` has this copy's size and format: CopyInto can fill it.
  bool Fits(vtkTextureObject* texture) const;
  /// Copies this into `texture` (Fits), whose context is current.
  void CopyInto(vtkTextureObject* texture) const;
  /// What the copy holds, 16-bit texels counted as such (mmv::TextureBytes).
  size_t GetBytes() const { return this->Bytes; }
  bool IsInHostMemory() const { return this->Host != nullptr; }

private:
  KeptTexture() = default;
  struct HostPages;
  bool ReadBack(vtkTextureObject* texture);

  vtkSmartPointer<vtkTextureObject> Texture; // on the GPU
  std::unique_ptr<HostPages> Host;           // or in host memory
  int Dimensions[3] = { 0, 0, 0 };
  int Components = 0;
  int VTKType = 0;
  unsigned int Format = 0; // the texels' format and type in host memory
  unsigned int Type = 0;
  size_t Bytes = 0;
};
}

#endif
