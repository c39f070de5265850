#include "vtkImageErrorMetrics.h"
#include "vtkObjectFactory.h"
vtkStandardNewMacro(vtkImageErrorMetrics);
