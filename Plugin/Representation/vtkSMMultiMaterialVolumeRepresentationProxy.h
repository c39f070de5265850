/**
 * @class   vtkSMMultiMaterialVolumeRepresentationProxy
 * @brief   Server-manager proxy of the Multi-Material Volume representation:
 *          its information properties come from the processes that render.
 *
 * A vtkSMRepresentationProxy reads each information property from one
 * process. Connected to a pvserver the representation renders on the server
 * (remote rendering) or on the client (below the remote render threshold),
 * and under MPI on every server rank, so one process's counters
 * (IrradianceUpdateCount, MultiMaterialActive...) can stay 0 while the
 * image is drawn elsewhere. After the usual update this proxy gathers a
 * vtkPVMultiMaterialInformation from the client and every render-server
 * rank, which keeps per value the largest (the process that drew), and
 * writes it into the information properties. In one process nothing
 * changes.
 */
#ifndef vtkSMMultiMaterialVolumeRepresentationProxy_h
#define vtkSMMultiMaterialVolumeRepresentationProxy_h

#include "vtkMultiMaterialVolumeParaViewModule.h" // export macro
#include "vtkSMRepresentationProxy.h"

class VTKMULTIMATERIALVOLUMEPARAVIEW_EXPORT vtkSMMultiMaterialVolumeRepresentationProxy
  : public vtkSMRepresentationProxy
{
public:
  static vtkSMMultiMaterialVolumeRepresentationProxy* New();
  vtkTypeMacro(vtkSMMultiMaterialVolumeRepresentationProxy, vtkSMRepresentationProxy);
  void PrintSelf(ostream& os, vtkIndent indent) override;

protected:
  vtkSMMultiMaterialVolumeRepresentationProxy();
  ~vtkSMMultiMaterialVolumeRepresentationProxy() override;

  void UpdatePropertyInformationInternal(vtkSMProperty* prop = nullptr) override;

private:
  vtkSMMultiMaterialVolumeRepresentationProxy(
    const vtkSMMultiMaterialVolumeRepresentationProxy&) = delete;
  void operator=(const vtkSMMultiMaterialVolumeRepresentationProxy&) = delete;
};

#endif
