// The CPU stages of the lighting (pre-filter, gradient, classification, the
// error probe's comparison) are vtkSMPTools loops. Some VTK builds, Debian's
// ParaView among them, default to the Sequential backend, which runs them on
// one core; mmv::RunOnAllCores runs them with VTK's STDThread backend then,
// unless the user chose a backend (VTK_SMP_BACKEND_IN_USE), whose choice
// stands. VTK_SMP_MAX_THREADS still bounds the threads.
#ifndef vtkMultiMaterialThreads_h
#define vtkMultiMaterialThreads_h

#include "vtkSMPTools.h"

#include <cstdlib>
#include <cstring>

namespace mmv
{
/// Whether RunOnAllCores switches to VTK's STDThread backend here.
inline bool ThreadsAddedToSequentialVTK()
{
  return !std::getenv("VTK_SMP_BACKEND_IN_USE") &&
    std::strcmp(vtkSMPTools::GetBackend(), "Sequential") == 0;
}

/// Calls `work`, whose vtkSMPTools loops use every core even where VTK's
/// default backend is Sequential. Not for work that runs inside another
/// vtkSMPTools loop.
template <typename Work>
void RunOnAllCores(Work&& work)
{
  if (ThreadsAddedToSequentialVTK())
  {
    vtkSMPTools::LocalScope(vtkSMPTools::Config(std::string("STDThread")), work);
  }
  else
  {
    work();
  }
}
}

#endif
