#include "vtkPVMultiMaterialVolumeRepresentation.h"

#include "vtkColorTransferFunction.h"
#include "vtkMaterialLibrary.h"
#include "vtkMultiMaterialVolumeMapper.h"
#include "vtkObjectFactory.h"
#include "vtkVolumeProperty.h"

vtkStandardNewMacro(vtkPVMultiMaterialVolumeRepresentation);

namespace
{
// The MaterialPreset value that selects MaterialNodes (the domain's none_string).
constexpr const char* CustomPreset = "Custom";
}

//------------------------------------------------------------------------------
vtkPVMultiMaterialVolumeRepresentation::vtkPVMultiMaterialVolumeRepresentation()
{
  // The base class drives whatever mapper sits here; ours is a
  // vtkOpenGLGPUVolumeRayCastMapper, so everything generic keeps working.
  vtkNew<vtkMultiMaterialVolumeMapper> mapper;
  mapper->SetMaterialTransferFunction(this->Materials);
  this->VolumeMapper = mapper;

  this->AppliedNodes->SetName("MaterialNodes");
  vtkNew<vtkMaterialLibrary> library;
  for (int i = 0; i < library->GetNumberOfPresets(); ++i)
  {
    this->PresetNames->InsertNextValue(library->GetPresetName(i));
  }
}

//------------------------------------------------------------------------------
vtkPVMultiMaterialVolumeRepresentation::~vtkPVMultiMaterialVolumeRepresentation() = default;

//------------------------------------------------------------------------------
vtkMultiMaterialVolumeMapper* vtkPVMultiMaterialVolumeRepresentation::GetMultiMaterialMapper()
{
  return vtkMultiMaterialVolumeMapper::SafeDownCast(this->VolumeMapper);
}

//------------------------------------------------------------------------------
void vtkPVMultiMaterialVolumeRepresentation::SetNumberOfMaterialNodeValues(int count)
{
  if (this->PendingNodes.Announce(count) &&
    this->PendingNodes.Apply(this, this->CustomMaterials))
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
      vtkErrorMacro("Unknown material preset \"" << value << "\". Keeping \""
                                                  << this->MaterialPreset << "\".");
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

  // vtkSetMacro only bumps the mapper's MTime on a real change, so setting
  // these every frame costs nothing.
  mapper->SetIrradianceMemoryMB(this->IrradianceMemoryMB);
  mapper->SetIrradianceScale(this->IrradianceScale);
  mapper->SetMultipleScattering(this->MultipleScattering);
  mapper->SetPreIntegration(this->PreIntegration);
  mapper->SetPointLightRadius(this->PointLightRadius);
  mapper->SetSampleDistance(static_cast<float>(this->SampleDistance));
  mapper->SetAutoAdjustSampleDistances(this->AutoAdjustSampleDistances);
  mapper->SetLockSampleDistanceToInputSpacing(this->LockSampleDistanceToInputSpacing);
  mapper->SetInteractiveIrradiance(this->InteractiveIrradiance);
  mapper->SetShadowEstimation(this->ShadowEstimation);
  mapper->SetPiecewiseShadowSlices(this->PiecewiseShadowSlices);
}

//------------------------------------------------------------------------------
// Setters only record the value: UpdateMapperParameters() hands it to the mapper
// at the next render. Modified(), not MarkModified(): re-executing the
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
vtkPVMMVSetter(IrradianceMemoryMB, double);
vtkPVMMVSetter(IrradianceScale, double);
vtkPVMMVSetter(MultipleScattering, bool);
vtkPVMMVSetter(PreIntegration, bool);
vtkPVMMVSetter(PointLightRadius, double);
vtkPVMMVSetter(SampleDistance, double);
vtkPVMMVSetter(AutoAdjustSampleDistances, bool);
vtkPVMMVSetter(LockSampleDistanceToInputSpacing, bool);
vtkPVMMVSetter(InteractiveIrradiance, int);
vtkPVMMVSetter(ShadowEstimation, int);
vtkPVMMVSetter(PiecewiseShadowSlices, int);
#undef vtkPVMMVSetter

//------------------------------------------------------------------------------
int vtkPVMultiMaterialVolumeRepresentation::GetIrradianceUpdateCount()
{
  auto* mapper = this->GetMultiMaterialMapper();
  return mapper ? mapper->GetIrradianceUpdateCount() : 0;
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

double vtkPVMultiMaterialVolumeRepresentation::GetLastIrradianceSeconds()
{
  auto* mapper = this->GetMultiMaterialMapper();
  return mapper ? mapper->GetLastIrradianceSeconds() : 0.0;
}

const char* vtkPVMultiMaterialVolumeRepresentation::GetIrradianceResolutionInfo()
{
  auto* mapper = this->GetMultiMaterialMapper();
  return mapper ? mapper->GetIrradianceResolutionReason() : "";
}

int vtkPVMultiMaterialVolumeRepresentation::GetMultiMaterialActive()
{
  auto* mapper = this->GetMultiMaterialMapper();
  return mapper && mapper->GetMultiMaterialActive() ? 1 : 0;
}

//------------------------------------------------------------------------------
void vtkPVMultiMaterialVolumeRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "MaterialPreset: \"" << this->MaterialPreset << "\"\n";
  os << indent << "MaterialNodes: " << this->CustomMaterials->GetSize() << " nodes\n";
  os << indent << "IrradianceMemoryMB: " << this->IrradianceMemoryMB << "\n";
  os << indent << "IrradianceScale: " << this->IrradianceScale << "\n";
  os << indent << "MultipleScattering: " << this->MultipleScattering << "\n";
  os << indent << "PreIntegration: " << this->PreIntegration << "\n";
  os << indent << "PointLightRadius: " << this->PointLightRadius << "\n";
  os << indent << "SampleDistance: " << this->SampleDistance << "\n";
  os << indent << "AutoAdjustSampleDistances: " << this->AutoAdjustSampleDistances << "\n";
  os << indent << "LockSampleDistanceToInputSpacing: " << this->LockSampleDistanceToInputSpacing
     << "\n";
  os << indent << "InteractiveIrradiance: " << this->InteractiveIrradiance << "\n";
  os << indent << "ShadowEstimation: " << this->ShadowEstimation << "\n";
  os << indent << "PiecewiseShadowSlices: " << this->PiecewiseShadowSlices << "\n";
}
