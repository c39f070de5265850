// The CPU stages of the lighting (pre-filter, gradient, classification, the
// error probe's comparison) are parallel loops. Some VTK builds, Debian's
// ParaView among them, default to the Sequential SMP backend, which runs
// them on one core; mmv::RunOnAllCores runs them on every core then, unless
// the user chose a backend (VTK_SMP_BACKEND_IN_USE), whose choice stands.
// VTK_SMP_MAX_THREADS still bounds the threads.
//
// Inside RunOnAllCores the loops written with mmv::For run on workers that
// stay between loops: VTK 9.2's STDThread backend starts its threads anew
// for every loop, about half a millisecond on 16 cores, and one change of
// the transfer function runs tens of loops. Loops written with
// vtkSMPTools::For (those with thread-local state) get VTK's STDThread
// backend there.
#ifndef vtkMultiMaterialThreads_h
#define vtkMultiMaterialThreads_h

#include "vtkMultiMaterialVolumeFiltersModule.h" // export macro
#include "vtkSMPTools.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <functional>

namespace mmv
{
/// Whether RunOnAllCores adds threads here (VTK's backend is Sequential and
/// the user chose none).
inline bool ThreadsAddedToSequentialVTK()
{
  return !std::getenv("VTK_SMP_BACKEND_IN_USE") &&
    std::strcmp(vtkSMPTools::GetBackend(), "Sequential") == 0;
}

/// The threads mmv::For runs on in this thread: 0 outside RunOnAllCores
/// (or where it adds none), else the number of threads VTK would use.
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT int& AllCoresThreads();

/// job(c) for every chunk c in [0, chunks), on `threads` threads: this one
/// and workers that wait between calls. Calls from several threads at once
/// take turns; a call from inside a job runs its chunks on its own thread.
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT void RunChunks(
  int threads, vtkIdType chunks, const std::function<void(vtkIdType)>& job);

/// Calls `work`, whose loops use every core even where VTK's default
/// backend is Sequential. Not for work that runs inside a parallel loop.
template <typename Work>
void RunOnAllCores(Work&& work)
{
  if (!ThreadsAddedToSequentialVTK())
  {
    work();
    return;
  }
  vtkSMPTools::LocalScope(vtkSMPTools::Config(std::string("STDThread")),
    [&]()
    {
      int& threads = AllCoresThreads();
      const int outer = threads;
      threads = vtkSMPTools::GetEstimatedNumberOfThreads();
      work();
      threads = outer;
    });
}

/// vtkSMPTools::For with the same chunks (`grain` items each; 0: a few per
/// thread), on RunOnAllCores' workers inside it and through vtkSMPTools
/// elsewhere. `functor(begin, end)` must not keep state between chunks.
template <typename Functor>
void For(vtkIdType first, vtkIdType last, vtkIdType grain, Functor&& functor)
{
  const int threads = AllCoresThreads();
  if (threads < 2)
  {
    vtkSMPTools::For(first, last, grain, functor);
    return;
  }
  const vtkIdType n = last - first;
  if (n <= 0)
  {
    return;
  }
  const vtkIdType chunk = grain > 0 ? grain : std::max<vtkIdType>(1, n / (4 * threads));
  if (n <= chunk)
  {
    functor(first, last);
    return;
  }
  RunChunks(threads, (n + chunk - 1) / chunk,
    [&](vtkIdType c)
    {
      const vtkIdType begin = first + c * chunk;
      functor(begin, std::min(last, begin + chunk));
    });
}

template <typename Functor>
void For(vtkIdType first, vtkIdType last, Functor&& functor)
{
  mmv::For(first, last, 0, functor);
}
}

#endif
