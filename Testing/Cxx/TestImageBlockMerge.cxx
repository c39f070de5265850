// Image blocks merged into one image (mmv::MergeImageBlocks): what readers
// and filters hand over as multiblock or partitioned image data, on the way
// to the ray caster and the MPI exchange.
#include "vtkImageBlockMerge.h"

#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <gtest/gtest.h>

#include <string>

namespace
{
// The value every block stores at lattice point (i, j, k) (global indices).
float Value(int i, int j, int k)
{
  return static_cast<float>(i + 100 * j + 10000 * k);
}

// A block of the lattice with origin (1, 2, 3) and spacing (0.5, 1, 2),
// covering global point indices `global`, described with its own origin
// moved by `originShift` lattice steps (extents shifted back), as readers
// write blocks either way.
vtkSmartPointer<vtkImageData> Block(const int global[6], const int originShift[3] = nullptr)
{
  const double spacing[3] = { 0.5, 1.0, 2.0 };
  const int shift[3] = { originShift ? originShift[0] : 0, originShift ? originShift[1] : 0,
    originShift ? originShift[2] : 0 };
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetSpacing(spacing);
  image->SetOrigin(
    1.0 + shift[0] * spacing[0], 2.0 + shift[1] * spacing[1], 3.0 + shift[2] * spacing[2]);
  image->SetExtent(global[0] - shift[0], global[1] - shift[0], global[2] - shift[1],
    global[3] - shift[1], global[4] - shift[2], global[5] - shift[2]);
  vtkNew<vtkFloatArray> values;
  values->SetName("density");
  vtkNew<vtkIntArray> labels;
  labels->SetName("label");
  values->SetNumberOfTuples(image->GetNumberOfPoints());
  labels->SetNumberOfTuples(image->GetNumberOfPoints());
  vtkIdType id = 0;
  for (int k = global[4]; k <= global[5]; ++k)
  {
    for (int j = global[2]; j <= global[3]; ++j)
    {
      for (int i = global[0]; i <= global[1]; ++i)
      {
        values->SetValue(id, Value(i, j, k));
        labels->SetValue(id, i + j + k);
        ++id;
      }
    }
  }
  image->GetPointData()->AddArray(labels);
  image->GetPointData()->SetScalars(values);
  return image;
}

// Every point of `image` holds Value() of its lattice indices.
void ExpectLattice(vtkImageData* image, const int whole[6])
{
  int extent[6];
  image->GetExtent(extent);
  double world[3];
  for (int a = 0; a < 6; ++a)
  {
    ASSERT_EQ(extent[a], whole[a]) << a;
  }
  vtkDataArray* values = image->GetPointData()->GetScalars();
  ASSERT_NE(values, nullptr);
  EXPECT_STREQ(values->GetName(), "density");
  ASSERT_NE(image->GetPointData()->GetArray("label"), nullptr);
  vtkIdType id = 0;
  for (int k = extent[4]; k <= extent[5]; ++k)
  {
    for (int j = extent[2]; j <= extent[3]; ++j)
    {
      for (int i = extent[0]; i <= extent[1]; ++i, ++id)
      {
        ASSERT_EQ(values->GetTuple1(id), Value(i, j, k)) << i << " " << j << " " << k;
        ASSERT_EQ(image->GetPointData()->GetArray("label")->GetTuple1(id), i + j + k);
      }
    }
  }
  // The lattice itself: point (0, 0, 0) at the shared origin.
  image->TransformIndexToPhysicalPoint(0, 0, 0, world);
  EXPECT_DOUBLE_EQ(world[0], 1.0);
  EXPECT_DOUBLE_EQ(world[1], 2.0);
  EXPECT_DOUBLE_EQ(world[2], 3.0);
}
}

TEST(ImageBlockMerge, PartitionsSharingFacesMergeIntoTheirBox)
{
  // Four partitions of [0, 9] x [0, 5] x [2, 8], split along x and z with
  // shared faces (as ParaView's pieces), two described with moved origins.
  const int a[6] = { 0, 4, 0, 5, 2, 5 };
  const int b[6] = { 4, 9, 0, 5, 2, 5 };
  const int c[6] = { 0, 4, 0, 5, 5, 8 };
  const int d[6] = { 4, 9, 0, 5, 5, 8 };
  const int moved[3] = { 4, 0, 5 };
  vtkNew<vtkPartitionedDataSet> partitions;
  partitions->SetPartition(0, Block(a));
  partitions->SetPartition(1, Block(b, moved));
  partitions->SetPartition(2, Block(c));
  partitions->SetPartition(3, Block(d, moved));
  std::string error;
  vtkSmartPointer<vtkImageData> merged = mmv::MergeImageBlocks(partitions, error);
  ASSERT_NE(merged, nullptr) << error;
  EXPECT_TRUE(error.empty());
  const int whole[6] = { 0, 9, 0, 5, 2, 8 };
  ExpectLattice(merged, whole);
}

TEST(ImageBlockMerge, NestedMultiblockWithEmptyBlocksMerges)
{
  const int a[6] = { 0, 9, 0, 2, 0, 3 };
  const int b[6] = { 0, 9, 3, 5, 0, 3 };
  vtkNew<vtkMultiBlockDataSet> inner;
  inner->SetBlock(0, Block(b));
  inner->SetBlock(1, vtkNew<vtkImageData>()); // empty: skipped
  vtkNew<vtkMultiBlockDataSet> outer;
  outer->SetBlock(0, Block(a));
  outer->SetBlock(1, inner);
  outer->SetBlock(2, nullptr);
  std::string error;
  vtkSmartPointer<vtkImageData> merged = mmv::MergeImageBlocks(outer, error);
  ASSERT_NE(merged, nullptr) << error;
  const int whole[6] = { 0, 9, 0, 5, 0, 3 };
  ExpectLattice(merged, whole);
}

TEST(ImageBlockMerge, NoBlocksGiveAnEmptyImage)
{
  // A rank without data: an empty image, so it still joins the exchange.
  vtkNew<vtkPartitionedDataSet> none;
  std::string error;
  vtkSmartPointer<vtkImageData> merged = mmv::MergeImageBlocks(none, error);
  ASSERT_NE(merged, nullptr);
  EXPECT_EQ(merged->GetNumberOfPoints(), 0);
  EXPECT_TRUE(error.empty()) << error;
}

TEST(ImageBlockMerge, BlocksThatCannotFormOneImageAreRejectedWithTheReason)
{
  std::string error;
  const int a[6] = { 0, 4, 0, 5, 0, 3 };
  const int farAway[6] = { 6, 9, 0, 5, 0, 3 }; // points x = 5 missing
  {
    vtkNew<vtkPartitionedDataSet> gap;
    gap->SetPartition(0, Block(a));
    gap->SetPartition(1, Block(farAway));
    EXPECT_EQ(mmv::MergeImageBlocks(gap, error), nullptr);
    EXPECT_NE(error.find("uncovered"), std::string::npos) << error;
    EXPECT_NE(error.find("24 of the 240"), std::string::npos) << error;
  }
  {
    vtkNew<vtkPartitionedDataSet> spacing;
    spacing->SetPartition(0, Block(a));
    auto other = Block(farAway);
    other->SetSpacing(0.5, 1.0, 2.5);
    spacing->SetPartition(1, other);
    EXPECT_EQ(mmv::MergeImageBlocks(spacing, error), nullptr);
    EXPECT_NE(error.find("spacing"), std::string::npos) << error;
  }
  {
    vtkNew<vtkPartitionedDataSet> offLattice;
    offLattice->SetPartition(0, Block(a));
    const int next[6] = { 4, 9, 0, 5, 0, 3 };
    auto other = Block(next);
    other->SetOrigin(1.2, 2.0, 3.0); // 0.4 of a step off
    offLattice->SetPartition(1, other);
    EXPECT_EQ(mmv::MergeImageBlocks(offLattice, error), nullptr);
    EXPECT_NE(error.find("lattice steps"), std::string::npos) << error;
  }
  {
    vtkNew<vtkMultiBlockDataSet> mixed;
    mixed->SetBlock(0, Block(a));
    mixed->SetBlock(1, vtkNew<vtkPolyData>());
    EXPECT_EQ(mmv::MergeImageBlocks(mixed, error), nullptr);
    EXPECT_NE(error.find("vtkPolyData"), std::string::npos) << error;
  }
  {
    vtkNew<vtkPartitionedDataSet> unshared;
    unshared->SetPartition(0, Block(a));
    const int next[6] = { 4, 9, 0, 5, 0, 3 };
    auto other = Block(next);
    other->GetPointData()->RemoveArray("density");
    other->GetPointData()->RemoveArray("label");
    vtkNew<vtkFloatArray> different;
    different->SetName("pressure");
    different->SetNumberOfTuples(other->GetNumberOfPoints());
    different->Fill(0.0);
    other->GetPointData()->SetScalars(different);
    unshared->SetPartition(1, other);
    EXPECT_EQ(mmv::MergeImageBlocks(unshared, error), nullptr);
    EXPECT_NE(error.find("share no point array"), std::string::npos) << error;
  }
  EXPECT_EQ(mmv::MergeImageBlocks(Block(a), error), nullptr);
  EXPECT_NE(error.find("not a composite"), std::string::npos) << error;
}
