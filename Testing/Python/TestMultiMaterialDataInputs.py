"""The data ParaView users volume-render, in pvpython:
- first use: Show() then SetRepresentationType("Multi-Material Volume") while
  Coloring is Solid Color colours by the first point array, as Volume does,
  and renders as an explicit ColorBy of that array (identical image);
  setting the Representation property does the same; data without arrays
  give an error that says why nothing is drawn;
- cell data (PointDatatoCellData) are shaded with materials;
- a vector coloured by Magnitude renders as the magnitude computed by a
  Calculator (PSNR >= 40 dB), and by its X component as that component."""

import os

from paraview import simple


import mmv_testing as mmv

args = mmv.parse_args()
mmv.load_plugin(args)
checker = mmv.Checker()
errors = mmv.ErrorCapture()


def frame(view):
    view.CameraPosition = [60.0, -45.0, 40.0]
    view.CameraFocalPoint = [0.0, 0.0, 0.0]
    view.CameraViewUp = [0.0, 0.0, 1.0]
    view.CameraViewAngle = 30.0


def shot(view, name):
    return mmv.render_image(view, os.path.join(args.temp_dir, name))


# --- First use ---------------------------------------------------------------
# The camera is set once; without this the first render would reset it.
simple._DisableFirstRenderCameraReset()
wavelet = mmv.make_volume()
view = mmv.make_view()
frame(view)
display = simple.Show(wavelet, view)
checker.check(not display.ColorArrayName[1], "Show() starts with Solid Color (%s)"
              % list(display.ColorArrayName))
display.SetRepresentationType(mmv.REPRESENTATION)
checker.check(list(display.ColorArrayName) == ["POINTS", "RTData"],
              "after the switch ColorArrayName is %s" % list(display.ColorArrayName))
first = shot(view, "PVFirstUse.png")
checker.check(mmv.check_not_blank(first, "first use"), "the first-use image is not background")
checker.check(mmv.info(display, "MultiMaterialActive") == 1, "first use is shaded with materials")
simple.Delete(display)

# The same view with the array chosen by hand first.
explicit = simple.Show(wavelet, view)
simple.ColorBy(explicit, ("POINTS", "RTData"))
explicit.RescaleTransferFunctionToDataRange(True)
explicit.SetRepresentationType(mmv.REPRESENTATION)
by_hand = shot(view, "PVFirstUseExplicit.png")
difference = mmv.mean_difference(first, by_hand)
checker.check(difference == 0.0, "first use equals an explicit ColorBy (mean |difference| %.3f)"
              % difference)
simple.Delete(explicit)

# Setting the property (as Python traces do) colours as well.
by_property = simple.Show(wavelet, view)
by_property.Representation = mmv.REPRESENTATION
checker.check(list(by_property.ColorArrayName) == ["POINTS", "RTData"],
              "setting Representation colours by %s" % list(by_property.ColorArrayName))
simple.Delete(by_property)
errors.take()

# No array at all: a clear error, nothing drawn.
bare = simple.PassArrays(Input=wavelet)
bare.PointDataArrays = []
bare.CellDataArrays = []
bare.UpdatePipeline()
nothing = simple.Show(bare, view)
nothing.SetRepresentationType(mmv.REPRESENTATION)
log = errors.take_errors()
checker.check("no point or cell array" in log, "data without arrays say why nothing is drawn: %r"
              % log[:300])
checker.check(not nothing.ColorArrayName[1], "and stay uncoloured")
simple.Delete(nothing)
simple.Delete(bare)

# --- Cell data ---------------------------------------------------------------
cells = simple.PointDatatoCellData(Input=wavelet)
cell_display = simple.Show(cells, view)
cell_display.SetRepresentationType(mmv.REPRESENTATION)
checker.check(list(cell_display.ColorArrayName) == ["CELLS", "RTData"],
              "cell data colour by the cell array (%s)" % list(cell_display.ColorArrayName))
cell_image = shot(view, "PVCellData.png")
checker.check(mmv.check_not_blank(cell_image, "cell data"), "cell data are drawn")
checker.check(mmv.info(cell_display, "MultiMaterialActive") == 1,
              "cell data are shaded with materials")
simple.Delete(cell_display)


# --- Vectors -----------------------------------------------------------------
def show_array(source, array, configure=None):
    """Shows `array` with the same colour and opacity maps over [0, 30]."""
    shown = simple.Show(source, view)
    simple.ColorBy(shown, ("POINTS", array))
    lut = simple.GetColorTransferFunction(array)
    lut.ApplyPreset("Cool to Warm", True)
    if configure:
        configure(lut)
    lut.RescaleTransferFunction(0.0, 30.0)
    pwf = simple.GetOpacityTransferFunction(array)
    pwf.Points = [0.0, 0.0, 0.5, 0.0, 8.0, 0.0, 0.5, 0.0, 30.0, 0.8, 0.5, 0.0]
    pwf.RescaleTransferFunction(0.0, 30.0)
    shown.ScalarOpacityUnitDistance = 1.0
    shown.SetRepresentationType(mmv.REPRESENTATION)
    return shown


gradient = simple.Gradient(Input=wavelet)  # 'Gradient', three components
gradient.ScalarArray = ["POINTS", "RTData"]
speed = simple.Calculator(Input=gradient)
speed.ResultArrayName = "GradientMagnitude"
speed.Function = "mag(Gradient)"
speed.ResultArrayType = "Float"
x = simple.Calculator(Input=gradient)
x.ResultArrayName = "GradientX"
x.Function = "abs(Gradient_X)"
x.ResultArrayType = "Float"
absolute = simple.Calculator(Input=gradient)  # |components|: the ramp starts at 0
absolute.ResultArrayName = "AbsGradient"
absolute.Function = "abs(Gradient_X)*iHat+abs(Gradient_Y)*jHat+abs(Gradient_Z)*kHat"
absolute.ResultArrayType = "Float"

scalar = show_array(speed, "GradientMagnitude")
reference = shot(view, "PVGradientMagnitudeScalar.png")
checker.check(mmv.check_not_blank(reference, "precomputed magnitude"), "the magnitude is drawn")
simple.Delete(scalar)

magnitude = show_array(gradient, "Gradient",
                       lambda lut: setattr(lut, "VectorMode", "Magnitude"))
by_magnitude = shot(view, "PVGradientMagnitude.png")
checker.check(mmv.info(magnitude, "MultiMaterialActive") == 1,
              "a vector by Magnitude is shaded with materials")
value = mmv.psnr(by_magnitude, reference)
checker.check(value >= 40.0, "Magnitude vs the Calculator's magnitude: PSNR %.1f dB" % value)
simple.Delete(magnitude)

scalar_x = show_array(x, "GradientX")
reference_x = shot(view, "PVGradientXScalar.png")
simple.Delete(scalar_x)


def component_x(lut):
    lut.VectorMode = "Component"
    lut.VectorComponent = 0


component = show_array(absolute, "AbsGradient", component_x)
by_component = shot(view, "PVGradientX.png")
checker.check(mmv.info(component, "MultiMaterialActive") == 1,
              "a vector by its X component is shaded with materials")
value = mmv.psnr(by_component, reference_x)
checker.check(value >= 40.0, "X component vs the Calculator's X: PSNR %.1f dB" % value)
different = mmv.psnr(by_component, reference)
checker.check(different < 30.0, "and differs from the magnitude (PSNR %.1f dB)" % different)
simple.Delete(component)

log = errors.take_errors()
checker.check(log == "", "no VTK errors: %r" % log[:500])
checker.finish()
