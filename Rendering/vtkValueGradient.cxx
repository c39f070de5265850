#include "vtkValueGradient.h"

#include "vtkDataArray.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>

namespace mmv
{

void ComputeValueGradients(vtkDataArray* scalars, int component, const int dims[3],
  const double range[2], std::vector<float>& gradients)
{
  const vtkIdType stride[3] = { 1, dims[0], static_cast<vtkIdType>(dims[0]) * dims[1] };
  const vtkIdType count = stride[2] * dims[2];
  const double scale = range[1] > range[0] ? 1.0 / (range[1] - range[0]) : 0.0;
  std::vector<float> values(count);
  vtkSMPTools::For(0, count, [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType v = begin; v < end; ++v)
    {
      values[v] = static_cast<float>((scalars->GetComponent(v, component) - range[0]) * scale);
    }
  });
  gradients.resize(3 * count);
  vtkSMPTools::For(0, count, [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType v = begin; v < end; ++v)
    {
      const int index[3] = { static_cast<int>(v % dims[0]),
        static_cast<int>((v / dims[0]) % dims[1]), static_cast<int>(v / stride[2]) };
      for (int a = 0; a < 3; ++a)
      {
        const vtkIdType below = index[a] > 0 ? v - stride[a] : v;
        const vtkIdType above = index[a] + 1 < dims[a] ? v + stride[a] : v;
        const float g = 0.5f * (values[above] - values[below]);
        gradients[3 * v + a] = std::isfinite(g) ? g : 0.0f;
      }
    }
  });
}

} // namespace mmv
