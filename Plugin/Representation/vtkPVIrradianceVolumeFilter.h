/**
 * @class   vtkPVIrradianceVolumeFilter
 * @brief   vtkIrradianceVolumeFilter with flat, ParaView-friendly inputs.
 *
 * ParaView's "Irradiance Volume" filter. The base class takes a
 * vtkPiecewiseFunction, a vtkMaterialTransferFunction and vtkLights; this
 * class owns them and sets them from plain numbers so that server-manager
 * properties can drive it:
 *  - the opacity function from (value, opacity) pairs,
 *  - the material nodes as for vtkPVMultiMaterialVolumeRepresentation,
 *  - light 0: a directional light travelling along LightDirection,
 *  - light 1 (with UsePointLight): a point light at PointLightPosition.
 * Both lights are white with intensity 1; the output arrays are the fraction
 * of each light reaching every voxel (Irradiance_0, Irradiance_1).
 */
#ifndef vtkPVIrradianceVolumeFilter_h
#define vtkPVIrradianceVolumeFilter_h

#include "vtkIrradianceVolumeFilter.h"
#include "vtkLight.h"                             // for vtkNew ivar
#include "vtkMaterialTransferFunction.h"          // for vtkNew ivar
#include "vtkMultiMaterialVolumeParaViewModule.h" // export macro
#include "vtkNew.h"                               // for vtkNew
#include "vtkPVMaterialNodeBuffer.h"              // for ivar
#include "vtkPiecewiseFunction.h"                 // for vtkNew ivar

class VTKMULTIMATERIALVOLUMEPARAVIEW_EXPORT vtkPVIrradianceVolumeFilter
  : public vtkIrradianceVolumeFilter
{
public:
  static vtkPVIrradianceVolumeFilter* New();
  vtkTypeMacro(vtkPVIrradianceVolumeFilter, vtkIrradianceVolumeFilter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The scalar opacity function as (value, opacity) pairs.
  void AddOpacityPoint(double value, double opacity);
  void RemoveAllOpacityPoints();
  ///@}

  ///@{
  /// Material nodes, pushed as a count then every value (10 per node, or the
  /// older 9 or 8); applied all or nothing once complete, see
  /// vtkPVMaterialNodeBuffer.
  void SetNumberOfMaterialNodeValues(int count);
  void SetMaterialNodeValue(int index, double value);
  ///@}

  /// Direction the directional light travels, world coordinates. Default (0, 0, -1).
  void SetLightDirection(double x, double y, double z);

  ///@{
  /// The optional point light (off by default), world coordinates.
  void SetUsePointLight(bool use);
  void SetPointLightPosition(double x, double y, double z);
  ///@}

protected:
  vtkPVIrradianceVolumeFilter();
  ~vtkPVIrradianceVolumeFilter() override;

private:
  vtkPVIrradianceVolumeFilter(const vtkPVIrradianceVolumeFilter&) = delete;
  void operator=(const vtkPVIrradianceVolumeFilter&) = delete;

  void UpdateLights();

  vtkNew<vtkPiecewiseFunction> Opacity;
  vtkNew<vtkMaterialTransferFunction> Materials;
  vtkNew<vtkLight> DirectionalLight;
  vtkNew<vtkLight> PointLight;
  vtkPVMaterialNodeBuffer PendingNodes;
  bool UsePointLight = false;
};

#endif
