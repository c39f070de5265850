/**
 * @file   vtkMultiMaterialParameters.h
 * @brief  The one description of the material and light parameters.
 *
 * The material transfer function, its JSON files, the CPU irradiance filter
 * and (through the GLSL prelude) the GPU shaders all read this table, so the
 * CPU model and the GPU path cannot drift apart.
 *
 * It is the CPU/GPU contract: besides the parameters it defines the material
 * texture's texel layout (MaterialTexelLayout), the light kinds and the
 * shadow-ray constants, all emitted to GLSL as generated names
 * (MaterialGLSLPrelude, ShadowRayGLSLPrelude). Next to it: the light struct
 * (vtkMultiMaterialLightModel.h), the one light-uniform layout of the ray
 * cast and the irradiance pass (vtkMultiMaterialLightUniforms.h) and the
 * diffusion's face coefficient, sub-steps and stiffness bounds
 * (vtkIrradianceDiffusion.h). TestShaderMirror runs each GLSL function
 * against its C++ twin.
 *
 * | index | key           | symbol | unit             | default | UI range    |
 * |-------|---------------|--------|------------------|---------|-------------|
 * | 0     | ambient       | ka     | -                | 0.2     | 0 .. 1      |
 * | 1     | diffuse       | kd     | -                | 0.7     | 0 .. 1      |
 * | 2     | specular      | ks     | -                | 0.2     | 0 .. 1      |
 * | 3     | shininess     | ke     | Blinn exponent   | 20      | 0 .. 200    |
 * | 4     | attenuation   | c_t    | x extinction mu  | 1       | 0 .. 2      |
 * | 5     | scattering    | s      | voxel^2          | 0       | 0 .. 20     |
 * | 6     | reflection    | r      | -                | 0       | 0 .. 1      |
 * | 7     | anisotropy    | g      | mean cosine      | 0       | -0.9 .. 0.9 |
 * | 8     | emission      | e      | x colour         | 0       | 0 .. 10     |
 * | 9     | transmission_r| T_r    | -                | 1       | 0 .. 1      |
 * | 10    | transmission_g| T_g    | -                | 1       | 0 .. 1      |
 * | 11    | transmission_b| T_b    | -                | 1       | 0 .. 1      |
 *
 * Attenuation: the extinction seen by shadow rays is sigma = c_t * mu, where
 * mu = -ln(1 - alpha) / u is the extinction implied by the scalar opacity
 * alpha and the volume property's scalar-opacity unit distance u.
 * Scattering: the diffusion strength of eq. 15, in (data voxel)^2 per unit time,
 * solved to t = 1 (so it does not change with the irradiance resolution).
 * Anisotropy: g of the Henyey-Greenstein phase function, the mean cosine of
 * the scattering angle (0 isotropic, > 0 forward); |g| < 1 (HardMin and
 * HardMax are +-0.99: g = +-1 is a delta, not a phase function). The path
 * tracer scatters with it; the ray caster and the reference renderer weight
 * the particles' share of the ambient term of each light (the hybrid model,
 * mmvSurfaceShare) by 4 pi HG(g) between the light's and the view's
 * directions (vtkMultiMaterialPhaseFunction.h), which is 1 at g = 0, so
 * g = 0 renders exactly as the isotropic model did.
 * Emission: Yang et al. eq. 27. Emitted radiance per unit length is
 * e * colour * sigma_t (the emitting particles are the ones that absorb), so
 * a segment of opacity alpha adds e * colour * alpha (= e * I_c) to the
 * radiance, whatever the lights and shadows; a homogeneous slab of optical
 * depth tau glows with e * colour * (1 - exp(-tau)).
 * Transmission (selective absorption, Yang et al. eq. 26):
 * the colour T = (T_r, T_g, T_b) filters the light that crosses the medium,
 * on top of the grey attenuation: channel lambda's shadow extinction is
 *   sigma_lambda = c_t * mu * w_lambda,  w_lambda = 1 - ln(max(T_lambda, T_min))
 * (mmv::TransmissionWeight, T_min = MinTransmission), so light crossing a grey
 * optical depth tau = int c_t mu ds of a homogeneous medium arrives as
 *   exp(-tau_lambda) = exp(-tau) * T_lambda^tau:
 * every unit of grey depth tints it by T once more. T = (1, 1, 1), the
 * default, gives w = 1: exactly the grey attenuation of before (a node, a
 * JSON file or a MaterialNodes list without T is grey). Yang's
 * alpha_lambda = alpha (1 - c_lambda) makes white transparent instead; ours
 * keeps c_t the one control of the shadow's strength. Only shadows are
 * tinted (irradiance, mmv::IrradianceTint); the colour seen through the
 * medium stays the colour map's.
 */
#ifndef vtkMultiMaterialParameters_h
#define vtkMultiMaterialParameters_h

#include <cmath>
#include <cstdio>
#include <string>

namespace mmv
{

enum MaterialParameter : int
{
  Ambient = 0,
  Diffuse,
  Specular,
  Shininess,
  Attenuation,
  Scattering,
  Reflection,
  Anisotropy,
  Emission,
  TransmissionR,
  TransmissionG,
  TransmissionB,
  MaterialParameterCount
};

struct MaterialParameterInfo
{
  const char* Key;      // JSON key and ParaView label stem
  const char* GLSLName; // stem of its texel macros in the GLSL prelude
  double Default;
  double SoftMin; // editor range
  double SoftMax;
  double HardMax;       // larger values are rejected as input errors
  double HardMin = 0.0; // smaller values are rejected as input errors
};

constexpr MaterialParameterInfo MaterialParameterTable[MaterialParameterCount] = {
  { "ambient", "MMV_AMBIENT", 0.2, 0.0, 1.0, 1.0e3 },
  { "diffuse", "MMV_DIFFUSE", 0.7, 0.0, 1.0, 1.0e3 },
  { "specular", "MMV_SPECULAR", 0.2, 0.0, 1.0, 1.0e3 },
  { "shininess", "MMV_SHININESS", 20.0, 0.0, 200.0, 1.0e4 },
  { "attenuation", "MMV_ATTENUATION", 1.0, 0.0, 2.0, 1.0e3 },
  { "scattering", "MMV_SCATTERING", 0.0, 0.0, 20.0, 1.0e4 },
  { "reflection", "MMV_REFLECTION", 0.0, 0.0, 1.0, 1.0e3 },
  { "anisotropy", "MMV_ANISOTROPY", 0.0, -0.9, 0.9, 0.99, -0.99 },
  { "emission", "MMV_EMISSION", 0.0, 0.0, 10.0, 1.0e4 },
  { "transmission_r", "MMV_TRANSMISSION_R", 1.0, 0.0, 1.0, 1.0 },
  { "transmission_g", "MMV_TRANSMISSION_G", 1.0, 0.0, 1.0, 1.0 },
  { "transmission_b", "MMV_TRANSMISSION_B", 1.0, 0.0, 1.0, 1.0 },
};

/// Smallest transmission used: T = 0 would make the extinction infinite
/// (w = 1 - ln T); 1e-3 gives w = 7.9, black after a few units of depth.
constexpr double MinTransmission = 1.0e-3;

/// The factor w_lambda of channel lambda's shadow extinction (table comment):
/// 1 for T = 1 (grey).
inline double TransmissionWeight(double transmission)
{
  return 1.0 - std::log(transmission > MinTransmission ? transmission : MinTransmission);
}

/// The selective part of the extinction factor, w_lambda - 1 = -ln T >= 0:
/// what the tint pass integrates (its shadow table, GetShadowTintTable).
inline double SelectiveAbsorption(double transmission)
{
  return TransmissionWeight(transmission) - 1.0;
}

/// True when the colour filters (some channel below 1): the shaders then
/// need the RGB irradiance (variant MMV_USE_RGB_IRRADIANCE).
inline bool IsChromaticTransmission(double r, double g, double b)
{
  return r < 1.0 || g < 1.0 || b < 1.0;
}

/**
 * The RGB irradiance of a non-white transmission colour, stored compressed:
 * E_lambda = E * K_lambda, E today's grey irradiance (extinction c_t mu, the
 * full-resolution 16-bit texture, piecewise rays and diffusion as before)
 * and K_lambda = exp(-int c_t mu (-ln T_lambda)) <= 1 the tint, the
 * transmittance of the selective part alone (vtkPreIntegrationTable's
 * I_tau), exact in the product because optical depths add. K is smooth
 * where E has its detail (it only changes where tinted material lies
 * between the voxel and the light), so it is stored at 1/TintResolutionDivisor
 * of the irradiance resolution per axis (TintDimension; the grids share
 * their end points), by full shadow rays from every tint voxel, and not
 * diffused. GPU: one RGBA16F texture per light (alpha unused), so
 * 8 bytes / 8 = 1 byte per irradiance voxel per light
 * (TintBytesPerVoxelPerLight) on top of the 2 of E: 1.5x the grey memory.
 */
constexpr int TintResolutionDivisor = 2;
constexpr double TintBytesPerVoxelPerLight =
  8.0 / (TintResolutionDivisor * TintResolutionDivisor * TintResolutionDivisor);

/// Tint grid points along an axis of `irradianceDim` irradiance points:
/// every `divisor`-th irradiance point and the last one (end points shared).
inline int TintDimension(int irradianceDim, int divisor = TintResolutionDivisor)
{
  if (irradianceDim <= 2 || divisor <= 1)
  {
    return irradianceDim;
  }
  const int n = (irradianceDim - 1 + divisor - 1) / divisor + 1;
  return n < 2 ? 2 : n;
}

/**
 * Dim lights on a coarser grid. A light's share of the image bounds the
 * image error its irradiance can cause: a light at most DimLightRatio of the
 * brightest light's radiance (the light kit's fill, back and head lights are
 * 1/3 to 1/3.5 of its key light) is estimated on every DimLightStride-th
 * point of the irradiance grid per axis and interpolated trilinearly, an
 * eighth of the shadow rays (docs/performance.md, "Dim lights", measures
 * the image error on smooth and fine-structured volumes). Grids too small
 * to coarsen (LightGridDimension below MinimumLightGridDimension on an
 * axis) keep every light on the irradiance grid.
 */
constexpr int DimLightStride = 2;
constexpr double DimLightRatio = 0.5;
constexpr int MinimumLightGridDimension = 8;

/// Points along an axis of `irradianceDim` irradiance points of a light grid
/// of stride `stride` (the end points shared, as the tint grid's).
inline int LightGridDimension(int irradianceDim, int stride)
{
  return TintDimension(irradianceDim, stride);
}

/// The grid stride of a light of radiance `luminance` among lights whose
/// brightest has `brightest`, on an irradiance grid of `dims`.
inline int LightGridStride(double luminance, double brightest, const int dims[3])
{
  if (!(luminance <= DimLightRatio * brightest))
  {
    return 1;
  }
  for (int a = 0; a < 3; ++a)
  {
    if (LightGridDimension(dims[a], DimLightStride) < MinimumLightGridDimension)
    {
      return 1;
    }
  }
  return DimLightStride;
}

/// Rows of the ray caster's material texture (vtkMultiMaterialTextures.h):
/// (ka, kd, ks, ke), (r, 0, 0, g), (e, 0, 0, 0). GLSL: MMV_MATERIAL_ROWS.
constexpr int MaterialTextureRows = 3;

/// Where a parameter sits in the material texture: texel row and channel;
/// row -1: not in it (no ray-cast shader reads it: the shadow rays and the
/// diffusion get c_t and s through their own tables).
struct MaterialTexel
{
  int Row;
  int Channel;
};

/// The texel layout, by parameter. Row 0 is what every shaded segment
/// reads; the optional terms' parameters are in rows the shader fetches only
/// when its variant uses them. GLSL: MMV_BLINN_PHONG_ROW for the row 0 texel,
/// MMV_<NAME>_ROW and MMV_<NAME>_CHANNEL for the others (MaterialGLSLPrelude);
/// the texture is packed by PackMaterialTexels.
constexpr MaterialTexel MaterialTexelLayout[MaterialParameterCount] = {
  { 0, 0 },  // ambient
  { 0, 1 },  // diffuse
  { 0, 2 },  // specular
  { 0, 3 },  // shininess
  { -1, 0 }, // attenuation
  { -1, 0 }, // scattering
  { 1, 0 },  // reflection
  { 1, 3 },  // anisotropy
  { 2, 0 },  // emission
  { -1, 0 }, // transmission_r: the shadow table's, not the ray cast's
  { -1, 0 }, // transmission_g
  { -1, 0 }, // transmission_b
};

/// The Blinn-Phong coefficients are read as one texel (ka, kd, ks, ke), the
/// vec4 mmvBlinnPhong takes (GLSL: MMV_BLINN_PHONG_ROW).
constexpr int BlinnPhongRow = MaterialTexelLayout[Ambient].Row;
static_assert(MaterialTexelLayout[Ambient].Channel == 0 &&
    MaterialTexelLayout[Diffuse].Row == BlinnPhongRow &&
    MaterialTexelLayout[Diffuse].Channel == 1 &&
    MaterialTexelLayout[Specular].Row == BlinnPhongRow &&
    MaterialTexelLayout[Specular].Channel == 2 &&
    MaterialTexelLayout[Shininess].Row == BlinnPhongRow &&
    MaterialTexelLayout[Shininess].Channel == 3,
  "mmvBlinnPhong reads (ka, kd, ks, ke) as one texel");

/// Writes the parameters `values` of table entry `entry` (of `entries`)
/// into RGBA texels laid out as MaterialTexelLayout (rows of `entries`
/// texels); channels no parameter uses stay as they are.
inline void PackMaterialTexels(
  const float values[MaterialParameterCount], int entry, int entries, float* texels)
{
  for (int p = 0; p < MaterialParameterCount; ++p)
  {
    const MaterialTexel& texel = MaterialTexelLayout[p];
    if (texel.Row < 0)
    {
      continue;
    }
    texels[4 * (texel.Row * entries + entry) + texel.Channel] = values[p];
  }
}

/// How a light is modelled (vtkMultiMaterialLightModel.h): its kind, as the
/// light uniforms hold it (GLSL: MMV_DIRECTIONAL_LIGHT, MMV_POINT_LIGHT,
/// MMV_SPOT_LIGHT).
enum LightKind : int
{
  DirectionalLight = 0,
  PointLight = 1,
  SpotLight = 2
};

/// The GLSL names of the light kinds, by kind.
constexpr const char* LightKindGLSLNames[] = { "MMV_DIRECTIONAL_LIGHT", "MMV_POINT_LIGHT",
  "MMV_SPOT_LIGHT" };

/// Lights the GPU path supports at once (more: the strongest are kept).
constexpr int MaxLights = 8;

/// A VTK light attenuation polynomial c0 + c1 d + c2 d^2 below this is
/// clamped to it, so the falloff stays finite (at most 1e4) at the light
/// itself, e.g. for (0, 0, 1) (GLSL: MMV_MIN_ATTENUATION_DENOMINATOR).
constexpr double MinAttenuationDenominator = 1.0e-4;

/// Bytes one light costs per irradiance voxel on the GPU (16-bit storage).
/// The CPU filter uses the same figure so both pick the same resolution.
constexpr double IrradianceBytesPerVoxelPerLight = 2.0;

/// The hybrid surface/particle model (Yang et al. eqs. 5-8, mmvSurfaceShare):
/// the gradient of the normalised value, per voxel, at which surface elements
/// and particles take equal shares of a segment's extinction. It is the
/// paper's Delta v_std / Delta l_std (over all ray directions), with one
/// opacity transfer function for both elements (its Fig. 4c); its CT figures
/// put it at 0.0008-0.0024 (Delta v_std 13-40 of 4096 per Delta l_std of 4
/// voxels). 0.005 is the Monte Carlo truth's own scale for surface events
/// (Kroes et al., vtkMultiMaterialPathTracer::SurfaceGradientPerVoxel) and
/// fits that truth at least as well as 0.002 (docs/performance.md,
/// "Anisotropy and the hybrid shading"). A one-voxel edge
/// across 5 % of the range is 91 % surface, noise of 0.01 % of the range 2 %.
/// Read by the mapper (mmv_surfaceEqualShare) and the reference renderer.
constexpr double SurfaceEqualShareGradientPerVoxel = 0.005;

/// With an automatic irradiance resolution, an irradiance voxel need not
/// cover fewer pixels than this on screen (mmv::ChooseIrradianceResolution):
/// sub-pixel irradiance detail cannot show. A coarser rule blurs thin shells
/// (docs/performance.md, "Diffusion: exponential series against backward
/// Euler").
constexpr double PixelsPerIrradianceVoxel = 1.0;

/// Default IrradianceErrorBound (dB): with an automatic resolution, the
/// error probe (vtkIrradianceResolutionProbe) keeps the coarsest grid whose
/// opacity-weighted irradiance PSNR against the budget's grid reaches it.
/// It lies above what thin shells score at the first coarser grid, so they
/// keep their grid, and below what large smooth volumes score, so those
/// coarsen (docs/performance.md, "The error probe").
constexpr double DefaultIrradianceErrorBoundDB = 34.0;
/// Largest IrradianceErrorBound accepted (dB): far beyond 16-bit textures.
constexpr double MaxIrradianceErrorBoundDB = 200.0;

/// How the irradiance of a light is estimated (vtkShadowSweep.h).
enum ShadowEstimation : int
{
  /// One ray per voxel to the volume boundary (Zhang & Ma §5.1): exact,
  /// O(n^4) for an n^3 grid.
  FullShadowRays = 0,
  /// Piecewise shadow rays swept along the light (around a point or spot
  /// light inside the grid, in six pyramids from it outward). O(n^3 K).
  PiecewiseShadowRays = 1
};

/// Slices K a piecewise shadow ray spans at most, by default. Smaller K
/// means more chunks and blurrier shadow edges, larger K longer rays; 16 was
/// the fastest (docs/performance.md, "Piecewise shadow rays").
constexpr int DefaultPiecewiseShadowSlices = 16;

/// Default time integration of the diffusion (ExponentialDiffusion of the
/// mapper, the estimator and the CPU filter): the exponential's Chebyshev series,
/// exact in time. It is as accurate as backward Euler in fewer passes
/// (docs/performance.md, "Diffusion: exponential series against backward
/// Euler").
constexpr bool DefaultExponentialDiffusion = true;

/// Default irradiance memory budget in MB (the paper's recommendation).
constexpr double DefaultIrradianceBudgetMB = 64.0;

/// Default LightDirectionTolerance in degrees (vtkMultiMaterialLightTolerance.h):
/// 0, every light move recomputes, so the image at rest equals a fresh render.
constexpr double DefaultLightDirectionToleranceDegrees = 0.0;
/// Largest LightDirectionTolerance accepted, in degrees.
constexpr double MaxLightDirectionToleranceDegrees = 45.0;

/// Transmittance below which a shadow ray stops (the paper's early
/// termination); GLSL: MMV_MIN_TRANSMITTANCE.
constexpr double MinShadowTransmittance = 1.0e-4;

/// A shadow ray of length `end` takes floor(end / h + tolerance) full steps:
/// the tolerance keeps an end that is a whole number of steps from dropping
/// the last one by rounding. The GPU's float needs a wider one than the
/// CPU's double (GLSL: MMV_STEP_TOLERANCE).
constexpr double ShadowStepTolerance = 1.0e-9;
constexpr double ShadowStepToleranceFloat = 1.0e-5;

/// A last partial segment shorter than this fraction of a step is dropped, so
/// that rounding adds no zero-length segment (GLSL: MMV_REST_TOLERANCE).
constexpr double ShadowRestTolerance = 1.0e-9;

/// A piecewise shadow ray ends on its sweep plane (mmv::ReachesSweepPlane)
/// if the plane is no farther than its exit distance times (1 + relative)
/// plus absolute: a ray grazing the plane's edge then reads the edge
/// (clamped) instead of flipping between plane and boundary with rounding,
/// so float and double agree (GLSL: MMV_SWEEP_PLANE_*_TOLERANCE).
constexpr double SweepPlaneRelativeTolerance = 1.0e-4;
constexpr double SweepPlaneAbsoluteTolerance = 1.0e-6;

/// Opacity is clamped below 1 before taking the log: alpha = 1 would mean
/// infinite extinction. 1 - 1e-6 gives mu = 13.8 / u, opaque for any use.
constexpr double MaxOpacity = 1.0 - 1.0e-6;

/// Extinction per world unit implied by a scalar opacity alpha given per unit
/// distance u (VTK's convention: opacity alpha over a length u).
inline double ExtinctionFromOpacity(double alpha, double unitDistance)
{
  if (!(alpha > 0.0)) // also catches NaN
  {
    return 0.0;
  }
  const double a = alpha < MaxOpacity ? alpha : MaxOpacity;
  return -std::log1p(-a) / unitDistance;
}

/// Checks one material parameter value; fills `why` when it is rejected.
inline bool IsValidMaterialValue(int parameter, double value, std::string* why = nullptr)
{
  if (parameter < 0 || parameter >= MaterialParameterCount)
  {
    if (why)
    {
      *why = "unknown material parameter index " + std::to_string(parameter);
    }
    return false;
  }
  const MaterialParameterInfo& info = MaterialParameterTable[parameter];
  if (!std::isfinite(value))
  {
    if (why)
    {
      *why = std::string(info.Key) + " is not a finite number";
    }
    return false;
  }
  if (value < info.HardMin)
  {
    if (why)
    {
      *why = info.HardMin == 0.0
        ? std::string(info.Key) + " is negative (" + std::to_string(value) + ")"
        : std::string(info.Key) + " = " + std::to_string(value) + " is below the minimum " +
          std::to_string(info.HardMin);
    }
    return false;
  }
  if (value > info.HardMax)
  {
    if (why)
    {
      *why = std::string(info.Key) + " = " + std::to_string(value) + " exceeds the maximum " +
        std::to_string(info.HardMax);
    }
    return false;
  }
  return true;
}

/// The GLSL `#define` prelude of the contract above: the texture's rows, the
/// Blinn-Phong texel, the texel of each parameter the shaders read alone
/// (MMV_<NAME>_ROW, MMV_<NAME>_CHANNEL), the light kinds and the attenuation
/// clamp. Shaders read the material texture and test light kinds only
/// through these names.
inline std::string MaterialGLSLPrelude()
{
  std::string s;
  for (int i = 0; i < MaterialParameterCount; ++i)
  {
    if (MaterialTexelLayout[i].Row < 0 || MaterialTexelLayout[i].Row == BlinnPhongRow)
    {
      continue;
    }
    const std::string stem = std::string("#define ") + MaterialParameterTable[i].GLSLName;
    s += stem + "_ROW " + std::to_string(MaterialTexelLayout[i].Row) + "\n";
    s += stem + "_CHANNEL " + std::to_string(MaterialTexelLayout[i].Channel) + "\n";
  }
  s += "#define MMV_MATERIAL_ROWS " + std::to_string(MaterialTextureRows) + "\n";
  s += "#define MMV_BLINN_PHONG_ROW " + std::to_string(BlinnPhongRow) + "\n";
  for (int kind : { DirectionalLight, PointLight, SpotLight })
  {
    s += std::string("#define ") + LightKindGLSLNames[kind] + " " + std::to_string(kind) + "\n";
  }
  char denominator[32];
  std::snprintf(denominator, sizeof(denominator), "%.9e", MinAttenuationDenominator);
  s += std::string("#define MMV_MIN_ATTENUATION_DENOMINATOR ") + denominator + "\n";
  return s;
}

/// The GLSL `#define`s of the shadow-ray constants above, from those
/// constants, so the GPU ray march stops where the CPU one does.
inline std::string ShadowRayGLSLPrelude()
{
  // Enough digits that the float the shader sees is the nearest to ours.
  auto literal = [](double value)
  {
    char buffer[32];
    std::snprintf(buffer, sizeof(buffer), "%.9e", value);
    return std::string(buffer);
  };
  return "#define MMV_MIN_TRANSMITTANCE " + literal(MinShadowTransmittance) + "\n" +
    "#define MMV_STEP_TOLERANCE " + literal(ShadowStepToleranceFloat) + "\n" +
    "#define MMV_REST_TOLERANCE " + literal(ShadowRestTolerance) + "\n" +
    "#define MMV_SWEEP_PLANE_RELATIVE_TOLERANCE " + literal(SweepPlaneRelativeTolerance) + "\n" +
    "#define MMV_SWEEP_PLANE_ABSOLUTE_TOLERANCE " + literal(SweepPlaneAbsoluteTolerance) + "\n";
}

} // namespace mmv

#endif
