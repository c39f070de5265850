// placeholder (being written)
#ifndef vtkImageErrorMetrics_h
#define vtkImageErrorMetrics_h
#include "vtkMultiMaterialVolumeModule.h"
#include "vtkObject.h"
class VTKMULTIMATERIALVOLUME_EXPORT vtkImageErrorMetrics : public vtkObject
{
public:
  static vtkImageErrorMetrics* New();
  vtkTypeMacro(vtkImageErrorMetrics, vtkObject);
protected:
  vtkImageErrorMetrics() = default;
  ~vtkImageErrorMetrics() override = default;
private:
  vtkImageErrorMetrics(const vtkImageErrorMetrics&) = delete;
  void operator=(const vtkImageErrorMetrics&) = delete;
};
#endif
