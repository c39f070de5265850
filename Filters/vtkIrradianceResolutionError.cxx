#include "vtkIrradianceResolutionError.h"

#include "vtkSMPThreadLocal.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mmv
{

double VisibleIrradiancePSNR(const IrradianceGrid& fine,
  const std::vector<std::vector<float>>& fineValues, const std::vector<float>& weights,
  const IrradianceGrid& coarse, const std::vector<std::vector<float>>& coarseValues)
{
  const vtkIdType fineVoxels = fine.GetNumberOfVoxels();
  const size_t lights = fineValues.size();
  bool fits = lights > 0 && coarseValues.size() == lights &&
    static_cast<vtkIdType>(weights.size()) == fineVoxels;
  for (size_t l = 0; fits && l < lights; ++l)
  {
    fits = static_cast<vtkIdType>(fineValues[l].size()) == fineVoxels &&
      static_cast<vtkIdType>(coarseValues[l].size()) == coarse.GetNumberOfVoxels();
  }
  if (!fits)
  {
    return std::numeric_limits<double>::quiet_NaN();
  }
  // Fine index -> coarse index, one affine map for the whole grid.
  const glm::dmat3 toCoarse = coarse.PhysicalToIndexMatrix() * fine.IndexToPhysicalMatrix();
  const glm::dvec3 offset = coarse.PhysicalToIndex(fine.Origin);

  struct Sums
  {
    double WeightedError = 0.0;
    double Weight = 0.0;
  };
  vtkSMPThreadLocal<Sums> local;
  vtkSMPTools::For(0, fineVoxels,
    [&](vtkIdType begin, vtkIdType end)
    {
      Sums& sums = local.Local();
      for (vtkIdType v = begin; v < end; ++v)
      {
        const double w = weights[v];
        if (!(w > 0.0))
        {
          continue;
        }
        const glm::dvec3 index = toCoarse * fine.IndexOfVoxel(v) + offset;
        double error = 0.0;
        for (size_t l = 0; l < lights; ++l)
        {
          const double d =
            SampleTrilinear(coarse, coarseValues[l].data(), index) - fineValues[l][v];
          error += d * d;
        }
        sums.WeightedError += w * error;
        sums.Weight += w * static_cast<double>(lights);
      }
    });
  Sums total;
  for (const Sums& s : local)
  {
    total.WeightedError += s.WeightedError;
    total.Weight += s.Weight;
  }
  if (!(total.Weight > 0.0) || !(total.WeightedError > 0.0))
  {
    return std::numeric_limits<double>::infinity();
  }
  return -10.0 * std::log10(total.WeightedError / total.Weight);
}

std::vector<float> OpacityWeights(
  const std::vector<float>& normalizedValues, const std::vector<float>& opacityTable)
{
  std::vector<float> weights(normalizedValues.size(), 0.0f);
  const int n = static_cast<int>(opacityTable.size());
  if (n == 0)
  {
    return weights;
  }
  for (size_t v = 0; v < normalizedValues.size(); ++v)
  {
    const float value = normalizedValues[v];
    if (std::isnan(value))
    {
      continue;
    }
    const double x = std::min(std::max(static_cast<double>(value), 0.0), 1.0) * (n - 1);
    const int i = std::min(static_cast<int>(x), n - 1);
    const int j = std::min(i + 1, n - 1);
    const double t = x - i;
    const double w = (1.0 - t) * opacityTable[i] + t * opacityTable[j];
    weights[v] = w > 0.0 ? static_cast<float>(w) : 0.0f;
  }
  return weights;
}

} // namespace mmv
