/**
 * @class   vtkMultiMaterialReflection
 * @brief   The environment reflection of Zhang & Ma eq. 17 for the GPU ray
 *          caster: where c_r comes from and how I(x, w_r) is estimated.
 *
 * Consumer of two producers: the environment (vtkMultiMaterialEnvironment
 * from the renderer, bound by vtkMultiMaterialEnvironmentTexture) and the pre-filtered extinction
 * of the irradiance pass (vtkIrradianceEstimator: its scalars and shadow-opacity table, marched as
 * its shadow rays march them). Gives the shader variant its
 * MMV_ENVIRONMENT and MMV_REFLECTION_VISIBILITY, binds the textures and sets
 * the uniforms of Shaders/mmvReflection.glsl.
 *
 * The visibility is marched from each shaded sample
 * (mmv::MarchedReflectionVisibility) or from each irradiance voxel by
 * vtkReflectionVisibilityPass when the camera or the volume changed
 * (mmv::ViewDependentReflectionVisibility). Either needs the pre-filtered
 * volume, which the irradiance pass
 * builds only when there is a light: without one, reflections are unoccluded
 * (with a warning); the reference renderer does the same.
 */
#ifndef vtkMultiMaterialReflection_h
#define vtkMultiMaterialReflection_h

#include "vtkMultiMaterialVolumeModule.h" // export macro
#include "vtkNew.h"                       // environment
#include "vtkObject.h"

#include <string> // problems
#include <vector> // problems

class vtkIrradianceEstimator;
class vtkMaterialTransferFunction;
class vtkMatrix4x4;
class vtkMultiMaterialEnvironment;
class vtkMultiMaterialEnvironmentTexture;
class vtkReflectionVisibilityPass;
class vtkRenderer;
class vtkShaderProgram;
class vtkWindow;
namespace mmv
{
struct IrradianceGrid;
}

class VTKMULTIMATERIALVOLUME_EXPORT vtkMultiMaterialReflection : public vtkObject
{
public:
  static vtkMultiMaterialReflection* New();
  vtkTypeMacro(vtkMultiMaterialReflection, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Reads the environment (`source`: mmv::ReflectionSource) and, for
   * `visibility` (mmv::ReflectionVisibility; Automatic resolves to the
   * per-sample march or the pass from the renderer's size and the grid's
   * voxels, mmv::PerSampleMarchPixelsPerVoxel), the pass's pre-filtered volume
   * on `grid` with its table of `tableSize` entries built for `stepLength`
   * (object units); `pass` may be null (no light). What cannot be honoured
   * is appended to `problems`. With `keepWhileCameraMoves` (an interactive
   * frame), the view-dependent visibility of an earlier camera is kept as
   * long as the volume is the same; the next frame without it recomputes.
   */
  void Update(vtkRenderer* ren, vtkMatrix4x4* objectToWorld, int source, int visibility,
    vtkIrradianceEstimator* pass, const mmv::IrradianceGrid& grid, int tableSize, double stepLength,
    std::vector<std::string>* problems, bool keepWhileCameraMoves = false);

  /**
   * Where the materials can reflect, for the view-dependent pass to skip
   * the voxels whose neighbourhood holds no such value: the interval of
   * `materials`' GetNonZeroRange(mmv::Reflection) in the pass's normalised
   * values over `scalarRange`, widened by one step of the material table
   * (`tableSize` entries: the ray cast interpolates between them). Call
   * before Update(); without materials the whole range counts.
   */
  void SetReflectiveValues(
    vtkMaterialTransferFunction* materials, const double scalarRange[2], int tableSize);
  /// The interval in the pass's normalised values (0..1: everything).
  const float* GetReflectiveRange() const { return this->ReflectiveRange; }

  /// mmv::EnvironmentKind and mmv::ReflectionVisibility in effect.
  int GetEnvironmentKind() const;
  int GetVisibility() const { return this->Visibility; }
  /// Whether the marched visibility honours a cutaway (the pass's cropping
  /// region and clipping planes: what they remove does not occlude).
  bool GetCutaway() const { return this->Cutaway; }
  vtkMultiMaterialEnvironment* GetEnvironment();
  /// The view-dependent pass (its UpdateCount: how often it was recomputed).
  vtkReflectionVisibilityPass* GetVisibilityPass();

  void ReleaseGraphicsResources(vtkWindow* window);

  ///@{
  /// Binds / unbinds the textures; the uniforms of mmvReflection.glsl.
  void Activate();
  void Deactivate();
  void SetUniforms(vtkShaderProgram* program) const;
  ///@}

protected:
  vtkMultiMaterialReflection();
  ~vtkMultiMaterialReflection() override;

private:
  vtkMultiMaterialReflection(const vtkMultiMaterialReflection&) = delete;
  void operator=(const vtkMultiMaterialReflection&) = delete;

  bool UpdateVisibilityPass(vtkRenderer* ren, vtkMatrix4x4* objectToWorld,
    const mmv::IrradianceGrid& grid, bool keepWhileCameraMoves, std::vector<std::string>* problems);
  void SetMarchUniforms(vtkShaderProgram* program) const;

  vtkNew<vtkMultiMaterialEnvironmentTexture> Environment;
  vtkNew<vtkReflectionVisibilityPass> VisibilityPass;
  int Visibility = 0;
  bool Cutaway = false;
  vtkIrradianceEstimator* Pass = nullptr; // not owned
  float ToIndex[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  float ToObject[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  float Eye[4] = { 0, 0, 1, 0 };
  std::vector<double> VolumeKey; // of the view-dependent visibility held
  float Origin[3] = { 0, 0, 0 };
  int Dimensions[3] = { 1, 1, 1 };
  float Offset = 0.0f;
  float TableSize = 1.0f;
  float StepLength = 1.0f;
  float ReflectiveRange[2] = { 0.0f, 1.0f };
};

#endif
