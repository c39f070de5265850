"""Several Multi-Material Volume representations in one view light each other:
a plate above a floor, each its own source on the same point spacing, one
directional scene light from above. The two representations must give the
image of the same plate and floor as one volume (PSNR >= 35 dB), the plate's
shadow must be on the floor (the floor alone differs by more than 5 dB more),
and hiding the plate must take its shadow away (the floor alone, >= 50 dB).

Under MPI (`mpiexec -np N pvbatch`, after the -np 1 run that writes the
reference) each volume is split over the ranks, every rank lights its
pieces through the other volume's global pre-filtered values, and the
image must equal -np 1's (PSNR >= 40 dB; 23.1 dB when pieces neither cast
nor received)."""


from paraview import simple

import os

from paraview import servermanager

import mmv_testing as mmv

args = mmv.parse_args()
simple.LoadPlugin(args.plugin, remote=True)
checker = mmv.Checker()
errors = mmv.ErrorCapture()
ranks = servermanager.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()

PLATE = "exp(-((coordsZ-14)/2.5)^8-(coordsX/7)^8-(coordsY/7)^8)"
FLOOR = "exp(-((coordsZ+18)/2.5)^8)"
XY = [-12, 12, -12, 12]

view = mmv.make_view()
mmv.add_directional_light(view, [8.0, 4.0, 100.0])
view.CameraPosition = [55.0, -70.0, 30.0]
view.CameraFocalPoint = [0.0, 0.0, -4.0]
view.CameraViewUp = [0.0, 0.0, 1.0]
view.CameraViewAngle = 30.0


def source(zs, expression):
    wavelet = simple.Wavelet()
    wavelet.WholeExtent = XY + zs
    calculator = simple.Calculator(Input=wavelet)
    calculator.ResultArrayName = "density"
    calculator.Function = "200*(%s)" % expression
    return calculator


# One colour over the density's range, opaque from 150 on; kept as set.
density_colours = simple.GetColorTransferFunction("density")
density_colours.RGBPoints = [0.0, 0.9, 0.85, 0.8, 200.0, 0.9, 0.85, 0.8]
density_colours.AutomaticRescaleRangeMode = "Never"
density_opacity = simple.GetOpacityTransferFunction("density")
density_opacity.Points = [0.0, 0.0, 0.5, 0.0, 60.0, 0.0, 0.5, 0.0, 150.0, 0.9, 0.5, 0.0,
                          200.0, 0.9, 0.5, 0.0]
density_opacity.AllowDuplicateScalars = 1


def show(data):
    return mmv.show_multi_material(data, view, "density")


def render(name):
    return mmv.render_image(view, image_path(name, ranks))


def image_path(name, ranks):
    return os.path.join(args.temp_dir, "PVMultiMaterialSceneShadows%s_%d.png" % (name, ranks))


# The same plate and floor as one volume.
whole_source = source([-24, 24], "%s+%s" % (PLATE, FLOOR))
show(whole_source)
one = render("One")
simple.Hide(whole_source, view)

# Each as its own representation: the plate's box above the floor's.
plate_source = source([4, 24], PLATE)
floor_source = source([-24, -4], FLOOR)
plate = show(plate_source)
floor = show(floor_source)
two = render("Two")
checker.check(mmv.check_not_blank(two, "plate and floor"), "the volumes are visible")
for name, rep in (("plate", plate), ("floor", floor)):
    checker.check(mmv.info(rep, "MultiMaterialActive") == 1, "the %s is shaded with materials" % name)
together = mmv.psnr(two, one)
print("two representations vs one volume: PSNR %.1f dB" % together)
checker.check(together >= 35.0, "two representations light each other as one volume does "
              "(PSNR %.1f dB >= 35)" % together)

if ranks > 1:
    reference = image_path("Two", 1)
    checker.check(os.path.exists(reference), "the -np 1 reference exists (%s)" % reference)
    if os.path.exists(reference):
        value = mmv.psnr(two, mmv.read_png(reference))
        print("-np %d vs -np 1: PSNR %.1f dB" % (ranks, value))
        checker.check(value >= 40.0, "volumes in pieces shadow each other as -np 1 does "
                      "(PSNR %.1f dB >= 40)" % value)

# The floor alone (the plate hidden): its shadow goes with it.
simple.Hide(plate_source, view)
hidden = render("PlateHidden")
simple.Hide(floor_source, view)
alone_source = source([-24, -4], FLOOR)
show(alone_source)
floor_alone = render("FloorAlone")
simple.Hide(alone_source, view)
simple.Show(floor_source, view)
after_hiding = mmv.psnr(hidden, floor_alone)
print("plate hidden vs floor alone: PSNR %.1f dB" % after_hiding)
checker.check(after_hiding >= 50.0, "a hidden plate casts no shadow (PSNR %.1f dB >= 50)"
              % after_hiding)
# The shadow was there: without the plate and its shadow the image differs
# much more from the two volumes than one volume does.
shadowless = mmv.psnr(two, hidden)
print("plate and floor vs floor alone: PSNR %.1f dB" % shadowless)
checker.check(shadowless < together - 5.0, "the plate's shadow is on the floor (%.1f dB < %.1f - 5)"
              % (shadowless, together))
# Shown again, the plate shadows the floor again.
simple.Show(plate_source, view)
again = render("Again")
print("shown again vs before: PSNR %.1f dB" % mmv.psnr(again, two))
checker.check(mmv.psnr(again, two) >= 50.0, "the plate shown again shadows the floor as before")

problems = errors.take()
checker.check(not problems, "no VTK errors or warnings: %s" % problems)
errors.close()
checker.finish()
