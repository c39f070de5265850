/**
 * @class   vtkMultiMaterialShaderHook
 * @brief   Carries the mapper's shader replacements and uniform/texture binding
 *          into vtkOpenGLGPUVolumeRayCastMapper.
 *
 * VTK 9.2's shader-building methods are not virtual, and ParaView renders
 * volumes through vtkLODProp3D, which does not forward a volume's shader
 * property. A vtkOpenGLRenderPass placed in the volume's RenderPasses() key is
 * consulted by the base mapper on every shader build (Pre/PostReplaceShaderValues)
 * and every draw (SetShaderParameters), whatever prop holds the volume, so
 * vtkMultiMaterialVolumeMapper installs one from inside GPURender().
 *
 * The hook acts only for its owner mapper and is inert otherwise; its shader
 * stage MTime changes only when the replacements change, so a camera move or
 * a new light colour never rebuilds the shader.
 */
#ifndef vtkMultiMaterialShaderHook_h
#define vtkMultiMaterialShaderHook_h

#include "vtkMultiMaterialVolumeModule.h" // export macro
#include "vtkOpenGLRenderPass.h"

#include <functional> // parameter callback
#include <string>     // replacements
#include <utility>    // std::pair
#include <vector>     // replacements

class vtkAbstractMapper;
class vtkInformation;

class VTKMULTIMATERIALVOLUME_EXPORT vtkMultiMaterialShaderHook : public vtkOpenGLRenderPass
{
public:
  static vtkMultiMaterialShaderHook* New();
  vtkTypeMacro(vtkMultiMaterialShaderHook, vtkOpenGLRenderPass);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  using Replacements = std::vector<std::pair<std::string, std::string>>;
  using ParameterCallback = std::function<void(vtkShaderProgram*)>;

  /// The mapper this pass serves (not reference counted; the mapper clears
  /// it in its destructor).
  void SetOwner(vtkAbstractMapper* owner) { this->Owner = owner; }

  /// Fragment-shader tag -> text, applied before VTK's own substitutions.
  /// Bumps the shader stage MTime only when they differ from the current ones.
  void SetFragmentReplacements(const Replacements& replacements);
  const Replacements& GetFragmentReplacements() const { return this->FragmentReplacements; }

  /// Called with the bound program before each draw of the owner.
  void SetParameterCallback(ParameterCallback callback) { this->Callback = std::move(callback); }

  /// The fragment shader source after the last build with this pass (tests).
  const std::string& GetLastFragmentSource() const { return this->LastFragmentSource; }

  /// Puts this pass first in `keys`' RenderPasses() list if it is not there.
  /// First, because the base mapper sizes its draw buffers from the last pass
  /// (dual depth peeling must stay last).
  void InstallInto(vtkInformation* keys);
  /// Takes this pass out of `keys`' RenderPasses() list.
  /// Both leave every reference count as balanced as they found it, unlike
  /// VTK 9.2's key Append()/Clear() (see the .cxx), so the hook dies with the
  /// volume or the mapper, whichever goes last.
  void RemoveFrom(vtkInformation* keys);

  bool PreReplaceShaderValues(std::string& vertexShader, std::string& geometryShader,
    std::string& fragmentShader, vtkAbstractMapper* mapper, vtkProp* prop) override;
  bool PostReplaceShaderValues(std::string& vertexShader, std::string& geometryShader,
    std::string& fragmentShader, vtkAbstractMapper* mapper, vtkProp* prop) override;
  bool SetShaderParameters(vtkShaderProgram* program, vtkAbstractMapper* mapper, vtkProp* prop,
    vtkOpenGLVertexArrayObject* vao = nullptr) override;
  vtkMTimeType GetShaderStageMTime() override;

  /// Never used as a scene pass.
  void Render(const vtkRenderState*) override {}

protected:
  vtkMultiMaterialShaderHook();
  ~vtkMultiMaterialShaderHook() override;

private:
  vtkMultiMaterialShaderHook(const vtkMultiMaterialShaderHook&) = delete;
  void operator=(const vtkMultiMaterialShaderHook&) = delete;

  vtkAbstractMapper* Owner = nullptr;
  Replacements FragmentReplacements;
  ParameterCallback Callback;
  std::string LastFragmentSource;
  vtkTimeStamp ReplacementTime;
};

#endif
