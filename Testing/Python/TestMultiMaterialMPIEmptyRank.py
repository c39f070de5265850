"""Ranks without data must not hang the global-shadow exchange:
a volume of one cell (2 x 2 x 2 points) cannot be split, so under
`mpiexec -np 3 pvbatch` two of the three ranks get an empty piece. Every rank
still reaches every collective call: the script ends (ctest's timeout would
catch a hang), rank 0 shades its piece from the global grid, and no rank
reports an error."""

import os

from paraview import simple
from paraview import servermanager
from vtkmodules.vtkCommonExecutionModel import vtkExtentTranslator

import mmv_testing as mmv

args = mmv.parse_args()
simple.LoadPlugin(args.plugin, remote=True)
checker = mmv.Checker()
errors = mmv.ErrorCapture()
ranks = servermanager.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()
checker.check(ranks >= 2, "running on %d ranks" % ranks)

WHOLE = [0, 1, 0, 1, 0, 1]
translator = vtkExtentTranslator()
translator.SetWholeExtent(WHOLE)
translator.SetNumberOfPieces(ranks)
empty = 0
for piece in range(ranks):
    translator.SetPiece(piece)
    translator.PieceToExtent()
    extent = translator.GetExtent()
    empty += 1 if any(extent[2 * a] > extent[2 * a + 1] for a in range(3)) else 0
    print("piece %d: extent %s" % (piece, list(extent)))
checker.check(empty >= 1, "%d of %d ranks have no data" % (empty, ranks))

view = mmv.make_view()
wavelet = simple.Wavelet()
wavelet.WholeExtent = WHOLE
rep = mmv.show_volume(wavelet, view, preset="bone")
view.CameraPosition = [4.0, -3.0, 3.0]
view.CameraFocalPoint = [0.5, 0.5, 0.5]
low, high = wavelet.PointData["RTData"].GetRange()
simple.GetOpacityTransferFunction("RTData").Points = [low, 0.8, 0.5, 0.0, high, 0.8, 0.5, 0.0]
image = mmv.render_image(view, os.path.join(args.temp_dir, "PVMultiMaterialMPIEmpty_%d.png" % ranks))
# Twice: the second update must not exchange again, nor hang.
simple.Render(view)
checker.check(mmv.check_not_blank(image, "one-cell volume"), "the volume is drawn")
info = mmv.info(rep, "GlobalIrradianceInfo")
print("global irradiance: %s" % info)
checker.check(("over %d ranks" % ranks) in info, "rank 0 lights its piece from the global grid")
checker.check(mmv.info(rep, "MultiMaterialActive") == 1, "rank 0 shaded with materials")
checker.check(errors.take_errors() == "", "no VTK errors on rank 0")
checker.finish()
