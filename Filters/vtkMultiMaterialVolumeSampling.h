/**
 * @file   vtkMultiMaterialVolumeSampling.h
 * @brief  What the CPU renderers share to read a volume: trilinear sampling of
 *         the scalars, the index/object geometry, the colour table and the
 *         camera's pixel rays.
 *
 * vtkMultiMaterialReferenceRenderer (our optical model) and
 * vtkMultiMaterialPathTracer (the physical one) both read the scene through
 * these, so that their images differ only by the model, never by a
 * half-voxel shift, a different colour lookup or a different pixel centre.
 */
#ifndef vtkMultiMaterialVolumeSampling_h
#define vtkMultiMaterialVolumeSampling_h

#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkMatrix3x3.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkVolumeProperty.h"

#include <glm/glm.hpp>
#include <glm/mat3x3.hpp>

#include <algorithm>
#include <string>
#include <vector>

namespace mmv
{

/// The data on its grid: trilinear sampling at continuous index coordinates,
/// clamped to the grid like the GPU's clamp-to-edge textures.
struct ScalarField
{
  int Dims[3] = { 0, 0, 0 };
  const double* Values = nullptr;

  double Sample(const glm::dvec3& p) const { return this->SampleArray(this->Values, p); }

  template <typename T>
  T SampleArray(const T* a, const glm::dvec3& p) const
  {
    int i0[3];
    double f[3];
    for (int c = 0; c < 3; ++c)
    {
      const double x = std::min(std::max(p[c], 0.0), this->Dims[c] - 1.0);
      i0[c] = std::min(static_cast<int>(x), this->Dims[c] - 2);
      f[c] = x - i0[c];
    }
    const long long sx = 1;
    const long long sy = this->Dims[0];
    const long long sz = static_cast<long long>(this->Dims[0]) * this->Dims[1];
    const T* b = a + i0[0] + i0[1] * sy + i0[2] * sz;
    const double c00 = b[0] + f[0] * (b[sx] - b[0]);
    const double c10 = b[sy] + f[0] * (b[sy + sx] - b[sy]);
    const double c01 = b[sz] + f[0] * (b[sz + sx] - b[sz]);
    const double c11 = b[sz + sy] + f[0] * (b[sz + sy + sx] - b[sz + sy]);
    const double c0 = c00 + f[1] * (c10 - c00);
    const double c1 = c01 + f[1] * (c11 - c01);
    return static_cast<T>(c0 + f[2] * (c1 - c0));
  }
};

/// Index -> object map of an image: origin + direction * diag(spacing).
/// False when the spacing or direction is degenerate.
inline bool ImageIndexToObject(vtkImageData* image, glm::dvec3& origin, glm::dmat3& indexToObject)
{
  const double* spacing = image->GetSpacing();
  const double* o = image->GetOrigin();
  const double* direction = image->GetDirectionMatrix()->GetData();
  for (int r = 0; r < 3; ++r)
  {
    origin[r] = o[r];
    for (int c = 0; c < 3; ++c)
    {
      indexToObject[c][r] = direction[r * 3 + c] * spacing[c]; // glm is column-major
    }
  }
  return glm::determinant(indexToObject) != 0.0;
}

/**
 * Reads an image's active point scalars (component 0) into `values` and
 * `field`, their finite range (a constant volume gets [v, v + 1], as the
 * mapper does) and the index -> object geometry. Returns "" on success, else
 * what is wrong with the input.
 */
inline std::string LoadScalarField(vtkImageData* image, std::vector<double>& values,
  ScalarField& field, double range[2], glm::dvec3& origin, glm::dmat3& indexToObject)
{
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  if (!scalars)
  {
    return "the input has no point scalars";
  }
  image->GetDimensions(field.Dims);
  if (field.Dims[0] < 2 || field.Dims[1] < 2 || field.Dims[2] < 2)
  {
    return "the input needs at least 2 points along every axis";
  }
  const vtkIdType count = image->GetNumberOfPoints();
  values.resize(count);
  for (vtkIdType v = 0; v < count; ++v)
  {
    values[v] = scalars->GetComponent(v, 0);
  }
  field.Values = values.data();
  scalars->GetFiniteRange(range, 0);
  if (!(range[1] > range[0]))
  {
    range[1] = range[0] + 1.0;
  }
  if (!ImageIndexToObject(image, origin, indexToObject))
  {
    return "the input's spacing or direction is degenerate";
  }
  return "";
}

/// The property's colour (gray or RGB; white without either) tabulated at
/// `size` points over `range`, rgb per entry.
inline void TabulateColor(
  vtkVolumeProperty* property, const double range[2], int size, std::vector<double>& rgb)
{
  rgb.assign(3 * static_cast<size_t>(size), 1.0);
  if (property->GetColorChannels(0) == 1 && property->GetGrayTransferFunction(0))
  {
    std::vector<double> gray(size);
    property->GetGrayTransferFunction(0)->GetTable(range[0], range[1], size, gray.data());
    for (int i = 0; i < size; ++i)
    {
      rgb[3 * i] = rgb[3 * i + 1] = rgb[3 * i + 2] = gray[i];
    }
  }
  else if (vtkColorTransferFunction* color = property->GetRGBTransferFunction(0))
  {
    color->GetTable(range[0], range[1], size, rgb.data());
  }
}

/// Homogeneous point transform.
inline glm::dvec3 TransformPoint(const vtkMatrix4x4* m, const glm::dvec3& x)
{
  double in[4] = { x.x, x.y, x.z, 1.0 };
  double out[4];
  vtkMatrix4x4::MultiplyPoint(m->GetData(), in, out);
  return glm::dvec3(out[0], out[1], out[2]) / out[3];
}

/// The ray of NDC point (x, y) in the space `ndcToSpace` maps to: from the
/// near plane, unit direction, length to the far plane (0 if degenerate).
inline void PixelRay(const vtkMatrix4x4* ndcToSpace, double x, double y, glm::dvec3& origin,
  glm::dvec3& direction, double& length)
{
  origin = TransformPoint(ndcToSpace, glm::dvec3(x, y, -1.0));
  const glm::dvec3 farPoint = TransformPoint(ndcToSpace, glm::dvec3(x, y, 1.0));
  length = glm::length(farPoint - origin);
  direction = length > 0.0 ? (farPoint - origin) / length : glm::dvec3(0.0, 0.0, -1.0);
}

/// The camera's view-up in object space (unit; +y if it degenerates): the
/// axis of the background gradient seen as an environment.
inline glm::dvec3 ViewUpInObject(vtkCamera* camera, vtkMatrix4x4* worldToObject)
{
  const double* up = camera->GetViewUp();
  glm::dvec3 u(0.0);
  for (int i = 0; i < 3; ++i)
  {
    u[i] = worldToObject->GetElement(i, 0) * up[0] + worldToObject->GetElement(i, 1) * up[1] +
      worldToObject->GetElement(i, 2) * up[2];
  }
  return glm::length(u) > 0.0 ? glm::normalize(u) : glm::dvec3(0.0, 1.0, 0.0);
}

/// NDC -> object matrix of the camera at width x height, for PixelRay().
inline void NDCToObject(
  vtkCamera* camera, int width, int height, vtkMatrix4x4* worldToObject, vtkMatrix4x4* ndcToObject)
{
  vtkNew<vtkMatrix4x4> ndcToWorld;
  ndcToWorld->DeepCopy(
    camera->GetCompositeProjectionTransformMatrix(static_cast<double>(width) / height, -1.0, 1.0));
  ndcToWorld->Invert();
  vtkMatrix4x4::Multiply4x4(worldToObject, ndcToWorld, ndcToObject);
}

} // namespace mmv

#endif
