#include "vtkMultiMaterialVolumeGeometry.h"

#include "vtkCamera.h"
#include "vtkImageData.h"
#include "vtkMatrix3x3.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkVolume.h"

#include <algorithm>
#include <cmath>

namespace mmv
{

void SamePointsMap(double n, double m, float& scale, float& bias)
{
  if (n > 1 && m > 1)
  {
    scale = static_cast<float>(n * (m - 1) / ((n - 1) * m));
    bias = static_cast<float>(0.5 / m - 0.5 * (m - 1) / ((n - 1) * m));
  }
  else
  {
    scale = 0.0f;
    bias = 0.5f;
  }
}

void WholeVolumeMaps(vtkImageData* image, float physicalToIndex[16], float gradientToObject[9],
  float dimensions[3], float spacing[3])
{
  int dims[3];
  image->GetDimensions(dims);
  const int* e = image->GetExtent();
  double first[3];
  image->TransformContinuousIndexToPhysicalPoint(e[0], e[2], e[4], first);
  vtkNew<vtkMatrix3x3> inverse;
  vtkMatrix3x3::Invert(image->GetDirectionMatrix(), inverse);
  const double* s = image->GetSpacing();
  std::fill(physicalToIndex, physicalToIndex + 16, 0.0f);
  physicalToIndex[15] = 1.0f;
  for (int r = 0; r < 3; ++r)
  {
    const double sr = std::abs(s[r]) > 0.0 ? s[r] : 1.0;
    double translation = 0.0;
    for (int c = 0; c < 3; ++c)
    {
      const double p = inverse->GetElement(r, c) / sr;
      physicalToIndex[4 * c + r] = static_cast<float>(p);
      translation -= p * first[c];
      // GLSL gets transpose(A), A = diag(1 / ((n - 1) s)) D^-1.
      const double a = inverse->GetElement(r, c) / (dims[r] > 1 ? (dims[r] - 1) * sr : sr);
      gradientToObject[3 * r + c] = static_cast<float>(a);
    }
    physicalToIndex[12 + r] = static_cast<float>(translation);
    dimensions[r] = static_cast<float>(dims[r]);
    spacing[r] = static_cast<float>(std::abs(sr));
  }
}

void PieceToGlobalIrradianceMap(const IrradianceGrid& grid, const double offset[3],
  const int pieceDims[3], float scale[3], float bias[3])
{
  for (int a = 0; a < 3; ++a)
  {
    // Piece point i (texture coordinate t = (i + 0.5) / n) is point o + i of
    // the whole volume, at irradiance index (o + i) / r (r data points per
    // irradiance voxel), texture coordinate ((o + i) / r + 0.5) / m.
    const double n = pieceDims[a];
    const double m = grid.Dimensions[a];
    const double r = grid.DataVoxelsPerVoxel[a];
    if (m > 1 && r > 0.0)
    {
      scale[a] = static_cast<float>(n / (r * m));
      bias[a] = static_cast<float>(((offset[a] - 0.5) / r + 0.5) / m);
    }
    else
    {
      scale[a] = 0.0f;
      bias[a] = 0.5f;
    }
  }
}

double ExpectedSampleDistance(vtkVolume* vol, vtkImageData* image, double sampleDistance,
  bool autoAdjust, bool lock, double spacingAdjusted)
{
  if (!autoAdjust)
  {
    return lock ? spacingAdjusted : sampleDistance;
  }
  vtkMatrix4x4* m = vol->GetMatrix();
  const double* spacing = image->GetSpacing();
  double smallest = VTK_DOUBLE_MAX;
  for (int i = 0; i < 3; ++i)
  {
    const double column = std::sqrt(m->GetElement(0, i) * m->GetElement(0, i) +
      m->GetElement(1, i) * m->GetElement(1, i) + m->GetElement(2, i) * m->GetElement(2, i));
    smallest = std::min(smallest, std::abs(spacing[i] * column));
  }
  return smallest;
}

double ProjectedPixelsPerVoxel(vtkRenderer* ren, vtkVolume* vol, vtkImageData* image)
{
  if (!ren || !ren->GetActiveCamera() || !ren->GetRenderWindow())
  {
    return 0.0;
  }
  const int* size = ren->GetSize();
  if (!size || size[0] < 1 || size[1] < 1)
  {
    return 0.0;
  }
  double center[3];
  image->GetCenter(center);
  vtkMatrix4x4* m = vol->GetMatrix();
  auto toDisplay = [&](const double p[3], double out[2])
  {
    double world[4] = { p[0], p[1], p[2], 1.0 };
    m->MultiplyPoint(world, world);
    ren->SetWorldPoint(world[0] / world[3], world[1] / world[3], world[2] / world[3], 1.0);
    ren->WorldToDisplay();
    const double* d = ren->GetDisplayPoint();
    out[0] = d[0];
    out[1] = d[1];
  };
  double c[2];
  toDisplay(center, c);
  double largest = 0.0;
  vtkMatrix3x3* direction = image->GetDirectionMatrix();
  for (int a = 0; a < 3; ++a)
  {
    double p[3];
    for (int i = 0; i < 3; ++i)
    {
      p[i] = center[i] + direction->GetElement(i, a) * image->GetSpacing()[a];
    }
    double q[2];
    toDisplay(p, q);
    const double pixels = std::hypot(q[0] - c[0], q[1] - c[1]);
    largest = std::isfinite(pixels) ? std::max(largest, pixels) : largest;
  }
  return largest;
}

} // namespace mmv
