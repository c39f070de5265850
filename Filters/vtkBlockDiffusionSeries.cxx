#include "vtkBlockDiffusionSeries.h"

#include "vtkMultiMaterialThreads.h"

#include <algorithm>

namespace
{
// c_f x_f, or 0 where the face exchanges nothing (mmvFaceFlux).
inline float FaceFlux(float c, float x)
{
  return c > 0.0f ? c * x : 0.0f;
}

// fn(v, n, xy, z, total) for every block of `box` that exchanges light
// (total = sum of its face coefficients > 0): v its index, n its six face
// neighbours' (clamped at the grid's faces, where the coefficient is 0), xy
// and z its texels. The z slices run in parallel.
template <typename Fn>
void ForExchangingBlocks(
  const int dims[3], const float* facesXY, const float* facesZ, const int box[6], Fn&& fn)
{
  const vtkIdType sy = dims[0];
  const vtkIdType sz = static_cast<vtkIdType>(dims[0]) * dims[1];
  mmv::For(box[4], box[5] + 1, 1,
    [&](vtkIdType kBegin, vtkIdType kEnd)
    {
      for (vtkIdType k = kBegin; k < kEnd; ++k)
      {
        for (int j = box[2]; j <= box[3]; ++j)
        {
          for (int i = box[0]; i <= box[1]; ++i)
          {
            const vtkIdType v = i + j * sy + k * sz;
            const float* xy = facesXY + 4 * v;
            const float* z = facesZ + 4 * v;
            const float total = xy[0] + xy[1] + xy[2] + xy[3] + z[0] + z[1];
            if (!(total > 0.0f))
            {
              continue;
            }
            const vtkIdType n[6] = { i > 0 ? v - 1 : v, i + 1 < dims[0] ? v + 1 : v,
              j > 0 ? v - sy : v, j + 1 < dims[1] ? v + sy : v, k > 0 ? v - sz : v,
              k + 1 < dims[2] ? v + sz : v };
            fn(v, n, xy, z, total);
          }
        }
      }
    });
}

// One Clenshaw step over the blocks of `box` that exchange light; the others
// are left unwritten, as the fragment shader leaves them.
template <int C>
void ClenshawStep(const int dims[3], const float* facesXY, const float* facesZ, const int box[6],
  float alpha, float beta, float gamma, float invRate, const float* u0, const float* current,
  const float* previous, float* next)
{
  ForExchangingBlocks(dims, facesXY, facesZ, box,
    [&](vtkIdType v, const vtkIdType* n, const float* xy, const float* z, float total)
    {
      for (int c = 0; c < C; ++c)
      {
        const float b = current[C * v + c];
        const float neighbours = FaceFlux(xy[0], current[C * n[0] + c]) +
          FaceFlux(xy[1], current[C * n[1] + c]) + FaceFlux(xy[2], current[C * n[2] + c]) +
          FaceFlux(xy[3], current[C * n[3] + c]) + FaceFlux(z[0], current[C * n[4] + c]) +
          FaceFlux(z[1], current[C * n[5] + c]);
        const float applied = b + invRate * (neighbours - total * b) / z[2];
        float result = alpha * u0[C * v + c];
        if (beta != 0.0f)
        {
          result += beta * applied;
        }
        if (gamma != 0.0f)
        {
          result += gamma * previous[C * v + c];
        }
        next[C * v + c] = result;
      }
    });
}

template <int C>
void Series(const int dims[3], const float* facesXY, const float* facesZ, const int box[6],
  const std::vector<double>& coefficients, float invRate, const float* u0,
  std::array<std::vector<float>, 3>& iterates, float* change)
{
  const vtkIdType blocks = static_cast<vtkIdType>(dims[0]) * dims[1] * dims[2];
  // b_n+1 = b_n+2 = 0: their weights are 0 and u0 stands in for them.
  const float* current = u0;
  const float* previous = u0;
  const int n = static_cast<int>(coefficients.size()) - 1;
  for (int k = n; k >= 0; --k)
  {
    float* next = nullptr;
    for (auto& iterate : iterates)
    {
      if (iterate.data() != current && iterate.data() != previous)
      {
        next = iterate.data();
        break;
      }
    }
    ClenshawStep<C>(dims, facesXY, facesZ, box, static_cast<float>(coefficients[k]),
      k == n ? 0.0f : (k == 0 ? 1.0f : 2.0f), k >= n - 1 ? 0.0f : -1.0f, invRate, u0, current,
      previous, next);
    previous = current;
    current = next;
  }
  // MMV_CHANGE: the change where a block exchanges light, 0 elsewhere.
  std::fill(change, change + C * blocks, 0.0f);
  ForExchangingBlocks(dims, facesXY, facesZ, box,
    [&](vtkIdType v, const vtkIdType*, const float*, const float*, float)
    {
      for (int c = 0; c < C; ++c)
      {
        change[C * v + c] = current[C * v + c] - u0[C * v + c];
      }
    });
}
} // namespace

namespace mmv
{

bool BlockDiffusionSeries::Change(const int dims[3], int channels, const float* facesXY,
  const float* facesZ, const int box[6], const std::vector<double>& coefficients, double invRate,
  const float* u0, float* change)
{
  if (channels != 1 && channels != 2 && channels != 4)
  {
    return false;
  }
  const size_t values = static_cast<size_t>(channels) * dims[0] * dims[1] * dims[2];
  if (coefficients.empty() || box[1] < box[0] || box[3] < box[2] || box[5] < box[4])
  {
    std::fill(change, change + values, 0.0f);
    return true;
  }
  for (auto& iterate : this->Iterates)
  {
    iterate.resize(values);
  }
  const float rate = static_cast<float>(invRate);
  mmv::RunOnAllCores(
    [&]()
    {
      switch (channels)
      {
        case 1:
          Series<1>(dims, facesXY, facesZ, box, coefficients, rate, u0, this->Iterates, change);
          break;
        case 2:
          Series<2>(dims, facesXY, facesZ, box, coefficients, rate, u0, this->Iterates, change);
          break;
        default:
          Series<4>(dims, facesXY, facesZ, box, coefficients, rate, u0, this->Iterates, change);
      }
    });
  return true;
}

void BlockDiffusionSeries::ReleaseScratch()
{
  for (auto& iterate : this->Iterates)
  {
    std::vector<float>().swap(iterate);
  }
}

} // namespace mmv
