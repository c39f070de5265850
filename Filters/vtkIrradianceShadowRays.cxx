#include "vtkIrradianceShadowRays.h"

#include "vtkAlgorithm.h"
#include "vtkMultiMaterialParameters.h"
#include "vtkMultiMaterialThreads.h" // mmv::For
#include "vtkPreIntegrationTable.h"
#include "vtkSMPTools.h"
#include "vtkShadowSweep.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

namespace mmv
{
namespace shadowrays
{
namespace
{
/// Shadow-ray work is split into this many chunks per light, so progress and
/// AbortExecute are handled on the calling thread between chunks.
constexpr int ChunksPerLight = 20;

/// Distance along index-space direction `d` from `p` (inside) to the grid's box.
double ExitDistance(const mmv::IrradianceGrid& grid, const glm::dvec3& p, const glm::dvec3& d)
{
  double t = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a)
  {
    if (d[a] > 0.0)
    {
      t = std::min(t, (grid.Dimensions[a] - 1 - p[a]) / d[a]);
    }
    else if (d[a] < 0.0)
    {
      t = std::min(t, -p[a] / d[a]);
    }
  }
  return std::max(t, 0.0);
}

/// The march of MarchTransmittance and MarchTint, for a grey (double) or a
/// per-channel (glm::dvec3) transmittance T: `opacity(t1, t2)` is a
/// segment's opacity, Largest(T) decides the early stop. One loop, so the
/// grey and the tinted shadows step alike (the GLSL has the two as
/// mmvMarchTransmittance and mmvMarchTint: no templates there).
inline double Largest(double t)
{
  return t;
}
inline double Largest(const glm::dvec3& t)
{
  return std::max({ t.r, t.g, t.b });
}

template <typename T, typename Opacity>
T March(const RayContext& ctx, const glm::dvec3& start, const glm::dvec3& indexDir, double end,
  double startValue, T transmittance, const Opacity& opacity)
{
  const mmv::IrradianceGrid& grid = *ctx.Irradiance;
  const double h = ctx.Step;
  const vtkIdType steps = static_cast<vtkIdType>(std::floor(end / h + mmv::ShadowStepTolerance));
  // A segment's opacity, 0 where its midpoint is cut away.
  const auto alphaAt = [&](double t1, double t2, const glm::dvec3& middle)
  { return mmv::mmvIsCut(ctx.Cut, middle) ? T(0.0) : opacity(t1, t2); };
  double previous = startValue;
  for (vtkIdType n = 1; n <= steps; ++n)
  {
    if (Largest(transmittance) < mmv::MinShadowTransmittance)
    {
      return transmittance;
    }
    const double next =
      mmv::SampleTrilinear(grid, ctx.Prefiltered, start + (static_cast<double>(n) * h) * indexDir);
    transmittance *=
      1.0 - alphaAt(previous, next, start + ((static_cast<double>(n) - 0.5) * h) * indexDir);
    previous = next;
  }
  const double rest = end - static_cast<double>(steps) * h;
  if (rest > mmv::ShadowRestTolerance * h && Largest(transmittance) >= mmv::MinShadowTransmittance)
  {
    const double next = mmv::SampleTrilinear(grid, ctx.Prefiltered, start + end * indexDir);
    const T alpha =
      alphaAt(previous, next, start + (0.5 * (static_cast<double>(steps) * h + end)) * indexDir);
    // Optical depth is linear in the segment length for a linear value ramp.
    transmittance *= glm::pow(glm::max(T(0.0), 1.0 - alpha), T(rest / h));
  }
  return transmittance;
}

/**
 * Transmittance over [0, end] (world units) of the ray from index `start`
 * along index-space direction `indexDir` (eqs. 9-10), by pre-integrated
 * segments of length Step and one shorter final segment that ends exactly at
 * `end`, starting from `transmittance` (what lies beyond `end`) so that early
 * termination sees the whole product.
 */
double MarchTransmittance(const RayContext& ctx, const glm::dvec3& start,
  const glm::dvec3& indexDir, double end, double startValue, double transmittance)
{
  return March(ctx, start, indexDir, end, startValue, transmittance,
    [&](double t1, double t2) { return ctx.Table->LookupShadowOpacity(t1, t2); });
}

/// The ray from index `start` (physical point `x`) toward the light: its
/// index-space direction per world unit, and how far it runs, to the volume
/// boundary or the light.
double RayToLight(const RayContext& ctx, const mmv::LightSource& light, const glm::dvec3& start,
  const glm::dvec3& x, glm::dvec3& indexDir)
{
  double lightDistance = 0.0;
  indexDir = ctx.PhysicalToIndex * mmv::mmvDirectionToLight(light, x, lightDistance);
  const double exit = ExitDistance(*ctx.Irradiance, start, indexDir);
  return lightDistance >= 0.0 ? std::min(exit, lightDistance) : exit;
}

/// Transmittance from irradiance voxel `v` toward the light: a full shadow
/// ray, to the volume boundary (or the light).
double ShadowTransmittance(const RayContext& ctx, const mmv::LightSource& light, vtkIdType v)
{
  const mmv::IrradianceGrid& grid = *ctx.Irradiance;
  const glm::dvec3 start = grid.IndexOfVoxel(v);
  glm::dvec3 indexDir;
  const double end = RayToLight(ctx, light, start, grid.IndexToPhysical(start), indexDir);
  return MarchTransmittance(ctx, start, indexDir, end, ctx.Prefiltered[v], 1.0);
}

/**
 * The tint K (mmv::TintResolutionDivisor's comment): per channel, the
 * transmittance of the selective extinction c_t mu (-ln T) over [0, end],
 * marched as MarchTransmittance (same steps, same cutaway) with the tint
 * table; stops once every channel is below mmv::MinShadowTransmittance.
 * Mirrors mmvMarchTint of Shaders/mmvShadowRay.glsl.
 */
glm::dvec3 MarchTint(const RayContext& ctx, const glm::dvec3& start, const glm::dvec3& indexDir,
  double end, double startValue)
{
  return March(ctx, start, indexDir, end, startValue, glm::dvec3(1.0),
    [&](double t1, double t2)
    {
      double rgb[3] = { 0.0, 0.0, 0.0 };
      ctx.Table->LookupShadowTint(t1, t2, rgb);
      return glm::dvec3(rgb[0], rgb[1], rgb[2]);
    });
}

/// The grid of the tint: every `divisor`-th point of `grid` (end points shared).
mmv::IrradianceGrid MakeTintGrid(const mmv::IrradianceGrid& grid, int divisor)
{
  mmv::IrradianceGrid tint = grid;
  for (int a = 0; a < 3; ++a)
  {
    tint.Dimensions[a] = mmv::TintDimension(grid.Dimensions[a], divisor);
    if (tint.Dimensions[a] > 1)
    {
      tint.Spacing[a] =
        grid.Spacing[a] * (grid.Dimensions[a] - 1) / static_cast<double>(tint.Dimensions[a] - 1);
    }
  }
  return tint;
}

/// Bilinear value of `values` in slice `plane` of axis `axis` at the in-slice
/// coordinates of index `q`, clamped to the part of the slice in `range`
/// (mmv::SliceReadRange). Not mmv::SampleTrilinear: that also reads the next
/// slice (with weight 0), which this chunk's threads may be writing.
double SampleSlice(const int dims[3], const float* values, int axis, int plane, const int range[4],
  const glm::dvec3& q)
{
  const int b = (axis + 1) % 3;
  const int c = (axis + 2) % 3;
  int i0[3];
  double f[3];
  int step[3] = { 0, 0, 0 };
  for (int k = 0; k < 2; ++k)
  {
    const int a = k == 0 ? b : c;
    const int lo = range[2 * k];
    const int hi = range[2 * k + 1];
    const double x = std::min(std::max(q[a], static_cast<double>(lo)), static_cast<double>(hi));
    i0[a] = std::min(static_cast<int>(x), std::max(hi - 1, lo));
    f[a] = hi > lo ? x - i0[a] : 0.0;
    step[a] = hi > lo ? 1 : 0;
  }
  const vtkIdType stride[3] = { 1, dims[0], static_cast<vtkIdType>(dims[0]) * dims[1] };
  const vtkIdType base = plane * stride[axis] + i0[b] * stride[b] + i0[c] * stride[c];
  const vtkIdType db = step[b] * stride[b];
  const vtkIdType dc = step[c] * stride[c];
  return (1.0 - f[c]) * ((1.0 - f[b]) * values[base] + f[b] * values[base + db]) +
    f[c] * ((1.0 - f[b]) * values[base + dc] + f[b] * values[base + db + dc]);
}
} // namespace

void ComputeTint(
  const RayContext& ctx, const mmv::LightSource& light, int divisor, float* out, vtkIdType& rays)
{
  const mmv::IrradianceGrid& grid = *ctx.Irradiance;
  const mmv::IrradianceGrid tintGrid = MakeTintGrid(grid, divisor);
  const vtkIdType n = tintGrid.GetNumberOfVoxels();
  std::vector<float> channels[3];
  for (auto& channel : channels)
  {
    channel.assign(static_cast<std::size_t>(n), 1.0f);
  }
  mmv::For(0, n,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType t = begin; t < end; ++t)
      {
        const glm::dvec3 x = tintGrid.IndexToPhysical(tintGrid.IndexOfVoxel(t));
        const glm::dvec3 start = grid.PhysicalToIndex(x);
        glm::dvec3 indexDir;
        const double exit = RayToLight(ctx, light, start, x, indexDir);
        const glm::dvec3 k =
          MarchTint(ctx, start, indexDir, exit, mmv::SampleTrilinear(grid, ctx.Prefiltered, start));
        for (int c = 0; c < 3; ++c)
        {
          channels[c][t] = static_cast<float>(k[c]);
        }
      }
    });
  rays += n;
  const glm::dmat3 toTint = tintGrid.PhysicalToIndexMatrix() * grid.IndexToPhysicalMatrix();
  mmv::For(0, grid.GetNumberOfVoxels(),
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType v = begin; v < end; ++v)
      {
        const glm::dvec3 index = toTint * grid.IndexOfVoxel(v);
        for (int c = 0; c < 3; ++c)
        {
          out[3 * v + c] =
            static_cast<float>(mmv::SampleTrilinear(tintGrid, channels[c].data(), index));
        }
      }
    });
}

bool SweepPiecewiseShadowRays(vtkAlgorithm* self, const RayContext& ctx,
  const mmv::LightSource& light, const mmv::ShadowSweep& sweep,
  const std::vector<unsigned char>& nonEmpty, double progress, double progressSpan,
  std::vector<float>& transmittance, vtkIdType& rays)
{
  const mmv::IrradianceGrid& grid = *ctx.Irradiance;
  const int* dims = grid.Dimensions;
  const bool point = light.Kind != mmv::DirectionalLight;
  transmittance.resize(grid.GetNumberOfVoxels(), 0.0f);
  const int a = sweep.Axis;
  const int b = (a + 1) % 3;
  const int c = (a + 2) % 3;
  const vtkIdType stride[3] = { 1, dims[0], static_cast<vtkIdType>(dims[0]) * dims[1] };
  std::atomic<vtkIdType> cast{ 0 };
  const int chunks = sweep.GetNumberOfChunks();
  for (int chunk = 0; chunk < chunks; ++chunk)
  {
    int first, last, plane;
    sweep.GetChunk(chunk, first, last, plane);
    const int read = sweep.GetReadSlice(chunk);
    int range[4];
    const bool reads = plane >= 0 && mmv::SliceReadRange(sweep, plane, dims, range);
    const vtkIdType sliceSize = static_cast<vtkIdType>(dims[b]) * dims[c];
    mmv::For(0, sliceSize * (last - first + 1),
      [&](vtkIdType begin, vtkIdType end)
      {
        vtkIdType local = 0;
        for (vtkIdType n = begin; n < end; ++n)
        {
          const int slice = first + static_cast<int>(n / sliceSize);
          const vtkIdType v =
            slice * stride[a] + (n % dims[b]) * stride[b] + ((n % sliceSize) / dims[b]) * stride[c];
          const glm::dvec3 start = grid.IndexOfVoxel(v);
          if (sweep.Pyramid && !mmv::InSweptPyramid(sweep, glm::vec3(start)))
          {
            continue; // another pyramid's
          }
          const glm::dvec3 x = grid.IndexToPhysical(start);
          // Outside a spot light's cone a voxel's own value is 0.
          const bool unlit = point && mmv::mmvLightGeometryTerm(light, x) <= 0.0;
          if ((!nonEmpty[v] || unlit) && slice != read)
          {
            continue;
          }
          ++local;
          glm::dvec3 indexDir;
          double exit = RayToLight(ctx, light, start, x, indexDir);
          double far = 1.0;
          double distance = 0.0;
          if (reads && mmv::ReachesSweepPlane(start[a], indexDir[a], plane, exit, distance))
          {
            exit = distance;
            far =
              SampleSlice(dims, transmittance.data(), a, plane, range, start + distance * indexDir);
          }
          transmittance[v] = static_cast<float>(
            MarchTransmittance(ctx, start, indexDir, exit, ctx.Prefiltered[v], far));
        }
        cast += local;
      });
    rays += cast.exchange(0);
    self->UpdateProgress(progress + progressSpan * (chunk + 1) / chunks);
    if (self->GetAbortExecute())
    {
      return false;
    }
  }
  return true;
}

bool CastShadowRays(vtkAlgorithm* self, const RayContext& ctx, const mmv::LightSource& light,
  const std::vector<vtkIdType>& computed, float* irradiance, double progress, double progressSpan,
  vtkIdType& rays)
{
  const mmv::IrradianceGrid& grid = *ctx.Irradiance;
  const vtkIdType n = static_cast<vtkIdType>(computed.size());
  std::atomic<vtkIdType> cast{ 0 };
  for (int chunk = 0; chunk < ChunksPerLight; ++chunk)
  {
    const vtkIdType first = n * chunk / ChunksPerLight;
    const vtkIdType last = n * (chunk + 1) / ChunksPerLight;
    mmv::For(first, last,
      [&](vtkIdType begin, vtkIdType end)
      {
        vtkIdType local = 0;
        for (vtkIdType c = begin; c < end; ++c)
        {
          const vtkIdType v = computed[c];
          const double geometry =
            mmv::mmvLightGeometryTerm(light, grid.IndexToPhysical(grid.IndexOfVoxel(v)));
          if (geometry > 0.0) // outside a spot light's cone: no ray
          {
            irradiance[v] = static_cast<float>(geometry * ShadowTransmittance(ctx, light, v));
            ++local;
          }
        }
        cast += local;
      });
    rays += cast.exchange(0);
    self->UpdateProgress(progress + progressSpan * (chunk + 1) / ChunksPerLight);
    if (self->GetAbortExecute())
    {
      return false;
    }
  }
  return true;
}
}
}
