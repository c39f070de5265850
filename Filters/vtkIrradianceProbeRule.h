/**
 * @file   vtkIrradianceProbeRule.h
 * @brief  When the error probe's grid choice still holds: the rule that keeps
 *         it through opacity edits and time steps.
 *
 * vtkIrradianceResolutionProbe measures how fine an irradiance grid the
 * data's structure needs under its transfer function, which costs several
 * irradiance updates. What decides that choice is where the extinction is
 * (which data values cast shadows: the support of the extinction) and how
 * sharp it is (the largest optical depth per unit length), not the exact
 * opacity values: dragging an opacity point within the support, or stepping
 * through a series on the same grid, keeps the structure the probe saw. So
 * the choice is kept until, against the signature it was measured for,
 *  - an end of the support moves by more than SupportTolerance of the scalar
 *    range, or the support appears or vanishes, or
 *  - the peak optical depth changes by more than a factor PeakRatio.
 * Changes are compared with the measured signature, never the last one, so
 * a long drag adds up and measures again once it has moved far enough. The
 * tables are sampled over the opacity function's own range, not the data's,
 * so a time step whose values span another range keeps the signature.
 */
#ifndef vtkIrradianceProbeRule_h
#define vtkIrradianceProbeRule_h

#include <algorithm>
#include <cmath>
#include <vector>

namespace mmv
{

/// An end of the support may move this fraction of the sampled range.
constexpr double ProbeSupportTolerance = 1.0 / 32.0;
/// The peak optical depth may change by this factor either way.
constexpr double ProbePeakRatio = 2.0;

/// What the probe's choice depends on in the transfer functions.
struct ProbeSignature
{
  bool Empty = true;       // no value casts a shadow
  double SupportLow = 0.0; // the lowest and highest data value with extinction
  double SupportHigh = 0.0;
  double PeakDepth = 0.0; // the largest optical depth per unit length
  double Width = 0.0;     // the sampled range's width: the support's scale
};

/**
 * The signature of the opacity table `opacity` (n entries over `range`, the
 * scalar opacity per `unitDistance`) times the attenuation table
 * `attenuation` (n entries at the same values, or empty for 1).
 */
inline ProbeSignature MakeProbeSignature(const std::vector<float>& opacity,
  const std::vector<float>& attenuation, const double range[2], double unitDistance)
{
  ProbeSignature signature;
  signature.Width = std::abs(range[1] - range[0]);
  const int n = static_cast<int>(opacity.size());
  const double unit = unitDistance > 0.0 ? unitDistance : 1.0;
  for (int i = 0; i < n; ++i)
  {
    const double alpha = std::min(std::max(static_cast<double>(opacity[i]), 0.0), 0.9999);
    const double a = i < static_cast<int>(attenuation.size()) ? attenuation[i] : 1.0;
    const double depth = -std::log1p(-alpha) * std::max(a, 0.0) / unit;
    if (!(depth > 0.0))
    {
      continue;
    }
    const double value = n > 1 ? range[0] + (range[1] - range[0]) * i / (n - 1) : range[0];
    if (signature.Empty)
    {
      signature.SupportLow = value;
    }
    signature.Empty = false;
    signature.SupportHigh = value;
    signature.PeakDepth = std::max(signature.PeakDepth, depth);
  }
  return signature;
}

/// Whether `now` differs materially from `measured`: the probe must
/// measure again.
inline bool ProbeSignatureChanged(const ProbeSignature& measured, const ProbeSignature& now)
{
  if (measured.Empty || now.Empty)
  {
    return measured.Empty != now.Empty;
  }
  const double tolerance = ProbeSupportTolerance * std::max(measured.Width, now.Width);
  if (std::abs(now.SupportLow - measured.SupportLow) > tolerance ||
    std::abs(now.SupportHigh - measured.SupportHigh) > tolerance)
  {
    return true;
  }
  const double ratio = now.PeakDepth / measured.PeakDepth;
  return !(ratio <= ProbePeakRatio && ratio >= 1.0 / ProbePeakRatio);
}

} // namespace mmv

#endif
