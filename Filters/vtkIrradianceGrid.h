/**
 * @file   vtkIrradianceGrid.h
 * @brief  Geometry and pre-filtered data of the irradiance volume, shared by
 *         the CPU filter (vtkIrradianceVolumeFilter) and the GPU estimator
 *         (vtkIrradianceEstimator) so both estimate irradiance on the same grid
 *         from the same samples.
 *
 * The grid spans the same bounds as the data's points: voxel (0,0,0) sits on
 * the data's first point and the last voxel on its last point, so
 * spacing = (dataDims - 1) * dataSpacing / (dims - 1) per axis (an axis of one
 * voxel keeps the data spacing). Positions are in the image's physical
 * (object) space, direction matrix included.
 */
#ifndef vtkIrradianceGrid_h
#define vtkIrradianceGrid_h

#include "vtkMultiMaterialVolumeFiltersModule.h" // export macro
#include "vtkType.h"                             // vtkIdType

#include <glm/glm.hpp>

#include <algorithm> // std::equal

#include <string>
#include <vector>

class vtkDataArray;
class vtkImageData;

namespace mmv
{

struct IrradianceGrid
{
  int Dimensions[3] = { 0, 0, 0 };
  glm::dvec3 Origin{ 0.0 };             // physical position of voxel (0,0,0)
  glm::dvec3 Spacing{ 1.0 };            // along the index axes
  glm::dmat3 Direction{ 1.0 };          // columns: index axes in physical space
  glm::dvec3 DataVoxelsPerVoxel{ 1.0 }; // irradiance spacing / data spacing

  vtkIdType GetNumberOfVoxels() const
  {
    return static_cast<vtkIdType>(this->Dimensions[0]) * this->Dimensions[1] * this->Dimensions[2];
  }
  /// The same voxels in the same place: dimensions, origin, spacing and
  /// direction (DataVoxelsPerVoxel follows from them and the data).
  bool IsSameGrid(const IrradianceGrid& o) const
  {
    return std::equal(this->Dimensions, this->Dimensions + 3, o.Dimensions) &&
      this->Origin == o.Origin && this->Spacing == o.Spacing && this->Direction == o.Direction;
  }
  /// The integer index of voxel `v` (x fastest), as doubles for the maps below.
  glm::dvec3 IndexOfVoxel(vtkIdType v) const
  {
    const vtkIdType nx = this->Dimensions[0];
    const vtkIdType nxy = nx * this->Dimensions[1];
    return glm::dvec3(static_cast<double>(v % nx),
      static_cast<double>((v / nx) % this->Dimensions[1]), static_cast<double>(v / nxy));
  }
  /// Linear part of the index -> physical map: Direction * diag(Spacing).
  glm::dmat3 IndexToPhysicalMatrix() const
  {
    return this->Direction *
      glm::dmat3(glm::dvec3(this->Spacing[0], 0.0, 0.0), glm::dvec3(0.0, this->Spacing[1], 0.0),
        glm::dvec3(0.0, 0.0, this->Spacing[2]));
  }
  /// Physical position of the grid's centre.
  glm::dvec3 Center() const
  {
    return this->IndexToPhysical(
      0.5 * (glm::dvec3(this->Dimensions[0], this->Dimensions[1], this->Dimensions[2]) - 1.0));
  }
  /// Its inverse: a true inverse, since VTK allows non-orthonormal directions.
  glm::dmat3 PhysicalToIndexMatrix() const { return glm::inverse(this->IndexToPhysicalMatrix()); }
  glm::dvec3 IndexToPhysical(const glm::dvec3& ijk) const
  {
    return this->Origin + this->IndexToPhysicalMatrix() * ijk;
  }
  glm::dvec3 PhysicalToIndex(const glm::dvec3& p) const
  {
    return this->PhysicalToIndexMatrix() * (p - this->Origin);
  }
};

/// Lights an irradiance texture holds, one per channel.
constexpr int IrradianceLightsPerTexture = 4;

/// Channels of the 16-bit irradiance texture that holds `lights` (1-4)
/// lights: R16, RG16, else RGBA16 (RGB16 is not colour-renderable in core
/// OpenGL, so three lights take four channels).
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT int IrradianceTextureChannels(int lights);

/// Bytes per voxel that the irradiance textures of `numberOfLights` lights
/// hold: four lights to a texture, the last with IrradianceTextureChannels
/// of the rest, IrradianceBytesPerVoxelPerLight per channel (the GPU's
/// memory, what the budget counts).
/// `tinted`: plus each light's tint (a non-white transmission colour),
/// mmv::TintBytesPerVoxelPerLight.
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT double IrradianceBytesPerVoxel(
  int numberOfLights, bool tinted = false);

/**
 * Irradiance dimensions for data of `dataDims` points: `scale` in (0, 1]
 * scales every axis; scale <= 0 picks the largest scale whose
 * IrradianceBytesPerVoxel(numberOfLights) fit `budgetMB`. Axes never exceed
 * the data's and never drop below min(2, data).
 */
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT void ComputeIrradianceDimensions(const int dataDims[3],
  int numberOfLights, double budgetMB, double scale, int irradianceDims[3], bool tinted = false);

/// Checks an IrradianceScale (0: automatic; (0, 1]: that fraction of the
/// data's resolution): above 1 returns 1, negative or NaN returns 0, and
/// `why` (if given) says so; valid values come back unchanged.
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT double ValidIrradianceScale(double scale, std::string* why);

/// Checks an IrradianceErrorBound (dB; 0: no error probe): NaN or negative
/// returns 0, above mmv::MaxIrradianceErrorBoundDB returns that maximum, and
/// `why` (if given) says so; valid values come back unchanged.
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT double ValidIrradianceErrorBound(
  double bound, std::string* why);

/// The irradiance resolution a frame uses, and why (for logs and the UI).
struct IrradianceResolution
{
  int Dimensions[3] = { 0, 0, 0 };
  double Scale = 1.0; // the scale applied to every axis
  std::string Reason;
};

/**
 * Models no more than the image can show:
 *  - userScale > 0: that scale, as ComputeIrradianceDimensions applies it;
 *  - otherwise the coarser of the memory budget's scale and the screen's:
 *    an irradiance voxel need not cover fewer than
 *    mmv::PixelsPerIrradianceVoxel pixels, so with `pixelsPerDataVoxel`
 *    pixels per data voxel the scale is pixelsPerDataVoxel /
 *    PixelsPerIrradianceVoxel, rounded up to quarter octaves (2^(k/4)) so
 *    that small zooms keep the grid. pixelsPerDataVoxel <= 0 (unknown, e.g.
 *    no camera) leaves the budget alone in charge.
 */
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT IrradianceResolution ChooseIrradianceResolution(
  const int dataDims[3], int numberOfLights, double budgetMB, double userScale,
  double pixelsPerDataVoxel, bool tinted = false);

/// The grid of `irradianceDims` spanning `image`'s points.
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT IrradianceGrid MakeIrradianceGrid(
  vtkImageData* image, const int irradianceDims[3]);

/**
 * The same from image geometry alone (e.g. pipeline information, before the
 * data exists): `direction` is row-major like vtkImageData's; null means
 * identity.
 */
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT IrradianceGrid MakeIrradianceGrid(const int extent[6],
  const double origin[3], const double spacing[3], const double* direction,
  const int irradianceDims[3]);

/**
 * Trilinear interpolation of `values` (one per voxel, x fastest) at the
 * continuous index `index`, clamped to the grid. The prefilter samples the
 * data this way and the CPU shadow rays sample the prefiltered values; the
 * GPU pass gets the same from a linear 3D texture.
 */
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT double SampleTrilinear(
  const IrradianceGrid& grid, const float* values, const glm::dvec3& index);

/**
 * Narrows [t0, t1] to the parameters where p + t d lies in the box of voxel
 * centres [0, dims - 1] (index space; the slab test); false when the line
 * misses it there. The CPU renderers' rays and the scene shadows' marches
 * clip with it.
 */
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT bool ClipToIndexBox(
  const glm::dvec3& p, const glm::dvec3& d, const int dims[3], double& t0, double& t1);

/// One component of the scalars as floats (read through the array's own type).
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT std::vector<float> CopyComponent(
  vtkDataArray* scalars, int component);
/// The same into `values` (resized; its memory reused).
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT void CopyComponent(
  vtkDataArray* scalars, int component, std::vector<float>& values);
/// Tuples [first, first + count) into `values` (resized; its memory reused).
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT void CopyComponent(vtkDataArray* scalars, int component,
  vtkIdType first, vtkIdType count, std::vector<float>& values);
/// Tuples [first, first + count) of one component mapped to
/// (v - range[0]) / (range[1] - range[0]) (0 for an empty range) into
/// `values`, which must hold `count` floats; NaN stays NaN.
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT void NormalizeComponent(vtkDataArray* scalars, int component,
  vtkIdType first, vtkIdType count, const double range[2], float* values);

/**
 * Where PrefilterScalars samples the data: voxel j's footprint is centred on
 * the data's continuous index j * Ratio and holds Samples points per axis
 * (midpoint rule over one irradiance spacing; one sample, the data point
 * itself, where the grid equals the data grid).
 */
struct FootprintLayout
{
  double Ratio[3] = { 0.0, 0.0, 0.0 }; // data points per irradiance voxel
  int Samples[3] = { 1, 1, 1 };
};
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT FootprintLayout MakeFootprintLayout(
  const int dataDims[3], const int gridDims[3]);
/// Sample q (0 <= q[a] < Samples[a]) of the footprint of the voxel at
/// integer index `voxel`, as a continuous data index (not clamped).
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT glm::dvec3 FootprintSample(
  const FootprintLayout& layout, const glm::dvec3& voxel, const int q[3]);

/**
 * The buffers PrefilterScalars works in, a slab of slices in size (the
 * values as floats, filtered along x, then along y), kept by a caller that
 * filters step after step: on some machines fresh memory costs more than
 * the filtering.
 */
struct PrefilterScratch
{
  vtkIdType SlabPoints = 1 << 21; // data points per slab (at least one slice)
  std::vector<float> Values;
  std::vector<double> AlongX;
  std::vector<double> AlongY;
};

/**
 * Box-filters component `component` of `scalars` (point data of `image`) over
 * each grid voxel's footprint (trilinear samples on a regular sub-grid,
 * clamped to the data bounds); an exact copy when the grid equals the data
 * grid. Values stay in data units. Multithreaded (vtkSMPTools). `scratch`:
 * the buffers to reuse (null: new ones).
 */
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT void PrefilterScalars(vtkImageData* image,
  vtkDataArray* scalars, int component, const IrradianceGrid& grid, std::vector<float>& prefiltered,
  PrefilterScratch* scratch = nullptr);

/**
 * NaN and -Inf in `values` become `low`, +Inf becomes `high` (the finite
 * range's ends), so that no table lookup reads out of bounds; returns
 * whether any value was replaced. Both the mapper and the CPU filter clean
 * their pre-filtered values with it and report NonFiniteScalarsMessage.
 */
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT bool ReplaceNonFinite(
  std::vector<float>& values, float low, float high);
/// What a user is told when ReplaceNonFinite replaced values.
constexpr const char* NonFiniteScalarsMessage =
  "the scalars contain NaN or Inf: NaN and -Inf are lit as the finite minimum, +Inf as the "
  "maximum";

} // namespace mmv

#endif
