#include "vtkIrradianceResolutionProbe.h"

#include "vtkImageData.h"
#include "vtkIrradianceResolutionError.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

namespace
{
/// The probe's grids: the reference's scale times 2^(-k/2), k = 1 ... 4.
constexpr int ProbeSteps = 4;
/// One light: four lights cost more time and told smooth volumes from thin
/// shells apart less clearly.
constexpr int ProbeLightCount = 1;
}

vtkStandardNewMacro(vtkIrradianceResolutionProbe);

vtkIrradianceResolutionProbe::vtkIrradianceResolutionProbe() = default;
vtkIrradianceResolutionProbe::~vtkIrradianceResolutionProbe() = default;

bool vtkIrradianceResolutionProbe::Key::operator==(const Key& o) const
{
  return std::equal(this->DataDimensions, this->DataDimensions + 3, o.DataDimensions) &&
    std::equal(this->DataSpacing, this->DataSpacing + 3, o.DataSpacing) &&
    this->BudgetMB == o.BudgetMB && this->BoundDB == o.BoundDB && this->TableSize == o.TableSize &&
    this->ShadowEstimation == o.ShadowEstimation &&
    this->PiecewiseShadowSlices == o.PiecewiseShadowSlices && this->Cut == o.Cut;
}

vtkIrradianceResolutionProbe::Key vtkIrradianceResolutionProbe::MakeKey(
  const vtkIrradianceInputCache::VolumeKey& key, vtkImageData* image, double budgetMB,
  double boundDB)
{
  // The probe has its own light and no scattering; the data's values and the
  // transfer functions are judged by the signature.
  Key made;
  image->GetDimensions(made.DataDimensions);
  image->GetSpacing(made.DataSpacing);
  made.BudgetMB = budgetMB;
  made.BoundDB = boundDB;
  made.TableSize = key.TableSize;
  made.ShadowEstimation = key.ShadowEstimation;
  made.PiecewiseShadowSlices = key.PiecewiseShadowSlices;
  made.Cut = key.Cut;
  return made;
}

bool vtkIrradianceResolutionProbe::Holds(const vtkIrradianceInputCache::VolumeKey& key,
  vtkImageData* image, double budgetMB, double boundDB, const SignatureFunction& signature)
{
  if (!this->HasResult || !(MakeKey(key, image, budgetMB, boundDB) == this->Measured))
  {
    return false;
  }
  if (key == this->Seen)
  {
    return true;
  }
  if (mmv::ProbeSignatureChanged(this->MeasuredSignature, signature()))
  {
    return false;
  }
  this->Seen = key;
  return true;
}

std::vector<mmv::LightSource> vtkIrradianceResolutionProbe::ProbeLights()
{
  // Oblique to every axis, so no axis-aligned feature is seen edge-on.
  static const double directions[ProbeLightCount][3] = { { 1, 1, 1 } };
  std::vector<mmv::LightSource> lights(ProbeLightCount);
  for (int l = 0; l < ProbeLightCount; ++l)
  {
    lights[l].Kind = mmv::DirectionalLight;
    const double* d = directions[l];
    lights[l].ToLight = glm::normalize(glm::dvec3(d[0], d[1], d[2]));
  }
  return lights;
}

double vtkIrradianceResolutionProbe::Choose(vtkOpenGLRenderWindow* context,
  const vtkIrradianceInputCache::VolumeKey& key, vtkImageData* image, vtkDataArray* scalars,
  const double range[2], double budgetMB, int maxAxis, double boundDB,
  const std::vector<float>& opacityTable, const SignatureFunction& signature,
  const ComputeFunction& compute)
{
  if (this->Holds(key, image, budgetMB, boundDB, signature))
  {
    return this->Scale;
  }
  const auto start = std::chrono::steady_clock::now();
  ++this->NumberOfProbes;
  this->Measured = MakeKey(key, image, budgetMB, boundDB);
  this->MeasuredSignature = signature();
  this->Seen = key;
  this->HasResult = true;
  if (!this->Measure(context, image, scalars, key.DataTime, range, budgetMB, maxAxis, boundDB,
        opacityTable, compute))
  {
    // Keep the reference: the frame's own computation reports the failure.
    this->Scale = this->Candidates.empty() ? 1.0 : this->Candidates.front().Scale;
    this->Summary = "error probe failed: the budget's grid";
  }
  this->LastProbeSeconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // Grids for other data would waste memory until the next change.
  this->Pass->ReleaseGraphicsResources(context);
  return this->Scale;
}

bool vtkIrradianceResolutionProbe::Measure(vtkOpenGLRenderWindow* context, vtkImageData* image,
  vtkDataArray* scalars, vtkMTimeType dataTime, const double range[2], double budgetMB, int maxAxis,
  double boundDB, const std::vector<float>& opacityTable, const ComputeFunction& compute)
{
  this->Candidates.clear();
  const std::vector<mmv::LightSource> lights = ProbeLights();
  int dataDims[3];
  image->GetDimensions(dataDims);

  // The reference: the finest grid the budget allows the probe's lights.
  Candidate reference;
  mmv::ComputeIrradianceDimensions(dataDims, ProbeLightCount, budgetMB, 0.0, reference.Dimensions);
  reference.Scale = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    if (dataDims[a] > 1)
    {
      reference.Scale =
        std::max(reference.Scale, static_cast<double>(reference.Dimensions[a]) / dataDims[a]);
    }
  }
  reference.Scale = reference.Scale > 0.0 ? reference.Scale : 1.0;
  reference.PSNR = std::numeric_limits<double>::infinity();
  this->Candidates.push_back(reference);
  this->Scale = reference.Scale;

  auto estimate = [&](const int wanted[3], std::vector<std::vector<float>>& values)
  {
    int dims[3];
    for (int a = 0; a < 3; ++a)
    {
      dims[a] = maxAxis > 1 ? std::min(wanted[a], maxAxis) : wanted[a];
    }
    this->Prefilter->UpdatePrefiltered(image, scalars, nullptr, dims, dataTime, range);
    return compute(this->Pass, this->Prefilter->GetGrid(), this->Prefilter->GetPrefiltered(),
             this->Prefilter->GetPrefilteredVersion(), lights) &&
      this->Pass->ReadBackLights(context, 0, static_cast<int>(lights.size()), values);
  };
  std::vector<std::vector<float>> fine;
  if (!estimate(reference.Dimensions, fine))
  {
    return false;
  }
  const mmv::IrradianceGrid fineGrid = this->Prefilter->GetGrid();
  const std::vector<float> weights =
    mmv::OpacityWeights(this->Prefilter->GetPrefiltered(), opacityTable);

  char text[256];
  std::snprintf(text, sizeof(text), "error probe: the reference %dx%dx%d", reference.Dimensions[0],
    reference.Dimensions[1], reference.Dimensions[2]);
  std::string summary = text;
  for (int k = 1; k <= ProbeSteps; ++k)
  {
    Candidate candidate;
    candidate.Scale = reference.Scale * std::exp2(-0.5 * k);
    mmv::ComputeIrradianceDimensions(
      dataDims, ProbeLightCount, budgetMB, candidate.Scale, candidate.Dimensions);
    const int* c = candidate.Dimensions;
    const int* p = this->Candidates.back().Dimensions;
    if (c[0] == p[0] && c[1] == p[1] && c[2] == p[2])
    {
      break; // already at the smallest grid
    }
    std::vector<std::vector<float>> coarse;
    if (!estimate(candidate.Dimensions, coarse))
    {
      return false;
    }
    candidate.PSNR =
      mmv::VisibleIrradiancePSNR(fineGrid, fine, weights, this->Prefilter->GetGrid(), coarse);
    this->Candidates.push_back(candidate);
    std::snprintf(text, sizeof(text), ", scale %.3g: %.1f dB", candidate.Scale, candidate.PSNR);
    summary += text;
    if (!(candidate.PSNR >= boundDB))
    {
      break;
    }
    this->Scale = candidate.Scale;
  }
  std::snprintf(text, sizeof(text), " (bound %.3g dB): scale %.3g", boundDB, this->Scale);
  this->Summary = summary + text;
  return true;
}

void vtkIrradianceResolutionProbe::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Pass->ReleaseGraphicsResources(window);
  this->HasResult = false;
}

void vtkIrradianceResolutionProbe::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Summary: " << this->Summary << "\n";
  os << indent << "NumberOfProbes: " << this->NumberOfProbes << "\n";
  os << indent << "LastProbeSeconds: " << this->LastProbeSeconds << "\n";
}
