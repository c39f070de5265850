/**
 * @class   vtkMultiMaterialPathTracer
 * @brief   Physically based Monte Carlo reference: an unbiased solution of the
 *          radiative transfer equation on the mapper's inputs (Kroes et al.,
 *          Exposure Render), on the CPU with vtkSMPTools.
 *
 * vtkMultiMaterialReferenceRenderer renders *our* optical model exactly (the
 * same-model reference); this class renders the *physics* the models
 * approximate (the physical reference), so that every real-time method can be
 * scored against one truth.
 *
 *  - Medium: extinction sigma_t = -ln(1 - alpha) / u (alpha: scalar opacity of
 *    the trilinearly interpolated scalar, u: scalar-opacity unit distance, as
 *    everywhere else); single-scattering albedo = the colour TF's RGB, per
 *    channel; Henyey-Greenstein phase function with the material's
 *    anisotropy g (vtkMultiMaterialPhaseFunction.h); emission e * colour *
 *    sigma_t per unit length (Yang et al. eq. 27, the ray caster's e * I_c
 *    per segment), scored at every collision.
 *  - Free flights by delta (Woodcock) tracking against a majorant grid (the
 *    largest extinction per brick of 8^3 cells), so empty space costs one
 *    step per brick; shadow rays by ratio tracking on the same grid.
 *  - Next-event estimation to every active light (no limit of eight), with
 *    the mapper's light conventions (vtkMultiMaterialLights.h): directional,
 *    point (falloff of eq. 12, radius PointLightRadius) and spot lights, each
 *    delivering colour * intensity * geometry term as irradiance.
 *  - Multiple scattering, up to MaxBounces events, Russian roulette from the
 *    third event on (survival = the path's largest throughput channel).
 *  - The renderer's background is an infinitely distant environment: camera
 *    rays that leave the volume see it as VTK draws it (its vertical
 *    gradient in screen space when GradientBackground is on); scattered rays
 *    that leave it gather it by direction, the gradient running along the
 *    camera's view-up (mmv::mmvEnvironment, as our reflection does).
 *  - Surface scattering (on by default; Kroes et al. §3.3): at an event, a
 *    BRDF instead of the phase function with probability
 *    1 - exp(-|grad| / SurfaceGradientPerVoxel), |grad| the normalised
 *    value's gradient per voxel. The BRDF is albedo * ((1 - ks) / pi +
 *    ks (e + 8) / (8 pi) cos^e(theta_h)), normalised Blinn-Phong from the
 *    material's ks and shininess e: it never reflects more than it receives.
 *  - One path per sample through each pixel centre (no anti-aliasing, so
 *    pixels line up with the other renderers'). Each pixel's random stream is
 *    seeded from Seed and the pixel index alone: the image is the same for any
 *    thread count. The per-pixel standard error of the mean is returned with
 *    the image.
 *
 * Not Python-wrapped (like the reference renderer): use the mmvBenchmark
 * program. vtkSMPTools runs sequentially unless a threaded backend is
 * selected (e.g. VTK_SMP_BACKEND_IN_USE=STDThread).
 */
#ifndef vtkMultiMaterialPathTracer_h
#define vtkMultiMaterialPathTracer_h

#include "vtkMultiMaterialVolumeFiltersModule.h" // export macro
#include "vtkMultiMaterialVolumeScene.h"
#include "vtkSmartPointer.h" // members

class vtkImageData;
class vtkMaterialTransferFunction;
class vtkMatrix4x4;
class vtkRenderer;
class vtkVolume;
class vtkVolumeProperty;

class VTKMULTIMATERIALVOLUMEFILTERS_EXPORT vtkMultiMaterialPathTracer
  : public vtkMultiMaterialVolumeScene
{
public:
  static vtkMultiMaterialPathTracer* New();
  vtkTypeMacro(vtkMultiMaterialPathTracer, vtkMultiMaterialVolumeScene);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  // The scene (data, property, materials, matrix): vtkMultiMaterialVolumeScene.

  /// Surface events (Kroes et al.): the gradient of the normalised value per
  /// voxel g0 in the probability 1 - exp(-|grad| / g0) of a BRDF event. The
  /// ground truth's own definition, kept apart from the ray caster's hybrid
  /// share (mmv::SurfaceEqualShareGradientPerVoxel) so the truth does not move
  /// with the model it judges.
  static constexpr double SurfaceGradientPerVoxel = 0.005;

  /// Paths per pixel (default 64). Render() rejects values below 1.
  vtkSetMacro(SamplesPerPixel, int);
  vtkGetMacro(SamplesPerPixel, int);

  /// Most scattering events on a path (default 64; 1 = single scattering,
  /// 0 = attenuated background and emission only). Render() rejects
  /// negative values.
  vtkSetMacro(MaxBounces, int);
  vtkGetMacro(MaxBounces, int);

  /// Hybrid BRDF/phase-function events (default on); off: the phase
  /// function at every event.
  vtkSetMacro(SurfaceScattering, bool);
  vtkGetMacro(SurfaceScattering, bool);
  vtkBooleanMacro(SurfaceScattering, bool);

  /// Radius epsilon of point and spot lights; 0 (default): smallest spacing.
  vtkSetClampMacro(PointLightRadius, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(PointLightRadius, double);

  /// Seed of the per-pixel random streams (default 0): same seed, same image.
  vtkSetMacro(Seed, unsigned int);
  vtkGetMacro(Seed, unsigned int);

  /**
   * Renders the scene as the renderer's active camera, lights and background
   * show it at width x height. The returned image (owned by this object,
   * replaced by the next render) has width x height x 1 points, bottom row
   * first like vtkRenderWindow::GetPixelData, with the double RGB arrays
   * "Radiance" (the per-pixel mean, unclamped) and "StandardError" (of that
   * mean) and the unsigned-char RGB scalars "Colors" (clamped to [0, 1],
   * rounded). Returns null (with an error) on invalid input.
   */
  vtkImageData* Render(vtkRenderer* ren, int width, int height);

  /// Render() with the input, property and matrix of `volume` (and, for a
  /// vtkMultiMaterialVolumeMapper, its material function and
  /// PointLightRadius), at the renderer's size in pixels.
  vtkImageData* RenderToImage(vtkRenderer* ren, vtkVolume* volume);

  ///@{
  /// What the last render did.
  vtkGetMacro(LastRenderSeconds, double);
  vtkGetMacro(NumberOfPaths, long long);
  vtkGetMacro(NumberOfEvents, long long);
  ///@}

protected:
  vtkMultiMaterialPathTracer();
  ~vtkMultiMaterialPathTracer() override;

  int SamplesPerPixel = 64;
  int MaxBounces = 64;
  bool SurfaceScattering = true;
  double PointLightRadius = 0.0;
  unsigned int Seed = 0;

  double LastRenderSeconds = 0.0;
  long long NumberOfPaths = 0;
  long long NumberOfEvents = 0;

private:
  vtkMultiMaterialPathTracer(const vtkMultiMaterialPathTracer&) = delete;
  void operator=(const vtkMultiMaterialPathTracer&) = delete;

  vtkSmartPointer<vtkImageData> Output;
};

#endif
