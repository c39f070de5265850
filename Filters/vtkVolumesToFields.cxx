#include "vtkVolumesToFields.h"

#include "vtkMultiMaterialThreads.h"

#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMatrix3x3.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkVolumesToFields);

namespace
{
// Where an output coordinate falls in one input axis: the lower sample and
// the weight of the upper one, or outside.
struct AxisSample
{
  int Lower = 0;
  float Weight = 0.0f;
  bool Inside = false;
};

// Sample positions of `n` output points along one axis in an input axis of
// `inputPoints` points. Positions within 1e-5 of a sample snap to it, so a
// shared lattice copies values exactly.
std::vector<AxisSample> AxisSamples(
  int n, double origin, double spacing, int inputPoints, double inputOrigin, double inputSpacing)
{
  std::vector<AxisSample> samples(n);
  const double eps = 1e-5;
  for (int i = 0; i < n; ++i)
  {
    double t = (origin + i * spacing - inputOrigin) / inputSpacing;
    if (t < -eps || t > inputPoints - 1 + eps)
    {
      continue;
    }
    const double nearest = std::round(t);
    t = std::abs(t - nearest) < eps ? nearest : t;
    t = std::min(std::max(t, 0.0), static_cast<double>(inputPoints - 1));
    AxisSample& s = samples[i];
    s.Inside = true;
    s.Lower = std::min(static_cast<int>(std::floor(t)), std::max(inputPoints - 2, 0));
    s.Weight = static_cast<float>(t - s.Lower);
  }
  return samples;
}

// `field` of `input` trilinearly interpolated at the output's points into
// `out`; points outside the input get `outside`.
void Resample(vtkImageData* input, vtkDataArray* field, const double origin[3],
  const double spacing[3], const int dims[3], float outside, float* out)
{
  int inputDims[3];
  input->GetDimensions(inputDims);
  double inputOrigin[3];
  input->GetOrigin(inputOrigin);
  const double* inputSpacing = input->GetSpacing();
  const int* extent = input->GetExtent();
  std::vector<AxisSample> axes[3];
  for (int a = 0; a < 3; ++a)
  {
    axes[a] = AxisSamples(dims[a], origin[a], spacing[a], inputDims[a],
      inputOrigin[a] + extent[2 * a] * inputSpacing[a], inputSpacing[a]);
  }
  // Floats as they are; other types and layouts as one float copy.
  vtkSmartPointer<vtkFloatArray> values = vtkFloatArray::FastDownCast(field);
  if (!values)
  {
    values = vtkSmartPointer<vtkFloatArray>::New();
    values->DeepCopy(field);
  }
  const float* v = values->GetPointer(0);
  const vtkIdType sx = 1;
  const vtkIdType sy = inputDims[0];
  const vtkIdType sz = static_cast<vtkIdType>(inputDims[0]) * inputDims[1];
  const vtkIdType dx = inputDims[0] > 1 ? sx : 0;
  const vtkIdType dy = inputDims[1] > 1 ? sy : 0;
  const vtkIdType dz = inputDims[2] > 1 ? sz : 0;
  mmv::For(0, static_cast<vtkIdType>(dims[1]) * dims[2], 0,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType row = begin; row < end; ++row)
      {
        const AxisSample& y = axes[1][row % dims[1]];
        const AxisSample& z = axes[2][row / dims[1]];
        float* o = out + row * dims[0];
        if (!y.Inside || !z.Inside)
        {
          std::fill(o, o + dims[0], outside);
          continue;
        }
        const vtkIdType base = y.Lower * sy + z.Lower * sz;
        for (int i = 0; i < dims[0]; ++i)
        {
          const AxisSample& x = axes[0][i];
          if (!x.Inside)
          {
            o[i] = outside;
            continue;
          }
          const float* p = v + base + x.Lower * sx;
          const float fx = x.Weight, fy = y.Weight, fz = z.Weight;
          const float c00 = p[0] + fx * (p[dx] - p[0]);
          const float c10 = p[dy] + fx * (p[dy + dx] - p[dy]);
          const float c01 = p[dz] + fx * (p[dz + dx] - p[dz]);
          const float c11 = p[dz + dy] + fx * (p[dz + dy + dx] - p[dz + dy]);
          const float c0 = c00 + fy * (c10 - c00);
          const float c1 = c01 + fy * (c11 - c01);
          o[i] = c0 + fz * (c1 - c0);
        }
      }
    });
}

// `name`, or with "_2", "_3", ... where an earlier field took it.
std::string UniqueName(const char* name, int input, std::set<std::string>& taken)
{
  const std::string base = name && *name ? name : "Field" + std::to_string(input);
  std::string unique = base;
  for (int n = 2; taken.count(unique); ++n)
  {
    unique = base + "_" + std::to_string(n);
  }
  taken.insert(unique);
  return unique;
}
} // namespace

int vtkVolumesToFields::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  info->Set(vtkAlgorithm::INPUT_IS_REPEATABLE(), 1);
  return 1;
}

vtkDataArray* vtkVolumesToFields::FieldOf(vtkImageData* input)
{
  if (!input)
  {
    return nullptr;
  }
  vtkPointData* pd = input->GetPointData();
  vtkDataArray* scalars = pd->GetScalars();
  if (scalars && scalars->GetNumberOfComponents() == 1)
  {
    return scalars;
  }
  for (int a = 0; a < pd->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* array = pd->GetArray(a);
    if (array && array->GetNumberOfComponents() == 1)
    {
      return array;
    }
  }
  return nullptr;
}

void vtkVolumesToFields::UnionGrid(int inputs, const double* lower, const double* upper,
  const double* spacings, double origin[3], double spacing[3], int dimensions[3])
{
  for (int a = 0; a < 3; ++a)
  {
    double lo = lower[a], hi = upper[a], step = spacings[a];
    for (int i = 1; i < inputs; ++i)
    {
      lo = std::min(lo, lower[3 * i + a]);
      hi = std::max(hi, upper[3 * i + a]);
      step = std::min(step, spacings[3 * i + a]);
    }
    origin[a] = lo;
    spacing[a] = step;
    // A relative tolerance keeps a box that ends on a sample from gaining
    // one more; a count beyond int's range saturates (and is refused).
    const double points = std::ceil((hi - lo) / step - 1e-6) + 1.0;
    dimensions[a] = points < VTK_INT_MAX ? static_cast<int>(points) : VTK_INT_MAX;
  }
}

bool vtkVolumesToFields::OutputGrid(const std::vector<InputBox>& boxes, double origin[3],
  double spacing[3], int dimensions[3], std::string& error) const
{
  const int n = static_cast<int>(boxes.size());
  if (n < 1 || n > MaximumNumberOfInputs)
  {
    error = std::to_string(n) + " inputs: between 1 and " + std::to_string(MaximumNumberOfInputs) +
      " volumes can be one ray's fields";
    return false;
  }
  std::vector<double> lower(3 * n), upper(3 * n), spacings(3 * n);
  for (int i = 0; i < n; ++i)
  {
    const InputBox& box = boxes[i];
    if (!box.AxisAligned)
    {
      error =
        "input " + std::to_string(i) + " has a direction matrix: only axis-aligned volumes merge";
      return false;
    }
    for (int a = 0; a < 3; ++a)
    {
      const double s = box.Spacing[a];
      if (!(s > 0.0) || !std::isfinite(s) || box.Extent[2 * a + 1] < box.Extent[2 * a])
      {
        error = "input " + std::to_string(i) + " is empty or has a spacing that is not positive";
        return false;
      }
      lower[3 * i + a] = box.Origin[a] + box.Extent[2 * a] * s;
      upper[3 * i + a] = box.Origin[a] + box.Extent[2 * a + 1] * s;
      spacings[3 * i + a] = s;
    }
  }
  UnionGrid(n, lower.data(), upper.data(), spacings.data(), origin, spacing, dimensions);
  const double points = static_cast<double>(dimensions[0]) * dimensions[1] * dimensions[2];
  if (!(points <= static_cast<double>(this->MaximumNumberOfPoints)))
  {
    error = "the merged grid " + std::to_string(dimensions[0]) + " x " +
      std::to_string(dimensions[1]) + " x " + std::to_string(dimensions[2]) +
      " has more than MaximumNumberOfPoints (" + std::to_string(this->MaximumNumberOfPoints) +
      ") points";
    return false;
  }
  return true;
}

int vtkVolumesToFields::RequestInformation(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  double origin[3] = { 0.0, 0.0, 0.0 };
  double spacing[3] = { 1.0, 1.0, 1.0 };
  int dims[3] = { 0, 0, 0 };
  // Inputs that cannot merge (or whose geometry is not announced) give an
  // empty extent here and their error in RequestData, which also empties
  // the output and places it by the data themselves.
  vtkInformationVector* inputs = inputVector[0];
  std::vector<InputBox> boxes(inputs->GetNumberOfInformationObjects());
  bool announced = true;
  for (size_t i = 0; i < boxes.size(); ++i)
  {
    vtkInformation* info = inputs->GetInformationObject(static_cast<int>(i));
    announced = announced && info->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT());
    if (announced)
    {
      InputBox& box = boxes[i];
      info->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), box.Extent);
      if (info->Has(vtkDataObject::ORIGIN()))
      {
        info->Get(vtkDataObject::ORIGIN(), box.Origin);
      }
      if (info->Has(vtkDataObject::SPACING()))
      {
        info->Get(vtkDataObject::SPACING(), box.Spacing);
      }
      if (info->Has(vtkDataObject::DIRECTION()))
      {
        vtkNew<vtkMatrix3x3> direction;
        info->Get(vtkDataObject::DIRECTION(), direction->GetData());
        box.AxisAligned = direction->IsIdentity();
      }
    }
  }
  std::string error;
  if (!announced || !this->OutputGrid(boxes, origin, spacing, dims, error))
  {
    dims[0] = dims[1] = dims[2] = 0;
  }
  std::copy(dims, dims + 3, this->AnnouncedDimensions);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  const int extent[6] = { 0, dims[0] - 1, 0, dims[1] - 1, 0, dims[2] - 1 };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  outInfo->Set(vtkDataObject::ORIGIN(), origin, 3);
  outInfo->Set(vtkDataObject::SPACING(), spacing, 3);
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, VTK_FLOAT, 1);
  return 1;
}

int vtkVolumesToFields::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  // Any input point may fall in the output: each input whole.
  vtkInformationVector* inputs = inputVector[0];
  for (int i = 0; i < inputs->GetNumberOfInformationObjects(); ++i)
  {
    vtkInformation* info = inputs->GetInformationObject(i);
    info->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(),
      info->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()), 6);
  }
  return 1;
}

int vtkVolumesToFields::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* output = vtkImageData::GetData(outputVector);
  vtkInformationVector* inputs = inputVector[0];
  output->SetExtent(0, -1, 0, -1, 0, -1);
  output->GetPointData()->Initialize();
  double origin[3], spacing[3];
  int dims[3];
  const int n = inputs->GetNumberOfInformationObjects();
  std::vector<vtkImageData*> images(n);
  std::vector<vtkDataArray*> fields(n);
  std::vector<InputBox> boxes(n);
  for (int i = 0; i < n; ++i)
  {
    images[i] = vtkImageData::GetData(inputs, i);
    fields[i] = FieldOf(images[i]);
    if (!fields[i])
    {
      vtkErrorMacro("input " << i << " has no one-component point array");
      return 0;
    }
    images[i]->GetExtent(boxes[i].Extent);
    images[i]->GetOrigin(boxes[i].Origin);
    images[i]->GetSpacing(boxes[i].Spacing);
    boxes[i].AxisAligned = images[i]->GetDirectionMatrix()->IsIdentity();
  }
  std::string error;
  if (!this->OutputGrid(boxes, origin, spacing, dims, error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  if (!std::equal(dims, dims + 3, this->AnnouncedDimensions))
  {
    // Downstream filters were told the announced extent and may crop to it.
    vtkWarningMacro("the inputs' data make a " << dims[0] << " x " << dims[1] << " x " << dims[2]
                                               << " grid, their pipeline information another: "
                                                  "a source upstream announces a wrong geometry");
  }
  output->SetOrigin(origin);
  output->SetSpacing(spacing);
  output->SetExtent(0, dims[0] - 1, 0, dims[1] - 1, 0, dims[2] - 1);
  const vtkIdType points = output->GetNumberOfPoints();
  std::set<std::string> taken;
  mmv::RunOnAllCores(
    [&]()
    {
      for (int i = 0; i < n; ++i)
      {
        vtkNew<vtkFloatArray> array;
        array->SetName(UniqueName(fields[i]->GetName(), i, taken).c_str());
        array->SetNumberOfTuples(points);
        Resample(images[i], fields[i], origin, spacing, dims,
          static_cast<float>(fields[i]->GetRange(0)[0]), array->GetPointer(0));
        if (i == 0)
        {
          output->GetPointData()->SetScalars(array);
        }
        else
        {
          output->GetPointData()->AddArray(array);
        }
      }
    });
  return 1;
}

void vtkVolumesToFields::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "MaximumNumberOfPoints: " << this->MaximumNumberOfPoints << "\n";
}
