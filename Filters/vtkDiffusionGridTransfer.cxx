#include "vtkDiffusionGridTransfer.h"

#include "vtkMultiMaterialThreads.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace mmv
{

void RestrictToDiffusionBlocks(const int dims[3], const float* fine, const float* classes,
  const DiffusionGrid& coarse, int channels, const int blocks[6], float* restricted)
{
  const int* f = coarse.Factor;
  const int* cd = coarse.Dimensions;
  const vtkIdType sy = dims[0];
  const vtkIdType sz = static_cast<vtkIdType>(dims[0]) * dims[1];
  mmv::For(blocks[4], blocks[5] + 1, 1,
    [&](vtkIdType kBegin, vtkIdType kEnd)
    {
      for (vtkIdType ck = kBegin; ck < kEnd; ++ck)
      {
        for (int cj = blocks[2]; cj <= blocks[3]; ++cj)
        {
          for (int ci = blocks[0]; ci <= blocks[1]; ++ci)
          {
            float sum[4] = { 0.0f, 0.0f, 0.0f, 0.0f };
            int count = 0;
            const int last[3] = { std::min((ci + 1) * f[0], dims[0]),
              std::min((cj + 1) * f[1], dims[1]),
              std::min(static_cast<int>(ck + 1) * f[2], dims[2]) };
            for (int k = static_cast<int>(ck) * f[2]; k < last[2]; ++k)
            {
              for (int j = cj * f[1]; j < last[1]; ++j)
              {
                for (int i = ci * f[0]; i < last[0]; ++i)
                {
                  const vtkIdType v = i + j * sy + k * sz;
                  if (classes[v] > 0.0f)
                  {
                    for (int c = 0; c < 4; ++c)
                    {
                      sum[c] += fine[4 * v + c];
                    }
                    ++count;
                  }
                }
              }
            }
            const vtkIdType b = ci + cd[0] * (cj + static_cast<vtkIdType>(cd[1]) * ck);
            for (int c = 0; c < channels; ++c)
            {
              restricted[channels * b + c] = count > 0 ? sum[c] / static_cast<float>(count) : 0.0f;
            }
          }
        }
      }
    });
}

void ProlongDiffusionChange(const int dims[3], const float* fine, const float* classes,
  const DiffusionGrid& coarse, int channels, const float* change, const float* facesZ, int mask,
  const int box[6], float* out)
{
  const int* cd = coarse.Dimensions;
  // Per axis and voxel index: the lower and upper corner blocks' offsets and
  // the upper one's weight (the GPU's linear filtering of the clamped
  // coordinate u).
  struct Corners
  {
    vtkIdType Lower;
    vtkIdType Upper;
    float Weight;
  };
  std::vector<Corners> axes[3];
  const vtkIdType blockStride[3] = { 1, cd[0], static_cast<vtkIdType>(cd[0]) * cd[1] };
  for (int a = 0; a < 3; ++a)
  {
    axes[a].resize(dims[a]);
    const float fa = static_cast<float>(coarse.Factor[a]);
    for (int i = 0; i < dims[a]; ++i)
    {
      const float u = std::min(std::max((static_cast<float>(i) - 0.5f * (fa - 1.0f)) / fa, 0.0f),
        static_cast<float>(cd[a] - 1));
      const int lower = static_cast<int>(std::floor(u));
      axes[a][i] = { lower * blockStride[a], std::min(lower + 1, cd[a] - 1) * blockStride[a],
        u - static_cast<float>(lower) };
    }
  }
  const vtkIdType sy = dims[0];
  const vtkIdType sz = static_cast<vtkIdType>(dims[0]) * dims[1];
  mmv::For(box[4], box[5] + 1, 1,
    [&](vtkIdType kBegin, vtkIdType kEnd)
    {
      for (vtkIdType k = kBegin; k < kEnd; ++k)
      {
        const Corners& z = axes[2][k];
        for (int j = box[2]; j <= box[3]; ++j)
        {
          const Corners& y = axes[1][j];
          for (int i = box[0]; i <= box[1]; ++i)
          {
            const vtkIdType v = i + j * sy + k * sz;
            float value[4] = { fine[4 * v], fine[4 * v + 1], fine[4 * v + 2], fine[4 * v + 3] };
            if (classes[v] > 0.0f)
            {
              const Corners& x = axes[0][i];
              // The corners in the filtering's order (x fastest), their
              // weights products of the axes' as the GPU forms them.
              const vtkIdType blocks[8] = { x.Lower + y.Lower + z.Lower,
                x.Upper + y.Lower + z.Lower, x.Lower + y.Upper + z.Lower,
                x.Upper + y.Upper + z.Lower, x.Lower + y.Lower + z.Upper,
                x.Upper + y.Lower + z.Upper, x.Lower + y.Upper + z.Upper,
                x.Upper + y.Upper + z.Upper };
              float weights = 0.0f;
              float sum[4] = { 0.0f, 0.0f, 0.0f, 0.0f };
              for (int corner = 0; corner < 8; ++corner)
              {
                const float w = ((corner & 1) ? x.Weight : 1.0f - x.Weight) *
                  ((corner & 2) ? y.Weight : 1.0f - y.Weight) *
                  ((corner & 4) ? z.Weight : 1.0f - z.Weight);
                const vtkIdType b = blocks[corner];
                weights += w * facesZ[4 * b + 3];
                for (int c = 0; c < channels; ++c)
                {
                  sum[c] += w * change[channels * b + c];
                }
              }
              if (weights > 0.0f)
              {
                for (int c = 0; c < channels; ++c)
                {
                  value[c] = std::max(value[c] + sum[c] / weights, 0.0f);
                }
              }
            }
            for (int c = 0; c < 4; ++c)
            {
              if ((mask >> c) & 1)
              {
                out[4 * v + c] = value[c];
              }
            }
          }
        }
      }
    });
}

} // namespace mmv
