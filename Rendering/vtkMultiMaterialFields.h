/**
 * @class   vtkMultiMaterialFields
 * @brief   The fields vtkMultiMaterialVolumeMapper shades: one, or the 2-4
 *          independent components of its scalars, each with its own colour,
 *          opacity (the volume property's, per component) and materials.
 *
 * The ray cast reads every field: its own pre-integrated segment tables and
 * material table (stacked in one texture each, vtkMultiMaterialTextures),
 * and shades each segment by each field's share of its opacity. The
 * lighting reads one field: with one, the data itself; with several, their
 * combined shadow extinction (mmv::CombineFieldExtinction), seen through
 * an identity opacity function and materials whose attenuation is 1 and
 * whose scattering is the fields' mixture. Everything the lighting does
 * (pre-filter, probe, shadows, diffusion) then runs unchanged on that field.
 * The shading normals are the gradient of the sum of the fields' values,
 * each normalised over its range: boundaries of every field, and nothing
 * an opacity edit changes. Plain state owned by the mapper.
 */
#ifndef vtkMultiMaterialFields_h
#define vtkMultiMaterialFields_h

#include "vtkCombinedFieldExtinction.h"   // MaxFields
#include "vtkFloatArray.h"                // vtkNew
#include "vtkMaterialTransferFunction.h"  // vtkNew
#include "vtkMultiMaterialVolumeModule.h" // export macro
#include "vtkNew.h"
#include "vtkSmartPointer.h"
#include "vtkVolumeProperty.h" // vtkNew

#include <array>
#include <string>
#include <vector>

class vtkColorTransferFunction;
class vtkDataArray;
class vtkDataSetAttributes;
class vtkPreIntegrationTable;

class VTKMULTIMATERIALVOLUME_EXPORT vtkMultiMaterialFields
{
public:
  vtkMultiMaterialFields();
  ~vtkMultiMaterialFields();

  /// Field f's materials (f in [0, mmv::MaxFields)); field 0's are the
  /// mapper's MaterialTransferFunction.
  void SetMaterials(int field, vtkMaterialTransferFunction* materials);
  vtkMaterialTransferFunction* GetMaterials(int field) const;
  /// The latest modification time of any field's materials.
  vtkMTimeType GetMaterialsMTime() const;

  /**
   * `scalars` with the named arrays of `attributes` as further components
   * (mmv::MakeFieldArray), kept while none of them changes. Null, with
   * `error` set, when they do not fit.
   */
  vtkDataArray* WithArrays(vtkDataArray* scalars, vtkDataSetAttributes* attributes,
    const std::vector<std::string>& names, std::string* error);

  /// Takes the fields of `scalars` (one per component); their ranges are
  /// the components' finite ranges. False for more than mmv::MaxFields.
  bool SetScalars(vtkDataArray* scalars);
  int GetNumberOfFields() const { return this->Count; }
  /// Field f's value range (what its tables span).
  const double* GetRange(int field) const { return this->Ranges[field].data(); }

  /// Builds each field's segment tables (colour, opacity and unit distance of
  /// `property`'s component f) for segments of `step`; false if one fails.
  /// `rebuilt` counts the tables rebuilt, `seconds` adds their build time.
  bool UpdateSegmentTables(vtkVolumeProperty* property, double step, int tableSize,
    int* rebuilt = nullptr, double* seconds = nullptr);
  std::vector<vtkPreIntegrationTable*> GetSegmentTables() const;
  std::vector<vtkMaterialTransferFunction*> GetMaterialsOfFields() const;
  /// Ranges of the fields, two per field.
  std::vector<double> GetRanges() const;
  int GetTableSize() const;

  /// Whether some field's materials have `parameter` non-zero.
  bool AnyNonZero(int parameter) const;
  /// Whether some field's materials reflect / tint their shadows.
  bool AnyReflection() const;
  bool AnyChromaticTransmission() const;

  /**
   * With several fields: recomputes the lighting's field (when the scalars,
   * an opacity or a material changed). `scalars` are the ones SetScalars
   * took, or the same components as cell data. False with `error` set when
   * they cannot be combined.
   */
  bool UpdateLighting(
    vtkDataArray* scalars, vtkVolumeProperty* property, int tableSize, std::string* error);
  /// The lighting's one field: the data (one field) or D (several).
  vtkDataArray* GetLightingScalars(vtkDataArray* scalars) const;
  /// Its value range, opacity and materials.
  const double* GetLightingRange(const double* dataRange) const;
  vtkVolumeProperty* GetLightingProperty(vtkVolumeProperty* property) const;
  vtkMaterialTransferFunction* GetLightingMaterials() const;

  /// What the gradient (the shading normals) is computed of, over its range:
  /// the data (one field) or the sum of the normalised fields (several),
  /// remade when the scalars change.
  vtkDataArray* GetGradientScalars(vtkDataArray* scalars);
  const double* GetGradientRange(const double* dataRange) const;

private:
  vtkMultiMaterialFields(const vtkMultiMaterialFields&) = delete;
  void operator=(const vtkMultiMaterialFields&) = delete;

  vtkColorTransferFunction* ColorOf(vtkVolumeProperty* property, int field);

  int Count = 1;
  std::array<std::array<double, 2>, mmv::MaxFields> Ranges{};
  std::array<vtkSmartPointer<vtkMaterialTransferFunction>, mmv::MaxFields> Materials;
  std::array<vtkSmartPointer<vtkPreIntegrationTable>, mmv::MaxFields> Tables;
  // A grey (one-channel) colour function as RGB, per field.
  std::array<vtkSmartPointer<vtkColorTransferFunction>, mmv::MaxFields> GrayAsColor;
  std::array<vtkMTimeType, mmv::MaxFields> GrayTime{};

  // The lighting's field with several fields, and what it was made of.
  vtkNew<vtkFloatArray> Combined;
  vtkNew<vtkVolumeProperty> CombinedProperty;
  vtkNew<vtkMaterialTransferFunction> CombinedMaterials;
  std::vector<double> CombinedKey;
  vtkNew<vtkFloatArray> Summed;
  std::vector<double> SummedKey;
  double SummedRange[2] = { 0.0, 1.0 };
  std::vector<float> CombinedScattering;

  // The scalars with further arrays as components, and what they were made
  // of (the arrays and their modification times).
  vtkSmartPointer<vtkDataArray> WithArraysArray;
  std::vector<std::pair<vtkDataArray*, vtkMTimeType>> WithArraysFrom;
};

#endif
