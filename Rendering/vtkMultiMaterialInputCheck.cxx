#include "vtkMultiMaterialInputCheck.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkVolume.h"
#include "vtkVolumeMapper.h"
#include "vtkVolumeProperty.h"

namespace mmv
{

InputCheck CheckMultiMaterialInputs(vtkVolumeMapper* mapper, vtkRenderer* ren, vtkVolume* vol)
{
  InputCheck check;
  if (mapper->GetBlendMode() != vtkVolumeMapper::COMPOSITE_BLEND)
  {
    return check; // other blend modes are the base class's business
  }
  auto* image = vtkImageData::SafeDownCast(mapper->GetInput());
  auto* context = vtkOpenGLRenderWindow::SafeDownCast(ren->GetRenderWindow());
  if (!image || !vol->GetProperty() || !context)
  {
    if (mapper->GetInput())
    {
      check.Reason = "multi-material shading needs vtkImageData input; using VTK's shading";
    }
    return check;
  }
  int cellFlag = 0;
  vtkDataArray* scalars = vtkAbstractMapper::GetScalars(image, mapper->GetScalarMode(),
    mapper->GetArrayAccessMode(), mapper->GetArrayId(), mapper->GetArrayName(), cellFlag);
  if (!scalars)
  {
    return check; // the base class reports missing scalars
  }
  // An empty image (0 points) crashed the irradiance pre-filter
  // (TestBadInput.EmptyVolume); fewer scalars than points would read past them.
  if (image->GetNumberOfPoints() < 1 ||
    scalars->GetNumberOfTuples() <
      (cellFlag ? image->GetNumberOfCells() : image->GetNumberOfPoints()))
  {
    check.Reason = "the input has no points or fewer scalars than points; nothing to shade";
    return check;
  }
  if (cellFlag)
  {
    check.Reason = "multi-material shading needs point scalars (cell scalars given); "
                   "using VTK's shading";
    return check;
  }
  int dataDims[3];
  image->GetDimensions(dataDims);
  if (dataDims[0] < 2 || dataDims[1] < 2 || dataDims[2] < 2)
  {
    // Found by TestBadInput.SingleSliceAnd2DImages: a single slice has no
    // thickness, so seen face-on it integrates to nothing (a black image).
    check.Caveat = "the input is a single slice (one point along an axis): it has no "
                   "thickness and may render empty";
  }
  if (scalars->GetNumberOfComponents() != 1)
  {
    check.Reason = "multi-material shading needs one-component scalars; using VTK's shading";
    return check;
  }
  if (vol->GetProperty()->GetTransferFunctionMode() != vtkVolumeProperty::TF_1D)
  {
    check.Reason = "multi-material shading needs a 1D transfer function; using VTK's shading";
    return check;
  }
  check.Supported = true;
  check.Image = image;
  check.Scalars = scalars;
  check.Context = context;
  return check;
}

} // namespace mmv
