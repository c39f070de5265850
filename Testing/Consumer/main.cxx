// Links against MultiMaterialVolume::Rendering found by find_package and checks a
// closed-form case: a built-in preset applied to a material transfer function
// evaluates to the preset's parameters anywhere in the range.
#include "vtkMaterialLibrary.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkNew.h"

#include <cmath>
#include <iostream>

int main()
{
  vtkNew<vtkMaterialLibrary> library;
  double preset[vtkMaterialTransferFunction::NumberOfParameters];
  if (!library->GetPreset("bone", preset))
  {
    std::cerr << "no bone preset\n";
    return 1;
  }
  vtkNew<vtkMaterialTransferFunction> materials;
  if (!materials->ApplyPreset("bone", 0.0, 100.0))
  {
    return 1;
  }
  double value[vtkMaterialTransferFunction::NumberOfParameters];
  materials->Evaluate(42.0, value);
  for (int i = 0; i < vtkMaterialTransferFunction::NumberOfParameters; ++i)
  {
    if (std::abs(value[i] - preset[i]) > 1e-12)
    {
      std::cerr << "parameter " << i << ": " << value[i] << " != " << preset[i] << "\n";
      return 1;
    }
  }
  std::cout << "find_package(MultiMaterialVolume) consumer OK (" << library->GetNumberOfPresets()
            << " presets)\n";
  return 0;
}
