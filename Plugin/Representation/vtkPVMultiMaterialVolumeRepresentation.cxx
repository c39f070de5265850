#include "vtkPVMultiMaterialVolumeRepresentation.h"
#include "vtkObjectFactory.h"
vtkStandardNewMacro(vtkPVMultiMaterialVolumeRepresentation);
