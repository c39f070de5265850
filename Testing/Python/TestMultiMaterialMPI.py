"""Run with `mpiexec -np 2 pvbatch`: the Wavelet is split between the ranks,
each rank renders its piece as a Multi-Material Volume and ParaView composites
them. Each rank computes irradiance from its own piece only, so shadows do not
cross the piece boundary: the image is compared with the serial baseline only
loosely, and the difference is printed."""

import os

from paraview import simple
from paraview import servermanager

import mmv_testing as mmv

args = mmv.parse_args()
# The plugin must be loaded on every rank: remote=True goes to the server
# side, which in pvbatch is all the ranks.
simple.LoadPlugin(args.plugin, remote=True)
checker = mmv.Checker()
errors = mmv.ErrorCapture()

ranks = servermanager.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()
checker.check(ranks >= 1, "running on %d rank(s)" % ranks)

view = mmv.make_view()
wavelet = mmv.make_volume()
rep = mmv.show_volume(wavelet, view, preset="bone")
path = os.path.join(args.temp_dir, "PVMultiMaterialVolumeMPI_%d.png" % ranks)
image = mmv.render_image(view, path)
checker.check(mmv.check_not_blank(image, "MPI render"), "the composited volume is visible")
checker.check(mmv.info(rep, "MultiMaterialActive") == 1, "rank 0 shaded with materials")

pieces = wavelet.GetDataInformation().DataInformation.GetNumberOfDataSets()
print("the data has %d piece(s)" % pieces)
if args.baseline_dir:
    baseline = mmv.read_png(os.path.join(args.baseline_dir, "PVMultiMaterialVolume.png"))
    d = mmv.mean_difference(image, baseline)
    print("mean |difference| from the serial baseline: %.3f" % d)
    # Loose: shadows and scattering stop at the rank boundary (see docs/paraview.md).
    checker.check(d < 25.0, "the image resembles the serial one")
checker.check(errors.take_errors() == "", "no VTK errors on rank 0")
checker.finish()
