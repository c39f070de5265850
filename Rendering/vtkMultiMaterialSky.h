/**
 * @class   vtkMultiMaterialSky
 * @brief   The environment light of vtkMultiMaterialVolumeMapper: the
 *          renderer's background (or environment texture) as a sky that
 *          lights the volume through its occlusion.
 *
 * Update() estimates the sky's visibility moments (vtkSkyVisibility.h) on a
 * grid of at most mmv::SkyVoxelsPerAxis voxels per axis spanning the data's
 * points, from the extinction the shadows use (opacity, unit distance and
 * the materials' attenuation), averaged over each sky voxel, and uploads them
 * as one RGBA 3D texture; where materials scatter, each moment is diffused
 * as a light's irradiance is. It re-estimates only when the data, the
 * range or the sampled extinction or scattering change; the sky's colours
 * (SetColors, from the background) are uniforms, so a new background only
 * reshades.
 *
 * The ray cast adds mmvSkyRadiance (Shaders/mmvShading.glsl) per segment:
 * the sky's single scattering as the path tracer models it, isotropic for
 * particles and Lambertian for surfaces, with the sky's radiance fitted as
 * L(w) = mean + slope w (exact for VTK's background gradient).
 * Not a vtkObject: plain state owned by the mapper.
 */
#ifndef vtkMultiMaterialSky_h
#define vtkMultiMaterialSky_h

#include "vtkCoarseExtinction.h"          // CoarseExtinction
#include "vtkIrradianceGrid.h"            // IrradianceGrid
#include "vtkMultiMaterialVolumeModule.h" // export macro
#include "vtkNew.h"
#include "vtkSkyVisibility.h" // SkyVoxelsPerAxis, SkyDirectionCount
#include "vtkSmartPointer.h"
#include "vtkType.h" // vtkMTimeType

#include <glm/glm.hpp>

#include <list>
#include <string>
#include <vector>

class vtkDataArray;
class vtkImageData;
class vtkMaterialTransferFunction;
class vtkMultiMaterialEnvironment;
class vtkMatrix4x4;
class vtkOpenGLRenderWindow;
class vtkRenderer;
class vtkShaderProgram;
class vtkTextureObject;
class vtkVolumeProperty;
class vtkWindow;

namespace mmv
{
/// What one frame's sky reads.
struct SkyInputs
{
  vtkRenderer* Renderer = nullptr;
  vtkMatrix4x4* WorldToObject = nullptr; // the volume's
  vtkImageData* Image = nullptr;
  vtkDataArray* Scalars = nullptr; // one component, point data of Image
  const double* Range = nullptr;
  vtkVolumeProperty* Property = nullptr; // its first opacity
  vtkMaterialTransferFunction* Materials = nullptr;
  int TableSize = 256;
  double Strength = 0.0;          // EnvironmentLighting
  bool UseTexture = true;         // the environment texture, when the renderer has one
  bool Distributed = false;       // the image is one piece of a distributed volume
  bool MultipleScattering = true; // the sky's light diffuses where materials scatter
  bool ExponentialDiffusion = true;
};
}

class VTKMULTIMATERIALVOLUME_EXPORT vtkMultiMaterialSky
{
public:
  vtkMultiMaterialSky();
  ~vtkMultiMaterialSky();

  /**
   * The frame's sky: its colours, and its visibility when the data or the
   * opacity changed. False: no sky this frame (off, black, distributed,
   * a bad strength: `warnings` say why; or the GPU failed: `error`).
   */
  bool Refresh(
    const mmv::SkyInputs& inputs, std::vector<std::string>& warnings, std::string& error);

  /**
   * Brings the visibility up to date for `scalars` (point data of `image`,
   * one component, normalised over `range`) under `property`'s first
   * opacity and `materials`' attenuation. False: nothing to bind (an error
   * was reported through `problem`).
   */
  bool Update(vtkOpenGLRenderWindow* context, const mmv::SkyInputs& in, std::string* problem);

  /// The sky's radiance: `strength` times the renderer's background (its
  /// environment texture when `useTexture` and it has one), in the object
  /// space of `worldToObject`. Returns whether the sky is dark (nothing to
  /// shade).
  bool SetColors(vtkRenderer* ren, vtkMatrix4x4* worldToObject, double strength, bool useTexture,
    std::vector<std::string>* problems);

  /// The environment the colours come from (pin ParaView's background on it,
  /// as on the reflections').
  vtkMultiMaterialEnvironment* GetEnvironment() { return this->Environment; }

  /// The sky's uniforms and texture unit (the texture must be active).
  void SetUniforms(vtkShaderProgram* program) const;
  void Activate();
  void Deactivate();

  /// Estimations so far, the last one's wall seconds, the grid.
  int GetUpdateCount() const { return this->UpdateCount; }
  double GetLastSeconds() const { return this->LastSeconds; }
  const mmv::IrradianceGrid& GetGrid() const { return this->Grid; }
  /// The visibility moments of the last estimation (mmv::SkyMomentsPerVoxel per voxel).
  const std::vector<float>& GetMoments() const { return this->Moments; }

  void ReleaseGraphicsResources(vtkWindow* window);

private:
  vtkMultiMaterialSky(const vtkMultiMaterialSky&) = delete;
  void operator=(const vtkMultiMaterialSky&) = delete;

  /// What the moments were estimated from: the data, and the sampled
  /// extinction and scattering (not the tables' times, so that an edit of a
  /// colour or of ka re-estimates nothing).
  struct Key
  {
    // The data: its array and that array's time (the image around it may be
    // a new copy each frame, as in ParaView), and the points' geometry.
    vtkDataArray* Scalars = nullptr;
    vtkMTimeType ScalarsTime = 0;
    mmv::IrradianceGrid Points;
    double Range[2] = { 0.0, 0.0 };
    std::vector<float> Extinction; // per unit length, over the range
    std::vector<float> Scattering; // s where the opacity is > 0; empty: no diffusion
    bool Exponential = true;
    bool operator==(const Key& o) const;
  };

  /// The data's extinction averaged onto the sky's grid (Extinction) and
  /// its visibility moments (Moments).
  void EstimateMoments(vtkImageData* image, vtkDataArray* scalars, const Key& key);
  /// Multiple scattering: each moment diffused with the scattering averaged
  /// onto the sky's grid (the diffusion is linear: any sky still shades).
  void DiffuseMoments(
    const mmv::IrradianceGrid& points, const mmv::IrradianceGrid& grid, const Key& key);
  /// Moments into the texture: in place when the grid keeps its size.
  bool Upload(
    vtkOpenGLRenderWindow* context, const mmv::IrradianceGrid& grid, std::string* problem);

  bool HasKey = false;
  Key Held;
  /// The moments of earlier data (a series' steps, which ParaView's
  /// animation caching hands back), most recent first: about 1 MB each on
  /// the CPU, so that a second loop estimates nothing.
  struct KeptMoments
  {
    Key From;
    mmv::IrradianceGrid Grid;
    std::vector<float> Moments;
  };
  std::list<KeptMoments> Kept;
  static constexpr size_t MaxKept = 32;
  /// Makes the kept moments of `key` on `grid` current; false: none kept.
  bool RestoreKept(const Key& key, const mmv::IrradianceGrid& grid);

  vtkNew<vtkMultiMaterialEnvironment> Environment;
  mmv::CoarseExtinction Extinction; // on the sky's grid, as the other volumes' shadows see it
  std::vector<float> Moments;
  mmv::IrradianceGrid Grid;
  int DataDimensions[3] = { 1, 1, 1 }; // the points the grid spans
  vtkSmartPointer<vtkTextureObject> Texture;
  int UpdateCount = 0;
  double LastSeconds = 0.0;

  glm::vec3 Mean{ 0.0f };
  glm::mat3 Slope{ 0.0f }; // colour = Slope * direction
};

#endif
