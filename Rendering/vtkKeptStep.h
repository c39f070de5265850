/**
 * @file   vtkKeptStep.h
 * @brief  What the copies kept of earlier time steps (the irradiance, the
 *         gradient volume) share: whether a step's data can still come
 *         back, and which copies make room for a new one.
 *
 * ParaView's animation cache hands a step back with the very scalar array it
 * was rendered from; an array deleted or modified since can never match a
 * copy again. A copy whose data can come back is never dropped to make room
 * for a new step: a series longer than the budget keeps its first steps, as
 * ParaView's own cache stops at its limit, instead of evicting each step for
 * the next and finding none of them on the next loop.
 */
#ifndef vtkKeptStep_h
#define vtkKeptStep_h

#include "vtkType.h"        // vtkMTimeType
#include "vtkWeakPointer.h" // the array may go away

#include <cstddef>
#include <iterator>
#include <list>

class vtkDataArray;

namespace mmv
{
/// A step's scalar array as it was when a copy was kept for it.
class KeptStepData
{
public:
  KeptStepData() = default;
  KeptStepData(vtkDataArray* scalars, vtkMTimeType time);
  /// `scalars` is this array, unmodified since.
  bool Is(vtkDataArray* scalars) const;
  /// The array still exists and is unmodified since.
  bool CanReturn() const;
  /// The same array at the same modification time.
  bool operator==(const KeptStepData& o) const;

private:
  vtkWeakPointer<vtkDataArray> Scalars;
  vtkMTimeType Time = 0;
};

/// Room for `bytes` more under `budget` among `entries` (each with a
/// `CanReturn()`), which hold `used` bytes: drops the entries whose data cannot come back
/// (`drop(iterator)` releases one and lowers `used`), never another. False:
/// what is left leaves no room.
template <class Entry, class Drop>
bool MakeRoomForStep(
  std::list<Entry>& entries, const size_t& used, size_t bytes, size_t budget, Drop drop)
{
  for (auto entry = entries.begin(); entry != entries.end();)
  {
    const auto next = std::next(entry);
    if (!entry->CanReturn())
    {
      drop(entry);
    }
    entry = next;
  }
  return bytes <= budget && used <= budget - bytes;
}
}

#endif
