/**
 * @file   vtkTableLookup.h
 * @brief  How the irradiance estimator reads a per-value table (opacity,
 *         scattering) at a normalised value: one definition for the CPU's
 *         classification, voxel count and brick occupancy.
 *
 * Linear interpolation of an n-entry table over [0, 1], as a bilinear
 * texture lookup at (x + 0.5) / n would do it; Shaders/mmvClassifyFS.glsl
 * computes the same on the GPU (IrradianceEstimator.GPUClassesAndNeededPointsMatchTheCPU).
 */
#ifndef vtkTableLookup_h
#define vtkTableLookup_h

#include <algorithm>
#include <cmath>
#include <vector>

namespace mmv
{

/// Where value t falls in a table of n >= 2 entries: between Entry and
/// Entry + 1, at Weight in [0, 1] from Entry. NaN reads as the lowest value,
/// as mmv::ReplaceNonFinite makes it (an index made from NaN would read
/// outside the table).
struct TablePosition
{
  int Entry = 0;
  float Weight = 0.0f;
};

inline TablePosition LocateInTable(int n, float t)
{
  const float c = std::isnan(t) ? 0.0f : std::min(std::max(t, 0.0f), 1.0f);
  const float x = c * static_cast<float>(n - 1);
  TablePosition p;
  p.Entry = std::min(static_cast<int>(x), n - 2);
  p.Weight = x - static_cast<float>(p.Entry);
  return p;
}

inline float LookupTable(const std::vector<float>& table, float t)
{
  const TablePosition p = LocateInTable(static_cast<int>(table.size()), t);
  return (1.0f - p.Weight) * table[p.Entry] + p.Weight * table[p.Entry + 1];
}

} // namespace mmv

#endif
