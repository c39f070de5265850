/**
 * @file   vtkIrradianceDiffusion.h
 * @brief  Multiple scattering as diffusion of the irradiance (Zhang & Ma eq. 15).
 *
 * Solves dI/dt = div(s grad I) on a regular grid up to time T with zero-flux
 * boundaries. The scheme is implicit (backward Euler, a few sub-steps, each
 * solved by Jacobi-preconditioned conjugate gradients), so it is stable for
 * every s >= 0: an explicit step would blow up once s*dt/h^2 > 1/6. The
 * implicit operator is an M-matrix, so the discrete maximum principle holds
 * (no new maxima or minima), and the flux form makes the total sum of I
 * invariant (energy is conserved) up to the solver tolerance.
 *
 * Face coefficients are the harmonic mean of the two voxels' s, so light does
 * not diffuse across voxels with s = 0 (empty space).
 */
#ifndef vtkIrradianceDiffusion_h
#define vtkIrradianceDiffusion_h

#include "vtkMultiMaterialVolumeModule.h" // export macro

namespace mmv
{

struct DiffusionSettings
{
  double Time = 1.0;           // T, in the units of s
  int MaxSubSteps = 8;         // backward-Euler steps used to reach T
  double Tolerance = 1.0e-7;   // relative residual of each CG solve
  int MaxIterations = 2000;    // per CG solve
};

struct DiffusionReport
{
  int SubSteps = 0;
  int Iterations = 0;          // CG iterations summed over sub-steps
  double FinalResidual = 0.0;  // relative residual of the last solve
  /// True when `irradiance` was left untouched (and the counts above are 0):
  ///  - an argument is null, a dimension is below 1, or Time is not > 0
  ///    (NaN included);
  ///  - no voxel has s > 0;
  ///  - no two face-neighbouring voxels both have s > 0: face coefficients
  ///    are harmonic means, so every flux is zero and nothing can move.
  bool Skipped = false;
};

/**
 * Diffuses `irradiance` (dims[0]*dims[1]*dims[2] floats, x fastest) in place.
 * `strength` holds s per voxel (same layout, >= 0). `spacing` is the grid
 * spacing in the units s is expressed in (data voxels for the filter).
 * Multithreaded with vtkSMPTools. Returns a report of what was done.
 */
VTKMULTIMATERIALVOLUME_EXPORT DiffusionReport DiffuseIrradiance(const int dims[3],
  const double spacing[3], const float* strength, float* irradiance,
  const DiffusionSettings& settings = DiffusionSettings());

} // namespace mmv

#endif
