/**
 * @class   vtkPreIntegrationTable
 * @brief   Pre-integrated colour, opacity, shading position and shadow opacity
 *          for ray segments of a fixed length (Zhang & Ma eqs. 5-7).
 *
 * A segment of length StepLength (world units) along which the data value
 * runs linearly from t1 (front) to t2 (back). With mu(t) = -ln(1-alpha(t))/u
 * the extinction implied by the scalar opacity (u = ScalarOpacityUnitDistance)
 * and c(t) the colour:
 *
 *   I_alpha(t1,t2) = 1 - exp(-int_0^L mu dx)                          (eq. 6)
 *   I_c(t1,t2)     = int_0^L c mu exp(-int_0^x mu) dx  (opacity-weighted) (eq. 5)
 *   I_beta(t1,t2)  = fraction of the segment before the first non-zero opacity (eq. 7)
 *   I_sigma(t1,t2) = 1 - exp(-int_0^L c_t mu dx)   (shadow opacity, c_t = attenuation)
 *   I_tau(t1,t2)   = 1 - exp(-int_0^L c_t mu (-ln T_lambda) dx), per channel lambda:
 *                    the tint opacity, the selective part of the shadow's
 *                    extinction (T the transmission colour,
 *                    vtkMultiMaterialParameters.h); built only when some
 *                    node's T is not white
 *
 * Tables are TableSize x TableSize over the table range (GetTableRange());
 * entry (i, j) has front value t1 = range[0] + i*d and back value
 * t2 = range[0] + j*d, with d = (range[1]-range[0])/(TableSize-1), stored at
 * index j*TableSize + i. t1 = t2 gives the homogeneous-segment limit.
 *
 * How the entries are computed (not Lum, Wilson & Ma's colour rescaling):
 *  - Each table cell [t_k, t_k+1] is split at every node of the opacity,
 *    colour and material functions into pieces on which all of them are
 *    smooth, so features narrower than a cell (spikes, steps) are resolved.
 *  - Opacity I_alpha: the optical depth of each piece is integrated in closed
 *    form where the opacity is linear (the usual case; exact for the true
 *    TF, the MaxOpacity clamp included) and by 5-point Gauss-Legendre where
 *    it is curved (midpoint/sharpness); a segment's depth is then a
 *    difference of prefix sums over its cells.
 *  - Shadow opacity I_sigma: the same with c_t * mu, c_t by the piece's
 *    Gauss rule, weighted so that the depth of mu stays exact.
 *  - Colour I_c: per piece, a least-squares fit c0 + c1 q in the normalised
 *    optical depth q (clamped to the colour's range over the piece), whose
 *    emission is integrated exactly; pieces are composited front to back
 *    within each cell, in both directions, and cells front to back along the
 *    segment, exactly. Each diagonal |j - i| = m is filled with a sliding
 *    window (add the front cell, drop the back one: O(1) per entry), so the
 *    whole table costs O(n^2) (diagonals run in parallel).
 *  - Shading position I_beta: found at the TF node where non-zero opacity
 *    starts, not at table resolution.
 *
 * Update() rebuilds only when an input (or a setting) changed since the last
 * build; GetBuildCount() tells how often it did. When only the colours
 * changed, it recomputes the colour channels alone from the kept opacity
 * parts (GetColorOnlyBuildCount()), to the same bits as a full build.
 */
#ifndef vtkPreIntegrationTable_h
#define vtkPreIntegrationTable_h

#include "vtkMultiMaterialVolumeFiltersModule.h" // export macro
#include "vtkObject.h"
#include "vtkSmartPointer.h" // members

class vtkColorTransferFunction;
class vtkPiecewiseFunction;
class vtkMaterialTransferFunction;

class VTKMULTIMATERIALVOLUMEFILTERS_EXPORT vtkPreIntegrationTable : public vtkObject
{
public:
  static vtkPreIntegrationTable* New();
  vtkTypeMacro(vtkPreIntegrationTable, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Inputs. Colour may be null (white); opacity is required; the material
  /// function supplies the attenuation c_t for the shadow table (null: c_t = 1).
  void SetColorTransferFunction(vtkColorTransferFunction* ctf);
  vtkColorTransferFunction* GetColorTransferFunction();
  void SetScalarOpacity(vtkPiecewiseFunction* otf);
  vtkPiecewiseFunction* GetScalarOpacity();
  void SetMaterialTransferFunction(vtkMaterialTransferFunction* mtf);
  vtkMaterialTransferFunction* GetMaterialTransferFunction();
  ///@}

  /// Segment length Delta x in world units (> 0). Default 1.
  vtkSetMacro(StepLength, double);
  vtkGetMacro(StepLength, double);

  /// VTK's scalar-opacity unit distance u (> 0). Default 1.
  vtkSetMacro(ScalarOpacityUnitDistance, double);
  vtkGetMacro(ScalarOpacityUnitDistance, double);

  /// Table resolution n (n x n entries), 2..4096. Default 256.
  vtkSetMacro(TableSize, int);
  vtkGetMacro(TableSize, int);

  /// Data range mapped onto the table axes. When empty (the default: min >=
  /// max), the opacity TF's range; when that is empty too, [min, min + 1].
  vtkSetVector2Macro(ScalarRange, double);
  vtkGetVector2Macro(ScalarRange, double);

  /// The range the current tables were built over, after the fallbacks of
  /// ScalarRange; { 0, 1 } before the first successful build.
  void GetTableRange(double range[2]) const;

  /**
   * Rebuilds the tables if anything changed. Returns false (with an error)
   * for invalid settings (no opacity function, StepLength <= 0, ...), in
   * which case the previous tables are kept.
   */
  bool Update();

  ///@{
  /// The tables (layout above). nullptr before the first successful Update();
  /// a failed Update() keeps the previous tables.
  /// RGBA, 4 floats per entry: I_c (opacity-weighted colour) and I_alpha.
  const float* GetColorOpacityTable() const;
  /// 1 float per entry: I_beta in [0, 1].
  const float* GetShadingPositionTable() const;
  /// 1 float per entry: I_sigma, the shadow-ray opacity.
  const float* GetShadowOpacityTable() const;
  /// 4 floats per entry: I_tau per channel (r, g, b) and 0; nullptr when
  /// every transmission colour is white (grey shadows: no tint to compute).
  const float* GetShadowTintTable() const;
  ///@}

  ///@{
  /// Bilinear lookups by data value (clamped to the table range) for CPU
  /// users; 0 before the first successful build.
  double LookupOpacity(double t1, double t2) const;
  double LookupShadowOpacity(double t1, double t2) const;
  /// I_tau per channel; 0 without a tint table.
  void LookupShadowTint(double t1, double t2, double rgb[3]) const;
  double LookupShadingPosition(double t1, double t2) const;
  void LookupColor(double t1, double t2, double rgba[4]) const;
  ///@}

  /// Number of times the tables were (re)built.
  vtkGetMacro(BuildCount, int);
  /// Of those, the builds after a change of the colours alone (the colour
  /// function's values, not its nodes' positions), which recomputed only the
  /// colour channels of GetColorOpacityTable(): the opacity parts of the
  /// integrals are kept from the last full build (for tables up to 512).
  vtkGetMacro(ColorOnlyBuildCount, int);
  /// Wall-clock seconds of the last build.
  vtkGetMacro(LastBuildSeconds, double);

protected:
  vtkPreIntegrationTable();
  ~vtkPreIntegrationTable() override;

  double StepLength = 1.0;
  double ScalarOpacityUnitDistance = 1.0;
  int TableSize = 256;
  double ScalarRange[2] = { 0.0, 0.0 };
  int BuildCount = 0;
  int ColorOnlyBuildCount = 0;
  double LastBuildSeconds = 0.0;

private:
  vtkPreIntegrationTable(const vtkPreIntegrationTable&) = delete;
  void operator=(const vtkPreIntegrationTable&) = delete;

  // The steps of Update(): settings valid (errors otherwise), inputs older
  // than the tables, the range the tables span.
  bool CheckSettings();
  bool IsUpToDate();
  void ResolveRange(double range[2]);

  class vtkInternals;
  vtkInternals* Internals;
};

#endif
