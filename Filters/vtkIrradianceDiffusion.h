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

#include "vtkMultiMaterialVolumeFiltersModule.h" // export macro
#include "vtkType.h"                             // vtkIdType

#include <vector> // restriction

namespace mmv
{

struct DiffusionSettings
{
  double Time = 1.0;         // T, in the units of s
  int MaxSubSteps = 8;       // backward-Euler steps used to reach T
  double Tolerance = 1.0e-7; // relative residual of each CG solve
  int MaxIterations = 2000;  // per CG solve
  /// Diffusion-grid voxels per diffusion length L = sqrt(2 s_max T): the
  /// scattered light is no sharper than L, so the change the diffusion makes
  /// is computed on the irradiance grid coarsened by the whole factor nearest
  /// (in ratio) to a spacing of L / VoxelsPerDiffusionLength (never finer
  /// than the irradiance grid). This bounds the stiffness s dt / h^2 of the coarse
  /// system, so the solve costs the same for every s. 0 disables coarsening.
  /// 2 still resolves thin scattering layers such as a head's skin, which 1
  /// blurs, at a fraction of the full-resolution cost (docs/performance.md,
  /// "Diffusion: exponential series against backward Euler").
  double VoxelsPerDiffusionLength = 2.0;
  /// The diffusion grid keeps at least this many voxels per axis (where the
  /// irradiance grid has them): coarser, the change is interpolated between
  /// so few blocks that the direct light's curvature inside a block shows
  /// as ripples (at 8, FailureCases.DiffusionStaysBoundedAndMonotone's
  /// 17-voxel slab rippled at s = 1000).
  int MinimumVoxelsPerAxis = 12;
  /// The GPU's error per sub-step, as a fraction of the largest irradiance
  /// (errors of sub-steps add up, so the total is at most MaxSubSteps times
  /// this): a sub-step stops once every Jacobi correction |J(x) - x| is below
  /// (1 - rho) times it, and after the sweeps the Chebyshev error bound
  /// needs at the latest.
  double SweepTolerance = 1.0e-3;
  /// How the diffusion is integrated in time. False (this struct's default,
  /// and the reference renderer's): MaxSubSteps backward-Euler steps (CG on
  /// the CPU, Chebyshev-accelerated Jacobi on the GPU), first order in time.
  /// True (what the filter, the mapper and the estimator use by default,
  /// mmv::DefaultExponentialDiffusion): the exponential exp(-T C^-1 A)
  /// applied as a truncated Chebyshev series (ExponentialChebyshevCoefficients),
  /// exact in time and in several times fewer GPU passes (docs/performance.md,
  /// "Diffusion: exponential series against backward Euler").
  bool Exponential = false;
};

/**
 * The diffusion of lights whose transmittance is estimated on a light grid of
 * `stride` (mmv::LightGridStride: the light kit's dim lights). Their
 * transmittance has no detail finer than `stride` irradiance voxels and their
 * share of the image is small, so their diffusion grid may be `stride` times
 * coarser: VoxelsPerDiffusionLength / stride, where the scattering fills
 * that grid's blocks (FilledBlockShare; docs/performance.md, "Dim lights on
 * a coarser grid", measures the image error).
 */
inline DiffusionSettings LightGridDiffusionSettings(DiffusionSettings settings, int stride)
{
  if (stride > 1 && settings.VoxelsPerDiffusionLength > 0.0)
  {
    settings.VoxelsPerDiffusionLength /= stride;
  }
  return settings;
}

/**
 * The share of the scattering voxels that lie in blocks they fill entirely,
 * from the blocks' capacities (RestrictToDiffusionGrid): 1 where the
 * scattering is thicker than the blocks, near 0 for a layer thinner than
 * one. A layer thinner than a block exchanges light across its thickness,
 * which the block's one mean cannot; on a one-voxel shell lit from outside
 * that keeps the lit face too bright. 0 where nothing scatters.
 */
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT double FilledBlockShare(
  const float* capacity, vtkIdType blocks);

/// The FilledBlockShare a coarser diffusion grid needs to stand in for the
/// lights' own (LightGridDiffusionSettings). Measured under the light kit: a
/// one-voxel shell has 0.03 (29.9 dB on the coarser grid), the MR head's and
/// the CT's scattering bodies 0.86-0.95 (54-56 dB).
constexpr double MinimumFilledBlockShare = 0.5;

struct DiffusionReport
{
  int SubSteps = 0;
  int Iterations = 0;         // CG iterations summed over sub-steps
  double FinalResidual = 0.0; // relative residual of the last solve
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
 * `capacity` (optional, same layout) is the fraction of each voxel that
 * holds light (C dI/dt = div(s grad I)): the diffusion grid gives blocks
 * only partly filled with scattering voxels their share; null means 1.
 * Multithreaded with vtkSMPTools. Returns a report of what was done.
 */
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT DiffusionReport DiffuseIrradiance(const int dims[3],
  const double spacing[3], const float* strength, float* irradiance,
  const DiffusionSettings& settings = DiffusionSettings(), const float* capacity = nullptr);

/// Face coefficient between two voxels: the harmonic mean of their s, so a
/// voxel with s = 0 blocks the flux completely (an arithmetic mean would
/// not). The GPU reads it precomputed (DiffusionBlockTexels).
inline double DiffusionFaceStrength(double a, double b)
{
  return (a > 0.0 && b > 0.0) ? 2.0 * a * b / (a + b) : 0.0;
}

/// The coefficient c_f of the face between two neighbours along an axis of
/// spacing h: DiffusionFaceStrength / h^2, rounded to float as the solvers
/// store it.
inline float DiffusionFaceCoefficient(double a, double b, double h)
{
  const double spacing = h > 0.0 ? h : 1.0;
  return static_cast<float>(DiffusionFaceStrength(a, b) / (spacing * spacing));
}

/**
 * What one GPU diffusion pass reads per block, two RGBA texels in two
 * arrays (4 floats per block each): `facesXY` holds the face coefficients
 * toward -x, +x, -y and +y, `facesZ` those toward -z and +z, the capacity
 * (1 where a block has none, as the solvers treat it) and 1 where the block
 * scatters (0 otherwise). A face to a missing neighbour has coefficient 0,
 * the zero-flux boundary. `exchanges` (one float per block) is 1 where a
 * face coefficient is above 0, the blocks the passes compute, else 0.
 * `capacity` may be null (1 everywhere). Returns MaxDiffusionRate of the
 * same inputs, exactly (the faces are the operator's rows): one pass over the
 * blocks instead of two.
 */
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT double DiffusionBlockTexels(const int dims[3],
  const double spacing[3], const float* strength, const float* capacity,
  std::vector<float>& facesXY, std::vector<float>& facesZ, std::vector<float>& exchanges);

/// The largest row sum of the diffusion operator over the capacity (a
/// Gershgorin bound of its rates), in 1 / unit time; 0 when nothing can move.
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT double MaxDiffusionRate(const int dims[3],
  const double spacing[3], const float* strength, const float* capacity = nullptr);

/// Backward-Euler sub-steps to reach `settings.Time` on a grid whose largest
/// rate is `maxRate`: as many as an explicit scheme would need, capped.
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT int DiffusionSubSteps(
  double maxRate, const DiffusionSettings& settings = DiffusionSettings());

/// The spectral radius bound of the Jacobi iteration of one sub-step of
/// length dt: with r = dt * maxRate, each row of the iteration matrix sums
/// to at most rho = r / (1 + r).
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT double JacobiSpectralRadius(double dtTimesMaxRate);

/// Plain Jacobi sweeps that bring the error below settings.SweepTolerance:
/// ln(tol) / ln(rho). For comparison only; the GPU accelerates them.
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT int JacobiSweeps(
  double dtTimesMaxRate, const DiffusionSettings& settings = DiffusionSettings());

/**
 * Sweeps of Chebyshev-accelerated Jacobi (the Chebyshev semi-iterative
 * method, weights omega_1 = 1, omega_2 = 1 / (1 - rho^2 / 2),
 * omega_k+1 = 1 / (1 - rho^2 omega_k / 4)) that bring the error below
 * settings.SweepTolerance: the error falls as 2 c^k / (1 + c^2k) with
 * c = rho / (1 + sqrt(1 - rho^2)), about the square root of plain Jacobi's
 * count for stiff systems. At least 1.
 */
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT int ChebyshevSweeps(
  double dtTimesMaxRate, const DiffusionSettings& settings = DiffusionSettings());

/**
 * The Chebyshev series of the diffusion's exponential: with rate bound R
 * (MaxDiffusionRate, so the rates of C^-1 A lie in [0, 2R]) and
 * B = I - C^-1 A / R (spectrum in [-1, 1]),
 *   exp(-T C^-1 A) = sum_k c_k T_k(B),  c_k the coefficients of
 *   exp(-a (1 - y)) on [-1, 1], a = T R,
 * truncated at the first n whose tail sum_{k > n} |c_k| is below
 * `tolerance` (|T_k| <= 1 there, so that bounds the error relative to the
 * largest irradiance). The degree grows as sqrt(a), not as a: a = 21 (the
 * CT's `skin`) needs n = 17 at 1e-3. Empty when a is not > 0.
 */
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT std::vector<double> ExponentialChebyshevCoefficients(
  double a, double tolerance);

/// The weight omega_k (k >= 1) of sweep k of a sub-step.
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT double ChebyshevWeight(int k, double rho);

/**
 * The grid the diffusion's change is computed on: the irradiance grid of
 * `dims` (spacing `spacing` in the units of s) coarsened by a whole factor per
 * axis. Coarse voxel J covers fine voxels [J f, J f + f) and sits at their
 * centre, fine index J f + (f - 1) / 2.
 */
struct DiffusionGrid
{
  int Factor[3] = { 1, 1, 1 };
  int Dimensions[3] = { 0, 0, 0 };
  double Spacing[3] = { 1.0, 1.0, 1.0 };
  double DiffusionLength = 0.0; // sqrt(2 s_max T), in the units of spacing

  vtkIdType GetNumberOfVoxels() const
  {
    return static_cast<vtkIdType>(this->Dimensions[0]) * this->Dimensions[1] * this->Dimensions[2];
  }
  bool IsIdentity() const { return this->Factor[0] * this->Factor[1] * this->Factor[2] == 1; }
  /// The continuous coarse index of fine index i along `axis`, clamped to
  /// the coarse grid (for trilinear prolongation).
  double CoarseCoordinate(int axis, int i) const
  {
    const double f = this->Factor[axis];
    const double u = (i - 0.5 * (f - 1.0)) / f;
    return u < 0.0 ? 0.0 : (u > this->Dimensions[axis] - 1 ? this->Dimensions[axis] - 1 : u);
  }
};

VTKMULTIMATERIALVOLUMEFILTERS_EXPORT DiffusionGrid PlanDiffusionGrid(const int dims[3],
  const double spacing[3], double maxStrength,
  const DiffusionSettings& settings = DiffusionSettings());

/**
 * Restriction to the diffusion grid: the coarse strength is the block mean of
 * s over all its voxels (a half-empty block conducts half as well), the
 * capacity the fraction of its voxels with s > 0 (a thin scattering shell
 * fills a block only in part), and the coarse irradiance the mean over those
 * voxels (0 when none), so partly filled blocks do not look darker than they
 * are. Any output may be null.
 */
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT void RestrictToDiffusionGrid(const int dims[3],
  const DiffusionGrid& coarse, const float* strength, const float* fine,
  std::vector<float>* coarseStrength, std::vector<float>* coarseIrradiance,
  std::vector<float>* coarseCapacity = nullptr);

/**
 * Multiple scattering as the paper computes it, at the cost of a coarse grid:
 * restrict the irradiance to the diffusion grid (PlanDiffusionGrid), diffuse
 * it there with the blocks' capacities (DiffuseIrradiance), and add the
 * change it made to every voxel with s > 0 (clamped at 0), interpolated
 * trilinearly over the corner blocks that scatter. With a factor of 1 this
 * equals DiffuseIrradiance. The GPU pass (vtkIrradianceEstimator) computes
 * the same.
 *
 * Adding the change keeps the direct light's detail finer than a block,
 * which a full solve would smooth; interpolating the diffused field instead
 * smooths it; it is closer to the full solve at a lit slab's face
 * (DiffusionGrid.CoarseChangeApproachesTheFullSolve), but the reference
 * renderer adds its change to each sample's own direct light, and adding the
 * change matches it better on the benchmark scenes. The change it is.
 */
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT DiffusionReport DiffuseIrradianceOnDiffusionGrid(
  const int dims[3], const double spacing[3], const float* strength, float* irradiance,
  const DiffusionSettings& settings = DiffusionSettings(), DiffusionGrid* usedGrid = nullptr);

} // namespace mmv

#endif
