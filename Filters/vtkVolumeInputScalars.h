/**
 * @file   vtkVolumeInputScalars.h
 * @brief  The point scalars on an image that multi-material shading lights,
 *         made from the data ParaView users volume-render: cell scalars (an
 *         image of the cell centres), vectors (their magnitude or one
 *         component) and several arrays read as several fields.
 *
 * Shared by vtkMultiMaterialVolumeMapper and vtkIrradianceVolumeFilter, so
 * that the GPU and the CPU model light the same field.
 */
#ifndef vtkVolumeInputScalars_h
#define vtkVolumeInputScalars_h

#include "vtkMultiMaterialVolumeFiltersModule.h" // export macro
#include "vtkSmartPointer.h"                     // return values

#include <string> // error messages
#include <vector> // arrays

class vtkDataArray;
class vtkImageData;

namespace mmv
{

/// How a multi-component array becomes one value per tuple; the values are
/// those of vtkSmartVolumeMapper::VectorModeType and vtkScalarsToColors, so
/// that ParaView's colour map setting can be forwarded as it is.
enum VectorModes
{
  VectorModeDisabled = -1, ///< multi-component scalars are not reduced
  VectorModeMagnitude = 0, ///< the Euclidean norm of the tuple
  VectorModeComponent = 1  ///< one component
};

/**
 * The image whose points are the centres of `image`'s cells, holding
 * `cellScalars` as point scalars. VTK's ray caster draws cell data as a
 * texture whose texel centres are the cell centres, interpolated linearly
 * between them, so this grid (the cell dimensions, the origin moved half a
 * spacing along each index axis, same spacing and direction) is where the
 * field it draws is known; gradients, pre-filtering and shadows computed on
 * it light what is drawn. Null when an axis has a single point (no cells
 * along it) or the array has fewer tuples than cells.
 */
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT vtkSmartPointer<vtkImageData> MakeCellCentreImage(
  vtkImageData* image, vtkDataArray* cellScalars);

/**
 * A one-component array of `vectors`' magnitude (VectorModeMagnitude) or its
 * component `component` (VectorModeComponent), named as `vectors`, so that
 * it can stand in for it. Magnitudes are double for double input, else float;
 * a component keeps the array's type. Null (with `error` set) for a
 * component outside [0, components) or an unknown mode.
 */
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT vtkSmartPointer<vtkDataArray> MakeVectorScalars(
  vtkDataArray* vectors, int mode, int component, std::string* error);

/**
 * Several fields as one array: `first` (the scalars) as component 0 and each
 * of `others` as the next component, float, named as `first`, so that it can
 * stand in for it. Null (with `error` set) when an array is missing, has
 * more than one component or fewer tuples than `first`, or there would be
 * more than 4 fields.
 */
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT vtkSmartPointer<vtkDataArray> MakeFieldArray(
  vtkDataArray* first, const std::vector<vtkDataArray*>& others, std::string* error);

/**
 * The range the lighting maps component `component` over: the finite range
 * (NaN and Inf left out), widened to [v, v + 1] for a constant component.
 * Integers have no NaN or Inf, so they take the plain range: the one VTK's
 * ray caster asks for too, computed once and kept by the array (which keeps
 * the finite range apart).
 */
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT void LightingRange(
  vtkDataArray* scalars, int component, double range[2]);

} // namespace mmv

#endif
