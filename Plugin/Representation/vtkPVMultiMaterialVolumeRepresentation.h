// placeholder (being written)
#ifndef vtkPVMultiMaterialVolumeRepresentation_h
#define vtkPVMultiMaterialVolumeRepresentation_h
#include "vtkMultiMaterialVolumeParaViewModule.h"
#include "vtkImageVolumeRepresentation.h"
class VTKMULTIMATERIALVOLUMEPARAVIEW_EXPORT vtkPVMultiMaterialVolumeRepresentation : public vtkImageVolumeRepresentation
{
public:
  static vtkPVMultiMaterialVolumeRepresentation* New();
  vtkTypeMacro(vtkPVMultiMaterialVolumeRepresentation, vtkImageVolumeRepresentation);
};
#endif
