// placeholder (being written)
#ifndef vtkMultiMaterialReferenceRenderer_h
#define vtkMultiMaterialReferenceRenderer_h
#include "vtkMultiMaterialVolumeModule.h"
#include "vtkObject.h"
class VTKMULTIMATERIALVOLUME_EXPORT vtkMultiMaterialReferenceRenderer : public vtkObject
{
public:
  static vtkMultiMaterialReferenceRenderer* New();
  vtkTypeMacro(vtkMultiMaterialReferenceRenderer, vtkObject);
protected:
  vtkMultiMaterialReferenceRenderer() = default;
  ~vtkMultiMaterialReferenceRenderer() override = default;
private:
  vtkMultiMaterialReferenceRenderer(const vtkMultiMaterialReferenceRenderer&) = delete;
  void operator=(const vtkMultiMaterialReferenceRenderer&) = delete;
};
#endif
