/**
 * @class   vtkMultiMaterialFieldSettings
 * @brief   The further fields of the Multi-Material Volume representation:
 *          arrays besides the coloured one, each with its own colour map,
 *          opacity function and material preset.
 *
 * The properties arrive as ParaView pushes repeated properties (cleared,
 * then added one by one); Apply() hands them to the mapper (its FieldArrays
 * and field materials) and to the volume property (component f + 1's
 * colour, opacity and unit distance). Only as many fields as have an
 * array, a colour map and an opacity function are drawn; a preset applies
 * over its field's colour map range ("" or "Custom": the default material).
 */
#ifndef vtkMultiMaterialFieldSettings_h
#define vtkMultiMaterialFieldSettings_h

#include "vtkColorTransferFunction.h"    // vtkSmartPointer
#include "vtkMaterialTransferFunction.h" // vtkSmartPointer
#include "vtkPiecewiseFunction.h"        // vtkSmartPointer
#include "vtkSmartPointer.h"

#include <array>
#include <string>
#include <vector>

class vtkMultiMaterialVolumeMapper;
class vtkObject;
class vtkVolumeProperty;

class vtkMultiMaterialFieldSettings
{
public:
  /// Fields besides the coloured one.
  static constexpr int MaxFurtherFields = 3;

  void ClearArrays() { this->Arrays.clear(); }
  void AddArray(const char* name) { this->Arrays.emplace_back(name ? name : ""); }
  void ClearColors() { this->Colors.clear(); }
  void AddColor(vtkColorTransferFunction* colors) { this->Colors.emplace_back(colors); }
  void ClearOpacities() { this->Opacities.clear(); }
  void AddOpacity(vtkPiecewiseFunction* opacity) { this->Opacities.emplace_back(opacity); }
  void ClearPresets() { this->Presets.clear(); }
  void AddPreset(const char* name) { this->Presets.emplace_back(name ? name : ""); }

  /// Configures `mapper` and `property` for the fields; `reporter` names
  /// the problems (vtkErrorWithObjectMacro), reported once until they change.
  void Apply(
    vtkMultiMaterialVolumeMapper* mapper, vtkVolumeProperty* property, vtkObject* reporter);

  /// Fields drawn by the last Apply() besides the coloured one.
  int GetNumberOfFurtherFields() const { return this->Drawn; }

private:
  std::vector<std::string> Arrays;
  std::vector<vtkSmartPointer<vtkColorTransferFunction>> Colors;
  std::vector<vtkSmartPointer<vtkPiecewiseFunction>> Opacities;
  std::vector<std::string> Presets;

  // Each field's materials, and the preset and range they were made for.
  std::array<vtkSmartPointer<vtkMaterialTransferFunction>, MaxFurtherFields> Materials;
  std::array<std::string, MaxFurtherFields> MaterialPresets;
  std::array<std::array<double, 2>, MaxFurtherFields> MaterialRanges{};
  int Drawn = 0;
  std::string LastProblem;
};

#endif
