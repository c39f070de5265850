#include "vtkKeptTexture.h"

#include "vtkIrradianceComputeProgram.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkTextureCopy.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include <cstdint>
#include <limits>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace
{
mmv::KeptTexture::Place KeptPlace = mmv::KeptTexture::Place::Automatic;

/// The host format and type that hold `texture`'s texels as they are (a plain
/// copy both ways); false for formats the kept copies do not use.
bool HostFormatOf(vtkTextureObject* texture, unsigned int& format, unsigned int& type)
{
  const int components = texture->GetComponents();
  const unsigned int formats[] = { GL_RED, GL_RG, GL_RGB, GL_RGBA };
  if (components < 1 || components > 4)
  {
    return false;
  }
  format = formats[components - 1];
  const int vtkType = texture->GetVTKDataType();
  switch (texture->GetInternalFormat(vtkType, components, false))
  {
    case GL_R16F:
    case GL_RG16F:
    case GL_RGB16F:
    case GL_RGBA16F:
      type = GL_HALF_FLOAT;
      return true;
    case GL_R16:
    case GL_RG16:
    case GL_RGB16:
    case GL_RGBA16:
      type = GL_UNSIGNED_SHORT;
      return true;
    case GL_R32F:
    case GL_RG32F:
    case GL_RGB32F:
    case GL_RGBA32F:
      type = GL_FLOAT;
      return true;
    default:
      return false;
  }
}

size_t TypeBytes(unsigned int type)
{
  return type == GL_FLOAT ? 4 : 2;
}

/// Pixel transfers to and from client memory, tightly packed, for the
/// lifetime of this object.
class ClientPixelTransfers
{
public:
  ClientPixelTransfers()
  {
    glGetIntegerv(GL_PACK_ALIGNMENT, &this->Pack);
    glGetIntegerv(GL_UNPACK_ALIGNMENT, &this->Unpack);
    glGetIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &this->PackBuffer);
    glGetIntegerv(GL_PIXEL_UNPACK_BUFFER_BINDING, &this->UnpackBuffer);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
  }
  ~ClientPixelTransfers()
  {
    glPixelStorei(GL_PACK_ALIGNMENT, this->Pack);
    glPixelStorei(GL_UNPACK_ALIGNMENT, this->Unpack);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, static_cast<GLuint>(this->PackBuffer));
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, static_cast<GLuint>(this->UnpackBuffer));
  }
  ClientPixelTransfers(const ClientPixelTransfers&) = delete;
  ClientPixelTransfers& operator=(const ClientPixelTransfers&) = delete;

private:
  GLint Pack = 4;
  GLint Unpack = 4;
  GLint PackBuffer = 0;
  GLint UnpackBuffer = 0;
};
}

namespace mmv
{
/// Host memory of its own mapping, advised to transparent huge pages (2 MB):
/// freed at once when dropped, and a fault per 2 MB where the kernel has them.
struct KeptTexture::HostPages
{
  explicit HostPages(size_t bytes)
  {
#if defined(__linux__)
    constexpr size_t huge = size_t(2) << 20;
    const size_t rounded = (bytes + huge - 1) / huge * huge;
    this->MappedBytes = rounded + huge; // room to start at a 2 MB boundary
    void* mapping =
      mmap(nullptr, this->MappedBytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (mapping == MAP_FAILED)
    {
      return;
    }
    this->Mapping = mapping;
    const std::uintptr_t start = reinterpret_cast<std::uintptr_t>(mapping);
    this->Data = reinterpret_cast<char*>((start + huge - 1) / huge * huge);
    // Advice only: without huge pages the memory is the same, in 4 KB pages.
    madvise(this->Data, rounded, MADV_HUGEPAGE);
#else
    this->Owned.reset(new (std::nothrow) char[bytes]);
    this->Data = this->Owned.get();
#endif
  }
  ~HostPages()
  {
#if defined(__linux__)
    if (this->Mapping)
    {
      munmap(this->Mapping, this->MappedBytes);
    }
#endif
  }
  HostPages(const HostPages&) = delete;
  HostPages& operator=(const HostPages&) = delete;

  char* Data = nullptr;
#if defined(__linux__)
  void* Mapping = nullptr;
  size_t MappedBytes = 0;
#else
  std::unique_ptr<char[]> Owned;
#endif
};

void KeptTexture::SetPlace(Place place)
{
  KeptPlace = place;
}

KeptTexture::Place KeptTexture::GetPlace()
{
  return KeptPlace;
}

std::unique_ptr<KeptTexture> KeptTexture::Make(
  vtkOpenGLRenderWindow* context, vtkTextureObject* texture)
{
  if (!context || !texture || !texture->GetHandle())
  {
    return nullptr;
  }
  std::unique_ptr<KeptTexture> kept(new KeptTexture);
  kept->Dimensions[0] = texture->GetWidth();
  kept->Dimensions[1] = texture->GetHeight();
  kept->Dimensions[2] = texture->GetDepth();
  kept->Components = texture->GetComponents();
  kept->VTKType = texture->GetVTKDataType();
  kept->Bytes = mmv::TextureBytes(texture);
  const bool host = KeptPlace == Place::Host ||
    (KeptPlace == Place::Automatic && vtkIrradianceComputeProgram::IsSoftwareRenderer());
  if (host && kept->ReadBack(texture))
  {
    return kept;
  }
  if (!mmv::CanCopyTextures())
  {
    return nullptr;
  }
  kept->Texture = mmv::NewTextureLike(context, texture);
  if (!kept->Texture)
  {
    return nullptr;
  }
  mmv::CopyTexture3D(texture, kept->Texture);
  return kept;
}

bool KeptTexture::ReadBack(vtkTextureObject* texture)
{
  if (!glGetTextureImage || !glTextureSubImage3D ||
    !HostFormatOf(texture, this->Format, this->Type))
  {
    return false;
  }
  const size_t bytes = static_cast<size_t>(this->Dimensions[0]) * this->Dimensions[1] *
    this->Dimensions[2] * this->Components * TypeBytes(this->Type);
  if (bytes > static_cast<size_t>(std::numeric_limits<GLsizei>::max()))
  {
    return false; // more than one read can return
  }
  auto pages = std::unique_ptr<HostPages>(new HostPages(bytes));
  if (!pages->Data)
  {
    return false;
  }
  ClientPixelTransfers transfers;
  glGetTextureImage(
    texture->GetHandle(), 0, this->Format, this->Type, static_cast<GLsizei>(bytes), pages->Data);
  this->Host = std::move(pages);
  return true;
}

KeptTexture::~KeptTexture()
{
  if (this->Texture)
  {
    // The context is current wherever copies are dropped (a render, or a
    // release of graphics resources).
    this->Texture->ReleaseGraphicsResources(this->Texture->GetContext());
  }
}

bool KeptTexture::Fits(vtkTextureObject* texture) const
{
  return texture && texture->GetHandle() &&
    static_cast<int>(texture->GetWidth()) == this->Dimensions[0] &&
    static_cast<int>(texture->GetHeight()) == this->Dimensions[1] &&
    static_cast<int>(texture->GetDepth()) == this->Dimensions[2] &&
    texture->GetComponents() == this->Components && texture->GetVTKDataType() == this->VTKType;
}

void KeptTexture::CopyInto(vtkTextureObject* texture) const
{
  if (this->Texture)
  {
    mmv::CopyTexture3D(this->Texture, texture);
    return;
  }
  ClientPixelTransfers transfers;
  glTextureSubImage3D(texture->GetHandle(), 0, 0, 0, 0, this->Dimensions[0], this->Dimensions[1],
    this->Dimensions[2], this->Format, this->Type, this->Host->Data);
}
}
