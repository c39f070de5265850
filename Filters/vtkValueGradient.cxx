#include "vtkValueGradient.h"

#include "vtkIrradianceGrid.h" // NormalizeComponent

#include "vtkDataArray.h"
#include "vtkMultiMaterialThreads.h" // mmv::For
#include "vtkSMPTools.h"

#include <glm/gtc/packing.hpp>

#if defined(__GNUC__) && defined(__x86_64__)
#include <immintrin.h> // F16C
#endif

#include <algorithm>
#include <cmath>

namespace mmv
{

namespace
{
/// Slices [below, above] of component `component`, normalised over `range`.
void NormalizeSlices(vtkDataArray* scalars, int component, const int dims[3], const double range[2],
  int below, int above, std::vector<float>& values)
{
  const vtkIdType sliceSize = static_cast<vtkIdType>(dims[0]) * dims[1];
  values.resize(static_cast<size_t>(sliceSize) * (above - below + 1));
  NormalizeComponent(scalars, component, below * sliceSize, static_cast<vtkIdType>(values.size()),
    range, values.data());
}

/// IEEE half floats of `count` floats, round to nearest even: by the
/// processor's F16C instructions where it has them (a few times faster than
/// glm's bit manipulation, which rounds the ties of subnormal halves away
/// from zero instead: at most one unit of 2^-24 apart), else by glm.
#if defined(__GNUC__) && defined(__x86_64__)
__attribute__((target("avx,f16c"))) void PackHalvesF16C(
  const float* in, unsigned short* out, size_t count)
{
  size_t i = 0;
  for (; i + 8 <= count; i += 8)
  {
    const __m128i h = _mm256_cvtps_ph(_mm256_loadu_ps(in + i), _MM_FROUND_TO_NEAREST_INT);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out + i), h);
  }
  for (; i < count; ++i)
  {
    out[i] = _cvtss_sh(in[i], _MM_FROUND_TO_NEAREST_INT);
  }
}

bool HasF16C()
{
  static const bool has = __builtin_cpu_supports("avx") && __builtin_cpu_supports("f16c");
  return has;
}
#endif

void PackHalves(const float* in, unsigned short* out, size_t count)
{
#if defined(__GNUC__) && defined(__x86_64__)
  if (HasF16C())
  {
    PackHalvesF16C(in, out, count);
    return;
  }
#endif
  for (size_t i = 0; i < count; ++i)
  {
    out[i] = static_cast<unsigned short>(glm::packHalf1x16(in[i]));
  }
}

/// The central differences (one-sided halves on the faces; non-finite ones
/// 0) of slices [firstSlice, lastSlice], from `values` holding slices
/// `below` on, a row (j, k) at a time into `out` (3 per voxel) through
/// `store(row, target, count)`. One row per task: no index arithmetic per
/// voxel.
template <typename Out, typename Store>
void GradientRows(const std::vector<float>& values, int below, const int dims[3], int firstSlice,
  int lastSlice, Out* out, Store store)
{
  const vtkIdType sliceSize = static_cast<vtkIdType>(dims[0]) * dims[1];
  const int slices = lastSlice - firstSlice + 1;
  mmv::For(0, static_cast<vtkIdType>(dims[1]) * slices,
    [&](vtkIdType begin, vtkIdType end)
    {
      std::vector<float> gradients(3 * static_cast<size_t>(dims[0]));
      for (vtkIdType row = begin; row < end; ++row)
      {
        const int j = static_cast<int>(row % dims[1]);
        const int k = firstSlice + static_cast<int>(row / dims[1]);
        const float* center = values.data() + (k - below) * sliceSize + j * dims[0];
        const float* yBelow = j > 0 ? center - dims[0] : center;
        const float* yAbove = j + 1 < dims[1] ? center + dims[0] : center;
        const float* zBelow = k > 0 ? center - sliceSize : center;
        const float* zAbove = k + 1 < dims[2] ? center + sliceSize : center;
        for (int i = 0; i < dims[0]; ++i)
        {
          const float differences[3] = { center[i + 1 < dims[0] ? i + 1 : i] -
              center[i > 0 ? i - 1 : i],
            yAbove[i] - yBelow[i], zAbove[i] - zBelow[i] };
          for (int a = 0; a < 3; ++a)
          {
            const float g = 0.5f * differences[a];
            gradients[3 * i + a] = std::isfinite(g) ? g : 0.0f;
          }
        }
        store(gradients.data(), out + 3 * (row * dims[0]), gradients.size());
      }
    });
}
} // namespace

void ComputeValueGradients(vtkDataArray* scalars, int component, const int dims[3],
  const double range[2], std::vector<float>& gradients)
{
  std::vector<float> values;
  NormalizeSlices(scalars, component, dims, range, 0, dims[2] - 1, values);
  gradients.resize(3 * values.size());
  GradientRows(values, 0, dims, 0, dims[2] - 1, gradients.data(),
    [](const float* row, float* target, size_t count) { std::copy(row, row + count, target); });
}

void ComputeHalfValueGradients(vtkDataArray* scalars, int component, const int dims[3],
  const double range[2], int firstSlice, int lastSlice, std::vector<float>& values,
  std::vector<unsigned short>& halves)
{
  halves.resize(3 * static_cast<size_t>(dims[0]) * dims[1] * (lastSlice - firstSlice + 1));
  ComputeHalfValueGradients(
    scalars, component, dims, range, firstSlice, lastSlice, values, halves.data());
}

void ComputeHalfValueGradients(vtkDataArray* scalars, int component, const int dims[3],
  const double range[2], int firstSlice, int lastSlice, std::vector<float>& values,
  unsigned short* halves)
{
  // The slab's slices and one more on each side (clamped).
  const int below = std::max(0, firstSlice - 1);
  NormalizeSlices(
    scalars, component, dims, range, below, std::min(dims[2] - 1, lastSlice + 1), values);
  GradientRows(values, below, dims, firstSlice, lastSlice, halves, PackHalves);
}

double ValidGradientSmoothing(double sigma, std::string* why)
{
  if (sigma >= 0.0 && sigma <= MaxGradientSmoothing)
  {
    return sigma;
  }
  const bool above = sigma > MaxGradientSmoothing;
  if (why)
  {
    *why = "GradientSmoothing " + std::to_string(sigma) +
      (above ? " is above " + std::to_string(MaxGradientSmoothing) + " voxels; using it"
             : " must be a number >= 0; using 0 (no smoothing)");
  }
  return above ? MaxGradientSmoothing : 0.0;
}

void GradientSmoothingVoxels(double sigma, const double spacing[3], double voxels[3])
{
  const double largest =
    std::max({ std::abs(spacing[0]), std::abs(spacing[1]), std::abs(spacing[2]) });
  for (int a = 0; a < 3; ++a)
  {
    const double h = std::abs(spacing[a]);
    voxels[a] = sigma > 0.0 && h > 0.0 ? sigma * largest / h : 0.0;
  }
}

void SmoothVectors(
  std::vector<float>& values, int components, const int dims[3], const double sigma[3])
{
  const vtkIdType stride[3] = { 1, dims[0], static_cast<vtkIdType>(dims[0]) * dims[1] };
  const vtkIdType count = stride[2] * dims[2];
  std::vector<float> source;
  for (int a = 0; a < 3; ++a)
  {
    if (!(sigma[a] > 0.0) || dims[a] < 2)
    {
      continue;
    }
    const int radius = std::max(1, static_cast<int>(std::ceil(3.0 * sigma[a])));
    std::vector<double> weights(2 * radius + 1);
    double total = 0.0;
    for (int t = -radius; t <= radius; ++t)
    {
      weights[t + radius] = std::exp(-0.5 * t * t / (sigma[a] * sigma[a]));
      total += weights[t + radius];
    }
    for (double& w : weights)
    {
      w /= total;
    }
    source = values;
    mmv::For(0, count,
      [&](vtkIdType begin, vtkIdType end)
      {
        for (vtkIdType v = begin; v < end; ++v)
        {
          const int i = static_cast<int>((v / stride[a]) % dims[a]);
          for (int c = 0; c < components; ++c)
          {
            double sum = 0.0;
            for (int t = -radius; t <= radius; ++t)
            {
              const int n = std::min(std::max(i + t, 0), dims[a] - 1);
              sum += weights[t + radius] * source[components * (v + (n - i) * stride[a]) + c];
            }
            values[components * v + c] = static_cast<float>(sum);
          }
        }
      });
  }
}

std::vector<float> ResampleVectors(
  const std::vector<float>& values, int components, const int dims[3], const int newDims[3])
{
  std::vector<float> out(static_cast<size_t>(components) * newDims[0] * newDims[1] * newDims[2]);
  double ratio[3];
  for (int a = 0; a < 3; ++a)
  {
    ratio[a] = newDims[a] > 1 ? (dims[a] - 1.0) / (newDims[a] - 1.0) : 0.0;
  }
  const vtkIdType sy = dims[0];
  const vtkIdType sz = static_cast<vtkIdType>(dims[0]) * dims[1];
  mmv::For(0, newDims[2],
    [&](vtkIdType k0, vtkIdType k1)
    {
      for (vtkIdType k = k0; k < k1; ++k)
      {
        for (int j = 0; j < newDims[1]; ++j)
        {
          for (int i = 0; i < newDims[0]; ++i)
          {
            const double p[3] = { i * ratio[0], j * ratio[1], k * ratio[2] };
            int lo[3];
            int hi[3];
            double w[3];
            for (int a = 0; a < 3; ++a)
            {
              lo[a] = std::min(static_cast<int>(p[a]), dims[a] - 1);
              hi[a] = std::min(lo[a] + 1, dims[a] - 1);
              w[a] = p[a] - lo[a];
            }
            const size_t target = components *
              (i + static_cast<size_t>(newDims[0]) * (j + static_cast<size_t>(newDims[1]) * k));
            for (int c = 0; c < components; ++c)
            {
              double sum = 0.0;
              for (int corner = 0; corner < 8; ++corner)
              {
                const int x = corner & 1 ? hi[0] : lo[0];
                const int y = corner & 2 ? hi[1] : lo[1];
                const int z = corner & 4 ? hi[2] : lo[2];
                const double weight = (corner & 1 ? w[0] : 1 - w[0]) *
                  (corner & 2 ? w[1] : 1 - w[1]) * (corner & 4 ? w[2] : 1 - w[2]);
                sum += weight * values[components * (x + y * sy + z * sz) + c];
              }
              out[target + c] = static_cast<float>(sum);
            }
          }
        }
      }
    });
  return out;
}

std::vector<unsigned short> PackHalfFloats(const std::vector<float>& values)
{
  std::vector<unsigned short> halves(values.size());
  mmv::For(0, static_cast<vtkIdType>(values.size()),
    [&](vtkIdType begin, vtkIdType end) {
      PackHalves(values.data() + begin, halves.data() + begin, static_cast<size_t>(end - begin));
    });
  return halves;
}

} // namespace mmv
