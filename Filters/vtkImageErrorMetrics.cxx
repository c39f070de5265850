#include "vtkImageErrorMetrics.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkImageErrorMetrics);

namespace
{
constexpr int Window = 11;
constexpr double WindowSigma = 1.5;
constexpr double K1 = 0.01;
constexpr double K2 = 0.03;

// An image's colour channels as planes of doubles, x fastest.
struct Planes
{
  int Width = 0;
  int Height = 0;
  int Channels = 0;
  bool Bytes = false;
  std::vector<std::vector<double>> Data;
};

bool Extract(vtkImageData* image, Planes& planes, std::string& why)
{
  vtkDataArray* scalars = image ? image->GetPointData()->GetScalars() : nullptr;
  if (!scalars)
  {
    why = "an image is missing or has no point scalars";
    return false;
  }
  int dims[3];
  image->GetDimensions(dims);
  if (dims[2] != 1)
  {
    why = "images must be 2D (one slice)";
    return false;
  }
  const int nc = scalars->GetNumberOfComponents();
  planes.Width = dims[0];
  planes.Height = dims[1];
  planes.Channels = nc >= 3 ? 3 : 1; // alpha (4th or 2nd component) is ignored
  planes.Bytes = scalars->GetDataType() == VTK_UNSIGNED_CHAR;
  const vtkIdType n = scalars->GetNumberOfTuples();
  planes.Data.assign(planes.Channels, std::vector<double>(n));
  for (int c = 0; c < planes.Channels; ++c)
  {
    for (vtkIdType i = 0; i < n; ++i)
    {
      planes.Data[c][i] = scalars->GetComponent(i, c);
    }
  }
  return true;
}

bool ExtractPair(
  vtkImageData* test, vtkImageData* reference, Planes& a, Planes& b, std::string& why)
{
  if (!Extract(test, a, why) || !Extract(reference, b, why))
  {
    return false;
  }
  if (a.Width != b.Width || a.Height != b.Height)
  {
    why = "image sizes differ (" + std::to_string(a.Width) + "x" + std::to_string(a.Height) +
      " vs " + std::to_string(b.Width) + "x" + std::to_string(b.Height) + ")";
    return false;
  }
  if (a.Channels != b.Channels)
  {
    why = "one image is gray and the other colour";
    return false;
  }
  return true;
}

std::vector<double> Luminance(const Planes& p)
{
  if (p.Channels == 1)
  {
    return p.Data[0];
  }
  std::vector<double> y(p.Data[0].size());
  for (size_t i = 0; i < y.size(); ++i)
  {
    y[i] = 0.299 * p.Data[0][i] + 0.587 * p.Data[1][i] + 0.114 * p.Data[2][i];
  }
  return y;
}

// Separable Gaussian filter keeping only the positions where the whole
// window fits ("valid"): (w - 10) x (h - 10) outputs.
std::vector<double> FilterValid(const std::vector<double>& in, int w, int h)
{
  std::array<double, Window> g;
  double sum = 0.0;
  for (int i = 0; i < Window; ++i)
  {
    const double x = i - Window / 2;
    g[i] = std::exp(-x * x / (2.0 * WindowSigma * WindowSigma));
    sum += g[i];
  }
  for (double& v : g)
  {
    v /= sum;
  }
  const int ow = w - Window + 1;
  const int oh = h - Window + 1;
  std::vector<double> rows(static_cast<size_t>(ow) * h);
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < ow; ++x)
    {
      double s = 0.0;
      for (int k = 0; k < Window; ++k)
      {
        s += g[k] * in[static_cast<size_t>(y) * w + x + k];
      }
      rows[static_cast<size_t>(y) * ow + x] = s;
    }
  }
  std::vector<double> out(static_cast<size_t>(ow) * oh);
  for (int y = 0; y < oh; ++y)
  {
    for (int x = 0; x < ow; ++x)
    {
      double s = 0.0;
      for (int k = 0; k < Window; ++k)
      {
        s += g[k] * rows[static_cast<size_t>(y + k) * ow + x];
      }
      out[static_cast<size_t>(y) * ow + x] = s;
    }
  }
  return out;
}

// Mean SSIM of two planes with dynamic range `peak`.
double MeanSSIM(
  const std::vector<double>& x, const std::vector<double>& y, int w, int h, double peak)
{
  const size_t n = x.size();
  std::vector<double> xx(n), yy(n), xy(n);
  for (size_t i = 0; i < n; ++i)
  {
    xx[i] = x[i] * x[i];
    yy[i] = y[i] * y[i];
    xy[i] = x[i] * y[i];
  }
  const std::vector<double> mx = FilterValid(x, w, h);
  const std::vector<double> my = FilterValid(y, w, h);
  const std::vector<double> exx = FilterValid(xx, w, h);
  const std::vector<double> eyy = FilterValid(yy, w, h);
  const std::vector<double> exy = FilterValid(xy, w, h);
  const double c1 = (K1 * peak) * (K1 * peak);
  const double c2 = (K2 * peak) * (K2 * peak);
  double sum = 0.0;
  for (size_t i = 0; i < mx.size(); ++i)
  {
    const double vx = exx[i] - mx[i] * mx[i];
    const double vy = eyy[i] - my[i] * my[i];
    const double cxy = exy[i] - mx[i] * my[i];
    sum += ((2.0 * mx[i] * my[i] + c1) * (2.0 * cxy + c2)) /
      ((mx[i] * mx[i] + my[i] * my[i] + c1) * (vx + vy + c2));
  }
  return sum / static_cast<double>(mx.size());
}

// Black -> purple -> red -> yellow -> white, x in [0, 1].
void HeatColor(double x, unsigned char rgb[3])
{
  static const double stops[5][3] = { { 0, 0, 0 }, { 0.45, 0.05, 0.55 }, { 0.9, 0.15, 0.1 },
    { 1.0, 0.85, 0.0 }, { 1, 1, 1 } };
  x = std::min(std::max(x, 0.0), 1.0) * 4.0;
  const int i = std::min(static_cast<int>(x), 3);
  const double f = x - i;
  for (int c = 0; c < 3; ++c)
  {
    const double v = (1.0 - f) * stops[i][c] + f * stops[i + 1][c];
    rgb[c] = static_cast<unsigned char>(std::lround(v * 255.0));
  }
}

uint32_t Crc32(const unsigned char* data, size_t n, uint32_t crc = 0)
{
  static const std::array<uint32_t, 256> table = []
  {
    std::array<uint32_t, 256> t{};
    for (uint32_t i = 0; i < 256; ++i)
    {
      uint32_t c = i;
      for (int k = 0; k < 8; ++k)
      {
        c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      }
      t[i] = c;
    }
    return t;
  }();
  crc = ~crc;
  for (size_t i = 0; i < n; ++i)
  {
    crc = table[(crc ^ data[i]) & 0xFF] ^ (crc >> 8);
  }
  return ~crc;
}

void PutU32(std::vector<unsigned char>& out, uint32_t v)
{
  out.push_back(static_cast<unsigned char>(v >> 24));
  out.push_back(static_cast<unsigned char>(v >> 16));
  out.push_back(static_cast<unsigned char>(v >> 8));
  out.push_back(static_cast<unsigned char>(v));
}

void PutChunk(
  std::vector<unsigned char>& out, const char type[4], const std::vector<unsigned char>& data)
{
  PutU32(out, static_cast<uint32_t>(data.size()));
  const size_t start = out.size();
  out.insert(out.end(), type, type + 4);
  out.insert(out.end(), data.begin(), data.end());
  PutU32(out, Crc32(out.data() + start, out.size() - start));
}
}

vtkImageErrorMetrics::vtkImageErrorMetrics()
{
  this->RMSE = this->PSNR = this->SSIM = this->MaximumError = this->PeakUsed =
    std::numeric_limits<double>::quiet_NaN();
}

vtkImageErrorMetrics::~vtkImageErrorMetrics() = default;

bool vtkImageErrorMetrics::Compute(vtkImageData* test, vtkImageData* reference)
{
  this->RMSE = this->PSNR = this->SSIM = this->MaximumError = this->PeakUsed =
    std::numeric_limits<double>::quiet_NaN();
  Planes a, b;
  std::string why;
  if (!ExtractPair(test, reference, a, b, why))
  {
    vtkErrorMacro("cannot compare the images: " << why);
    return false;
  }
  const double peak = this->Peak > 0.0 ? this->Peak : (a.Bytes && b.Bytes ? 255.0 : 1.0);
  double sum = 0.0;
  double largest = 0.0;
  for (int c = 0; c < a.Channels; ++c)
  {
    for (size_t i = 0; i < a.Data[c].size(); ++i)
    {
      const double d = a.Data[c][i] - b.Data[c][i];
      sum += d * d;
      largest = std::max(largest, std::abs(d));
    }
  }
  const double count = static_cast<double>(a.Channels) * a.Data[0].size();
  this->RMSE = std::sqrt(sum / count);
  this->PSNR = this->RMSE > 0.0 ? 20.0 * std::log10(peak / this->RMSE)
                                : std::numeric_limits<double>::infinity();
  this->MaximumError = largest;
  this->PeakUsed = peak;

  if (a.Width >= Window && a.Height >= Window)
  {
    if (this->SSIMMode == SSIM_LUMINANCE)
    {
      this->SSIM = MeanSSIM(Luminance(a), Luminance(b), a.Width, a.Height, peak);
    }
    else
    {
      double s = 0.0;
      for (int c = 0; c < a.Channels; ++c)
      {
        s += MeanSSIM(a.Data[c], b.Data[c], a.Width, a.Height, peak);
      }
      this->SSIM = s / a.Channels;
    }
  }
  else
  {
    vtkWarningMacro("SSIM needs images of at least " << Window << "x" << Window << " pixels");
  }
  return true;
}

vtkSmartPointer<vtkImageData> vtkImageErrorMetrics::ErrorHeatMap(
  vtkImageData* test, vtkImageData* reference, double maxError)
{
  Planes a, b;
  std::string why;
  if (!ExtractPair(test, reference, a, b, why))
  {
    vtkErrorMacro("cannot compare the images: " << why);
    return nullptr;
  }
  const size_t n = a.Data[0].size();
  std::vector<double> error(n, 0.0);
  double largest = 0.0;
  for (size_t i = 0; i < n; ++i)
  {
    for (int c = 0; c < a.Channels; ++c)
    {
      error[i] = std::max(error[i], std::abs(a.Data[c][i] - b.Data[c][i]));
    }
    largest = std::max(largest, error[i]);
  }
  const double scale = maxError > 0.0 ? maxError : (largest > 0.0 ? largest : 1.0);
  vtkNew<vtkUnsignedCharArray> colors;
  colors->SetName("ErrorHeatMap");
  colors->SetNumberOfComponents(3);
  colors->SetNumberOfTuples(static_cast<vtkIdType>(n));
  for (size_t i = 0; i < n; ++i)
  {
    HeatColor(error[i] / scale, colors->GetPointer(static_cast<vtkIdType>(3 * i)));
  }
  auto map = vtkSmartPointer<vtkImageData>::New();
  map->SetDimensions(a.Width, a.Height, 1);
  map->GetPointData()->SetScalars(colors);
  return map;
}

bool vtkImageErrorMetrics::WriteErrorHeatMap(
  const char* fileName, vtkImageData* test, vtkImageData* reference, double maxError)
{
  vtkSmartPointer<vtkImageData> map = this->ErrorHeatMap(test, reference, maxError);
  return map && vtkImageErrorMetrics::WritePNG(fileName, map);
}

bool vtkImageErrorMetrics::WritePNG(const char* fileName, vtkImageData* image)
{
  vtkDataArray* scalars = image ? image->GetPointData()->GetScalars() : nullptr;
  if (!fileName || !scalars || scalars->GetDataType() != VTK_UNSIGNED_CHAR)
  {
    vtkGenericWarningMacro("WritePNG needs a file name and an unsigned-char image");
    return false;
  }
  int dims[3];
  image->GetDimensions(dims);
  const int w = dims[0];
  const int h = dims[1] * dims[2];
  const int nc = scalars->GetNumberOfComponents();
  const unsigned char* px = static_cast<vtkUnsignedCharArray*>(scalars)->GetPointer(0);

  // Raw scanlines (filter type 0), top row first; VTK stores bottom first.
  std::vector<unsigned char> raw;
  raw.reserve(static_cast<size_t>(h) * (3 * w + 1));
  for (int y = h - 1; y >= 0; --y)
  {
    raw.push_back(0);
    for (int x = 0; x < w; ++x)
    {
      const unsigned char* p = px + (static_cast<size_t>(y) * w + x) * nc;
      for (int c = 0; c < 3; ++c)
      {
        raw.push_back(p[nc >= 3 ? c : 0]);
      }
    }
  }
  // zlib stream of stored (uncompressed) deflate blocks: simple and exact.
  std::vector<unsigned char> z = { 0x78, 0x01 };
  for (size_t pos = 0;;)
  {
    const size_t len = std::min<size_t>(65535, raw.size() - pos);
    const bool last = pos + len >= raw.size();
    z.push_back(last ? 1 : 0);
    z.push_back(static_cast<unsigned char>(len & 0xFF));
    z.push_back(static_cast<unsigned char>(len >> 8));
    z.push_back(static_cast<unsigned char>(~len & 0xFF));
    z.push_back(static_cast<unsigned char>((~len >> 8) & 0xFF));
    z.insert(z.end(), raw.begin() + pos, raw.begin() + pos + len);
    pos += len;
    if (last)
    {
      break;
    }
  }
  uint32_t s1 = 1, s2 = 0; // Adler-32
  for (unsigned char c : raw)
  {
    s1 = (s1 + c) % 65521;
    s2 = (s2 + s1) % 65521;
  }
  PutU32(z, (s2 << 16) | s1);

  std::vector<unsigned char> png = { 0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n' };
  std::vector<unsigned char> header;
  PutU32(header, static_cast<uint32_t>(w));
  PutU32(header, static_cast<uint32_t>(h));
  header.insert(header.end(), { 8, 2, 0, 0, 0 }); // 8-bit RGB, deflate, no filter, no interlace
  PutChunk(png, "IHDR", header);
  PutChunk(png, "IDAT", z);
  PutChunk(png, "IEND", {});
  std::ofstream file(fileName, std::ios::binary);
  file.write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
  return static_cast<bool>(file);
}

void vtkImageErrorMetrics::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SSIMMode: " << (this->SSIMMode == SSIM_LUMINANCE ? "luminance" : "per channel")
     << "\n";
  os << indent << "Peak: " << this->Peak << "\n";
  os << indent << "RMSE: " << this->RMSE << "\n";
  os << indent << "PSNR: " << this->PSNR << "\n";
  os << indent << "SSIM: " << this->SSIM << "\n";
  os << indent << "MaximumError: " << this->MaximumError << "\n";
}
