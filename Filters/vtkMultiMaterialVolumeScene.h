/**
 * @class   vtkMultiMaterialVolumeScene
 * @brief   The scene the CPU references render: data, volume property,
 *          materials and the volume's matrix.
 *
 * vtkMultiMaterialReferenceRenderer (the same-model reference) and
 * vtkMultiMaterialPathTracer (the physical one) take the same inputs as the
 * mapper; this base class holds them once. RenderToImage() of either takes
 * them from a vtkVolume (AdoptVolume).
 */
#ifndef vtkMultiMaterialVolumeScene_h
#define vtkMultiMaterialVolumeScene_h

#include "vtkMultiMaterialMapperSettings.h"      // mmv::MapperSettings
#include "vtkMultiMaterialVolumeFiltersModule.h" // export macro
#include "vtkObject.h"
#include "vtkSmartPointer.h" // members

#include <optional> // AdoptVolume

class vtkImageData;
class vtkMaterialTransferFunction;
class vtkMatrix4x4;
class vtkRenderer;
class vtkVolume;
class vtkVolumeProperty;

class VTKMULTIMATERIALVOLUMEFILTERS_EXPORT vtkMultiMaterialVolumeScene : public vtkObject
{
public:
  vtkTypeMacro(vtkMultiMaterialVolumeScene, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The scene: data (active point scalars, component 0), colour/opacity,
  /// materials (null: the defaults everywhere) and the object-to-world matrix
  /// (null: identity).
  void SetInputData(vtkImageData* image);
  vtkImageData* GetInput();
  void SetVolumeProperty(vtkVolumeProperty* property);
  vtkVolumeProperty* GetVolumeProperty();
  void SetMaterialTransferFunction(vtkMaterialTransferFunction* materials);
  vtkMaterialTransferFunction* GetMaterialTransferFunction();
  void SetVolumeMatrix(vtkMatrix4x4* matrix);
  vtkMatrix4x4* GetVolumeMatrix();
  ///@}

protected:
  vtkMultiMaterialVolumeScene();
  ~vtkMultiMaterialVolumeScene() override;

  /// The volume's data, property and matrix, and the materials of its mapper
  /// when that is a vtkMultiMaterialVolumeMapper (whose settings are returned
  /// in `mmvMapper`, else it is empty). False (with an error) when the volume
  /// has no mapper.
  bool AdoptVolume(vtkVolume* volume, std::optional<mmv::MapperSettings>& mmvMapper);

  /// Render()'s common checks: a renderer with a camera, a positive size,
  /// input data and a property with a scalar opacity (an error otherwise).
  bool CheckRenderInputs(vtkRenderer* ren, int width, int height);

  vtkSmartPointer<vtkImageData> Input;
  vtkSmartPointer<vtkVolumeProperty> Property;
  vtkSmartPointer<vtkMaterialTransferFunction> Materials;
  vtkSmartPointer<vtkMatrix4x4> Matrix;

private:
  vtkMultiMaterialVolumeScene(const vtkMultiMaterialVolumeScene&) = delete;
  void operator=(const vtkMultiMaterialVolumeScene&) = delete;
};

#endif
