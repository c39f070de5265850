#include "vtkMultiMaterialFieldSettings.h"

#include "vtkColorTransferFunction.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMultiMaterialVolumeMapper.h"
#include "vtkPiecewiseFunction.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <sstream>

void vtkMultiMaterialFieldSettings::Apply(
  vtkMultiMaterialVolumeMapper* mapper, vtkVolumeProperty* property, vtkObject* reporter)
{
  std::ostringstream problem;
  const size_t complete = std::min({ this->Arrays.size(), this->Colors.size(),
    this->Opacities.size(), static_cast<size_t>(MaxFurtherFields) });
  if (this->Arrays.size() > static_cast<size_t>(MaxFurtherFields))
  {
    problem << this->Arrays.size() << " field arrays: at most " << MaxFurtherFields
            << " can be shaded besides the coloured array; the first " << MaxFurtherFields
            << " are. ";
  }
  if (complete < std::min(this->Arrays.size(), static_cast<size_t>(MaxFurtherFields)))
  {
    problem << "field arrays without a colour map and an opacity function (FieldLookupTables, "
               "FieldScalarOpacityFunctions) are not drawn. ";
  }
  std::vector<std::string> names;
  for (size_t f = 0; f < complete; ++f)
  {
    if (this->Arrays[f].empty() || !this->Colors[f] || !this->Opacities[f])
    {
      problem << "field " << f + 1 << " needs an array name, a colour map and an opacity "
              << "function; the fields from it on are not drawn. ";
      break;
    }
    names.push_back(this->Arrays[f]);
  }
  this->Drawn = static_cast<int>(names.size());
  for (int f = 0; f < this->Drawn; ++f)
  {
    const int component = f + 1;
    property->SetColor(component, this->Colors[f]);
    property->SetScalarOpacity(component, this->Opacities[f]);
    property->SetScalarOpacityUnitDistance(component, property->GetScalarOpacityUnitDistance(0));

    const std::string preset = f < static_cast<int>(this->Presets.size()) ? this->Presets[f] : "";
    double range[2];
    this->Colors[f]->GetRange(range);
    if (!(range[1] > range[0]))
    {
      range[1] = range[0] + 1.0;
    }
    vtkSmartPointer<vtkMaterialTransferFunction>& materials = this->Materials[f];
    if (!materials)
    {
      materials = vtkSmartPointer<vtkMaterialTransferFunction>::New();
    }
    if (preset != this->MaterialPresets[f] || range[0] != this->MaterialRanges[f][0] ||
      range[1] != this->MaterialRanges[f][1])
    {
      materials->RemoveAllNodes();
      if (!preset.empty() && preset != "Custom" &&
        !materials->ApplyPreset(preset.c_str(), range[0], range[1]))
      {
        problem << "field " << f + 1 << ": unknown material preset '" << preset
                << "'; the default material is used. ";
      }
      this->MaterialPresets[f] = preset;
      this->MaterialRanges[f] = { range[0], range[1] };
    }
    mapper->SetFieldMaterialTransferFunction(component, materials);
  }
  mapper->SetFieldArrays(names);

  const std::string text = problem.str();
  if (!text.empty() && text != this->LastProblem)
  {
    vtkErrorWithObjectMacro(reporter, << text);
  }
  this->LastProblem = text;
}
