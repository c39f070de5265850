#include "vtkSMMultiMaterialVolumeRepresentationProxy.h"

#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPVMultiMaterialInformation.h"
#include "vtkPVSession.h"
#include "vtkSMDoubleVectorProperty.h"
#include "vtkSMIntVectorProperty.h"
#include "vtkSMPropertyIterator.h"
#include "vtkSMStringVectorProperty.h"
#include "vtkSmartPointer.h"

#include <string>
#include <vector>

vtkStandardNewMacro(vtkSMMultiMaterialVolumeRepresentationProxy);

//------------------------------------------------------------------------------
vtkSMMultiMaterialVolumeRepresentationProxy::vtkSMMultiMaterialVolumeRepresentationProxy() =
  default;

//------------------------------------------------------------------------------
vtkSMMultiMaterialVolumeRepresentationProxy::~vtkSMMultiMaterialVolumeRepresentationProxy() =
  default;

//------------------------------------------------------------------------------
void vtkSMMultiMaterialVolumeRepresentationProxy::UpdatePropertyInformationInternal(
  vtkSMProperty* prop)
{
  this->Superclass::UpdatePropertyInformationInternal(prop);
  if (!this->ObjectsCreated || (prop && !prop->GetInformationOnly()))
  {
    return;
  }
  // Which process renders depends on the view (remote rendering above its
  // threshold, local below, both for still and interactive frames), so both
  // answer and the information keeps, per value, the process that drew.
  // The result is not tested: ParaView 5.11's client session reports false
  // after a successful gather from a server; the information is.
  vtkNew<vtkPVMultiMaterialInformation> info;
  this->GatherInformation(info, vtkPVSession::CLIENT | vtkPVSession::RENDER_SERVER);
  if (!info->HasValues())
  {
    return;
  }
  vtkSmartPointer<vtkSMPropertyIterator> iter;
  iter.TakeReference(this->NewPropertyIterator());
  std::vector<double> numbers;
  std::string text;
  for (iter->Begin(); !iter->IsAtEnd(); iter->Next())
  {
    vtkSMProperty* property = iter->GetProperty();
    if (!property->GetInformationOnly() || (prop && prop != property))
    {
      continue;
    }
    const std::string name = iter->GetKey();
    if (auto* ivp = vtkSMIntVectorProperty::SafeDownCast(property))
    {
      if (info->GetNumbers(name, numbers))
      {
        std::vector<int> values(numbers.begin(), numbers.end());
        ivp->SetNumberOfElements(static_cast<unsigned int>(values.size()));
        ivp->SetElements(values.data(), static_cast<unsigned int>(values.size()));
      }
    }
    else if (auto* dvp = vtkSMDoubleVectorProperty::SafeDownCast(property))
    {
      if (info->GetNumbers(name, numbers))
      {
        dvp->SetNumberOfElements(static_cast<unsigned int>(numbers.size()));
        dvp->SetElements(numbers.data(), static_cast<unsigned int>(numbers.size()));
      }
    }
    else if (auto* svp = vtkSMStringVectorProperty::SafeDownCast(property))
    {
      if (info->GetText(name, text))
      {
        svp->SetNumberOfElements(1);
        svp->SetElement(0, text.c_str());
      }
    }
  }
}

//------------------------------------------------------------------------------
void vtkSMMultiMaterialVolumeRepresentationProxy::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
