#include "vtkMultiMaterialReflection.h"

#include "vtkCamera.h"
#include "vtkIrradianceEstimator.h"
#include "vtkIrradianceGrid.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMatrix4x4.h"
#include "vtkMultiMaterialEnvironment.h"
#include "vtkMultiMaterialEnvironmentTexture.h"
#include "vtkMultiMaterialParameters.h"
#include "vtkMultiMaterialShaderAssembly.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkReflectionVisibilityPass.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"

#include <algorithm>

vtkStandardNewMacro(vtkMultiMaterialReflection);

vtkMultiMaterialReflection::vtkMultiMaterialReflection() = default;
vtkMultiMaterialReflection::~vtkMultiMaterialReflection() = default;

vtkMultiMaterialEnvironment* vtkMultiMaterialReflection::GetEnvironment()
{
  return this->Environment->GetEnvironment();
}

int vtkMultiMaterialReflection::GetEnvironmentKind() const
{
  return this->Environment->GetEnvironment()->GetKind();
}

void vtkMultiMaterialReflection::SetReflectiveValues(
  vtkMaterialTransferFunction* materials, const double scalarRange[2], int tableSize)
{
  double values[2];
  const double width = scalarRange[1] - scalarRange[0];
  if (!materials || !(width > 0.0) || tableSize < 2 ||
    !materials->GetNonZeroRange(mmv::Reflection, values))
  {
    // Nothing reflects (the shader then has no reflection) or no range to
    // map to: skip nothing.
    this->ReflectiveRange[0] = 0.0f;
    this->ReflectiveRange[1] = 1.0f;
    return;
  }
  const double step = 1.0 / (tableSize - 1);
  for (int i = 0; i < 2; ++i)
  {
    const double t = (values[i] - scalarRange[0]) / width + (i ? step : -step);
    this->ReflectiveRange[i] = static_cast<float>(std::min(std::max(t, 0.0), 1.0));
  }
}

void vtkMultiMaterialReflection::Update(vtkRenderer* ren, vtkMatrix4x4* objectToWorld, int source,
  int visibility, vtkIrradianceEstimator* pass, const mmv::IrradianceGrid& grid, int tableSize,
  double stepLength, std::vector<std::string>* problems, bool keepWhileCameraMoves)
{
  this->Environment->Update(ren, objectToWorld, source, problems);
  if (visibility == mmv::AutomaticReflectionVisibility)
  {
    const int* size = ren->GetSize();
    const double pixels = static_cast<double>(size[0]) * size[1];
    const double voxels =
      static_cast<double>(grid.Dimensions[0]) * grid.Dimensions[1] * grid.Dimensions[2];
    visibility = pixels < mmv::PerSampleMarchPixelsPerVoxel * voxels
      ? mmv::MarchedReflectionVisibility
      : mmv::ViewDependentReflectionVisibility;
  }
  this->Visibility = mmv::UnoccludedReflections;
  this->Cutaway = false;
  this->Pass = nullptr;
  if (visibility != mmv::MarchedReflectionVisibility &&
    visibility != mmv::ViewDependentReflectionVisibility)
  {
    return;
  }
  if (!pass || !pass->GetScalarTexture() || !pass->GetShadowTableTexture())
  {
    if (problems)
    {
      problems->push_back("reflections are not occluded by the volume without a light (their "
                          "visibility marches the pre-filtered volume the irradiance pass builds)");
    }
    return;
  }
  this->Visibility = visibility;
  this->Pass = pass;
  // The pass's cutaway is the mapper's of this frame (or, while its
  // irradiance is kept during interaction, of the irradiance shown).
  this->Cutaway = !pass->GetCutaway().IsEmpty();
  const glm::dmat3 toIndex = grid.PhysicalToIndexMatrix();
  const glm::dmat3 toObject = grid.IndexToPhysicalMatrix();
  for (int c = 0; c < 3; ++c)
  {
    for (int r = 0; r < 3; ++r)
    {
      this->ToIndex[3 * c + r] = static_cast<float>(toIndex[c][r]); // column-major, as GLSL
      this->ToObject[3 * c + r] = static_cast<float>(toObject[c][r]);
    }
    this->Origin[c] = static_cast<float>(grid.Origin[c]);
    this->Dimensions[c] = grid.Dimensions[c];
  }
  // Voxels of the grid marched: its smallest spacing is the march's step.
  this->Offset = static_cast<float>(mmv::ReflectionVisibilityOffsetVoxels * stepLength);
  this->TableSize = static_cast<float>(tableSize);
  this->StepLength = static_cast<float>(stepLength);
  if (visibility == mmv::ViewDependentReflectionVisibility &&
    !this->UpdateVisibilityPass(ren, objectToWorld, grid, keepWhileCameraMoves, problems))
  {
    this->Visibility = mmv::MarchedReflectionVisibility;
  }
}

bool vtkMultiMaterialReflection::UpdateVisibilityPass(vtkRenderer* ren, vtkMatrix4x4* objectToWorld,
  const mmv::IrradianceGrid& grid, bool keepWhileCameraMoves, std::vector<std::string>* problems)
{
  auto* context = vtkOpenGLRenderWindow::SafeDownCast(ren->GetRenderWindow());
  vtkCamera* camera = ren->GetActiveCamera();
  if (!context || !camera)
  {
    return false;
  }
  // The camera in object space: its position, or (parallel projection) the
  // direction toward it, which is all the mirror directions depend on.
  vtkNew<vtkMatrix4x4> worldToObject;
  vtkMatrix4x4::Invert(objectToWorld, worldToObject);
  double eye[4];
  if (camera->GetParallelProjection())
  {
    const double* d = camera->GetDirectionOfProjection();
    const double toCamera[4] = { -d[0], -d[1], -d[2], 0.0 };
    worldToObject->MultiplyPoint(toCamera, eye);
    eye[3] = 0.0;
  }
  else
  {
    const double* p = camera->GetPosition();
    const double position[4] = { p[0], p[1], p[2], 1.0 };
    worldToObject->MultiplyPoint(position, eye);
    for (int c = 0; c < 3; ++c)
    {
      eye[c] /= eye[3] != 0.0 ? eye[3] : 1.0;
    }
    eye[3] = 1.0;
  }
  // Stale when the camera, the pre-filtered volume (a new upload), its
  // cutaway, grid or table changed.
  std::vector<double> key;
  key.push_back(static_cast<double>(this->Pass->GetNumberOfVolumeUploads()));
  key.push_back(static_cast<double>(this->Pass->GetScalarTexture()->GetHandle()));
  key.push_back(static_cast<double>(this->Pass->GetShadowTableTexture()->GetHandle()));
  const std::vector<double> cut = this->Pass->GetCutaway().Key();
  key.insert(key.end(), cut.begin(), cut.end());
  key.insert(key.end(), this->ToIndex, this->ToIndex + 9);
  key.insert(key.end(), this->Origin, this->Origin + 3);
  key.insert(key.end(),
    { double(this->Offset), double(this->TableSize), double(this->StepLength),
      double(this->ReflectiveRange[0]), double(this->ReflectiveRange[1]) });
  // A piece of a volume in parallel reads only the irradiance pass's region.
  int region[6];
  this->Pass->GetRegion(region);
  key.insert(key.end(), region, region + 6);
  if (keepWhileCameraMoves && key == this->VolumeKey &&
    this->VisibilityPass->GetVisibilityTexture())
  {
    return true; // an earlier camera's, until the interaction ends
  }
  this->VolumeKey = key;
  std::copy(eye, eye + 4, this->Eye);
  key.insert(key.end(), eye, eye + 4);
  this->Pass->GetScalarTexture()->Activate();
  this->Pass->GetShadowTableTexture()->Activate();
  const bool ok = this->VisibilityPass->Update(context, grid.Dimensions, region,
    mmv::ReflectionMarchDefines(this->Cutaway), key,
    [this](vtkShaderProgram* program)
    {
      this->SetMarchUniforms(program);
      program->SetUniformMatrix3x3("mmv_visibilityToObject", const_cast<float*>(this->ToObject));
      program->SetUniform4f("mmv_eye", this->Eye);
      program->SetUniform2f("mmv_reflectiveRange", this->ReflectiveRange);
    });
  this->Pass->GetScalarTexture()->Deactivate();
  this->Pass->GetShadowTableTexture()->Deactivate();
  if (!ok && problems)
  {
    problems->push_back("the view-dependent visibility of reflections could not be computed: "
                        "marched per sample instead");
  }
  return ok;
}

vtkReflectionVisibilityPass* vtkMultiMaterialReflection::GetVisibilityPass()
{
  return this->VisibilityPass;
}

void vtkMultiMaterialReflection::ReleaseGraphicsResources(vtkWindow* window)
{
  this->VisibilityPass->ReleaseGraphicsResources(window);
}

void vtkMultiMaterialReflection::Activate()
{
  this->Environment->Activate();
  if (this->Visibility == mmv::ViewDependentReflectionVisibility)
  {
    this->VisibilityPass->GetVisibilityTexture()->Activate();
  }
  else if (this->Pass)
  {
    this->Pass->GetScalarTexture()->Activate();
    this->Pass->GetShadowTableTexture()->Activate();
  }
}

void vtkMultiMaterialReflection::Deactivate()
{
  this->Environment->Deactivate();
  if (this->Visibility == mmv::ViewDependentReflectionVisibility)
  {
    this->VisibilityPass->GetVisibilityTexture()->Deactivate();
  }
  else if (this->Pass)
  {
    this->Pass->GetScalarTexture()->Deactivate();
    this->Pass->GetShadowTableTexture()->Deactivate();
  }
}

void vtkMultiMaterialReflection::SetMarchUniforms(vtkShaderProgram* program) const
{
  // The uniforms of Shaders/mmvShadowRay.glsl, as the irradiance pass sets
  // them, and of mmvReflectionMarch.glsl.
  program->SetUniformi("scalars", this->Pass->GetScalarTexture()->GetTextureUnit());
  program->SetUniformi("shadowTable", this->Pass->GetShadowTableTexture()->GetTextureUnit());
  program->SetUniformf("tableSize", this->TableSize);
  program->SetUniform1iv("dims", 3, this->Dimensions);
  program->SetUniformf("stepLength", this->StepLength);
  program->SetUniformMatrix3x3("mmv_visibilityToIndex", const_cast<float*>(this->ToIndex));
  program->SetUniform3f("mmv_visibilityOrigin", this->Origin);
  program->SetUniformf("mmv_visibilityOffset", this->Offset);
  this->Pass->SetCutawayUniforms(program);
}

void vtkMultiMaterialReflection::SetUniforms(vtkShaderProgram* program) const
{
  this->Environment->SetUniforms(program);
  if (this->Visibility == mmv::MarchedReflectionVisibility)
  {
    this->SetMarchUniforms(program);
  }
  else if (this->Visibility == mmv::ViewDependentReflectionVisibility)
  {
    const float dims[3] = { float(this->Dimensions[0]), float(this->Dimensions[1]),
      float(this->Dimensions[2]) };
    program->SetUniformi(
      "mmv_reflectionVisibility", this->VisibilityPass->GetVisibilityTexture()->GetTextureUnit());
    program->SetUniformMatrix3x3("mmv_visibilityToIndex", const_cast<float*>(this->ToIndex));
    program->SetUniform3f("mmv_visibilityOrigin", this->Origin);
    program->SetUniform3f("mmv_visibilityDims", dims);
  }
}

void vtkMultiMaterialReflection::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Visibility: " << this->Visibility << "\n";
  os << indent << "Cutaway: " << this->Cutaway << "\n";
  this->VisibilityPass->PrintSelf(os, indent.GetNextIndent());
  this->Environment->PrintSelf(os, indent.GetNextIndent());
}
