#include "vtkPVMultiMaterialVolumeRepresentation.h"

#include "vtkMultiMaterialFieldSettings.h"

#include "vtkCellData.h"
#include "vtkColorTransferFunction.h"
#include "vtkCommand.h"
#include "vtkCommunicator.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataObject.h"
#include "vtkGlobalPrefilterExchange.h"
#include "vtkImageBlockMerge.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIrradianceEstimator.h"
#include "vtkMaterialLibrary.h"
#include "vtkMultiMaterialLightingQuality.h"
#include "vtkMultiMaterialLiveObjects.h"
#include "vtkMultiMaterialVolumeMapper.h"
#include "vtkMultiProcessController.h"
#include "vtkObjectFactory.h"
#include "vtkPResampleToImage.h"
#include "vtkPVGeneralSettings.h"
#include "vtkPVRenderView.h"
#include "vtkPVView.h"
#include "vtkPointData.h"
#include "vtkRectilinearGrid.h"
#include "vtkRenderer.h"
#include "vtkResampleToImage.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUniformGridAMR.h"
#include "vtkVolumeInputScalars.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

vtkStandardNewMacro(vtkPVMultiMaterialVolumeRepresentation);

namespace
{
// The MaterialPreset value that selects MaterialNodes (the domain's none_string).
constexpr const char* CustomPreset = "Custom";
}

//------------------------------------------------------------------------------
vtkPVMultiMaterialVolumeRepresentation::vtkPVMultiMaterialVolumeRepresentation()
  : Fields(new vtkMultiMaterialFieldSettings)
{
  vtkMultiMaterialLiveObjects::Constructed("vtkPVMultiMaterialVolumeRepresentation");
  // The base class drives whatever mapper sits here; ours is a
  // vtkOpenGLGPUVolumeRayCastMapper, so everything generic keeps working.
  vtkNew<vtkMultiMaterialVolumeMapper> mapper;
  mapper->SetMaterialTransferFunction(this->Materials);
  // ParaView's progress bar listens to the representation, not its mapper.
  // The client repaints the bar inside the render; the mapper keeps VTK's
  // OpenGL state across each report (vtkMultiMaterialIrradianceStage).
  mapper->AddObserver(
    vtkCommand::ProgressEvent, this, &vtkPVMultiMaterialVolumeRepresentation::ForwardProgress);
  this->VolumeMapper = mapper;

  this->AppliedNodes->SetName("MaterialNodes");
  vtkNew<vtkMaterialLibrary> library;
  for (int i = 0; i < library->GetNumberOfPresets(); ++i)
  {
    this->PresetNames->InsertNextValue(library->GetPresetName(i));
  }
}

//------------------------------------------------------------------------------
vtkPVMultiMaterialVolumeRepresentation::~vtkPVMultiMaterialVolumeRepresentation()
{
  vtkMultiMaterialLiveObjects::Destroyed("vtkPVMultiMaterialVolumeRepresentation");
}

//------------------------------------------------------------------------------
void vtkPVMultiMaterialVolumeRepresentation::ForwardProgress(
  vtkObject* caller, unsigned long, void* progress)
{
  // Only the irradiance update's events carry a text; the mapper's pipeline
  // progress (its input's update, every frame) is left out.
  auto* mapper = vtkAlgorithm::SafeDownCast(caller);
  if (!mapper || !mapper->GetProgressText())
  {
    return;
  }
  this->SetProgressText(mapper->GetProgressText());
  this->UpdateProgress(*static_cast<double*>(progress));
  // This representation's own pipeline progress carries no text.
  this->SetProgressText(nullptr);
}

//------------------------------------------------------------------------------
vtkMultiMaterialVolumeMapper* vtkPVMultiMaterialVolumeRepresentation::GetMultiMaterialMapper()
{
  return vtkMultiMaterialVolumeMapper::SafeDownCast(this->VolumeMapper);
}

//------------------------------------------------------------------------------
void vtkPVMultiMaterialVolumeRepresentation::SetNumberOfMaterialNodeValues(int count)
{
  if (this->PendingNodes.Announce(count) && this->PendingNodes.Apply(this, this->CustomMaterials))
  {
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkPVMultiMaterialVolumeRepresentation::SetMaterialNodeValue(int index, double value)
{
  if (this->PendingNodes.Receive(index, value) &&
    this->PendingNodes.Apply(this, this->CustomMaterials))
  {
    this->Modified();
  }
}

//------------------------------------------------------------------------------
bool vtkPVMultiMaterialVolumeRepresentation::UsesPreset() const
{
  return !this->MaterialPreset.empty() && this->MaterialPreset != CustomPreset;
}

//------------------------------------------------------------------------------
void vtkPVMultiMaterialVolumeRepresentation::SetMaterialPreset(const char* name)
{
  const std::string value = name ? name : "";
  if (value == this->MaterialPreset)
  {
    return;
  }
  if (!value.empty() && value != CustomPreset)
  {
    vtkNew<vtkMaterialLibrary> library;
    if (!library->HasPreset(value.c_str()))
    {
      vtkErrorMacro(
        "Unknown material preset \"" << value << "\". Keeping \"" << this->MaterialPreset << "\".");
      return;
    }
  }
  this->MaterialPreset = value;
  this->PresetRange[0] = 0.0;
  this->PresetRange[1] = -1.0; // forces ApplyPreset at the next render
  this->Modified();
}

//------------------------------------------------------------------------------
vtkStringArray* vtkPVMultiMaterialVolumeRepresentation::GetMaterialPresetNames()
{
  return this->PresetNames;
}

//------------------------------------------------------------------------------
vtkDoubleArray* vtkPVMultiMaterialVolumeRepresentation::GetAppliedMaterialNodes()
{
  const int size = this->Materials->GetSize();
  this->AppliedNodes->SetNumberOfValues(
    static_cast<vtkIdType>(size) * vtkMaterialTransferFunction::NodeStride);
  this->Materials->GetNodes(this->AppliedNodes->GetPointer(0));
  return this->AppliedNodes;
}

//------------------------------------------------------------------------------
void vtkPVMultiMaterialVolumeRepresentation::UpdateMapperParameters()
{
  this->Superclass::UpdateMapperParameters();
  vtkMultiMaterialVolumeMapper* mapper = this->GetMultiMaterialMapper();
  if (!mapper)
  {
    return;
  }

  if (this->UsesPreset())
  {
    // The colour map's range: ParaView keeps it the same on every rank, where
    // each rank's own data range would give each piece different materials.
    double range[2] = { 0.0, 1.0 };
    if (vtkColorTransferFunction* color = this->Property->GetRGBTransferFunction(0))
    {
      color->GetRange(range);
    }
    if (!(range[1] > range[0]))
    {
      range[1] = range[0] + 1.0;
    }
    if (range[0] != this->PresetRange[0] || range[1] != this->PresetRange[1])
    {
      // Validated in SetMaterialPreset, so this only fails on a broken library.
      if (this->Materials->ApplyPreset(this->MaterialPreset.c_str(), range[0], range[1]))
      {
        this->PresetRange[0] = range[0];
        this->PresetRange[1] = range[1];
      }
    }
  }
  else if (this->Materials->GetMTime() < this->CustomMaterials->GetMTime() ||
    this->PresetRange[1] < this->PresetRange[0])
  {
    // Back from a preset, or MaterialNodes changed.
    this->Materials->DeepCopy(this->CustomMaterials);
    this->PresetRange[0] = 0.0;
    this->PresetRange[1] = 0.0;
  }

  if (this->Resampled)
  {
    // Resampling probes cell arrays into point arrays of the same name.
    mapper->SetScalarModeToUsePointFieldData();
  }
  int component = 0;
  mapper->SetVectorMode(this->MapperVectorMode(component));
  mapper->SetVectorComponent(component);
  this->Fields->Apply(mapper, this->Property, this);

  // vtkSetMacro only bumps the mapper's MTime on a real change, so setting
  // these every frame costs nothing. The radius depends on the data's
  // bounds, the sampling is VTK's own.
  mapper->SetPointLightRadius(this->LightFalloff == 1 ? this->FalloffRadius() : 0.0);
  mapper->SetSampleDistance(static_cast<float>(this->SampleDistance));
  mapper->SetAutoAdjustSampleDistances(this->AutoAdjustSampleDistances);
  mapper->SetLockSampleDistanceToInputSpacing(this->LockSampleDistanceToInputSpacing);
  // Earlier steps come back as the same data objects only from the view's
  // animation cache; without it every step is new data. The scene turns the
  // view's cache on for its own frames only: the setting keeps the budget
  // through the renders between them (a screenshot, the GUI's repaint),
  // which would otherwise drop every kept step before the next loop.
  auto* view = vtkPVView::SafeDownCast(this->GetView());
  const bool caching = (view && view->GetUseCache()) ||
    vtkPVGeneralSettings::GetInstance()->GetCacheGeometryForAnimation();
  mapper->SetIrradianceCacheMB(caching ? this->IrradianceCacheMB : 0.0);
}

//------------------------------------------------------------------------------
// The further fields' properties: kept, handed to the mapper and the volume
// property in UpdateMapperParameters().
#define vtkPVMMVFieldList(clear, add, type, plural, singular)                                      \
  void vtkPVMultiMaterialVolumeRepresentation::clear()                                             \
  {                                                                                                \
    this->Fields->Clear##plural();                                                                 \
    this->Modified();                                                                              \
  }                                                                                                \
  void vtkPVMultiMaterialVolumeRepresentation::add(type value)                                     \
  {                                                                                                \
    this->Fields->Add##singular(value);                                                            \
    this->Modified();                                                                              \
  }
vtkPVMMVFieldList(ClearFieldArrays, AddFieldArray, const char*, Arrays, Array);
vtkPVMMVFieldList(
  ClearFieldLookupTables, AddFieldLookupTable, vtkColorTransferFunction*, Colors, Color);
vtkPVMMVFieldList(ClearFieldScalarOpacityFunctions, AddFieldScalarOpacityFunction,
  vtkPiecewiseFunction*, Opacities, Opacity);
vtkPVMMVFieldList(ClearFieldMaterialPresets, AddFieldMaterialPreset, const char*, Presets, Preset);
#undef vtkPVMMVFieldList

int vtkPVMultiMaterialVolumeRepresentation::GetNumberOfFields()
{
  vtkMultiMaterialVolumeMapper* mapper = this->GetMultiMaterialMapper();
  return mapper ? mapper->GetNumberOfFields() : 1;
}

//------------------------------------------------------------------------------
double vtkPVMultiMaterialVolumeRepresentation::FalloffRadius() const
{
  if (this->PointLightRadius > 0.0)
  {
    return this->PointLightRadius;
  }
  // Automatic: light falls off over the data's scale, so a radius of 0 (the
  // default) is a valid choice too, not a mode that silently does nothing.
  const double* b = this->DataBounds;
  double d2 = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    const double extent = b[2 * a + 1] - b[2 * a];
    d2 += extent > 0.0 ? extent * extent : 0.0;
  }
  return d2 > 0.0 ? 0.25 * std::sqrt(d2) : 1.0;
}

//------------------------------------------------------------------------------
void vtkPVMultiMaterialVolumeRepresentation::SetLightingQuality(int level)
{
  if (level == mmv::LightingQualityCustom)
  {
    this->LightingQuality = level;
    return;
  }
  const mmv::LightingQualitySettings* row = mmv::GetLightingQualitySettings(level);
  if (!row)
  {
    vtkErrorMacro("LightingQuality " << level
                                     << " is not 0 (Fast), 1 (Balanced), 2 (Exact) or 3 "
                                        "(Custom); keeping "
                                     << this->LightingQuality << ".");
    return;
  }
  this->LightingQuality = level;
  this->SetShadowEstimation(row->ShadowEstimation);
  this->SetPiecewiseShadowSlices(row->PiecewiseShadowSlices);
  this->SetExponentialDiffusion(row->ExponentialDiffusion != 0);
  this->SetPieceIrradianceOnly(row->PieceIrradianceOnly != 0);
  this->SetLightDirectionTolerance(row->LightDirectionTolerance);
  this->SetReflectionVisibility(row->ReflectionVisibility);
  this->SetIrradianceErrorBound(row->IrradianceErrorBound);
  this->SetIrradianceMemoryMB(row->IrradianceMemoryMB);
  this->SetIrradianceScale(row->IrradianceScale);
  this->SetDimLightCoarsening(row->DimLightCoarsening != 0);
}

//------------------------------------------------------------------------------
int vtkPVMultiMaterialVolumeRepresentation::MapperVectorMode(int& component)
{
  // Vectors as Volume draws them: vtkImageVolumeRepresentation hands the
  // colour map's Magnitude / component to its mapper when components are
  // independent (MapScalars on); dependent ones (RGBA, MapScalars off) are
  // not reduced, and render with VTK's shading.
  component = 0;
  vtkColorTransferFunction* colors =
    this->Property ? this->Property->GetRGBTransferFunction(0) : nullptr;
  if (!colors || !this->Property->GetIndependentComponents())
  {
    return mmv::VectorModeDisabled;
  }
  component = std::max(colors->GetVectorComponent(), 0);
  const int mode = colors->GetVectorMode();
  // vtkScalarsToColors::RGBCOLORS has no single value to shade.
  return mode == vtkScalarsToColors::MAGNITUDE || mode == vtkScalarsToColors::COMPONENT
    ? mode
    : mmv::VectorModeDisabled;
}

//------------------------------------------------------------------------------
// The mapper's settings go to it directly, as ParaView's own representations
// forward to their mapper; the setting's row (vtkMultiMaterialSettings.h)
// clamps it there.
#define vtkPVMMVForward(name, type)                                                                \
  void vtkPVMultiMaterialVolumeRepresentation::Set##name(type value)                               \
  {                                                                                                \
    if (vtkMultiMaterialVolumeMapper* mapper = this->GetMultiMaterialMapper())                     \
    {                                                                                              \
      mapper->Set##name(value);                                                                    \
    }                                                                                              \
  }
vtkPVMMVForward(IrradianceMemoryMB, double);
vtkPVMMVForward(IrradianceScale, double);
vtkPVMMVForward(IrradianceErrorBound, double);
vtkPVMMVForward(GradientSmoothing, double);
vtkPVMMVForward(MultipleScattering, bool);
vtkPVMMVForward(PreIntegration, bool);
vtkPVMMVForward(InteractiveIrradiance, int);
vtkPVMMVForward(ShadowEstimation, int);
vtkPVMMVForward(PiecewiseShadowSlices, int);
vtkPVMMVForward(ExponentialDiffusion, bool);
vtkPVMMVForward(PieceIrradianceOnly, bool);
vtkPVMMVForward(DimLightCoarsening, bool);
vtkPVMMVForward(LightDirectionTolerance, double);
vtkPVMMVForward(ReflectionSource, int);
vtkPVMMVForward(ReflectionVisibility, int);
vtkPVMMVForward(EnvironmentLighting, double);
#undef vtkPVMMVForward

// What depends on the view or the data is kept here and handed over in
// UpdateMapperParameters(). Modified(), not MarkModified(): re-executing the
// representation would deliver a new data object and void the irradiance cache.
#define vtkPVMMVSetter(name, type)                                                                 \
  void vtkPVMultiMaterialVolumeRepresentation::Set##name(type value)                               \
  {                                                                                                \
    if (this->name != value)                                                                       \
    {                                                                                              \
      this->name = value;                                                                          \
      this->Modified();                                                                            \
    }                                                                                              \
  }
vtkPVMMVSetter(SampleDistance, double);
vtkPVMMVSetter(AutoAdjustSampleDistances, bool);
vtkPVMMVSetter(LockSampleDistanceToInputSpacing, bool);
vtkPVMMVSetter(IrradianceCacheMB, double);
vtkPVMMVSetter(LightFalloff, int);
#undef vtkPVMMVSetter

//------------------------------------------------------------------------------
void vtkPVMultiMaterialVolumeRepresentation::SetPointLightRadius(double radius)
{
  if (!(radius >= 0.0))
  {
    // Reported here, where the value arrives: 0 (automatic) is what is used.
    vtkWarningMacro("PointLightRadius " << radius
                                        << " is not a length: using 0 (automatic, a quarter of "
                                           "the data's diagonal).");
    radius = 0.0;
  }
  if (this->PointLightRadius != radius)
  {
    this->PointLightRadius = radius;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
int vtkPVMultiMaterialVolumeRepresentation::GetIrradianceUpdateCount()
{
  auto* mapper = this->GetMultiMaterialMapper();
  return mapper ? mapper->GetIrradianceUpdateCount() : 0;
}

int vtkPVMultiMaterialVolumeRepresentation::GetSkyUpdateCount()
{
  auto* mapper = this->GetMultiMaterialMapper();
  return mapper ? mapper->GetSkyUpdateCount() : 0;
}

int vtkPVMultiMaterialVolumeRepresentation::GetDiffusionPassCount()
{
  auto* mapper = this->GetMultiMaterialMapper();
  return mapper ? mapper->GetDiffusionPassCount() : 0;
}

int vtkPVMultiMaterialVolumeRepresentation::GetPreIntegrationCount()
{
  auto* mapper = this->GetMultiMaterialMapper();
  return mapper ? mapper->GetPreIntegrationCount() : 0;
}

int vtkPVMultiMaterialVolumeRepresentation::GetRayCastCount()
{
  auto* mapper = this->GetMultiMaterialMapper();
  return mapper ? mapper->GetRayCastCount() : 0;
}

int vtkPVMultiMaterialVolumeRepresentation::GetNumberOfShadedLights()
{
  auto* mapper = this->GetMultiMaterialMapper();
  return mapper ? mapper->GetNumberOfShadedLights() : 0;
}

int vtkPVMultiMaterialVolumeRepresentation::GetDeferredIrradianceCount()
{
  auto* mapper = this->GetMultiMaterialMapper();
  return mapper ? mapper->GetDeferredIrradianceCount() : 0;
}

int vtkPVMultiMaterialVolumeRepresentation::GetIrradianceCacheHitCount()
{
  auto* mapper = this->GetMultiMaterialMapper();
  return mapper ? mapper->GetIrradianceCacheHitCount() : 0;
}

double vtkPVMultiMaterialVolumeRepresentation::GetLastIrradianceSeconds()
{
  auto* mapper = this->GetMultiMaterialMapper();
  return mapper ? mapper->GetLastIrradianceSeconds() : 0.0;
}

double vtkPVMultiMaterialVolumeRepresentation::GetLastSkySeconds()
{
  auto* mapper = this->GetMultiMaterialMapper();
  return mapper ? mapper->GetLastSkySeconds() : 0.0;
}

double vtkPVMultiMaterialVolumeRepresentation::GetLastEstimatedIrradianceVoxels()
{
  vtkMultiMaterialVolumeMapper* mapper = this->GetMultiMaterialMapper();
  return mapper ? static_cast<double>(mapper->GetIrradianceEstimator()->GetLastEstimatedVoxels())
                : 0.0;
}

const char* vtkPVMultiMaterialVolumeRepresentation::GetIrradianceResolutionInfo()
{
  auto* mapper = this->GetMultiMaterialMapper();
  return mapper ? mapper->GetIrradianceResolutionReason() : "";
}

const char* vtkPVMultiMaterialVolumeRepresentation::GetLastIrradianceStages()
{
  auto* mapper = this->GetMultiMaterialMapper();
  this->StagesInfo = mapper ? mapper->GetLastIrradianceStages() : std::string();
  return this->StagesInfo.c_str();
}

int vtkPVMultiMaterialVolumeRepresentation::GetIrradianceProbeCount()
{
  auto* mapper = this->GetMultiMaterialMapper();
  return mapper ? mapper->GetNumberOfIrradianceProbes() : 0;
}

int vtkPVMultiMaterialVolumeRepresentation::GetMultiMaterialActive()
{
  auto* mapper = this->GetMultiMaterialMapper();
  return mapper && mapper->GetMultiMaterialActive() ? 1 : 0;
}

//------------------------------------------------------------------------------
int vtkPVMultiMaterialVolumeRepresentation::FillInputPortInformation(int port, vtkInformation* info)
{
  this->Superclass::FillInputPortInformation(port, info);
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkMultiBlockDataSet");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPartitionedDataSetCollection");
  // AMR and other data sets are resampled to image data (RequestData).
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkUniformGridAMR");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataSet");
  return 1;
}

//------------------------------------------------------------------------------
void vtkPVMultiMaterialVolumeRepresentation::SetSamplingDimensions(int x, int y, int z)
{
  if (x < 2 || y < 2 || z < 2)
  {
    vtkErrorMacro("SamplingDimensions need at least 2 points per axis, got "
      << x << " " << y << " " << z << "; keeping " << this->SamplingDimensions[0] << " "
      << this->SamplingDimensions[1] << " " << this->SamplingDimensions[2]);
    return;
  }
  if (x != this->SamplingDimensions[0] || y != this->SamplingDimensions[1] ||
    z != this->SamplingDimensions[2])
  {
    this->SamplingDimensions[0] = x;
    this->SamplingDimensions[1] = y;
    this->SamplingDimensions[2] = z;
    this->MarkModified(); // resample again
  }
}

//------------------------------------------------------------------------------
int vtkPVMultiMaterialVolumeRepresentation::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  ++this->DataGeneration;
  this->Resampled = false;
  this->ResampleInfo.clear();
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkDataObject* input = inInfo ? inInfo->Get(vtkDataObject::DATA_OBJECT()) : nullptr;
  auto* blocks = vtkCompositeDataSet::SafeDownCast(input);
  auto* dataset = vtkDataSet::SafeDownCast(input);
  if (dataset && !vtkImageData::SafeDownCast(dataset))
  {
    return this->RequestResampledData(request, inInfo, dataset, outputVector);
  }
  // AMR's blocks overlap across levels (or differ in spacing): resampled,
  // not merged like image blocks that tile a box.
  if (auto* amr = vtkUniformGridAMR::SafeDownCast(input))
  {
    return this->RequestResampledData(request, inInfo, amr, outputVector);
  }
  if (!blocks)
  {
    return this->Superclass::RequestData(request, inputVector, outputVector);
  }
  // The base class draws image data: hand it the blocks merged. An error
  // leaves an empty image, so this rank still joins every collective call.
  std::string error;
  vtkSmartPointer<vtkImageData> merged = mmv::MergeImageBlocks(blocks, error);
  if (!merged)
  {
    vtkErrorMacro("cannot draw these blocks as one volume: " << error);
    merged = vtkSmartPointer<vtkImageData>::New();
  }
  vtkNew<vtkInformationVector> substitute;
  substitute->SetNumberOfInformationObjects(1);
  vtkInformation* info = substitute->GetInformationObject(0);
  info->Copy(inInfo);
  info->Set(vtkDataObject::DATA_OBJECT(), merged);
  info->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), merged->GetExtent(), 6);
  vtkInformationVector* inputs[1] = { substitute };
  return this->Superclass::RequestData(request, inputs, outputVector);
}

//------------------------------------------------------------------------------
int vtkPVMultiMaterialVolumeRepresentation::RequestResampledData(vtkInformation* request,
  vtkInformation* inInfo, vtkDataObject* data, vtkInformationVector* outputVector)
{
  // As Volume's "Resample To Image": an image over the data's bounds, cells
  // and points probed at its points; every rank takes part, and in parallel
  // each gets its piece of one global image (vtkPResampleToImage), so the
  // pieces meet in the global pre-filter as image pieces do. AMR blocks are
  // probed finest level first (vtkCompositeDataProbeFilter), so a point takes
  // the value of the finest block that holds it.
  const auto start = std::chrono::steady_clock::now();
  auto* dataset = vtkDataSet::SafeDownCast(data);
  auto* blocks = vtkCompositeDataSet::SafeDownCast(data);
  const vtkIdType cells =
    dataset ? dataset->GetNumberOfCells() : (blocks ? blocks->GetNumberOfCells() : 0);
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  const bool parallel = controller && controller->GetNumberOfProcesses() > 1;
  // Data without cells on every rank are not resampled: vtkPResampleToImage
  // dereferences a mask array that it never made (a crash under MPI), and
  // there is nothing to draw. A rank without cells still resamples when
  // another has some: its piece of the image comes from them.
  vtkIdType totalCells = cells;
  if (parallel)
  {
    controller->AllReduce(&cells, &totalCells, 1, vtkCommunicator::SUM_OP);
  }
  vtkSmartPointer<vtkImageData> image;
  if (totalCells > 0)
  {
    vtkSmartPointer<vtkResampleToImage> resample;
    if (parallel)
    {
      auto pieces = vtkSmartPointer<vtkPResampleToImage>::New();
      pieces->SetController(controller);
      resample = pieces;
    }
    else
    {
      resample = vtkSmartPointer<vtkResampleToImage>::New();
    }
    resample->SetUseInputBounds(true);
    resample->SetSamplingDimensions(this->SamplingDimensions);
    resample->SetInputDataObject(data);
    resample->Update();
    image = resample->GetOutput();
  }
  if (!image)
  {
    image = vtkSmartPointer<vtkImageData>::New();
  }
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::ostringstream text;
  text << data->GetClassName() << " (";
  if (auto* amr = vtkUniformGridAMR::SafeDownCast(data))
  {
    text << amr->GetTotalNumberOfBlocks() << " blocks in " << amr->GetNumberOfLevels()
         << " levels, ";
  }
  text << cells << " cells) ";
  if (totalCells > 0)
  {
    text << "resampled to " << this->SamplingDimensions[0] << "x" << this->SamplingDimensions[1]
         << "x" << this->SamplingDimensions[2] << " points in " << seconds << " s";
  }
  else
  {
    text << "not resampled: no cells";
  }
  this->ResampleInfo = text.str();
  this->Resampled = true;
  if (totalCells == 0 && (!parallel || controller->GetLocalProcessId() == 0))
  {
    vtkWarningMacro("the data have no cells: there is nothing to resample and nothing is drawn");
  }

  vtkNew<vtkInformationVector> substitute;
  substitute->SetNumberOfInformationObjects(1);
  vtkInformation* info = substitute->GetInformationObject(0);
  info->Copy(inInfo);
  info->Set(vtkDataObject::DATA_OBJECT(), image);
  int wholeExtent[6] = { 0, this->SamplingDimensions[0] - 1, 0, this->SamplingDimensions[1] - 1, 0,
    this->SamplingDimensions[2] - 1 };
  info->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(),
    totalCells > 0 ? wholeExtent : image->GetExtent(), 6);
  vtkInformationVector* inputs[1] = { substitute };
  return this->Superclass::RequestData(request, inputs, outputVector);
}

//------------------------------------------------------------------------------
int vtkPVMultiMaterialVolumeRepresentation::ProcessViewRequest(
  vtkInformationRequestKey* request_type, vtkInformation* inInfo, vtkInformation* outInfo)
{
  if (!this->Superclass::ProcessViewRequest(request_type, inInfo, outInfo))
  {
    return 0;
  }
  if (request_type == vtkPVView::REQUEST_UPDATE())
  {
    this->UpdateGlobalVolume();
  }
  else if (request_type == vtkPVView::REQUEST_RENDER())
  {
    this->PinReflectionBackground();
  }
  return 1;
}

//------------------------------------------------------------------------------
void vtkPVMultiMaterialVolumeRepresentation::PinReflectionBackground()
{
  // Before the render the renderer holds the view's background; while the
  // ranks draw for parallel compositing it is cleared to black, which the
  // reflections would otherwise show, unlike a serial render.
  auto* view = vtkPVRenderView::SafeDownCast(this->GetView());
  vtkMultiMaterialVolumeMapper* mapper = this->GetMultiMaterialMapper();
  if (!view || !mapper || !view->GetRenderer())
  {
    return;
  }
  vtkRenderer* renderer = view->GetRenderer();
  const double* bottom = renderer->GetBackground();
  const double* top = renderer->GetGradientBackground() ? renderer->GetBackground2() : bottom;
  mapper->SetReflectionBackground(bottom, top);
}

//------------------------------------------------------------------------------
void vtkPVMultiMaterialVolumeRepresentation::UpdateGlobalVolume()
{
  vtkMultiMaterialVolumeMapper* mapper = this->GetMultiMaterialMapper();
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  if (!mapper || !controller || controller->GetNumberOfProcesses() < 2)
  {
    return; // one process: the mapper lights its input, as without MPI
  }
  // Everything in the key is the same on every rank (proxy properties and the
  // count of RequestData), so every rank decides alike.
  std::string array;
  bool cells = false;
  vtkInformation* info = this->GetInputArrayInformation(0);
  if (info && info->Has(vtkDataObject::FIELD_NAME()))
  {
    const int association = info->Get(vtkDataObject::FIELD_ASSOCIATION());
    if (association == vtkDataObject::FIELD_ASSOCIATION_POINTS ||
      association == vtkDataObject::FIELD_ASSOCIATION_CELLS)
    {
      array = info->Get(vtkDataObject::FIELD_NAME());
      cells = association == vtkDataObject::FIELD_ASSOCIATION_CELLS;
    }
  }
  int component = 0;
  const int vectorMode = this->MapperVectorMode(component);
  const mmv::IlluminationSettings& own = mapper->GetSettings();
  const std::vector<double> key = { double(this->DataGeneration), own.IrradianceMemoryMB,
    own.IrradianceScale, double(vectorMode), double(component), double(cells) };
  if (key == this->GlobalKey && array == this->GlobalArray)
  {
    return;
  }
  this->GlobalKey = key;
  this->GlobalArray = array;

  mmv::GlobalPrefilterSettings settings;
  settings.BudgetMB = own.IrradianceMemoryMB;
  settings.Scale = own.IrradianceScale;
  std::string error;
  auto* piece = vtkImageData::SafeDownCast(this->Cache);
  // A vector is lit as the mapper reduces it (VectorMode), from the colour
  // map's settings, which every rank shares.
  vtkDataSetAttributes* attributes = nullptr;
  if (piece)
  {
    attributes = cells ? static_cast<vtkDataSetAttributes*>(piece->GetCellData())
                       : static_cast<vtkDataSetAttributes*>(piece->GetPointData());
  }
  vtkDataArray* scalars =
    attributes && !array.empty() ? attributes->GetArray(array.c_str()) : nullptr;
  vtkSmartPointer<vtkDataArray> reduced;
  if (scalars && scalars->GetNumberOfComponents() > 1 && vectorMode != mmv::VectorModeDisabled)
  {
    reduced = mmv::MakeVectorScalars(scalars, vectorMode, component, nullptr);
  }
  vtkSmartPointer<vtkImageData> litPiece;
  if (cells && scalars)
  {
    // Cell data are lit on each piece's grid of cell centres, as the mapper
    // lights them; the pieces' centres lie on one lattice, the whole
    // volume's cell centres.
    litPiece = mmv::MakeCellCentreImage(piece, reduced ? reduced.Get() : scalars);
    piece = litPiece;
  }
  else if (reduced)
  {
    litPiece = vtkSmartPointer<vtkImageData>::New();
    litPiece->ShallowCopy(piece);
    litPiece->GetPointData()->AddArray(reduced); // replaces the vector
    piece = litPiece;
  }
  const bool valid = mmv::ExchangeGlobalPrefilter(controller, piece,
    array.empty() ? nullptr : array.c_str(), settings, this->GlobalVolume, error);
  mapper->SetGlobalPrefilteredVolume(valid ? this->GlobalVolume.Get() : nullptr);
  std::ostringstream text;
  if (valid)
  {
    int dims[3];
    this->GlobalVolume->GetIrradianceDimensions(dims);
    text << dims[0] << "x" << dims[1] << "x" << dims[2] << " global grid over "
         << controller->GetNumberOfProcesses() << " ranks; "
         << this->GlobalVolume->GetBytesExchanged() << " bytes sent per rank; "
         << this->GlobalVolume->GetExchangeSeconds() << " s";
  }
  else if (!array.empty() && error != "no piece has data")
  {
    text << "no global shadows: " << error;
    // Every rank knows; one message is enough.
    if (controller->GetLocalProcessId() == 0)
    {
      vtkErrorMacro(
        "the pieces cannot be lit together (" << error << "); each rank lights its own piece");
    }
  }
  this->GlobalInfo = text.str();
}

const char* vtkPVMultiMaterialVolumeRepresentation::GetGlobalIrradianceInfo()
{
  return this->GlobalInfo.c_str();
}

//------------------------------------------------------------------------------
void vtkPVMultiMaterialVolumeRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "MaterialPreset: \"" << this->MaterialPreset << "\"\n";
  os << indent << "MaterialNodes: " << this->CustomMaterials->GetSize() << " nodes\n";
  os << indent << "PointLightRadius: " << this->PointLightRadius << "\n";
  os << indent << "LightFalloff: " << this->LightFalloff << "\n";
  os << indent << "SampleDistance: " << this->SampleDistance << "\n";
  os << indent << "AutoAdjustSampleDistances: " << this->AutoAdjustSampleDistances << "\n";
  os << indent << "LockSampleDistanceToInputSpacing: " << this->LockSampleDistanceToInputSpacing
     << "\n";
  os << indent << "IrradianceCacheMB: " << this->IrradianceCacheMB << "\n";
  os << indent << "LightingQuality: " << this->LightingQuality << "\n";
  // The mapper's settings: the mapper's PrintSelf.
  os << indent << "SamplingDimensions: " << this->SamplingDimensions[0] << " "
     << this->SamplingDimensions[1] << " " << this->SamplingDimensions[2] << "\n";
  os << indent << "ResampleInfo: " << this->ResampleInfo << "\n";
}
