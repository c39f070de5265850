#include "vtkIrradianceTexels.h"

#include "vtkMultiMaterialThreads.h" // mmv::For

#include <algorithm>
#include <cmath>
#include <vector>

namespace mmv
{
namespace
{

// Along one axis of the irradiance grid: each voxel's light grid texels and
// the upper one's weight, as the upsampling's filtered fetch at its
// clamped coordinate takes them.
struct AxisTexels
{
  std::vector<vtkIdType> Lo;
  std::vector<vtkIdType> Hi;
  std::vector<float> Weight;

  AxisTexels(int voxels, int points, float toLightGrid, vtkIdType stride)
    : Lo(voxels)
    , Hi(voxels)
    , Weight(voxels)
  {
    for (int i = 0; i < voxels; ++i)
    {
      const float q = std::min(
        std::max(static_cast<float>(i) * toLightGrid, 0.0f), static_cast<float>(points - 1));
      const float below = std::floor(q);
      const int lo = static_cast<int>(below);
      this->Lo[i] = lo * stride;
      this->Hi[i] = std::min(lo + 1, points - 1) * stride;
      this->Weight[i] = q - below;
    }
  }
};

class TexelWriter
{
public:
  TexelWriter(const IrradianceTexelInputs& inputs, int channels, unsigned short* texels)
    : In(inputs)
    , Channels(channels)
    , Texels(texels)
  {
    const int* d = inputs.Dimensions;
    this->Stride[0] = 1;
    this->Stride[1] = d[0];
    this->Stride[2] = static_cast<vtkIdType>(d[0]) * d[1];
    if (inputs.StridedMask != 0)
    {
      const int* n = inputs.LightGridDimensions;
      const vtkIdType c = inputs.LightGridChannels;
      const vtkIdType stride[3] = { c, c * n[0], c * n[0] * n[1] };
      for (int a = 0; a < 3; ++a)
      {
        this->Axes.emplace_back(d[a], n[a], inputs.IndexToLightGrid[a], stride[a]);
      }
    }
  }

  void Row(int y, int z, int x0, int x1) const
  {
    const IrradianceTexelInputs& in = this->In;
    const vtkIdType row = y * this->Stride[1] + z * this->Stride[2];
    for (int x = x0; x <= x1; ++x)
    {
      const vtkIdType v = row + x;
      float value[4] = { 0.0f, 0.0f, 0.0f, 0.0f };
      const float voxelClass = in.Classes[v];
      if (voxelClass >= 0.0f)
      {
        this->Value(x, y, z, v, value);
      }
      else
      {
        // Over the set bits only, as the fill pass.
        int count = 0;
        for (int bit = 0, m = EmptyVoxelNeighbors(voxelClass); m != 0; ++bit, m >>= 1)
        {
          if ((m & 1) != 0)
          {
            int ijk[3] = { x, y, z };
            const int step = 2 * (bit & 1) - 1;
            ijk[bit >> 1] += step;
            float neighbor[4];
            this->Value(ijk[0], ijk[1], ijk[2], v + step * this->Stride[bit >> 1], neighbor);
            for (int l = 0; l < in.Lights; ++l)
            {
              value[l] += neighbor[l];
            }
            ++count;
          }
        }
        for (int l = 0; count > 0 && l < in.Lights; ++l)
        {
          value[l] /= static_cast<float>(count);
        }
      }
      unsigned short* texel = this->Texels + v * this->Channels;
      for (int c = 0; c < this->Channels; ++c)
      {
        texel[c] = ToUnorm16(value[c]);
      }
    }
  }

  void GatherRow(int y, int z, int x0, int x1, float* values) const
  {
    const vtkIdType row = y * this->Stride[1] + z * this->Stride[2];
    for (int x = x0; x <= x1; ++x)
    {
      const vtkIdType v = row + x;
      if (this->In.Classes[v] >= 0.0f)
      {
        this->Value(x, y, z, v, values + v * this->Channels);
      }
    }
  }

private:
  // A non-empty voxel's value per light: the light grid's trilinear
  // interpolation for a strided light, else the sweep's.
  void Value(int x, int y, int z, vtkIdType v, float* value) const
  {
    const IrradianceTexelInputs& in = this->In;
    const float* p[8] = {};
    float fx = 0.0f, fy = 0.0f, fz = 0.0f;
    if (in.StridedMask != 0)
    {
      const AxisTexels& ax = this->Axes[0];
      const AxisTexels& ay = this->Axes[1];
      const AxisTexels& az = this->Axes[2];
      const vtkIdType x0 = ax.Lo[x], x1 = ax.Hi[x];
      const vtkIdType y0 = ay.Lo[y], y1 = ay.Hi[y];
      const vtkIdType z0 = az.Lo[z], z1 = az.Hi[z];
      fx = ax.Weight[x];
      fy = ay.Weight[y];
      fz = az.Weight[z];
      const float* g = in.LightGrid;
      p[0] = g + x0 + y0 + z0;
      p[1] = g + x1 + y0 + z0;
      p[2] = g + x0 + y1 + z0;
      p[3] = g + x1 + y1 + z0;
      p[4] = g + x0 + y0 + z1;
      p[5] = g + x1 + y0 + z1;
      p[6] = g + x0 + y1 + z1;
      p[7] = g + x1 + y1 + z1;
    }
    for (int l = 0; l < in.Lights; ++l)
    {
      if ((in.StridedMask & (1 << l)) == 0)
      {
        value[l] = in.Fine[v * in.FineChannels + l];
        continue;
      }
      const float c00 = p[0][l] + fx * (p[1][l] - p[0][l]);
      const float c10 = p[2][l] + fx * (p[3][l] - p[2][l]);
      const float c01 = p[4][l] + fx * (p[5][l] - p[4][l]);
      const float c11 = p[6][l] + fx * (p[7][l] - p[6][l]);
      const float c0 = c00 + fy * (c10 - c00);
      const float c1 = c01 + fy * (c11 - c01);
      value[l] = c0 + fz * (c1 - c0);
    }
  }

  // Clamped, rounded to nearest; NaN gives 0.
  static unsigned short ToUnorm16(float value)
  {
    const float clamped = value > 0.0f ? (value < 1.0f ? value : 1.0f) : 0.0f;
    return static_cast<unsigned short>(clamped * 65535.0f + 0.5f);
  }

  const IrradianceTexelInputs& In;
  const int Channels;
  unsigned short* const Texels;
  vtkIdType Stride[3];
  std::vector<AxisTexels> Axes; // x, y, z; only with strided lights
};

// Row(y, z, first, last) for every row of `box`, on all cores.
template <typename RowFunction>
void ForRows(const IndexBox& box, RowFunction&& row)
{
  const int* b = box.Bounds;
  const int rows = b[3] - b[2] + 1;
  mmv::For(0, static_cast<vtkIdType>(rows) * (b[5] - b[4] + 1), 0,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType r = begin; r < end; ++r)
      {
        row(b[2] + static_cast<int>(r % rows), b[4] + static_cast<int>(r / rows), b[0], b[1]);
      }
    });
}

} // namespace

//------------------------------------------------------------------------------
void WriteIrradianceTexels(
  const IrradianceTexelInputs& inputs, const IndexBox& box, int channels, unsigned short* texels)
{
  if (box.IsEmpty())
  {
    return;
  }
  const TexelWriter writer(inputs, channels, texels);
  ForRows(box, [&](int y, int z, int x0, int x1) { writer.Row(y, z, x0, x1); });
}

//------------------------------------------------------------------------------
void GatherIrradianceValues(
  const IrradianceTexelInputs& inputs, const IndexBox& box, int channels, float* values)
{
  if (box.IsEmpty())
  {
    return;
  }
  const TexelWriter writer(inputs, channels, nullptr);
  ForRows(box, [&](int y, int z, int x0, int x1) { writer.GatherRow(y, z, x0, x1, values); });
}

} // namespace mmv
