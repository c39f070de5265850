#include "vtkMultiMaterialInputCheck.h"

#include "vtkCombinedFieldExtinction.h"
#include "vtkDataArray.h"
#include "vtkGPUVolumeRayCastMapper.h"
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
  // The ray caster's copy holds what it draws (a vector reduced by VectorMode).
  vtkDataSet* scalarSource = image;
  if (auto* gpu = vtkGPUVolumeRayCastMapper::SafeDownCast(mapper))
  {
    vtkDataSet* copy = gpu->GetTransformedInput(0);
    scalarSource = copy && copy->GetNumberOfPoints() == image->GetNumberOfPoints() ? copy : image;
  }
  int cellFlag = 0;
  vtkDataArray* scalars = vtkAbstractMapper::GetScalars(scalarSource, mapper->GetScalarMode(),
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
  int dataDims[3];
  image->GetDimensions(dataDims);
  const bool flat = dataDims[0] < 2 || dataDims[1] < 2 || dataDims[2] < 2;
  if (cellFlag == 1 && flat)
  {
    // VTK's ray caster would upload a texture with no texel along that axis.
    check.Reason = "cell scalars on an image with a single point along an axis have no "
                   "volume to render; using VTK's shading";
    return check;
  }
  if (cellFlag != 0 && cellFlag != 1)
  {
    return check; // field data: the base class reports it
  }
  if (flat)
  {
    // Found by TestBadInput.SingleSliceAnd2DImages: a single slice has no
    // thickness, so seen face-on it integrates to nothing (a black image).
    check.Caveat = "the input is a single slice (one point along an axis): it has no "
                   "thickness and may render empty";
  }
  const int components = scalars->GetNumberOfComponents();
  if (components > 1 && !vol->GetProperty()->GetIndependentComponents())
  {
    check.Reason = "multi-material shading needs one-component scalars or independent "
                   "components (for vectors, set the mapper's VectorMode, or colour by "
                   "Magnitude or a component); using VTK's shading";
    return check;
  }
  if (components > mmv::MaxFields)
  {
    check.Reason = "the scalars have " + std::to_string(components) + " components: at most " +
      std::to_string(mmv::MaxFields) + " fields can be shaded together; using VTK's shading";
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
  check.CellData = cellFlag == 1;
  check.Context = context;
  return check;
}

} // namespace mmv
