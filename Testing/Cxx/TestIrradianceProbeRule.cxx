// The rule that keeps the error probe's grid choice (vtkIrradianceProbeRule.h):
// the signature's closed forms and the edits that do and do not re-measure.
#include "vtkIrradianceProbeRule.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace
{
constexpr int N = 65;
const double Range[2] = { 100.0, 420.0 }; // width 320: the support's tolerance is 10

/// Opacity `peak` on [low, high] (data values), 0 elsewhere.
std::vector<float> Box(double low, double high, double peak)
{
  std::vector<float> table(N);
  for (int i = 0; i < N; ++i)
  {
    const double value = Range[0] + (Range[1] - Range[0]) * i / (N - 1);
    table[i] = value >= low && value <= high ? static_cast<float>(peak) : 0.0f;
  }
  return table;
}
}

TEST(IrradianceProbeRule, SignatureIsTheSupportAndThePeakOpticalDepth)
{
  // Table entries every 5 data units: [200, 300] is entries 20 ... 40.
  std::vector<float> attenuation(N, 1.0f);
  attenuation[30] = 2.0f;
  const mmv::ProbeSignature s =
    mmv::MakeProbeSignature(Box(200.0, 300.0, 0.5), attenuation, Range, 2.0);
  EXPECT_FALSE(s.Empty);
  EXPECT_DOUBLE_EQ(s.SupportLow, 200.0);
  EXPECT_DOUBLE_EQ(s.SupportHigh, 300.0);
  // -ln(1 - 0.5) x attenuation 2 / unit distance 2.
  EXPECT_NEAR(s.PeakDepth, std::log(2.0), 1e-12);
  // Zero attenuation casts no shadow, whatever the opacity.
  const mmv::ProbeSignature none =
    mmv::MakeProbeSignature(Box(200.0, 300.0, 0.5), std::vector<float>(N, 0.0f), Range, 1.0);
  EXPECT_TRUE(none.Empty);
}

TEST(IrradianceProbeRule, AnOpacityDragWithinTheSupportKeepsTheChoice)
{
  const std::vector<float> none;
  const mmv::ProbeSignature measured =
    mmv::MakeProbeSignature(Box(200.0, 300.0, 0.5), none, Range, 1.0);
  // The opacity value dragged: the optical depth within a factor 2 keeps it.
  for (double peak : { 0.3, 0.4, 0.6, 0.7 })
  {
    EXPECT_FALSE(mmv::ProbeSignatureChanged(
      measured, mmv::MakeProbeSignature(Box(200.0, 300.0, peak), none, Range, 1.0)))
      << peak;
  }
  // ln 2 = 0.693: 0.2 gives 0.223 (x 0.32), 0.8 gives 1.61 (x 2.3).
  for (double peak : { 0.2, 0.8 })
  {
    EXPECT_TRUE(mmv::ProbeSignatureChanged(
      measured, mmv::MakeProbeSignature(Box(200.0, 300.0, peak), none, Range, 1.0)))
      << peak;
  }
  // The unit distance scales the depth as the opacity does.
  EXPECT_TRUE(mmv::ProbeSignatureChanged(
    measured, mmv::MakeProbeSignature(Box(200.0, 300.0, 0.5), none, Range, 0.4)));
}

TEST(IrradianceProbeRule, TheSupportMovingFartherThanItsToleranceMeasuresAgain)
{
  const std::vector<float> none;
  const mmv::ProbeSignature measured =
    mmv::MakeProbeSignature(Box(200.0, 300.0, 0.5), none, Range, 1.0);
  // One table step (5 units) either way is within 10.
  EXPECT_FALSE(mmv::ProbeSignatureChanged(
    measured, mmv::MakeProbeSignature(Box(195.0, 305.0, 0.5), none, Range, 1.0)));
  EXPECT_FALSE(mmv::ProbeSignatureChanged(
    measured, mmv::MakeProbeSignature(Box(210.0, 290.0, 0.5), none, Range, 1.0)));
  // 15 units is not.
  EXPECT_TRUE(mmv::ProbeSignatureChanged(
    measured, mmv::MakeProbeSignature(Box(215.0, 300.0, 0.5), none, Range, 1.0)));
  EXPECT_TRUE(mmv::ProbeSignatureChanged(
    measured, mmv::MakeProbeSignature(Box(200.0, 285.0, 0.5), none, Range, 1.0)));
  // Everything transparent, or back: always measured again.
  const mmv::ProbeSignature empty = mmv::MakeProbeSignature(Box(0.0, 0.0, 0.5), none, Range, 1.0);
  ASSERT_TRUE(empty.Empty);
  EXPECT_TRUE(mmv::ProbeSignatureChanged(measured, empty));
  EXPECT_TRUE(mmv::ProbeSignatureChanged(empty, measured));
  EXPECT_FALSE(mmv::ProbeSignatureChanged(empty, empty));
}

TEST(IrradianceProbeRule, SmallChangesAddUpAgainstTheMeasuredSignature)
{
  // A drag in steps each within the rule of the previous one ends outside it
  // of the measured one: the caller compares with the measured signature.
  const std::vector<float> none;
  const mmv::ProbeSignature measured =
    mmv::MakeProbeSignature(Box(200.0, 300.0, 0.5), none, Range, 1.0);
  mmv::ProbeSignature previous = measured;
  bool changed = false;
  for (double low = 205.0; low <= 240.0; low += 5.0)
  {
    const mmv::ProbeSignature now = mmv::MakeProbeSignature(Box(low, 300.0, 0.5), none, Range, 1.0);
    EXPECT_FALSE(mmv::ProbeSignatureChanged(previous, now)) << low;
    changed = changed || mmv::ProbeSignatureChanged(measured, now);
    previous = now;
  }
  EXPECT_TRUE(changed);
}
