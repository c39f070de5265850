/**
 * @file   vtkMultiMaterialPropertyObserver.h
 * @brief  How the plugin's client-side behaviours (first use, Lighting
 *         Quality's link, the further fields' colour maps) hear of property
 *         changes: an observer of the proxy manager's PropertyModifiedEvent,
 *         registered once per process when the library is loaded.
 *
 * Only a process with a server manager (the GUI client, pvpython; not
 * pvserver) has a proxy manager to observe. Each behaviour is a vtkCommand
 * whose Execute receives a vtkSMProxyManager::ModifiedPropertyInformation.
 */
#ifndef vtkMultiMaterialPropertyObserver_h
#define vtkMultiMaterialPropertyObserver_h

#include "vtkCommand.h"
#include "vtkNew.h"
#include "vtkSMProxyManager.h"

namespace mmv
{
/// A static object of this type registers one `Observer` at load time.
template <typename Observer>
struct PropertyObserverRegistration
{
  PropertyObserverRegistration()
  {
    if (vtkSMProxyManager::IsInitialized())
    {
      vtkNew<Observer> observer;
      vtkSMProxyManager::GetProxyManager()->AddObserver(
        vtkCommand::PropertyModifiedEvent, observer);
    }
  }
};
}

#endif
