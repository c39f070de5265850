/**
 * @class   vtkIrradianceVolumeFilter
 * @brief   CPU reference of the decoupled-shading irradiance volume (Zhang & Ma §5).
 *
 * Input: vtkImageData with point scalars (the active scalars, component 0).
 * Output: vtkImageData at the irradiance resolution with one float point array
 * per light, "Irradiance_0", "Irradiance_1", ... in the order the lights were
 * added. Values are the fraction of each light reaching the voxel centre
 * (eqs. 9-14), without the light's colour and intensity, which the shading
 * applies; lights that are switched off or have zero intensity produce a zero
 * array and cost no shadow rays.
 *
 * Steps (§5.1, §5.2):
 *  1. Resolution: IrradianceScale in (0, 1] if set, otherwise the largest
 *     scale whose 16-bit-per-light storage fits IrradianceMemoryMB (never above
 *     the data resolution); see ComputeIrradianceDimensions().
 *  2. Pre-filter the data to that resolution (box filter over each irradiance
 *     voxel's footprint). Grid and pre-filter are vtkIrradianceGrid.h's, which
 *     the GPU path uses too.
 *  3. For every voxel whose pre-filtered value has opacity > 0 (sparse; the
 *     count is NumberOfComputedVoxels), the transmittance toward each light:
 *     directional lights by piecewise shadow rays (vtkShadowSweep.h; every
 *     voxel, swept along the light) unless ShadowEstimation says full rays;
 *     otherwise cast one shadow ray per light with the
 *     pre-integrated shadow opacity (sigma = attenuation * mu), steps of
 *     ShadowStepScale irradiance voxels, early termination at transmittance
 *     mmv::MinShadowTransmittance (1e-4). Directional lights: ray to the
 *     volume boundary; point and spot lights: to the light or the boundary,
 *     times eps^2/max(eps^2, d^2), spot visibility by vtkLight's cone
 *     half-angle (vtkMultiMaterialLightModel.h).
 *  4. Multiple scattering: diffusion with per-voxel s from the material TF,
 *     its change computed on a grid coarsened to the diffusion length
 *     (mmv::DiffuseIrradianceOnDiffusionGrid, as the GPU estimator does), skipped
 *     when every s is zero or MultipleScattering is off.
 *  5. Empty voxels next to computed ones take the mean of their computed
 *     neighbours, so trilinear lookups at material boundaries are not darkened
 *     by empty space; other empty voxels stay 0.
 *
 * Lights are taken in world coordinates (vtkLight::GetTransformedPosition /
 * FocalPoint). The image's direction matrix is honoured.
 * Transmission colour (vtkMultiMaterialParameters.h): when some material
 * node's T is not white, each light also gets "IrradianceTint_<k>", 3
 * components, the tint K per channel (full shadow rays of the selective
 * extinction on the tint grid, TintResolutionDivisor, interpolated to the
 * irradiance grid, not diffused): the RGB irradiance is Irradiance_<k> times
 * it. Grey materials output no tint arrays.
 * Multithreaded with vtkSMPTools; reports progress and honours AbortExecute.
 */
#ifndef vtkIrradianceVolumeFilter_h
#define vtkIrradianceVolumeFilter_h

#include "vtkImageAlgorithm.h"
#ifndef __VTK_WRAP__                 // GLM: the wrappers take minutes to parse it
#include "vtkMultiMaterialCutaway.h" // mmv::Cutaway
#endif
#include "vtkMultiMaterialParameters.h"          // ShadowEstimation
#include "vtkMultiMaterialSettings.h"            // the shared defaults
#include "vtkMultiMaterialVolumeFiltersModule.h" // export macro
#include "vtkSmartPointer.h"                     // InputScalars

class vtkDataArray;
class vtkImageData;
class vtkLight;
class vtkLightCollection;
class vtkMaterialTransferFunction;
class vtkPlaneCollection;
class vtkVolumeMapper;
class vtkPiecewiseFunction;

class VTKMULTIMATERIALVOLUMEFILTERS_EXPORT vtkIrradianceVolumeFilter : public vtkImageAlgorithm
{
public:
  static vtkIrradianceVolumeFilter* New();
  vtkTypeMacro(vtkIrradianceVolumeFilter, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Scalar opacity TF (required) and its unit distance (VTK's convention).
  void SetScalarOpacity(vtkPiecewiseFunction* otf);
  vtkPiecewiseFunction* GetScalarOpacity();
  vtkSetMacro(ScalarOpacityUnitDistance, double);
  vtkGetMacro(ScalarOpacityUnitDistance, double);
  ///@}

  /// Material TF (attenuation and scattering); null means the defaults.
  void SetMaterialTransferFunction(vtkMaterialTransferFunction* mtf);
  vtkMaterialTransferFunction* GetMaterialTransferFunction();

  ///@{
  /// The lights, in world coordinates.
  ///@{
  /**
   * Cutaways, as vtkVolumeMapper defines them: what the cropping region
   * (data coordinates, VTK's region flags) and the clipping planes (world
   * coordinates; a plane keeps the side its normal points to) remove is
   * empty for the shadow rays. Copy a mapper's with CopyCutaway().
   */
  vtkSetMacro(Cropping, bool);
  vtkGetMacro(Cropping, bool);
  vtkSetVector6Macro(CroppingRegionPlanes, double);
  vtkGetVector6Macro(CroppingRegionPlanes, double);
  vtkSetMacro(CroppingRegionFlags, int);
  vtkGetMacro(CroppingRegionFlags, int);
  void SetClippingPlanes(vtkPlaneCollection* planes);
  vtkPlaneCollection* GetClippingPlanes();
  void CopyCutaway(vtkVolumeMapper* mapper);
  ///@}

  void AddLight(vtkLight* light);
  void RemoveAllLights();
  void SetLights(vtkLightCollection* lights);
  vtkLightCollection* GetLights();
  ///@}

  /// Irradiance resolution as a fraction of the data's (0 < x <= 1); 0 (default)
  /// chooses it from IrradianceMemoryMB. Values above 1 are reported
  /// (warning) and used as 1; negative or NaN ones as 0.
  vtkSetMacro(IrradianceScale, double);
  vtkGetMacro(IrradianceScale, double);

  /// Memory budget in MB for the irradiance volume (16 bits per light per voxel).
  vtkSetClampMacro(IrradianceMemoryMB, double, 0.001, 1.0e6);
  vtkGetMacro(IrradianceMemoryMB, double);

  /// Falloff of point and spot lights. 0 (default): VTK's, by each light's
  /// AttenuationValues (constant, linear, quadratic; the default (1, 0, 0)
  /// means none). > 0: the paper's eq. 12 with this radius epsilon (object
  /// units), (epsilon / distance)^2 beyond it. A negative or non-finite
  /// value is reported (warning) and treated as 0.
  vtkSetMacro(PointLightRadius, double);
  vtkGetMacro(PointLightRadius, double);

  /// Shadow-ray step in irradiance voxels (default 1).
  vtkSetClampMacro(ShadowStepScale, double, 0.05, 16.0);
  vtkGetMacro(ShadowStepScale, double);

  /**
   * How lights are estimated (mmv::ShadowEstimation, vtkShadowSweep.h): 1,
   * piecewise shadow rays swept along the light (default; O(n^3 K) for an
   * n^3 grid; around a point or spot light inside the grid in six
   * pyramids), or 0, full shadow rays (exact, O(n^4)).
   */
  vtkSetClampMacro(ShadowEstimation, int, 0, 1);
  vtkGetMacro(ShadowEstimation, int);

  /// Slices K a piecewise shadow ray spans at most (default
  /// mmv::DefaultPiecewiseShadowSlices).
  vtkSetClampMacro(PiecewiseShadowSlices, int, 1, 4096);
  vtkGetMacro(PiecewiseShadowSlices, int);

  /// Diffusion for multiple scattering (default on).
  vtkSetMacro(MultipleScattering, bool);
  vtkGetMacro(MultipleScattering, bool);
  vtkBooleanMacro(MultipleScattering, bool);

  /// The diffusion's time integration (mmv::DiffusionSettings::Exponential):
  /// on (default, mmv::DefaultExponentialDiffusion, as the mapper), the
  /// exponential's Chebyshev series; off, backward-Euler sub-steps solved by
  /// conjugate gradients.
  vtkSetMacro(ExponentialDiffusion, bool);
  vtkGetMacro(ExponentialDiffusion, bool);
  vtkBooleanMacro(ExponentialDiffusion, bool);

  /**
   * The tint grid of a non-white transmission colour is the irradiance grid
   * divided by this per axis (mmv::TintDimension): 2 (default,
   * mmv::TintResolutionDivisor) as the GPU stores it, 1 for the tint at full
   * resolution (the uncompressed RGB irradiance).
   */
  vtkSetClampMacro(TintResolutionDivisor, int, 1, 16);
  vtkGetMacro(TintResolutionDivisor, int);
  /// Fills empty voxels bordering computed ones (step 5; default on).
  vtkSetMacro(FillEmptyNeighbors, bool);
  vtkGetMacro(FillEmptyNeighbors, bool);
  vtkBooleanMacro(FillEmptyNeighbors, bool);

  ///@{
  /// What the last execution did.
  vtkGetMacro(NumberOfComputedVoxels, vtkIdType);
  vtkGetMacro(NumberOfShadowRays, vtkIdType);
  vtkGetMacro(DiffusionIterations, int);
  vtkGetVector3Macro(IrradianceDimensions, int);
  ///@}

  /**
   * The irradiance grid for data of `dataDims` points: `scale` in (0, 1]
   * scales every axis; scale <= 0 picks the largest scale whose
   * numberOfLights * 2 bytes per voxel fit `budgetMB`. Axes never exceed the
   * data's and never drop below min(2, data). Same as
   * mmv::ComputeIrradianceDimensions (vtkIrradianceGrid.h), which the GPU
   * mapper calls, so both pick the same resolution.
   */
  static void ComputeIrradianceDimensions(const int dataDims[3], int numberOfLights,
    double budgetMB, double scale, int irradianceDims[3]);

  /// Includes the opacity and material functions and the lights, so that
  /// editing any of them re-executes the filter.
  vtkMTimeType GetMTime() override;

protected:
#ifndef __VTK_WRAP__
  mmv::Cutaway MakeCutaway();
#endif
  bool Cropping = false;
  double CroppingRegionPlanes[6] = { 0.0, 1.0, 0.0, 1.0, 0.0, 1.0 };
  int CroppingRegionFlags = 0x0002000; // VTK_CROP_SUBVOLUME

  vtkIrradianceVolumeFilter();
  ~vtkIrradianceVolumeFilter() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  // The scalars to light, after checking the input and the settings; for
  // cell scalars `input` becomes the grid of the cell centres, which
  // `cellCentres` holds. Null after reporting an error.
  vtkDataArray* InputScalars(vtkInformationVector** inputVector, vtkImageData* output,
    vtkImageData*& input, vtkSmartPointer<vtkImageData>& cellCentres);
  // IrradianceDimensions for this input, the lights and the scale or budget.
  void UpdateIrradianceDimensions(vtkImageData* input);
  double ScalarOpacityUnitDistance = 1.0;
  // The settings it shares with the mapper start at the mapper's defaults.
  double IrradianceScale = mmv::DefaultIlluminationSettings.IrradianceScale;
  double IrradianceMemoryMB = mmv::DefaultIlluminationSettings.IrradianceMemoryMB;
  double PointLightRadius = mmv::DefaultIlluminationSettings.PointLightRadius;
  double ShadowStepScale = 1.0;
  int ShadowEstimation = mmv::DefaultIlluminationSettings.ShadowEstimation;
  int PiecewiseShadowSlices = mmv::DefaultIlluminationSettings.PiecewiseShadowSlices;
  bool MultipleScattering = mmv::DefaultIlluminationSettings.MultipleScattering;
  bool ExponentialDiffusion = mmv::DefaultIlluminationSettings.ExponentialDiffusion;
  bool FillEmptyNeighbors = true;
  int TintResolutionDivisor = mmv::TintResolutionDivisor;
  // Some material node has a non-white transmission colour: the budget
  // holds the tint too.
  bool IsTinted();

  vtkIdType NumberOfComputedVoxels = 0;
  vtkIdType NumberOfShadowRays = 0;
  int DiffusionIterations = 0;
  int IrradianceDimensions[3] = { 0, 0, 0 };

private:
  vtkIrradianceVolumeFilter(const vtkIrradianceVolumeFilter&) = delete;
  void operator=(const vtkIrradianceVolumeFilter&) = delete;

  class vtkInternals;
  vtkInternals* Internals;
};

#endif
