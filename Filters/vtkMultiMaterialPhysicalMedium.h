/**
 * @file   vtkMultiMaterialPhysicalMedium.h
 * @brief  Our material parameters for a participating medium of known
 *         physics: single-scattering albedo a, Henyey-Greenstein anisotropy
 *         g and extinction per voxel, fitted to the Monte Carlo truth
 *         (vtkMultiMaterialPathTracer).
 *
 * The colour transfer function stays the albedo and the scalar opacity the
 * extinction, as the path tracer reads them; what the mapping sets are the
 * parameters our model leaves free: ka, kd, attenuation c_t and
 * scattering s (ks = 0, no surface; g as given; r = e = 0).
 * Fitted by Testing/Benchmark/mmvMediumCalibration; the formula and its
 * reading are in docs/how-it-works.md ("Physical media"), its residual in
 * docs/performance.md ("Physical media").
 */
#ifndef vtkMultiMaterialPhysicalMedium_h
#define vtkMultiMaterialPhysicalMedium_h

#include "vtkMultiMaterialParameters.h"
#include "vtkMultiMaterialVolumeFiltersModule.h" // export macro

#include <string>

namespace mmv
{

/// The domain the mapping accepts. Fitted on albedo 0.3 ... 0.99, g 0 ...
/// 0.8 and extinction 0.056 ... 0.89 per voxel (a ball of radius 18
/// voxels); docs/performance.md ("Physical media") gives the residual.
/// Backward scattering (g < 0) was not measured and is rejected.
constexpr double PhysicalMediumMaxAlbedo = 0.999;
constexpr double PhysicalMediumMaxAnisotropy = 0.9;

/**
 * The fitted coefficients, with a = albedo, g, tau = extinction per voxel:
 *
 *   ka  = (1 + GainScale a^GainAlbedoPower / (GainOffset + sqrt(1 - a))
 *              (1 - exp(-tau / GainDepth)) (1 + ForwardGain g^ForwardPower))
 *         / (4 pi (1 + DenseDimming tau))
 *   c_t = (1 - a g)^AttenuationPower
 *   s   = ScatteringScale a^ScatteringAlbedoPower / tau^ScatteringDepthPower
 *   kd = ks = 0, shininess 1, r = e = 0, anisotropy = g.
 *
 * Limits: a -> 0 gives single scattering (ka = 1 / (4 pi (1 + DenseDimming
 * tau)), c_t = 1, s = 0); g = 0 keeps c_t = 1 (the light multiple
 * scattering adds comes through ka and s).
 */
struct PhysicalMediumFit
{
  double GainScale;
  double GainOffset;
  double GainDepth;
  double DenseDimming;
  double GainAlbedoPower;
  double ForwardGain;
  double ForwardPower;
  double AttenuationPower;
  double ScatteringScale;
  double ScatteringAlbedoPower;
  double ScatteringDepthPower;
};

constexpr PhysicalMediumFit PhysicalMediumCoefficients = { 2.47, 0.364, 0.244, 0.86, 1.28, 1.26,
  4.6, 1.34, 1.87, 3.8, 0.88 };

/// A physically derived preset of the material library
/// (Filters/Materials/<Name>.json): PhysicalMediumToMaterial of these
/// values, rounded to 6 digits (TestPhysicalMedium checks that they agree).
struct PhysicalPreset
{
  const char* Name;
  double Albedo;
  double Anisotropy;
  double ExtinctionPerVoxel;
};

/// Fog or cloud droplets; soft tissue; soot (black-carbon smoke). The
/// extinction, 0.25 per voxel (opacity 0.22 per voxel), is a typical one:
/// for another density, call PhysicalMediumToMaterial.
constexpr PhysicalPreset PhysicalPresets[] = {
  { "fog", 0.99, 0.8, 0.25 },
  { "tissue", 0.9, 0.8, 0.25 },
  { "soot", 0.3, 0.6, 0.25 },
};

/**
 * Fills `parameters` (mmv::MaterialParameterCount values, in the table's
 * order) for a medium of single-scattering albedo `albedo` in [0, 0.999],
 * anisotropy `g` in [0, 0.9] and extinction `extinctionPerVoxel` > 0
 * (sigma_t times the voxel size: -ln(1 - alpha) for opacity alpha per voxel).
 * Returns false and explains in `why` (parameters untouched) for input
 * outside that domain or not finite.
 */
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT bool PhysicalMediumToMaterial(double albedo, double g,
  double extinctionPerVoxel, double parameters[MaterialParameterCount], std::string* why = nullptr);

} // namespace mmv

#endif
