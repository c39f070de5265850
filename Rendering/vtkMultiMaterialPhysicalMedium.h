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
 * Fitted by Testing/Benchmark/mmvMediumCalibration; the table, the formula's
 * derivation and its residual are in docs/benchmark.md ("Mapping physical
 * media to our parameters").
 */
#ifndef vtkMultiMaterialPhysicalMedium_h
#define vtkMultiMaterialPhysicalMedium_h

#include "vtkMultiMaterialParameters.h"
#include "vtkMultiMaterialVolumeModule.h" // export macro

#include <string>

namespace mmv
{

/// The domain the mapping was fitted on and is defined for.
constexpr double PhysicalMediumMaxAlbedo = 0.999;
constexpr double PhysicalMediumMaxAnisotropy = 0.9;

/**
 * Fills `parameters` (mmv::MaterialParameterCount values, in the table's
 * order) for a medium of single-scattering albedo `albedo` in [0, 0.999],
 * anisotropy `g` in [-0.9, 0.9] and extinction `extinctionPerVoxel` > 0
 * (sigma_t times the voxel size: -ln(1 - alpha) for opacity alpha per voxel).
 * Returns false and explains in `why` (parameters untouched) for input
 * outside that domain or not finite.
 */
VTKMULTIMATERIALVOLUME_EXPORT bool PhysicalMediumToMaterial(double albedo, double g,
  double extinctionPerVoxel, double parameters[MaterialParameterCount],
  std::string* why = nullptr);

} // namespace mmv

#endif
