// libFuzzer target: vtkMaterialTransferFunction::FromJSON and
// vtkMaterialLibrary::AddPresetsFromJSON on arbitrary bytes. Besides crashes
// and sanitizer reports, it checks that whatever is accepted round-trips:
// ToJSON() of the result must parse again to the same nodes/presets.
#include "vtkMaterialLibrary.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkNew.h"
#include "vtkObject.h"

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  static const bool quiet = []
  {
    vtkObject::GlobalWarningDisplayOff(); // rejected input is the common case
    return true;
  }();
  (void)quiet;
  const std::string text(reinterpret_cast<const char*>(data), size);

  vtkNew<vtkMaterialTransferFunction> function;
  if (function->FromJSON(text))
  {
    vtkNew<vtkMaterialTransferFunction> copy;
    if (!copy->FromJSON(function->ToJSON()) || copy->GetSize() != function->GetSize())
    {
      std::abort(); // accepted input must round-trip
    }
    std::vector<double> a(8 * function->GetSize()), b(8 * copy->GetSize());
    function->GetNodes(a.data());
    copy->GetNodes(b.data());
    if (a != b)
    {
      std::abort();
    }
  }

  vtkNew<vtkMaterialLibrary> library;
  const int builtins = library->GetNumberOfPresets();
  if (library->AddPresetsFromJSON(text))
  {
    vtkNew<vtkMaterialLibrary> copy;
    if (!copy->AddPresetsFromJSON(library->ToJSON()) ||
      copy->GetNumberOfPresets() != library->GetNumberOfPresets())
    {
      std::abort();
    }
  }
  else if (library->GetNumberOfPresets() != builtins)
  {
    std::abort(); // rejected input must leave the library unchanged
  }
  return 0;
}
