"""SaveState / ResetSession / LoadState keeps every Multi-Material Volume
property (MaterialNodes exactly) and renders the same image."""

import os

from paraview import simple

import mmv_testing as mmv

args = mmv.parse_args()
mmv.load_plugin(args)
checker = mmv.Checker()

NODES = [40.0, 0.15, 0.7, 0.35, 42.0, 0.9, 0.25, 0.05, -0.25, 0.0, 1.0, 1.0, 1.0,
         123.456789012345, 0.2, 0.6, 0.1, 7.5, 1.25, 0.5, 0.0, 0.0, 0.375, 1.0, 1.0, 1.0,
         277.0, 0.05, 0.95, 0.6, 80.0, 2.0, 0.0, 0.3, 0.75, 0.0, 1.0, 1.0, 1.0]
SETTINGS = {"MaterialPreset": "Custom", "IrradianceMemoryMB": 12.5, "IrradianceScale": 0.5,
            "MultipleScattering": 0, "PreIntegration": 0, "PointLightRadius": 2.5,
            "AutoAdjustSampleDistances": 0, "SampleDistance": 0.75}

view = mmv.make_view()
rep = mmv.show_volume(mmv.make_volume(), view, preset=None)
rep.MaterialNodes = NODES
for name, value in SETTINGS.items():
    setattr(rep, name, value)
before = mmv.render_image(view, os.path.join(args.temp_dir, "state_before.png"))

state = os.path.join(args.temp_dir, "MultiMaterialState.pvsm")
simple.SaveState(state)
with open(state) as f:
    checker.check('value="Multi-Material Volume"' in f.read(), "the state names the representation")

simple.ResetSession()
mmv.load_plugin(args)
simple.LoadState(state)
view = simple.GetActiveViewOrCreate("RenderView")
source = simple.FindSource("Wavelet1")
rep = simple.GetDisplayProperties(source, view)

checker.check(rep.Representation == mmv.REPRESENTATION, "Representation restored")
restored = list(rep.MaterialNodes)
checker.check(restored == NODES, "MaterialNodes restored exactly: %s" % restored)
for name, value in SETTINGS.items():
    checker.check(rep.GetPropertyValue(name) == value,
                  "%s restored (%r)" % (name, rep.GetPropertyValue(name)))
after = mmv.render_image(view, os.path.join(args.temp_dir, "state_after.png"))
checker.check(mmv.info(rep, "AppliedMaterialNodes") == NODES, "the mapper uses the restored nodes")
d = mmv.mean_difference(before, after)
checker.check(d <= mmv.BASELINE_THRESHOLD, "same image after LoadState (mean |difference| %.3f)" % d)
checker.finish()
