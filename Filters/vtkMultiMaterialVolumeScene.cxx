#include "vtkMultiMaterialVolumeScene.h"

#include "vtkAbstractVolumeMapper.h"
#include "vtkImageData.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMatrix4x4.h"
#include "vtkPiecewiseFunction.h"
#include "vtkRenderer.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

vtkMultiMaterialVolumeScene::vtkMultiMaterialVolumeScene() = default;
vtkMultiMaterialVolumeScene::~vtkMultiMaterialVolumeScene() = default;

namespace
{
/// Sets `member` and marks `owner` modified when the pointer changes.
template <typename T>
void SetMember(vtkObject* owner, vtkSmartPointer<T>& member, T* value)
{
  if (member != value)
  {
    member = value;
    owner->Modified();
  }
}
}

void vtkMultiMaterialVolumeScene::SetInputData(vtkImageData* image)
{
  SetMember(this, this->Input, image);
}

vtkImageData* vtkMultiMaterialVolumeScene::GetInput()
{
  return this->Input;
}

void vtkMultiMaterialVolumeScene::SetVolumeProperty(vtkVolumeProperty* property)
{
  SetMember(this, this->Property, property);
}

vtkVolumeProperty* vtkMultiMaterialVolumeScene::GetVolumeProperty()
{
  return this->Property;
}

void vtkMultiMaterialVolumeScene::SetMaterialTransferFunction(
  vtkMaterialTransferFunction* materials)
{
  SetMember(this, this->Materials, materials);
}

vtkMaterialTransferFunction* vtkMultiMaterialVolumeScene::GetMaterialTransferFunction()
{
  return this->Materials;
}

void vtkMultiMaterialVolumeScene::SetVolumeMatrix(vtkMatrix4x4* matrix)
{
  SetMember(this, this->Matrix, matrix);
}

vtkMatrix4x4* vtkMultiMaterialVolumeScene::GetVolumeMatrix()
{
  return this->Matrix;
}

bool vtkMultiMaterialVolumeScene::AdoptVolume(
  vtkVolume* volume, std::optional<mmv::MapperSettings>& mmvMapper)
{
  mmvMapper.reset();
  if (!volume || !volume->GetMapper())
  {
    vtkErrorMacro("RenderToImage needs a renderer and a volume with a mapper");
    return false;
  }
  vtkAbstractVolumeMapper* mapper = volume->GetMapper();
  this->SetInputData(vtkImageData::SafeDownCast(mapper->GetDataSetInput()));
  this->SetVolumeProperty(volume->GetProperty());
  this->SetVolumeMatrix(volume->GetMatrix());
  mmv::MapperSettings settings;
  if (mmv::ReadMapperSettings(mapper, settings))
  {
    mmvMapper = settings;
    this->SetMaterialTransferFunction(settings.Materials);
  }
  return true;
}

bool vtkMultiMaterialVolumeScene::CheckRenderInputs(vtkRenderer* ren, int width, int height)
{
  if (!ren || !ren->GetActiveCamera() || width < 1 || height < 1)
  {
    vtkErrorMacro("Render needs a renderer with a camera and a positive image size");
    return false;
  }
  if (!this->Input || !this->Property || !this->Property->GetScalarOpacity(0))
  {
    vtkErrorMacro("Render needs input data and a volume property with a scalar opacity");
    return false;
  }
  return true;
}

void vtkMultiMaterialVolumeScene::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Input: " << this->Input.Get() << "\n";
  os << indent << "VolumeProperty: " << this->Property.Get() << "\n";
  os << indent << "MaterialTransferFunction: " << this->Materials.Get() << "\n";
  os << indent << "VolumeMatrix: " << this->Matrix.Get() << "\n";
}
