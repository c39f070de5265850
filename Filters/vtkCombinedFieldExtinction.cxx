#include "vtkCombinedFieldExtinction.h"

#include "vtkArrayDispatch.h"
#include "vtkDataArray.h"
#include "vtkDataArrayRange.h"
#include "vtkFloatArray.h"
#include "vtkMultiMaterialThreads.h" // mmv::For
#include "vtkSMPTools.h"
#include "vtkTableLookup.h"

#include <algorithm>
#include <cmath>

namespace mmv
{
namespace
{
/// Beyond this optical depth per unit, D is 1 in float; a finite cap keeps
/// the interpolation of an opaque entry free of inf * 0.
constexpr float MaxExtinction = 1000.0f;

/// Where a field is visible but casts no shadow (c_t = 0), D must still mark
/// the voxel non-empty, so that it is lit: it takes this much opacity, whose
/// shadow no image can show.
constexpr float VisibleWithoutShadow = 1e-7f;

/// One field's tables as a voxel reads them: its shadow extinction per
/// object unit (c_t sigma), its opacity and its scattering.
struct FieldTables
{
  double Offset = 0.0;
  double Scale = 1.0; // value -> t in [0, 1]
  std::vector<float> Extinction;
  std::vector<float> Opacity;
  std::vector<float> Scattering;

  float Normalised(double value) const { return static_cast<float>((value - Offset) * Scale); }
};

std::vector<FieldTables> MakeTables(const std::vector<FieldOptics>& optics)
{
  std::vector<FieldTables> tables(optics.size());
  for (size_t f = 0; f < optics.size(); ++f)
  {
    const FieldOptics& o = optics[f];
    FieldTables& t = tables[f];
    const double width = o.Range[1] - o.Range[0];
    t.Offset = o.Range[0];
    t.Scale = width > 0.0 ? 1.0 / width : 0.0;
    t.Opacity = o.Opacity;
    t.Scattering = o.Scattering;
    t.Extinction.resize(o.Opacity.size());
    for (size_t i = 0; i < o.Opacity.size(); ++i)
    {
      const double alpha = std::min(std::max(static_cast<double>(o.Opacity[i]), 0.0), 1.0);
      const double sigma = alpha >= 1.0 ? MaxExtinction : -std::log1p(-alpha) / o.UnitDistance;
      const double attenuation = i < o.Attenuation.size() ? o.Attenuation[i] : 1.0;
      t.Extinction[i] =
        static_cast<float>(std::min(attenuation * sigma, static_cast<double>(MaxExtinction)));
    }
  }
  return tables;
}

/// D of one tuple.
template <typename Tuple>
float TupleOpacity(const Tuple& values, const std::vector<FieldTables>& tables)
{
  float depth = 0.0f;
  bool visible = false;
  for (size_t f = 0; f < tables.size(); ++f)
  {
    const float t = tables[f].Normalised(static_cast<double>(values[f]));
    depth += LookupTable(tables[f].Extinction, t);
    visible = visible || LookupTable(tables[f].Opacity, t) > 0.0f;
  }
  const float d = 1.0f - std::exp(-depth);
  return visible ? std::max(d, VisibleWithoutShadow) : d;
}

struct CombineWorker
{
  template <typename Array>
  void operator()(Array* array, const std::vector<FieldTables>& tables, float* out) const
  {
    const auto tuples = vtk::DataArrayTupleRange(array);
    mmv::For(0, array->GetNumberOfTuples(),
      [&](vtkIdType first, vtkIdType last)
      {
        for (vtkIdType i = first; i < last; ++i)
        {
          out[i] = TupleOpacity(tuples[i], tables);
        }
      });
  }
};

struct ScatteringWorker
{
  template <typename Array>
  /// The fields' total opacity and opacity-weighted scattering per bin of
  /// the tuples' D (already computed, `d`).
  void operator()(Array* array, const std::vector<FieldTables>& tables, const float* d, int bins,
    std::vector<double>& weights, std::vector<double>& sums) const
  {
    const auto tuples = vtk::DataArrayTupleRange(array);
    for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
    {
      const TablePosition p = LocateInTable(bins, d[i]);
      const int bin = p.Weight < 0.5f ? p.Entry : p.Entry + 1;
      for (size_t f = 0; f < tables.size(); ++f)
      {
        const float t = tables[f].Normalised(static_cast<double>(tuples[i][f]));
        const float alpha = LookupTable(tables[f].Opacity, t);
        weights[bin] += alpha;
        sums[bin] += alpha * LookupTable(tables[f].Scattering, t);
      }
    }
  }
};

/// The weighted means; a bin no voxel fell into (the pre-filter's averages
/// can land there) takes the linear interpolation of its nearest filled
/// neighbours, or the nearest one beyond the last.
std::vector<float> FillEmptyBins(
  const std::vector<double>& weights, const std::vector<double>& sums)
{
  const int bins = static_cast<int>(weights.size());
  std::vector<float> means(bins, 0.0f);
  std::vector<int> filled;
  for (int b = 0; b < bins; ++b)
  {
    if (weights[b] > 0.0)
    {
      means[b] = static_cast<float>(sums[b] / weights[b]);
      filled.push_back(b);
    }
  }
  if (filled.empty())
  {
    return means;
  }
  size_t next = 0;
  for (int b = 0; b < bins; ++b)
  {
    while (next < filled.size() && filled[next] < b)
    {
      ++next;
    }
    if (next < filled.size() && filled[next] == b)
    {
      continue;
    }
    if (next == 0 || next == filled.size())
    {
      means[b] = means[filled[next == 0 ? 0 : filled.size() - 1]];
      continue;
    }
    const int low = filled[next - 1];
    const int high = filled[next];
    const float w = static_cast<float>(b - low) / static_cast<float>(high - low);
    means[b] = (1.0f - w) * means[low] + w * means[high];
  }
  return means;
}

bool Scatters(const std::vector<FieldOptics>& optics)
{
  for (const FieldOptics& o : optics)
  {
    if (std::any_of(o.Scattering.begin(), o.Scattering.end(), [](float s) { return s > 0.0f; }))
    {
      return true;
    }
  }
  return false;
}
} // namespace

bool CombineFieldExtinction(vtkDataArray* fields, const std::vector<FieldOptics>& optics, int bins,
  vtkFloatArray* opacity, std::vector<float>& scattering, std::string* error)
{
  const auto fail = [&](const std::string& why)
  {
    if (error)
    {
      *error = why;
    }
    return false;
  };
  if (!fields)
  {
    return fail("no array of fields");
  }
  const int components = fields->GetNumberOfComponents();
  if (components > MaxFields)
  {
    return fail(std::to_string(components) + " fields; at most " + std::to_string(MaxFields) +
      " can be shaded together");
  }
  if (components != static_cast<int>(optics.size()))
  {
    return fail("the array has " + std::to_string(components) + " components for " +
      std::to_string(optics.size()) + " fields' optics");
  }
  for (const FieldOptics& o : optics)
  {
    if (o.Opacity.size() < 2 || o.Scattering.size() != o.Opacity.size() ||
      o.Attenuation.size() != o.Opacity.size() || !(o.UnitDistance > 0.0))
    {
      return fail("a field's opacity, attenuation and scattering tables need 2 or more entries "
                  "each, and a positive unit distance");
    }
  }
  if (bins < 2)
  {
    return fail("the scattering needs 2 or more bins");
  }
  const std::vector<FieldTables> tables = MakeTables(optics);
  opacity->SetNumberOfComponents(1);
  opacity->SetNumberOfTuples(fields->GetNumberOfTuples());
  float* d = opacity->GetPointer(0);
  if (!vtkArrayDispatch::Dispatch::Execute(fields, CombineWorker{}, tables, d))
  {
    CombineWorker{}(fields, tables, d);
  }
  opacity->Modified();
  scattering.clear();
  if (!Scatters(optics))
  {
    return true;
  }
  std::vector<double> weights(bins, 0.0);
  std::vector<double> sums(bins, 0.0);
  if (!vtkArrayDispatch::Dispatch::Execute(
        fields, ScatteringWorker{}, tables, d, bins, weights, sums))
  {
    ScatteringWorker{}(fields, tables, d, bins, weights, sums);
  }
  scattering = FillEmptyBins(weights, sums);
  return true;
}

float CombinedOpacity(const double* values, const std::vector<FieldOptics>& optics)
{
  return TupleOpacity(values, MakeTables(optics));
}

} // namespace mmv
