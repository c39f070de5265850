/**
 * @class   vtkMultiMaterialEnvironment
 * @brief   The environment colour c_r(omega_r) of Zhang & Ma eq. 17, read from
 *          a renderer: its environment texture or its background.
 *
 * Source (mmv::ReflectionSource): the renderer's environment texture
 * (vtkRenderer::SetEnvironmentTexture, which ParaView's "Skybox" background
 * with environment lighting sets) when one is set: a cube map (six 2D images,
 * +x -x +y -y +z -z) or one 2D equirectangular image, oriented by the
 * renderer's EnvironmentUp and EnvironmentRight exactly as VTK's skybox
 * shows it. Otherwise, or with mmv::ReflectBackground, the background: its
 * vertical gradient around the camera's view-up (Background at the bottom,
 * Background2 at the top when GradientBackground is on), as before.
 *
 * Bad input gets a warning (Update()'s problems) and the background: a
 * texture whose input is not a 2D image (a 3D image, a cube map without six
 * equal 2D faces) or an empty image (no points, no scalars).
 *
 * This is the CPU side (no OpenGL): Update() reads the texture's input
 * images (vtkImageData, not the GL texture) and Lookup() samples them as
 * OpenGL does (nearest or bilinear as the texture's Interpolate, repeat or
 * clamp as its Repeat, sRGB decoded when the texture says so; 8-bit values /
 * 255, others as they are), for the reference renderer. The GPU side,
 * vtkMultiMaterialEnvironmentTexture (Rendering/), binds the same texture and
 * sets the uniforms of Shaders/mmvReflection.glsl from the frame and colours
 * read here, so both read the same texels.
 */
#ifndef vtkMultiMaterialEnvironment_h
#define vtkMultiMaterialEnvironment_h

#include "vtkMultiMaterialEnvironmentLookup.h"   // mmv::ReflectionSource, EnvironmentKind
#include "vtkMultiMaterialVolumeFiltersModule.h" // export macro
#include "vtkObject.h"
#include "vtkSmartPointer.h" // images

#include <glm/glm.hpp> // directions
#include <string>      // problems
#include <vector>      // faces

class vtkImageData;
class vtkMatrix4x4;
class vtkRenderer;
class vtkTexture;

class VTKMULTIMATERIALVOLUMEFILTERS_EXPORT vtkMultiMaterialEnvironment : public vtkObject
{
public:
  static vtkMultiMaterialEnvironment* New();
  vtkTypeMacro(vtkMultiMaterialEnvironment, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Reads `ren`'s environment for a volume whose object space maps to world
   * space by `objectToWorld` (the volume's matrix). Problems with the texture
   * (the background is used instead) are appended to `problems`.
   */
  void Update(
    vtkRenderer* ren, vtkMatrix4x4* objectToWorld, int source, std::vector<std::string>* problems);

  /**
   * Pins the background gradient Update() reads (bottom and top colours)
   * instead of the renderer's. ParaView clears the renderer's background to
   * black while parallel ranks draw for compositing, so its representation
   * pins the view's background before each render. Clear to read the
   * renderer again. Both return whether anything changed.
   */
  bool SetBackgroundOverride(const double bottom[3], const double top[3]);
  bool ClearBackgroundOverride();

  /// mmv::EnvironmentKind of the last Update().
  int GetKind() const { return this->Kind; }

  /// c_r along object-space direction d (any length but zero), on the CPU.
  glm::dvec3 Lookup(const glm::dvec3& d) const;

  /// The environment as a sky of radiance mean + slope w (object space):
  /// exact for the background's gradient, the least-squares (order-1
  /// spherical-harmonic) fit of a texture. vtkMultiMaterialSky and the
  /// reference renderer light the volume with it.
  void FitLinear(glm::dvec3& mean, glm::dmat3& slope) const;

  ///@{
  /// What the GPU side uploads and binds: the renderer's texture (null for
  /// the background), whether its images are grey (one or two components),
  /// the texture's frame in object space (right, up, front) and the
  /// background gradient (object-space view-up, bottom and top colours).
  vtkTexture* GetTexture() const;
  bool GetGrey() const;
  const glm::dvec3& GetFrameRight() const { return this->Right; }
  const glm::dvec3& GetFrameUp() const { return this->Up; }
  const glm::dvec3& GetFrameFront() const { return this->Front; }
  const glm::dvec3& GetViewUp() const { return this->ViewUp; }
  const glm::dvec3& GetBackgroundBottom() const { return this->Bottom; }
  const glm::dvec3& GetBackgroundTop() const { return this->Top; }
  ///@}

protected:
  vtkMultiMaterialEnvironment();
  ~vtkMultiMaterialEnvironment() override;

private:
  vtkMultiMaterialEnvironment(const vtkMultiMaterialEnvironment&) = delete;
  void operator=(const vtkMultiMaterialEnvironment&) = delete;

  // Checks the texture's inputs and keeps its images; false (with the
  // problem) when it cannot be used.
  bool ReadTexture(vtkTexture* texture, std::string& problem);
  glm::dvec3 SampleImage(int image, const glm::dvec2& st, bool repeat) const;
  glm::dvec3 Texel(int image, int i, int j) const;

  int Kind = mmv::BackgroundEnvironment;
  vtkSmartPointer<vtkTexture> Texture;
  std::vector<vtkSmartPointer<vtkImageData>> Images;
  bool Interpolate = false;
  bool Repeat = true;
  bool SRGB = false;
  // The frame in object space (world axes pulled back by objectToWorld).
  glm::dvec3 Right{ 1.0, 0.0, 0.0 };
  glm::dvec3 Up{ 0.0, 1.0, 0.0 };
  glm::dvec3 Front{ 0.0, 0.0, -1.0 };
  // Background gradient: object-space view-up and the two colours.
  glm::dvec3 ViewUp{ 0.0, 1.0, 0.0 };
  glm::dvec3 Bottom{ 0.0 };
  glm::dvec3 Top{ 0.0 };
  bool Override = false;
  glm::dvec3 OverrideBottom{ 0.0 };
  glm::dvec3 OverrideTop{ 0.0 };
};

#endif
