#include "vtkIrradianceVolumeFilter.h"

#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIrradianceDiffusion.h"
#include "vtkIrradianceGrid.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMultiMaterialLightModel.h"
#include "vtkMultiMaterialCutaway.h"
#include "vtkPlane.h"
#include "vtkPlaneCollection.h"
#include "vtkVolumeMapper.h"
#include "vtkMultiMaterialLights.h"
#include "vtkMultiMaterialParameters.h"
#include "vtkObjectFactory.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPreIntegrationTable.h"
#include "vtkSMPTools.h"
#include "vtkShadowSweep.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkVolumeInputScalars.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

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

/// Origin, spacing and direction of `grid` in VTK's row-major form.
struct GridGeometry
{
  double Origin[3];
  double Spacing[3];
  double Direction[9];
  explicit GridGeometry(const mmv::IrradianceGrid& grid)
  {
    for (int a = 0; a < 3; ++a)
    {
      this->Origin[a] = grid.Origin[a];
      this->Spacing[a] = grid.Spacing[a];
      for (int r = 0; r < 3; ++r)
      {
        this->Direction[3 * r + a] = grid.Direction[a][r]; // glm: [column][row]
      }
    }
  }
};

/// The output's geometry, in the pipeline information and on the data.
void SetGridGeometry(const mmv::IrradianceGrid& grid, vtkInformation* info)
{
  const GridGeometry g(grid);
  info->Set(vtkDataObject::ORIGIN(), g.Origin, 3);
  info->Set(vtkDataObject::SPACING(), g.Spacing, 3);
  info->Set(vtkDataObject::DIRECTION(), g.Direction, 9);
}

void SetGridGeometry(const mmv::IrradianceGrid& grid, vtkImageData* image)
{
  const GridGeometry g(grid);
  image->SetOrigin(g.Origin);
  image->SetSpacing(g.Spacing);
  image->SetDirectionMatrix(g.Direction);
}

/// What the shadow rays of one light need.
struct LightTask
{
  mmv::LightSource Source;
  bool Active = false;
};

/// Shared with the GPU mapper, so both see the same lights.
LightTask MakeLightTask(vtkLight* light, double radius, std::vector<std::string>& problems)
{
  LightTask task;
  task.Active = mmv::IsLightActive(light);
  task.Source = mmv::MakeLightSource(light, nullptr, radius, task.Active ? &problems : nullptr);
  return task;
}

/// Voxels whose pre-filtered value has a non-zero opacity, in index order.
std::vector<vtkIdType> FindComputedVoxels(vtkPiecewiseFunction* otf,
  const std::vector<float>& prefiltered, std::vector<unsigned char>& nonEmpty)
{
  nonEmpty.assign(prefiltered.size(), 0);
  std::vector<vtkIdType> computed;
  // Serial: vtkPiecewiseFunction::GetValue is not const.
  for (size_t v = 0; v < prefiltered.size(); ++v)
  {
    if (otf->GetValue(prefiltered[v]) > 0.0)
    {
      nonEmpty[v] = 1;
      computed.push_back(static_cast<vtkIdType>(v));
    }
  }
  return computed;
}

/// One task and one zeroed "Irradiance_<k>" array per light, in order.
void MakeLightTasks(vtkLightCollection* lights, double radius, vtkIdType size,
  std::vector<LightTask>& tasks, std::vector<vtkSmartPointer<vtkFloatArray>>& arrays,
  std::vector<std::string>& problems)
{
  vtkCollectionSimpleIterator it;
  lights->InitTraversal(it);
  while (vtkLight* light = lights->GetNextLight(it))
  {
    tasks.push_back(MakeLightTask(light, radius, problems));
    vtkNew<vtkFloatArray> array;
    array->SetName(("Irradiance_" + std::to_string(arrays.size())).c_str());
    array->SetNumberOfTuples(size);
    std::fill_n(array->GetPointer(0), size, 0.0f);
    arrays.emplace_back(array);
  }
}

/// Everything the shadow rays read; shared by all threads, read-only.
struct RayContext
{
  const mmv::IrradianceGrid* Irradiance;
  const float* Prefiltered;
  const vtkPreIntegrationTable* Table;
  double Step;
  glm::dmat3 PhysicalToIndex; // of *Irradiance, inverted once
  mmv::IndexCutaway Cut;      // removed by cropping and clipping: empty
};

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
  const auto alphaAt = [&](double t1, double t2, const glm::dvec3& middle) {
    return mmv::mmvIsCut(ctx.Cut, middle) ? T(0.0) : opacity(t1, t2);
  };
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

/// Transmittance from irradiance voxel `v` toward the light: a full shadow
/// ray, to the volume boundary (or the light).
double ShadowTransmittance(const RayContext& ctx, const mmv::LightSource& light, vtkIdType v)
{
  const mmv::IrradianceGrid& grid = *ctx.Irradiance;
  const glm::dvec3 start = grid.IndexOfVoxel(v);
  const glm::dvec3 x = grid.IndexToPhysical(start);
  double lightDistance = 0.0;
  const glm::dvec3 dir = mmv::mmvDirectionToLight(light, x, lightDistance);
  const glm::dvec3 indexDir = ctx.PhysicalToIndex * dir;
  double end = ExitDistance(grid, start, indexDir);
  if (lightDistance >= 0.0)
  {
    end = std::min(end, lightDistance);
  }
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
  return March(ctx, start, indexDir, end, startValue, glm::dvec3(1.0), [&](double t1, double t2) {
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

/**
 * The tint of one light at every voxel of the tint grid (full shadow rays
 * through the irradiance grid's pre-filtered values), interpolated
 * trilinearly to the irradiance grid: 3 components per irradiance voxel,
 * what the ray cast reads from its tint texture.
 */
void ComputeTint(const RayContext& ctx, const mmv::LightSource& light, int divisor, float* out,
  vtkIdType& rays)
{
  const mmv::IrradianceGrid& grid = *ctx.Irradiance;
  const mmv::IrradianceGrid tintGrid = MakeTintGrid(grid, divisor);
  const vtkIdType n = tintGrid.GetNumberOfVoxels();
  std::vector<float> channels[3];
  for (auto& channel : channels)
  {
    channel.assign(static_cast<std::size_t>(n), 1.0f);
  }
  vtkSMPTools::For(0, n, [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType t = begin; t < end; ++t)
    {
      const glm::dvec3 x = tintGrid.IndexToPhysical(tintGrid.IndexOfVoxel(t));
      const glm::dvec3 start = grid.PhysicalToIndex(x);
      double lightDistance = 0.0;
      const glm::dvec3 indexDir = ctx.PhysicalToIndex * mmv::mmvDirectionToLight(light, x, lightDistance);
      double exit = ExitDistance(grid, start, indexDir);
      if (lightDistance >= 0.0)
      {
        exit = std::min(exit, lightDistance);
      }
      const glm::dvec3 k = MarchTint(
        ctx, start, indexDir, exit, mmv::SampleTrilinear(grid, ctx.Prefiltered, start));
      for (int c = 0; c < 3; ++c)
      {
        channels[c][t] = static_cast<float>(k[c]);
      }
    }
  });
  rays += n;
  const glm::dmat3 toTint = tintGrid.PhysicalToIndexMatrix() * grid.IndexToPhysicalMatrix();
  vtkSMPTools::For(0, grid.GetNumberOfVoxels(), [&](vtkIdType begin, vtkIdType end) {
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

/// Bilinear value of `values` in slice `plane` of axis `axis` at the in-slice
/// coordinates of index `q` (clamped to the slice). Not mmv::SampleTrilinear:
/// that also reads the next slice (with weight 0), which this chunk's
/// threads may be writing.
double SampleSlice(const int dims[3], const float* values, int axis, int plane, const glm::dvec3& q)
{
  const int b = (axis + 1) % 3;
  const int c = (axis + 2) % 3;
  int i0[3];
  double f[3];
  for (const int a : { b, c })
  {
    const double x = std::min(std::max(q[a], 0.0), static_cast<double>(dims[a] - 1));
    i0[a] = std::min(static_cast<int>(x), std::max(dims[a] - 2, 0));
    f[a] = dims[a] > 1 ? x - i0[a] : 0.0;
  }
  const vtkIdType stride[3] = { 1, dims[0], static_cast<vtkIdType>(dims[0]) * dims[1] };
  const vtkIdType base = plane * stride[axis] + i0[b] * stride[b] + i0[c] * stride[c];
  const vtkIdType db = dims[b] > 1 ? stride[b] : 0;
  const vtkIdType dc = dims[c] > 1 ? stride[c] : 0;
  return (1.0 - f[c]) * ((1.0 - f[b]) * values[base] + f[b] * values[base + db]) +
    f[c] * ((1.0 - f[b]) * values[base + dc] + f[b] * values[base + db + dc]);
}

/**
 * Piecewise shadow rays of directional light `light` (vtkShadowSweep.h) into
 * `transmittance`, one value per voxel of the grid: the non-empty ones, and
 * the empty ones on the slices a later chunk reads (the rest stay 0).
 * Progress and AbortExecute are handled between chunks; returns false when
 * aborted. Adds the rays cast to `rays`.
 */
bool SweepPiecewiseShadowRays(vtkAlgorithm* self, const RayContext& ctx,
  const mmv::LightSource& light, int slicesPerChunk, const std::vector<unsigned char>& nonEmpty,
  double progress, double progressSpan, std::vector<float>& transmittance, vtkIdType& rays)
{
  const mmv::IrradianceGrid& grid = *ctx.Irradiance;
  const int* dims = grid.Dimensions;
  const glm::dvec3 indexDir = ctx.PhysicalToIndex * light.ToLight;
  const mmv::ShadowSweep sweep = mmv::PlanShadowSweep(dims, indexDir, slicesPerChunk);
  transmittance.assign(grid.GetNumberOfVoxels(), 0.0f);
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
    const vtkIdType sliceSize = static_cast<vtkIdType>(dims[b]) * dims[c];
    vtkSMPTools::For(0, sliceSize * (last - first + 1), [&](vtkIdType begin, vtkIdType end) {
      vtkIdType local = 0;
      for (vtkIdType n = begin; n < end; ++n)
      {
        const int slice = first + static_cast<int>(n / sliceSize);
        const vtkIdType v = slice * stride[a] + (n % dims[b]) * stride[b] +
          ((n % sliceSize) / dims[b]) * stride[c];
        if (!nonEmpty[v] && slice != read)
        {
          continue;
        }
        ++local;
        const glm::dvec3 start = grid.IndexOfVoxel(v);
        double exit = ExitDistance(grid, start, indexDir);
        double far = 1.0;
        double distance = 0.0;
        if (mmv::ReachesSweepPlane(start[a], indexDir[a], plane, exit, distance))
        {
          exit = distance;
          far = SampleSlice(dims, transmittance.data(), a, plane, start + distance * indexDir);
        }
        transmittance[v] =
          static_cast<float>(MarchTransmittance(ctx, start, indexDir, exit, ctx.Prefiltered[v], far));
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

/// Empty voxels next to computed ones take the mean of those neighbours.
void FillEmptyNeighborVoxels(
  const mmv::IrradianceGrid& grid, const std::vector<unsigned char>& nonEmpty, float* values)
{
  const int* dims = grid.Dimensions;
  const vtkIdType stride[3] = { 1, dims[0], static_cast<vtkIdType>(dims[0]) * dims[1] };
  vtkSMPTools::For(0, grid.GetNumberOfVoxels(), [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType v = begin; v < end; ++v)
    {
      if (nonEmpty[v])
      {
        continue;
      }
      const glm::dvec3 index = grid.IndexOfVoxel(v);
      double sum = 0.0;
      int count = 0;
      for (int a = 0; a < 3; ++a)
      {
        // Only computed voxels are read, and those are never written here.
        if (index[a] > 0 && nonEmpty[v - stride[a]])
        {
          sum += values[v - stride[a]];
          ++count;
        }
        if (index[a] + 1 < dims[a] && nonEmpty[v + stride[a]])
        {
          sum += values[v + stride[a]];
          ++count;
        }
      }
      if (count > 0)
      {
        values[v] = static_cast<float>(sum / count);
      }
    }
  });
}

/// The shadow-opacity table for segments of length `step` over the data range.
bool PrepareTable(vtkPreIntegrationTable* table, vtkPiecewiseFunction* otf,
  vtkMaterialTransferFunction* mtf, double unitDistance, double step, vtkDataArray* scalars)
{
  double range[2];
  // Finite range: NaN/Inf voxels made the table reject the whole volume.
  scalars->GetFiniteRange(range, 0);
  if (!(range[0] < range[1]))
  {
    // A constant volume: put its value on the first table node, so lookups
    // there are exact rather than interpolated.
    range[1] = range[0] + 1.0;
  }
  table->SetScalarOpacity(otf);
  table->SetMaterialTransferFunction(mtf);
  table->SetScalarOpacityUnitDistance(unitDistance);
  table->SetStepLength(step);
  table->SetScalarRange(range);
  return table->Update();
}

/**
 * Shadow rays of one light for every computed voxel, in chunks so progress
 * and AbortExecute are handled on the calling thread. Returns false when
 * aborted.
 */
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
    vtkSMPTools::For(first, last, [&](vtkIdType begin, vtkIdType end) {
      vtkIdType local = 0;
      for (vtkIdType c = begin; c < end; ++c)
      {
        const vtkIdType v = computed[c];
        const double geometry = mmv::mmvLightGeometryTerm(light, grid.IndexToPhysical(grid.IndexOfVoxel(v)));
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

/**
 * Multiple scattering (eq. 15) of every active light's irradiance. s is the
 * material's scattering at the pre-filtered value, 0 in empty voxels, and is
 * given in data voxels^2, so the grid spacing is passed in data voxels.
 * The change is computed on the diffusion grid (DiffuseIrradianceOnDiffusionGrid),
 * as the GPU pass does. Returns the iterations (series terms or CG).
 */
int DiffuseLights(const mmv::IrradianceGrid& grid, const std::vector<float>& prefiltered,
  const std::vector<vtkIdType>& computed, vtkMaterialTransferFunction* mtf,
  const std::vector<LightTask>& tasks, const std::vector<vtkSmartPointer<vtkFloatArray>>& arrays,
  bool exponential)
{
  mmv::DiffusionSettings settings;
  settings.Exponential = exponential;
  std::vector<float> strength(grid.GetNumberOfVoxels(), 0.0f);
  bool any = false;
  for (const vtkIdType v : computed)
  {
    strength[v] = static_cast<float>(mtf
        ? mtf->EvaluateParameter(prefiltered[v], mmv::Scattering)
        : mmv::MaterialParameterTable[mmv::Scattering].Default);
    any = any || strength[v] > 0.0f;
  }
  if (!any)
  {
    return 0;
  }
  const double spacing[3] = { grid.DataVoxelsPerVoxel[0], grid.DataVoxelsPerVoxel[1],
    grid.DataVoxelsPerVoxel[2] };
  int iterations = 0;
  for (size_t l = 0; l < tasks.size(); ++l)
  {
    if (tasks[l].Active)
    {
      iterations += mmv::DiffuseIrradianceOnDiffusionGrid(
        grid.Dimensions, spacing, strength.data(), arrays[l]->GetPointer(0), settings)
                      .Iterations;
    }
  }
  return iterations;
}

/**
 * The scalars (component 0) box-filtered to the irradiance grid, non-finite
 * values replaced by the ends of the finite range as the mapper does.
 * Returns whether any were replaced.
 */
bool PrefilterFinite(vtkImageData* input, vtkDataArray* scalars, const mmv::IrradianceGrid& grid,
  std::vector<float>& prefiltered)
{
  mmv::PrefilterScalars(input, scalars, 0, grid, prefiltered);
  double finite[2];
  scalars->GetFiniteRange(finite, 0);
  return mmv::ReplaceNonFinite(
    prefiltered, static_cast<float>(finite[0]), static_cast<float>(finite[1]));
}

/**
 * The transmittance toward every active light, into its array: piecewise
 * shadow rays or one full ray per computed voxel, as `estimation` says for
 * that light. Progress runs from 0.1 to 0.9. Returns false when aborted.
 */
bool ShadowLights(vtkAlgorithm* self, const RayContext& ctx, const std::vector<LightTask>& tasks,
  const std::vector<vtkSmartPointer<vtkFloatArray>>& arrays, const std::vector<vtkIdType>& computed,
  const std::vector<unsigned char>& nonEmpty, int estimation, int slicesPerChunk, vtkIdType& rays)
{
  std::vector<float> transmittance; // reused from light to light
  for (size_t l = 0; l < tasks.size(); ++l)
  {
    if (!tasks[l].Active)
    {
      continue;
    }
    const double progress = 0.1 + 0.8 * l / tasks.size();
    const double span = 0.8 / tasks.size();
    bool finished = true;
    if (mmv::UsesPiecewiseShadowRays(estimation, tasks[l].Source))
    {
      finished = SweepPiecewiseShadowRays(self, ctx, tasks[l].Source, slicesPerChunk, nonEmpty,
        progress, span, transmittance, rays);
      float* irradiance = arrays[l]->GetPointer(0);
      for (const vtkIdType v : computed)
      {
        irradiance[v] = transmittance[v];
      }
    }
    else
    {
      finished = CastShadowRays(
        self, ctx, tasks[l].Source, computed, arrays[l]->GetPointer(0), progress, span, rays);
    }
    if (!finished)
    {
      return false;
    }
  }
  return true;
}

/// One "IrradianceTint_<k>" array per light, 3 components: white where the
/// light is off, its tint (ComputeTint) elsewhere.
std::vector<vtkSmartPointer<vtkFloatArray>> MakeTints(
  const RayContext& ctx, const std::vector<LightTask>& tasks, int divisor, vtkIdType& rays)
{
  const vtkIdType size = ctx.Irradiance->GetNumberOfVoxels();
  std::vector<vtkSmartPointer<vtkFloatArray>> tints;
  for (size_t l = 0; l < tasks.size(); ++l)
  {
    vtkNew<vtkFloatArray> tint;
    tint->SetName(("IrradianceTint_" + std::to_string(l)).c_str());
    tint->SetNumberOfComponents(3);
    tint->SetNumberOfTuples(size);
    std::fill_n(tint->GetPointer(0), 3 * size, 1.0f);
    if (tasks[l].Active)
    {
      ComputeTint(ctx, tasks[l].Source, divisor, tint->GetPointer(0), rays);
    }
    tints.emplace_back(tint);
  }
  return tints;
}

} // namespace

class vtkIrradianceVolumeFilter::vtkInternals
{
public:
  vtkSmartPointer<vtkPiecewiseFunction> Opacity;
  vtkSmartPointer<vtkMaterialTransferFunction> Material;
  vtkSmartPointer<vtkLightCollection> Lights = vtkSmartPointer<vtkLightCollection>::New();
  vtkNew<vtkPreIntegrationTable> Table;
  vtkSmartPointer<vtkPlaneCollection> ClippingPlanes;
};

vtkStandardNewMacro(vtkIrradianceVolumeFilter);

vtkIrradianceVolumeFilter::vtkIrradianceVolumeFilter()
  : Internals(new vtkInternals)
{
  this->SetNumberOfInputPorts(1);
  this->SetNumberOfOutputPorts(1);
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataSetAttributes::SCALARS);
}

vtkIrradianceVolumeFilter::~vtkIrradianceVolumeFilter()
{
  delete this->Internals;
}

void vtkIrradianceVolumeFilter::SetScalarOpacity(vtkPiecewiseFunction* otf)
{
  if (this->Internals->Opacity != otf)
  {
    this->Internals->Opacity = otf;
    this->Modified();
  }
}

vtkPiecewiseFunction* vtkIrradianceVolumeFilter::GetScalarOpacity()
{
  return this->Internals->Opacity;
}

void vtkIrradianceVolumeFilter::SetMaterialTransferFunction(vtkMaterialTransferFunction* mtf)
{
  if (this->Internals->Material != mtf)
  {
    this->Internals->Material = mtf;
    this->Modified();
  }
}

vtkMaterialTransferFunction* vtkIrradianceVolumeFilter::GetMaterialTransferFunction()
{
  return this->Internals->Material;
}

void vtkIrradianceVolumeFilter::AddLight(vtkLight* light)
{
  if (light)
  {
    this->Internals->Lights->AddItem(light);
    this->Modified();
  }
}

void vtkIrradianceVolumeFilter::RemoveAllLights()
{
  this->Internals->Lights->RemoveAllItems();
  this->Modified();
}

void vtkIrradianceVolumeFilter::SetLights(vtkLightCollection* lights)
{
  vtkSmartPointer<vtkLightCollection> next = lights;
  if (!next)
  {
    next = vtkSmartPointer<vtkLightCollection>::New();
  }
  if (next != this->Internals->Lights)
  {
    this->Internals->Lights = next;
    this->Modified();
  }
}

vtkLightCollection* vtkIrradianceVolumeFilter::GetLights()
{
  return this->Internals->Lights;
}

void vtkIrradianceVolumeFilter::SetClippingPlanes(vtkPlaneCollection* planes)
{
  if (this->Internals->ClippingPlanes != planes)
  {
    this->Internals->ClippingPlanes = planes;
    this->Modified();
  }
}

vtkPlaneCollection* vtkIrradianceVolumeFilter::GetClippingPlanes()
{
  return this->Internals->ClippingPlanes;
}

void vtkIrradianceVolumeFilter::CopyCutaway(vtkVolumeMapper* mapper)
{
  if (!mapper)
  {
    return;
  }
  this->SetCropping(mapper->GetCropping() != 0);
  this->SetCroppingRegionPlanes(mapper->GetCroppingRegionPlanes());
  this->SetCroppingRegionFlags(mapper->GetCroppingRegionFlags());
  this->SetClippingPlanes(mapper->GetClippingPlanes());
}

mmv::Cutaway vtkIrradianceVolumeFilter::MakeCutaway()
{
  int dropped = 0;
  const mmv::Cutaway cut = mmv::MakeCutaway(this->Cropping, this->CroppingRegionPlanes,
    this->CroppingRegionFlags, this->Internals->ClippingPlanes, nullptr, &dropped);
  if (dropped > 0)
  {
    vtkWarningMacro("more than " << mmv::MaxCutPlanes << " clipping planes: " << dropped
                                 << " ignored by the shadow rays");
  }
  return cut;
}

vtkMTimeType vtkIrradianceVolumeFilter::GetMTime()
{
  vtkMTimeType mtime = this->Superclass::GetMTime();
  if (this->Internals->Opacity)
  {
    mtime = std::max(mtime, this->Internals->Opacity->GetMTime());
  }
  if (this->Internals->Material)
  {
    mtime = std::max(mtime, this->Internals->Material->GetMTime());
  }
  mtime = std::max(mtime, this->Internals->Lights->GetMTime());
  if (vtkPlaneCollection* planes = this->Internals->ClippingPlanes)
  {
    mtime = std::max(mtime, planes->GetMTime());
    for (int i = 0; i < planes->GetNumberOfItems(); ++i)
    {
      mtime = std::max(mtime, planes->GetItem(i)->GetMTime());
    }
  }
  vtkCollectionSimpleIterator it;
  this->Internals->Lights->InitTraversal(it);
  while (vtkLight* light = this->Internals->Lights->GetNextLight(it))
  {
    mtime = std::max(mtime, light->GetMTime());
  }
  return mtime;
}

void vtkIrradianceVolumeFilter::ComputeIrradianceDimensions(const int dataDims[3],
  int numberOfLights, double budgetMB, double scale, int irradianceDims[3])
{
  mmv::ComputeIrradianceDimensions(dataDims, numberOfLights, budgetMB, scale, irradianceDims);
}

int vtkIrradianceVolumeFilter::RequestInformation(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  int extent[6];
  double origin[3] = { 0.0, 0.0, 0.0 };
  double spacing[3] = { 1.0, 1.0, 1.0 };
  double direction[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent);
  inInfo->Get(vtkDataObject::ORIGIN(), origin);
  inInfo->Get(vtkDataObject::SPACING(), spacing);
  if (inInfo->Has(vtkDataObject::DIRECTION()))
  {
    inInfo->Get(vtkDataObject::DIRECTION(), direction);
  }
  const int dataDims[3] = { extent[1] - extent[0] + 1, extent[3] - extent[2] + 1,
    extent[5] - extent[4] + 1 };
  int dims[3];
  mmv::ComputeIrradianceDimensions(dataDims, this->Internals->Lights->GetNumberOfItems(),
    this->IrradianceMemoryMB, mmv::ValidIrradianceScale(this->IrradianceScale, nullptr), dims,
    this->IsTinted());
  const mmv::IrradianceGrid grid =
    mmv::MakeIrradianceGrid(extent, origin, spacing, direction, dims);
  const int outExtent[6] = { 0, dims[0] - 1, 0, dims[1] - 1, 0, dims[2] - 1 };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), outExtent, 6);
  SetGridGeometry(grid, outInfo);
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, VTK_FLOAT, 1);
  return 1;
}

int vtkIrradianceVolumeFilter::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  // Every voxel's shadow ray may cross the whole volume.
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(),
    inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()), 6);
  return 1;
}

vtkDataArray* vtkIrradianceVolumeFilter::InputScalars(vtkInformationVector** inputVector,
  vtkImageData* output, vtkImageData*& input, vtkSmartPointer<vtkImageData>& cellCentres)
{
  if (!input || !output)
  {
    vtkErrorMacro("Input and output must be vtkImageData.");
    return nullptr;
  }
  if (!this->Internals->Opacity)
  {
    vtkErrorMacro("No scalar opacity function set.");
    return nullptr;
  }
  if (!(this->ScalarOpacityUnitDistance > 0.0))
  {
    vtkErrorMacro("ScalarOpacityUnitDistance must be positive, got "
      << this->ScalarOpacityUnitDistance << ".");
    return nullptr;
  }
  int association = vtkDataObject::FIELD_ASSOCIATION_POINTS;
  vtkDataArray* scalars = this->GetInputArrayToProcess(0, inputVector, association);
  if (scalars && association == vtkDataObject::FIELD_ASSOCIATION_CELLS)
  {
    // As the mapper does: cell values live on the grid of the cell centres.
    cellCentres = mmv::MakeCellCentreImage(input, scalars);
    if (!cellCentres)
    {
      vtkErrorMacro("The cell scalars need an image with cells along every axis and a value "
                    "per cell.");
      return nullptr;
    }
    input = cellCentres;
  }
  if (!scalars || scalars->GetNumberOfTuples() != input->GetNumberOfPoints() ||
    input->GetNumberOfPoints() == 0)
  {
    vtkErrorMacro("The input has no point or cell scalars to process.");
    return nullptr;
  }
  return scalars;
}

void vtkIrradianceVolumeFilter::UpdateIrradianceDimensions(vtkImageData* input)
{
  const int* inExtent = input->GetExtent();
  const int dataDims[3] = { inExtent[1] - inExtent[0] + 1, inExtent[3] - inExtent[2] + 1,
    inExtent[5] - inExtent[4] + 1 };
  std::string scaleProblem;
  const double scale = mmv::ValidIrradianceScale(this->IrradianceScale, &scaleProblem);
  if (!scaleProblem.empty())
  {
    vtkWarningMacro(<< scaleProblem);
  }
  mmv::ComputeIrradianceDimensions(dataDims, this->Internals->Lights->GetNumberOfItems(),
    this->IrradianceMemoryMB, scale, this->IrradianceDimensions, this->IsTinted());
}

int vtkIrradianceVolumeFilter::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  this->NumberOfComputedVoxels = 0;
  this->NumberOfShadowRays = 0;
  this->DiffusionIterations = 0;
  vtkImageData* input = vtkImageData::GetData(inputVector[0]);
  vtkImageData* output = vtkImageData::GetData(outputVector);
  vtkPiecewiseFunction* otf = this->Internals->Opacity;
  vtkSmartPointer<vtkImageData> cellCentres;
  vtkDataArray* scalars = this->InputScalars(inputVector, output, input, cellCentres);
  if (!scalars)
  {
    return 0;
  }

  // Step 1: geometry of the irradiance grid.
  this->UpdateIrradianceDimensions(input);
  const mmv::IrradianceGrid grid = mmv::MakeIrradianceGrid(input, this->IrradianceDimensions);
  output->SetExtent(0, grid.Dimensions[0] - 1, 0, grid.Dimensions[1] - 1, 0, grid.Dimensions[2] - 1);
  SetGridGeometry(grid, output);

  // Step 2: pre-filter and find the voxels worth computing.
  std::vector<float> prefiltered;
  if (PrefilterFinite(input, scalars, grid, prefiltered))
  {
    vtkWarningMacro(<< mmv::NonFiniteScalarsMessage << ".");
  }
  std::vector<unsigned char> nonEmpty;
  const std::vector<vtkIdType> computed = FindComputedVoxels(otf, prefiltered, nonEmpty);
  this->NumberOfComputedVoxels = static_cast<vtkIdType>(computed.size());
  this->UpdateProgress(0.1);
  if (this->Internals->Lights->GetNumberOfItems() == 0)
  {
    vtkWarningMacro("No lights: the output has no irradiance arrays.");
    return 1;
  }

  // Step 3: shadow rays.
  const double step =
    this->ShadowStepScale * std::min({ grid.Spacing[0], grid.Spacing[1], grid.Spacing[2] });
  if (!PrepareTable(this->Internals->Table, otf, this->Internals->Material,
        this->ScalarOpacityUnitDistance, step, scalars))
  {
    vtkErrorMacro("Could not build the shadow pre-integration table.");
    return 0;
  }
  std::string radiusProblem;
  const double radius = mmv::ValidPointLightRadius(this->PointLightRadius, &radiusProblem);
  if (!radiusProblem.empty())
  {
    vtkWarningMacro(<< radiusProblem);
  }
  std::vector<LightTask> tasks;
  std::vector<vtkSmartPointer<vtkFloatArray>> arrays;
  std::vector<std::string> problems;
  MakeLightTasks(
    this->Internals->Lights, radius, grid.GetNumberOfVoxels(), tasks, arrays, problems);
  for (const std::string& problem : problems)
  {
    vtkWarningMacro(<< problem);
  }
  const RayContext ctx{ &grid, prefiltered.data(), this->Internals->Table, step,
    grid.PhysicalToIndexMatrix(), mmv::ToIndexSpace(this->MakeCutaway(), grid) };
  if (!ShadowLights(this, ctx, tasks, arrays, computed, nonEmpty, this->ShadowEstimation,
        this->PiecewiseShadowSlices, this->NumberOfShadowRays))
  {
    output->Initialize();
    return 1;
  }

  // The tint of a non-white transmission colour (grey materials: none, the
  // output is what it always was).
  std::vector<vtkSmartPointer<vtkFloatArray>> tints;
  if (this->Internals->Table->GetShadowTintTable())
  {
    tints = MakeTints(ctx, tasks, this->TintResolutionDivisor, this->NumberOfShadowRays);
  }

  // Steps 4 and 5: multiple scattering, then the empty neighbours.
  if (this->MultipleScattering)
  {
    this->DiffusionIterations =
      DiffuseLights(grid, prefiltered, computed, this->Internals->Material, tasks, arrays,
        this->ExponentialDiffusion);
  }
  for (size_t l = 0; l < tasks.size(); ++l)
  {
    if (this->FillEmptyNeighbors && tasks[l].Active)
    {
      FillEmptyNeighborVoxels(grid, nonEmpty, arrays[l]->GetPointer(0));
    }
    output->GetPointData()->AddArray(arrays[l]);
  }
  for (const auto& tint : tints)
  {
    output->GetPointData()->AddArray(tint);
  }
  output->GetPointData()->SetActiveScalars(arrays[0]->GetName());
  this->UpdateProgress(1.0);
  return 1;
}

bool vtkIrradianceVolumeFilter::IsTinted()
{
  return this->Internals->Material && this->Internals->Material->HasChromaticTransmission();
}

void vtkIrradianceVolumeFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ScalarOpacity: " << this->Internals->Opacity.Get() << "\n";
  os << indent << "ScalarOpacityUnitDistance: " << this->ScalarOpacityUnitDistance << "\n";
  os << indent << "MaterialTransferFunction: " << this->Internals->Material.Get() << "\n";
  os << indent << "Lights: " << this->Internals->Lights->GetNumberOfItems() << "\n";
  os << indent << "IrradianceScale: " << this->IrradianceScale << "\n";
  os << indent << "IrradianceMemoryMB: " << this->IrradianceMemoryMB << "\n";
  os << indent << "PointLightRadius: " << this->PointLightRadius << "\n";
  os << indent << "Cropping: " << this->Cropping << "\n";
  os << indent << "CroppingRegionPlanes: " << this->CroppingRegionPlanes[0] << " "
     << this->CroppingRegionPlanes[1] << " " << this->CroppingRegionPlanes[2] << " "
     << this->CroppingRegionPlanes[3] << " " << this->CroppingRegionPlanes[4] << " "
     << this->CroppingRegionPlanes[5] << "\n";
  os << indent << "CroppingRegionFlags: " << this->CroppingRegionFlags << "\n";
  os << indent << "ClippingPlanes: "
     << (this->Internals->ClippingPlanes ? this->Internals->ClippingPlanes->GetNumberOfItems() : 0)
     << "\n";
  os << indent << "ShadowStepScale: " << this->ShadowStepScale << "\n";
  os << indent << "ShadowEstimation: " << this->ShadowEstimation << "\n";
  os << indent << "PiecewiseShadowSlices: " << this->PiecewiseShadowSlices << "\n";
  os << indent << "MultipleScattering: " << this->MultipleScattering << "\n";
  os << indent << "ExponentialDiffusion: " << this->ExponentialDiffusion << "\n";
  os << indent << "FillEmptyNeighbors: " << this->FillEmptyNeighbors << "\n";
  os << indent << "TintResolutionDivisor: " << this->TintResolutionDivisor << "\n";
  os << indent << "NumberOfComputedVoxels: " << this->NumberOfComputedVoxels << "\n";
  os << indent << "NumberOfShadowRays: " << this->NumberOfShadowRays << "\n";
  os << indent << "DiffusionIterations: " << this->DiffusionIterations << "\n";
  os << indent << "IrradianceDimensions: " << this->IrradianceDimensions[0] << " "
     << this->IrradianceDimensions[1] << " " << this->IrradianceDimensions[2] << "\n";
}
