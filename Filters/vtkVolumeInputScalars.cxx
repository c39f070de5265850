#include "vtkVolumeInputScalars.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMultiMaterialThreads.h" // mmv::For
#include "vtkPointData.h"
#include "vtkSMPTools.h"

#include <cmath>
#include <string>

namespace mmv
{

vtkSmartPointer<vtkImageData> MakeCellCentreImage(vtkImageData* image, vtkDataArray* cellScalars)
{
  if (!image || !cellScalars)
  {
    return nullptr;
  }
  int extent[6];
  image->GetExtent(extent);
  for (int a = 0; a < 3; ++a)
  {
    if (extent[2 * a + 1] <= extent[2 * a])
    {
      return nullptr; // no cell along this axis has a thickness
    }
  }
  auto centres = vtkSmartPointer<vtkImageData>::New();
  // Cell (i, j, k) spans points i..i+1: its centre is continuous index i + 0.5.
  centres->SetExtent(extent[0], extent[1] - 1, extent[2], extent[3] - 1, extent[4], extent[5] - 1);
  centres->SetSpacing(image->GetSpacing());
  centres->SetDirectionMatrix(image->GetDirectionMatrix());
  double origin[3];
  image->TransformContinuousIndexToPhysicalPoint(0.5, 0.5, 0.5, origin);
  centres->SetOrigin(origin);
  if (cellScalars->GetNumberOfTuples() < centres->GetNumberOfPoints())
  {
    return nullptr;
  }
  // Cell ids run x fastest over the cell dimensions, as the centres' point ids.
  centres->GetPointData()->SetScalars(cellScalars);
  return centres;
}

vtkSmartPointer<vtkDataArray> MakeVectorScalars(
  vtkDataArray* vectors, int mode, int component, std::string* error)
{
  auto fail = [error](const std::string& message)
  {
    if (error)
    {
      *error = message;
    }
    return vtkSmartPointer<vtkDataArray>();
  };
  if (!vectors)
  {
    return fail("no array");
  }
  const int components = vectors->GetNumberOfComponents();
  const vtkIdType tuples = vectors->GetNumberOfTuples();
  vtkSmartPointer<vtkDataArray> result;
  if (mode == VectorModeMagnitude)
  {
    if (vectors->GetDataType() == VTK_DOUBLE)
    {
      result = vtkSmartPointer<vtkDoubleArray>::New();
    }
    else
    {
      result = vtkSmartPointer<vtkFloatArray>::New();
    }
    result->SetNumberOfTuples(tuples);
    for (vtkIdType t = 0; t < tuples; ++t)
    {
      double sum = 0.0;
      for (int c = 0; c < components; ++c)
      {
        const double v = vectors->GetComponent(t, c);
        sum += v * v;
      }
      result->SetComponent(t, 0, std::sqrt(sum));
    }
  }
  else if (mode == VectorModeComponent)
  {
    if (component < 0 || component >= components)
    {
      return fail("component " + std::to_string(component) + " does not exist: the array \"" +
        (vectors->GetName() ? vectors->GetName() : "") + "\" has " + std::to_string(components) +
        " component(s), numbered from 0");
    }
    result.TakeReference(vtkDataArray::CreateDataArray(vectors->GetDataType()));
    result->SetNumberOfTuples(tuples);
    result->CopyComponent(0, vectors, component);
  }
  else
  {
    return fail("unknown vector mode " + std::to_string(mode));
  }
  result->SetName(vectors->GetName());
  return result;
}

void LightingRange(vtkDataArray* scalars, int component, double range[2])
{
  const int type = scalars->GetDataType();
  if (type == VTK_FLOAT || type == VTK_DOUBLE)
  {
    scalars->GetFiniteRange(range, component);
  }
  else
  {
    scalars->GetRange(range, component);
  }
  if (!(range[1] > range[0]))
  {
    range[1] = range[0] + 1.0; // constant: any non-empty range will do
  }
}

vtkSmartPointer<vtkDataArray> MakeFieldArray(
  vtkDataArray* first, const std::vector<vtkDataArray*>& others, std::string* error)
{
  auto fail = [error](const std::string& message)
  {
    if (error)
    {
      *error = message;
    }
    return nullptr;
  };
  const int fields = 1 + static_cast<int>(others.size());
  if (!first || first->GetNumberOfComponents() != 1)
  {
    return fail("the scalars need one component to be read with further fields");
  }
  if (fields > 4)
  {
    return fail(std::to_string(fields) + " fields: at most 4 can be shaded together");
  }
  const vtkIdType tuples = first->GetNumberOfTuples();
  for (size_t f = 0; f < others.size(); ++f)
  {
    if (!others[f])
    {
      return fail("field " + std::to_string(f + 1) + " is not an array of the input");
    }
    if (others[f]->GetNumberOfComponents() != 1 || others[f]->GetNumberOfTuples() < tuples)
    {
      return fail(std::string("field array ") +
        (others[f]->GetName() ? others[f]->GetName() : "(unnamed)") +
        " needs one component and a value per point or cell");
    }
  }
  auto result = vtkSmartPointer<vtkFloatArray>::New();
  result->SetNumberOfComponents(fields);
  result->SetNumberOfTuples(tuples);
  float* out = result->GetPointer(0);
  for (int f = 0; f < fields; ++f)
  {
    vtkDataArray* in = f == 0 ? first : others[f - 1];
    mmv::For(0, tuples,
      [&](vtkIdType begin, vtkIdType end)
      {
        for (vtkIdType i = begin; i < end; ++i)
        {
          out[i * fields + f] = static_cast<float>(in->GetComponent(i, 0));
        }
      });
  }
  result->SetName(first->GetName());
  return result;
}

} // namespace mmv
