#include "vtkMultiMaterialVolumeMapper.h"

#include "vtkCellData.h"
#include "vtkColorTransferFunction.h"
#include "vtkDataArray.h"
#include "vtkGlobalPrefilteredVolume.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkIrradianceEstimator.h"
#include "vtkLightCollection.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMatrix4x4.h"
#include "vtkMultiMaterialEnvironment.h"
#include "vtkMultiMaterialFields.h"
#include "vtkMultiMaterialInputCheck.h"
#include "vtkMultiMaterialIrradianceStage.h"
#include "vtkMultiMaterialLights.h"
#include "vtkMultiMaterialLiveObjects.h"
#include "vtkMultiMaterialParameters.h"
#include "vtkMultiMaterialReflection.h"
#include "vtkMultiMaterialSceneShadows.h"
#include "vtkMultiMaterialShaderAssembly.h"
#include "vtkMultiMaterialShaderHook.h"
#include "vtkMultiMaterialShadingUniforms.h"
#include "vtkMultiMaterialSky.h"
#include "vtkMultiMaterialStageClock.h"
#include "vtkMultiMaterialTextures.h"
#include "vtkMultiMaterialThreads.h"
#include "vtkMultiMaterialVolumeGeometry.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPreIntegrationTable.h"
#include "vtkReflectionVisibilityPass.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkSmartPointer.h"
#include "vtkTextureObject.h"
#include "vtkValueGradient.h"
#include "vtkVectorScalarsCache.h"
#include "vtkVolume.h"
#include "vtkVolumeBricking.h"
#include "vtkVolumeInputHelper.h"
#include "vtkVolumeInputScalars.h"
#include "vtkVolumeProperty.h"
#include "vtkVolumeTexture.h"
#include "vtk_glew.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <set>
#include <sstream>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkMultiMaterialVolumeMapper);

namespace
{
using Clock = std::chrono::steady_clock;

double Seconds(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}
}

class vtkMultiMaterialVolumeMapper::vtkInternals
{
public:
  // The fields shaded (their materials, segment tables and the lighting's
  // field).
  vtkMultiMaterialFields Fields;
  vtkMaterialTransferFunction* Materials() const { return this->Fields.GetMaterials(0); }
  // The whole volume when the input is one piece of it (global shadows).
  vtkSmartPointer<vtkGlobalPrefilteredVolume> Global;
  vtkGlobalPrefilteredVolume* ActiveGlobal() const
  {
    return this->Global && this->Global->GetValid() ? this->Global.Get() : nullptr;
  }
  // The value range the estimator's and the gradient's normalisation use: the
  // global one when the input is one piece of a volume, else the piece's.
  const double* ValueRange(const double pieceRange[2]) const
  {
    vtkGlobalPrefilteredVolume* global = this->ActiveGlobal();
    return global ? global->GetScalarRange() : pieceRange;
  }
  vtkNew<vtkMultiMaterialTextures> Textures;
  vtkMultiMaterialIrradianceStage Irradiance;
  vtkMultiMaterialSky Sky;                   // the environment light
  vtkMultiMaterialSceneShadows SceneShadows; // with the renderer's other volumes
  mmv::StageClock PrepareStages;             // where the last preparation went
  vtkNew<vtkMultiMaterialShaderHook> ShaderHook;

  // The lights of this frame, in object space.
  std::vector<mmv::ShadingLight> Lights;
  std::vector<int> LightOrder; // the collection indices' order (OrderForIrradianceTextures)
  // The ray cast's uniforms of this frame, set whenever VTK binds its program.
  vtkMultiMaterialShadingUniforms Uniforms;
  vtkNew<vtkMultiMaterialReflection> Reflection; // eq. 17's c_r and visibility

  std::set<std::string> Warnings;

  // Cell scalars are lit on the image of the cell centres; rebuilt only when
  // the input or its scalars change, so the stages' MTime keys hold.
  vtkSmartPointer<vtkImageData> CellCentres;
  vtkImageData* CellCentresOf = nullptr;
  vtkDataArray* CellCentresScalars = nullptr;
  vtkMTimeType CellCentresTime = 0;
  vtkImageData* CellCentreImage(vtkImageData* image, vtkDataArray* scalars)
  {
    const vtkMTimeType time = std::max(image->GetMTime(), scalars->GetMTime());
    if (!this->CellCentres || image != this->CellCentresOf || scalars != this->CellCentresScalars ||
      time != this->CellCentresTime)
    {
      this->CellCentres = mmv::MakeCellCentreImage(image, scalars);
      this->CellCentresOf = image;
      this->CellCentresScalars = scalars;
      this->CellCentresTime = time;
    }
    return this->CellCentres;
  }

  std::string LastFieldError; // FieldArrays' problem, reported once until it changes

  // The one-component arrays VectorMode made of vectors: the same array for
  // the same vector, so that kept steps' irradiance matches its key.
  vtkVectorScalarsCache Reduced;
  std::string LastVectorError; // reported once until it changes
  int DrawnComponents = 0;     // of the scalars the ray caster drew last

  void SetUniforms(vtkShaderProgram* program)
  {
    this->Uniforms.Apply(
      program, this->Textures, this->Fields.GetTableSize(), this->Irradiance.GetEstimator());
    if (this->Uniforms.GetVariant().Sky)
    {
      this->Sky.SetUniforms(program);
    }
  }
  void ActivateTextures(bool on)
  {
    this->Uniforms.ActivateTextures(on, this->Textures, this->Irradiance.GetEstimator());
    if (this->Uniforms.GetVariant().Sky)
    {
      on ? this->Sky.Activate() : this->Sky.Deactivate();
    }
  }
};

//------------------------------------------------------------------------------
vtkMultiMaterialVolumeMapper::vtkMultiMaterialVolumeMapper()
  : Internals(new vtkInternals)
{
  vtkMultiMaterialLiveObjects::Constructed("vtkMultiMaterialVolumeMapper");
  this->Internals->ShaderHook->SetOwner(this);
  vtkInternals* internals = this->Internals;
  this->Internals->ShaderHook->SetParameterCallback(
    [internals](vtkShaderProgram* program) { internals->SetUniforms(program); });
}

vtkMultiMaterialVolumeMapper::~vtkMultiMaterialVolumeMapper()
{
  // The hook may outlive us in a volume's keys: leave it inert.
  this->Internals->ShaderHook->SetOwner(nullptr);
  this->Internals->ShaderHook->SetParameterCallback(nullptr);
  this->Internals->ShaderHook->SetFragmentReplacements({});
  delete this->Internals;
  vtkMultiMaterialLiveObjects::Destroyed("vtkMultiMaterialVolumeMapper");
}

void vtkMultiMaterialVolumeMapper::SetMaterialTransferFunction(vtkMaterialTransferFunction* m)
{
  this->SetFieldMaterialTransferFunction(0, m);
}

vtkMaterialTransferFunction* vtkMultiMaterialVolumeMapper::GetMaterialTransferFunction()
{
  return this->Internals->Materials();
}

void vtkMultiMaterialVolumeMapper::SetFieldMaterialTransferFunction(
  int field, vtkMaterialTransferFunction* m)
{
  if (field < 0 || field >= mmv::MaxFields)
  {
    vtkErrorMacro("field " << field << " is out of [0, " << mmv::MaxFields - 1
                           << "]: the materials are not set");
    return;
  }
  if (this->Internals->Fields.GetMaterials(field) != m)
  {
    this->Internals->Fields.SetMaterials(field, m);
    this->Modified();
  }
}

vtkMaterialTransferFunction* vtkMultiMaterialVolumeMapper::GetFieldMaterialTransferFunction(
  int field)
{
  if (field < 0 || field >= mmv::MaxFields)
  {
    vtkErrorMacro("field " << field << " is out of [0, " << mmv::MaxFields - 1 << "]");
    return nullptr;
  }
  return this->Internals->Fields.GetMaterials(field);
}

void vtkMultiMaterialVolumeMapper::SetGlobalPrefilteredVolume(vtkGlobalPrefilteredVolume* volume)
{
  if (this->Internals->Global != volume)
  {
    this->Internals->Global = volume;
    this->Modified();
  }
}

// The reflection's and the sky's environments keep the pinned colours (they
// read them in every Update instead of the renderer's).
void vtkMultiMaterialVolumeMapper::SetReflectionBackground(
  const double bottom[3], const double top[3])
{
  const bool sky = this->Internals->Sky.GetEnvironment()->SetBackgroundOverride(bottom, top);
  if (this->Internals->Reflection->GetEnvironment()->SetBackgroundOverride(bottom, top) || sky)
  {
    this->Modified();
  }
}

void vtkMultiMaterialVolumeMapper::ClearReflectionBackground()
{
  const bool sky = this->Internals->Sky.GetEnvironment()->ClearBackgroundOverride();
  if (this->Internals->Reflection->GetEnvironment()->ClearBackgroundOverride() || sky)
  {
    this->Modified();
  }
}

vtkGlobalPrefilteredVolume* vtkMultiMaterialVolumeMapper::GetGlobalPrefilteredVolume()
{
  return this->Internals->Global;
}

vtkMTimeType vtkMultiMaterialVolumeMapper::GetMTime()
{
  vtkMTimeType t = this->Superclass::GetMTime();
  if (this->Internals->Global)
  {
    t = std::max(t, this->Internals->Global->GetMTime());
  }
  return std::max(t, this->Internals->Fields.GetMaterialsMTime());
}

bool vtkMultiMaterialVolumeMapper::ReadIrradiance(
  vtkRenderWindow* window, int light, std::vector<float>& values)
{
  auto* context = vtkOpenGLRenderWindow::SafeDownCast(window);
  if (!context || light < 0 || light >= this->NumberOfShadedLights)
  {
    vtkErrorMacro("ReadIrradiance: no irradiance for light " << light);
    return false;
  }
  context->MakeCurrent();
  return this->Internals->Irradiance.GetEstimator()->ReadBack(context, light, values);
}

vtkIrradianceEstimator* vtkMultiMaterialVolumeMapper::GetIrradianceEstimator()
{
  return this->Internals->Irradiance.GetEstimator();
}

std::string vtkMultiMaterialVolumeMapper::GetLastFragmentShaderSource()
{
  return this->Internals->ShaderHook->GetLastFragmentSource();
}

size_t vtkMultiMaterialVolumeMapper::GetIrradianceCacheBytes()
{
  return this->Internals->Irradiance.GetStepCacheBytes();
}

int vtkMultiMaterialVolumeMapper::GetGradientUploadCount()
{
  return this->Internals->Textures->GetGradientUploads();
}

vtkIdType vtkMultiMaterialVolumeMapper::GetMultiMaterialMemoryBytes()
{
  return this->Internals->Irradiance.GetEstimator()->GetTextureMemoryBytes() +
    this->Internals->Textures->GetMemoryBytes();
}

void vtkMultiMaterialVolumeMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Internals->Textures->ReleaseGraphicsResources(window);
  this->Internals->Irradiance.ReleaseGraphicsResources(window);
  this->Internals->Sky.ReleaseGraphicsResources(window);
  this->Internals->SceneShadows.ReleaseGraphicsResources(window);
  this->Internals->Reflection->ReleaseGraphicsResources(window);
  this->Superclass::ReleaseGraphicsResources(window);
}

void vtkMultiMaterialVolumeMapper::SetPartitions(
  unsigned short x, unsigned short y, unsigned short z)
{
  this->PartitionsRequested = static_cast<int>(x) * y * z > 1;
  this->RequestedPartitions[0] = x;
  this->RequestedPartitions[1] = y;
  this->RequestedPartitions[2] = z;
  this->Superclass::SetPartitions(x, y, z);
  std::copy(this->RequestedPartitions, this->RequestedPartitions + 3, this->BrickPartitions);
}

bool vtkMultiMaterialVolumeMapper::FitBricksToTextureLimit(vtkRenderer* ren)
{
  auto* image = vtkImageData::SafeDownCast(this->GetInput());
  auto* context = vtkOpenGLRenderWindow::SafeDownCast(ren->GetRenderWindow());
  if (!image || !context)
  {
    return true; // the base class reports what it cannot render
  }
  int dims[3];
  image->GetDimensions(dims);
  const int maxSize = vtkTextureObject::GetMaximumTextureSize3D(context);
  int parts[3];
  int cellFlag = 0;
  vtkDataArray* scalars = vtkAbstractMapper::GetScalars(
    image, this->ScalarMode, this->ArrayAccessMode, this->ArrayId, this->ArrayName, cellFlag);
  const double bytesPerPoint =
    scalars ? scalars->GetDataTypeSize() * scalars->GetNumberOfComponents() : 4.0;
  if (maxSize <= 0 ||
    !mmv::ChooseBrickPartitions(dims, maxSize, this->RequestedPartitions, parts) ||
    !mmv::LimitBrickBytes(dims, bytesPerPoint, this->Settings.MaxBrickMB * 1024.0 * 1024.0, parts))
  {
    vtkErrorMacro("the volume (" << dims[0] << " x " << dims[1] << " x " << dims[2]
                                 << " points) cannot be cut into bricks that fit the largest 3D "
                                    "texture of this OpenGL context ("
                                 << maxSize << ") and MaxBrickMB; not rendering it");
    return false;
  }
  if (!std::equal(parts, parts + 3, this->BrickPartitions))
  {
    // VTK partitions the texture when it next uploads the data.
    this->Superclass::SetPartitions(static_cast<unsigned short>(parts[0]),
      static_cast<unsigned short>(parts[1]), static_cast<unsigned short>(parts[2]));
    std::copy(parts, parts + 3, this->BrickPartitions);
  }
  if (!std::equal(parts, parts + 3, this->RequestedPartitions))
  {
    std::ostringstream message;
    message << "the volume (" << dims[0] << " x " << dims[1] << " x " << dims[2]
            << " points) is larger than the largest 3D texture of this OpenGL context (" << maxSize
            << ") or MaxBrickMB (" << this->Settings.MaxBrickMB << "): rendered in " << parts[0]
            << " x " << parts[1] << " x " << parts[2] << " bricks";
    this->WarnOnce(message.str());
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkMultiMaterialVolumeMapper::SetVectorComponent(int component)
{
  if (component < 0)
  {
    vtkErrorMacro("VectorComponent must be 0 or more (the first component is 0), got "
      << component << "; keeping " << this->VectorComponent);
    return;
  }
  if (component != this->VectorComponent)
  {
    this->VectorComponent = component;
    this->Modified();
  }
}

void vtkMultiMaterialVolumeMapper::Render(vtkRenderer* ren, vtkVolume* vol)
{
  if (!this->SelectDrawnScalars(ren))
  {
    return;
  }
  this->Superclass::Render(ren, vol);
}

namespace
{
// Puts `wanted` where `current` is in `attributes` (same name, or the active
// scalars when unnamed); false when neither finds it.
bool ReplaceArray(vtkDataSetAttributes* attributes, vtkDataArray* current, vtkDataArray* wanted)
{
  if (current == wanted)
  {
    return true;
  }
  if (current->GetName() && current->GetName()[0] && wanted->GetName() &&
    strcmp(current->GetName(), wanted->GetName()) == 0)
  {
    attributes->AddArray(wanted); // replaces the array of that name, in place
    return attributes->GetArray(wanted->GetName()) == wanted;
  }
  if (attributes->GetScalars() == current)
  {
    attributes->SetScalars(wanted);
    return true;
  }
  return false;
}
}

void vtkMultiMaterialVolumeMapper::AddFieldArray(const char* name)
{
  if (!name || !name[0])
  {
    vtkErrorMacro("a field array needs a name");
    return;
  }
  this->FieldArrays.emplace_back(name);
  this->Modified();
}

void vtkMultiMaterialVolumeMapper::RemoveAllFieldArrays()
{
  if (!this->FieldArrays.empty())
  {
    this->FieldArrays.clear();
    this->Modified();
  }
}

void vtkMultiMaterialVolumeMapper::SetFieldArrays(const std::vector<std::string>& names)
{
  if (names != this->FieldArrays)
  {
    this->RemoveAllFieldArrays();
    for (const std::string& name : names)
    {
      this->AddFieldArray(name.c_str());
    }
  }
}

const char* vtkMultiMaterialVolumeMapper::GetFieldArray(int i) const
{
  return i >= 0 && i < this->GetNumberOfFieldArrays() ? this->FieldArrays[i].c_str() : nullptr;
}

vtkDataArray* vtkMultiMaterialVolumeMapper::WithFieldArrays(
  vtkDataSet* input, int cellFlag, vtkDataArray* scalars)
{
  vtkInternals& in = *this->Internals;
  if (this->FieldArrays.empty())
  {
    return scalars;
  }
  vtkDataSetAttributes* attributes = cellFlag == 1
    ? static_cast<vtkDataSetAttributes*>(input->GetCellData())
    : static_cast<vtkDataSetAttributes*>(input->GetPointData());
  std::string error;
  vtkDataArray* fielded = in.Fields.WithArrays(scalars, attributes, this->FieldArrays, &error);
  if (!fielded && error != in.LastFieldError)
  {
    vtkErrorMacro("field arrays: " << error << "; shading the scalars alone");
  }
  in.LastFieldError = error;
  return fielded ? fielded : scalars;
}

bool vtkMultiMaterialVolumeMapper::SelectDrawnScalars(vtkRenderer* ren)
{
  vtkInternals& in = *this->Internals;
  vtkDataSet* input = this->GetInput();
  if (!input || this->GetNumberOfInputConnections(0) < 1)
  {
    return true; // the base class reports a missing input
  }
  // What ValidateInput would do first, so that the copy holds this data.
  this->GetInputAlgorithm(0, 0)->Update();
  input = this->GetInput();
  int cellFlag = 0;
  vtkDataArray* original = input
    ? vtkAbstractMapper::GetScalars(
        input, this->ScalarMode, this->ArrayAccessMode, this->ArrayId, this->ArrayName, cellFlag)
    : nullptr;
  if (!original || (cellFlag != 0 && cellFlag != 1))
  {
    return true; // the base class reports missing or field scalars
  }
  vtkDataArray* wanted = original;
  if (this->VectorMode != mmv::VectorModeDisabled && original->GetNumberOfComponents() > 1)
  {
    in.Reduced.SetKeepAll(this->Settings.IrradianceCacheMB > 0.0);
    std::string error;
    wanted = in.Reduced.Get(original, this->VectorMode, this->VectorComponent, &error);
    if (!wanted)
    {
      if (error != in.LastVectorError)
      {
        vtkErrorMacro("VectorComponent " << this->VectorComponent << ": " << error
                                         << "; not rendering the volume");
        in.LastVectorError = error;
      }
      return false;
    }
    in.LastVectorError.clear();
  }
  wanted = this->WithFieldArrays(input, cellFlag, wanted);
  // The copy VTK draws (made here as ValidateInput would, and kept by it as
  // long as the input does not change): it gets `wanted` in the vector's
  // place, or the original back when VectorMode no longer reduces it.
  this->CloneInputs();
  vtkDataSet* copy = this->GetTransformedInput(0);
  if (!copy)
  {
    return true;
  }
  int copyFlag = 0;
  vtkDataArray* current = vtkAbstractMapper::GetScalars(
    copy, this->ScalarMode, this->ArrayAccessMode, this->ArrayId, this->ArrayName, copyFlag);
  if (!current)
  {
    return true;
  }
  vtkDataSetAttributes* attributes = copyFlag == 1
    ? static_cast<vtkDataSetAttributes*>(copy->GetCellData())
    : static_cast<vtkDataSetAttributes*>(copy->GetPointData());
  if (!ReplaceArray(attributes, current, wanted))
  {
    vtkErrorMacro("cannot select a vector's "
      << (this->VectorMode == mmv::VectorModeMagnitude ? "magnitude" : "component")
      << " of an unnamed array that is not the active scalars; name the array; not rendering "
         "the volume");
    return false;
  }
  // VTK 9.2's ray caster keeps its transfer-function tables per component of
  // the first scalars it drew and crashes (vtkVolumeInputHelper::
  // RefreshTransferFunction) when the scalars of the same input gain
  // components: start its resources afresh (DataInputs.
  // SwitchingFromAScalarToAVectorArrayDoesNotCrash).
  const int components = wanted->GetNumberOfComponents();
  if (in.DrawnComponents != 0 && components != in.DrawnComponents && ren && ren->GetRenderWindow())
  {
    this->ReleaseGraphicsResources(ren->GetRenderWindow());
  }
  in.DrawnComponents = components;
  return true;
}

//------------------------------------------------------------------------------
void vtkMultiMaterialVolumeMapper::GPURender(vtkRenderer* ren, vtkVolume* vol)
{
  vtkInternals& in = *this->Internals;
  if (!this->FitBricksToTextureLimit(ren))
  {
    return; // VTK would abort in vtkTextureObject::Bind
  }
  vtkInformation* keys = vol->GetPropertyKeys();
  if (!keys)
  {
    vtkNew<vtkInformation> newKeys;
    vol->SetPropertyKeys(newKeys);
    keys = newKeys;
  }

  const auto prepareStart = Clock::now();
  const int updatesBefore = this->IrradianceUpdateCount;
  mmv::RunOnAllCores([&]() { this->MultiMaterialActive = this->PrepareMultiMaterial(ren, vol); });
  this->LastPrepareSeconds = Seconds(prepareStart) -
    (this->IrradianceUpdateCount != updatesBefore ? this->LastIrradianceSeconds : 0.0);
  if (!this->MultiMaterialActive)
  {
    // Exactly the base class: no pass in the volume's keys.
    in.ShaderHook->SetFragmentReplacements({});
    in.ShaderHook->RemoveFrom(keys);
    this->Superclass::GPURender(ren, vol);
    return;
  }

  in.ShaderHook->InstallInto(keys);
  in.ActivateTextures(true);
  const auto start = Clock::now();
  if (this->Settings.TimeStages)
  {
    glFinish();
  }
  this->Superclass::GPURender(ren, vol);
  if (this->Settings.TimeStages)
  {
    glFinish();
    this->LastRayCastSeconds = Seconds(start);
  }
  in.ActivateTextures(false);
  ++this->RayCastCount;
}

//------------------------------------------------------------------------------
void vtkMultiMaterialVolumeMapper::WarnOnce(const std::string& message)
{
  if (this->Internals->Warnings.insert(message).second)
  {
    vtkWarningMacro(<< message);
  }
}

//------------------------------------------------------------------------------
bool vtkMultiMaterialVolumeMapper::PrepareMultiMaterial(vtkRenderer* ren, vtkVolume* vol)
{
  mmv::StageClock& clock = this->Internals->PrepareStages;
  clock.Start();
  const mmv::InputCheck input = mmv::CheckMultiMaterialInputs(this, ren, vol);
  if (!input.Caveat.empty())
  {
    this->WarnOnce(input.Caveat);
  }
  if (!input.Supported)
  {
    if (!input.Reason.empty())
    {
      this->WarnOnce(input.Reason);
    }
    return false;
  }
  vtkInternals& in = *this->Internals;
  if (!in.Fields.SetScalars(input.Scalars))
  {
    return false; // more fields than the input check lets through
  }
  this->NumberOfFields = in.Fields.GetNumberOfFields();
  const bool bricks =
    this->BrickPartitions[0] * this->BrickPartitions[1] * this->BrickPartitions[2] > 1;
  if (this->NumberOfFields > 1 && (bricks || in.ActiveGlobal()))
  {
    this->WarnOnce("several fields in bricks (partitions) or in pieces of a distributed volume "
                   "are not lit with materials; using VTK's shading");
    return false;
  }
  // From here on the lighting reads one field: the data, or the several
  // fields' combined extinction, over its own range.
  if (!this->UpdateFieldLighting(vol, input.Scalars))
  {
    return false;
  }
  vtkDataArray* lighting = in.Fields.GetLightingScalars(input.Scalars);
  const double* range = in.Fields.GetRange(0);
  const double* lightingRange = in.Fields.GetLightingRange(range);
  vtkImageData* image = input.Image;
  if (input.CellData)
  {
    if (bricks)
    {
      this->WarnOnce("cell scalars in bricks (partitions) are not lit with materials; using "
                     "VTK's shading");
      return false;
    }
    image = in.CellCentreImage(input.Image, lighting);
    if (!image)
    {
      this->WarnOnce("the cell scalars do not fill the image's cells; using VTK's shading");
      return false;
    }
  }
  in.Uniforms.SetCellData(input.CellData);

  // 1. Segment tables (pre-integration): only when the TFs or the step change.
  // From here on the lighting works on `image`: the input, or for cell
  // scalars the grid of the cell centres (the sampling step follows the
  // input, as VTK's does).
  clock.Mark("input");
  vtkDataArray* normals = in.Fields.GetGradientScalars(input.Scalars);
  if (!this->UpdateSegmentTables(input.Context, vol, input.Image))
  {
    return false;
  }
  clock.Mark("tables");
  if (!this->UpdateGradient(input.Context, image, normals, in.Fields.GetGradientRange(range)))
  {
    return false;
  }
  clock.Mark("gradient");

  // 2. Lights, in the volume's object space.
  vtkNew<vtkMatrix4x4> worldToObject;
  vtkMatrix4x4::Invert(vol->GetMatrix(), worldToObject);
  this->CollectShadedLights(ren, worldToObject);
  clock.Mark("lights");

  // 3. The irradiance volume: only when lights, opacity, materials or data change.
  this->LastRenderInteractive = vol->GetAllocatedRenderTime() < 1.0;
  this->NumberOfUpdatedLights = 0;
  if (!in.Lights.empty() &&
    !this->UpdateIrradiance(ren, vol, image, lighting, lightingRange, worldToObject))
  {
    return false;
  }

  clock.Mark("irradiance");

  // 4. The environment light: only when the data or the opacity change.
  this->SkyShaded = this->UpdateSky(ren, image, lighting, lightingRange,
    in.Fields.GetLightingProperty(vol->GetProperty()), worldToObject);
  clock.Mark("sky");

  // 5. The shader variant and the per-frame uniforms.
  this->UpdateShading(ren, image, worldToObject, range);
  clock.Mark("shading");
  return true;
}

bool vtkMultiMaterialVolumeMapper::UpdateIrradiance(vtkRenderer* ren, vtkVolume* vol,
  vtkImageData* image, vtkDataArray* scalars, const double range[2], vtkMatrix4x4* worldToObject)
{
  vtkInternals& in = *this->Internals;
  mmv::IrradianceStageInputs inputs;
  inputs.Renderer = ren;
  inputs.Volume = vol;
  inputs.Image = image;
  inputs.Scalars = scalars;
  inputs.PieceRange = range;
  inputs.Global = in.ActiveGlobal();
  inputs.Materials = in.Fields.GetLightingMaterials();
  inputs.Property = in.Fields.GetLightingProperty(vol->GetProperty());
  inputs.Lights = &in.Lights;
  int droppedPlanes = 0;
  inputs.Cut = mmv::MakeCutaway(this, worldToObject, &droppedPlanes);
  if (droppedPlanes > 0)
  {
    this->WarnOnce("more than " + std::to_string(mmv::MaxCutPlanes) +
      " clipping planes: the shadow rays ignore the others");
  }
  // The other volumes shadow this one.
  in.SceneShadows.Gather(ren, vol, this);
  if (in.SceneShadows.GetOverlapping())
  {
    this->WarnOnce("this volume's box overlaps another multi-material volume's: VTK draws "
                   "each volume's ray cast over the other's, not along one ray, so their "
                   "overlap is blended by drawing order; merge volumes that overlap into one "
                   "image with a field each (vtkVolumesToFields, ParaView's Volumes To "
                   "Fields) and shade the fields together (FieldArrays)");
  }
  inputs.Scene = &in.SceneShadows;
  inputs.Settings = this->Settings;
  inputs.Interactive = this->LastRenderInteractive;
  inputs.Reporter = this;
  mmv::IrradianceStageReport report;
  const bool updated = in.Irradiance.Update(inputs, report);
  for (const std::string& warning : report.Warnings)
  {
    this->WarnOnce(warning);
  }
  if (report.GridSet)
  {
    std::copy(report.Dimensions, report.Dimensions + 3, this->IrradianceDimensions);
  }
  this->NumberOfUpdatedLights = report.UpdatedLights;
  if (report.UpdatedLights > 0)
  {
    ++this->IrradianceUpdateCount;
    this->DiffusionPassCount += report.DiffusionPasses;
    this->LastIrradianceSeconds = report.Seconds;
  }
  this->DeferredIrradianceCount += report.Deferred ? 1 : 0;
  this->IrradianceCacheHitCount += report.CacheHit ? 1 : 0;
  return updated;
}

bool vtkMultiMaterialVolumeMapper::UpdateSky(vtkRenderer* ren, vtkImageData* image,
  vtkDataArray* scalars, const double range[2], vtkVolumeProperty* property,
  vtkMatrix4x4* worldToObject)
{
  vtkInternals& in = *this->Internals;
  mmv::SkyInputs inputs{ ren, worldToObject, image, scalars, range, property,
    in.Fields.GetLightingMaterials(), this->Settings.PreIntegrationTableSize,
    this->Settings.EnvironmentLighting,
    this->Settings.ReflectionSource == mmv::ReflectEnvironmentTexture, in.ActiveGlobal() != nullptr,
    this->Settings.MultipleScattering, this->Settings.ExponentialDiffusion };
  std::vector<std::string> warnings;
  std::string error;
  const bool shaded = in.Sky.Refresh(inputs, warnings, error);
  for (const std::string& warning : warnings)
  {
    this->WarnOnce(warning);
  }
  if (!error.empty())
  {
    vtkErrorMacro(<< error);
  }
  return shaded;
}

const mmv::CoarseExtinction* vtkMultiMaterialVolumeMapper::GetSceneOccluder(vtkVolume* vol)
{
  if (!vol || this->GetNumberOfInputConnections(0) < 1)
  {
    return nullptr;
  }
  if (vtkGlobalPrefilteredVolume* global = this->Internals->ActiveGlobal())
  {
    // A piece casts the whole volume's shadow, as every rank sees it.
    return this->Internals->SceneShadows.UpdateOccluder(global, vol->GetProperty(),
      this->Internals->Materials(), this->Settings.PreIntegrationTableSize);
  }
  // Another volume may light itself before this one renders: its data now.
  this->GetInputAlgorithm(0, 0)->Update();
  auto* image = vtkImageData::SafeDownCast(this->GetInput());
  int cellFlag = 0;
  vtkDataArray* scalars = image ? vtkAbstractMapper::GetScalars(image, this->ScalarMode,
                                    this->ArrayAccessMode, this->ArrayId, this->ArrayName, cellFlag)
                                : nullptr;
  std::string problem;
  const mmv::CoarseExtinction* occluder =
    this->Internals->SceneShadows.UpdateOccluder(image, scalars, cellFlag, vol->GetProperty(),
      this->Internals->Materials(), this->Settings.PreIntegrationTableSize, &problem);
  if (!problem.empty())
  {
    this->WarnOnce(problem);
  }
  return occluder;
}

int vtkMultiMaterialVolumeMapper::GetNumberOfSceneOccluders()
{
  return this->Internals->SceneShadows.GetNumberOfOccluders();
}

int vtkMultiMaterialVolumeMapper::GetSceneShadowUpdateCount()
{
  return this->Internals->SceneShadows.GetUpdateCount();
}

double vtkMultiMaterialVolumeMapper::GetLastSceneShadowSeconds()
{
  return this->Internals->SceneShadows.GetLastSeconds();
}

int vtkMultiMaterialVolumeMapper::GetSkyUpdateCount()
{
  return this->Internals->Sky.GetUpdateCount();
}

double vtkMultiMaterialVolumeMapper::GetLastSkySeconds()
{
  return this->Internals->Sky.GetLastSeconds();
}

bool vtkMultiMaterialVolumeMapper::UpdateFieldLighting(vtkVolume* vol, vtkDataArray* scalars)
{
  std::string error;
  if (!this->Internals->Fields.UpdateLighting(
        scalars, vol->GetProperty(), this->Settings.PreIntegrationTableSize, &error))
  {
    this->WarnOnce(
      "the fields' combined extinction could not be made (" + error + "); using VTK's shading");
    return false;
  }
  return true;
}

bool vtkMultiMaterialVolumeMapper::UpdateSegmentTables(
  vtkOpenGLRenderWindow* context, vtkVolume* vol, vtkImageData* image)
{
  vtkInternals& in = *this->Internals;
  int extent[6];
  image->GetExtent(extent);
  const double step = mmv::ExpectedSampleDistance(vol, image, this->SampleDistance,
    this->AutoAdjustSampleDistances != 0, this->LockSampleDistanceToInputSpacing != 0,
    this->SpacingAdjustedSampleDistance(image->GetSpacing(), extent));
  int rebuilt = 0;
  double seconds = 0.0;
  if (!in.Fields.UpdateSegmentTables(
        vol->GetProperty(), step, this->Settings.PreIntegrationTableSize, &rebuilt, &seconds))
  {
    return false;
  }
  if (rebuilt > 0)
  {
    ++this->PreIntegrationCount;
    this->LastPreIntegrationSeconds = seconds;
  }
  in.Uniforms.SetTableStep(step);
  in.Textures->UpdateSegmentTables(context, in.Fields.GetSegmentTables());
  in.Textures->UpdateMaterialTable(context, in.Fields.GetMaterialsOfFields(), in.Fields.GetRanges(),
    this->Settings.PreIntegrationTableSize);
  return true;
}

bool vtkMultiMaterialVolumeMapper::UpdateGradient(
  vtkOpenGLRenderWindow* context, vtkImageData* image, vtkDataArray* scalars, const double range[2])
{
  vtkInternals& in = *this->Internals;
  // Pieces of one volume share the gradient's normalisation (and so its
  // shading fade) when they share a global range.
  const double* gradientRange = in.ValueRange(range);
  int dataDims[3];
  image->GetDimensions(dataDims);
  std::string smoothingProblem;
  const double smoothing =
    mmv::ValidGradientSmoothing(this->Settings.GradientSmoothing, &smoothingProblem);
  if (!smoothingProblem.empty())
  {
    this->WarnOnce(smoothingProblem);
  }
  double smoothingVoxels[3];
  mmv::GradientSmoothingVoxels(smoothing, image->GetSpacing(), smoothingVoxels);
  // The steps of a series kept with their irradiance keep their gradients.
  in.Textures->SetKeptGradientBytes(
    static_cast<size_t>(this->Settings.IrradianceCacheMB * 1048576.0));
  if (!in.Textures->UpdateGradientTexture(context, scalars, dataDims, gradientRange,
        this->Settings.MaxBrickMB * 1024.0 * 1024.0, smoothingVoxels))
  {
    this->WarnOnce("the gradient volume could not be created (too large for this OpenGL "
                   "context?); using VTK's shading");
    return false;
  }
  in.Uniforms.SetGradientMap(dataDims, in.Textures->GetGradientTextureDimensions());
  return true;
}

void vtkMultiMaterialVolumeMapper::CollectShadedLights(
  vtkRenderer* ren, vtkMatrix4x4* worldToObject)
{
  vtkInternals& in = *this->Internals;
  int dropped = 0;
  std::vector<std::string> problems;
  std::string radiusProblem;
  const double radius = mmv::ValidPointLightRadius(this->Settings.PointLightRadius, &radiusProblem);
  if (!radiusProblem.empty())
  {
    problems.push_back(radiusProblem);
  }
  in.Lights = mmv::CollectLights(
    ren->GetLights(), worldToObject, radius, mmv::MaxLights, &dropped, &problems);
  mmv::OrderForIrradianceTextures(in.Lights, in.LightOrder);
  for (const std::string& problem : problems)
  {
    this->WarnOnce(problem);
  }
  if (dropped > 0)
  {
    this->WarnOnce("more than " + std::to_string(mmv::MaxLights) +
      " active lights: shading with the strongest " + std::to_string(mmv::MaxLights));
  }
  if (in.Lights.empty() && !(this->Settings.EnvironmentLighting > 0.0))
  {
    this->WarnOnce("no active light: the volume is shaded with its ambient term only");
  }
  this->NumberOfShadedLights = static_cast<int>(in.Lights.size());
}

void vtkMultiMaterialVolumeMapper::UpdateShading(
  vtkRenderer* ren, vtkImageData* image, vtkMatrix4x4* worldToObject, const double range[2])
{
  vtkInternals& in = *this->Internals;
  mmv::ShaderVariant variant;
  variant.NumberOfLights = this->NumberOfShadedLights;
  variant.Fields = in.Fields.GetNumberOfFields();
  const bool several = variant.Fields > 1;
  // The reflection's visibility and the tints march one field's tables.
  if (several && in.Fields.AnyReflection())
  {
    this->WarnOnce("reflection (r) is not shaded with several fields; ignored");
  }
  if (several && in.Fields.AnyChromaticTransmission())
  {
    this->WarnOnce("transmission colours are not modelled with several fields: their shadows "
                   "are grey");
  }
  variant.Reflection = !several && in.Fields.AnyReflection();
  variant.PreIntegration = this->Settings.PreIntegration;
  const bool all = this->Settings.CompileUnusedOpticalTerms;
  variant.Anisotropy = variant.NumberOfLights > 0 && (all || in.Fields.AnyNonZero(mmv::Anisotropy));
  variant.Emission = all || in.Fields.AnyNonZero(mmv::Emission);
  variant.Sky = this->SkyShaded;
  // Tints only where the estimator computed them (a non-white transmission
  // colour); not forced by CompileUnusedOpticalTerms: without the estimator's
  // tint textures there is nothing to bind.
  vtkIrradianceEstimator* pass = in.Irradiance.GetEstimator();
  variant.RGBIrradiance = variant.NumberOfLights > 0 && !several &&
    in.Fields.AnyChromaticTransmission() && pass &&
    pass->GetTintTexture(variant.NumberOfLights - 1) != nullptr;
  if (variant.Reflection)
  {
    this->UpdateReflection(ren, worldToObject, range);
    variant.Environment = in.Reflection->GetEnvironmentKind();
    variant.ReflectionVisibility = in.Reflection->GetVisibility();
    variant.ReflectionCutaway = in.Reflection->GetCutaway();
  }
  if (variant != in.Uniforms.GetVariant() || in.ShaderHook->GetFragmentReplacements().empty())
  {
    in.ShaderHook->SetFragmentReplacements(mmv::RayCastReplacements(variant));
  }
  in.Uniforms.SetVariant(variant);
  in.Uniforms.SetLights(in.Lights);
  in.Uniforms.SetGeometry(image, this->IrradianceDimensions, in.ActiveGlobal());
  in.Uniforms.SetReflection(variant.Reflection ? in.Reflection.Get() : nullptr);
}

void vtkMultiMaterialVolumeMapper::UpdateReflection(
  vtkRenderer* ren, vtkMatrix4x4* worldToObject, const double range[2])
{
  vtkInternals& in = *this->Internals;
  in.Reflection->SetReflectiveValues(
    in.Materials(), in.ValueRange(range), this->Settings.PreIntegrationTableSize);
  vtkNew<vtkMatrix4x4> objectToWorld;
  vtkMatrix4x4::Invert(worldToObject, objectToWorld);
  const mmv::IrradianceGrid& grid = in.Irradiance.GetGrid();
  std::vector<std::string> problems;
  in.Reflection->Update(ren, objectToWorld, this->Settings.ReflectionSource,
    this->Settings.ReflectionVisibility, in.Lights.empty() ? nullptr : in.Irradiance.GetEstimator(),
    grid, this->Settings.PreIntegrationTableSize,
    std::min({ grid.Spacing.x, grid.Spacing.y, grid.Spacing.z }), &problems,
    this->LastRenderInteractive && this->Settings.InteractiveIrradiance == ReuseWhileInteracting);
  for (const std::string& problem : problems)
  {
    this->WarnOnce(problem);
  }
}

vtkIdType vtkMultiMaterialVolumeMapper::GetReflectionVisibilityUpdateCount()
{
  return this->Internals->Reflection->GetVisibilityPass()->GetUpdateCount();
}

const char* vtkMultiMaterialVolumeMapper::GetIrradianceResolutionReason()
{
  return this->Internals->Irradiance.GetResolutionReason().c_str();
}

std::string vtkMultiMaterialVolumeMapper::GetLastIrradianceStages()
{
  return this->Internals->Irradiance.GetStageSeconds().Report();
}

std::string vtkMultiMaterialVolumeMapper::GetLastPrepareStages()
{
  return this->Internals->PrepareStages.Report();
}

int vtkMultiMaterialVolumeMapper::GetNumberOfIrradianceProbes()
{
  return this->Internals->Irradiance.GetProbe()->GetNumberOfProbes();
}

vtkIrradianceResolutionProbe* vtkMultiMaterialVolumeMapper::GetIrradianceResolutionProbe()
{
  return this->Internals->Irradiance.GetProbe();
}

// Each setting's Set/Get, clamped to its row of MMV_ILLUMINATION_SETTINGS.
#define MMV_SETTING_ACCESSORS(type, name, value, low, high, doc)                                   \
  void vtkMultiMaterialVolumeMapper::Set##name(type v)                                             \
  {                                                                                                \
    v = mmv::ClampSetting(v, low, high);                                                           \
    if (this->Settings.name != v)                                                                  \
    {                                                                                              \
      this->Settings.name = v;                                                                     \
      this->Modified();                                                                            \
    }                                                                                              \
  }                                                                                                \
  type vtkMultiMaterialVolumeMapper::Get##name()                                                   \
  {                                                                                                \
    return this->Settings.name;                                                                    \
  }
MMV_ILLUMINATION_SETTINGS(MMV_SETTING_ACCESSORS)
#undef MMV_SETTING_ACCESSORS

void vtkMultiMaterialVolumeMapper::SetSettings(const mmv::IlluminationSettings& settings)
{
#define MMV_SET_SETTING(type, name, value, low, high, doc) this->Set##name(settings.name);
  MMV_ILLUMINATION_SETTINGS(MMV_SET_SETTING)
#undef MMV_SET_SETTING
}

//------------------------------------------------------------------------------
void vtkMultiMaterialVolumeMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
#define MMV_PRINT_SETTING(type, name, value, low, high, doc)                                       \
  os << indent << #name ": " << this->Settings.name << "\n";
  MMV_ILLUMINATION_SETTINGS(MMV_PRINT_SETTING)
#undef MMV_PRINT_SETTING
  os << indent << "VectorMode: "
     << (this->VectorMode == mmv::VectorModeMagnitude
            ? "Magnitude"
            : (this->VectorMode == mmv::VectorModeComponent ? "Component" : "Disabled"))
     << "\n";
  os << indent << "VectorComponent: " << this->VectorComponent << "\n";
  os << indent << "IrradianceResolution: " << this->Internals->Irradiance.GetResolutionReason()
     << "\n";
  os << indent << "DeferredIrradianceCount: " << this->DeferredIrradianceCount << "\n";
  os << indent << "IrradianceCacheHitCount: " << this->IrradianceCacheHitCount << "\n";
  os << indent << "SceneOccluders: " << this->Internals->SceneShadows.GetNumberOfOccluders()
     << "\n";
  os << indent << "IrradianceDimensions: " << this->IrradianceDimensions[0] << " "
     << this->IrradianceDimensions[1] << " " << this->IrradianceDimensions[2] << "\n";
  os << indent << "Counts (pre-integration, irradiance, ray cast): " << this->PreIntegrationCount
     << " " << this->IrradianceUpdateCount << " " << this->RayCastCount << "\n";
}
