/**
 * @class   vtkIrradianceResolutionProbe
 * @brief   The coarsest irradiance grid a volume needs, from the measured
 *          error of coarser grids (issue 9: "model no more than a scene needs").
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
 * diffusion smooths what it adds (with it, the probe cost 6x as much on the
 * CT and separated the scenes less). The result is kept until its key
 * changes.
 */
#ifndef vtkIrradianceResolutionProbe_h
#define vtkIrradianceResolutionProbe_h

#include "vtkIrradianceGrid.h"            // IrradianceGrid
#include "vtkIrradianceInputCache.h"      // VolumeKey
#include "vtkIrradianceVolumePass.h"      // vtkNew
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
  using ComputeFunction = std::function<bool(vtkIrradianceVolumePass* pass,
    const mmv::IrradianceGrid& grid, const std::vector<float>& prefiltered,
    unsigned long version, const std::vector<mmv::LightSource>& lights)>;

  /// One grid the probe measured.
  struct Candidate
  {
    double Scale = 1.0;
    int Dimensions[3] = { 0, 0, 0 };
    double PSNR = 0.0; // against the reference grid (dB); +inf for it
  };

  /**
   * The scale (a fraction of the data's resolution per axis) of the
   * coarsest grid within `boundDB` of the reference: the grid the memory
   * budget `budgetMB` allows for the probe's light. Re-measured only
   * when `key` (the irradiance's volume key; its light count and scattering
   * switch are ignored), the data's dimensions, the budget or the bound
   * changed. `opacityTable` (over the normalised range) weighs the voxels.
   * No grid axis exceeds `maxAxis` (the largest 3D texture). On failure
   * returns the reference scale.
   */
  double Choose(vtkOpenGLRenderWindow* context, const vtkIrradianceInputCache::VolumeKey& key,
    vtkImageData* image, vtkDataArray* scalars, const double range[2], double budgetMB,
    int maxAxis, double boundDB, const std::vector<float>& opacityTable,
    const ComputeFunction& compute);
#endif

  /// Whether Choose() with these arguments would measure (rather than
  /// return the kept result): the caller can report progress first.
  bool NeedsMeasurement(const vtkIrradianceInputCache::VolumeKey& key, vtkImageData* image,
    double budgetMB, double boundDB) const;
#endif

#ifndef __VTK_WRAP__
  /// The probe's light (object space).
#ifndef __VTK_WRAP__
  static std::vector<mmv::LightSource> ProbeLights();
  /// What the last measurement found, reference first.
  const std::vector<Candidate>& GetCandidates() const { return this->Candidates; }
#endif
  /// One line on the last choice, for the resolution reason.
  const std::string& GetSummary() const { return this->Summary; }
  /// Measurements made (a camera or light move must not add one).
  vtkGetMacro(NumberOfProbes, int);
  /// Wall seconds of the last measurement.
  vtkGetMacro(LastProbeSeconds, double);

  /// Forgets the result (graphics released): the next Choose() measures.
  void Invalidate() { this->HasResult = false; }
  void ReleaseGraphicsResources(vtkWindow* window);

protected:
  vtkIrradianceResolutionProbe();
  ~vtkIrradianceResolutionProbe() override;

private:
  vtkIrradianceResolutionProbe(const vtkIrradianceResolutionProbe&) = delete;
  void operator=(const vtkIrradianceResolutionProbe&) = delete;

  struct Key
  {
    vtkIrradianceInputCache::VolumeKey Volume;
    int DataDimensions[3] = { 0, 0, 0 };
    double BudgetMB = 0.0;
    double BoundDB = 0.0;
    bool operator==(const Key& o) const;
  };
  static Key MakeKey(const vtkIrradianceInputCache::VolumeKey& key, vtkImageData* image,
    double budgetMB, double boundDB);
  bool Measure(vtkOpenGLRenderWindow* context, vtkImageData* image, vtkDataArray* scalars,
    vtkMTimeType dataTime, const double range[2], double budgetMB, int maxAxis, double boundDB,
    const std::vector<float>& opacityTable,
    const ComputeFunction& compute);

  vtkNew<vtkIrradianceInputCache> Prefilter;
  vtkNew<vtkIrradianceVolumePass> Pass;
  bool HasResult = false;
  Key Measured;
  double Scale = 1.0;
  std::vector<Candidate> Candidates;
  std::string Summary;
  int NumberOfProbes = 0;
  double LastProbeSeconds = 0.0;
};

#endif
