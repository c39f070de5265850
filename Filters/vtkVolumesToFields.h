/**
 * @class   vtkVolumesToFields
 * @brief   Several overlapping image volumes on one grid, one field each, so
 *          that one ray integrates them all.
 *
 * VTK ray casts each vtkVolume alone and blends the images by drawing order,
 * so where two volumes overlap in space the one drawn second covers the
 * other whatever their depths. The multi-material mapper integrates several
 * fields of one image along one ray (AddFieldArray, with each field's colour,
 * opacity and materials): this filter turns several volumes into that image.
 *
 * Inputs: vtkImageData on the repeatable port 0, at most 4 (the fields one
 * ray shades). Each gives its active point scalars, or its first
 * one-component point array when the active scalars are missing or have
 * several components.
 *
 * Output: the union of the inputs' boxes, sampled with the finest spacing of
 * any input along each axis, origin at the union's lower corner. One float
 * point array per input, named as the input's array (a repeated name gets
 * "_2", "_3", ...), the first one the active scalars. Each input is
 * interpolated trilinearly, so inputs on the output's lattice (same spacing,
 * origins a whole number of steps apart) are copied exactly. Points outside
 * an input's box take that input's lowest value, which a transfer function
 * starting at zero opacity leaves transparent.
 *
 * Errors (vtkErrorMacro, empty output): no input, more than 4, an input with
 * a direction matrix other than identity, one without a one-component point
 * array, or a grid of more than MaximumNumberOfPoints points.
 */
#ifndef vtkVolumesToFields_h
#define vtkVolumesToFields_h

#include "vtkImageAlgorithm.h"
#include "vtkMultiMaterialVolumeFiltersModule.h" // export macro

#include <string> // errors
#include <vector> // the inputs' boxes

class vtkDataArray;
class vtkImageData;

class VTKMULTIMATERIALVOLUMEFILTERS_EXPORT vtkVolumesToFields : public vtkImageAlgorithm
{
public:
  static vtkVolumesToFields* New();
  vtkTypeMacro(vtkVolumesToFields, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The most fields one ray of the multi-material mapper shades.
  static constexpr int MaximumNumberOfInputs = 4;

  /// The largest output grid, in points (default 512^3): a fine volume
  /// overlapping a large one would otherwise ask for the large box at the
  /// fine spacing.
  vtkSetClampMacro(MaximumNumberOfPoints, vtkIdType, 1, VTK_ID_MAX);
  vtkGetMacro(MaximumNumberOfPoints, vtkIdType);

  /// The array an input contributes: its active point scalars
  /// when they have one component, else its first one-component point array,
  /// else nullptr.
  static vtkDataArray* FieldOf(vtkImageData* input);

  /**
   * The output grid of boxes [lower[3*i], upper[3*i]] (per axis, i over the
   * inputs) sampled with spacings `spacings[3*i]`: the union's lower corner
   * as origin, the finest spacing per axis, and enough points to reach the
   * union's upper corner.
   */
  static void UnionGrid(int inputs, const double* lower, const double* upper,
    const double* spacings, double origin[3], double spacing[3], int dimensions[3]);

protected:
  vtkVolumesToFields() = default;
  ~vtkVolumesToFields() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  vtkIdType MaximumNumberOfPoints = vtkIdType(512) * 512 * 512;

private:
  // One input's geometry, from its pipeline information or its data.
  struct InputBox
  {
    int Extent[6] = { 0, -1, 0, -1, 0, -1 };
    double Origin[3] = { 0.0, 0.0, 0.0 };
    double Spacing[3] = { 1.0, 1.0, 1.0 };
    bool AxisAligned = true;
  };

  // The output geometry of `boxes`; false, saying why in `error`, where
  // they cannot be merged.
  bool OutputGrid(const std::vector<InputBox>& boxes, double origin[3], double spacing[3],
    int dimensions[3], std::string& error) const;

  // The grid RequestInformation announced, to warn where the data differ.
  int AnnouncedDimensions[3] = { 0, 0, 0 };

  vtkVolumesToFields(const vtkVolumesToFields&) = delete;
  void operator=(const vtkVolumesToFields&) = delete;
};

#endif
