#include "vtkSkyVisibility.h"

#include "vtkTableLookup.h"

#include "vtkMultiMaterialThreads.h" // mmv::For
#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mmv
{

namespace
{

/// Rays that leave through a side within this many steps are marched.
constexpr double MarchedSideSteps = 8.0;

float CleanExtinction(float sigma)
{
  return sigma > 0.0f ? sigma : 0.0f; // NaN and negative: nothing absorbs
}

/// Which coarse voxel each fine index of one axis belongs to: the nearest.
std::vector<int> NearestCoarse(int fine, int coarse)
{
  std::vector<int> map(fine, 0);
  if (fine > 1 && coarse > 1)
  {
    const double ratio = static_cast<double>(coarse - 1) / (fine - 1);
    for (int i = 0; i < fine; ++i)
    {
      map[i] = std::min(coarse - 1, static_cast<int>(std::lround(i * ratio)));
    }
  }
  return map;
}

/// One slice of the sweep: the voxels whose index along `axis` is `slice`,
/// each from slice `slice + sign` (already swept).
struct SliceSweep
{
  const int* N;
  int Axis, U, V;
  glm::dvec3 Step; // index units, Step[Axis] = +-1
  double Length;   // physical length of Step
  const float* Extinction;
  float* T;

  vtkIdType Index(int a, int u, int v) const
  {
    int c[3];
    c[this->Axis] = a;
    c[this->U] = u;
    c[this->V] = v;
    return (static_cast<vtkIdType>(c[2]) * this->N[1] + c[1]) * this->N[0] + c[0];
  }

  /// Steps (of Step) from (u, v) until the ray leaves the box of voxel
  /// centres through a side (an in-slice axis); infinite when it never does.
  double StepsToSide(int u, int v) const
  {
    double steps = std::numeric_limits<double>::infinity();
    const int axes[2] = { this->U, this->V };
    const int at[2] = { u, v };
    for (int i = 0; i < 2; ++i)
    {
      const double e = this->Step[axes[i]];
      if (e != 0.0)
      {
        const double bound = e > 0.0 ? this->N[axes[i]] - 1 : 0;
        steps = std::min(steps, std::max(0.0, (bound - at[i]) / e));
      }
    }
    return steps;
  }

  /// The four voxels of `slice` around in-slice point (pu, pv) (clamped
  /// into the slice) and their bilinear weights.
  struct Tap
  {
    vtkIdType Index[4];
    double Weight[4];
  };
  Tap SliceTap(int slice, double pu, double pv) const
  {
    const int nu = this->N[this->U];
    const int nv = this->N[this->V];
    pu = std::min(std::max(pu, 0.0), nu - 1.0);
    pv = std::min(std::max(pv, 0.0), nv - 1.0);
    const int u0 = std::min(static_cast<int>(pu), std::max(nu - 2, 0));
    const int v0 = std::min(static_cast<int>(pv), std::max(nv - 2, 0));
    const double fu = pu - u0;
    const double fv = pv - v0;
    const int u1 = std::min(u0 + 1, nu - 1);
    const int v1 = std::min(v0 + 1, nv - 1);
    return Tap{ { this->Index(slice, u0, v0), this->Index(slice, u1, v0),
                  this->Index(slice, u0, v1), this->Index(slice, u1, v1) },
      { (1.0 - fu) * (1.0 - fv), fu * (1.0 - fv), (1.0 - fu) * fv, fu * fv } };
  }
  double ExtinctionAt(const Tap& tap) const
  {
    double sum = 0.0;
    for (int c = 0; c < 4; ++c)
    {
      sum += tap.Weight[c] * CleanExtinction(this->Extinction[tap.Index[c]]);
    }
    return sum;
  }
  double TransmittanceAt(const Tap& tap) const
  {
    double sum = 0.0;
    for (int c = 0; c < 4; ++c)
    {
      sum += tap.Weight[c] * this->T[tap.Index[c]];
    }
    return sum;
  }

  /// A ray that leaves through a side within a few steps, marched to its
  /// exit: interpolating it against the boundary's rays (T = 1) would
  /// smear the sky in across the last slices.
  double MarchToSide(int slice, int u, int v, double steps, int slicesLeft) const
  {
    const int sign = this->Step[this->Axis] > 0.0 ? 1 : -1;
    double depth = 0.0;
    double before = CleanExtinction(this->Extinction[this->Index(slice, u, v)]);
    for (int k = 0; k < slicesLeft && k < steps; ++k)
    {
      const double part = std::min(1.0, steps - k);
      const int next = slice + (k + 1) * sign;
      const double after = this->ExtinctionAt(
        this->SliceTap(next, u + (k + 1) * this->Step[this->U], v + (k + 1) * this->Step[this->V]));
      // A part step ends inside the cell: the extinction there by the trapezoid's line.
      const double end = before + part * (after - before);
      depth += 0.5 * (before + end) * part * this->Length;
      before = after;
    }
    return std::exp(-depth);
  }

  /// `slicesLeft`: slices from `slice` to the one nearest the sky.
  void Row(int slice, int previous, int slicesLeft, int v) const
  {
    const int nu = this->N[this->U];
    for (int u = 0; u < nu; ++u)
    {
      const vtkIdType x = this->Index(slice, u, v);
      const double sigma = CleanExtinction(this->Extinction[x]);
      const double steps = this->StepsToSide(u, v);
      if (steps < MarchedSideSteps)
      {
        this->T[x] = static_cast<float>(this->MarchToSide(slice, u, v, steps, slicesLeft));
        continue;
      }
      // Far from the sides, the point one step toward the sky lies in the
      // previous slice.
      const Tap tap = this->SliceTap(previous, u + this->Step[this->U], v + this->Step[this->V]);
      const double t = this->TransmittanceAt(tap);
      const double s = this->ExtinctionAt(tap);
      this->T[x] = static_cast<float>(t * std::exp(-0.5 * (sigma + s) * this->Length));
    }
  }
};

} // namespace

double ValidEnvironmentLighting(double strength, std::string* why)
{
  if (std::isfinite(strength) && strength >= 0.0 && strength <= MaxEnvironmentLighting)
  {
    return strength;
  }
  const bool high = std::isfinite(strength) && strength > MaxEnvironmentLighting;
  if (why)
  {
    *why = "EnvironmentLighting " + std::to_string(strength) +
      (high ? " is above the largest strength; using " + std::to_string(MaxEnvironmentLighting)
            : " must be finite and >= 0; the sky is off");
  }
  return high ? MaxEnvironmentLighting : 0.0;
}

std::vector<glm::dvec3> SkyDirections(int count)
{
  const int half = std::max(1, (count + 1) / 2);
  std::vector<glm::dvec3> directions(2 * half);
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < half; ++i)
  {
    // The first `half` points of a Fibonacci set of 2 * half on the sphere:
    // z = 1 - (2 i + 1) / (2 half) stays above 0.
    const double z = 1.0 - (2.0 * i + 1.0) / (2.0 * half);
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double phi = golden * i;
    directions[i] = glm::dvec3(r * std::cos(phi), r * std::sin(phi), z);
    directions[half + i] = -directions[i];
  }
  return directions;
}

IrradianceGrid CoarsenIrradianceGrid(const IrradianceGrid& fine, int stride)
{
  IrradianceGrid coarse = fine;
  const int s = std::max(1, stride);
  for (int a = 0; a < 3; ++a)
  {
    const int n = fine.Dimensions[a];
    const int m = n > 1 ? (n - 1 + s - 1) / s + 1 : n;
    coarse.Dimensions[a] = m;
    if (n > 1 && m > 1)
    {
      const double ratio = static_cast<double>(n - 1) / (m - 1);
      coarse.Spacing[a] = fine.Spacing[a] * ratio;
      coarse.DataVoxelsPerVoxel[a] = fine.DataVoxelsPerVoxel[a] * ratio;
    }
  }
  return coarse;
}

void AverageOntoGrid(const IrradianceGrid& fine, const float* values, const IrradianceGrid& coarse,
  std::vector<float>& out, const std::vector<float>* table)
{
  const int* n = fine.Dimensions;
  const int* m = coarse.Dimensions;
  out.assign(static_cast<size_t>(coarse.GetNumberOfVoxels()), 0.0f);
  if (fine.GetNumberOfVoxels() == 0 || (table && table->size() < 2))
  {
    return;
  }
  const std::vector<int> mx = NearestCoarse(n[0], m[0]);
  const std::vector<int> my = NearestCoarse(n[1], m[1]);
  const std::vector<int> mz = NearestCoarse(n[2], m[2]);
  // Each coarse z-slice sums its own fine slices: no two threads write one voxel.
  mmv::For(0, m[2],
    [&](vtkIdType first, vtkIdType last)
    {
      const size_t slice = static_cast<size_t>(m[0]) * m[1];
      std::vector<double> sum(slice);
      std::vector<int> count(slice);
      for (vtkIdType cz = first; cz < last; ++cz)
      {
        std::fill(sum.begin(), sum.end(), 0.0);
        std::fill(count.begin(), count.end(), 0);
        const int z0 = static_cast<int>(std::lower_bound(mz.begin(), mz.end(), cz) - mz.begin());
        const int z1 = static_cast<int>(std::upper_bound(mz.begin(), mz.end(), cz) - mz.begin());
        for (int z = z0; z < z1; ++z)
        {
          for (int y = 0; y < n[1]; ++y)
          {
            const float* row = values + (static_cast<size_t>(z) * n[1] + y) * n[0];
            const size_t base = static_cast<size_t>(my[y]) * m[0];
            for (int x = 0; x < n[0]; ++x)
            {
              sum[base + mx[x]] += table ? LookupTable(*table, row[x]) : row[x];
              ++count[base + mx[x]];
            }
          }
        }
        float* target = out.data() + cz * slice;
        for (size_t i = 0; i < slice; ++i)
        {
          target[i] = count[i] ? static_cast<float>(sum[i] / count[i]) : 0.0f;
        }
      }
    });
}

namespace
{
/// The sweep of SweepSkyTransmittance, its rows in parallel or not (a
/// sweep per thread: many small parallel loops cost more than they gain).
void Sweep(const IrradianceGrid& grid, const float* extinction, const glm::dvec3& direction,
  std::vector<float>& transmittance, bool parallelRows)
{
  transmittance.assign(static_cast<size_t>(grid.GetNumberOfVoxels()), 1.0f);
  const glm::dvec3 d = grid.PhysicalToIndexMatrix() * direction;
  int axis = 0;
  for (int a = 1; a < 3; ++a)
  {
    axis = std::abs(d[a]) > std::abs(d[axis]) ? a : axis;
  }
  if (!(std::abs(d[axis]) > 0.0) || transmittance.empty())
  {
    return;
  }
  SliceSweep sweep;
  sweep.N = grid.Dimensions;
  sweep.Axis = axis;
  sweep.U = (axis + 1) % 3;
  sweep.V = (axis + 2) % 3;
  sweep.Step = d / std::abs(d[axis]);
  sweep.Length = glm::length(grid.IndexToPhysicalMatrix() * sweep.Step);
  sweep.Extinction = extinction;
  sweep.T = transmittance.data();
  const int slices = grid.Dimensions[axis];
  const int sign = sweep.Step[axis] > 0.0 ? 1 : -1;
  // The slice nearest the sky keeps T = 1; each later one reads the one before.
  for (int depth = 1; depth < slices; ++depth)
  {
    const int slice = sign > 0 ? slices - 1 - depth : depth;
    auto rows = [&](vtkIdType first, vtkIdType last)
    {
      for (vtkIdType v = first; v < last; ++v)
      {
        sweep.Row(slice, slice + sign, depth, static_cast<int>(v));
      }
    };
    if (parallelRows)
    {
      mmv::For(0, grid.Dimensions[sweep.V], rows);
    }
    else
    {
      rows(0, grid.Dimensions[sweep.V]);
    }
  }
}
}

void SweepSkyTransmittance(const IrradianceGrid& grid, const float* extinction,
  const glm::dvec3& direction, std::vector<float>& transmittance)
{
  Sweep(grid, extinction, direction, transmittance, true);
}

void ComputeSkyVisibility(const IrradianceGrid& grid, const float* extinction,
  const std::vector<glm::dvec3>& directions, std::vector<float>& moments)
{
  const vtkIdType voxels = grid.GetNumberOfVoxels();
  moments.assign(static_cast<size_t>(voxels) * SkyMomentsPerVoxel, 0.0f);
  if (directions.empty())
  {
    return;
  }
  const double weight = 4.0 * M_PI / static_cast<double>(directions.size());
  // Directions in blocks, one sweep per thread, then summed in the
  // directions' order: the same moments for any thread count or block. A
  // block holds as many transmittances as about 32 MB allow (every
  // direction of the sky's own grid: a core each on a large machine), and
  // at least 8.
  const size_t count = directions.size();
  const size_t perBuffer = static_cast<size_t>(voxels) * sizeof(float);
  const size_t Block = std::max<size_t>(8, (size_t(32) << 20) / std::max<size_t>(1, perBuffer));
  std::vector<std::vector<float>> t(std::min(Block, count));
  for (size_t first = 0; first < count; first += Block)
  {
    const size_t n = std::min(Block, count - first);
    mmv::For(0, static_cast<vtkIdType>(n),
      [&](vtkIdType b0, vtkIdType b1)
      {
        for (vtkIdType b = b0; b < b1; ++b)
        {
          Sweep(grid, extinction, directions[first + b], t[b], false);
        }
      });
    mmv::For(0, voxels,
      [&](vtkIdType v0, vtkIdType v1)
      {
        for (vtkIdType i = v0; i < v1; ++i)
        {
          float* m = moments.data() + i * SkyMomentsPerVoxel;
          for (size_t b = 0; b < n; ++b)
          {
            const glm::dvec3& w = directions[first + b];
            const double wt = weight * t[b][i];
            m[0] += static_cast<float>(wt);
            m[1] += static_cast<float>(wt * w.x);
            m[2] += static_cast<float>(wt * w.y);
            m[3] += static_cast<float>(wt * w.z);
          }
        }
      });
  }
}

void DiffuseSkyMoments(const int dims[3], const double spacing[3], const float* strength,
  std::vector<float>& moments, const DiffusionSettings& settings)
{
  const size_t voxels = moments.size() / SkyMomentsPerVoxel;
  std::vector<float> channel(voxels);
  for (int c = 0; c < SkyMomentsPerVoxel; ++c)
  {
    for (size_t v = 0; v < voxels; ++v)
    {
      channel[v] = moments[v * SkyMomentsPerVoxel + c];
    }
    DiffuseIrradiance(dims, spacing, strength, channel.data(), settings);
    for (size_t v = 0; v < voxels; ++v)
    {
      moments[v * SkyMomentsPerVoxel + c] = channel[v];
    }
  }
}

} // namespace mmv
