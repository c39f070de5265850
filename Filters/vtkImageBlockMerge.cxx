#include "vtkImageBlockMerge.h"

#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataArray.h"
#include "vtkDataSetAttributes.h"
#include "vtkImageData.h"
#include "vtkMatrix3x3.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <sstream>
#include <vector>

namespace mmv
{
namespace
{
bool Near(double a, double b, double tolerance)
{
  return std::abs(a - b) <= tolerance * std::max({ 1.0, std::abs(a), std::abs(b) });
}

// The blocks' common point arrays: those of the first block that every other
// block has with the same type and component count (ghost markers excluded:
// the merged box has no ghosts).
std::vector<std::string> CommonArrays(const std::vector<vtkImageData*>& blocks)
{
  std::vector<std::string> names;
  vtkPointData* first = blocks.front()->GetPointData();
  for (int a = 0; a < first->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* array = first->GetArray(a);
    if (!array || !array->GetName() ||
      std::strcmp(array->GetName(), vtkDataSetAttributes::GhostArrayName()) == 0)
    {
      continue;
    }
    bool everywhere = true;
    for (vtkImageData* block : blocks)
    {
      vtkDataArray* other = block->GetPointData()->GetArray(array->GetName());
      everywhere = everywhere && other && other->GetDataType() == array->GetDataType() &&
        other->GetNumberOfComponents() == array->GetNumberOfComponents();
    }
    if (everywhere)
    {
      names.emplace_back(array->GetName());
    }
  }
  return names;
}

// Copies `from`'s tuples (a block of extent `extent`, shifted by `shift` into
// the merged lattice) into `to` (extent `whole`), a row at a time, and marks
// the rows in `covered` (when given).
void CopyBlock(vtkDataArray* from, const int extent[6], const int shift[3], vtkDataArray* to,
  const int whole[6], std::vector<char>* covered)
{
  const vtkIdType nx = extent[1] - extent[0] + 1;
  const vtkIdType wx = whole[1] - whole[0] + 1;
  const vtkIdType wy = whole[3] - whole[2] + 1;
  const vtkIdType ny = extent[3] - extent[2] + 1;
  const int bytes = from->GetDataTypeSize() * from->GetNumberOfComponents();
  const bool rows = from->HasStandardMemoryLayout() && to->HasStandardMemoryLayout();
  for (int k = extent[4]; k <= extent[5]; ++k)
  {
    for (int j = extent[2]; j <= extent[3]; ++j)
    {
      const vtkIdType source = ((k - extent[4]) * ny + (j - extent[2])) * nx;
      const vtkIdType target = ((k + shift[2] - whole[4]) * wy + (j + shift[1] - whole[2])) * wx +
        (extent[0] + shift[0] - whole[0]);
      if (rows)
      {
        std::memcpy(static_cast<char*>(to->GetVoidPointer(0)) + target * bytes,
          static_cast<const char*>(from->GetVoidPointer(0)) + source * bytes,
          static_cast<size_t>(nx * bytes));
      }
      else
      {
        for (vtkIdType i = 0; i < nx; ++i)
        {
          to->SetTuple(target + i, source + i, from);
        }
      }
      if (covered)
      {
        std::fill(covered->begin() + target, covered->begin() + target + nx, 1);
      }
    }
  }
}

// The image blocks of `composite` that have points, in traversal order;
// the error ("" if none).
std::string CollectBlocks(vtkDataObject* composite, std::vector<vtkImageData*>& blocks)
{
  auto* dataset = vtkCompositeDataSet::SafeDownCast(composite);
  if (!dataset)
  {
    return "the input is not a composite dataset";
  }
  vtkSmartPointer<vtkCompositeDataIterator> it;
  it.TakeReference(dataset->NewIterator());
  for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
  {
    vtkDataObject* leaf = it->GetCurrentDataObject();
    auto* image = vtkImageData::SafeDownCast(leaf);
    if (!image)
    {
      return std::string("a block is a ") + leaf->GetClassName() + ", not image data";
    }
    if (image->GetNumberOfPoints() > 0)
    {
      blocks.push_back(image);
    }
  }
  return "";
}

// Block b's offset from block 0 in whole lattice steps, per index axis; the
// error ("" if none) when its spacing, direction or origin leaves block 0's
// lattice.
std::string LatticeShift(vtkImageData* block, size_t b, const double spacing[3],
  const double origin[3], vtkMatrix3x3* direction, std::array<int, 3>& shift)
{
  const double* s = block->GetSpacing();
  const double* o = block->GetOrigin();
  for (int a = 0; a < 3; ++a)
  {
    if (!Near(s[a], spacing[a], 1e-6))
    {
      std::ostringstream text;
      text << "block " << b << " has spacing (" << s[0] << ", " << s[1] << ", " << s[2]
           << "), block 0 (" << spacing[0] << ", " << spacing[1] << ", " << spacing[2]
           << "): blocks must share one lattice";
      return text.str();
    }
    for (int c = 0; c < 3; ++c)
    {
      if (!Near(block->GetDirectionMatrix()->GetElement(a, c), direction->GetElement(a, c), 1e-6))
      {
        return "block " + std::to_string(b) + " has another direction matrix than block 0";
      }
    }
  }
  // The origin's offset in lattice steps: the direction's columns are the
  // index axes, so the steps are D^T (o - o0) / spacing.
  for (int a = 0; a < 3; ++a)
  {
    double along = 0.0;
    for (int c = 0; c < 3; ++c)
    {
      along += direction->GetElement(c, a) * (o[c] - origin[c]);
    }
    const double steps = along / spacing[a];
    shift[a] = static_cast<int>(std::lround(steps));
    if (std::abs(steps - shift[a]) > 1e-3)
    {
      std::ostringstream text;
      text << "block " << b << "'s origin is " << steps
           << " lattice steps from block 0's along axis " << a << ": blocks must share one lattice";
      return text.str();
    }
  }
  return "";
}
}

vtkSmartPointer<vtkImageData> MergeImageBlocks(vtkDataObject* composite, std::string& error)
{
  std::vector<vtkImageData*> blocks;
  error = CollectBlocks(composite, blocks);
  if (!error.empty())
  {
    return nullptr;
  }
  auto merged = vtkSmartPointer<vtkImageData>::New();
  if (blocks.empty())
  {
    return merged; // no data here: an empty image
  }
  vtkImageData* first = blocks.front();
  double spacing[3];
  double origin[3];
  first->GetSpacing(spacing);
  first->GetOrigin(origin);
  vtkMatrix3x3* direction = first->GetDirectionMatrix();
  int whole[6] = { VTK_INT_MAX, VTK_INT_MIN, VTK_INT_MAX, VTK_INT_MIN, VTK_INT_MAX, VTK_INT_MIN };
  std::vector<std::array<int, 3>> shifts;
  for (size_t b = 0; b < blocks.size(); ++b)
  {
    vtkImageData* block = blocks[b];
    std::array<int, 3> shift{};
    error = LatticeShift(block, b, spacing, origin, direction, shift);
    if (!error.empty())
    {
      return nullptr;
    }
    shifts.push_back(shift);
    const int* extent = block->GetExtent();
    for (int a = 0; a < 3; ++a)
    {
      whole[2 * a] = std::min(whole[2 * a], extent[2 * a] + shift[a]);
      whole[2 * a + 1] = std::max(whole[2 * a + 1], extent[2 * a + 1] + shift[a]);
    }
  }
  const std::vector<std::string> names = CommonArrays(blocks);
  if (names.empty())
  {
    error = "the blocks share no point array";
    return nullptr;
  }
  merged->SetOrigin(origin);
  merged->SetSpacing(spacing);
  merged->SetDirectionMatrix(direction);
  merged->SetExtent(whole);
  const vtkIdType points = merged->GetNumberOfPoints();
  std::vector<char> covered(static_cast<size_t>(points), 0);
  for (const std::string& name : names)
  {
    vtkDataArray* model = first->GetPointData()->GetArray(name.c_str());
    vtkSmartPointer<vtkDataArray> array;
    array.TakeReference(model->NewInstance());
    array->SetName(name.c_str());
    array->SetNumberOfComponents(model->GetNumberOfComponents());
    array->SetNumberOfTuples(points);
    // Every array covers the same points: the first one marks them.
    std::vector<char>* mark = name == names.front() ? &covered : nullptr;
    for (size_t b = 0; b < blocks.size(); ++b)
    {
      CopyBlock(blocks[b]->GetPointData()->GetArray(name.c_str()), blocks[b]->GetExtent(),
        shifts[b].data(), array, whole, mark);
    }
    merged->GetPointData()->AddArray(array);
  }
  const vtkIdType missing = std::count(covered.begin(), covered.end(), 0);
  if (missing > 0)
  {
    std::ostringstream text;
    text << "the " << blocks.size() << " blocks leave " << missing << " of the " << points
         << " points of their bounding extent [" << whole[0] << ", " << whole[1] << "] x ["
         << whole[2] << ", " << whole[3] << "] x [" << whole[4] << ", " << whole[5]
         << "] uncovered: blocks must tile a box";
    error = text.str();
    return nullptr;
  }
  vtkDataArray* scalars = first->GetPointData()->GetScalars();
  if (scalars && scalars->GetName() &&
    std::find(names.begin(), names.end(), scalars->GetName()) != names.end())
  {
    merged->GetPointData()->SetActiveScalars(scalars->GetName());
  }
  return merged;
}

} // namespace mmv
