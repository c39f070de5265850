// First use of the representation in ParaView: switching a display that
// colours with a solid colour to "Multi-Material Volume" colours it by a data
// array, as ParaView's Volume does.
//
// ParaView 5.11 does this for "Volume", "Slice" and "NVIDIA IndeX" only, by
// name, inside vtkSMPVRepresentationProxy::SetRepresentationType; a plugin
// cannot add its representation to that list or change the class of the
// UniformGridRepresentation proxy it extends. So this library, when it is
// loaded into a process that has a server manager (the GUI client, pvpython;
// not pvserver), observes the proxy manager: every registered proxy's
// property change reaches it as a PropertyModifiedEvent. When a display's
// "Representation" becomes "Multi-Material Volume" without scalar colouring,
// it picks the array Volume would pick (the first point array of the
// ColorArrayName domain, else the first array), colours by it and rescales the
// colour map to its range. With no array it reports why nothing is drawn.
// State files are left as they were saved.
#include "vtkCommand.h"
#include "vtkDataObject.h"
#include "vtkMultiMaterialPropertyObserver.h"
#include "vtkNew.h"
#include "vtkSMArrayListDomain.h"
#include "vtkSMPVRepresentationProxy.h"
#include "vtkSMProperty.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMProxyManager.h"
#include "vtkSMSessionProxyManager.h"

#include <cstring>

namespace
{
constexpr const char* RepresentationName = "Multi-Material Volume";

class vtkMultiMaterialFirstUseObserver : public vtkCommand
{
public:
  static vtkMultiMaterialFirstUseObserver* New() { return new vtkMultiMaterialFirstUseObserver; }

  void Execute(vtkObject*, unsigned long, void* callData) override
  {
    auto* info = static_cast<vtkSMProxyManager::ModifiedPropertyInformation*>(callData);
    if (this->Busy || !info || !info->PropertyName ||
      strcmp(info->PropertyName, "Representation") != 0)
    {
      return;
    }
    auto* display = vtkSMPVRepresentationProxy::SafeDownCast(info->Proxy);
    if (!display || !display->GetProperty("ColorArrayName"))
    {
      return;
    }
    const char* type = vtkSMPropertyHelper(display, "Representation").GetAsString();
    vtkSMSessionProxyManager* pxm = display->GetSessionProxyManager();
    if (!type || strcmp(type, RepresentationName) != 0 || display->GetUsingScalarColoring() ||
      (pxm && pxm->GetInLoadXMLState()))
    {
      return;
    }
    this->Busy = true; // colouring modifies properties of this display
    this->ColorByFirstArray(display);
    this->Busy = false;
  }

private:
  void ColorByFirstArray(vtkSMPVRepresentationProxy* display)
  {
    auto* arrays = display->GetProperty("ColorArrayName")->FindDomain<vtkSMArrayListDomain>();
    if (!arrays || arrays->GetNumberOfStrings() == 0)
    {
      vtkErrorWithObjectMacro(display,
        "Multi-Material Volume draws a data array through its colour and opacity maps, and "
        "this data has no point or cell array to draw: nothing is shown. Add an array (for "
        "example with a Calculator) or choose another representation.");
      return;
    }
    unsigned int index = 0;
    for (unsigned int i = 0; i < arrays->GetNumberOfStrings(); ++i)
    {
      if (arrays->GetFieldAssociation(i) == vtkDataObject::POINT)
      {
        index = i;
        break;
      }
    }
    if (display->SetScalarColoring(arrays->GetString(index), arrays->GetFieldAssociation(index)))
    {
      // As if the array had been picked in the toolbar.
      display->RescaleTransferFunctionToDataRange(true);
    }
  }

  bool Busy = false;
};

const mmv::PropertyObserverRegistration<vtkMultiMaterialFirstUseObserver> Registration;
}
