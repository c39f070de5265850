#include "vtkMultiMaterialReferenceRenderer.h"
#include "vtkObjectFactory.h"
vtkStandardNewMacro(vtkMultiMaterialReferenceRenderer);
