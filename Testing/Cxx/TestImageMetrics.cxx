// vtkImageErrorMetrics: RMSE / PSNR / SSIM on images with known answers,
// input validation and the heat-map PNG.
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkImageErrorMetrics.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

namespace
{
// A w x h RGB float image with channel values f(x, y, c).
vtkSmartPointer<vtkImageData> FloatImage(
  int w, int h, const std::function<double(int, int, int)>& f)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(w, h, 1);
  vtkNew<vtkFloatArray> rgb;
  rgb->SetNumberOfComponents(3);
  rgb->SetNumberOfTuples(static_cast<vtkIdType>(w) * h);
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < w; ++x)
    {
      for (int c = 0; c < 3; ++c)
      {
        rgb->SetComponent(static_cast<vtkIdType>(y) * w + x, c, f(x, y, c));
      }
    }
  }
  image->GetPointData()->SetScalars(rgb);
  return image;
}

vtkSmartPointer<vtkImageData> ByteImage(int w, int h, const std::function<int(int, int, int)>& f)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(w, h, 1);
  vtkNew<vtkUnsignedCharArray> rgb;
  rgb->SetNumberOfComponents(3);
  rgb->SetNumberOfTuples(static_cast<vtkIdType>(w) * h);
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < w; ++x)
    {
      for (int c = 0; c < 3; ++c)
      {
        rgb->SetValue(
          (static_cast<vtkIdType>(y) * w + x) * 3 + c, static_cast<unsigned char>(f(x, y, c)));
      }
    }
  }
  image->GetPointData()->SetScalars(rgb);
  return image;
}

// A structured test pattern in [0.1, 0.9]: checkerboard plus waves, on
// multiples of 1/256 so that float storage and offsets are exact.
double Pattern(int x, int y, int c)
{
  const double checker = ((x / 4 + y / 4) % 2) ? 0.3 : -0.3;
  const double v = 0.5 + checker + 0.1 * std::sin(0.3 * x + c) * std::cos(0.2 * y);
  return std::round(v * 256.0) / 256.0;
}

// The pattern blurred by a (2r+1)^2 box filter (clamped at the border).
vtkSmartPointer<vtkImageData> Blurred(int size, int r)
{
  return FloatImage(size, size,
    [size, r](int x, int y, int c)
    {
      double s = 0.0;
      int n = 0;
      for (int dy = -r; dy <= r; ++dy)
      {
        for (int dx = -r; dx <= r; ++dx)
        {
          const int xx = std::min(std::max(x + dx, 0), size - 1);
          const int yy = std::min(std::max(y + dy, 0), size - 1);
          s += Pattern(xx, yy, c);
          ++n;
        }
      }
      return s / n;
    });
}
}

TEST(ImageErrorMetrics, IdenticalImages)
{
  auto a = FloatImage(32, 24, Pattern);
  auto b = FloatImage(32, 24, Pattern);
  vtkNew<vtkImageErrorMetrics> metrics;
  ASSERT_TRUE(metrics->Compute(a, b));
  EXPECT_EQ(metrics->GetRMSE(), 0.0);
  EXPECT_TRUE(std::isinf(metrics->GetPSNR()) && metrics->GetPSNR() > 0.0);
  EXPECT_NEAR(metrics->GetSSIM(), 1.0, 1e-12);
  EXPECT_EQ(metrics->GetMaximumError(), 0.0);
  metrics->SetSSIMModeToPerChannel();
  ASSERT_TRUE(metrics->Compute(a, b));
  EXPECT_NEAR(metrics->GetSSIM(), 1.0, 1e-12);
}

TEST(ImageErrorMetrics, ConstantOffsetFloat)
{
  const double offset = 0.0625; // exact in binary: RMSE is exact too
  auto a = FloatImage(32, 32, Pattern);
  auto b = FloatImage(32, 32, [offset](int x, int y, int c) { return Pattern(x, y, c) + offset; });
  vtkNew<vtkImageErrorMetrics> metrics;
  ASSERT_TRUE(metrics->Compute(a, b));
  EXPECT_EQ(metrics->GetRMSE(), offset);
  EXPECT_DOUBLE_EQ(metrics->GetPSNR(), 20.0 * std::log10(1.0 / offset));
  EXPECT_EQ(metrics->GetPeakUsed(), 1.0);
  // An offset changes only the luminance term of SSIM: below 1, well above 0.
  EXPECT_LT(metrics->GetSSIM(), 1.0);
  EXPECT_GT(metrics->GetSSIM(), 0.9);
}

TEST(ImageErrorMetrics, ConstantOffsetBytes)
{
  auto a = ByteImage(20, 16, [](int x, int y, int c) { return (x * 7 + y * 3 + c * 40) % 200; });
  auto b =
    ByteImage(20, 16, [](int x, int y, int c) { return (x * 7 + y * 3 + c * 40) % 200 + 5; });
  vtkNew<vtkImageErrorMetrics> metrics;
  ASSERT_TRUE(metrics->Compute(b, a));
  EXPECT_DOUBLE_EQ(metrics->GetRMSE(), 5.0);
  EXPECT_DOUBLE_EQ(metrics->GetPSNR(), 20.0 * std::log10(255.0 / 5.0));
  EXPECT_EQ(metrics->GetPeakUsed(), 255.0);
  EXPECT_EQ(metrics->GetMaximumError(), 5.0);
}

TEST(ImageErrorMetrics, StrongerBlurLowersSSIM)
{
  constexpr int size = 48;
  auto sharp = FloatImage(size, size, Pattern);
  vtkNew<vtkImageErrorMetrics> metrics;
  for (int mode : { vtkImageErrorMetrics::SSIM_LUMINANCE, vtkImageErrorMetrics::SSIM_PER_CHANNEL })
  {
    metrics->SetSSIMMode(mode);
    double previous = 1.0;
    for (int r : { 1, 2, 4 })
    {
      ASSERT_TRUE(metrics->Compute(Blurred(size, r), sharp));
      const double ssim = metrics->GetSSIM();
      EXPECT_GT(ssim, 0.0) << "radius " << r;
      EXPECT_LT(ssim, 1.0) << "radius " << r;
      EXPECT_LT(ssim, previous) << "radius " << r;
      previous = ssim;
    }
  }
}

TEST(ImageErrorMetrics, MismatchedImagesAreErrors)
{
  vtkObject::GlobalWarningDisplayOff();
  vtkNew<vtkImageErrorMetrics> metrics;
  auto a = FloatImage(32, 32, Pattern);
  auto b = FloatImage(32, 31, Pattern);
  EXPECT_FALSE(metrics->Compute(a, b));
  EXPECT_TRUE(std::isnan(metrics->GetRMSE()));
  EXPECT_TRUE(std::isnan(metrics->GetSSIM()));
  EXPECT_FALSE(metrics->Compute(a, nullptr));
  vtkNew<vtkImageData> empty;
  empty->SetDimensions(32, 32, 1);
  EXPECT_FALSE(metrics->Compute(a, empty));
  auto gray = vtkSmartPointer<vtkImageData>::New();
  gray->SetDimensions(32, 32, 1);
  vtkNew<vtkDoubleArray> values;
  values->SetNumberOfTuples(32 * 32);
  values->FillValue(0.5);
  gray->GetPointData()->SetScalars(values);
  EXPECT_FALSE(metrics->Compute(a, gray));
  EXPECT_EQ(metrics->ErrorHeatMap(a, b), nullptr);
  vtkObject::GlobalWarningDisplayOn();
}

TEST(ImageErrorMetrics, HeatMapPNG)
{
  auto a = ByteImage(16, 12, [](int, int, int) { return 100; });
  auto b = ByteImage(16, 12, [](int x, int, int) { return 100 + 10 * x; });
  vtkNew<vtkImageErrorMetrics> metrics;
  vtkSmartPointer<vtkImageData> map = metrics->ErrorHeatMap(a, b, 150.0);
  ASSERT_NE(map, nullptr);
  auto* colors = vtkUnsignedCharArray::SafeDownCast(map->GetPointData()->GetScalars());
  ASSERT_NE(colors, nullptr);
  // No error is black, the largest (150) white.
  EXPECT_EQ(colors->GetValue(0), 0);
  EXPECT_EQ(colors->GetValue(3 * 15), 255);
  EXPECT_EQ(colors->GetValue(3 * 15 + 2), 255);

  const std::string path = ::testing::TempDir() + "mmv_heatmap.png";
  ASSERT_TRUE(metrics->WriteErrorHeatMap(path.c_str(), a, b));
  std::ifstream file(path, std::ios::binary);
  const std::vector<unsigned char> bytes(
    (std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  ASSERT_GT(bytes.size(), 16u * 12u * 3u);
  const unsigned char signature[8] = { 0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n' };
  EXPECT_TRUE(std::equal(signature, signature + 8, bytes.begin()));
  EXPECT_EQ(std::string(bytes.begin() + 12, bytes.begin() + 16), "IHDR");
  EXPECT_EQ(bytes[19], 16); // width, big-endian
  EXPECT_EQ(bytes[23], 12); // height
  std::remove(path.c_str());
}
