#include "vtkIrradianceDiffusion.h"

#include "vtkMath.h"
#include "vtkMultiMaterialThreads.h" // mmv::For
#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <vector>

namespace
{

using mmv::DiffusionFaceStrength;

/**
 * The system (I + dt*A) x = b of one backward-Euler step, A the flux-form
 * operator: (A p)_i = sum over faces f of c_f (p_i - p_j). Stored as one
 * coefficient per voxel and axis for the face towards the +axis neighbour
 * (0 on the last layer, which gives the zero-flux boundary).
 *
 * Reductions are computed per fixed block of grid rows and summed in block
 * order, so results do not depend on the number of threads.
 */
class DiffusionSystem
{
public:
  /// `capacity` (may be null: 1 everywhere) weighs each voxel's storage:
  /// the system becomes (C + dt*A) x = C b. Voxels with capacity 0 keep b.
  DiffusionSystem(
    const int dims[3], const double spacing[3], const float* strength, const float* capacity)
  {
    for (int a = 0; a < 3; ++a)
    {
      this->Dims[a] = dims[a];
    }
    this->Stride[0] = 1;
    this->Stride[1] = dims[0];
    this->Stride[2] = static_cast<vtkIdType>(dims[0]) * dims[1];
    this->Size = this->Stride[2] * dims[2];
    this->Rows = static_cast<vtkIdType>(dims[1]) * dims[2];
    // ~16k voxels per block: enough work per task, independent of threads.
    this->RowsPerBlock = std::max<vtkIdType>(1, 16384 / dims[0]);
    this->Blocks = (this->Rows + this->RowsPerBlock - 1) / this->RowsPerBlock;
    this->Partial.resize(static_cast<size_t>(this->Blocks) * 2);
    if (capacity)
    {
      this->Capacity.resize(this->Size);
      for (vtkIdType v = 0; v < this->Size; ++v)
      {
        this->Capacity[v] = capacity[v] > 0.0f ? capacity[v] : 1.0f;
      }
    }
    this->BuildCoefficients(spacing, strength);
  }

  /// Whether voxel v has a face with a non-zero coefficient.
  bool Exchanges(vtkIdType v) const { return this->RowSum(v) > 0.0; }

  /// The largest row sum of A over the capacity (Gershgorin: bounds the
  /// rates of C^-1 A).
  double GetMaxRowSum() const { return this->MaxRowSum; }
  vtkIdType GetSize() const { return this->Size; }

  /// Jacobi preconditioner of C + dt*A.
  void SetTimeStep(double dt)
  {
    this->Dt = dt;
    this->InvDiag.resize(this->Size);
    mmv::For(0, this->Size,
      [&](vtkIdType begin, vtkIdType end)
      {
        for (vtkIdType i = begin; i < end; ++i)
        {
          this->InvDiag[i] = static_cast<float>(1.0 / (this->CapacityOf(i) + dt * this->RowSum(i)));
        }
      });
  }

  double CapacityOf(vtkIdType v) const { return this->Capacity.empty() ? 1.0 : this->Capacity[v]; }

  /// Solves (C + dt*A) x = C b in place (x holds b on entry). Returns the
  /// iterations; `residual` receives the final relative residual.
  int Solve(std::vector<double>& x, double tolerance, int maxIterations, double& residual)
  {
    const vtkIdType n = this->Size;
    std::vector<double> r(n), p(n), q(n);
    double bNorm2 = 0.0;
    // x0 = b: r0 = C b - (C + dt A) b = -dt A b, zero for a uniform field.
    this->ForRows(
      [&](vtkIdType row, double* acc)
      {
        this->ApplyRow(row, x.data(), q.data(), this->Dt);
        for (vtkIdType i = this->RowStart(row), e = i + this->Dims[0]; i < e; ++i)
        {
          const double rhs = this->CapacityOf(i) * x[i];
          r[i] = rhs - q[i];
          p[i] = 0.0;
          acc[0] += r[i] * r[i] * this->InvDiag[i];
          acc[1] += rhs * rhs;
        }
      });
    double rz = this->Sum(0);
    bNorm2 = this->Sum(1);
    if (!(bNorm2 > 0.0))
    {
      residual = 0.0;
      return 0;
    }
    double rNorm2 = this->Dot(r, r);
    const double target2 = tolerance * tolerance * bNorm2;
    double beta = 0.0;
    int it = 0;
    while (rNorm2 > target2 && it < maxIterations && rz > 0.0)
    {
      // p = z + beta p, z = D^-1 r.
      mmv::For(0, n,
        [&](vtkIdType begin, vtkIdType end)
        {
          for (vtkIdType i = begin; i < end; ++i)
          {
            p[i] = r[i] * this->InvDiag[i] + beta * p[i];
          }
        });
      this->ForRows(
        [&](vtkIdType row, double* acc)
        {
          this->ApplyRow(row, p.data(), q.data(), this->Dt);
          for (vtkIdType i = this->RowStart(row), e = i + this->Dims[0]; i < e; ++i)
          {
            acc[0] += p[i] * q[i];
          }
        });
      const double pq = this->Sum(0);
      if (!(pq > 0.0))
      {
        break;
      }
      const double alpha = rz / pq;
      this->ForRows(
        [&](vtkIdType row, double* acc)
        {
          for (vtkIdType i = this->RowStart(row), e = i + this->Dims[0]; i < e; ++i)
          {
            x[i] += alpha * p[i];
            r[i] -= alpha * q[i];
            acc[0] += r[i] * r[i] * this->InvDiag[i];
            acc[1] += r[i] * r[i];
          }
        });
      const double rzNew = this->Sum(0);
      rNorm2 = this->Sum(1);
      beta = rzNew / rz;
      rz = rzNew;
      ++it;
    }
    residual = std::sqrt(rNorm2 / bNorm2);
    return it;
  }

private:
  void BuildCoefficients(const double spacing[3], const float* strength)
  {
    for (int a = 0; a < 3; ++a)
    {
      this->Spacing[a] = spacing[a];
      this->Coefficient[a].assign(this->Size, 0.0f);
    }
    std::vector<double> rowMax(this->Rows, 0.0);
    mmv::For(0, this->Rows,
      [&](vtkIdType begin, vtkIdType end)
      {
        for (vtkIdType row = begin; row < end; ++row)
        {
          const vtkIdType start = this->RowStart(row);
          const int j = static_cast<int>(row % this->Dims[1]);
          const int k = static_cast<int>(row / this->Dims[1]);
          for (int i = 0; i < this->Dims[0]; ++i)
          {
            const vtkIdType v = start + i;
            const double s = strength[v];
            const bool hasNext[3] = { i + 1 < this->Dims[0], j + 1 < this->Dims[1],
              k + 1 < this->Dims[2] };
            for (int a = 0; a < 3; ++a)
            {
              if (hasNext[a])
              {
                this->Coefficient[a][v] =
                  mmv::DiffusionFaceCoefficient(s, strength[v + this->Stride[a]], this->Spacing[a]);
              }
            }
          }
        }
      });
    // A second pass: row sums read the coefficients of neighbouring rows.
    mmv::For(0, this->Rows,
      [&](vtkIdType begin, vtkIdType end)
      {
        for (vtkIdType row = begin; row < end; ++row)
        {
          for (vtkIdType v = this->RowStart(row), e = v + this->Dims[0]; v < e; ++v)
          {
            rowMax[row] = std::max(rowMax[row], this->RowSum(v) / this->CapacityOf(v));
          }
        }
      });
    this->MaxRowSum = *std::max_element(rowMax.begin(), rowMax.end());
  }

  vtkIdType RowStart(vtkIdType row) const { return row * this->Dims[0]; }

  /// Sum of the face coefficients of voxel v (the diagonal of A).
  double RowSum(vtkIdType v) const
  {
    double sum = 0.0;
    for (int a = 0; a < 3; ++a)
    {
      sum += this->Coefficient[a][v];
      if (this->HasPrevious(v, a))
      {
        sum += this->Coefficient[a][v - this->Stride[a]];
      }
    }
    return sum;
  }

  bool HasPrevious(vtkIdType v, int axis) const
  {
    return (v / this->Stride[axis]) % this->Dims[axis] > 0;
  }

public:
  /// out = alpha u0 + beta (in - C^-1 A in / R) + gamma prev, over the whole
  /// grid: a step of the Clenshaw recurrence of the exponential's series
  /// (mirrored by Shaders/mmvDiffusionFS.glsl with MMV_EXPONENTIAL).
  void Clenshaw(const std::vector<double>& u0, const std::vector<double>& in,
    const std::vector<double>& prev, double alpha, double beta, double gamma,
    std::vector<double>& out) const
  {
    const double invRate = 1.0 / this->MaxRowSum;
    mmv::For(0, this->Rows,
      [&](vtkIdType begin, vtkIdType end)
      {
        for (vtkIdType row = begin; row < end; ++row)
        {
          this->ApplyRow(row, in.data(), out.data(), 1.0, false); // out = A in
          for (vtkIdType v = this->RowStart(row), e = v + this->Dims[0]; v < e; ++v)
          {
            const double applied = out[v] / this->CapacityOf(v); // C^-1 A in
            out[v] = alpha * u0[v] + beta * (in[v] - invRate * applied) + gamma * prev[v];
          }
        }
      });
  }

private:
  /// out = (C + dt A) in for one grid row, or dt A in without `capacity`.
  void ApplyRow(vtkIdType row, const double* in, double* out, double dt, bool capacity = true) const
  {
    const vtkIdType start = this->RowStart(row);
    const bool hasY[2] = { row % this->Dims[1] > 0, row % this->Dims[1] + 1 < this->Dims[1] };
    const bool hasZ[2] = { row / this->Dims[1] > 0, row / this->Dims[1] + 1 < this->Dims[2] };
    const float* cx = this->Coefficient[0].data();
    const float* cy = this->Coefficient[1].data();
    const float* cz = this->Coefficient[2].data();
    const vtkIdType sy = this->Stride[1];
    const vtkIdType sz = this->Stride[2];
    for (int i = 0; i < this->Dims[0]; ++i)
    {
      const vtkIdType v = start + i;
      const double c = in[v];
      double flux = 0.0;
      if (i + 1 < this->Dims[0])
      {
        flux += cx[v] * (c - in[v + 1]);
      }
      if (i > 0)
      {
        flux += cx[v - 1] * (c - in[v - 1]);
      }
      if (hasY[1])
      {
        flux += cy[v] * (c - in[v + sy]);
      }
      if (hasY[0])
      {
        flux += cy[v - sy] * (c - in[v - sy]);
      }
      if (hasZ[1])
      {
        flux += cz[v] * (c - in[v + sz]);
      }
      if (hasZ[0])
      {
        flux += cz[v - sz] * (c - in[v - sz]);
      }
      out[v] = (capacity ? this->CapacityOf(v) * c : 0.0) + dt * flux;
    }
  }

  /// Runs f(row, acc[2]) over all rows; acc accumulates into the row's block.
  template <typename F>
  void ForRows(F&& f)
  {
    mmv::For(0, this->Blocks,
      [&](vtkIdType begin, vtkIdType end)
      {
        for (vtkIdType b = begin; b < end; ++b)
        {
          double acc[2] = { 0.0, 0.0 };
          const vtkIdType last = std::min(this->Rows, (b + 1) * this->RowsPerBlock);
          for (vtkIdType row = b * this->RowsPerBlock; row < last; ++row)
          {
            f(row, acc);
          }
          this->Partial[2 * b] = acc[0];
          this->Partial[2 * b + 1] = acc[1];
        }
      });
  }

  /// Block partials of the last ForRows, added in block order (deterministic).
  double Sum(int which) const
  {
    double sum = 0.0;
    for (vtkIdType b = 0; b < this->Blocks; ++b)
    {
      sum += this->Partial[2 * b + which];
    }
    return sum;
  }

  double Dot(const std::vector<double>& u, const std::vector<double>& w)
  {
    this->ForRows(
      [&](vtkIdType row, double* acc)
      {
        for (vtkIdType i = this->RowStart(row), e = i + this->Dims[0]; i < e; ++i)
        {
          acc[0] += u[i] * w[i];
        }
      });
    return this->Sum(0);
  }

  int Dims[3];
  vtkIdType Stride[3];
  vtkIdType Size = 0;
  vtkIdType Rows = 0;
  vtkIdType RowsPerBlock = 1;
  vtkIdType Blocks = 0;
  double Spacing[3];
  double Dt = 0.0;
  double MaxRowSum = 0.0;
  std::vector<float> Coefficient[3];
  std::vector<float> InvDiag;
  std::vector<float> Capacity; // empty: 1 everywhere
  std::vector<double> Partial;
};

bool AnyPositive(const float* strength, vtkIdType n)
{
  return std::any_of(strength, strength + n, [](float s) { return s > 0.0f; });
}

} // namespace

namespace mmv
{

//------------------------------------------------------------------------------
double FilledBlockShare(const float* capacity, vtkIdType blocks)
{
  double all = 0.0;
  double filled = 0.0;
  for (vtkIdType b = 0; capacity && b < blocks; ++b)
  {
    all += capacity[b];
    filled += capacity[b] >= 1.0f ? capacity[b] : 0.0f;
  }
  return all > 0.0 ? filled / all : 0.0;
}

//------------------------------------------------------------------------------
double MaxDiffusionRate(
  const int dims[3], const double spacing[3], const float* strength, const float* capacity)
{
  const vtkIdType n = static_cast<vtkIdType>(dims[0]) * dims[1] * dims[2];
  if (n < 1 || !AnyPositive(strength, n))
  {
    return 0.0;
  }
  return DiffusionSystem(dims, spacing, strength, capacity).GetMaxRowSum();
}

int DiffusionSubSteps(double maxRate, const DiffusionSettings& settings)
{
  // As many sub-steps as an explicit scheme would need to stay stable
  // (dt * maxRate <= 1), capped: below that limit one implicit step is already
  // accurate; above it, extra steps buy first-order accuracy in time.
  const double explicitSteps = std::ceil(settings.Time * maxRate);
  return static_cast<int>(
    std::min<double>(std::max(1, settings.MaxSubSteps), std::max(1.0, explicitSteps)));
}

double JacobiSpectralRadius(double dtTimesMaxRate)
{
  return dtTimesMaxRate > 0.0 ? dtTimesMaxRate / (1.0 + dtTimesMaxRate) : 0.0;
}

int JacobiSweeps(double dtTimesMaxRate, const DiffusionSettings& settings)
{
  const double rho = JacobiSpectralRadius(dtTimesMaxRate);
  if (!(rho > 0.0))
  {
    return 1;
  }
  const double tolerance = std::min(std::max(settings.SweepTolerance, 1.0e-12), 0.5);
  return std::max(1, static_cast<int>(std::ceil(std::log(tolerance) / std::log(rho))));
}

int ChebyshevSweeps(double dtTimesMaxRate, const DiffusionSettings& settings)
{
  const double rho = JacobiSpectralRadius(dtTimesMaxRate);
  if (!(rho > 0.0))
  {
    return 1;
  }
  const double c = rho / (1.0 + std::sqrt(1.0 - rho * rho));
  const double tolerance = std::min(std::max(settings.SweepTolerance, 1.0e-12), 0.5);
  // 2 c^k / (1 + c^2k) <= 2 c^k <= tolerance.
  return std::max(1, static_cast<int>(std::ceil(std::log(0.5 * tolerance) / std::log(c))));
}

std::vector<double> ExponentialChebyshevCoefficients(double a, double tolerance)
{
  std::vector<double> c;
  if (!(a > 0.0) || !std::isfinite(a))
  {
    return c;
  }
  // c_k of f(y) = exp(-a (1 - y)) by the discrete cosine transform at N
  // Chebyshev nodes (f <= 1: no overflow for large a, as e^-a I_k(a) had);
  // the coefficients fall off beyond k ~ sqrt(2 a ln(1/tol)), so N covers
  // them with room.
  const double tol = std::min(std::max(tolerance, 1.0e-14), 0.5);
  const int needed = static_cast<int>(std::ceil(std::sqrt(2.0 * a * std::log(1.0 / tol)))) + 16;
  const int nodes = 2 * std::max(needed, 32);
  std::vector<double> f(nodes);
  for (int j = 0; j < nodes; ++j)
  {
    const double theta = vtkMath::Pi() * (j + 0.5) / nodes;
    f[j] = std::exp(-a * (1.0 - std::cos(theta)));
  }
  c.resize(nodes);
  for (int k = 0; k < nodes; ++k)
  {
    double sum = 0.0;
    for (int j = 0; j < nodes; ++j)
    {
      sum += f[j] * std::cos(k * vtkMath::Pi() * (j + 0.5) / nodes);
    }
    c[k] = (k == 0 ? 1.0 : 2.0) * sum / nodes;
  }
  // Truncate where the tail falls below the tolerance.
  double tail = 0.0;
  int degree = nodes - 1;
  while (degree > 0 && tail + std::abs(c[degree]) < tol)
  {
    tail += std::abs(c[degree]);
    --degree;
  }
  c.resize(degree + 1);
  return c;
}

double ChebyshevWeight(int k, double rho)
{
  double omega = 1.0;
  for (int i = 2; i <= k; ++i)
  {
    omega = i == 2 ? 1.0 / (1.0 - 0.5 * rho * rho) : 1.0 / (1.0 - 0.25 * rho * rho * omega);
  }
  return omega;
}

double DiffusionBlockTexels(const int dims[3], const double spacing[3], const float* strength,
  const float* capacity, std::vector<float>& facesXY, std::vector<float>& facesZ,
  std::vector<float>& exchanges)
{
  const vtkIdType stride[3] = { 1, dims[0], static_cast<vtkIdType>(dims[0]) * dims[1] };
  const vtkIdType count = stride[2] * dims[2];
  // Every texel is written below: vectors kept from the last plan are
  // reused without a fill.
  facesXY.resize(4 * count);
  facesZ.resize(4 * count);
  exchanges.resize(count);
  std::mutex maxRateMutex;
  double maxRate = 0.0;
  mmv::For(0, count,
    [&](vtkIdType begin, vtkIdType end)
    {
      double chunkMax = 0.0;
      for (vtkIdType v = begin; v < end; ++v)
      {
        const int index[3] = { static_cast<int>(v % dims[0]),
          static_cast<int>((v / dims[0]) % dims[1]), static_cast<int>(v / stride[2]) };
        float faces[6];
        for (int a = 0; a < 3; ++a)
        {
          faces[2 * a] = index[a] > 0
            ? DiffusionFaceCoefficient(strength[v - stride[a]], strength[v], spacing[a])
            : 0.0f;
          faces[2 * a + 1] = index[a] + 1 < dims[a]
            ? DiffusionFaceCoefficient(strength[v], strength[v + stride[a]], spacing[a])
            : 0.0f;
        }
        std::copy(faces, faces + 4, facesXY.begin() + 4 * v);
        facesZ[4 * v] = faces[4];
        facesZ[4 * v + 1] = faces[5];
        facesZ[4 * v + 2] = capacity && capacity[v] > 0.0f ? capacity[v] : 1.0f;
        facesZ[4 * v + 3] = strength[v] > 0.0f ? 1.0f : 0.0f;
        exchanges[v] =
          std::any_of(faces, faces + 6, [](float c) { return c > 0.0f; }) ? 1.0f : 0.0f;
        // The row sum in DiffusionSystem::RowSum's order (toward + then -
        // per axis), so the rate equals MaxDiffusionRate's bit for bit.
        double sum = 0.0;
        for (int a = 0; a < 3; ++a)
        {
          sum += faces[2 * a + 1];
          sum += faces[2 * a];
        }
        chunkMax = std::max(chunkMax, sum / static_cast<double>(facesZ[4 * v + 2]));
      }
      std::lock_guard<std::mutex> lock(maxRateMutex);
      maxRate = std::max(maxRate, chunkMax);
    });
  return maxRate;
}

DiffusionGrid PlanDiffusionGrid(
  const int dims[3], const double spacing[3], double maxStrength, const DiffusionSettings& settings)
{
  DiffusionGrid grid;
  grid.DiffusionLength =
    maxStrength > 0.0 && settings.Time > 0.0 ? std::sqrt(2.0 * maxStrength * settings.Time) : 0.0;
  const double target = settings.VoxelsPerDiffusionLength > 0.0
    ? grid.DiffusionLength / settings.VoxelsPerDiffusionLength
    : 0.0;
  for (int a = 0; a < 3; ++a)
  {
    const double h = spacing[a] > 0.0 ? spacing[a] : 1.0;
    const int largest = std::max(1, dims[a] / std::max(1, settings.MinimumVoxelsPerAxis));
    // The whole factor nearest in ratio (f or f + 1, split at sqrt(f (f + 1))):
    // an irradiance grid of 1.34 data voxels (scale 0.75) with L / 2 = 2
    // wants 1.5, and factor 1 would triple the diffusion grid of factor 2.
    const double wanted = target / h;
    int factor = std::max(1, static_cast<int>(std::floor(wanted)));
    if (wanted > std::sqrt(static_cast<double>(factor) * (factor + 1)))
    {
      ++factor;
    }
    grid.Factor[a] = std::min(largest, factor);
    grid.Dimensions[a] = (dims[a] + grid.Factor[a] - 1) / grid.Factor[a];
    grid.Spacing[a] = h * grid.Factor[a];
  }
  return grid;
}

void RestrictToDiffusionGrid(const int dims[3], const DiffusionGrid& coarse, const float* strength,
  const float* fine, std::vector<float>* coarseStrength, std::vector<float>* coarseIrradiance,
  std::vector<float>* coarseCapacity)
{
  const vtkIdType count = coarse.GetNumberOfVoxels();
  if (coarseStrength)
  {
    coarseStrength->assign(count, 0.0f);
  }
  if (coarseCapacity)
  {
    coarseCapacity->assign(count, 0.0f);
  }
  if (coarseIrradiance)
  {
    coarseIrradiance->assign(count, 0.0f);
  }
  const int* cd = coarse.Dimensions;
  const int* f = coarse.Factor;
  mmv::For(0, count,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType c = begin; c < end; ++c)
      {
        const int ci = static_cast<int>(c % cd[0]);
        const int cj = static_cast<int>((c / cd[0]) % cd[1]);
        const int ck = static_cast<int>(c / (static_cast<vtkIdType>(cd[0]) * cd[1]));
        double sSum = 0.0;
        double iSum = 0.0;
        int voxels = 0;
        int scattering = 0;
        for (int k = ck * f[2]; k < std::min(dims[2], (ck + 1) * f[2]); ++k)
        {
          for (int j = cj * f[1]; j < std::min(dims[1], (cj + 1) * f[1]); ++j)
          {
            for (int i = ci * f[0]; i < std::min(dims[0], (ci + 1) * f[0]); ++i)
            {
              const vtkIdType v =
                i + static_cast<vtkIdType>(dims[0]) * (j + static_cast<vtkIdType>(dims[1]) * k);
              ++voxels;
              if (strength[v] > 0.0f)
              {
                sSum += strength[v];
                iSum += fine ? fine[v] : 0.0;
                ++scattering;
              }
            }
          }
        }
        if (coarseStrength)
        {
          (*coarseStrength)[c] = static_cast<float>(sSum / voxels);
        }
        if (coarseIrradiance && scattering > 0)
        {
          (*coarseIrradiance)[c] = static_cast<float>(iSum / scattering);
        }
        if (coarseCapacity)
        {
          (*coarseCapacity)[c] = static_cast<float>(static_cast<double>(scattering) / voxels);
        }
      }
    });
}

DiffusionReport DiffuseIrradiance(const int dims[3], const double spacing[3], const float* strength,
  float* irradiance, const DiffusionSettings& settings, const float* capacity)
{
  DiffusionReport report;
  report.Skipped = true;
  if (!dims || !spacing || !strength || !irradiance || dims[0] < 1 || dims[1] < 1 || dims[2] < 1 ||
    !(settings.Time > 0.0))
  {
    return report;
  }
  const vtkIdType n = static_cast<vtkIdType>(dims[0]) * dims[1] * dims[2];
  if (!AnyPositive(strength, n))
  {
    return report;
  }
  DiffusionSystem system(dims, spacing, strength, capacity);
  // The largest row sum of A bounds its spectrum (Gershgorin); zero means no
  // two neighbouring voxels both scatter, so nothing can move.
  const double maxRate = system.GetMaxRowSum();
  if (!(maxRate > 0.0))
  {
    return report;
  }
  report.Skipped = false;
  if (settings.Exponential)
  {
    // Clenshaw: b_k = c_k u0 + 2 B b_k+1 - b_k+2 from k = n down to 1, then
    // S = c_0 u0 + B b_1 - b_2 (ExponentialChebyshevCoefficients).
    const std::vector<double> c =
      ExponentialChebyshevCoefficients(settings.Time * maxRate, settings.Tolerance);
    std::vector<double> u0(irradiance, irradiance + n);
    std::vector<double> next(n, 0.0), current(n, 0.0), previous(n, 0.0);
    for (size_t k = c.size(); k-- > 0;)
    {
      const bool last = k == 0;
      system.Clenshaw(u0, current, previous, c[k], last ? 1.0 : 2.0, -1.0, next);
      std::swap(previous, current);
      std::swap(current, next);
      ++report.Iterations;
    }
    report.SubSteps = 1;
    for (vtkIdType v = 0; v < n; ++v)
    {
      // A voxel that exchanges nothing (no face coefficient) keeps its value
      // exactly, not the truncated series' (1 - tail) of it.
      irradiance[v] =
        system.Exchanges(v) ? static_cast<float>(std::max(0.0, current[v])) : irradiance[v];
    }
    return report;
  }
  report.SubSteps = DiffusionSubSteps(maxRate, settings);
  const double dt = settings.Time / report.SubSteps;
  system.SetTimeStep(dt);

  std::vector<double> x(irradiance, irradiance + n);
  for (int step = 0; step < report.SubSteps; ++step)
  {
    report.Iterations += system.Solve(
      x, settings.Tolerance, std::max(1, settings.MaxIterations), report.FinalResidual);
  }
  std::copy(x.begin(), x.end(), irradiance);
  return report;
}

DiffusionReport DiffuseIrradianceOnDiffusionGrid(const int dims[3], const double spacing[3],
  const float* strength, float* irradiance, const DiffusionSettings& settings,
  DiffusionGrid* usedGrid)
{
  DiffusionReport report;
  report.Skipped = true;
  if (!dims || !spacing || !strength || !irradiance || dims[0] < 1 || dims[1] < 1 || dims[2] < 1)
  {
    return report;
  }
  const vtkIdType n = static_cast<vtkIdType>(dims[0]) * dims[1] * dims[2];
  const double maxStrength = *std::max_element(strength, strength + n);
  const DiffusionGrid coarse = PlanDiffusionGrid(dims, spacing, maxStrength, settings);
  if (usedGrid)
  {
    *usedGrid = coarse;
  }
  std::vector<float> coarseStrength;
  std::vector<float> before;
  std::vector<float> capacity;
  RestrictToDiffusionGrid(dims, coarse, strength, irradiance, &coarseStrength, &before, &capacity);
  std::vector<float> after = before;
  report = DiffuseIrradiance(coarse.Dimensions, coarse.Spacing, coarseStrength.data(), after.data(),
    settings, capacity.data());
  if (report.Skipped)
  {
    return report;
  }
  // Where the fine grid scatters, add the change, interpolated trilinearly.
  const int* cd = coarse.Dimensions;
  mmv::For(0, n,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType v = begin; v < end; ++v)
      {
        if (!(strength[v] > 0.0f))
        {
          continue;
        }
        const int index[3] = { static_cast<int>(v % dims[0]),
          static_cast<int>((v / dims[0]) % dims[1]),
          static_cast<int>(v / (static_cast<vtkIdType>(dims[0]) * dims[1])) };
        int lo[3];
        int hi[3];
        double w[3];
        for (int a = 0; a < 3; ++a)
        {
          const double u = coarse.CoarseCoordinate(a, index[a]);
          lo[a] = std::min(static_cast<int>(u), cd[a] - 1);
          hi[a] = std::min(lo[a] + 1, cd[a] - 1);
          w[a] = u - lo[a];
        }
        // Trilinear over the corners that scatter, renormalised: a corner
        // block without scattering voxels has no light to give.
        double sum = 0.0;
        double weights = 0.0;
        for (int corner = 0; corner < 8; ++corner)
        {
          double weight = 1.0;
          int c[3];
          for (int a = 0; a < 3; ++a)
          {
            const bool upper = (corner >> a) & 1;
            c[a] = upper ? hi[a] : lo[a];
            weight *= upper ? w[a] : 1.0 - w[a];
          }
          const vtkIdType id =
            c[0] + static_cast<vtkIdType>(cd[0]) * (c[1] + static_cast<vtkIdType>(cd[1]) * c[2]);
          if (weight > 0.0 && capacity[id] > 0.0f)
          {
            sum += weight * (after[id] - before[id]);
            weights += weight;
          }
        }
        if (weights > 0.0)
        {
          irradiance[v] = static_cast<float>(std::max(0.0, irradiance[v] + sum / weights));
        }
      }
    });
  return report;
}

} // namespace mmv
