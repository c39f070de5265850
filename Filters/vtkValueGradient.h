/**
 * @file   vtkValueGradient.h
 * @brief  The gradient the ray caster shades with, precomputed per voxel.
 *
 * Computing the gradient at every shaded sample by central differences costs
 * six fetches of the data texture, half of a sample's twelve. The
 * gradient is a property of the data alone, so it is computed once per data
 * change here and the shader reads it with one trilinear fetch
 * (Shaders/mmvRayCastDec.glsl, mmvGradient).
 *
 * What is stored: for voxel i, the central difference of the normalised
 * value (value - range[0]) / (range[1] - range[0]) per index unit,
 * (v[i+1] - v[i-1]) / 2 along each axis, with the neighbours clamped to the
 * volume (one-sided halves at the faces, as a clamped texture gives them).
 * Interpolating these trilinearly differs from the central difference of the
 * trilinear field at the sample (what the reference renderer keeps); the
 * difference is part of the image error against the reference
 * (docs/performance.md, "Accuracy against speed").
 */
#ifndef vtkValueGradient_h
#define vtkValueGradient_h

#include "vtkMultiMaterialVolumeFiltersModule.h" // export macro
#include "vtkType.h"

#include <string>
#include <vector>

class vtkDataArray;

namespace mmv
{

/**
 * Fills `gradients` with 3 floats per point of a `dims` grid (x fastest) from
 * component `component` of `scalars`. Non-finite values and their neighbours'
 * differences give 0 along that axis: NaN must not reach the shading.
 * Multithreaded (vtkSMPTools).
 */
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT void ComputeValueGradients(vtkDataArray* scalars,
  int component, const int dims[3], const double range[2], std::vector<float>& gradients);

/**
 * The shading normal's optional smoothing (GradientSmoothing of the mapper):
 * `sigma`, in units of the largest data spacing, as a standard deviation in
 * voxels along each axis, so that the Gaussian is round in world space.
 * Non-finite or negative sigma gives 0 and a reason in `why`; above
 * MaxGradientSmoothing it is clamped, with a reason.
 */
constexpr double MaxGradientSmoothing = 4.0;
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT double ValidGradientSmoothing(double sigma, std::string* why);
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT void GradientSmoothingVoxels(
  double sigma, const double spacing[3], double voxels[3]);

/**
 * Blurs `values` (`components` floats per point of a `dims` grid, x fastest)
 * by a separable Gaussian of `sigma[a]` voxels along axis a, truncated at
 * 3 sigma, the volume's faces repeated outward; axes with sigma 0 are left
 * alone. The gradient of thin shells sampled coarsely (the MR head's 3.2 mm
 * in x and y) turns at every voxel face; in the image that shows as stripes
 * at the voxel spacing (docs/stability.md, "Stripes on thin shells"), which a sigma of one voxel
 * removes.
 */
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT void SmoothVectors(
  std::vector<float>& values, int components, const int dims[3], const double sigma[3]);

/**
 * `values` (`components` floats per point of a `dims` grid, x fastest)
 * resampled trilinearly to a `newDims` grid spanning the same points (point j
 * of an axis at old point j (dims - 1) / (newDims - 1)).
 */
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT std::vector<float> ResampleVectors(
  const std::vector<float>& values, int components, const int dims[3], const int newDims[3]);

/**
 * Slices [firstSlice, lastSlice] (along z) of
 * PackHalfFloats(ComputeValueGradients(...)), bit for bit, into `halves`
 * (resized to 3 per voxel of those slices, x fastest): the gradient texture
 * is uploaded a slab at a time, so no buffer of the whole volume is made.
 * `values` is scratch (the normalised values of the slab and the slices on
 * either side), kept by the caller between slabs. Multithreaded.
 */
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT void ComputeHalfValueGradients(vtkDataArray* scalars,
  int component, const int dims[3], const double range[2], int firstSlice, int lastSlice,
  std::vector<float>& values, std::vector<unsigned short>& halves);
/// The same into `halves`, which holds 3 per voxel of those slices (a
/// mapped pixel buffer, say).
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT void ComputeHalfValueGradients(vtkDataArray* scalars,
  int component, const int dims[3], const double range[2], int firstSlice, int lastSlice,
  std::vector<float>& values, unsigned short* halves);

/// The values as IEEE half floats (GL_HALF_FLOAT), converted on every core:
/// the gradient texture is RGB16F, and a driver given 32-bit floats converts
/// them on one thread.
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT std::vector<unsigned short> PackHalfFloats(
  const std::vector<float>& values);
} // namespace mmv

#endif
