"""Global shadows under MPI: a plate casts a shadow on a floor
below it; the volume is split along z, so with 2, 3 or 4 ranks the plate and the
floor sit on different ranks. Run with `mpiexec -np N pvbatch` after the
`-np 1` run, which writes the reference image; every N must reproduce it
within PSNR >= 40 dB. Before global shadows, -np 3 differed by 23.5 dB: the
shadow disappeared.

With --blocks, every rank's piece is split in two image partitions (a
vtkPartitionedDataSet, as readers of multiblock image data produce): the
representation merges them, and the image must equal the -np 1 reference of
the plain pieces. With --tinted, the material has a transmission colour
(tinted shadows): -np 1 writes its own reference, -np 3 must equal it. With
--reflective, the `metal` preset reflects the view's background, which the
ranks must see as -np 1 does (before it was pinned: 32.7 dB). With --vector,
the field is a vector whose magnitude is the plain field, coloured by
Magnitude: every rank lights the magnitude, and -np 3 must equal the plain
-np 1 reference. With --cells, the field is cell data (PointDatatoCellData of
it), lit on each piece's grid of cell centres: -np 1 writes its own
reference, -np 2 must equal it.

Each rank estimates only the irradiance its piece reads (PieceIrradianceOnly):
rank 0 must estimate a share of the global grid, and with the option off
(every rank the whole grid) the image must be identical."""

import argparse
import os

import numpy

from paraview import simple
from paraview import servermanager
from vtkmodules.vtkCommonExecutionModel import vtkExtentTranslator

import mmv_testing as mmv

args = mmv.parse_args()
parser = argparse.ArgumentParser()
parser.add_argument("--blocks", action="store_true")
parser.add_argument("--tinted", action="store_true")
parser.add_argument("--reflective", action="store_true")
parser.add_argument("--vector", action="store_true")
parser.add_argument("--cells", action="store_true")
options = parser.parse_known_args()[0]
vector = options.vector
cells = options.cells
split_into_blocks = options.blocks
tinted = options.tinted
reflective = options.reflective
simple.LoadPlugin(args.plugin, remote=True)
checker = mmv.Checker()
errors = mmv.ErrorCapture()
ranks = servermanager.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()

WHOLE = [-12, 12, -12, 12, -24, 24]
PLATE_Z = 14.0
FLOOR_Z = -18.0
PLATE = "exp(-((coordsZ-%g)/2.5)^8-(coordsX/7)^8-(coordsY/7)^8)" % PLATE_Z
FLOOR = "exp(-((coordsZ-(%g))/2.5)^8)" % FLOOR_Z

# Where ParaView's pieces split the volume: the plate and the floor must sit
# on different ranks, or this test proves nothing about crossing them.
translator = vtkExtentTranslator()
translator.SetWholeExtent(WHOLE)
translator.SetNumberOfPieces(ranks)
owners = {}
for piece in range(ranks):
    translator.SetPiece(piece)
    translator.PieceToExtent()
    extent = translator.GetExtent()
    print("piece %d of %d: extent %s" % (piece, ranks, list(extent)))
    for name, z in (("plate", PLATE_Z), ("floor", FLOOR_Z)):
        if extent[4] <= z <= extent[5]:
            owners.setdefault(name, set()).add(piece)
if ranks > 1:
    checker.check(owners["plate"].isdisjoint(owners["floor"]),
                  "plate (pieces %s) and floor (pieces %s) on different ranks"
                  % (sorted(owners["plate"]), sorted(owners["floor"])))

view = mmv.make_view()
mmv.add_directional_light(view, [8.0, 4.0, 100.0])  # the light kit follows the camera

wavelet = simple.Wavelet()
wavelet.WholeExtent = WHOLE
calculator = simple.Calculator(Input=wavelet)
calculator.ResultArrayName = "density"
source = calculator
if cells:
    source = simple.PointDatatoCellData(Input=calculator)
if split_into_blocks:
    # Each rank's piece as two partitions sharing their middle z plane.
    source = simple.ProgrammableFilter(Input=calculator)
    source.OutputDataSetType = "vtkPartitionedDataSet"
    source.Script = """
from vtkmodules.vtkCommonDataModel import vtkImageData
piece = self.GetInputDataObject(0, 0)
out = self.GetOutputDataObject(0)
e = piece.GetExtent()
if piece.GetNumberOfPoints() > 0:
    middle = (e[4] + e[5]) // 2
    for n, (z0, z1) in enumerate(((e[4], middle), (middle, e[5]))):
        block = vtkImageData()
        block.DeepCopy(piece)
        block.Crop((e[0], e[1], e[2], e[3], z0, z1))
        out.SetPartition(n, block)
"""


def show(expression):
    # As a vector (0.6, 0.8, 0) x the field: its magnitude is the field.
    calculator.Function = "(%s)*(0.6*iHat+0.8*jHat)" % expression if vector else expression
    rep = simple.Show(source, view)
    rep.Representation = mmv.REPRESENTATION
    simple.ColorBy(rep, ("CELLS" if cells else "POINTS", "density"))
    lut = simple.GetColorTransferFunction("density")
    if vector:
        lut.VectorMode = "Magnitude"
    lut.RGBPoints = [0.0, 0.9, 0.85, 0.8, 200.0, 0.9, 0.85, 0.8]
    pwf = simple.GetOpacityTransferFunction("density")
    pwf.Points = [0.0, 0.0, 0.5, 0.0, 60.0, 0.0, 0.5, 0.0, 150.0, 0.9, 0.5, 0.0,
                  200.0, 0.9, 0.5, 0.0]
    lut.AutomaticRescaleRangeMode = "Never"
    pwf.AllowDuplicateScalars = 1
    rep.ScalarOpacityUnitDistance = 1.0
    if tinted:
        # matte's shading with a blue-green transmission colour (13 numbers a
        # node: value, ka, kd, ks, shininess, c_t, s, r, g, e, T rgb).
        rep.MaterialPreset = "Custom"
        node = [0.2, 0.7, 0.1, 10.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.6, 0.85, 0.95]
        rep.MaterialNodes = [0.0] + node + [200.0] + node
    else:
        rep.MaterialPreset = "metal" if reflective else "matte"
    view.CameraPosition = [55.0, -70.0, 30.0]
    view.CameraFocalPoint = [0.0, 0.0, -4.0]
    view.CameraViewUp = [0.0, 0.0, 1.0]
    view.CameraViewAngle = 30.0
    return rep


rep = show("200*(%s+%s)" % (PLATE, FLOOR))
variant = "Blocks" if split_into_blocks else ("Vector" if vector else (
    "Tinted" if tinted else ("Reflective" if reflective else ("Cells" if cells else ""))))
path = os.path.join(args.temp_dir, "PVMultiMaterialMPIShadows%s_%d.png" % (variant, ranks))
image = mmv.render_image(view, path)
checker.check(mmv.check_not_blank(image, "plate and floor"), "the volume is visible")
checker.check(mmv.info(rep, "MultiMaterialActive") == 1, "rank 0 shaded with materials")
print("global irradiance: %s" % mmv.info(rep, "GlobalIrradianceInfo"))
resolution = mmv.info(rep, "IrradianceResolutionInfo")
print("irradiance: %s" % resolution)
# Rank 0 estimates what its piece reads (PieceIrradianceOnly, the default):
# the whole global grid alone, a share of it among ranks. Either way only
# around the bricks that may hold non-empty voxels (vtkVoxelOccupancy.h):
# the plate and the floor leave most of the grid empty.
grid = [int(n) for n in resolution.split(" ")[0].split("x")]
whole = grid[0] * grid[1] * grid[2]  # one light
estimated = mmv.info(rep, "LastEstimatedIrradianceVoxels")[0]
print("rank 0 estimated %d of the global grid's %d voxels (%.0f %%)"
      % (estimated, whole, 100.0 * estimated / whole))
if ranks == 1:
    checker.check(0 < estimated < whole, "one rank estimates the grid around the plate and the "
                  "floor (%d of %d)" % (estimated, whole))
else:
    checker.check(0 < estimated <= 0.75 * whole,
                  "rank 0 estimates its share of the grid (%d of %d voxels <= 75 %%)"
                  % (estimated, whole))


plain = split_into_blocks or vector  # compared with the plain -np 1 image
reference = os.path.join(args.temp_dir, "PVMultiMaterialMPIShadows%s_1.png"
                         % ("" if plain else variant))
if ranks == 1 and not plain:
    # The shadow is there to be kept: without the plate the floor is brighter.
    show("200*(%s)" % FLOOR)
    floorOnly = mmv.render_image(view, os.path.join(args.temp_dir, "PVMultiMaterialMPIFloor.png"))
    lit = mmv.psnr(image, floorOnly)
    print("plate + floor vs floor alone: PSNR %.1f dB" % lit)
    checker.check(lit < 30.0, "the plate and its shadow change the image (%.1f dB < 30)" % lit)
else:
    checker.check(os.path.exists(reference), "the -np 1 reference exists (%s)" % reference)
    if os.path.exists(reference):
        value = mmv.psnr(image, mmv.read_png(reference))
        what = "-np %d%s" % (ranks, {"Blocks": " in blocks", "Tinted": " tinted",
                                     "Reflective": " reflective",
                                     "Vector": " by vector magnitude",
                                     "Cells": " cell data"}.get(variant, ""))
        difference = float(numpy.mean(numpy.abs(image - mmv.read_png(reference))))
        print("%s vs -np 1: PSNR %.2f dB, mean |difference| %.3f" % (what, value, difference))
        checker.check(value >= 40.0, "%s equals -np 1 (PSNR %.2f dB >= 40)" % (what, value))
if ranks > 1 and variant in ("", "Reflective", "Cells"):
    # Every rank estimating the whole grid instead draws the same pixels:
    # the region's irradiance (and reflection visibility) equals the whole
    # grid's bit for bit.
    rep.PieceIrradianceOnly = 0
    wholeImage = mmv.render_image(view, os.path.join(
        args.temp_dir, "PVMultiMaterialMPIShadows%sWhole_%d.png" % (variant, ranks)))
    wholeEstimated = mmv.info(rep, "LastEstimatedIrradianceVoxels")[0]
    checker.check(estimated < wholeEstimated <= whole, "PieceIrradianceOnly off: rank 0 "
                  "estimates more than its piece's share (%d > %d, of %d)"
                  % (wholeEstimated, estimated, whole))
    value = mmv.psnr(image, wholeImage)
    print("piece regions vs whole grids at -np %d: PSNR %.2f dB" % (ranks, value))
    checker.check(value == float("inf"), "piece regions draw the same pixels as whole grids")
checker.check(errors.take_errors() == "", "no VTK errors on rank 0")
checker.finish()
