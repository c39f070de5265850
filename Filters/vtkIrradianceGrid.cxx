#include "vtkIrradianceGrid.h"

#include "vtkArrayDispatch.h"
#include "vtkDataArray.h"
#include "vtkDataArrayRange.h"
#include "vtkImageData.h"
#include "vtkMatrix3x3.h"
#include "vtkMultiMaterialParameters.h"
#include "vtkMultiMaterialThreads.h" // mmv::For
#include "vtkSMPTools.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

namespace
{

/// Pre-filter samples per axis and irradiance voxel, at most.
constexpr int MaxFootprintSamples = 8;

/// Trilinear interpolation of `values` (dims, x fastest) at a continuous
/// index, clamped to the grid.
/// a (1 - w) + b w, where a tap of weight 0 is not read at all: a non-finite
/// neighbour must not turn a sample that sits exactly on a point into NaN
/// (0 * Inf is NaN), so at the data's resolution a NaN or Inf point stays
/// where it is.
double Lerp(double a, double b, double w)
{
  return w == 0.0 ? a : (w == 1.0 ? b : a * (1 - w) + b * w);
}

double Interpolate(const int dims[3], const float* values, const glm::dvec3& index)
{
  int i0[3];
  int i1[3];
  double w[3];
  for (int a = 0; a < 3; ++a)
  {
    const double x = std::min(std::max(index[a], 0.0), static_cast<double>(dims[a] - 1));
    i0[a] = std::min(static_cast<int>(x), dims[a] - 1);
    i1[a] = std::min(i0[a] + 1, dims[a] - 1);
    w[a] = x - i0[a];
  }
  const vtkIdType sy = dims[0];
  const vtkIdType sz = static_cast<vtkIdType>(dims[0]) * dims[1];
  auto at = [&](int i, int j, int k) { return static_cast<double>(values[i + j * sy + k * sz]); };
  // Taps of weight 0 along an axis are skipped (Lerp), so read lazily.
  auto row = [&](int j, int k)
  { return w[0] == 0.0 ? at(i0[0], j, k) : Lerp(at(i0[0], j, k), at(i1[0], j, k), w[0]); };
  auto plane = [&](int k)
  { return w[1] == 0.0 ? row(i0[1], k) : Lerp(row(i0[1], k), row(i1[1], k), w[1]); };
  return w[2] == 0.0 ? plane(i0[2]) : Lerp(plane(i0[2]), plane(i1[2]), w[2]);
}

} // namespace

namespace
{
/// (v - offset) * scale of one component of tuples [first, first + count).
struct AffineCopyWorker
{
  template <typename Array>
  void operator()(Array* array, int component, vtkIdType first, vtkIdType count, double offset,
    double scale, float* out) const
  {
    const auto tuples = vtk::DataArrayTupleRange(array);
    mmv::For(0, count,
      [&](vtkIdType begin, vtkIdType end)
      {
        for (vtkIdType i = begin; i < end; ++i)
        {
          out[i] = static_cast<float>(
            (static_cast<double>(tuples[first + i][component]) - offset) * scale);
        }
      });
  }
};

void AffineCopy(vtkDataArray* scalars, int component, vtkIdType first, vtkIdType count,
  double offset, double scale, float* out)
{
  if (!vtkArrayDispatch::Dispatch::Execute(
        scalars, AffineCopyWorker{}, component, first, count, offset, scale, out))
  {
    AffineCopyWorker{}(scalars, component, first, count, offset, scale, out);
  }
}
} // namespace

namespace mmv
{

std::vector<float> CopyComponent(vtkDataArray* scalars, int component)
{
  std::vector<float> values;
  CopyComponent(scalars, component, values);
  return values;
}

void CopyComponent(vtkDataArray* scalars, int component, std::vector<float>& values)
{
  CopyComponent(scalars, component, 0, scalars->GetNumberOfTuples(), values);
}

void CopyComponent(vtkDataArray* scalars, int component, vtkIdType first, vtkIdType count,
  std::vector<float>& values)
{
  values.resize(count);
  AffineCopy(scalars, component, first, count, 0.0, 1.0, values.data());
}

void NormalizeComponent(vtkDataArray* scalars, int component, vtkIdType first, vtkIdType count,
  const double range[2], float* values)
{
  const double scale = range[1] > range[0] ? 1.0 / (range[1] - range[0]) : 0.0;
  AffineCopy(scalars, component, first, count, range[0], scale, values);
}

int IrradianceTextureChannels(int lights)
{
  return lights <= 2 ? std::max(1, lights) : 4;
}

double IrradianceBytesPerVoxel(int numberOfLights, bool tinted)
{
  const int lights = std::max(1, numberOfLights);
  const int full = lights / IrradianceLightsPerTexture;
  const int rest = lights % IrradianceLightsPerTexture;
  const int channels =
    full * IrradianceLightsPerTexture + (rest > 0 ? IrradianceTextureChannels(rest) : 0);
  return IrradianceBytesPerVoxelPerLight * channels +
    (tinted ? TintBytesPerVoxelPerLight * lights : 0.0);
}

void ComputeIrradianceDimensions(const int dataDims[3], int numberOfLights, double budgetMB,
  double scale, int irradianceDims[3], bool tinted)
{
  int d[3];
  int lo[3];
  int active = 0;
  for (int a = 0; a < 3; ++a)
  {
    d[a] = std::max(1, dataDims[a]);
    lo[a] = std::min(2, d[a]);
    active += d[a] > 1 ? 1 : 0;
  }
  auto apply = [&](double s)
  {
    for (int a = 0; a < 3; ++a)
    {
      const int n = static_cast<int>(std::lround(d[a] * s));
      irradianceDims[a] = std::min(d[a], std::max(lo[a], n));
    }
  };
  if (scale > 0.0)
  {
    apply(std::min(scale, 1.0));
    return;
  }
  const double bytesPerVoxel = IrradianceBytesPerVoxel(numberOfLights, tinted);
  const double budgetVoxels = std::max(0.0, budgetMB) * 1024.0 * 1024.0 / bytesPerVoxel;
  auto voxels = [&]()
  { return static_cast<double>(irradianceDims[0]) * irradianceDims[1] * irradianceDims[2]; };
  const double dataVoxels = static_cast<double>(d[0]) * d[1] * d[2];
  // Start from the continuous answer (only axes longer than 1 shrink), then
  // step down until the rounded dimensions fit or reach their minimum.
  double s = active > 0 ? std::min(1.0, std::pow(budgetVoxels / dataVoxels, 1.0 / active)) : 1.0;
  apply(s);
  for (int i = 0; i < 4000 && voxels() > budgetVoxels; ++i)
  {
    if (irradianceDims[0] == lo[0] && irradianceDims[1] == lo[1] && irradianceDims[2] == lo[2])
    {
      break;
    }
    s *= 0.998;
    apply(s);
  }
}

IrradianceResolution ChooseIrradianceResolution(const int dataDims[3], int numberOfLights,
  double budgetMB, double userScale, double pixelsPerDataVoxel, bool tinted)
{
  IrradianceResolution result;
  char text[256];
  if (userScale > 0.0)
  {
    result.Scale = std::min(userScale, 1.0);
    ComputeIrradianceDimensions(
      dataDims, numberOfLights, budgetMB, result.Scale, result.Dimensions, tinted);
    std::snprintf(text, sizeof(text), "IrradianceScale %.3g (set by the user)", result.Scale);
    result.Reason = text;
    return result;
  }
  ComputeIrradianceDimensions(dataDims, numberOfLights, budgetMB, 0.0, result.Dimensions, tinted);
  double budgetScale = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    if (dataDims[a] > 1)
    {
      budgetScale = std::max(budgetScale, static_cast<double>(result.Dimensions[a]) / dataDims[a]);
    }
  }
  budgetScale = budgetScale > 0.0 ? budgetScale : 1.0;
  result.Scale = budgetScale;
  std::snprintf(text, sizeof(text), "memory budget %.4g MB for %d light(s): scale %.3g", budgetMB,
    numberOfLights, budgetScale);
  result.Reason = text;
  if (pixelsPerDataVoxel > 0.0 && std::isfinite(pixelsPerDataVoxel))
  {
    const double wanted = pixelsPerDataVoxel / PixelsPerIrradianceVoxel;
    const double screenScale = std::min(1.0, std::exp2(std::ceil(4.0 * std::log2(wanted)) / 4.0));
    if (screenScale < budgetScale)
    {
      result.Scale = screenScale;
      ComputeIrradianceDimensions(
        dataDims, numberOfLights, budgetMB, screenScale, result.Dimensions, tinted);
      std::snprintf(text, sizeof(text),
        "screen: %.3g px per data voxel, %.3g px per irradiance voxel: scale %.3g (the budget "
        "allows %.3g)",
        pixelsPerDataVoxel, PixelsPerIrradianceVoxel, screenScale, budgetScale);
      result.Reason = text;
    }
  }
  return result;
}

IrradianceGrid MakeIrradianceGrid(vtkImageData* image, const int irradianceDims[3])
{
  return MakeIrradianceGrid(image->GetExtent(), image->GetOrigin(), image->GetSpacing(),
    image->GetDirectionMatrix()->GetData(), irradianceDims);
}

IrradianceGrid MakeIrradianceGrid(const int extent[6], const double origin[3],
  const double spacing[3], const double* direction, const int irradianceDims[3])
{
  static constexpr double Identity[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  const double* dir = direction ? direction : Identity;
  IrradianceGrid grid;
  // Voxel (0,0,0) sits on the extent's first point, not on the image origin.
  double first[3];
  vtkImageData::TransformContinuousIndexToPhysicalPoint(
    extent[0], extent[2], extent[4], origin, spacing, dir, first);
  for (int a = 0; a < 3; ++a)
  {
    const int dataDim = extent[2 * a + 1] - extent[2 * a] + 1;
    grid.Dimensions[a] = irradianceDims[a];
    grid.Origin[a] = first[a];
    grid.Spacing[a] = spacing[a];
    grid.DataVoxelsPerVoxel[a] = 1.0;
    if (irradianceDims[a] > 1)
    {
      grid.DataVoxelsPerVoxel[a] = (dataDim - 1.0) / (irradianceDims[a] - 1.0);
      grid.Spacing[a] = spacing[a] * (dataDim - 1) / (irradianceDims[a] - 1);
    }
    for (int r = 0; r < 3; ++r)
    {
      grid.Direction[a][r] = dir[3 * r + a]; // glm: [column][row]
    }
  }
  return grid;
}

double SampleTrilinear(const IrradianceGrid& grid, const float* values, const glm::dvec3& index)
{
  return Interpolate(grid.Dimensions, values, index);
}

bool ClipToIndexBox(
  const glm::dvec3& p, const glm::dvec3& d, const int dims[3], double& t0, double& t1)
{
  for (int a = 0; a < 3; ++a)
  {
    const double high = dims[a] - 1.0;
    if (d[a] == 0.0)
    {
      if (p[a] < 0.0 || p[a] > high)
      {
        return false;
      }
      continue;
    }
    double tNear = (0.0 - p[a]) / d[a];
    double tFar = (high - p[a]) / d[a];
    if (tNear > tFar)
    {
      std::swap(tNear, tFar);
    }
    t0 = std::max(t0, tNear);
    t1 = std::min(t1, tFar);
  }
  return t1 > t0;
}

FootprintLayout MakeFootprintLayout(const int dataDims[3], const int gridDims[3])
{
  FootprintLayout layout;
  for (int a = 0; a < 3; ++a)
  {
    layout.Ratio[a] = gridDims[a] > 1 ? (dataDims[a] - 1.0) / (gridDims[a] - 1.0) : 0.0;
    // Axes at full resolution take the data value itself (an exact copy).
    layout.Samples[a] = gridDims[a] == dataDims[a]
      ? 1
      : std::min(MaxFootprintSamples, std::max(2, static_cast<int>(std::ceil(layout.Ratio[a]))));
  }
  return layout;
}

glm::dvec3 FootprintSample(const FootprintLayout& layout, const glm::dvec3& voxel, const int q[3])
{
  glm::dvec3 p = voxel * glm::dvec3(layout.Ratio[0], layout.Ratio[1], layout.Ratio[2]);
  for (int a = 0; a < 3; ++a)
  {
    if (layout.Samples[a] > 1)
    {
      // Midpoint rule over the footprint, one irradiance spacing wide.
      p[a] += layout.Ratio[a] * ((q[a] + 0.5) / layout.Samples[a] - 0.5);
    }
  }
  return p;
}

namespace
{
/// One axis of the footprint filter: for each grid index, the data points
/// its samples' linear weights reach (taps of weight 0 left out, as the
/// trilinear interpolation leaves them unread) and their summed weights.
struct AxisTaps
{
  std::vector<int> First; // per grid index: its first tap in Index/Weight
  std::vector<int> Index;
  std::vector<double> Weight;
};

AxisTaps MakeAxisTaps(const FootprintLayout& layout, int axis, int dataDim, int gridDim)
{
  AxisTaps taps;
  taps.First.push_back(0);
  std::vector<double> weights(dataDim, 0.0);
  std::vector<char> reached(dataDim, 0);
  for (int o = 0; o < gridDim; ++o)
  {
    std::vector<int> touched;
    for (int q = 0; q < layout.Samples[axis]; ++q)
    {
      glm::dvec3 voxel(0.0);
      voxel[axis] = o;
      const int sample[3] = { q, q, q };
      const double x = std::min(std::max(FootprintSample(layout, voxel, sample)[axis], 0.0),
        static_cast<double>(dataDim - 1));
      const int i0 = std::min(static_cast<int>(x), dataDim - 1);
      const int i1 = std::min(i0 + 1, dataDim - 1);
      const double w = x - i0;
      const double share = 1.0 / layout.Samples[axis];
      auto add = [&](int i, double weight)
      {
        if (!reached[i])
        {
          reached[i] = 1;
          touched.push_back(i);
        }
        weights[i] += share * weight;
      };
      // As Lerp: a weight of 0 or 1 reads one point only.
      if (w != 1.0)
      {
        add(i0, 1.0 - w);
      }
      if (w != 0.0)
      {
        add(i1, w);
      }
    }
    std::sort(touched.begin(), touched.end());
    for (int i : touched)
    {
      taps.Index.push_back(i);
      taps.Weight.push_back(weights[i]);
      weights[i] = 0.0;
      reached[i] = 0;
    }
    taps.First.push_back(static_cast<int>(taps.Index.size()));
  }
  return taps;
}

/// in[(i, j, k)] with strides (1, n0, n0 n1) filtered along `axis` into
/// `out`. Along y and z, whole rows along x at once, so every read is
/// contiguous; each output is the same sum in the same order as along x.
template <typename In, typename Out>
void FilterAxis(
  const In* in, const int inDims[3], int axis, const AxisTaps& t, int outLength, Out* out)
{
  int outDims[3] = { inDims[0], inDims[1], inDims[2] };
  outDims[axis] = outLength;
  const vtkIdType inStride[3] = { 1, inDims[0], static_cast<vtkIdType>(inDims[0]) * inDims[1] };
  const vtkIdType outStride[3] = { 1, outDims[0], static_cast<vtkIdType>(outDims[0]) * outDims[1] };
  if (axis == 0)
  {
    mmv::For(0, outDims[2],
      [&](vtkIdType begin, vtkIdType end)
      {
        for (vtkIdType z = begin; z < end; ++z)
        {
          for (int y = 0; y < outDims[1]; ++y)
          {
            const vtkIdType inBase = z * inStride[2] + y * inStride[1];
            const vtkIdType outBase = z * outStride[2] + y * outStride[1];
            for (int o = 0; o < outLength; ++o)
            {
              double sum = 0.0;
              for (int n = t.First[o]; n < t.First[o + 1]; ++n)
              {
                sum += t.Weight[n] * static_cast<double>(in[inBase + t.Index[n]]);
              }
              out[outBase + o] = static_cast<Out>(sum);
            }
          }
        }
      });
    return;
  }
  const int other = axis == 1 ? 2 : 1;
  const int width = inDims[0];
  mmv::For(0, outDims[other],
    [&](vtkIdType begin, vtkIdType end)
    {
      std::vector<double> row(width);
      for (vtkIdType w = begin; w < end; ++w)
      {
        for (int o = 0; o < outLength; ++o)
        {
          std::fill(row.begin(), row.end(), 0.0);
          for (int n = t.First[o]; n < t.First[o + 1]; ++n)
          {
            const double weight = t.Weight[n];
            const auto* source = in + w * inStride[other] + t.Index[n] * inStride[axis];
            for (int x = 0; x < width; ++x)
            {
              row[x] += weight * static_cast<double>(source[x]);
            }
          }
          Out* target = out + w * outStride[other] + o * outStride[axis];
          for (int x = 0; x < width; ++x)
          {
            target[x] = static_cast<Out>(row[x]);
          }
        }
      }
    });
}
}

void PrefilterScalars(vtkImageData* image, vtkDataArray* scalars, int component,
  const IrradianceGrid& grid, std::vector<float>& prefiltered, PrefilterScratch* scratch)
{
  PrefilterScratch local;
  PrefilterScratch& buffers = scratch ? *scratch : local;
  const int* extent = image->GetExtent();
  const int dataDims[3] = { extent[1] - extent[0] + 1, extent[3] - extent[2] + 1,
    extent[5] - extent[4] + 1 };
  const int* g = grid.Dimensions;
  const FootprintLayout layout = MakeFootprintLayout(dataDims, g);
  // The midpoint rule over trilinear samples is a tensor product of one 1D
  // filter per axis: filtered along x, then y, then z, each pass reading a
  // few points per output instead of 8 per sample per voxel.
  AxisTaps taps[3];
  for (int a = 0; a < 3; ++a)
  {
    taps[a] = MakeAxisTaps(layout, a, dataDims[a], g[a]);
  }
  // A slab of output slices at a time, from the data slices its z taps
  // read (filtered along x and y once per slab, a few again at the slab's
  // ends): the buffers hold a slab, not the volume. Each output is the same
  // sum in the same order as over the whole volume. Every output is
  // written: a new buffer's zeros are never read.
  prefiltered.resize(static_cast<size_t>(g[0]) * g[1] * g[2]);
  const vtkIdType sliceSize = static_cast<vtkIdType>(dataDims[0]) * dataDims[1];
  const int outputsPerSlab = static_cast<int>(
    std::max<vtkIdType>(1, buffers.SlabPoints / std::max<vtkIdType>(1, sliceSize)));
  for (int k0 = 0; k0 < g[2]; k0 += outputsPerSlab)
  {
    const int k1 = std::min(g[2], k0 + outputsPerSlab); // exclusive
    const AxisTaps& z = taps[2];
    const int first =
      *std::min_element(z.Index.begin() + z.First[k0], z.Index.begin() + z.First[k1]);
    const int last =
      *std::max_element(z.Index.begin() + z.First[k0], z.Index.begin() + z.First[k1]);
    AxisTaps slabTaps;
    slabTaps.First.assign(z.First.begin() + k0, z.First.begin() + k1 + 1);
    for (int& f : slabTaps.First)
    {
      f -= z.First[k0];
    }
    slabTaps.Weight.assign(z.Weight.begin() + z.First[k0], z.Weight.begin() + z.First[k1]);
    for (int n = z.First[k0]; n < z.First[k1]; ++n)
    {
      slabTaps.Index.push_back(z.Index[n] - first);
    }
    const int depth = last - first + 1;
    CopyComponent(scalars, component, first * sliceSize, depth * sliceSize, buffers.Values);
    buffers.AlongX.resize(static_cast<size_t>(g[0]) * dataDims[1] * depth);
    buffers.AlongY.resize(static_cast<size_t>(g[0]) * g[1] * depth);
    int dims[3] = { dataDims[0], dataDims[1], depth };
    FilterAxis(buffers.Values.data(), dims, 0, taps[0], g[0], buffers.AlongX.data());
    dims[0] = g[0];
    FilterAxis(buffers.AlongX.data(), dims, 1, taps[1], g[1], buffers.AlongY.data());
    dims[1] = g[1];
    FilterAxis(buffers.AlongY.data(), dims, 2, slabTaps, k1 - k0,
      prefiltered.data() + static_cast<size_t>(k0) * g[0] * g[1]);
  }
}

bool ReplaceNonFinite(std::vector<float>& values, float low, float high)
{
  std::atomic<bool> replaced(false);
  mmv::For(0, static_cast<vtkIdType>(values.size()),
    [&](vtkIdType begin, vtkIdType end)
    {
      bool here = false;
      for (vtkIdType i = begin; i < end; ++i)
      {
        float& v = values[i];
        if (!std::isfinite(v))
        {
          here = true;
          v = v > 0.0f ? high : low;
        }
      }
      if (here)
      {
        replaced = true;
      }
    });
  return replaced;
}

double ValidIrradianceScale(double scale, std::string* why)
{
  if (scale >= 0.0 && scale <= 1.0)
  {
    return scale;
  }
  const bool above = scale > 1.0;
  if (why)
  {
    *why = "IrradianceScale " + std::to_string(scale) +
      (above ? " is above 1 (the data's resolution); using 1"
             : " must be in [0, 1]; using 0 (automatic)");
  }
  return above ? 1.0 : 0.0;
}

double ValidIrradianceErrorBound(double bound, std::string* why)
{
  if (bound >= 0.0 && bound <= MaxIrradianceErrorBoundDB)
  {
    return bound;
  }
  const bool above = bound > MaxIrradianceErrorBoundDB;
  if (why)
  {
    *why = "IrradianceErrorBound " + std::to_string(bound) +
      (above ? " dB is above " + std::to_string(MaxIrradianceErrorBoundDB) +
            " (no coarser grid can reach it); using that"
             : " must be >= 0 dB; using 0 (no error probe)");
  }
  return above ? MaxIrradianceErrorBoundDB : 0.0;
}

} // namespace mmv
