#include "vtkIrradianceVolumeFilter.h"

#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIrradianceDiffusion.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMatrix3x3.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMultiMaterialLightModel.h"
#include "vtkMultiMaterialLights.h"
#include "vtkMultiMaterialParameters.h"
#include "vtkObjectFactory.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPreIntegrationTable.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace
{

/// Transmittance below which a shadow ray stops (the paper's early termination).
constexpr double MinTransmittance = 1.0e-4;
/// Shadow-ray work is split into this many chunks per light, so progress and
/// AbortExecute are handled on the calling thread between chunks.
constexpr int ChunksPerLight = 20;
/// Pre-filter samples per axis and irradiance voxel, at most.
constexpr int MaxFootprintSamples = 8;

/// A regular grid with a direction matrix, and its index <-> world maps.
struct Grid
{
  int Dims[3] = { 1, 1, 1 };
  double Origin[3] = { 0.0, 0.0, 0.0 };
  double Spacing[3] = { 1.0, 1.0, 1.0 };
  double Direction[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  glm::dmat3 IndexToWorld{ 1.0 };
  glm::dmat3 WorldToIndex{ 1.0 };

  void UpdateMatrices()
  {
    for (int r = 0; r < 3; ++r)
    {
      for (int c = 0; c < 3; ++c)
      {
        this->IndexToWorld[c][r] = this->Direction[3 * r + c] * this->Spacing[c]; // glm: [col][row]
      }
    }
    this->WorldToIndex = glm::inverse(this->IndexToWorld);
  }
  vtkIdType Size() const { return static_cast<vtkIdType>(this->Dims[0]) * this->Dims[1] * this->Dims[2]; }
  glm::dvec3 IndexOf(vtkIdType v) const
  {
    const vtkIdType nxy = static_cast<vtkIdType>(this->Dims[0]) * this->Dims[1];
    return glm::dvec3(static_cast<double>(v % this->Dims[0]),
      static_cast<double>((v / this->Dims[0]) % this->Dims[1]), static_cast<double>(v / nxy));
  }
  glm::dvec3 ToWorld(const glm::dvec3& index) const
  {
    return glm::dvec3(this->Origin[0], this->Origin[1], this->Origin[2]) + this->IndexToWorld * index;
  }
};

/// Trilinear interpolation at a continuous index, clamped to the grid.
double SampleTrilinear(const Grid& grid, const float* values, const glm::dvec3& index)
{
  int i0[3];
  int i1[3];
  double w[3];
  for (int a = 0; a < 3; ++a)
  {
    const double x = std::min(std::max(index[a], 0.0), static_cast<double>(grid.Dims[a] - 1));
    i0[a] = std::min(static_cast<int>(x), grid.Dims[a] - 1);
    i1[a] = std::min(i0[a] + 1, grid.Dims[a] - 1);
    w[a] = x - i0[a];
  }
  const vtkIdType sy = grid.Dims[0];
  const vtkIdType sz = static_cast<vtkIdType>(grid.Dims[0]) * grid.Dims[1];
  auto at = [&](int i, int j, int k) { return static_cast<double>(values[i + j * sy + k * sz]); };
  const double c00 = at(i0[0], i0[1], i0[2]) * (1 - w[0]) + at(i1[0], i0[1], i0[2]) * w[0];
  const double c10 = at(i0[0], i1[1], i0[2]) * (1 - w[0]) + at(i1[0], i1[1], i0[2]) * w[0];
  const double c01 = at(i0[0], i0[1], i1[2]) * (1 - w[0]) + at(i1[0], i0[1], i1[2]) * w[0];
  const double c11 = at(i0[0], i1[1], i1[2]) * (1 - w[0]) + at(i1[0], i1[1], i1[2]) * w[0];
  const double c0 = c00 * (1 - w[1]) + c10 * w[1];
  const double c1 = c01 * (1 - w[1]) + c11 * w[1];
  return c0 * (1 - w[2]) + c1 * w[2];
}

/// Distance along index-space direction `d` from `p` (inside) to the grid's box.
double ExitDistance(const Grid& grid, const glm::dvec3& p, const glm::dvec3& d)
{
  double t = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a)
  {
    if (d[a] > 0.0)
    {
      t = std::min(t, (grid.Dims[a] - 1 - p[a]) / d[a]);
    }
    else if (d[a] < 0.0)
    {
      t = std::min(t, -p[a] / d[a]);
    }
  }
  return std::max(t, 0.0);
}

/// The irradiance grid spanning the same bounds as the data grid.
Grid MakeIrradianceGrid(const Grid& data, const int dims[3])
{
  Grid grid = data;
  for (int a = 0; a < 3; ++a)
  {
    grid.Dims[a] = dims[a];
    if (dims[a] > 1)
    {
      grid.Spacing[a] = data.Spacing[a] * (data.Dims[a] - 1) / (dims[a] - 1);
    }
  }
  grid.UpdateMatrices();
  return grid;
}

/// The data grid from pipeline information; the origin moves to the first
/// point of `extent` so that indices start at 0.
Grid MakeDataGrid(vtkInformation* info, const int extent[6])
{
  Grid grid;
  info->Get(vtkDataObject::SPACING(), grid.Spacing);
  double origin[3] = { 0.0, 0.0, 0.0 };
  info->Get(vtkDataObject::ORIGIN(), origin);
  if (info->Has(vtkDataObject::DIRECTION()))
  {
    info->Get(vtkDataObject::DIRECTION(), grid.Direction);
  }
  vtkImageData::TransformContinuousIndexToPhysicalPoint(
    extent[0], extent[2], extent[4], origin, grid.Spacing, grid.Direction, grid.Origin);
  for (int a = 0; a < 3; ++a)
  {
    grid.Dims[a] = extent[2 * a + 1] - extent[2 * a] + 1;
  }
  grid.UpdateMatrices();
  return grid;
}

Grid MakeDataGrid(vtkImageData* image)
{
  Grid grid;
  const int* extent = image->GetExtent();
  image->GetSpacing(grid.Spacing);
  std::copy(image->GetDirectionMatrix()->GetData(), image->GetDirectionMatrix()->GetData() + 9,
    grid.Direction);
  image->TransformContinuousIndexToPhysicalPoint(extent[0], extent[2], extent[4], grid.Origin);
  for (int a = 0; a < 3; ++a)
  {
    grid.Dims[a] = extent[2 * a + 1] - extent[2 * a] + 1;
  }
  grid.UpdateMatrices();
  return grid;
}

/// Component 0 of the scalars as floats (one virtual call per value, once).
std::vector<float> CopyScalars(vtkDataArray* scalars)
{
  std::vector<float> values(scalars->GetNumberOfTuples());
  vtkSMPTools::For(0, scalars->GetNumberOfTuples(), [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType i = begin; i < end; ++i)
    {
      values[i] = static_cast<float>(scalars->GetComponent(i, 0));
    }
  });
  return values;
}

/**
 * Box filter of the data over each irradiance voxel's footprint (one
 * irradiance spacing wide, clamped to the data), by the midpoint rule on a
 * small sub-grid of trilinear samples. Axes at full resolution take the
 * data value itself, so equal resolutions give an exact copy.
 */
std::vector<float> Prefilter(const Grid& data, const std::vector<float>& values, const Grid& grid)
{
  double ratio[3];
  int samples[3];
  for (int a = 0; a < 3; ++a)
  {
    ratio[a] = grid.Dims[a] > 1 ? (data.Dims[a] - 1.0) / (grid.Dims[a] - 1.0) : 0.0;
    samples[a] = grid.Dims[a] == data.Dims[a]
      ? 1
      : std::min(MaxFootprintSamples, std::max(2, static_cast<int>(std::ceil(ratio[a]))));
  }
  std::vector<float> out(grid.Size());
  vtkSMPTools::For(0, grid.Size(), [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType v = begin; v < end; ++v)
    {
      const glm::dvec3 centre = grid.IndexOf(v) * glm::dvec3(ratio[0], ratio[1], ratio[2]);
      double sum = 0.0;
      for (int k = 0; k < samples[2]; ++k)
      {
        for (int j = 0; j < samples[1]; ++j)
        {
          for (int i = 0; i < samples[0]; ++i)
          {
            const int q[3] = { i, j, k };
            glm::dvec3 p = centre;
            for (int a = 0; a < 3; ++a)
            {
              if (samples[a] > 1)
              {
                p[a] += ratio[a] * ((q[a] + 0.5) / samples[a] - 0.5);
              }
            }
            sum += SampleTrilinear(data, values.data(), p);
          }
        }
      }
      out[v] = static_cast<float>(sum / (samples[0] * samples[1] * samples[2]));
    }
  });
  return out;
}

/// What the shadow rays of one light need.
struct LightTask
{
  mmv::LightSource Source;
  bool Active = false;
};

/// Shared with the GPU mapper, so both see the same lights.
LightTask MakeLightTask(vtkLight* light, double radius)
{
  LightTask task;
  task.Active = mmv::IsLightActive(light);
  task.Source = mmv::MakeLightSource(light, nullptr, radius);
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
  std::vector<LightTask>& tasks, std::vector<vtkSmartPointer<vtkFloatArray>>& arrays)
{
  vtkCollectionSimpleIterator it;
  lights->InitTraversal(it);
  while (vtkLight* light = lights->GetNextLight(it))
  {
    tasks.push_back(MakeLightTask(light, radius));
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
  const Grid* Irradiance;
  const float* Prefiltered;
  const vtkPreIntegrationTable* Table;
  double Step;
};

/**
 * Transmittance from irradiance voxel `v` toward the light (eqs. 9-10), by
 * pre-integrated segments of length Step and one shorter final segment that
 * ends exactly on the volume boundary (or at the light).
 */
double ShadowTransmittance(const RayContext& ctx, const mmv::LightSource& light, vtkIdType v)
{
  const Grid& grid = *ctx.Irradiance;
  const glm::dvec3 start = grid.IndexOf(v);
  const glm::dvec3 x = grid.ToWorld(start);
  double lightDistance = 0.0;
  const glm::dvec3 dir = mmv::mmvDirectionToLight(light, x, lightDistance);
  const glm::dvec3 indexDir = grid.WorldToIndex * dir;
  double end = ExitDistance(grid, start, indexDir);
  if (lightDistance >= 0.0)
  {
    end = std::min(end, lightDistance);
  }
  const double h = ctx.Step;
  // The tolerance keeps an end that is a whole number of steps from adding
  // a zero-length segment (or dropping the last full one) by rounding.
  const vtkIdType steps = static_cast<vtkIdType>(std::floor(end / h + 1.0e-9));
  double previous = ctx.Prefiltered[v];
  double transmittance = 1.0;
  for (vtkIdType n = 1; n <= steps; ++n)
  {
    const double next =
      SampleTrilinear(grid, ctx.Prefiltered, start + (static_cast<double>(n) * h) * indexDir);
    transmittance *= 1.0 - ctx.Table->LookupShadowOpacity(previous, next);
    if (transmittance < MinTransmittance)
    {
      return transmittance;
    }
    previous = next;
  }
  const double rest = end - static_cast<double>(steps) * h;
  if (rest > 1.0e-9 * h)
  {
    const double next = SampleTrilinear(grid, ctx.Prefiltered, start + end * indexDir);
    const double alpha = ctx.Table->LookupShadowOpacity(previous, next);
    // Optical depth is linear in the segment length for a linear value ramp.
    transmittance *= std::pow(std::max(0.0, 1.0 - alpha), rest / h);
  }
  return transmittance;
}

/// Empty voxels next to computed ones take the mean of those neighbours.
void FillEmptyNeighborVoxels(const Grid& grid, const std::vector<unsigned char>& nonEmpty, float* values)
{
  const vtkIdType stride[3] = { 1, grid.Dims[0], static_cast<vtkIdType>(grid.Dims[0]) * grid.Dims[1] };
  vtkSMPTools::For(0, grid.Size(), [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType v = begin; v < end; ++v)
    {
      if (nonEmpty[v])
      {
        continue;
      }
      const glm::dvec3 index = grid.IndexOf(v);
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
        if (index[a] + 1 < grid.Dims[a] && nonEmpty[v + stride[a]])
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
  scalars->GetRange(range, 0);
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
  const Grid& grid = *ctx.Irradiance;
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
        const double geometry = mmv::mmvLightGeometryTerm(light, grid.ToWorld(grid.IndexOf(v)));
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
 * Returns the CG iterations.
 */
int DiffuseLights(const Grid& grid, const Grid& data, const std::vector<float>& prefiltered,
  const std::vector<vtkIdType>& computed, vtkMaterialTransferFunction* mtf,
  const std::vector<LightTask>& tasks, const std::vector<vtkSmartPointer<vtkFloatArray>>& arrays)
{
  std::vector<float> strength(grid.Size(), 0.0f);
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
  double spacing[3];
  for (int a = 0; a < 3; ++a)
  {
    spacing[a] = grid.Dims[a] > 1 ? (data.Dims[a] - 1.0) / (grid.Dims[a] - 1.0) : 1.0;
  }
  int iterations = 0;
  for (size_t l = 0; l < tasks.size(); ++l)
  {
    if (tasks[l].Active)
    {
      iterations += mmv::DiffuseIrradiance(
        grid.Dims, spacing, strength.data(), arrays[l]->GetPointer(0))
                      .Iterations;
    }
  }
  return iterations;
}

} // namespace

class vtkIrradianceVolumeFilter::vtkInternals
{
public:
  vtkSmartPointer<vtkPiecewiseFunction> Opacity;
  vtkSmartPointer<vtkMaterialTransferFunction> Material;
  vtkSmartPointer<vtkLightCollection> Lights = vtkSmartPointer<vtkLightCollection>::New();
  vtkNew<vtkPreIntegrationTable> Table;
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
  int d[3];
  int lo[3];
  int active = 0;
  for (int a = 0; a < 3; ++a)
  {
    d[a] = std::max(1, dataDims[a]);
    lo[a] = std::min(2, d[a]);
    active += d[a] > 1 ? 1 : 0;
  }
  auto apply = [&](double s) {
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
  const double bytesPerVoxel = mmv::IrradianceBytesPerVoxelPerLight * std::max(1, numberOfLights);
  const double budgetVoxels = std::max(0.0, budgetMB) * 1024.0 * 1024.0 / bytesPerVoxel;
  auto voxels = [&]() {
    return static_cast<double>(irradianceDims[0]) * irradianceDims[1] * irradianceDims[2];
  };
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

int vtkIrradianceVolumeFilter::RequestInformation(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  int extent[6];
  inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent);
  const Grid data = MakeDataGrid(inInfo, extent);
  int dims[3];
  ComputeIrradianceDimensions(data.Dims, this->Internals->Lights->GetNumberOfItems(),
    this->IrradianceMemoryMB, this->IrradianceScale, dims);
  const Grid grid = MakeIrradianceGrid(data, dims);
  const int outExtent[6] = { 0, dims[0] - 1, 0, dims[1] - 1, 0, dims[2] - 1 };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), outExtent, 6);
  outInfo->Set(vtkDataObject::ORIGIN(), grid.Origin, 3);
  outInfo->Set(vtkDataObject::SPACING(), grid.Spacing, 3);
  outInfo->Set(vtkDataObject::DIRECTION(), grid.Direction, 9);
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

int vtkIrradianceVolumeFilter::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  this->NumberOfComputedVoxels = 0;
  this->NumberOfShadowRays = 0;
  this->DiffusionIterations = 0;
  vtkImageData* input = vtkImageData::GetData(inputVector[0]);
  vtkImageData* output = vtkImageData::GetData(outputVector);
  vtkPiecewiseFunction* otf = this->Internals->Opacity;
  if (!input || !output)
  {
    vtkErrorMacro("Input and output must be vtkImageData.");
    return 0;
  }
  if (!otf)
  {
    vtkErrorMacro("No scalar opacity function set.");
    return 0;
  }
  if (!(this->ScalarOpacityUnitDistance > 0.0))
  {
    vtkErrorMacro("ScalarOpacityUnitDistance must be positive, got "
      << this->ScalarOpacityUnitDistance << ".");
    return 0;
  }
  vtkDataArray* scalars = this->GetInputArrayToProcess(0, inputVector);
  if (!scalars || scalars->GetNumberOfTuples() != input->GetNumberOfPoints() ||
    input->GetNumberOfPoints() == 0)
  {
    vtkErrorMacro("The input has no point scalars to process.");
    return 0;
  }

  // Step 1: geometry of the irradiance grid.
  const Grid data = MakeDataGrid(input);
  const int numberOfLights = this->Internals->Lights->GetNumberOfItems();
  ComputeIrradianceDimensions(
    data.Dims, numberOfLights, this->IrradianceMemoryMB, this->IrradianceScale, this->IrradianceDimensions);
  const Grid grid = MakeIrradianceGrid(data, this->IrradianceDimensions);
  output->SetExtent(0, grid.Dims[0] - 1, 0, grid.Dims[1] - 1, 0, grid.Dims[2] - 1);
  output->SetOrigin(grid.Origin);
  output->SetSpacing(grid.Spacing);
  output->SetDirectionMatrix(grid.Direction);

  // Step 2: pre-filter and find the voxels worth computing.
  const std::vector<float> values = CopyScalars(scalars);
  const std::vector<float> prefiltered = Prefilter(data, values, grid);
  std::vector<unsigned char> nonEmpty;
  const std::vector<vtkIdType> computed = FindComputedVoxels(otf, prefiltered, nonEmpty);
  this->NumberOfComputedVoxels = static_cast<vtkIdType>(computed.size());
  this->UpdateProgress(0.1);
  if (numberOfLights == 0)
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
  const double radius = this->PointLightRadius > 0.0
    ? this->PointLightRadius
    : std::min({ data.Spacing[0], data.Spacing[1], data.Spacing[2] });
  std::vector<LightTask> tasks;
  std::vector<vtkSmartPointer<vtkFloatArray>> arrays;
  MakeLightTasks(this->Internals->Lights, radius, grid.Size(), tasks, arrays);
  const RayContext ctx{ &grid, prefiltered.data(), this->Internals->Table, step };
  for (size_t l = 0; l < tasks.size(); ++l)
  {
    if (tasks[l].Active &&
      !CastShadowRays(this, ctx, tasks[l].Source, computed, arrays[l]->GetPointer(0),
        0.1 + 0.8 * l / tasks.size(), 0.8 / tasks.size(), this->NumberOfShadowRays))
    {
      output->Initialize();
      return 1;
    }
  }

  // Steps 4 and 5: multiple scattering, then the empty neighbours.
  if (this->MultipleScattering)
  {
    this->DiffusionIterations = DiffuseLights(
      grid, data, prefiltered, computed, this->Internals->Material, tasks, arrays);
  }
  for (size_t l = 0; l < tasks.size(); ++l)
  {
    if (this->FillEmptyNeighbors && tasks[l].Active)
    {
      FillEmptyNeighborVoxels(grid, nonEmpty, arrays[l]->GetPointer(0));
    }
    output->GetPointData()->AddArray(arrays[l]);
  }
  output->GetPointData()->SetActiveScalars(arrays[0]->GetName());
  this->UpdateProgress(1.0);
  return 1;
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
  os << indent << "ShadowStepScale: " << this->ShadowStepScale << "\n";
  os << indent << "MultipleScattering: " << this->MultipleScattering << "\n";
  os << indent << "FillEmptyNeighbors: " << this->FillEmptyNeighbors << "\n";
  os << indent << "NumberOfComputedVoxels: " << this->NumberOfComputedVoxels << "\n";
  os << indent << "NumberOfShadowRays: " << this->NumberOfShadowRays << "\n";
  os << indent << "DiffusionIterations: " << this->DiffusionIterations << "\n";
  os << indent << "IrradianceDimensions: " << this->IrradianceDimensions[0] << " "
     << this->IrradianceDimensions[1] << " " << this->IrradianceDimensions[2] << "\n";
}
