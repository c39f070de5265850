/**
 * @file   vtkMultiMaterialSettings.h
 * @brief  The one description of vtkMultiMaterialVolumeMapper's settings:
 *         each field's type, default, accepted range and meaning.
 *
 * The mapper holds one mmv::IlluminationSettings and generates its Set/Get
 * methods from MMV_ILLUMINATION_SETTINGS; the irradiance stage takes the
 * struct whole; the CPU references adopt it (vtkMultiMaterialMapperSettings.h);
 * ParaView's representation forwards its properties to the mapper, and a test
 * (TestParaViewDefaults) checks every proxy default against this table.
 *
 * Range: a setter clamps to [Min, Max]. Settings whose bad values need a
 * message (NaN, a negative length) take any value and are checked, with a
 * warning, where they are used: their range is unbounded here.
 *
 * The settings, in table order:
 *  - IrradianceMemoryMB: GPU memory for the irradiance, 16 bits per light per
 *    voxel (the paper's 64 MB).
 *  - IrradianceCacheMB: GPU memory for the irradiance of earlier inputs, so
 *    that data coming back (a series' second loop, with ParaView's animation
 *    caching) costs a copy instead of an update (vtkIrradianceStepCache);
 *    their gradient volumes take as much again. A series longer than the
 *    budget keeps its first steps. Not kept for a piece of a volume in
 *    pieces.
 *  - IrradianceScale: the irradiance grid as a fraction of the data's
 *    (0 < x <= 1); 0 chooses it from the budget, the screen and the error
 *    probe. Above 1: used as 1; negative or NaN: 0 (both reported).
 *  - IrradianceErrorBound: with an automatic grid, the PSNR (dB) the
 *    irradiance may lose to a coarser grid; vtkIrradianceResolutionProbe
 *    measures coarser grids once per data or transfer-function change and
 *    keeps the coarsest within it (camera and light moves never re-measure).
 *    0: no probe. Negative or NaN: 0; above mmv::MaxIrradianceErrorBoundDB:
 *    that maximum (both reported).
 *  - GradientSmoothing: blurs the gradient volume by a Gaussian of this many
 *    times the largest data spacing; about 1 removes the stripes of thin
 *    shells sampled coarsely (docs/stability.md). Negative or NaN: 0; above
 *    mmv::MaxGradientSmoothing: clamped (both reported).
 *  - MultipleScattering: diffusion of the irradiance (skipped when every
 *    material's s is 0).
 *  - ShadowEstimation: mmv::PiecewiseShadowRays (rays ending on a slice
 *    computed before, vtkShadowSweep.h; around a point or spot light inside
 *    the grid, in six pyramids) or mmv::FullShadowRays (one ray per voxel to
 *    the boundary or the light).
 *  - PiecewiseShadowSlices: slices a piecewise shadow ray spans at most;
 *    fewer blur shadow edges more.
 *  - ExponentialDiffusion: the diffusion's time integration, the
 *    exponential's Chebyshev series (exact in time, fewer passes) or
 *    backward-Euler sub-steps.
 *  - LightDirectionTolerance: degrees a light may move and keep its
 *    irradiance (vtkMultiMaterialLightTolerance.h). 0: every move
 *    recomputes, so the image at rest equals a fresh render.
 *  - DimLightCoarsening: lights at most mmv::DimLightRatio of the brightest
 *    (the light kit's fill, back and head lights) get their shadows on every
 *    mmv::DimLightStride-th irradiance point per axis, interpolated.
 *  - PreIntegration: pre-integrated segments; off, post-classified samples.
 *  - PreIntegrationTableSize: n of the n x n pre-integration tables.
 *  - PointLightRadius: falloff of point and spot lights; 0, VTK's (each
 *    light's AttenuationValues); > 0, the paper's eq. 12 with this radius
 *    (object units). Negative or non-finite: 0 (reported).
 *  - CompileUnusedOpticalTerms: compiles the Henyey-Greenstein and emission
 *    terms even when every material leaves them at 0 (tests and benchmarks;
 *    the image is the same).
 *  - ReflectionSource: where reflections take their colour: the renderer's
 *    environment texture when set, else the background
 *    (mmv::ReflectEnvironmentTexture), or the background always
 *    (mmv::ReflectBackground).
 *  - ReflectionVisibility: the visibility of reflections (eq. 17), one of
 *    mmv::ReflectionVisibility; Automatic picks per frame the cheaper of the
 *    per-sample march and the view-dependent grid for the view's size.
 *  - InteractiveIrradiance: while interacting (VTK's allocated render time
 *    below 1 s) and only the lights moved, mmv::ReuseWhileInteracting keeps
 *    the last irradiance until the still frame; mmv::UpdateAlways recomputes.
 *  - TimeStages: brackets the stages with glFinish to time them (it stalls
 *    the pipeline).
 *  - PieceIrradianceOnly: under MPI each rank estimates only the irradiance
 *    its piece reads; off, the whole global grid.
 *  - MaxBrickMB: the largest brick of a volume drawn in bricks.
 */
#ifndef vtkMultiMaterialSettings_h
#define vtkMultiMaterialSettings_h

#include "vtkMultiMaterialParameters.h"      // ShadowEstimation, defaults
#include "vtkMultiMaterialReflectionModes.h" // ReflectionSource, ReflectionVisibility

#include <limits>

namespace mmv
{
/// What interactive renders do when only the lights moved (InteractiveIrradiance).
enum InteractiveIrradianceMode : int
{
  UpdateAlways = 0,
  ReuseWhileInteracting = 1
};

/// A range bound that accepts anything (the value is checked where used).
constexpr double Unbounded = std::numeric_limits<double>::infinity();

// X(type, name, default, min, max, one-line doc): one row per setting.
#define MMV_ILLUMINATION_SETTINGS(X)                                                               \
  X(double, IrradianceMemoryMB, mmv::DefaultIrradianceBudgetMB, 0.001, 1.0e6,                      \
    "GPU memory for the irradiance, MB")                                                           \
  X(double, IrradianceCacheMB, 0.0, 0.0, 1.0e6, "GPU memory for earlier inputs' irradiance, MB")   \
  X(double, IrradianceScale, 0.0, -mmv::Unbounded, mmv::Unbounded,                                 \
    "irradiance grid / data grid; 0 automatic")                                                    \
  X(double, IrradianceErrorBound, mmv::DefaultIrradianceErrorBoundDB, -mmv::Unbounded,             \
    mmv::Unbounded, "PSNR the automatic grid may lose, dB; 0 no probe")                            \
  X(double, GradientSmoothing, 0.0, -mmv::Unbounded, mmv::Unbounded,                               \
    "gradient blur, x the largest spacing")                                                        \
  X(bool, MultipleScattering, true, 0, 1, "diffusion of the irradiance")                           \
  X(int, ShadowEstimation, mmv::PiecewiseShadowRays, 0, 1,                                         \
    "full (0) or piecewise (1) shadow rays")                                                       \
  X(int, PiecewiseShadowSlices, mmv::DefaultPiecewiseShadowSlices, 1, 4096,                        \
    "slices a piecewise shadow ray spans")                                                         \
  X(bool, ExponentialDiffusion, mmv::DefaultExponentialDiffusion, 0, 1,                            \
    "Chebyshev exponential (on) or backward Euler (off)")                                          \
  X(double, LightDirectionTolerance, mmv::DefaultLightDirectionToleranceDegrees, 0.0,              \
    mmv::MaxLightDirectionToleranceDegrees, "degrees a light may move and keep its irradiance")    \
  X(bool, DimLightCoarsening, true, 0, 1, "dim lights' shadows on a coarser grid")                 \
  X(bool, PreIntegration, true, 0, 1, "pre-integrated segments")                                   \
  X(int, PreIntegrationTableSize, 256, 16, 1024, "n of the n x n pre-integration tables")          \
  X(double, PointLightRadius, 0.0, -mmv::Unbounded, mmv::Unbounded,                                \
    "eq. 12 falloff radius; 0 the lights' attenuation")                                            \
  X(bool, CompileUnusedOpticalTerms, false, 0, 1, "compile terms no material uses")                \
  X(double, EnvironmentLighting, 0.0, -mmv::Unbounded, mmv::Unbounded,                             \
    "the sky's strength (the background as a light); 0 off")                                       \
  X(int, ReflectionSource, mmv::ReflectEnvironmentTexture, 0, 1,                                   \
    "environment texture (0) or background (1)")                                                   \
  X(int, ReflectionVisibility, mmv::AutomaticReflectionVisibility, 0, 3,                           \
    "none, marched, view-dependent grid, automatic")                                               \
  X(int, InteractiveIrradiance, mmv::ReuseWhileInteracting, 0, 1,                                  \
    "update always (0) or keep while interacting (1)")                                             \
  X(bool, TimeStages, false, 0, 1, "time the stages with glFinish")                                \
  X(bool, PieceIrradianceOnly, true, 0, 1, "under MPI, only the irradiance a piece reads")         \
  X(double, MaxBrickMB, 512.0, 1.0, 1.0e6, "largest brick of a volume in bricks, MB")

/// Every setting of vtkMultiMaterialVolumeMapper, at its default.
struct IlluminationSettings
{
#define MMV_SETTING_FIELD(type, name, value, low, high, doc) type name = value;
  MMV_ILLUMINATION_SETTINGS(MMV_SETTING_FIELD)
#undef MMV_SETTING_FIELD
};

/// The defaults, for tables built from them at compile time.
constexpr IlluminationSettings DefaultIlluminationSettings{};

/// A row of the table, for code that walks every setting (tests, PrintSelf).
struct SettingDescription
{
  const char* Name;
  double Default;
  double Min;
  double Max;
  const char* Doc;
};

constexpr SettingDescription IlluminationSettingDescriptions[] = {
#define MMV_SETTING_ROW(type, name, value, low, high, doc)                                         \
  { #name, static_cast<double>(value), static_cast<double>(low), static_cast<double>(high), doc },
  MMV_ILLUMINATION_SETTINGS(MMV_SETTING_ROW)
#undef MMV_SETTING_ROW
};

/// `value` clamped to a row's [low, high] (NaN passes, as vtkSetClampMacro's).
template <typename T>
T ClampSetting(T value, double low, double high)
{
  const double v = static_cast<double>(value);
  return v < low ? static_cast<T>(low) : (v > high ? static_cast<T>(high) : value);
}
}

#endif
