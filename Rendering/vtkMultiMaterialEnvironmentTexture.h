/**
 * @class   vtkMultiMaterialEnvironmentTexture
 * @brief   The environment colour c_r of eq. 17 on the GPU: binds the
 *          renderer's environment texture and sets the uniforms of
 *          Shaders/mmvReflection.glsl.
 *
 * The GL side of vtkMultiMaterialEnvironment (Filters/, CPU), which it owns:
 * Update() reads the renderer's environment there (texture images, frame,
 * background gradient), Activate() uploads (when the images changed) and
 * binds the same vtkTexture VTK's skybox uses, and SetUniforms() passes the
 * frame and colours read on the CPU, so the shader and
 * vtkMultiMaterialEnvironment::Lookup() read the same texels.
 */
#ifndef vtkMultiMaterialEnvironmentTexture_h
#define vtkMultiMaterialEnvironmentTexture_h

#include "vtkMultiMaterialVolumeModule.h" // export macro
#include "vtkNew.h"                       // environment
#include "vtkObject.h"

#include <string> // problems
#include <vector> // problems

class vtkMatrix4x4;
class vtkMultiMaterialEnvironment;
class vtkRenderer;
class vtkShaderProgram;

class VTKMULTIMATERIALVOLUME_EXPORT vtkMultiMaterialEnvironmentTexture : public vtkObject
{
public:
  static vtkMultiMaterialEnvironmentTexture* New();
  vtkTypeMacro(vtkMultiMaterialEnvironmentTexture, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// vtkMultiMaterialEnvironment::Update() of the environment, and the
  /// renderer whose context Activate() uses.
  void Update(
    vtkRenderer* ren, vtkMatrix4x4* objectToWorld, int source, std::vector<std::string>* problems);

  /// The CPU environment of the last Update().
  vtkMultiMaterialEnvironment* GetEnvironment();

  ///@{
  /// Uploads (if needed) and binds the texture, sets the uniforms of
  /// Shaders/mmvReflection.glsl, unbinds. Between Activate() and Deactivate()
  /// the renderer of the last Update() must be current.
  void Activate();
  void Deactivate();
  void SetUniforms(vtkShaderProgram* program) const;
  ///@}

protected:
  vtkMultiMaterialEnvironmentTexture();
  ~vtkMultiMaterialEnvironmentTexture() override;

private:
  vtkMultiMaterialEnvironmentTexture(const vtkMultiMaterialEnvironmentTexture&) = delete;
  void operator=(const vtkMultiMaterialEnvironmentTexture&) = delete;

  vtkNew<vtkMultiMaterialEnvironment> Environment;
  vtkRenderer* Renderer = nullptr; // of the last Update(), not owned
  bool Active = false;
};

#endif
