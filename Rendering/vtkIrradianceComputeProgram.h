/**
 * @class   vtkIrradianceComputeProgram
 * @brief   A compute-shader program that VTK's shader cache can bind.
 *
 * VTK 9.2's vtkShaderProgram knows vertex, fragment and geometry shaders
 * only. This subclass links a compute shader into the same program object,
 * so that vtkOpenGLShaderCache::ReadyShaderProgram() binds it (its
 * bookkeeping of the bound program stays right) and the SetUniform*()
 * methods work unchanged. vtkIrradianceEstimator dispatches its voxel
 * passes with it where the context has OpenGL 4.3.
 */
#ifndef vtkIrradianceComputeProgram_h
#define vtkIrradianceComputeProgram_h

#include "vtkMultiMaterialVolumeModule.h"
#include "vtkShaderProgram.h"

#include <string>

class VTKMULTIMATERIALVOLUME_EXPORT vtkIrradianceComputeProgram : public vtkShaderProgram
{
public:
  static vtkIrradianceComputeProgram* New();
  vtkTypeMacro(vtkIrradianceComputeProgram, vtkShaderProgram);

  /// Compiles and links `source` (with its #version line) in the current
  /// context; false, with the compiler's log in GetError(), on failure.
  bool Build(const std::string& source);

  /// Whether the current context runs compute shaders with image stores
  /// (OpenGL 4.3).
  static bool IsSupported();

  /// Whether the current context renders on the CPU (Mesa's llvmpipe,
  /// softpipe or swrast), where compute dispatches do not pay.
  static bool IsSoftwareRenderer();

protected:
  vtkIrradianceComputeProgram() = default;
  ~vtkIrradianceComputeProgram() override = default;

private:
  vtkIrradianceComputeProgram(const vtkIrradianceComputeProgram&) = delete;
  void operator=(const vtkIrradianceComputeProgram&) = delete;
};

#endif
