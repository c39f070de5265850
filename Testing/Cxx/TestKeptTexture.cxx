// A kept copy of a 3D texture (a time step's irradiance or gradient volume)
// comes back bit for bit, whether it is kept on the GPU or in host memory,
// for the formats the kept steps use, with rows that are not 4-byte aligned;
// it is a copy (the texture's later contents do not reach it), and it leaves
// the pixel-transfer state as it found it.
#include "mmvTestWindow.h"

#include "vtkIrradianceComputeProgram.h"
#include "vtkKeptTexture.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace
{
constexpr int Dims[3] = { 13, 7, 5 }; // 13 texels of 2 or 6 bytes: unaligned rows

struct Format
{
  int Components;
  unsigned int Internal;
  unsigned int Base;
};
const Format Formats[] = { { 1, GL_R16F, GL_RED }, { 3, GL_RGB16F, GL_RGB },
  { 4, GL_RGBA16F, GL_RGBA } };

struct Context
{
  Context()
  {
    this->Window = mmvtest::NewRenderWindow();
    this->Window->SetOffScreenRendering(1);
    this->Window->SetSize(8, 8);
    this->Window->Render();
    this->GL = vtkOpenGLRenderWindow::SafeDownCast(this->Window);
    this->GL->MakeCurrent();
  }
  vtkSmartPointer<vtkRenderWindow> Window;
  vtkOpenGLRenderWindow* GL = nullptr;
};

std::vector<float> Values(int components, float phase)
{
  std::vector<float> values(static_cast<size_t>(components) * Dims[0] * Dims[1] * Dims[2]);
  for (size_t i = 0; i < values.size(); ++i)
  {
    values[i] = static_cast<float>(std::sin(0.37 * i + phase) * 100.0);
  }
  return values;
}

vtkSmartPointer<vtkTextureObject> NewTexture(
  vtkOpenGLRenderWindow* context, const Format& format, std::vector<float> values)
{
  auto texture = vtkSmartPointer<vtkTextureObject>::New();
  texture->SetContext(context);
  texture->SetInternalFormat(format.Internal);
  texture->SetFormat(format.Base);
  texture->SetDataType(GL_FLOAT);
  texture->Create3DFromRaw(Dims[0], Dims[1], Dims[2], format.Components, VTK_FLOAT, values.data());
  return texture;
}

/// The texture's texels as half floats.
std::vector<unsigned short> Halves(vtkTextureObject* texture, const Format& format)
{
  std::vector<unsigned short> texels(
    static_cast<size_t>(format.Components) * Dims[0] * Dims[1] * Dims[2]);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTextureImage(texture->GetHandle(), 0, format.Base, GL_HALF_FLOAT,
    static_cast<GLsizei>(texels.size() * 2), texels.data());
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  return texels;
}
}

TEST(KeptTexture, ComesBackBitForBitFromTheGPUAndFromHostMemory)
{
  Context context;
  ASSERT_NE(context.GL, nullptr);
  for (auto place : { mmv::KeptTexture::Place::GPU, mmv::KeptTexture::Place::Host })
  {
    const bool host = place == mmv::KeptTexture::Place::Host;
    mmv::KeptTexture::SetPlace(place);
    for (const Format& format : Formats)
    {
      SCOPED_TRACE(
        std::string(host ? "host, " : "GPU, ") + std::to_string(format.Components) + " components");
      auto texture = NewTexture(context.GL, format, Values(format.Components, 0.0f));
      const std::vector<unsigned short> original = Halves(texture, format);
      // Pixel-transfer state that is not the copies' own.
      glPixelStorei(GL_PACK_ALIGNMENT, 8);
      glPixelStorei(GL_UNPACK_ALIGNMENT, 2);
      std::unique_ptr<mmv::KeptTexture> kept = mmv::KeptTexture::Make(context.GL, texture);
      ASSERT_NE(kept, nullptr);
      EXPECT_EQ(kept->IsInHostMemory(), host);
      EXPECT_EQ(kept->GetBytes(), original.size() * 2);
      GLint pack = 0;
      GLint unpack = 0;
      glGetIntegerv(GL_PACK_ALIGNMENT, &pack);
      glGetIntegerv(GL_UNPACK_ALIGNMENT, &unpack);
      EXPECT_EQ(pack, 8);
      EXPECT_EQ(unpack, 2);
      glPixelStorei(GL_UNPACK_ALIGNMENT, 4);

      // New values in the texture do not reach the copy, which restores the
      // old ones into it and into a texture of its own.
      auto other = NewTexture(context.GL, format, Values(format.Components, 1.0f));
      auto fresh = NewTexture(context.GL, format, Values(format.Components, 2.0f));
      ASSERT_NE(Halves(fresh, format), original);
      ASSERT_TRUE(kept->Fits(other));
      ASSERT_TRUE(kept->Fits(fresh));
      kept->CopyInto(other);
      kept->CopyInto(fresh);
      EXPECT_EQ(Halves(other, format), original);
      EXPECT_EQ(Halves(fresh, format), original);
      EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));

      // Another size or format does not fit.
      const Format& wrong = format.Components == 4 ? Formats[0] : Formats[2];
      EXPECT_FALSE(kept->Fits(NewTexture(context.GL, wrong, Values(wrong.Components, 0.0f))));
    }
  }
  mmv::KeptTexture::SetPlace(mmv::KeptTexture::Place::Automatic);
}

TEST(KeptTexture, ASoftwareRendererKeepsCopiesInHostMemory)
{
  // Where a texture is host memory anyway, the copy skips the renderer's new
  // texture storage; a GPU keeps it beside the texture.
  Context context;
  ASSERT_NE(context.GL, nullptr);
  mmv::KeptTexture::SetPlace(mmv::KeptTexture::Place::Automatic);
  auto texture = NewTexture(context.GL, Formats[2], Values(4, 0.0f));
  std::unique_ptr<mmv::KeptTexture> kept = mmv::KeptTexture::Make(context.GL, texture);
  ASSERT_NE(kept, nullptr);
  EXPECT_EQ(kept->IsInHostMemory(), vtkIrradianceComputeProgram::IsSoftwareRenderer());
}
