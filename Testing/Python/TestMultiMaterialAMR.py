"""Overlapping AMR in the Multi-Material Volume representation: ParaView's
AMR representation offers it, and the blocks are resampled to image data
(SamplingDimensions) as unstructured grids are. A Gaussian pulse (3 blocks
on 2 levels, 605 cells), coloured by its cell array, must be shaded with
materials, report what the resampling cost, and render as the same AMR
resampled by hand with ResampleToImage at the same dimensions (PSNR >= 40
dB). An AMR with no cells (no levels, or a level whose block holds no data)
must warn, draw nothing and not crash.

Under `mpiexec -np N pvbatch` (--mpi-reference), -np 1 writes a reference
image of the AMR and every N > 1 must reproduce it (PSNR >= 40 dB): each
rank resamples its blocks into its piece of one image (vtkPResampleToImage).

With --server-port N (run_client_server.py) the same checks run connected
to a pvserver that renders (remote rendering): the representation, its
resampling and its information properties live on the server."""

import argparse
import os

import numpy

from paraview import simple
from paraview import servermanager

import mmv_testing as mmv

args = mmv.parse_args()
parser = argparse.ArgumentParser()
parser.add_argument("--mpi-reference", action="store_true")
parser.add_argument("--server-port", type=int)
options, _ = parser.parse_known_args()
if options.server_port:
    simple.Connect("localhost", options.server_port)
    # The server renders for any data size.
    simple.GetSettingsProxy("RenderViewSettings").RemoteRenderThreshold = 0
mmv.load_plugin(args)
checker = mmv.Checker()
errors = mmv.ErrorCapture()
# Client/server images are kept apart from the builtin session's.
TAG = "cs" if options.server_port else ""
if options.server_port:
    connection = servermanager.ActiveConnection
    checker.check(connection.IsRemote(), "connected to a pvserver")
    ranks = connection.GetNumberOfDataPartitions()
else:
    ranks = servermanager.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()
DIMS = [40, 40, 40]
ARRAY = "Gaussian-Pulse"
CENTRE = [-0.75, -0.75, 1.25]


simple._DisableFirstRenderCameraReset()
view = mmv.make_view()
lut = simple.GetColorTransferFunction(ARRAY)
lut.AutomaticRescaleRangeMode = "Never"
pwf = simple.GetOpacityTransferFunction(ARRAY)

# The pulse in the middle of the AMR's box (x, y in [-2, 0.5], z in [0, 2.5]);
# the two level-1 blocks cover part of it at half the spacing.
pulse = simple.AMRGaussianPulseSource()
pulse.PulseAmplitude = 1.0
pulse.XPulseOrigin, pulse.YPulseOrigin, pulse.ZPulseOrigin = CENTRE
pulse.XPulseWidth = pulse.YPulseWidth = pulse.ZPulseWidth = 0.8
pulse.UpdatePipeline()
cells = pulse.GetDataInformation().GetNumberOfCells()
print("AMR: %d cells, %s" % (cells, pulse.GetDataInformation().DataInformation.GetDataSetTypeAsString()))
# The source makes every block on every rank: under MPI each rank holds all.
checker.check(cells == 605 * ranks, "the AMR has its 605 cells (3 blocks on 2 levels) on each "
              "of %d ranks: %d" % (ranks, cells))


def show(source, association, dims=None):
    shown = simple.Show(source, view)
    if dims:
        shown.SamplingDimensions = dims
    # Coloured first: a display without arrays switched from Solid Color is
    # told that nothing can be drawn (an error), which is not what this tests.
    simple.ColorBy(shown, (association, ARRAY))
    shown.SetRepresentationType(mmv.REPRESENTATION)
    lut.ApplyPreset("Cool to Warm", True)
    lut.RescaleTransferFunction(0.0, 1.0)
    pwf.Points = [0.0, 0.0, 0.5, 0.0, 0.15, 0.0, 0.5, 0.0, 0.5, 0.6, 0.5, 0.0,
                  1.0, 0.9, 0.5, 0.0]
    shown.ScalarOpacityUnitDistance = 0.2
    shown.MaterialPreset = "bone"
    view.CameraPosition = [CENTRE[0] + 7.0, CENTRE[1] - 5.5, CENTRE[2] + 4.5]
    view.CameraFocalPoint = CENTRE
    view.CameraViewUp = [0.0, 0.0, 1.0]
    view.CameraViewAngle = 30.0
    return shown


shown = show(pulse, "CELLS", DIMS)
print("AMR display: %s" % shown.GetXMLName())
available = list(shown.GetProperty("Representation").Available)
checker.check(mmv.REPRESENTATION in available,
              "AMR is offered %s: %s" % (mmv.REPRESENTATION, available))
checker.check(shown.Representation == mmv.REPRESENTATION,
              "the AMR display shows %s: %s" % (mmv.REPRESENTATION, shown.Representation))
image = mmv.render_image(view, os.path.join(args.temp_dir, "PVAMR_%s%d.png" % (TAG, ranks)))
checker.check(mmv.info(shown, "MultiMaterialActive") == 1, "the AMR is shaded with materials")
checker.check(mmv.check_not_blank(image, "AMR"), "the AMR is drawn")
info = mmv.info(shown, "ResampleInfo")
print("AMR: %s" % info)
checker.check("(3 blocks in 2 levels, 605 cells) resampled to 40x40x40 points in" in info,
              "the resampling is reported: %r" % info)
# A render with no change resamples nothing: the report stays the same.
mmv.render_image(view, os.path.join(args.temp_dir, "PVAMRAgain_%s%d.png" % (TAG, ranks)))
checker.check(mmv.info(shown, "ResampleInfo") == info,
              "a second render does not resample again")
simple.Hide(pulse, view)

by_hand = simple.ResampleToImage(Input=pulse)
by_hand.SamplingDimensions = DIMS
by_hand.UseInputBounds = 1
manual = show(by_hand, "POINTS")
reference = mmv.render_image(view, os.path.join(args.temp_dir, "PVAMRByHand_%s%d.png" % (TAG, ranks)))
value = mmv.psnr(image, reference)
checker.check(value >= 40.0, "AMR vs ResampleToImage by hand: PSNR %.1f dB" % value)
simple.Hide(by_hand, view)

# Other SamplingDimensions resample again (and change the image).
shown = simple.Show(pulse, view)
shown.SamplingDimensions = [12, 12, 12]
coarse = mmv.render_image(view, os.path.join(args.temp_dir, "PVAMRCoarse_%s%d.png" % (TAG, ranks)))
info = mmv.info(shown, "ResampleInfo")
checker.check("resampled to 12x12x12 points" in info,
              "new SamplingDimensions resample again: %r" % info)
value = mmv.psnr(image, coarse)
checker.check(value < 40.0, "12^3 samples draw another image than 40^3: PSNR %.1f dB" % value)
simple.Hide(pulse, view)

# The pulse's blocks that KEEP (an expression of the block's number k, its
# level, this rank and the ranks) selects; the others are left empty.
SELECTED_BLOCKS = """
from vtkmodules.vtkFiltersAMR import vtkAMRGaussianPulseSource
from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline as sddp
pulse = vtkAMRGaussianPulseSource()
pulse.SetPulseAmplitude(1.0)
pulse.SetPulseOrigin(%r)
pulse.SetPulseWidth(0.8, 0.8, 0.8)
pulse.Update()
whole = pulse.GetOutput()
levels = whole.GetNumberOfLevels()
out = self.GetOutput()
out.Initialize(levels, [whole.GetNumberOfDataSets(level) for level in range(levels)])
out.SetOrigin(whole.GetDataSet(0, 0).GetOrigin())
out.SetGridDescription(whole.GetGridDescription())
request = self.GetOutputInformation(0)
ranks = request.Get(sddp.UPDATE_NUMBER_OF_PIECES()) or 1
rank = request.Get(sddp.UPDATE_PIECE_NUMBER())
k = 0
for level in range(levels):
    spacing = [0.0, 0.0, 0.0]
    whole.GetSpacing(level, spacing)
    out.SetSpacing(level, spacing)
    for index in range(whole.GetNumberOfDataSets(level)):
        out.SetAMRBox(level, index, whole.GetAMRBox(level, index))
        if KEEP:
            out.SetDataSet(level, index, whole.GetDataSet(level, index))
        k += 1
""" % (CENTRE,)


def selected_blocks(keep):
    source = simple.ProgrammableSource(OutputDataSetType="vtkHierarchicalBoxDataSet")
    source.Script = SELECTED_BLOCKS.replace("KEEP", keep)
    source.UpdatePipeline()
    return source


# The finest block that holds a point gives its value: the level-0 block alone
# (the whole box at twice the spacing) draws another image.
coarse_only = selected_blocks("level == 0")
shown = show(coarse_only, "CELLS", DIMS)
level0 = mmv.render_image(view, os.path.join(args.temp_dir, "PVAMRLevel0_%s%d.png" % (TAG, ranks)))
value = mmv.psnr(image, level0)
checker.check(value < 40.0, "level 0 alone draws another image than both levels: PSNR %.1f dB"
              % value)
simple.Hide(coarse_only, view)


def check_against_one_rank(source, what):
    """The image at -np N must equal -np 1's (written by -np 1)."""
    shown = show(source, "CELLS", DIMS)
    path = os.path.join(args.temp_dir, "PVAMR%s_%d.png" % (what, ranks))
    picture = mmv.render_image(view, path)
    print("%s: %s" % (what, mmv.info(shown, "ResampleInfo")))
    checker.check(mmv.info(shown, "MultiMaterialActive") == 1, "%s: shaded with materials" % what)
    reference = os.path.join(args.temp_dir, "PVAMR%s_1.png" % what)
    if ranks > 1:
        checker.check(os.path.exists(reference), "the -np 1 reference exists (%s)" % reference)
        if os.path.exists(reference):
            value = mmv.psnr(picture, mmv.read_png(reference))
            checker.check(value >= 40.0, "%s: -np %d vs -np 1: PSNR %.1f dB" % (what, ranks, value))
    simple.Hide(source, view)


if options.mpi_reference:
    check_against_one_rank(pulse, "Whole")
    # As AMR readers deliver it under MPI: each rank holds a share of the
    # blocks (block k on rank k % ranks), the others are empty there; where a
    # fine block on one rank covers a coarse block on another, the fine one
    # must win.
    distributed = selected_blocks("k % ranks == rank")
    cells = distributed.GetDataInformation().GetNumberOfCells()
    checker.check(cells == 605, "the distributed AMR has 605 cells over %d ranks: %d"
                  % (ranks, cells))
    check_against_one_rank(distributed, "Distributed")

# No cells: a warning, nothing drawn, no crash. `levels` 0: no levels at
# all; 1: one level with one block that holds no data set. (In a function:
# the programmable source's script runs in this interpreter and its imports,
# numpy's among them, replace global names.)
def check_without_cells(levels):
    source = simple.ProgrammableSource(OutputDataSetType="vtkHierarchicalBoxDataSet")
    source.Script = "self.GetOutput().Initialize(%d, [1] * %d)" % (levels, levels)
    source.UpdatePipeline()
    errors.take()
    nothing = show(source, "CELLS", DIMS)
    checker.check(nothing.Representation == mmv.REPRESENTATION,
                  "an empty AMR shows %s: %s" % (mmv.REPRESENTATION, nothing.Representation))
    blank = mmv.render_image(view, os.path.join(args.temp_dir,
                                                "PVAMREmpty%d_%d.png" % (levels, ranks)))
    text = errors.take()
    checker.check("the data have no cells" in text,
                  "an AMR with %d levels and no cells says so: %r"
                  % (levels, text[text.find("the data have no cells") - 100:][:300]))
    covered = float(numpy.mean(numpy.any(numpy.abs(blank - blank[0, 0]) > 8, axis=2)))
    checker.check(covered == 0.0, "an empty AMR draws nothing: %.3f of the pixels" % covered)
    print("empty AMR (%d levels): %s" % (levels, mmv.info(nothing, "ResampleInfo")))
    simple.Delete(nothing)
    simple.Delete(source)


for levels in (0, 1):
    check_without_cells(levels)

log = errors.take_errors()
checker.check(log == "", "no VTK errors: %r" % log[:500])
checker.finish()
