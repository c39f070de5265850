#include "vtkSweptTransmittance.h"

#include "vtkMultiMaterialParameters.h" // shadow-ray constants
#include "vtkMultiMaterialThreads.h"    // mmv::For

#include <algorithm>
#include <cmath>

#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
#include <immintrin.h>
#endif

namespace mmv
{
namespace
{

// The shadow-ray constants as the shader sees them (ShadowRayGLSLPrelude).
const float MinTransmittance = static_cast<float>(MinShadowTransmittance);
const float StepTolerance = static_cast<float>(ShadowStepToleranceFloat);
const float RestTolerance = static_cast<float>(ShadowRestTolerance);
const float PlaneRelativeTolerance = static_cast<float>(SweepPlaneRelativeTolerance);
const float PlaneAbsoluteTolerance = static_cast<float>(SweepPlaneAbsoluteTolerance);

// The texels around x along an axis of n points, the edge ones clamped,
// and the upper one's weight: linear filtering with clamp-to-edge.
inline void Texels(float x, int n, int& lo, int& hi, float& f)
{
  const float below = std::floor(x);
  f = x - below;
  const int i = static_cast<int>(below);
  lo = std::min(std::max(i, 0), n - 1);
  hi = std::min(std::max(i + 1, 0), n - 1);
}

// Trilinear: along a row between offsets a0 and a1 (weight f) in each of the
// four rows p00, p10 (the next across, weight fc), p01 and p11 (the next
// along the sweep, weight fa).
inline float Trilinear(const float* p00, const float* p10, const float* p01, const float* p11,
  vtkIdType a0, vtkIdType a1, float f, float fc, float fa)
{
  const float b00 = p00[a0] + f * (p00[a1] - p00[a0]);
  const float b10 = p10[a0] + f * (p10[a1] - p10[a0]);
  const float b01 = p01[a0] + f * (p01[a1] - p01[a0]);
  const float b11 = p11[a0] + f * (p11[a1] - p11[a0]);
  const float e0 = b00 + fc * (b10 - b00);
  const float e1 = b01 + fc * (b11 - b01);
  return e0 + fa * (e1 - e0);
}

// mmvShadowOpacity: the table (n x n), bilinear, the edge entries clamped.
inline float ShadowOpacityOf(const float* table, int n, float t1, float t2)
{
  // Clamped; a NaN value reads entry 0 (an index from it would be undefined).
  const float x = (t1 > 0.0f ? std::min(t1, 1.0f) : 0.0f) * static_cast<float>(n - 1);
  const float y = (t2 > 0.0f ? std::min(t2, 1.0f) : 0.0f) * static_cast<float>(n - 1);
  const int i = std::min(static_cast<int>(x), n - 2);
  const int j = std::min(static_cast<int>(y), n - 2);
  const float fx = x - static_cast<float>(i);
  const float fy = y - static_cast<float>(j);
  const float* row = table + static_cast<vtkIdType>(j) * n + i;
  const float a = row[0] + fx * (row[1] - row[0]);
  const float b = row[n] + fx * (row[n + 1] - row[n]);
  return a + fy * (b - a);
}

// One step of a run's march, points [first, count): each point still lit
// (transmittance t >= MinTransmittance) whose segment from `previous` to
// `next` leaves the table's clear corner takes t (1 - alpha); `previous`
// becomes `next`. Returns whether any point was still lit.
inline bool MarchStep(int first, int count, const float* table, int n, float clearBelow,
  float* transmittance, float* previous, const float* next)
{
  bool any = false;
  for (int i = first; i < count; ++i)
  {
    const float t = transmittance[i];
    if (t >= MinTransmittance)
    {
      if (!(previous[i] < clearBelow && next[i] < clearBelow))
      {
        transmittance[i] = t * (1.0f - ShadowOpacityOf(table, n, previous[i], next[i]));
      }
      any = true;
    }
    previous[i] = next[i];
  }
  return any;
}

#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
#define MMV_MARCH_AVX2
// MarchStep eight points at a time, the table read by masked gathers: a
// scalar march branches on each point's transmittance and clear corner and
// reads its four entries one by one (the light kit's shadows on the chest:
// 0.18 s against 0.22-0.23 s on the development VM). The same operations
// in the same order, without FMA (none is enabled here), so every value is
// the scalar one, bit for bit.
__attribute__((target("avx2"))) bool MarchStepAVX2(int count, const float* table, int n,
  float clearBelow, float* transmittance, float* previous, const float* next)
{
  const __m256 minimum = _mm256_set1_ps(MinTransmittance);
  const __m256 clear = _mm256_set1_ps(clearBelow);
  const __m256 zero = _mm256_setzero_ps();
  const __m256 one = _mm256_set1_ps(1.0f);
  const __m256 scale = _mm256_set1_ps(static_cast<float>(n - 1));
  const __m256i lastEntry = _mm256_set1_epi32(n - 2);
  const __m256i rowLength = _mm256_set1_epi32(n);
  int lit = 0;
  int i = 0;
  for (; i + 8 <= count; i += 8)
  {
    const __m256 t = _mm256_loadu_ps(transmittance + i);
    const __m256 p = _mm256_loadu_ps(previous + i);
    const __m256 q = _mm256_loadu_ps(next + i);
    const __m256 active = _mm256_cmp_ps(t, minimum, _CMP_GE_OQ);
    const __m256 inCorner =
      _mm256_and_ps(_mm256_cmp_ps(p, clear, _CMP_LT_OQ), _mm256_cmp_ps(q, clear, _CMP_LT_OQ));
    const __m256 lookup = _mm256_andnot_ps(inCorner, active);
    lit |= _mm256_movemask_ps(active);
    if (_mm256_movemask_ps(lookup) != 0)
    {
      // max(v, 0) gives 0 for NaN (its second operand), as the scalar clamp.
      const __m256 x = _mm256_mul_ps(_mm256_min_ps(_mm256_max_ps(p, zero), one), scale);
      const __m256 y = _mm256_mul_ps(_mm256_min_ps(_mm256_max_ps(q, zero), one), scale);
      const __m256i ix = _mm256_min_epi32(_mm256_cvttps_epi32(x), lastEntry);
      const __m256i iy = _mm256_min_epi32(_mm256_cvttps_epi32(y), lastEntry);
      const __m256 fx = _mm256_sub_ps(x, _mm256_cvtepi32_ps(ix));
      const __m256 fy = _mm256_sub_ps(y, _mm256_cvtepi32_ps(iy));
      const __m256i at = _mm256_add_epi32(_mm256_mullo_epi32(iy, rowLength), ix);
      const __m256 r00 = _mm256_mask_i32gather_ps(zero, table, at, lookup, 4);
      const __m256 r01 = _mm256_mask_i32gather_ps(zero, table + 1, at, lookup, 4);
      const __m256 r10 = _mm256_mask_i32gather_ps(zero, table + n, at, lookup, 4);
      const __m256 r11 = _mm256_mask_i32gather_ps(zero, table + n + 1, at, lookup, 4);
      const __m256 a = _mm256_add_ps(r00, _mm256_mul_ps(fx, _mm256_sub_ps(r01, r00)));
      const __m256 b = _mm256_add_ps(r10, _mm256_mul_ps(fx, _mm256_sub_ps(r11, r10)));
      const __m256 alpha = _mm256_add_ps(a, _mm256_mul_ps(fy, _mm256_sub_ps(b, a)));
      const __m256 shaded = _mm256_mul_ps(t, _mm256_sub_ps(one, alpha));
      _mm256_storeu_ps(transmittance + i, _mm256_blendv_ps(t, shaded, lookup));
    }
    _mm256_storeu_ps(previous + i, q);
  }
  const bool rest = MarchStep(i, count, table, n, clearBelow, transmittance, previous, next);
  return lit != 0 || rest;
}
#endif

// MarchStep over [0, count), eight at a time where the CPU has AVX2.
inline bool MarchStepAll(int count, const float* table, int n, float clearBelow,
  float* transmittance, float* previous, const float* next)
{
#ifdef MMV_MARCH_AVX2
  static const bool avx2 = __builtin_cpu_supports("avx2");
  if (avx2)
  {
    return MarchStepAVX2(count, table, n, clearBelow, transmittance, previous, next);
  }
#endif
  return MarchStep(0, count, table, n, clearBelow, transmittance, previous, next);
}

// One sweep of one light: the shader's functions on the CPU arrays.
class Sweeper
{
public:
  Sweeper(const SweptTransmittanceInputs& inputs, const glm::vec3& toLight,
    const ShadowSweep& sweep, float* target, int channels, int channel)
    : In(inputs)
    , Direction(inputs.WorldToIndex * toLight)
    , Axis(sweep.Axis)
    , Target(target)
    , Channels(channels)
    , Channel(channel)
  {
    const int* d = inputs.Dimensions;
    this->ScalarStride[0] = 1;
    this->ScalarStride[1] = d[0];
    this->ScalarStride[2] = static_cast<vtkIdType>(d[0]) * d[1];
    const int* t = inputs.TargetDimensions;
    this->TargetStride[0] = 1;
    this->TargetStride[1] = t[0];
    this->TargetStride[2] = static_cast<vtkIdType>(t[0]) * t[1];
    // The table's clear corner: entries [0, z]^2 all 0. A segment whose ends
    // both lie below ClearBelow reads only those (x < z - 1/2, so x + 1 <= z)
    // and lets everything through: the march skips its lookup.
    const int n = inputs.TableSize;
    const float* table = inputs.ShadowTable;
    int z = -1;
    for (bool clear = true; clear && z + 1 < n;)
    {
      const int next = z + 1;
      for (int k = 0; clear && k <= next; ++k)
      {
        clear = table[static_cast<vtkIdType>(next) * n + k] == 0.0f &&
          table[static_cast<vtkIdType>(k) * n + next] == 0.0f;
      }
      z = clear ? next : z;
    }
    this->ClearBelow = z > 0 ? (static_cast<float>(z) - 0.5f) / static_cast<float>(n - 1) : -1.0f;
  }

  vtkIdType Chunk(const ShadowSweep& sweep, int chunk, const IndexBox& box);

private:
  // mmvSampleScalar: trilinear, the edge texels clamped.
  float SampleScalar(const glm::vec3& index) const
  {
    int lo[3];
    int hi[3];
    float f[3];
    for (int a = 0; a < 3; ++a)
    {
      Texels(index[a], this->In.Dimensions[a], lo[a], hi[a], f[a]);
    }
    const vtkIdType* stride = this->ScalarStride;
    auto row = [&](int j, int k) { return this->In.Scalars + j * stride[1] + k * stride[2]; };
    return Trilinear(row(lo[1], lo[2]), row(hi[1], lo[2]), row(lo[1], hi[2]), row(hi[1], hi[2]),
      lo[0], hi[0], f[0], f[1], f[2]);
  }

  float ShadowOpacity(float t1, float t2) const
  {
    return ShadowOpacityOf(this->In.ShadowTable, this->In.TableSize, t1, t2);
  }

  // mmvExitDistance.
  float ExitDistance(const glm::vec3& p) const
  {
    float t = 3.0e38f;
    for (int a = 0; a < 3; ++a)
    {
      const float d = this->Direction[a];
      if (d > 0.0f)
      {
        t = std::min(t, (static_cast<float>(this->In.Dimensions[a] - 1) - p[a]) / d);
      }
      else if (d < 0.0f)
      {
        t = std::min(t, -p[a] / d);
      }
    }
    return std::max(t, 0.0f);
  }

  // mmvReachesSweepPlane.
  static bool ReachesPlane(
    float start, float direction, float plane, float exitDistance, float& distance)
  {
    distance = 0.0f;
    if (plane < 0.0f || direction == 0.0f)
    {
      return false;
    }
    distance = (plane - start) / direction;
    return distance >= 0.0f &&
      distance <= exitDistance * (1.0f + PlaneRelativeTolerance) + PlaneAbsoluteTolerance;
  }

  // mmvSampleSlice: bilinear in light grid slice `plane` at q's in-slice
  // coordinates, clamped to the read range.
  float SampleSlice(int plane, const glm::vec3& q, const int range[4]) const
  {
    const int b = (this->Axis + 1) % 3;
    const int c = (this->Axis + 2) % 3;
    int i0[3] = { 0, 0, 0 };
    i0[this->Axis] = plane;
    float f[3] = { 0.0f, 0.0f, 0.0f };
    for (int k = 0; k < 2; ++k)
    {
      const int a = k == 0 ? b : c;
      const int lo = range[2 * k];
      const int hi = range[2 * k + 1];
      const float x = std::min(std::max(q[a], static_cast<float>(lo)), static_cast<float>(hi));
      i0[a] = std::min(static_cast<int>(x), std::max(hi - 1, lo));
      f[a] = hi > lo ? x - static_cast<float>(i0[a]) : 0.0f;
    }
    const vtkIdType db = range[1] > range[0] ? this->TargetStride[b] : 0;
    const vtkIdType dc = range[3] > range[2] ? this->TargetStride[c] : 0;
    const vtkIdType base =
      i0[0] * this->TargetStride[0] + i0[1] * this->TargetStride[1] + i0[2] * this->TargetStride[2];
    auto value = [&](vtkIdType p) { return this->Target[p * this->Channels + this->Channel]; };
    const float v00 = value(base);
    const float v10 = value(base + db);
    const float v01 = value(base + dc);
    const float v11 = value(base + db + dc);
    return (1.0f - f[c]) * ((1.0f - f[b]) * v00 + f[b] * v10) +
      f[c] * ((1.0f - f[b]) * v01 + f[b] * v11);
  }

  // mmvMarchTransmittance.
  float March(const glm::vec3& start, float end, float startValue, float transmittance) const
  {
    const float h = this->In.StepLength;
    const int steps = static_cast<int>(std::floor(end / h + StepTolerance));
    float previous = startValue;
    for (int n = 1; n <= steps; ++n)
    {
      if (transmittance < MinTransmittance)
      {
        return transmittance;
      }
      const float next = this->SampleScalar(start + (static_cast<float>(n) * h) * this->Direction);
      transmittance *= 1.0f - this->ShadowOpacity(previous, next);
      previous = next;
    }
    const float rest = end - static_cast<float>(steps) * h;
    if (rest > RestTolerance * h && transmittance >= MinTransmittance)
    {
      const float next = this->SampleScalar(start + end * this->Direction);
      const float alpha = this->ShadowOpacity(previous, next);
      transmittance *= std::pow(std::max(0.0f, 1.0f - alpha), rest / h);
    }
    return transmittance;
  }

  glm::vec3 Start(const int v[3]) const
  {
    return glm::vec3(v[0], v[1], v[2]) * this->In.TargetToIndex;
  }

  bool IsEmpty(const int v[3]) const
  {
    const vtkIdType p = v[0] + v[1] * this->TargetStride[1] + v[2] * this->TargetStride[2];
    return this->In.Strided ? this->In.Needed[p] == 0 : this->In.Classes[p] < 0.0f;
  }

  float StartValue(const int v[3], const glm::vec3& start) const
  {
    return this->In.Strided
      ? this->SampleScalar(start)
      : this->In.Scalars[v[0] + v[1] * this->ScalarStride[1] + v[2] * this->ScalarStride[2]];
  }

  // The shader's main for one point, given the chunk's plane (-1: none) and
  // read range.
  float Point(const int v[3], int plane, const int range[4]) const
  {
    const glm::vec3 start = this->Start(v);
    float exitDistance = this->ExitDistance(start);
    float far = 1.0f;
    float distance;
    const float planeCoord =
      plane < 0 ? -1.0f : static_cast<float>(plane) * this->In.TargetToIndex[this->Axis];
    if (range[0] <= range[1] && range[2] <= range[3] &&
      ReachesPlane(
        start[this->Axis], this->Direction[this->Axis], planeCoord, exitDistance, distance))
    {
      exitDistance = distance;
      far = this->SampleSlice(
        plane, (start + distance * this->Direction) / this->In.TargetToIndex, range);
    }
    return this->March(start, exitDistance, this->StartValue(v, start), far);
  }

  // The points of one row that march together (Row).
  struct Run
  {
    int RowAxis = 0;
    int First = 0; // the run's points along RowAxis
    int Last = -1;
    glm::vec3 RowStart{ 0.0f }; // the row's start, at its first point
    bool PlaneRead = false;     // the rays end on the chunk's plane
    float End = 0.0f;           // where each of them ends
    int Steps = 0;
    bool RestSampled = false;
    bool Shared = false; // the weight along the row is the row's as well
    int Ratio = 1;       // irradiance points per light grid point along the row
  };

  // Step n's offset from a point (n = Steps + 1: the end).
  glm::vec3 Offset(const Run& run, int n) const
  {
    return n <= run.Steps ? (static_cast<float>(n) * this->In.StepLength) * this->Direction
                          : run.End * this->Direction;
  }

  void Write(const int v[3], float value) const
  {
    const vtkIdType p = v[0] + v[1] * this->TargetStride[1] + v[2] * this->TargetStride[2];
    this->Target[p * this->Channels + this->Channel] = value;
  }

  void Row(int rowAxis, int v[3], int first, int last, int plane, int readSlice, const int range[4],
    std::vector<float>& scratch) const;
  Run PlanRun(int rowAxis, int v[3], int lo, int hi, int plane, const int range[4]) const;
  void SampleRun(
    const Run& run, const float* startAlong, const glm::vec3& offset, float* out) const;
  void MarchRun(const Run& run, int v[3], int plane, const int range[4], bool skip,
    std::vector<float>& scratch) const;

  const SweptTransmittanceInputs& In;
  const glm::vec3 Direction; // toward the light, irradiance index per world unit
  const int Axis;
  float* Target;
  const int Channels;
  const int Channel;
  vtkIdType ScalarStride[3];
  vtkIdType TargetStride[3];
  float ClearBelow;
};

//------------------------------------------------------------------------------
// The points [first, last] along rowAxis of the row through v: the empty
// ones at its ends get 0 (off a read slice), the run marches together, the
// others point by point.
void Sweeper::Row(int rowAxis, int v[3], int first, int last, int plane, int readSlice,
  const int range[4], std::vector<float>& scratch) const
{
  const bool skip = this->In.SkipEmpty && v[this->Axis] != readSlice;
  int lo = first;
  int hi = last;
  if (skip)
  {
    while (lo <= hi && (v[rowAxis] = lo, this->IsEmpty(v)))
    {
      this->Write(v, 0.0f);
      ++lo;
    }
    while (hi >= lo && (v[rowAxis] = hi, this->IsEmpty(v)))
    {
      this->Write(v, 0.0f);
      --hi;
    }
  }
  if (lo > hi)
  {
    return;
  }
  const Run run = this->PlanRun(rowAxis, v, lo, hi, plane, range);
  for (int x = lo; x <= hi; ++x)
  {
    if (x == run.First && run.First <= run.Last)
    {
      x = run.Last;
      continue;
    }
    v[rowAxis] = x;
    this->Write(v, skip && this->IsEmpty(v) ? 0.0f : this->Point(v, plane, range));
  }
  if (run.First <= run.Last)
  {
    this->MarchRun(run, v, plane, range, skip, scratch);
  }
}

//------------------------------------------------------------------------------
// The run of the points [lo, hi] of the row through v: those whose rays end
// at the same distance, computed as each point computes it (all that reach
// the chunk's plane, or, in the first chunk, all that leave through the
// sweep's far face; contiguous, as the exit along the row is monotonic in
// the point); where the weight along the row is shared, only those whose
// samples' texels along the row all lie in it (no clamp).
Sweeper::Run Sweeper::PlanRun(
  int rowAxis, int v[3], int lo, int hi, int plane, const int range[4]) const
{
  const int axis = this->Axis;
  const glm::vec3 dir = this->Direction;
  Run run;
  run.RowAxis = rowAxis;
  v[rowAxis] = lo;
  run.RowStart = this->Start(v);
  run.PlaneRead = plane >= 0 && range[0] <= range[1] && range[2] <= range[3];
  const float planeCoord = static_cast<float>(plane) * this->In.TargetToIndex[axis];
  if (run.PlaneRead)
  {
    run.End = (planeCoord - run.RowStart[axis]) / dir[axis];
  }
  else
  {
    run.End = std::max(0.0f,
      dir[axis] > 0.0f
        ? (static_cast<float>(this->In.Dimensions[axis] - 1) - run.RowStart[axis]) / dir[axis]
        : -run.RowStart[axis] / dir[axis]);
  }
  auto inRun = [&](int x)
  {
    v[rowAxis] = x;
    const glm::vec3 start = this->Start(v);
    const float exitDistance = this->ExitDistance(start);
    float distance;
    return run.PlaneRead
      ? ReachesPlane(start[axis], dir[axis], planeCoord, exitDistance, distance) &&
        distance == run.End
      : exitDistance == run.End;
  };
  run.First = lo;
  while (run.First <= hi && !inRun(run.First))
  {
    ++run.First;
  }
  run.Last = hi;
  while (run.Last >= run.First && !inRun(run.Last))
  {
    --run.Last;
  }
  const float h = this->In.StepLength;
  run.Steps = static_cast<int>(std::floor(run.End / h + StepTolerance));
  run.RestSampled = run.End - static_cast<float>(run.Steps) * h > RestTolerance * h;
  const float toIndexAlong = this->In.TargetToIndex[rowAxis];
  run.Ratio = static_cast<int>(toIndexAlong);
  run.Shared = toIndexAlong >= 1.0f && static_cast<float>(run.Ratio) == toIndexAlong;
  if (run.Shared && run.First <= run.Last)
  {
    double lowest = 0.0;
    double highest = 0.0;
    for (int n = 1; n <= run.Steps + (run.RestSampled ? 1 : 0); ++n)
    {
      const double below = std::floor(this->Offset(run, n)[rowAxis]);
      lowest = std::min(lowest, below);
      highest = std::max(highest, below);
    }
    const int lastAlong = this->In.Dimensions[rowAxis] - 1;
    run.First = std::max(run.First, static_cast<int>(std::ceil(-lowest / run.Ratio)));
    run.Last =
      std::min(run.Last, static_cast<int>(std::floor((lastAlong - 1 - highest) / run.Ratio)));
  }
  return run;
}

//------------------------------------------------------------------------------
// The run's values at `offset` from each of its points (startAlong: their
// starts along the row): across the row and along the sweep the row's
// weights; along it the row's too where shared, else each point's own.
void Sweeper::SampleRun(
  const Run& run, const float* startAlong, const glm::vec3& offset, float* out) const
{
  const int rowAxis = run.RowAxis;
  const int c = 3 - this->Axis - rowAxis;
  int lo[2];
  int hi[2];
  float f[2];
  const int axes[2] = { c, this->Axis };
  for (int k = 0; k < 2; ++k)
  {
    Texels(
      run.RowStart[axes[k]] + offset[axes[k]], this->In.Dimensions[axes[k]], lo[k], hi[k], f[k]);
  }
  const vtkIdType* stride = this->ScalarStride;
  auto row = [&](int i, int k)
  { return this->In.Scalars + i * stride[c] + k * stride[this->Axis]; };
  const float* p00 = row(lo[0], lo[1]);
  const float* p10 = row(hi[0], lo[1]);
  const float* p01 = row(lo[0], hi[1]);
  const float* p11 = row(hi[0], hi[1]);
  const int count = run.Last - run.First + 1;
  const vtkIdType along = stride[rowAxis];
  const float o = offset[rowAxis];
  if (run.Shared)
  {
    const float below = std::floor(o);
    const float w = o - below;
    const vtkIdType first =
      (static_cast<vtkIdType>(run.Ratio) * run.First + static_cast<vtkIdType>(below)) * along;
    const vtkIdType step = run.Ratio * along;
    if (step == 1)
    {
      // Contiguous: vectorised.
      const float* q00 = p00 + first;
      const float* q10 = p10 + first;
      const float* q01 = p01 + first;
      const float* q11 = p11 + first;
      for (int i = 0; i < count; ++i)
      {
        out[i] = Trilinear(q00, q10, q01, q11, i, i + 1, w, f[0], f[1]);
      }
      return;
    }
    for (int i = 0; i < count; ++i)
    {
      const vtkIdType a0 = first + i * step;
      out[i] = Trilinear(p00, p10, p01, p11, a0, a0 + along, w, f[0], f[1]);
    }
    return;
  }
  const int lastAlong = this->In.Dimensions[rowAxis] - 1;
  for (int i = 0; i < count; ++i)
  {
    // In the run every sample lies in the grid: truncation is the floor
    // (a rounding below 0 weights texel 0 by 1 + x, x ~ -1e-7).
    const float x = startAlong[i] + o;
    const int i0 = static_cast<int>(x);
    out[i] = Trilinear(p00, p10, p01, p11, i0 * along, std::min(i0 + 1, lastAlong) * along,
      x - static_cast<float>(i0), f[0], f[1]);
  }
}

//------------------------------------------------------------------------------
// The shader's march for every point of the run at once, then its writes.
void Sweeper::MarchRun(const Run& run, int v[3], int plane, const int range[4], bool skip,
  std::vector<float>& scratch) const
{
  const int rowAxis = run.RowAxis;
  const int count = run.Last - run.First + 1;
  scratch.resize(4 * static_cast<size_t>(count));
  float* previous = scratch.data();
  float* transmittance = previous + count;
  float* startAlong = transmittance + count;
  float* next = startAlong + count;
  for (int i = 0; i < count; ++i)
  {
    v[rowAxis] = run.First + i;
    const glm::vec3 start = this->Start(v);
    startAlong[i] = start[rowAxis];
    previous[i] = this->StartValue(v, start);
    transmittance[i] = run.PlaneRead
      ? this->SampleSlice(
          plane, (start + run.End * this->Direction) / this->In.TargetToIndex, range)
      : 1.0f;
  }
  for (int n = 1; n <= run.Steps; ++n)
  {
    this->SampleRun(run, startAlong, this->Offset(run, n), next);
    if (!MarchStepAll(count, this->In.ShadowTable, this->In.TableSize, this->ClearBelow,
          transmittance, previous, next))
    {
      break;
    }
  }
  if (run.RestSampled)
  {
    const float h = this->In.StepLength;
    const float rest = run.End - static_cast<float>(run.Steps) * h;
    this->SampleRun(run, startAlong, this->Offset(run, run.Steps + 1), next);
    for (int i = 0; i < count; ++i)
    {
      // In the clear corner alpha is 0 and the power 1, exactly: no pow.
      if (transmittance[i] >= MinTransmittance &&
        !(previous[i] < this->ClearBelow && next[i] < this->ClearBelow))
      {
        const float alpha = this->ShadowOpacity(previous[i], next[i]);
        transmittance[i] *= std::pow(std::max(0.0f, 1.0f - alpha), rest / h);
      }
    }
  }
  for (int i = 0; i < count; ++i)
  {
    v[rowAxis] = run.First + i;
    this->Write(v, skip && this->IsEmpty(v) ? 0.0f : transmittance[i]);
  }
}

//------------------------------------------------------------------------------
vtkIdType Sweeper::Chunk(const ShadowSweep& sweep, int chunk, const IndexBox& box)
{
  if (box.IsEmpty())
  {
    return 0;
  }
  int first, last, plane;
  sweep.GetChunk(chunk, first, last, plane);
  int range[4] = { 0, -1, 0, -1 }; // the first chunk reads no slice
  if (plane >= 0)
  {
    SliceReadRange(sweep, plane, this->In.TargetDimensions, range);
  }
  const int readSlice = sweep.GetReadSlice(chunk);
  // Rows along an in-slice axis: every point of a row lies on one slice.
  const int rowAxis = this->Axis == 0 ? 1 : 0;
  const int c = 3 - this->Axis - rowAxis;
  const int* b = box.Bounds;
  const vtkIdType across = b[2 * c + 1] - b[2 * c] + 1;
  const vtkIdType rows = across * (b[2 * this->Axis + 1] - b[2 * this->Axis] + 1);
  mmv::For(0, rows,
    [&](vtkIdType begin, vtkIdType end)
    {
      // Per thread, kept: an update sweeps thousands of row blocks, and
      // allocating for each would churn the heap.
      thread_local std::vector<float> scratch;
      for (vtkIdType r = begin; r < end; ++r)
      {
        int v[3];
        v[c] = b[2 * c] + static_cast<int>(r % across);
        v[this->Axis] = b[2 * this->Axis] + static_cast<int>(r / across);
        v[rowAxis] = b[2 * rowAxis];
        this->Row(rowAxis, v, b[2 * rowAxis], b[2 * rowAxis + 1], plane, readSlice, range, scratch);
      }
    });
  return box.GetNumberOfVoxels();
}

} // namespace

//------------------------------------------------------------------------------
vtkIdType SweepTransmittanceOnCPU(const SweptTransmittanceInputs& inputs, const glm::vec3& toLight,
  const ShadowSweep& sweep, const std::vector<IndexBox>& boxes, float* target, int channels,
  int channel)
{
  Sweeper sweeper(inputs, toLight, sweep, target, channels, channel);
  vtkIdType points = 0;
  for (int chunk = 0; chunk < sweep.GetNumberOfChunks() && chunk < static_cast<int>(boxes.size());
       ++chunk)
  {
    points += sweeper.Chunk(sweep, chunk, boxes[chunk]);
  }
  return points;
}

} // namespace mmv
