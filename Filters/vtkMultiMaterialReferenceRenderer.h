/**
 * @class   vtkMultiMaterialReferenceRenderer
 * @brief   Ground-truth CPU renderer of the multi-material optical model,
 *          without the decoupling shortcuts (the reference of Zhang & Ma Fig. 9).
 *
 * Renders what vtkMultiMaterialVolumeMapper approximates, in double precision,
 * one ray per pixel centre (vtkSMPTools over image rows):
 *
 *  - Camera: the renderer's active camera (parallel or perspective) at the
 *    requested image size; the ray of pixel (i, j) runs from the near to the
 *    far plane through NDC ((i + 0.5) / W * 2 - 1, (j + 0.5) / H * 2 - 1).
 *    Rays are traced in the volume's object (data) space.
 *  - Quadrature: the ray's part inside the data bounds is cut into equal
 *    segments no longer than SampleDistance (default: smallest spacing / 8);
 *    each segment is evaluated at its midpoint (trilinear value) with
 *    alpha = 1 - exp(-mu h), I_c = c alpha (plain midpoint rule, no
 *    pre-integration tables), and composited front to back. Rays stop once
 *    the transmittance drops below MinimumTransmittance.
 *  - Irradiance: at every segment midpoint, one shadow ray per light on the
 *    full-resolution data, midpoint steps no longer than ShadowSampleDistance
 *    (default: smallest spacing / 8), extinction sigma = attenuation * mu, up
 *    to the data bounds (or the light); point/spot geometry terms of eqs.
 *    11-14 with radius PointLightRadius (default: smallest spacing). No
 *    pre-filtering and no irradiance volume.
 *  - Multiple scattering (MultipleScattering on and some s > 0): per light,
 *    the direct irradiance at every data voxel (shadow rays as above) is
 *    diffused with mmv::DiffuseIrradiance (grid spacing 1 data voxel,
 *    backward Euler by default, ExponentialDiffusion: exactly; s of the
 *    voxel's value where its opacity is > 0, else 0, like the irradiance
 *    filter). The sample then uses its own shadow-ray irradiance plus the
 *    trilinearly interpolated change the diffusion made at the voxels,
 *    clamped at 0: exact where nothing scatters, full data resolution where
 *    something does.
 *  - Shading: per segment, the formulas of Shaders/mmvRayCastDec.glsl:
 *    mmv::mmvBlinnPhong per light with its colour * intensity, two-sided
 *    normal from central differences (+-1 voxel) of the normalised value,
 *    the hybrid model's surface share (mmv::mmvSurfaceShare, Yang et al.), and the
 *    environment reflection of eq. 17 when the material function has
 *    reflection: c_r from vtkMultiMaterialEnvironment (the renderer's
 *    environment texture or background, ReflectionSource), times the
 *    visibility I(x, w_r) (ReflectionVisibility, with a light): a shadow ray
 *    along w_r as above, from the sample moved
 *    mmv::ReflectionVisibilityOffsetVoxels smallest spacings along n.
 *    The particles' share (1 - w) of the ambient term of each light is
 *    weighted by mmv::mmvHenyeyGreensteinRelative(g, -v.l) (1 at g = 0),
 *    and every
 *    segment adds its emission e * I_c (mmv::mmvEmission).
 *    No active light: ambient emission ka * I_c (plus e * I_c), unless the
 *    environment light (EnvironmentLighting) lights the volume: its
 *    mmv::mmvSkyRadiance per segment, from the sky's visibility moments
 *    (vtkSkyVisibility.h) on the data's grid, each diffused by
 *    mmv::DiffuseIrradiance where materials scatter (MultipleScattering).
 *  - Background: the colour is composited over the renderer's background
 *    (its vertical gradient when GradientBackground is on).
 *
 * Transfer functions (colour or gray, scalar opacity, materials) are
 * tabulated at 65536 points over the scalar range and interpolated linearly,
 * which differs from direct evaluation by far less than one 8-bit level.
 *
 * The module is not Python-wrapped: from pvpython, use the mmvBenchmark
 * program (Testing/Benchmark) that writes the reference images.
 *
 * vtkSMPTools runs sequentially unless a threaded backend is selected (e.g.
 * vtkSMPTools::SetBackend("STDThread") or VTK_SMP_BACKEND_IN_USE=STDThread).
 */
#ifndef vtkMultiMaterialReferenceRenderer_h
#define vtkMultiMaterialReferenceRenderer_h

#include "vtkMultiMaterialVolumeFiltersModule.h" // export macro
#include "vtkMultiMaterialVolumeScene.h"
#include "vtkSmartPointer.h" // members

class vtkImageData;
class vtkMaterialTransferFunction;
class vtkMatrix4x4;
class vtkVolumeMapper;
class vtkRenderer;
class vtkVolume;
class vtkVolumeProperty;

class VTKMULTIMATERIALVOLUMEFILTERS_EXPORT vtkMultiMaterialReferenceRenderer
  : public vtkMultiMaterialVolumeScene
{
public:
  static vtkMultiMaterialReferenceRenderer* New();
  vtkTypeMacro(vtkMultiMaterialReferenceRenderer, vtkMultiMaterialVolumeScene);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  // The scene (data, property, materials, matrix): vtkMultiMaterialVolumeScene.

  ///@{
  /// The mapper whose cropping region and clipping planes remove parts of
  /// the volume, as VTK's ray caster does, for the primary rays and the
  /// shadow rays (what is cut away casts no shadow). RenderToImage() sets it
  /// to the volume's mapper; null: nothing is cut.
  void SetCutawayMapper(vtkVolumeMapper* mapper);
  vtkVolumeMapper* GetCutawayMapper();
  ///@}

  /// Primary-ray step in object units; 0 (default) means smallest spacing / 8.
  vtkSetClampMacro(SampleDistance, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(SampleDistance, double);

  /// Shadow-ray step in object units; 0 (default) means smallest spacing / 8.
  vtkSetClampMacro(ShadowSampleDistance, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(ShadowSampleDistance, double);

  /// Falloff of point and spot lights. 0 (default): VTK's, by each light's
  /// AttenuationValues (constant, linear, quadratic; the default (1, 0, 0)
  /// means none). > 0: the paper's eq. 12 with this radius epsilon (object
  /// units), (epsilon / distance)^2 beyond it. A negative or non-finite
  /// value is reported (warning) and treated as 0.
  vtkSetMacro(PointLightRadius, double);
  vtkGetMacro(PointLightRadius, double);

  /// Multiple scattering by diffusion (default on; skipped when every s = 0).
  vtkSetMacro(MultipleScattering, bool);
  vtkGetMacro(MultipleScattering, bool);
  vtkBooleanMacro(MultipleScattering, bool);

  /// The diffusion's time integration (mmv::DiffusionSettings::Exponential).
  /// Off (default): 8 backward-Euler steps, kept as the ground truth so that
  /// accuracy figures stay comparable although the mapper integrates exactly
  /// by default. On: the exact exponential, the stricter truth
  /// (docs/performance.md, "Diffusion: exponential series against backward
  /// Euler").
  vtkSetMacro(ExponentialDiffusion, bool);
  vtkGetMacro(ExponentialDiffusion, bool);
  vtkBooleanMacro(ExponentialDiffusion, bool);

  /// The environment light, as vtkMultiMaterialVolumeMapper's (RenderToImage()
  /// copies it): the sky's visibility moments on the data's own grid (the
  /// GPU's at most mmv::SkyVoxelsPerAxis per axis), shaded by
  /// mmv::mmvSkyRadiance. 0 (default): off; negative or NaN: off, warned.
  vtkSetMacro(EnvironmentLighting, double);
  vtkGetMacro(EnvironmentLighting, double);

  /// As vtkMultiMaterialVolumeMapper's (RenderToImage() copies them).
  vtkSetClampMacro(ReflectionSource, int, 0, 1);
  vtkGetMacro(ReflectionSource, int);
  vtkSetClampMacro(ReflectionVisibility, int, 0, 1);
  vtkGetMacro(ReflectionVisibility, int);

  /// Primary and shadow rays stop below this transmittance. Default 1e-6.
  vtkSetClampMacro(MinimumTransmittance, double, 0.0, 1.0);
  vtkGetMacro(MinimumTransmittance, double);

  /**
   * Renders the scene as the renderer's active camera, lights and background
   * show it at width x height. The returned image (owned by this object,
   * replaced by the next render) has width x height x 1 points with
   * unsigned-char RGB scalars "Colors" (clamped to [0, 1], rounded, bottom
   * row first like vtkRenderWindow::GetPixelData) and the double-precision,
   * unclamped RGB array "Radiance". Returns null (with an error) on invalid
   * input.
   */
  vtkImageData* Render(vtkRenderer* ren, int width, int height);

  /// Render() with the input, property and matrix of `volume` (and, for a
  /// vtkMultiMaterialVolumeMapper, its material function, MultipleScattering
  /// and PointLightRadius), at the renderer's size in pixels.
  vtkImageData* RenderToImage(vtkRenderer* ren, vtkVolume* volume);

  ///@{
  /// What the last render did.
  vtkGetMacro(LastRenderSeconds, double);
  vtkGetMacro(LastScatteringSeconds, double);
  vtkGetMacro(NumberOfSamples, vtkIdType);
  vtkGetMacro(NumberOfShadowRays, vtkIdType);
  vtkGetMacro(ScatteringApplied, bool);
  ///@}

protected:
  vtkMultiMaterialReferenceRenderer();
  ~vtkMultiMaterialReferenceRenderer() override;

  double SampleDistance = 0.0;
  double ShadowSampleDistance = 0.0;
  double PointLightRadius = 0.0;
  bool MultipleScattering = true;
  bool ExponentialDiffusion = false;
  double MinimumTransmittance = 1.0e-6;
  int ReflectionSource = 0;     // mmv::ReflectEnvironmentTexture
  int ReflectionVisibility = 1; // mmv::MarchedReflectionVisibility
  double EnvironmentLighting = 0.0;

  double LastRenderSeconds = 0.0;
  double LastScatteringSeconds = 0.0;
  vtkIdType NumberOfSamples = 0;
  vtkIdType NumberOfShadowRays = 0;
  bool ScatteringApplied = false;

private:
  vtkMultiMaterialReferenceRenderer(const vtkMultiMaterialReferenceRenderer&) = delete;
  void operator=(const vtkMultiMaterialReferenceRenderer&) = delete;

  vtkSmartPointer<vtkVolumeMapper> CutawayMapper;
  vtkSmartPointer<vtkImageData> Output;
};

#endif
