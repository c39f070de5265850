/**
 * @class   vtkIrradianceResolutionProbe
 * @brief   The coarsest irradiance grid a volume needs, from the measured
 *          error of coarser grids: model no more than a scene needs.
 *
 * Smooth data (a CT of soft tissue) keeps its lighting on a grid an eighth
 * of the voxels, while thin shells lose their self-shadowing on any coarser
 * grid; neither the screen nor the memory budget can tell the two apart. The
 * probe measures it: it estimates the direct irradiance of one directional
 * probe light (along (1, 1, 1), fixed in object space) on the reference grid
 * and on grids of scale reference * 2^(-k/2), k = 1 ... 4,
 * and keeps the coarsest whose mmv::VisibleIrradiancePSNR against the
 * reference reaches the bound; the first that misses it ends the search.
 *
 * The probe light does not follow the camera, so the choice depends only on
 * the data, the transfer functions and the budget: a camera move (and
 * ParaView's light kit with it) never re-probes, and a fresh render of any
 * camera chooses the same grid. Multiple scattering is left out, since the
 * diffusion smooths what it adds. The result is kept while the grid's
 * geometry, the budget, the bound and the shadow settings stay, and the
 * transfer functions keep their support and sharpness
 * (vtkIrradianceProbeRule.h): an opacity drag or a new time step on the same
 * grid does not measure again.
 */
#ifndef vtkIrradianceResolutionProbe_h
#define vtkIrradianceResolutionProbe_h

#include "vtkIrradianceEstimator.h"       // vtkNew
#include "vtkIrradianceGrid.h"            // IrradianceGrid
#include "vtkIrradianceInputCache.h"      // VolumeKey
#include "vtkIrradianceProbeRule.h"       // ProbeSignature
#include "vtkMultiMaterialLightModel.h"   // LightSource
#include "vtkMultiMaterialVolumeModule.h" // export macro
#include "vtkNew.h"
#include "vtkObject.h"

#include <functional>
#include <string>
#include <vector>

class vtkDataArray;
class vtkImageData;
class vtkOpenGLRenderWindow;
class vtkWindow;

class VTKMULTIMATERIALVOLUME_EXPORT vtkIrradianceResolutionProbe : public vtkObject
{
public:
  static vtkIrradianceResolutionProbe* New();
  vtkTypeMacro(vtkIrradianceResolutionProbe, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

#ifndef __VTK_WRAP__
  /// Estimates the irradiance of `lights` on `grid` (normalised pre-filtered
  /// data `prefiltered`, its version) into `pass`, as the mapper's frame
  /// does but without multiple scattering. False: it failed (reported).
  using ComputeFunction = std::function<bool(vtkIrradianceEstimator* pass,
    const mmv::IrradianceGrid& grid, const std::vector<float>& prefiltered, unsigned long version,
    const std::vector<mmv::LightSource>& lights)>;

  /// One grid the probe measured.
  struct Candidate
  {
    double Scale = 1.0;
    int Dimensions[3] = { 0, 0, 0 };
    double PSNR = 0.0; // against the reference grid (dB); +inf for it
  };

  /// The transfer functions' signature, asked for only when the volume key
  /// differs from the last one seen (no sampling on the per-frame path).
  using SignatureFunction = std::function<mmv::ProbeSignature()>;

  /**
   * The scale (a fraction of the data's resolution per axis) of the
   * coarsest grid within `boundDB` of the reference: the grid the memory
   * budget `budgetMB` allows for the probe's light. Measured again only
   * when Holds() is false. `opacityTable` (over the normalised range)
   * weighs the voxels. No grid axis exceeds `maxAxis` (the largest 3D
   * texture). On failure returns the reference scale.
   */
  double Choose(vtkOpenGLRenderWindow* context, const vtkIrradianceInputCache::VolumeKey& key,
    vtkImageData* image, vtkDataArray* scalars, const double range[2], double budgetMB, int maxAxis,
    double boundDB, const std::vector<float>& opacityTable, const SignatureFunction& signature,
    const ComputeFunction& compute);

  /**
   * Whether the kept choice holds for these inputs (so Choose() returns it
   * without measuring): same grid geometry (dimensions, spacing), budget,
   * bound, shadow settings and cutaway, and a signature within the rule of
   * vtkIrradianceProbeRule.h of the measured one. The data's values and
   * modification time do not count: a time step on the same grid keeps it.
   */
  bool Holds(const vtkIrradianceInputCache::VolumeKey& key, vtkImageData* image, double budgetMB,
    double boundDB, const SignatureFunction& signature);
#endif

#ifndef __VTK_WRAP__
  /// The probe's light (object space).
  static std::vector<mmv::LightSource> ProbeLights();
  /// What the last measurement found, reference first.
  const std::vector<Candidate>& GetCandidates() const
  {
    return this->Candidates;
  }
#endif
  /// One line on the last choice, for the resolution reason.
  const std::string& GetSummary() const
  {
    return this->Summary;
  }
  /// Measurements made (a camera or light move must not add one).
  vtkGetMacro(NumberOfProbes, int);
  /// Wall seconds of the last measurement.
  vtkGetMacro(LastProbeSeconds, double);

  /// Forgets the result (graphics released): the next Choose() measures.
  void Invalidate()
  {
    this->HasResult = false;
  }
  void ReleaseGraphicsResources(vtkWindow* window);

protected:
  vtkIrradianceResolutionProbe();
  ~vtkIrradianceResolutionProbe() override;

private:
  vtkIrradianceResolutionProbe(const vtkIrradianceResolutionProbe&) = delete;
  void operator=(const vtkIrradianceResolutionProbe&) = delete;

  /// What the choice depends on besides the transfer functions' signature.
  struct Key
  {
    int DataDimensions[3] = { 0, 0, 0 };
    double DataSpacing[3] = { 0.0, 0.0, 0.0 };
    double BudgetMB = 0.0;
    double BoundDB = 0.0;
    int TableSize = 0;
    int ShadowEstimation = 0;
    int PiecewiseShadowSlices = 0;
    std::vector<double> Cut;
    bool operator==(const Key& o) const;
  };
  static Key MakeKey(const vtkIrradianceInputCache::VolumeKey& key, vtkImageData* image,
    double budgetMB, double boundDB);
  bool Measure(vtkOpenGLRenderWindow* context, vtkImageData* image, vtkDataArray* scalars,
    vtkMTimeType dataTime, const double range[2], double budgetMB, int maxAxis, double boundDB,
    const std::vector<float>& opacityTable, const ComputeFunction& compute);

  vtkNew<vtkIrradianceInputCache> Prefilter;
  vtkNew<vtkIrradianceEstimator> Pass;
  bool HasResult = false;
  Key Measured;
  mmv::ProbeSignature MeasuredSignature;
  // The last volume key the kept choice was found to hold for.
  vtkIrradianceInputCache::VolumeKey Seen;
  double Scale = 1.0;
  std::vector<Candidate> Candidates;
  std::string Summary;
  int NumberOfProbes = 0;
  double LastProbeSeconds = 0.0;
};

#endif
