// Several fields in ParaView: when a display's FieldArrays change, each
// field gets the colour map and opacity function ParaView keeps for its
// array name (the ones the Color Map Editor edits when something is coloured
// by that array), rescaled to include the array's range, in
// FieldLookupTables and FieldScalarOpacityFunctions.
//
// A property's value cannot name proxies by itself, so, as
// vtkMultiMaterialFirstUse.cxx does, this library observes the proxy manager
// of a process that has one (the GUI client, pvpython) for the change. State
// files are left as they were saved; tables set after FieldArrays stay.
#include "vtkCommand.h"
#include "vtkDataObject.h"
#include "vtkMultiMaterialPropertyObserver.h"
#include "vtkNew.h"
#include "vtkPVArrayInformation.h"
#include "vtkPVDataInformation.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMProxy.h"
#include "vtkSMProxyManager.h"
#include "vtkSMSessionProxyManager.h"
#include "vtkSMSourceProxy.h"
#include "vtkSMTransferFunctionManager.h"
#include "vtkSMTransferFunctionProxy.h"

#include <cstring>
#include <vector>

namespace
{
class vtkMultiMaterialFieldColorMapsObserver : public vtkCommand
{
public:
  static vtkMultiMaterialFieldColorMapsObserver* New()
  {
    return new vtkMultiMaterialFieldColorMapsObserver;
  }

  void Execute(vtkObject*, unsigned long, void* callData) override
  {
    auto* info = static_cast<vtkSMProxyManager::ModifiedPropertyInformation*>(callData);
    if (this->Busy || !info || !info->Proxy || !info->PropertyName ||
      strcmp(info->PropertyName, "FieldArrays") != 0)
    {
      return;
    }
    vtkSMProxy* display = info->Proxy;
    vtkSMSessionProxyManager* pxm = display->GetSessionProxyManager();
    if (!pxm || pxm->GetInLoadXMLState() || !display->GetProperty("FieldLookupTables") ||
      !display->GetProperty("FieldScalarOpacityFunctions"))
    {
      return;
    }
    this->Busy = true; // the tables are properties of this display
    this->AssignColorMaps(display, pxm);
    this->Busy = false;
  }

private:
  // The array's range (component 0) in the display's input, if it has it.
  static bool ArrayRange(vtkSMProxy* display, const char* name, double range[2])
  {
    vtkSMPropertyHelper input(display, "Input", /*quiet*/ true);
    auto* source = vtkSMSourceProxy::SafeDownCast(input.GetAsProxy());
    if (!source)
    {
      return false;
    }
    vtkPVDataInformation* data = source->GetDataInformation(input.GetOutputPort());
    for (int association : { vtkDataObject::POINT, vtkDataObject::CELL })
    {
      if (vtkPVArrayInformation* array =
            data ? data->GetArrayInformation(name, association) : nullptr)
      {
        array->GetComponentRange(0, range);
        return range[1] >= range[0];
      }
    }
    return false;
  }

  void AssignColorMaps(vtkSMProxy* display, vtkSMSessionProxyManager* pxm)
  {
    vtkSMPropertyHelper names(display, "FieldArrays");
    vtkNew<vtkSMTransferFunctionManager> manager;
    std::vector<vtkSMProxy*> colors;
    std::vector<vtkSMProxy*> opacities;
    for (unsigned int i = 0; i < names.GetNumberOfElements(); ++i)
    {
      const char* name = names.GetAsString(i);
      if (!name || !name[0])
      {
        continue;
      }
      vtkSMProxy* color = manager->GetColorTransferFunction(name, pxm);
      vtkSMProxy* opacity = manager->GetOpacityTransferFunction(name, pxm);
      double range[2];
      if (ArrayRange(display, name, range))
      {
        vtkSMTransferFunctionProxy::RescaleTransferFunction(color, range, /*extend*/ true);
        vtkSMTransferFunctionProxy::RescaleTransferFunction(opacity, range, /*extend*/ true);
      }
      colors.push_back(color);
      opacities.push_back(opacity);
    }
    vtkSMPropertyHelper(display, "FieldLookupTables")
      .Set(colors.data(), static_cast<unsigned int>(colors.size()));
    vtkSMPropertyHelper(display, "FieldScalarOpacityFunctions")
      .Set(opacities.data(), static_cast<unsigned int>(opacities.size()));
    display->UpdateVTKObjects();
  }

  bool Busy = false;
};

const mmv::PropertyObserverRegistration<vtkMultiMaterialFieldColorMapsObserver> Registration;
}
