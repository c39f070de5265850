/**
 * @class   vtkIrradianceUpdatePlan
 * @brief   What one irradiance update recomputes, decided once from the
 *          inputs the irradiance volume was computed from and the new ones.
 *
 * The irradiance volume depends on the data, the irradiance grid, the
 * extinction (opacity and the materials' attenuation, transmission and
 * scattering), the shadow and diffusion settings, the cutaway, each light
 * and the other volumes that shadow it. The plan compares the inputs the held irradiance was
 * computed from with the new inputs once, names what changed (GetChanges()), and from that which
 * steps run:
 *  - nothing at all (IsCurrent());
 *  - whether an interactive frame may keep the last irradiance
 *    (KeepsVolume(): only the lights, the grid or the other volumes moved);
 *  - the pre-filtering of the data onto the grid (Prefilters());
 *  - new irradiance textures (Reallocates());
 *  - the shadows, diffusion and final write of which lights (GetLights():
 *    every light when anything but the lights changed, else the new lights
 *    and those beyond the tolerance of the placement their channel holds).
 *
 * The comparison of a light with its held placement is
 * mmv::LightWithinTolerance (its kind, cone, falloff and grid stride exactly,
 * its placement within LightDirectionTolerance), always against the held
 * placement, so small moves cannot add up.
 *
 * vtkIrradianceInputCache keeps the held inputs, the irradiance stage makes
 * the plan and vtkIrradianceEstimator executes its light marks. Pure CPU:
 * no OpenGL, unit-tested on its own.
 */
#ifndef vtkIrradianceUpdatePlan_h
#define vtkIrradianceUpdatePlan_h

#include "vtkMultiMaterialLightModel.h"          // mmv::LightSource
#include "vtkMultiMaterialParameters.h"          // DefaultExponentialDiffusion
#include "vtkMultiMaterialVolumeFiltersModule.h" // export macro
#include "vtkType.h"                             // vtkMTimeType

#include <glm/glm.hpp> // the grid's centre

#include <vector>

class VTKMULTIMATERIALVOLUMEFILTERS_EXPORT vtkIrradianceUpdatePlan
{
public:
  /// Everything the whole irradiance volume depends on besides the lights and
  /// the grid: a change recomputes every light.
  struct VolumeKey
  {
    vtkMTimeType DataTime = 0;
    vtkMTimeType OpacityTime = 0;
    int MaterialVersion = 0;
    double UnitDistance = 1.0;
    double Range[2] = { 0.0, 0.0 };
    bool MultipleScattering = false;
    int TableSize = 0;
    int NumberOfLights = 0;
    int ShadowEstimation = 0;
    int PiecewiseShadowSlices = 0;
    bool ExponentialDiffusion = mmv::DefaultExponentialDiffusion;
    /// mmv::Cutaway::Key(): what cropping and clipping remove casts no shadow.
    std::vector<double> Cut;
    /// The irradiance voxels the estimator estimates for (vtkIrradianceRegion.h).
    int Region[6] = { 0, -1, 0, -1, 0, -1 };
    /// The other volumes of the scene that shadow this one
    /// (vtkMultiMaterialSceneShadows::GetKey(): per occluder the version of
    /// its extinction and its placement relative to this volume); empty
    /// when the volume is alone.
    std::vector<double> Occluders;

    /// Equal when no field changed (VolumeChanges() is empty); a NaN never
    /// matches.
    bool operator==(const VolumeKey& o) const { return VolumeChanges(*this, o) == NoChange; }
    bool operator!=(const VolumeKey& o) const { return !(*this == o); }
  };

  /// What an irradiance volume is computed from, in the terms its update
  /// compares.
  struct Inputs
  {
    /// Data, extinction, settings, cutaway and region.
    VolumeKey Volume;
    /// The irradiance grid's dimensions.
    int Dimensions[3] = { 0, 0, 0 };
    /// The light placements (the held ones: what each channel holds).
    std::vector<mmv::LightSource> Lights;
  };

  /// What differs from the held irradiance's inputs, one bit each.
  enum Change : unsigned int
  {
    NoChange = 0,
    NothingHeld = 1u << 0, // nothing computed yet, released, or a failed update
    Data = 1u << 1,        // the data (a time step, an edit) or its scalar range
    Grid = 1u << 2,        // the irradiance grid's dimensions
    Extinction = 1u << 3,  // opacity, unit distance, sampled materials, table size
    Scattering = 1u << 4,  // multiple scattering on or off, the diffusion's integrator
    Shadows = 1u << 5,     // shadow estimation, piecewise slices
    Cutaway = 1u << 6,     // cropping, clipping planes, the region estimated for
    LightCount = 1u << 7,  // lights added or removed
    Lights = 1u << 8,      // a light beyond its tolerance (or its grid stride changed)
    Occluders = 1u << 9    // another volume moved, changed, appeared, hid or went
  };

  /**
   * The plan from `held` (null: nothing held) to `now`. A light within
   * `toleranceRadians` of its held placement keeps its irradiance; a point
   * or spot light's move is measured as the angle it subtends at `centre`
   * (the held grid's centre).
   */
  static vtkIrradianceUpdatePlan Make(
    const Inputs* held, const Inputs& now, double toleranceRadians, const glm::dvec3& centre);

  /**
   * Which of `now` are recomputed against the placements `held` their
   * channels hold: every one (`all`), a new one (no held placement), and one
   * beyond `toleranceRadians` (mmv::LightWithinTolerance about `centre`).
   */
  static std::vector<bool> MarkLights(const std::vector<mmv::LightSource>& held,
    const std::vector<mmv::LightSource>& now, bool all, double toleranceRadians,
    const glm::dvec3& centre);

  /// Change bits (or'ed).
  unsigned int GetChanges() const { return this->Changes; }
  bool Changed(Change change) const { return (this->Changes & change) != 0; }

  /// Nothing to recompute: the held irradiance is the new inputs'.
  bool IsCurrent() const { return this->Changes == NoChange; }
  /// Only the lights, the grid or the other volumes moved: an interactive
  /// frame may keep the held irradiance (the still frame after it updates).
  bool KeepsVolume() const;
  /// The data must be pre-filtered onto the grid again.
  bool Prefilters() const;
  /// The irradiance textures get new sizes: every light is recomputed.
  bool Reallocates() const;
  /// Everything but the lights changed, or nothing is held.
  bool RecomputesAllLights() const;
  /// Light k is recomputed (shadows, diffusion, final write) when marked.
  const std::vector<bool>& GetLights() const { return this->MarkedLights; }
  int GetNumberOfLights() const;
  /// The lights that are new or beyond their tolerance, whatever else
  /// changed: what vtkIrradianceEstimator recomputes when its own inputs
  /// (the values the keys stand for) turn out unchanged.
  const std::vector<bool>& GetMovedLights() const { return this->MovedLights; }
  /// With `multipleScattering` on, the updated lights are diffused.
  bool Diffuses(bool multipleScattering) const
  {
    return multipleScattering && this->GetNumberOfLights() > 0;
  }

  /// The change bits of the volume keys alone (Data, Extinction,
  /// Scattering, Shadows, Cutaway, LightCount, Occluders).
  static unsigned int VolumeChanges(const VolumeKey& held, const VolumeKey& now);

private:
  unsigned int Changes = NothingHeld;
  // Whether the irradiance textures' layout (lights per texture, channels)
  // changes with the number of lights.
  bool TextureLayoutChanged = true;
  std::vector<bool> MarkedLights;
  std::vector<bool> MovedLights;
};

#endif
