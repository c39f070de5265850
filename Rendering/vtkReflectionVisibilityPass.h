/**
 * @class   vtkReflectionVisibilityPass
 * @brief   The view-dependent visibility of reflections (Zhang & Ma eq. 17,
 *          Algorithm 1 lines 10-11): I(x, w_r) at every irradiance voxel in a
 *          3D texture, recomputed only when its inputs change.
 *
 * One GL resource: an R16 3D texture at irradiance resolution, filled by one
 * instanced layered draw (as vtkIrradianceEstimator fills its targets) of
 * Shaders/mmvReflectionVisibilityFS.glsl, which marches the irradiance pass's
 * pre-filtered extinction along the mirror direction of each voxel. The
 * caller (vtkMultiMaterialReflection) composes the march's defines, sets its
 * uniforms and says by a key (camera, volume, cutaway, grid) when the
 * texture is stale; the ray cast then interpolates it
 * (MMV_REFLECTION_VISIBILITY 2).
 */
#ifndef vtkReflectionVisibilityPass_h
#define vtkReflectionVisibilityPass_h

#include "vtkMultiMaterialVolumeModule.h" // export macro
#include "vtkObject.h"

#include <functional> // uniforms
#include <string>     // defines
#include <vector>     // key

class vtkOpenGLRenderWindow;
class vtkShaderProgram;
class vtkTextureObject;
class vtkWindow;

class VTKMULTIMATERIALVOLUME_EXPORT vtkReflectionVisibilityPass : public vtkObject
{
public:
  static vtkReflectionVisibilityPass* New();
  vtkTypeMacro(vtkReflectionVisibilityPass, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Recomputes the texture (`dims` voxels) unless `key` equals the last
   * computed one: the fragment shader is `defines` followed by the march
   * (mmvCutaway, mmvShadowRay, mmvReflectionMarch.glsl) and
   * mmvReflectionVisibilityFS.glsl; `setUniforms` sets its uniforms, with
   * the textures it samples active. `region` (i0, i1, j0, j1, k0, k1,
   * inclusive), when given, limits the draw to the voxels a piece reads
   * (vtkIrradianceEstimator::GetRegion): each voxel is its own march, so
   * they equal the whole texture's; the others keep what they held (it
   * belongs in `key`). Needs the context current. False (with an error)
   * when the context cannot draw it.
   */
  bool Update(vtkOpenGLRenderWindow* context, const int dims[3], const int* region,
    const std::string& defines, const std::vector<double>& key,
    const std::function<void(vtkShaderProgram*)>& setUniforms);

  /// The visibility (R16, linear; nullptr before a successful Update()).
  vtkTextureObject* GetVisibilityTexture() const;

  /// Textures computed so far (a test hook: only camera or volume changes count).
  vtkGetMacro(UpdateCount, vtkIdType);

  void ReleaseGraphicsResources(vtkWindow* window);

protected:
  vtkReflectionVisibilityPass();
  ~vtkReflectionVisibilityPass() override;

  vtkIdType UpdateCount = 0;

private:
  vtkReflectionVisibilityPass(const vtkReflectionVisibilityPass&) = delete;
  void operator=(const vtkReflectionVisibilityPass&) = delete;

  class vtkInternals;
  vtkInternals* Internals;
};

#endif
