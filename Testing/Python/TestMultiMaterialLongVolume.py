"""A volume longer than the largest 3D texture (2100 x 6 x 6 points; llvmpipe
allows 2048): VTK 9.2 does not partition it by itself and aborts the process
in vtkTextureObject::Bind (ParaView's own Volume representation still does).
The Multi-Material Volume must survive, say why, and draw the whole volume
in bricks, shaded with materials."""

import os

import numpy

from paraview import simple

import mmv_testing as mmv

args = mmv.parse_args()
mmv.load_plugin(args)
checker = mmv.Checker()
errors = mmv.ErrorCapture()

view = mmv.make_view()
wavelet = simple.Wavelet()
wavelet.WholeExtent = [0, 2099, 0, 5, 0, 5]
rep = mmv.show_volume(wavelet, view, preset="bone")
# Far from its centre the Wavelet falls below show_volume's opacity ramp:
# make the whole range visible, so that every brick shows.
low, high = wavelet.PointData["RTData"].GetRange()
simple.GetOpacityTransferFunction("RTData").Points = [low, 0.05, 0.5, 0.0, high, 0.3, 0.5, 0.0]
simple.GetColorTransferFunction("RTData").RescaleTransferFunction(low, high)
# 2100 x 500 x 500 units on screen, seen from the side.
rep.Scale = [1.0, 100.0, 100.0]
view.CameraFocalPoint = [1050.0, 250.0, 250.0]
view.CameraPosition = [1050.0, 250.0, 4500.0]
view.CameraViewUp = [0.0, 1.0, 0.0]
view.CameraParallelProjection = 1
view.CameraParallelScale = 1150.0

path = os.path.join(args.temp_dir, "PVMultiMaterialLongVolume.png")
image = mmv.render_image(view, path)
# Reaching this line is the first check: the process did not abort.
checker.check(mmv.check_not_blank(image, "long volume"), "the long volume is drawn")
background = image[0, 0]
columns = numpy.any(numpy.abs(image - background) > 8, axis=(0, 2))
shown = numpy.nonzero(columns)[0]
span = (shown[-1] - shown[0] + 1) / float(image.shape[1]) if len(shown) else 0.0
# The volume spans 2100 of the 2300 units the view shows across: 91% of the
# width; one missing brick would leave about half.
print("the volume spans %.1f%% of the width" % (100 * span))
checker.check(span > 0.85, "both bricks are drawn (%.2f of the width > 0.85)" % span)
checker.check(mmv.info(rep, "MultiMaterialActive") == 1, "the bricks are shaded with materials")
reported = errors.take_errors()
checker.check(reported == "", "no VTK error (%r)" % reported)
warnings = errors.take()
checker.check("2 x 1 x 1 bricks" in warnings, "the user is told the volume is rendered in bricks")
checker.finish()
