#include "vtkPVIrradianceVolumeFilter.h"

#include "vtkObjectFactory.h"

vtkStandardNewMacro(vtkPVIrradianceVolumeFilter);

//------------------------------------------------------------------------------
vtkPVIrradianceVolumeFilter::vtkPVIrradianceVolumeFilter()
{
  this->SetScalarOpacity(this->Opacity);
  this->SetMaterialTransferFunction(this->Materials);

  // Scene lights: GetTransformedPosition/FocalPoint are then the world
  // coordinates given here, with no camera involved.
  this->DirectionalLight->SetLightTypeToSceneLight();
  this->DirectionalLight->SetPositional(false);
  this->DirectionalLight->SetFocalPoint(0.0, 0.0, 0.0);
  this->DirectionalLight->SetPosition(0.0, 0.0, 1.0);
  this->PointLight->SetLightTypeToSceneLight();
  this->PointLight->SetPositional(true);
  // A cone angle of 90 degrees or more makes a positional light a point light.
  this->PointLight->SetConeAngle(180.0);
  this->UpdateLights();
}

//------------------------------------------------------------------------------
vtkPVIrradianceVolumeFilter::~vtkPVIrradianceVolumeFilter() = default;

//------------------------------------------------------------------------------
void vtkPVIrradianceVolumeFilter::AddOpacityPoint(double value, double opacity)
{
  this->Opacity->AddPoint(value, opacity);
}

//------------------------------------------------------------------------------
void vtkPVIrradianceVolumeFilter::RemoveAllOpacityPoints()
{
  this->Opacity->RemoveAllPoints();
}

//------------------------------------------------------------------------------
void vtkPVIrradianceVolumeFilter::SetNumberOfMaterialNodeValues(int count)
{
  if (this->PendingNodes.Announce(count))
  {
    this->PendingNodes.Apply(this, this->Materials);
  }
}

//------------------------------------------------------------------------------
void vtkPVIrradianceVolumeFilter::SetMaterialNodeValue(int index, double value)
{
  if (this->PendingNodes.Receive(index, value))
  {
    this->PendingNodes.Apply(this, this->Materials);
  }
}

//------------------------------------------------------------------------------
void vtkPVIrradianceVolumeFilter::SetLightDirection(double x, double y, double z)
{
  if (x == 0.0 && y == 0.0 && z == 0.0)
  {
    vtkErrorMacro("LightDirection must not be zero; keeping the previous direction.");
    return;
  }
  // A directional vtkLight shines from Position towards FocalPoint.
  this->DirectionalLight->SetPosition(-x, -y, -z);
}

//------------------------------------------------------------------------------
void vtkPVIrradianceVolumeFilter::SetUsePointLight(bool use)
{
  if (use != this->UsePointLight)
  {
    this->UsePointLight = use;
    this->UpdateLights();
  }
}

//------------------------------------------------------------------------------
void vtkPVIrradianceVolumeFilter::SetPointLightPosition(double x, double y, double z)
{
  this->PointLight->SetPosition(x, y, z);
}

//------------------------------------------------------------------------------
void vtkPVIrradianceVolumeFilter::UpdateLights()
{
  this->RemoveAllLights();
  this->AddLight(this->DirectionalLight);
  if (this->UsePointLight)
  {
    this->AddLight(this->PointLight);
  }
  this->Modified();
}

//------------------------------------------------------------------------------
void vtkPVIrradianceVolumeFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  double* p = this->DirectionalLight->GetPosition();
  os << indent << "LightDirection: " << -p[0] << ", " << -p[1] << ", " << -p[2] << "\n";
  os << indent << "UsePointLight: " << this->UsePointLight << "\n";
  p = this->PointLight->GetPosition();
  os << indent << "PointLightPosition: " << p[0] << ", " << p[1] << ", " << p[2] << "\n";
}
