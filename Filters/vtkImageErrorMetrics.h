/**
 * @class   vtkImageErrorMetrics
 * @brief   RMSE, PSNR and SSIM between a test image and a reference, and an
 *          error heat map.
 *
 * Images are 2D vtkImageData (x by y by 1) with point scalars of 1 (gray),
 * 3 (RGB) or 4 (RGBA, alpha ignored) components; both must have the same
 * size and component count. Values are compared in the images' own units, so
 * the peak is 255 for unsigned char images and 1 otherwise (floats in
 * [0, 1]) unless Peak is set.
 *
 *  - RMSE: root mean square difference over every pixel and colour channel.
 *  - PSNR: 20 log10(peak / RMSE) in dB; +infinity for identical images.
 *  - SSIM (Wang, Bovik, Sheikh & Simoncelli 2004): Gaussian window 11 x 11
 *    with sigma 1.5 (normalised), K1 = 0.01, K2 = 0.03, dynamic range = peak,
 *    averaged over the window positions that fit inside the image (the
 *    "valid" region; images need at least 11 x 11 pixels). Computed on the
 *    luminance Y = 0.299 R + 0.587 G + 0.114 B by default (like the authors'
 *    code on rgb2gray images), or per channel and averaged (SSIMMode).
 *
 * The heat map is |difference| (largest over the channels) mapped through a
 * black-purple-red-yellow-white scale from 0 to a chosen maximum, written as
 * an 8-bit RGB PNG by a small built-in encoder (no image I/O dependency).
 */
#ifndef vtkImageErrorMetrics_h
#define vtkImageErrorMetrics_h

#include "vtkMultiMaterialVolumeFiltersModule.h" // export macro
#include "vtkObject.h"
#include "vtkSmartPointer.h" // return type

class vtkImageData;

class VTKMULTIMATERIALVOLUMEFILTERS_EXPORT vtkImageErrorMetrics : public vtkObject
{
public:
  static vtkImageErrorMetrics* New();
  vtkTypeMacro(vtkImageErrorMetrics, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum SSIMModes
  {
    SSIM_LUMINANCE = 0,
    SSIM_PER_CHANNEL = 1
  };

  /// How SSIM treats colour (default SSIM_LUMINANCE).
  vtkSetClampMacro(SSIMMode, int, SSIM_LUMINANCE, SSIM_PER_CHANNEL);
  vtkGetMacro(SSIMMode, int);
  void SetSSIMModeToLuminance() { this->SetSSIMMode(SSIM_LUMINANCE); }
  void SetSSIMModeToPerChannel() { this->SetSSIMMode(SSIM_PER_CHANNEL); }

  /// Peak signal value; 0 (default) means 255 for unsigned char, else 1.
  vtkSetClampMacro(Peak, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(Peak, double);

  /**
   * Compares `test` with `reference`. Returns false (with an error, results
   * left at NaN) when an image is missing or lacks scalars, or when the sizes
   * or component counts differ.
   */
  bool Compute(vtkImageData* test, vtkImageData* reference);

  ///@{
  /// Results of the last Compute().
  vtkGetMacro(RMSE, double);
  vtkGetMacro(PSNR, double);
  vtkGetMacro(SSIM, double);
  vtkGetMacro(MaximumError, double);
  vtkGetMacro(PeakUsed, double);
  ///@}

  /**
   * The heat map of |test - reference| as unsigned-char RGB (same size),
   * `maxError` (image units) mapping to white; maxError <= 0 uses the
   * largest difference. Null (with an error) for mismatched images.
   */
  vtkSmartPointer<vtkImageData> ErrorHeatMap(
    vtkImageData* test, vtkImageData* reference, double maxError = 0.0);

  /// ErrorHeatMap() written to a PNG file; returns success.
  bool WriteErrorHeatMap(
    const char* fileName, vtkImageData* test, vtkImageData* reference, double maxError = 0.0);

  /// Writes the first three (or the one) unsigned-char components of a 2D
  /// image as an RGB PNG, top row first as viewers expect. Returns success.
  static bool WritePNG(const char* fileName, vtkImageData* image);

protected:
  vtkImageErrorMetrics();
  ~vtkImageErrorMetrics() override;

  int SSIMMode = SSIM_LUMINANCE;
  double Peak = 0.0;
  double RMSE;
  double PSNR;
  double SSIM;
  double MaximumError;
  double PeakUsed;

private:
  vtkImageErrorMetrics(const vtkImageErrorMetrics&) = delete;
  void operator=(const vtkImageErrorMetrics&) = delete;
};

#endif
