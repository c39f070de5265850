/**
 * @class   vtkMultiMaterialTextures
 * @brief   The ray caster's lookup textures: pre-integrated segment tables and
 *          the material table, uploaded only when their source changed.
 *
 * Segment tables: RGBA32F n x n (I_c rgb, I_alpha) and R32F n x n (I_beta)
 * from vtkPreIntegrationTable. Material table: RGBA32F n x 3, row 0 =
 * (ka, kd, ks, ke), row 1 = (r, 0, 0, g), row 2 = (e, 0, 0, 0), sampled
 * over the scalar range (the layout of mmv::MaterialParameterTable; the
 * shader reads row r at v = (r + 0.5) / mmv::MaterialTextureRows).
 * Several fields stack their tables along v, field f's above field f - 1's:
 * n x (n F) segment texels and n x (3 F) material texels for F fields.
 * Gradient volume: RGB16F at the data's resolution, the normalised-value
 * gradient per voxel (vtkValueGradient.h), uploaded when the data or its
 * range changed.
 */
#ifndef vtkMultiMaterialTextures_h
#define vtkMultiMaterialTextures_h

#include "vtkKeptStep.h"                  // kept gradients
#include "vtkMultiMaterialVolumeModule.h" // export macro
#include "vtkNew.h"
#include "vtkObject.h"
#include "vtkPixelBufferObject.h" // slab uploads
#include "vtkSmartPointer.h"      // kept gradients
#include "vtkTextureObject.h"     // kept gradients

#include <cstddef>
#include <functional> // table entries
#include <list>       // kept gradients
#include <vector>     // slab scratch

class vtkDataArray;
class vtkMaterialTransferFunction;
class vtkOpenGLRenderWindow;
class vtkPreIntegrationTable;
class vtkTextureObject;
class vtkWindow;

class VTKMULTIMATERIALVOLUME_EXPORT vtkMultiMaterialTextures : public vtkObject
{
public:
  static vtkMultiMaterialTextures* New();
  vtkTypeMacro(vtkMultiMaterialTextures, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Uploads the segment tables, one per field, if any was rebuilt (or the
  /// fields changed) since the last upload. All tables share one size.
  void UpdateSegmentTables(
    vtkOpenGLRenderWindow* context, const std::vector<vtkPreIntegrationTable*>& tables);
  void UpdateSegmentTables(vtkOpenGLRenderWindow* context, vtkPreIntegrationTable* table)
  {
    this->UpdateSegmentTables(context, std::vector<vtkPreIntegrationTable*>{ table });
  }

  /// Uploads the material tables, field f's n entries over ranges[2 f, 2 f + 1],
  /// if a function, a range or n changed. A null function uploads the defaults.
  void UpdateMaterialTable(vtkOpenGLRenderWindow* context,
    const std::vector<vtkMaterialTransferFunction*>& materials, const std::vector<double>& ranges,
    int n);
  void UpdateMaterialTable(vtkOpenGLRenderWindow* context, vtkMaterialTransferFunction* materials,
    const double range[2], int n)
  {
    this->UpdateMaterialTable(context, std::vector<vtkMaterialTransferFunction*>{ materials },
      std::vector<double>{ range[0], range[1] }, n);
  }

  /// Uploads the gradient volume of component 0 of `scalars` (point data of
  /// a `dims` grid) normalised over `range`, if any of them changed. False
  /// when the texture could not be created (too large for the context).
  /// `smoothing`: the Gaussian's standard deviation in voxels per axis
  /// (mmv::SmoothVectors); null or zeros: none.
  bool UpdateGradientTexture(vtkOpenGLRenderWindow* context, vtkDataArray* scalars,
    const int dims[3], const double range[2], double maxTextureBytes = 0.0,
    const double smoothing[3] = nullptr);

  /// GPU memory for the gradient volumes of earlier inputs (the steps of a
  /// series), so data coming back shows its kept copy instead of one
  /// recomputed and uploaded (vtkKeptStep.h says which stay). 0 (the
  /// default): none.
  void SetKeptGradientBytes(size_t bytes);
  vtkGetMacro(KeptGradientHits, int);
  size_t GetKeptGradientBytes() const { return this->KeptBytes; }

  vtkTextureObject* GetSegmentColorTexture() { return this->SegmentColor; }
  /// The gradient volume shown: the own texture, or the kept copy of data
  /// that came back (until the next upload).
  vtkTextureObject* GetGradientTexture()
  {
    return this->ShownGradient ? this->ShownGradient.Get() : this->Gradient.Get();
  }
  /// Texels of the gradient texture: the data's dimensions, or fewer along
  /// axes longer than the largest 3D texture (spanning the same points).
  const int* GetGradientTextureDimensions() const { return this->GradientTextureDimensions; }
  vtkTextureObject* GetSegmentPositionTexture() { return this->SegmentPosition; }
  vtkTextureObject* GetMaterialTexture() { return this->Material; }

  void Activate();
  void Deactivate();

  /// Number of uploads done (segment tables, material table).
  vtkGetMacro(SegmentUploads, int);
  vtkGetMacro(MaterialUploads, int);
  vtkGetMacro(GradientUploads, int);

  /// GPU memory held, in bytes.
  vtkIdType GetMemoryBytes() const;

  void ReleaseGraphicsResources(vtkWindow* window);

protected:
  vtkMultiMaterialTextures();
  ~vtkMultiMaterialTextures() override;

private:
  vtkMultiMaterialTextures(const vtkMultiMaterialTextures&) = delete;
  void operator=(const vtkMultiMaterialTextures&) = delete;

  void UploadTable(vtkOpenGLRenderWindow* context, vtkTextureObject* texture,
    const std::vector<vtkPreIntegrationTable*>& tables, int components, int n, int rows,
    const std::function<const float*(vtkPreIntegrationTable*)>& entries);

  vtkNew<vtkTextureObject> SegmentColor;
  vtkNew<vtkTextureObject> SegmentPosition;
  vtkNew<vtkTextureObject> Material;
  vtkNew<vtkTextureObject> Gradient;
  int GradientUploads = 0;
  struct KeptGradient
  {
    mmv::KeptStepData Data;
    double Range[2] = { 0.0, 0.0 };
    double Smoothing[3] = { 0.0, 0.0, 0.0 };
    int Dimensions[3] = { 0, 0, 0 };
    vtkSmartPointer<vtkTextureObject> Texture;
    size_t Bytes = 0;
    bool CanReturn() const { return this->Data.CanReturn(); }
  };
  bool UploadGradientSlabs(vtkDataArray* scalars, const int dims[3], const double range[2]);
  bool UploadGradientVolume(vtkDataArray* scalars, const int dims[3], const double range[2],
    const double sigma[3], const int textureDims[3]);
  // Scratch of UploadGradientSlabs, kept between steps: the slab's values,
  // the pixel buffer its gradients go to, and its gradients in client memory
  // where that buffer cannot be mapped.
  std::vector<float> SlabValues;
  vtkSmartPointer<vtkPixelBufferObject> SlabBuffer;
  std::vector<unsigned short> SlabHalves;
  bool RestoreKeptGradient(
    vtkDataArray* scalars, const int dims[3], const double range[2], const double smoothing[3]);
  void KeepGradient(vtkOpenGLRenderWindow* context);
  void TrimKeptGradients(size_t bytes);
  void DropKeptGradient(std::list<KeptGradient>::iterator kept);
  std::list<KeptGradient> Kept; // most recently used first
  // A kept copy shown in place of Gradient (RestoreKeptGradient), held here
  // as a trim may drop it from Kept meanwhile.
  vtkSmartPointer<vtkTextureObject> ShownGradient;
  size_t KeptBytes = 0;
  size_t KeptBudget = 0;
  bool GradientKept = false; // Kept holds a copy of the gradient volume shown
  int KeptGradientHits = 0;
  vtkDataArray* UploadedScalars = nullptr;
  vtkMTimeType UploadedScalarsTime = 0;
  double UploadedGradientRange[2] = { 0.0, 0.0 };
  double UploadedGradientSmoothing[3] = { 0.0, 0.0, 0.0 };
  int GradientDimensions[3] = { 0, 0, 0 };
  int GradientTextureDimensions[3] = { 0, 0, 0 };
  int SegmentUploads = 0;
  int MaterialUploads = 0;
  // What the uploaded tables were made of: per field, the table and its
  // build; the functions, their times and ranges.
  std::vector<std::pair<vtkPreIntegrationTable*, int>> UploadedTables;    // builds
  std::vector<std::pair<vtkPreIntegrationTable*, int>> UploadedPositions; // not colour-only
  std::vector<std::pair<vtkMaterialTransferFunction*, vtkMTimeType>> UploadedMaterials;
  std::vector<double> UploadedRanges;
  int UploadedMaterialSize = 0;
  int TableSize = 0;
};

#endif
