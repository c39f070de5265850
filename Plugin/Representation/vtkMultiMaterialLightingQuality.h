/**
 * @file   vtkMultiMaterialLightingQuality.h
 * @brief  The "Lighting Quality" choice of the Multi-Material Volume
 *         representation: what each level sets the irradiance internals to.
 *
 * One table, read by vtkPVMultiMaterialVolumeRepresentation::SetLightingQuality
 * (C++) and by the server manager's link that keeps the proxy's internal
 * properties equal to it (vtkMultiMaterialLightingQualityLink.cxx), so the
 * panel, Python and C++ agree. Balanced equals the properties' defaults. The
 * frame time and error of each level are in docs/paraview.md.
 */
#ifndef vtkMultiMaterialLightingQuality_h
#define vtkMultiMaterialLightingQuality_h

#include "vtkMultiMaterialSettings.h" // the defaults Balanced takes

namespace mmv
{
enum LightingQualityLevel
{
  LightingQualityFast = 0,
  LightingQualityBalanced = 1,
  LightingQualityExact = 2,
  // The internals as set one by one (from Python or C++); no table row.
  LightingQualityCustom = 3
};

constexpr int DefaultLightingQuality = LightingQualityBalanced;

struct LightingQualitySettings
{
  int ShadowEstimation;
  int PiecewiseShadowSlices;
  int ExponentialDiffusion;
  int PieceIrradianceOnly;
  double LightDirectionTolerance; // degrees
  int ReflectionVisibility;       // the proxy's enumeration
  double IrradianceErrorBound;    // dB
  double IrradianceMemoryMB;
  double IrradianceScale; // 0: chosen from the budget, the screen and the probe
  int DimLightCoarsening; // dim lights' shadows on every second irradiance point
};

/// Rows in LightingQualityLevel order (Fast, Balanced, Exact).
constexpr LightingQualitySettings LightingQualityTable[3] = {
  // Fast: shorter piecewise rays, a coarser grid (smaller budget, looser
  // probe bound), reflections visibility from the grid, and small light turns
  // keep their irradiance.
  { PiecewiseShadowRays, 4, 1, 1, 2.0, 2, 28.0, 16.0, 0.0, 1 },
  // Balanced: the defaults.
  { DefaultIlluminationSettings.ShadowEstimation, DefaultIlluminationSettings.PiecewiseShadowSlices,
    DefaultIlluminationSettings.ExponentialDiffusion ? 1 : 0,
    DefaultIlluminationSettings.PieceIrradianceOnly ? 1 : 0,
    DefaultIlluminationSettings.LightDirectionTolerance,
    DefaultIlluminationSettings.ReflectionVisibility,
    DefaultIlluminationSettings.IrradianceErrorBound,
    DefaultIlluminationSettings.IrradianceMemoryMB, DefaultIlluminationSettings.IrradianceScale,
    DefaultIlluminationSettings.DimLightCoarsening ? 1 : 0 },
  // Exact: full shadow rays on the data's own grid for every light,
  // per-sample reflection visibility, no tolerance.
  { FullShadowRays, DefaultPiecewiseShadowSlices, 1, 1, 0.0, 1, 0.0, 256.0, 1.0, 0 },
};

/// The row of `level`, or null for Custom and out-of-range levels.
inline const LightingQualitySettings* GetLightingQualitySettings(int level)
{
  return (level >= LightingQualityFast && level <= LightingQualityExact)
    ? &LightingQualityTable[level]
    : nullptr;
}
}

#endif
