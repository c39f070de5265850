// vtkGlobalPrefilteredVolume: pieces of one image, each pre-filtering its
// share, sum to exactly mmv::PrefilterScalars of the whole image; pieces that
// cannot be combined are refused alike on every rank. The MPI exchange itself
// is tested under mpiexec (Testing/Python/TestMultiMaterialMPIShadows.py);
// here the reductions are done by hand, as that exchange does them.
#include "mmvTestGlobalVolume.h"
#include "mmvTestScenes.h"

#include "vtkGlobalPrefilteredVolume.h"
#include "vtkIrradianceGrid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cfloat>
#include <cmath>

namespace
{
float Field(int i, int j, int k)
{
  return static_cast<float>(
    50.0 + 40.0 * std::sin(0.37 * i) * std::cos(0.23 * j) + 3.0 * k + ((i * 7 + j * 3 + k) % 5));
}

// The sub-image of `whole` over `extent` (points shared with the neighbours).
vtkSmartPointer<vtkImageData> Piece(vtkImageData* whole, const int extent[6])
{
  auto piece = vtkSmartPointer<vtkImageData>::New();
  piece->SetOrigin(whole->GetOrigin());
  piece->SetSpacing(whole->GetSpacing());
  piece->SetExtent(const_cast<int*>(extent));
  vtkNew<vtkFloatArray> values;
  values->SetName("values");
  values->SetNumberOfTuples(piece->GetNumberOfPoints());
  vtkIdType id = 0;
  for (int k = extent[4]; k <= extent[5]; ++k)
  {
    for (int j = extent[2]; j <= extent[3]; ++j)
    {
      for (int i = extent[0]; i <= extent[1]; ++i)
      {
        int ijk[3] = { i, j, k };
        values->SetValue(
          id++, whole->GetPointData()->GetScalars()->GetComponent(whole->ComputePointId(ijk), 0));
      }
    }
  }
  piece->GetPointData()->SetScalars(values);
  return piece;
}

// Both reductions by hand over `pieces` (nulls are ranks without data).
bool Combine(const std::vector<vtkSmartPointer<vtkImageData>>& pieces, double scale,
  vtkGlobalPrefilteredVolume* global, vtkIdType maxVoxels = 128 * 128 * 128)
{
  return mmvtest::CombinePieces(pieces, global, 64.0, 1, scale, maxVoxels);
}

// The largest difference between `global`'s values and the whole volume's
// own prefilter on the same grid (-1 when their sizes differ).
double LargestDifferenceFromWhole(vtkImageData* whole, vtkGlobalPrefilteredVolume* global)
{
  int dims[3];
  global->GetIrradianceDimensions(dims);
  const mmv::IrradianceGrid reference = mmv::MakeIrradianceGrid(whole, dims);
  std::vector<float> expected;
  mmv::PrefilterScalars(whole, whole->GetPointData()->GetScalars(), 0, reference, expected);
  if (expected.size() != global->GetValues().size())
  {
    return -1.0;
  }
  double worst = 0.0;
  for (size_t v = 0; v < expected.size(); ++v)
  {
    worst = std::max(worst, std::abs(double(expected[v]) - global->GetValues()[v]));
  }
  return worst;
}
} // namespace

TEST(GlobalPrefilteredVolume, PiecesSumToTheWholeVolumesPrefilter)
{
  auto whole = mmvtest::MakeVolume(29, Field);
  whole->SetOrigin(-3.0, 2.0, 0.5);
  whole->SetSpacing(0.5, 0.5, 0.5);
  // Three pieces along z and two along y, sharing their boundary points, as
  // ParaView's extent translator cuts them, plus a rank with no data.
  std::vector<vtkSmartPointer<vtkImageData>> pieces;
  const int cuts[4] = { 0, 9, 19, 28 };
  for (int z = 0; z < 3; ++z)
  {
    for (int y = 0; y < 2; ++y)
    {
      const int extent[6] = { 0, 28, y == 0 ? 0 : 14, y == 0 ? 14 : 28, cuts[z], cuts[z + 1] };
      pieces.push_back(Piece(whole, extent));
    }
  }
  pieces.push_back(nullptr);
  for (double scale : { 1.0, 0.5, 0.3 })
  {
    vtkNew<vtkGlobalPrefilteredVolume> global;
    ASSERT_TRUE(Combine(pieces, scale, global)) << global->GetLastError();
    int dims[3];
    global->GetIrradianceDimensions(dims);
    EXPECT_EQ(global->GetDataDimensions()[2], 29);
    const mmv::IrradianceGrid reference = mmv::MakeIrradianceGrid(whole, dims);
    const double worst = LargestDifferenceFromWhole(whole, global);
    ASSERT_GE(worst, 0.0) << "grid sizes differ";
    std::cout << "scale " << scale << ": " << dims[0] << "x" << dims[1] << "x" << dims[2]
              << ", largest difference from the whole volume's prefilter " << worst << std::endl;
    EXPECT_LT(worst, 1e-4) << "scale " << scale; // float sums of values up to ~130
    // The grid is the whole volume's, at its first point.
    for (int a = 0; a < 3; ++a)
    {
      EXPECT_NEAR(global->GetGrid().Origin[a], reference.Origin[a], 1e-12);
      EXPECT_NEAR(global->GetGrid().Spacing[a], reference.Spacing[a], 1e-12);
    }
    double range[2];
    whole->GetPointData()->GetScalars()->GetRange(range);
    EXPECT_EQ(global->GetScalarRange()[0], range[0]);
    EXPECT_EQ(global->GetScalarRange()[1], range[1]);
    const glm::dvec3 offset = global->PieceOffset(pieces[5]);
    EXPECT_EQ(offset.x, 0.0);
    EXPECT_EQ(offset.y, 14.0);
    EXPECT_EQ(offset.z, 19.0);
  }
}

// Pieces that overlap by ghost layers (two points here) own the overlap's
// samples twice: the exchanged counts keep every voxel the mean of its
// samples, so the values stay the whole volume's.
TEST(GlobalPrefilteredVolume, PiecesOverlappingByGhostLayersKeepTheWholeVolumesPrefilter)
{
  auto whole = mmvtest::MakeVolume(29, Field);
  std::vector<vtkSmartPointer<vtkImageData>> pieces;
  const int below[6] = { 0, 28, 0, 28, 0, 15 };
  const int above[6] = { 0, 28, 0, 28, 13, 28 };
  pieces.push_back(Piece(whole, below));
  pieces.push_back(Piece(whole, above));
  for (double scale : { 1.0, 0.5 })
  {
    vtkNew<vtkGlobalPrefilteredVolume> global;
    ASSERT_TRUE(Combine(pieces, scale, global)) << global->GetLastError();
    const double worst = LargestDifferenceFromWhole(whole, global);
    ASSERT_GE(worst, 0.0) << "grid sizes differ";
    std::cout << "scale " << scale << ", pieces overlapping by 2 points: largest difference "
              << worst << std::endl;
    EXPECT_LT(worst, 1e-4) << "scale " << scale;
  }
}

TEST(GlobalPrefilteredVolume, ExchangedGridStaysWithinItsBound)
{
  auto whole = mmvtest::MakeVolume(40, Field);
  vtkNew<vtkGlobalPrefilteredVolume> global;
  ASSERT_TRUE(Combine({ whole }, 1.0, global, 1000));
  EXPECT_LE(global->GetNumberOfVoxels(), 1000);
  EXPECT_GE(global->GetNumberOfVoxels(), 500) << "not needlessly coarse";
}

TEST(GlobalPrefilteredVolume, PiecesThatCannotBeCombinedAreRefused)
{
  auto whole = mmvtest::MakeVolume(17, Field);
  const int lower[6] = { 0, 16, 0, 16, 0, 8 };
  const int upper[6] = { 0, 16, 0, 16, 8, 16 };
  auto a = Piece(whole, lower);
  auto b = Piece(whole, upper);
  b->SetSpacing(1.0, 1.0, 2.0);
  vtkNew<vtkGlobalPrefilteredVolume> global;
  EXPECT_FALSE(Combine({ a, b }, 1.0, global));
  EXPECT_FALSE(global->GetValid());
  EXPECT_NE(std::string(global->GetLastError()).find("different"), std::string::npos)
    << global->GetLastError();

  // No rank with data: invalid, and said so.
  EXPECT_FALSE(Combine({ nullptr, nullptr }, 1.0, global));
  EXPECT_EQ(std::string(global->GetLastError()), "no piece has data");

  // Different origins are fine: a piece shifted by whole points.
  auto c = Piece(whole, upper);
  c->SetOrigin(0.0, 0.0, 0.0);
  EXPECT_TRUE(Combine({ a, c }, 1.0, global)) << global->GetLastError();
}
