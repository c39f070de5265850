"""Shows a Wavelet volume as 'Multi-Material Volume' with the bone preset and
compares the screenshot with Testing/Baseline/PVMultiMaterialVolume.png.
Also runs under pvbatch (the PVBatch test) and lists the presets."""

import os

from paraview import simple

import mmv_testing as mmv

args = mmv.parse_args()
mmv.load_plugin(args)
checker = mmv.Checker()
errors = mmv.ErrorCapture()

view = mmv.make_view()
rep = mmv.show_volume(mmv.make_volume(), view, preset="bone")

types = rep.GetProperty("Representation").Available
checker.check(mmv.REPRESENTATION in types, "'%s' is a representation type" % mmv.REPRESENTATION)
presets = rep.GetProperty("MaterialPreset").Available
checker.check(
    all(p in presets for p in ("plastic", "metal", "skin", "bone", "glass", "leaf", "matte", "smoke", "glow")),
    "MaterialPreset domain lists the library's presets: %s" % presets)

path = os.path.join(args.temp_dir, "PVMultiMaterialVolume.png")
image = mmv.render_image(view, path)
checker.check(mmv.check_not_blank(image, "render"), "the volume is visible")
checker.check(mmv.info(rep, "MultiMaterialActive") == 1, "the mapper shaded with materials")
checker.check(mmv.info(rep, "IrradianceUpdateCount") >= 1, "the irradiance volume was computed")
checker.check(mmv.info(rep, "NumberOfShadedLights") >= 1,
              "the view's lights reach the mapper (%d)" % mmv.info(rep, "NumberOfShadedLights"))
applied = mmv.info(rep, "AppliedMaterialNodes")
checker.check(len(applied) == 26 and abs(applied[0] - 37.0) < 1e-9 and abs(applied[13] - 277.0) < 1e-9,
              "the bone preset spans the colour map range: %s" % applied)
checker.check(mmv.compare_with_baseline(args, path, "PVMultiMaterialVolume.png"),
              "image matches the baseline")
log = errors.take_errors()
checker.check(log == "", "no VTK errors: %r" % log[:500])
checker.finish()
