#include "vtkIrradianceVolumeFilter.h"

#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIrradianceDiffusion.h"
#include "vtkIrradianceGrid.h"
#include "vtkIrradianceShadowRays.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMultiMaterialCutaway.h"
#include "vtkMultiMaterialLightModel.h"
#include "vtkMultiMaterialLights.h"
#include "vtkMultiMaterialParameters.h"
#include "vtkMultiMaterialThreads.h" // mmv::For
#include "vtkObjectFactory.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPlane.h"
#include "vtkPlaneCollection.h"
#include "vtkPointData.h"
#include "vtkPreIntegrationTable.h"
#include "vtkSMPTools.h"
#include "vtkShadowSweep.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkVolumeInputScalars.h"
#include "vtkVolumeMapper.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace
{
using mmv::shadowrays::RayContext;

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

/// Empty voxels next to computed ones take the mean of those neighbours.
void FillEmptyNeighborVoxels(
  const mmv::IrradianceGrid& grid, const std::vector<unsigned char>& nonEmpty, float* values)
{
  const int* dims = grid.Dimensions;
  const vtkIdType stride[3] = { 1, dims[0], static_cast<vtkIdType>(dims[0]) * dims[1] };
  mmv::For(0, grid.GetNumberOfVoxels(),
    [&](vtkIdType begin, vtkIdType end)
    {
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
 * Multiple scattering (eq. 15) of every active light's irradiance. s is the
 * material's scattering at the pre-filtered value, 0 in empty voxels, and is
 * given in data voxels^2, so the grid spacing is passed in data voxels.
 * The change is computed on the diffusion grid (DiffuseIrradianceOnDiffusionGrid),
 * as the GPU estimator does. Returns the iterations (series terms or CG).
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
    strength[v] = static_cast<float>(mtf ? mtf->EvaluateParameter(prefiltered[v], mmv::Scattering)
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
    const mmv::IrradianceGrid& grid = *ctx.Irradiance;
    const std::vector<mmv::ShadowSweep> sweeps = mmv::PlanLightSweeps(estimation, tasks[l].Source,
      grid.Dimensions, ctx.PhysicalToIndex, grid.Origin, slicesPerChunk);
    if (!sweeps.empty())
    {
      transmittance.assign(grid.GetNumberOfVoxels(), 0.0f);
      for (size_t s = 0; s < sweeps.size() && finished; ++s)
      {
        finished = mmv::shadowrays::SweepPiecewiseShadowRays(self, ctx, tasks[l].Source, sweeps[s],
          nonEmpty, progress + span * s / sweeps.size(), span / sweeps.size(), transmittance, rays);
      }
      // A point or spot light's falloff and cone, as CastShadowRays applies them.
      const bool point = tasks[l].Source.Kind != mmv::DirectionalLight;
      float* irradiance = arrays[l]->GetPointer(0);
      for (const vtkIdType v : computed)
      {
        irradiance[v] = point ? static_cast<float>(mmv::mmvLightGeometryTerm(tasks[l].Source,
                                                     grid.IndexToPhysical(grid.IndexOfVoxel(v))) *
                                  transmittance[v])
                              : transmittance[v];
      }
    }
    else
    {
      finished = mmv::shadowrays::CastShadowRays(
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
      mmv::shadowrays::ComputeTint(ctx, tasks[l].Source, divisor, tint->GetPointer(0), rays);
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

void vtkIrradianceVolumeFilter::ComputeIrradianceDimensions(
  const int dataDims[3], int numberOfLights, double budgetMB, double scale, int irradianceDims[3])
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
    vtkErrorMacro(
      "ScalarOpacityUnitDistance must be positive, got " << this->ScalarOpacityUnitDistance << ".");
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
  output->SetExtent(
    0, grid.Dimensions[0] - 1, 0, grid.Dimensions[1] - 1, 0, grid.Dimensions[2] - 1);
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
    this->DiffusionIterations = DiffuseLights(grid, prefiltered, computed,
      this->Internals->Material, tasks, arrays, this->ExponentialDiffusion);
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
