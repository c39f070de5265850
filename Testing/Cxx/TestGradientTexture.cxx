// The gradient volume as the ray cast reads it: uploaded a slab at a time
// (through a pixel buffer), the texture must hold exactly the halves the
// CPU computes for the whole volume, for a first upload and for new values
// in the same texture, NaN included.
#include "mmvTestWindow.h"

#include "vtkFloatArray.h"
#include "vtkMultiMaterialTextures.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkTextureObject.h"
#include "vtkValueGradient.h"
#include "vtk_glew.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace
{
// 128 x 128 slices: 64 a slab (about a million voxels), so 150 slices take
// three slabs, the last one short.
constexpr int Dims[3] = { 128, 128, 150 };

vtkNew<vtkFloatArray> MakeValues(double phase)
{
  vtkNew<vtkFloatArray> values;
  values->SetNumberOfValues(static_cast<vtkIdType>(Dims[0]) * Dims[1] * Dims[2]);
  for (vtkIdType i = 0; i < values->GetNumberOfValues(); ++i)
  {
    const int x = static_cast<int>(i % Dims[0]);
    const int y = static_cast<int>((i / Dims[0]) % Dims[1]);
    const int z = static_cast<int>(i / (Dims[0] * Dims[1]));
    values->SetValue(
      i, static_cast<float>(std::sin(0.11 * x + phase) * std::cos(0.07 * y) + 0.01 * z));
  }
  values->SetValue(Dims[0] * Dims[1] * 64 + 300, std::nanf("")); // on a slab's first slice
  return values;
}

/// The texture's texels as half floats, 3 per voxel.
std::vector<unsigned short> ReadBack(vtkTextureObject* texture)
{
  std::vector<unsigned short> texels(3 * static_cast<size_t>(Dims[0]) * Dims[1] * Dims[2]);
  texture->Activate();
  GLint alignment = 4;
  glGetIntegerv(GL_PACK_ALIGNMENT, &alignment);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTexImage(GL_TEXTURE_3D, 0, GL_RGB, GL_HALF_FLOAT, texels.data());
  glPixelStorei(GL_PACK_ALIGNMENT, alignment);
  texture->Deactivate();
  return texels;
}

size_t CountDifferent(const std::vector<unsigned short>& a, const std::vector<unsigned short>& b)
{
  size_t different = a.size() == b.size() ? 0 : a.size() + b.size();
  for (size_t i = 0; i < std::min(a.size(), b.size()); ++i)
  {
    different += a[i] != b[i] ? 1 : 0;
  }
  return different;
}
}

TEST(GradientTexture, SlabUploadsHoldTheCPUsHalvesBitForBit)
{
  vtkSmartPointer<vtkRenderWindow> window = mmvtest::NewRenderWindow();
  window->SetOffScreenRendering(1);
  window->SetSize(8, 8);
  window->Render();
  auto* gl = vtkOpenGLRenderWindow::SafeDownCast(window);
  ASSERT_NE(gl, nullptr);
  gl->MakeCurrent();
  vtkNew<vtkMultiMaterialTextures> textures;
  const double range[2] = { -1.0, 2.5 };
  for (double phase : { 0.0, 1.3 })
  {
    vtkNew<vtkFloatArray> values = MakeValues(phase);
    ASSERT_TRUE(textures->UpdateGradientTexture(gl, values, Dims, range));
    std::vector<unsigned short> expected;
    std::vector<float> scratch;
    mmv::ComputeHalfValueGradients(values, 0, Dims, range, 0, Dims[2] - 1, scratch, expected);
    EXPECT_EQ(CountDifferent(ReadBack(textures->GetGradientTexture()), expected), 0u) << phase;
  }
  EXPECT_EQ(textures->GetGradientUploads(), 2);
  // A texture of the other phase's values would differ: the comparison sees
  // the upload.
  vtkNew<vtkFloatArray> first = MakeValues(0.0);
  std::vector<unsigned short> other;
  std::vector<float> scratch;
  mmv::ComputeHalfValueGradients(first, 0, Dims, range, 0, Dims[2] - 1, scratch, other);
  EXPECT_GT(CountDifferent(ReadBack(textures->GetGradientTexture()), other), other.size() / 2);
  textures->ReleaseGraphicsResources(window);
}
