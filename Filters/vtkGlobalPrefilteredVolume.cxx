#include "vtkGlobalPrefilteredVolume.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkMatrix3x3.h"
#include "vtkMultiMaterialParameters.h"
#include "vtkMultiMaterialThreads.h" // mmv::For
#include "vtkObjectFactory.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <sstream>

vtkStandardNewMacro(vtkGlobalPrefilteredVolume);

namespace
{
// Summary layout: MIN-reduced, so maxima are stored negated and a piece
// without data gives +DBL_MAX (flags: +1).
enum SummaryIndex
{
  SummaryHasData = 0, // -1: this piece has data
  SummaryFirst = 1,   // 3: first point, in the direction frame
  SummaryNegLast = 4, // 3: -last point
  SummarySpacing = 7, // 3
  SummaryNegSpacing = 10,
  SummaryRangeMin = 13,
  SummaryNegRangeMax = 14,
  SummaryDirection = 15, // 9, row-major
  SummaryNegDirection = 24,
  SummaryMalformed = 33 // -1: data with fewer scalars than points
};

glm::dmat3 DirectionOf(vtkImageData* image)
{
  glm::dmat3 d(1.0);
  const double* m = image->GetDirectionMatrix()->GetData();
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      d[c][r] = m[3 * r + c];
    }
  }
  return d;
}

// The first point of `image` in its direction frame (physical = D * frame).
glm::dvec3 FirstPointInFrame(vtkImageData* image)
{
  const int* e = image->GetExtent();
  double p[3];
  image->TransformContinuousIndexToPhysicalPoint(e[0], e[2], e[4], p);
  return glm::inverse(DirectionOf(image)) * glm::dvec3(p[0], p[1], p[2]);
}

bool HasPoints(vtkImageData* piece, vtkDataArray* scalars)
{
  return piece && scalars && piece->GetNumberOfPoints() > 0;
}
}

vtkGlobalPrefilteredVolume::vtkGlobalPrefilteredVolume() = default;
vtkGlobalPrefilteredVolume::~vtkGlobalPrefilteredVolume() = default;

void vtkGlobalPrefilteredVolume::SummarizePiece(
  vtkImageData* piece, vtkDataArray* scalars, double summary[SummarySize])
{
  std::fill(summary, summary + SummarySize, DBL_MAX);
  summary[SummaryHasData] = 1.0;
  summary[SummaryMalformed] = 1.0;
  if (!HasPoints(piece, scalars))
  {
    return;
  }
  if (scalars->GetNumberOfTuples() < piece->GetNumberOfPoints() ||
    scalars->GetNumberOfComponents() < 1)
  {
    summary[SummaryMalformed] = -1.0;
    return;
  }
  summary[SummaryHasData] = -1.0;
  int dims[3];
  piece->GetDimensions(dims);
  const glm::dvec3 first = FirstPointInFrame(piece);
  const double* spacing = piece->GetSpacing();
  for (int a = 0; a < 3; ++a)
  {
    summary[SummaryFirst + a] = first[a];
    summary[SummaryNegLast + a] = -(first[a] + (dims[a] - 1) * spacing[a]);
    summary[SummarySpacing + a] = spacing[a];
    summary[SummaryNegSpacing + a] = -spacing[a];
  }
  double range[2];
  scalars->GetFiniteRange(range, 0);
  summary[SummaryRangeMin] = range[0];
  summary[SummaryNegRangeMax] = -range[1];
  const double* direction = piece->GetDirectionMatrix()->GetData();
  for (int i = 0; i < 9; ++i)
  {
    summary[SummaryDirection + i] = direction[i];
    summary[SummaryNegDirection + i] = -direction[i];
  }
}

bool vtkGlobalPrefilteredVolume::SetGeometry(const double reduced[SummarySize], double budgetMB,
  int expectedLights, double scale, vtkIdType maxVoxels)
{
  this->Invalidate();
  std::ostringstream error;
  if (reduced[SummaryMalformed] < 0.0)
  {
    error << "a piece has fewer scalars than points";
  }
  else if (reduced[SummaryHasData] > 0.0)
  {
    error << "no piece has data";
  }
  for (int a = 0; a < 3 && error.str().empty(); ++a)
  {
    const double lo = reduced[SummarySpacing + a];
    const double hi = -reduced[SummaryNegSpacing + a];
    if (!(lo > 0.0) || hi - lo > 1e-6 * hi)
    {
      error << "the pieces have different (or non-positive) spacings along axis " << a << ": " << lo
            << " to " << hi;
    }
  }
  for (int i = 0; i < 9 && error.str().empty(); ++i)
  {
    if (-reduced[SummaryNegDirection + i] - reduced[SummaryDirection + i] > 1e-9)
    {
      error << "the pieces have different direction matrices";
    }
  }
  if (!error.str().empty())
  {
    this->LastError = error.str();
    return false;
  }

  double direction[9];
  std::copy(reduced + SummaryDirection, reduced + SummaryDirection + 9, direction);
  for (int a = 0; a < 3; ++a)
  {
    this->Spacing[a] = reduced[SummarySpacing + a];
    this->FirstPoint[a] = reduced[SummaryFirst + a];
    const double length = -reduced[SummaryNegLast + a] - reduced[SummaryFirst + a];
    this->DataDimensions[a] = static_cast<int>(std::lround(length / this->Spacing[a])) + 1;
  }
  this->ScalarRange[0] = reduced[SummaryRangeMin];
  this->ScalarRange[1] = -reduced[SummaryNegRangeMax];
  if (!(this->ScalarRange[1] > this->ScalarRange[0]))
  {
    this->ScalarRange[1] = this->ScalarRange[0] + 1.0; // constant volume
  }

  int dims[3];
  mmv::ComputeIrradianceDimensions(this->DataDimensions, expectedLights, budgetMB, scale, dims);
  if (static_cast<double>(dims[0]) * dims[1] * dims[2] > static_cast<double>(maxVoxels))
  {
    const double capMB =
      static_cast<double>(maxVoxels) * mmv::IrradianceBytesPerVoxelPerLight / (1024.0 * 1024.0);
    mmv::ComputeIrradianceDimensions(this->DataDimensions, 1, capMB, 0.0, dims);
  }
  const int extent[6] = { 0, this->DataDimensions[0] - 1, 0, this->DataDimensions[1] - 1, 0,
    this->DataDimensions[2] - 1 };
  glm::dmat3 d(1.0);
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      d[c][r] = direction[3 * r + c];
    }
  }
  const glm::dvec3 origin = d * this->FirstPoint;
  const double o[3] = { origin.x, origin.y, origin.z };
  const double spacing[3] = { this->Spacing.x, this->Spacing.y, this->Spacing.z };
  this->Grid = mmv::MakeIrradianceGrid(extent, o, spacing, direction, dims);
  this->Values.clear();
  this->LastError.clear();
  return true;
}

glm::dvec3 vtkGlobalPrefilteredVolume::PieceOffset(vtkImageData* piece) const
{
  glm::dvec3 offset = (FirstPointInFrame(piece) - this->FirstPoint) / this->Spacing;
  for (int a = 0; a < 3; ++a)
  {
    // Pieces of one image sit on whole points; keep rounding noise out of the
    // ownership tests below.
    const double nearest = std::round(offset[a]);
    offset[a] = std::abs(offset[a] - nearest) < 1e-6 ? nearest : offset[a];
  }
  return offset;
}

void vtkGlobalPrefilteredVolume::AccumulatePiece(
  vtkImageData* piece, vtkDataArray* scalars, std::vector<float>& sums) const
{
  const vtkIdType voxels = this->Grid.GetNumberOfVoxels();
  sums.assign(2 * voxels, 0.0f);
  if (!HasPoints(piece, scalars) || scalars->GetNumberOfTuples() < piece->GetNumberOfPoints() ||
    voxels == 0)
  {
    return;
  }
  mmv::IrradianceGrid pieceGrid; // only its dimensions matter to SampleTrilinear
  piece->GetDimensions(pieceGrid.Dimensions);
  const int* n = pieceGrid.Dimensions;
  const int* whole = this->DataDimensions;
  const glm::dvec3 o = this->PieceOffset(piece);
  const mmv::FootprintLayout layout = mmv::MakeFootprintLayout(whole, this->Grid.Dimensions);
  const std::vector<float> values = mmv::CopyComponent(scalars, 0);
  // A sample belongs to the piece whose points [o, o + n - 1] hold it; on a
  // shared face it belongs to the piece above, except on the volume's last
  // face.
  auto owns = [&](const glm::dvec3& p)
  {
    for (int a = 0; a < 3; ++a)
    {
      const double last = o[a] + n[a] - 1;
      if (p[a] < o[a] || p[a] > last || (p[a] == last && last < whole[a] - 1 && n[a] > 1))
      {
        return false;
      }
    }
    return true;
  };
  const int* samples = layout.Samples;
  mmv::For(0, voxels,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType v = begin; v < end; ++v)
      {
        const glm::dvec3 voxel = this->Grid.IndexOfVoxel(v);
        bool near = true;
        for (int a = 0; a < 3; ++a)
        {
          const double centre = voxel[a] * layout.Ratio[a];
          near =
            near && centre + layout.Ratio[a] >= o[a] && centre - layout.Ratio[a] <= o[a] + n[a] - 1;
        }
        if (!near)
        {
          continue;
        }
        double sum = 0.0;
        int count = 0;
        for (int k = 0; k < samples[2]; ++k)
        {
          for (int j = 0; j < samples[1]; ++j)
          {
            for (int i = 0; i < samples[0]; ++i)
            {
              const int q[3] = { i, j, k };
              glm::dvec3 p = mmv::FootprintSample(layout, voxel, q);
              for (int a = 0; a < 3; ++a)
              {
                p[a] = std::min(std::max(p[a], 0.0), static_cast<double>(whole[a] - 1));
              }
              if (owns(p))
              {
                sum += mmv::SampleTrilinear(pieceGrid, values.data(), p - o);
                ++count;
              }
            }
          }
        }
        sums[v] = static_cast<float>(sum);
        sums[voxels + v] = static_cast<float>(count);
      }
    });
}

void vtkGlobalPrefilteredVolume::SetReducedSums(const std::vector<float>& sums)
{
  const vtkIdType voxels = this->Grid.GetNumberOfVoxels();
  if (voxels == 0 || static_cast<vtkIdType>(sums.size()) != 2 * voxels)
  {
    this->Invalidate();
    return;
  }
  this->Values.resize(voxels);
  for (vtkIdType v = 0; v < voxels; ++v)
  {
    const float count = sums[voxels + v];
    this->Values[v] = count > 0.0f ? sums[v] / count : 0.0f;
  }
  this->Valid = true;
  this->Modified();
}

void vtkGlobalPrefilteredVolume::Invalidate()
{
  if (this->Valid)
  {
    this->Valid = false;
    this->Modified();
  }
}

vtkIdType vtkGlobalPrefilteredVolume::GetNumberOfVoxels() const
{
  return this->Grid.GetNumberOfVoxels();
}

void vtkGlobalPrefilteredVolume::GetIrradianceDimensions(int dims[3]) const
{
  std::copy(this->Grid.Dimensions, this->Grid.Dimensions + 3, dims);
}

void vtkGlobalPrefilteredVolume::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Valid: " << this->Valid << "\n";
  os << indent << "DataDimensions: " << this->DataDimensions[0] << " " << this->DataDimensions[1]
     << " " << this->DataDimensions[2] << "\n";
  os << indent << "IrradianceDimensions: " << this->Grid.Dimensions[0] << " "
     << this->Grid.Dimensions[1] << " " << this->Grid.Dimensions[2] << "\n";
  os << indent << "ScalarRange: " << this->ScalarRange[0] << " " << this->ScalarRange[1] << "\n";
  os << indent << "BytesExchanged: " << this->BytesExchanged << "\n";
  os << indent << "LastError: " << this->LastError << "\n";
}
