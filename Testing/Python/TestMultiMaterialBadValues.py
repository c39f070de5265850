"""Bad MaterialNodes and an unknown preset are reported (VTK errors, which
pvpython prints) and ignored: the previous materials stay and rendering goes on.
A negative PointLightRadius, an IrradianceScale above 1 and an
EnvironmentLighting that is negative, NaN, infinite or huge are reported
(warnings) and replaced by 0, 1, 0 (no sky) and 100."""

import math
import os

from paraview import simple

import mmv_testing as mmv

args = mmv.parse_args()
mmv.load_plugin(args)
checker = mmv.Checker()
errors = mmv.ErrorCapture()

GOOD = [37.0, 0.1, 0.8, 0.3, 20.0, 1.0, 0.5, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0,
        277.0, 0.1, 0.8, 0.3, 20.0, 1.0, 0.5, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0]

view = mmv.make_view()
rep = mmv.show_volume(mmv.make_volume(), view, preset="Custom")
rep.MaterialNodes = GOOD
reference = mmv.render_image(view, os.path.join(args.temp_dir, "bad_reference.png"))
checker.check(errors.take_errors() == "", "good nodes: no error")


def expect_rejected(what, message_part):
    log = errors.take_errors()
    checker.check(message_part in log, "%s is reported: %r" % (what, log.strip()[-200:]))
    image = mmv.render_image(view, os.path.join(args.temp_dir, "bad_%s.png" % what.replace(" ", "_")))
    checker.check(mmv.info(rep, "AppliedMaterialNodes") == GOOD, "%s: previous nodes kept" % what)
    checker.check(mmv.mean_difference(image, reference) <= mmv.BASELINE_THRESHOLD,
                  "%s: the next render still works and is unchanged" % what)
    checker.check(mmv.info(rep, "MultiMaterialActive") == 1, "%s: still multi-material" % what)


rep.MaterialNodes = GOOD[:-1]
expect_rejected("25 numbers", "13 numbers per node")

too_anisotropic = list(GOOD)
too_anisotropic[8] = 1.0
rep.MaterialNodes = too_anisotropic
expect_rejected("anisotropy 1", "anisotropy")

nan = list(GOOD)
nan[2] = float("nan")
rep.MaterialNodes = nan
expect_rejected("NaN", "ERROR")

negative = list(GOOD)
negative[5] = -1.0
rep.MaterialNodes = negative
expect_rejected("negative attenuation", "ERROR")

for channel in (10, 11, 12):
    for bad, what in ((1.5, "above 1"), (-0.25, "negative")):
        tinted = list(GOOD)
        tinted[channel] = bad
        rep.MaterialNodes = tinted
        expect_rejected("transmission %d %s" % (channel - 10, what), "transmission_")

rep.MaterialPreset = "unobtainium"
expect_rejected("unknown preset", "Unknown material preset")

# A good list afterwards is taken again.
rep.MaterialNodes = GOOD[:13]
mmv.render_image(view, os.path.join(args.temp_dir, "bad_recovered.png"))
checker.check(mmv.info(rep, "AppliedMaterialNodes") == GOOD[:13], "a valid list is accepted again")

# The layout before anisotropy (8 numbers a node) still loads, with g = 0, e = 0.
rep.MaterialNodes = GOOD[:8] + GOOD[13:21]
mmv.render_image(view, os.path.join(args.temp_dir, "bad_legacy.png"))
checker.check(mmv.info(rep, "AppliedMaterialNodes") == GOOD, "8-number nodes load with g = 0")

# The layout before emission (9 numbers a node) still loads, with e = 0.
rep.MaterialNodes = GOOD[:9] + GOOD[13:22]
mmv.render_image(view, os.path.join(args.temp_dir, "bad_legacy9.png"))
checker.check(mmv.info(rep, "AppliedMaterialNodes") == GOOD, "9-number nodes load with e = 0")

# The layout before the transmission colour (10 numbers a node) still loads,
# grey (T = 1, 1, 1), and renders exactly as the 13-number list.
rep.MaterialNodes = GOOD[:10] + GOOD[13:23]
legacy10 = mmv.render_image(view, os.path.join(args.temp_dir, "bad_legacy10.png"))
checker.check(mmv.info(rep, "AppliedMaterialNodes") == GOOD, "10-number nodes load grey")
rep.MaterialNodes = GOOD
current = mmv.render_image(view, os.path.join(args.temp_dir, "bad_current13.png"))
checker.check(mmv.mean_difference(legacy10, current) == 0.0,
              "10- and 13-number grey nodes render the same image")
checker.check(errors.take_errors() == "", "no further errors")

# Out-of-range light and resolution values typed into the panel:
# one warning, then exactly what the fallback value renders, not black.
rep.MaterialNodes = GOOD


def expect_replaced(prop, bad, fallback, message_part):
    setattr(rep, prop, fallback)
    expected = mmv.render_image(view, os.path.join(args.temp_dir, "fallback_%s.png" % prop))
    errors.take()
    setattr(rep, prop, bad)
    image = mmv.render_image(view, os.path.join(args.temp_dir, "bad_%s.png" % prop))
    log = errors.take()
    checker.check(message_part in log, "%s = %r is reported: %r" % (prop, bad, log.strip()[-200:]))
    difference = mmv.mean_difference(image, expected)
    checker.check(difference == 0.0, "%s = %r renders as %r (mean |difference| %.3f)"
                  % (prop, bad, fallback, difference))
    checker.check(mmv.check_not_blank(image, "%s = %r" % (prop, bad)), "%s = %r is not blank"
                  % (prop, bad))
    mmv.render_image(view, os.path.join(args.temp_dir, "bad_%s_again.png" % prop))
    checker.check(errors.take() == "", "%s = %r is reported once" % (prop, bad))
    setattr(rep, prop, fallback)


rep.LightFalloff = "Inverse Square Beyond Radius"  # the radius is used
expect_replaced("PointLightRadius", -5.0, 0.0, "PointLightRadius -5")
expect_replaced("IrradianceScale", 5.0, 1.0, "IrradianceScale 5")
rep.IrradianceScale = 0.0
expect_replaced("EnvironmentLighting", -1.0, 0.0, "EnvironmentLighting -1")
expect_replaced("EnvironmentLighting", float("nan"), 0.0, "EnvironmentLighting nan")
expect_replaced("EnvironmentLighting", float("inf"), 0.0, "EnvironmentLighting inf")
expect_replaced("EnvironmentLighting", 1e30, 100.0, "EnvironmentLighting 1000000")
checker.finish()
