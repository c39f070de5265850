/**
 * @file   vtkCombinedFieldExtinction.h
 * @brief  Several fields on one grid (the components of one array, each with
 *         its own opacity and materials) as the one medium the lighting sees.
 *
 * Light does not know which field absorbs it: the shadow extinction at a
 * point is the sum of every field's, c_t,f(v_f) sigma_f(v_f), with
 * sigma_f = -ln(1 - alpha_f) / u_f from field f's opacity alpha_f per its
 * unit distance u_f. The lighting (pre-filter, shadows, diffusion, gradient)
 * runs on one derived field, the opacity of that sum over one object unit,
 *
 *     D = 1 - exp(-sum_f c_t,f sigma_f) = 1 - prod_f (1 - alpha_f)^(c_t,f / u_f),
 *
 * read through the identity opacity function (unit distance 1, attenuation
 * 1), so that its extinction is the sum again. D is bounded (an opaque field
 * gives D = 1) and, for one field with a linear opacity ramp from 0, it is
 * that field's own opacity: fields that do not overlap cast the shadows
 * the same data as one field would.
 *
 * Multiple scattering diffuses with the fields' scattering s_f mixed by
 * their opacity; the diffusion reads it per value of D, as the
 * opacity-weighted mean over the voxels of each bin of D (exact where the
 * scattering fields share one s, or where they do not share a bin of D).
 */
#ifndef vtkCombinedFieldExtinction_h
#define vtkCombinedFieldExtinction_h

#include "vtkMultiMaterialVolumeFiltersModule.h" // export macro

#include <string>
#include <vector>

class vtkDataArray;
class vtkFloatArray;

namespace mmv
{

/// Fields one array can carry (VTK's volume property maps at most 4
/// independent components).
constexpr int MaxFields = 4;

/// One field's optics as the lighting reads them, sampled at n values over
/// the field's range (component f of the array). A voxel's value reads each
/// field's shadow extinction c_t sigma interpolated linearly between the
/// entries (with n as large as the pre-integration tables, the opacity
/// function is resolved as finely as they resolve it).
struct FieldOptics
{
  double Range[2] = { 0.0, 1.0 };
  std::vector<float> Opacity;     ///< alpha per UnitDistance
  std::vector<float> Attenuation; ///< c_t
  std::vector<float> Scattering;  ///< s (data voxel^2)
  double UnitDistance = 1.0;
};

/**
 * D for every tuple of `fields` (component f read through optics[f]) into
 * `opacity` (one component, resized; its memory is reused), and into
 * `scattering` s per value of D: `bins` entries over [0, 1], the
 * opacity-weighted mean of the fields' s over the voxels of each bin (a bin
 * no voxel fell into interpolates its filled neighbours); empty when no
 * field scatters. False, with `error` set, when the array's components and
 * the optics differ in number, there are more than MaxFields, or a table is
 * empty. NaN reads as the lowest value of its field, as the single-field
 * lighting reads it.
 */
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT bool CombineFieldExtinction(vtkDataArray* fields,
  const std::vector<FieldOptics>& optics, int bins, vtkFloatArray* opacity,
  std::vector<float>& scattering, std::string* error);

/// D of one tuple of raw values (the formula above; the tests' closed form).
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT float CombinedOpacity(
  const double* values, const std::vector<FieldOptics>& optics);

} // namespace mmv

#endif
