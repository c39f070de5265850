#include "vtkCoarseExtinction.h"

#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMultiMaterialParameters.h"
#include "vtkMultiMaterialThreads.h" // mmv::For
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkSMPTools.h"
#include "vtkSkyVisibility.h" // CoarsenIrradianceGrid, AverageOntoGrid

#include <algorithm>
#include <atomic>
#include <cmath>

namespace mmv
{

std::vector<float> SampleExtinction(vtkPiecewiseFunction* opacity, double unitDistance,
  vtkMaterialTransferFunction* materials, const double range[2], int tableSize)
{
  std::vector<float> table(static_cast<size_t>(std::max(tableSize, 2)));
  const int n = static_cast<int>(table.size());
  for (int i = 0; i < n; ++i)
  {
    const double s = range[0] + (range[1] - range[0]) * i / (n - 1.0);
    const double attenuation = materials ? materials->EvaluateParameter(s, Attenuation) : 1.0;
    table[i] =
      static_cast<float>(attenuation * ExtinctionFromOpacity(opacity->GetValue(s), unitDistance));
  }
  return table;
}

void NormalizeScalars(vtkDataArray* scalars, const double range[2], std::vector<float>& values)
{
  const vtkIdType n = scalars->GetNumberOfTuples();
  values.resize(static_cast<size_t>(n));
  NormalizeComponent(scalars, 0, 0, n, range, values.data());
  mmv::For(0, n,
    [&](vtkIdType first, vtkIdType last)
    {
      for (vtkIdType i = first; i < last; ++i)
      {
        values[i] = std::isnan(values[i]) ? 0.0f : std::min(std::max(values[i], 0.0f), 1.0f);
      }
    });
}

IrradianceGrid CoarsenToAtMost(const IrradianceGrid& points, int maxVoxelsPerAxis)
{
  const int* dims = points.Dimensions;
  const int longest = std::max({ dims[0], dims[1], dims[2] });
  const int m = std::max(2, maxVoxelsPerAxis);
  const int stride = std::max(1, (longest - 1 + m - 2) / (m - 1));
  return CoarsenIrradianceGrid(points, stride);
}

bool CoarseExtinction::Key::operator==(const Key& o) const
{
  return this->Points.IsSameGrid(o.Points) && this->Source == o.Source &&
    this->SourceTime == o.SourceTime && this->Range[0] == o.Range[0] &&
    this->Range[1] == o.Range[1] && this->Table == o.Table &&
    this->MaxVoxelsPerAxis == o.MaxVoxelsPerAxis;
}

bool CoarseExtinction::Update(vtkImageData* image, vtkDataArray* scalars, const double range[2],
  const std::vector<float>& table, int maxVoxelsPerAxis)
{
  int dims[3];
  image->GetDimensions(dims);
  Key key;
  key.Source = scalars;
  key.SourceTime = scalars->GetMTime();
  key.Points = MakeIrradianceGrid(image, dims);
  key.Range[0] = range[0];
  key.Range[1] = range[1];
  key.Table = table;
  key.MaxVoxelsPerAxis = maxVoxelsPerAxis;
  return this->Update(std::move(key), scalars);
}

bool CoarseExtinction::Update(const IrradianceGrid& points, const std::vector<float>& values,
  const void* source, vtkMTimeType sourceTime, const double range[2],
  const std::vector<float>& table, int maxVoxelsPerAxis)
{
  Key key;
  key.Source = source;
  key.SourceTime = sourceTime;
  key.Points = points;
  key.Range[0] = range[0];
  key.Range[1] = range[1];
  key.Table = table;
  key.MaxVoxelsPerAxis = maxVoxelsPerAxis;
  // Read in place, normalised as scalars are.
  vtkNew<vtkFloatArray> view;
  view->SetArray(const_cast<float*>(values.data()), static_cast<vtkIdType>(values.size()), 1);
  return this->Update(std::move(key), view);
}

bool CoarseExtinction::Update(Key key, vtkDataArray* scalars)
{
  if (this->HasKey && key == this->Held)
  {
    return false;
  }
  // One counter for every instance: a version names one volume's values.
  static std::atomic<unsigned long> versions{ 0 };
  this->Grid = CoarsenToAtMost(key.Points, key.MaxVoxelsPerAxis);
  const bool sameData = this->HasKey && this->Held.Source == key.Source &&
    this->Held.SourceTime == key.SourceTime && this->Held.Range[0] == key.Range[0] &&
    this->Held.Range[1] == key.Range[1] && this->Held.Points.IsSameGrid(key.Points);
  if (!sameData)
  {
    NormalizeScalars(scalars, key.Range, this->Normalized);
  }
  AverageOntoGrid(key.Points, this->Normalized.data(), this->Grid, this->Values, &key.Table);
  this->Version = ++versions;
  this->Held = std::move(key);
  this->HasKey = true;
  return true;
}

} // namespace mmv
