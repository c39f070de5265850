"""Data other than image data in the Multi-Material Volume representation:
unstructured, structured and rectilinear grids are offered the
representation and resampled to image data (SamplingDimensions, shared with
Volume's where Volume has it) as Volume's "Resample To Image" does. Each must be shaded with materials and
render as the same data resampled by hand with ResampleToImage at the same
dimensions (PSNR >= 40 dB: the same filter on the same data should give the
same image), report what the resampling cost, and a grid with no cells must
warn, not crash."""

import os

from paraview import simple


import mmv_testing as mmv

args = mmv.parse_args()
mmv.load_plugin(args)
checker = mmv.Checker()
errors = mmv.ErrorCapture()
DIMS = [40, 40, 40]


# The camera is set for each image; without this the first render resets it.
simple._DisableFirstRenderCameraReset()
view = mmv.make_view()
wavelet = mmv.make_volume(extent=10)
lut = simple.GetColorTransferFunction("RTData")
lut.AutomaticRescaleRangeMode = "Never"
pwf = simple.GetOpacityTransferFunction("RTData")


def show(source, dims=None):
    shown = simple.Show(source, view)
    if dims:
        shown.SamplingDimensions = dims
    shown.SetRepresentationType(mmv.REPRESENTATION)
    lut.ApplyPreset("Cool to Warm", True)
    lut.RescaleTransferFunction(37.0, 277.0)
    pwf.Points = [37.0, 0.0, 0.5, 0.0, 160.0, 0.0, 0.5, 0.0, 200.0, 1.0, 0.5, 0.0,
                  277.0, 1.0, 0.5, 0.0]
    shown.ScalarOpacityUnitDistance = 1.0
    view.CameraPosition = [60.0, -45.0, 40.0]
    view.CameraFocalPoint = [0.0, 0.0, 0.0]
    view.CameraViewUp = [0.0, 0.0, 1.0]
    view.CameraViewAngle = 30.0
    return shown


# A rectilinear grid with uneven spacing (the UniformGridRepresentation path).
rectilinear = simple.ProgrammableSource()
rectilinear.OutputDataSetType = "vtkRectilinearGrid"
rectilinear.ScriptRequestInformation = """
executive = self.GetExecutive()
executive.GetOutputInformation(0).Set(executive.WHOLE_EXTENT(), 0, 20, 0, 20, 0, 20)
"""
rectilinear.Script = """
import math
from vtkmodules.vtkCommonCore import vtkDoubleArray, vtkFloatArray
out = self.GetRectilinearGridOutput()
xs = [-10.0 + 20.0 * (i / 20.0) ** 1.3 for i in range(21)]
def coordinates():
    a = vtkDoubleArray()
    for x in xs:
        a.InsertNextValue(x)
    return a
out.SetDimensions(21, 21, 21)
out.SetXCoordinates(coordinates())
out.SetYCoordinates(coordinates())
out.SetZCoordinates(coordinates())
values = vtkFloatArray()
values.SetName("RTData")
for k in range(21):
    for j in range(21):
        for i in range(21):
            r = math.sqrt(xs[i] ** 2 + xs[j] ** 2 + xs[k] ** 2)
            values.InsertNextValue(277.0 - 12.0 * r)
out.GetPointData().AddArray(values)
"""

for name, grid in (("unstructured", simple.Tetrahedralize(Input=wavelet)),
                   ("structured", simple.Transform(Input=wavelet)),
                   ("rectilinear", rectilinear)):
    shown = show(grid, DIMS)
    checker.check(mmv.REPRESENTATION in shown.GetProperty("Representation").Available,
                  "%s grids are offered %s" % (name, mmv.REPRESENTATION))
    image = mmv.render_image(view, os.path.join(args.temp_dir, "PVResampled_%s.png" % name))
    checker.check(mmv.info(shown, "MultiMaterialActive") == 1,
                  "the %s grid is shaded with materials" % name)
    checker.check(mmv.check_not_blank(image, name), "the %s grid is drawn" % name)
    info = mmv.info(shown, "ResampleInfo")
    print("%s: %s" % (name, info))
    checker.check("resampled to 40x40x40 points in" in info, "the resampling is reported: %r" % info)
    simple.Delete(shown)

    by_hand = simple.ResampleToImage(Input=grid)
    by_hand.SamplingDimensions = DIMS
    by_hand.UseInputBounds = 1
    manual = show(by_hand)
    reference = mmv.render_image(view, os.path.join(args.temp_dir,
                                                    "PVResampledByHand_%s.png" % name))
    value = mmv.psnr(image, reference)
    checker.check(value >= 40.0, "%s grid vs ResampleToImage by hand: PSNR %.1f dB" % (name, value))
    simple.Delete(manual)
    simple.Delete(by_hand)

# No cells: a warning, nothing drawn, no crash.
empty = simple.Threshold(Input=simple.Tetrahedralize(Input=wavelet))
empty.Scalars = ["POINTS", "RTData"]
if empty.GetProperty("LowerThreshold") is not None:
    empty.LowerThreshold = 1000.0
    empty.UpperThreshold = 2000.0
else:
    empty.ThresholdRange = [1000.0, 2000.0]
empty.UpdatePipeline()
errors.take()
nothing = show(empty, DIMS)
mmv.render_image(view, os.path.join(args.temp_dir, "PVResampledEmpty.png"))
log = errors.take()
checker.check("the data have no cells" in log, "a grid with no cells says so: %r"
              % log[log.find("the data have no cells") - 100:][:300])
simple.Delete(nothing)

log = errors.take_errors()
checker.check(log == "", "no VTK errors: %r" % log[:500])
checker.finish()
