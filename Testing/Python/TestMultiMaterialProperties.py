"""Every representation property reaches the mapper and changes the image or
the stage it should; lights added to the view reach the mapper."""

import os

from paraview import simple

import mmv_testing as mmv

args = mmv.parse_args()
mmv.load_plugin(args)
checker = mmv.Checker()
errors = mmv.ErrorCapture()

view = mmv.make_view()
rep = mmv.show_volume(mmv.make_volume(), view, preset="bone")
frame = [0]


def render():
    frame[0] += 1
    return mmv.render_image(view, os.path.join(args.temp_dir, "properties_%02d.png" % frame[0]))


def counters():
    return {name: mmv.info(rep, name) for name in
            ("IrradianceUpdateCount", "DiffusionPassCount", "PreIntegrationCount", "RayCastCount",
             "NumberOfShadedLights")}


def changed(a, b, what, minimum=0.5):
    d = mmv.mean_difference(a, b)
    return checker.check(d > minimum, "%s changes the image (mean |difference| %.2f)" % (what, d))


base = render()
c0 = counters()
checker.check(c0["IrradianceUpdateCount"] == 1 and c0["DiffusionPassCount"] >= 1,
              "bone scatters: irradiance and diffusion ran, the irradiance once (%s)" % c0)
# ParaView's first renders recompute the light kit from the camera with a
# rounding difference (1e-16): that once ran the whole irradiance twice.
checker.check(counters()["RayCastCount"] > 1, "the first frame drew more than once (%s)" % c0)

# A camera move: the light kit's lights follow the camera, so the irradiance
# follows too, but the segment tables do not change.
camera = view.GetActiveCamera()
camera.Azimuth(20)
render()
c1 = counters()
checker.check(c1["IrradianceUpdateCount"] > c0["IrradianceUpdateCount"] and
              c1["PreIntegrationCount"] == c0["PreIntegrationCount"],
              "camera move with the light kit: irradiance again, same tables (%s)" % c1)
camera.Azimuth(-20)

# MultipleScattering off: irradiance recomputed without a diffusion pass.
rep.MultipleScattering = 0
noScatter = render()
c2 = counters()
checker.check(c2["IrradianceUpdateCount"] > c1["IrradianceUpdateCount"],
              "MultipleScattering off recomputes the irradiance")
checker.check(c2["DiffusionPassCount"] == c1["DiffusionPassCount"],
              "MultipleScattering off runs no diffusion pass (%d -> %d)"
              % (c1["DiffusionPassCount"], c2["DiffusionPassCount"]))
changed(base, noScatter, "MultipleScattering", minimum=0.05)
rep.MultipleScattering = 1
render()

# IrradianceScale: new resolution, irradiance recomputed.
before = counters()["IrradianceUpdateCount"]
rep.IrradianceScale = 0.25
render()
checker.check(counters()["IrradianceUpdateCount"] > before, "IrradianceScale recomputes the irradiance")
rep.IrradianceScale = 0.0

# IrradianceMemoryMB: a tiny budget forces a coarser grid.
render()
before = counters()["IrradianceUpdateCount"]
rep.IrradianceMemoryMB = 0.01
render()
checker.check(counters()["IrradianceUpdateCount"] > before,
              "IrradianceMemoryMB recomputes the irradiance")
rep.IrradianceMemoryMB = 64
base = render()

# Presets.
rep.MaterialPreset = "metal"
metal = render()
changed(base, metal, "MaterialPreset bone -> metal")
rep.MaterialPreset = "bone"

# MaterialNodes (used once the preset is "Custom").
rep.MaterialNodes = [37.0, 0.1, 0.9, 0.0, 10.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0,
                     277.0, 0.1, 0.9, 0.0, 10.0, 1.0, 0.0, 0.0, 0.5, 0.0, 1.0, 1.0, 1.0]
rep.MaterialPreset = "Custom"
custom = render()
changed(base, custom, "MaterialNodes")
checker.check(mmv.info(rep, "AppliedMaterialNodes") == list(rep.MaterialNodes),
              "the mapper uses MaterialNodes")
rep.MaterialPreset = "bone"
base = render()

# PreIntegration off: post-classified samples.
rep.PreIntegration = 0
changed(base, render(), "PreIntegration off", minimum=0.05)
rep.PreIntegration = 1

# Sample distance: a coarse fixed step rebuilds the tables and shows.
render()
before = counters()["PreIntegrationCount"]
rep.AutoAdjustSampleDistances = 0
rep.SampleDistance = 3.0
coarse = render()
checker.check(counters()["PreIntegrationCount"] > before, "SampleDistance rebuilds the tables")
changed(base, coarse, "SampleDistance 3", minimum=0.05)
rep.AutoAdjustSampleDistances = 1
rep.SampleDistance = 1.0
# LightFalloff "Inverse Square Beyond Radius" selects eq. 12,
# (radius / distance)^2 beyond PointLightRadius; the default is VTK's falloff
# by the light's AttenuationValues (none here).
rep.LightFalloff = "Inverse Square Beyond Radius"
rep.PointLightRadius = 30.0
base = render()

# A spot light added with AddLight reaches the mapper.
lightsBefore = counters()
light = simple.AddLight(view=view)
light.Coords = "Scene"
light.Type = "Positional"
light.ConeAngle = 25.0
light.Position = [0.0, -40.0, 10.0]
light.FocalPoint = [0.0, 0.0, 0.0]
light.Intensity = 1.5
light.DiffuseColor = [1.0, 0.6, 0.3]
spot = render()
lightsAfter = counters()
checker.check(lightsAfter["NumberOfShadedLights"] == lightsBefore["NumberOfShadedLights"] + 1,
              "the spot light is shaded (%d -> %d lights)"
              % (lightsBefore["NumberOfShadedLights"], lightsAfter["NumberOfShadedLights"]))
checker.check(lightsAfter["IrradianceUpdateCount"] > lightsBefore["IrradianceUpdateCount"],
              "the spot light recomputes the irradiance")
changed(base, spot, "AddLight (spot)")

# The falloff matters for the spot light (back to VTK's attenuation).
rep.LightFalloff = "Light Attenuation"
changed(spot, render(), "LightFalloff", minimum=0.05)
rep.LightFalloff = "Inverse Square Beyond Radius"

# The light kit off: the spot light alone, and a camera move then costs no
# irradiance update (scene lights stay put relative to the volume).
view.UseLight = 0
render()
alone = counters()
checker.check(alone["NumberOfShadedLights"] == 1,
              "light kit off: only the spot light is shaded (%d)" % alone["NumberOfShadedLights"])
camera.Azimuth(30)
render()
checker.check(counters()["IrradianceUpdateCount"] == alone["IrradianceUpdateCount"],
              "camera move with a scene light only: no irradiance update")
camera.Azimuth(-30)
view.UseLight = 1
simple.RemoveLight(light)
render()
checker.check(counters()["NumberOfShadedLights"] == lightsBefore["NumberOfShadedLights"],
              "removing the light is seen by the mapper")

# A mouse drag with the light kit: interactive renders keep the irradiance
# (InteractiveIrradiance = Reuse While Interacting, the default), the still
# render after it updates it and equals a fresh render of that camera.
checker.check(rep.InteractiveIrradiance == "Reuse While Interacting",
              "InteractiveIrradiance defaults to Reuse While Interacting (%r)" % rep.InteractiveIrradiance)
render()
before = counters()
deferred = mmv.info(rep, "DeferredIrradianceCount")
for _ in range(3):
    camera.Azimuth(10)
    view.SMProxy.InteractiveRender()
checker.check(counters()["IrradianceUpdateCount"] == before["IrradianceUpdateCount"] and
              mmv.info(rep, "DeferredIrradianceCount") == deferred + 3,
              "interactive renders keep the irradiance (%s, deferred %d -> %d)"
              % (counters(), deferred, mmv.info(rep, "DeferredIrradianceCount")))
atRest = render()
checker.check(counters()["IrradianceUpdateCount"] == before["IrradianceUpdateCount"] + 1,
              "the still render after the drag updates the irradiance once")
info = mmv.info(rep, "IrradianceResolutionInfo")
checker.check(isinstance(info, str) and "x" in info and "(" in info,
              "IrradianceResolutionInfo says the grid and why: %r" % info)
saved = (list(view.CameraPosition), list(view.CameraFocalPoint), list(view.CameraViewUp))
fresh = mmv.show_volume(mmv.make_volume(), view, preset="bone")
view.CameraPosition, view.CameraFocalPoint, view.CameraViewUp = saved
rep.Visibility = 0
freshImage = render()
checker.check(mmv.mean_difference(atRest, freshImage) < 0.01,
              "the image at rest equals a fresh render (mean |difference| %.4f)"
              % mmv.mean_difference(atRest, freshImage))
fresh.Visibility = 0
rep.Visibility = 1

# Update Always: interactive renders update too.
rep.InteractiveIrradiance = "Update Always"
render()
before = counters()
camera.Azimuth(10)
view.SMProxy.InteractiveRender()
checker.check(counters()["IrradianceUpdateCount"] == before["IrradianceUpdateCount"] + 1,
              "Update Always: an interactive render updates the irradiance")
rep.InteractiveIrradiance = "Reuse While Interacting"

# ShadowEstimation: the light kit's directional lights by piecewise (default)
# or full shadow rays; switching recomputes the irradiance, and the two
# images differ, but only a little (shadow edges blur by about a voxel).
checker.check(rep.ShadowEstimation == "Piecewise Shadow Rays",
              "ShadowEstimation defaults to Piecewise Shadow Rays (%r)" % rep.ShadowEstimation)
piecewise = render()
before = counters()
rep.ShadowEstimation = "Full Shadow Rays"
full = render()
checker.check(counters()["IrradianceUpdateCount"] == before["IrradianceUpdateCount"] + 1,
              "switching to full shadow rays recomputes the irradiance")
d = mmv.mean_difference(piecewise, full)
checker.check(0.0 < d < 1.0, "piecewise and full shadow rays differ a little (mean |difference| %.3f)" % d)
rep.PiecewiseShadowSlices = 2
rep.ShadowEstimation = "Piecewise Shadow Rays"
short = render()
checker.check(counters()["IrradianceUpdateCount"] == before["IrradianceUpdateCount"] + 2,
              "PiecewiseShadowSlices reaches the mapper")
rep.PiecewiseShadowSlices = 16

# ExponentialDiffusion: multiple scattering integrated exactly in time (on by
# default); with a scattering material, switching to backward Euler
# recomputes the irradiance and the image changes a little
# (docs/performance.md, "Diffusion: exponential series against backward
# Euler": 47.6-53.4 dB on the CT).
checker.check(rep.ExponentialDiffusion == 1, "ExponentialDiffusion defaults to on")
rep.MaterialPreset = "skin"
exact = render()
before = counters()
rep.ExponentialDiffusion = 0
euler = render()
checker.check(counters()["IrradianceUpdateCount"] == before["IrradianceUpdateCount"] + 1,
              "switching to backward Euler recomputes the irradiance")
d = mmv.mean_difference(euler, exact)
checker.check(0.0 < d < 1.0,
              "backward Euler and the exponential differ a little (mean |difference| %.3f)" % d)
rep.ExponentialDiffusion = 1

# PieceIrradianceOnly (on by default) matters only to a piece of a volume in
# parallel: in one process the region is the whole grid, so switching it
# neither recomputes the irradiance nor changes the image.
checker.check(rep.PieceIrradianceOnly == 1, "PieceIrradianceOnly defaults to on")
render()
before = counters()
rep.PieceIrradianceOnly = 0
whole = render()
checker.check(counters()["IrradianceUpdateCount"] == before["IrradianceUpdateCount"],
              "PieceIrradianceOnly off in one process keeps the irradiance")
checker.check(mmv.mean_difference(whole, exact) < 1e-9,
              "PieceIrradianceOnly off in one process draws the same image")
rep.PieceIrradianceOnly = 1

# EnvironmentLighting: off by default; on, the background lights the volume
# (brighter on a grey background) after one estimation of the sky's
# occlusion; a new background colour reshades without estimating again.
checker.check(rep.EnvironmentLighting == 0.0, "EnvironmentLighting defaults to 0 (off)")
view.UseColorPaletteForBackground = 0
view.Background = [0.4, 0.4, 0.4]
dark = render()
rep.EnvironmentLighting = 1.0
lit = render()
sky = mmv.info(rep, "SkyUpdateCount")
checker.check(sky == 1, "EnvironmentLighting 1 estimates the sky once (%s)" % sky)
brighter = float((lit.astype(float) - dark.astype(float)).mean())
checker.check(brighter > 1.0, "the sky brightens the volume (mean +%.2f grey levels)" % brighter)
view.Background = [0.8, 0.8, 0.8]
render()
checker.check(mmv.info(rep, "SkyUpdateCount") == sky,
              "a new background reshades without estimating the sky again")
rep.EnvironmentLighting = 0.0

log = errors.take_errors()
checker.check(log == "", "no VTK errors: %r" % log[:500])
checker.finish()
