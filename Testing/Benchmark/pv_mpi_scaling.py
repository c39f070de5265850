"""Irradiance-update time and bytes exchanged against the number of MPI
ranks (docs/scaling.md, "Time and bytes per update"). Run under
`mpiexec --allow-run-as-root --oversubscribe -np N pvbatch pv_mpi_scaling.py
--plugin PLUGIN --csv FILE [--size S] [--reps R]`.

A Wavelet of S^3 points (default 128) split among the ranks, the
Multi-Material Volume with IrradianceScale 0.5 (the same grid on any number
of ranks) and one directional scene light. Measured on rank 0, medians over
R: the exchange that builds the global grid (forced again by nudging
IrradianceMemoryMB, which changes nothing else) and the bytes it sends per
rank; the irradiance update after a light move (the mapper's own timer), the
voxels x lights it estimated and that still frame's wall time, with each rank
estimating what its piece reads (PieceIrradianceOnly, default) and the whole
grid, interleaved; a frame with nothing changed. Appends two CSV lines per
run. Not a test."""

import argparse
import os
import re
import time

from paraview import simple
from paraview import servermanager

parser = argparse.ArgumentParser()
parser.add_argument("--plugin", required=True)
parser.add_argument("--csv", required=True)
parser.add_argument("--size", type=int, default=128)
parser.add_argument("--reps", type=int, default=5)
args, _ = parser.parse_known_args()
simple.LoadPlugin(args.plugin, remote=True)
ranks = servermanager.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()


def info(rep, name):
    rep.SMProxy.UpdatePropertyInformation()
    prop = rep.SMProxy.GetProperty(name)
    helper = servermanager.vtkSMPropertyHelper(prop)
    if isinstance(prop, servermanager.vtkSMStringVectorProperty):
        return helper.GetAsString(0)
    return helper.GetAsDouble(0)


def median(values):
    values = sorted(values)
    return values[len(values) // 2] if values else float("nan")


view = simple.CreateView("RenderView")
view.ViewSize = [400, 400]
view.OrientationAxesVisibility = 0
view.UseLight = 0
light = simple.AddLight(view=view)
light.Coords = "Scene"
light.Type = "Directional"
light.FocalPoint = [0.0, 0.0, 0.0]
light.Position = [10.0, 20.0, 100.0]
half = args.size // 2
wavelet = simple.Wavelet()
wavelet.WholeExtent = [-half, args.size - half - 1] * 3
rep = simple.Show(wavelet, view)
rep.Representation = "Multi-Material Volume"
simple.ColorBy(rep, ("POINTS", "RTData"))
simple.GetOpacityTransferFunction("RTData").Points = [37.0, 0.0, 0.5, 0.0, 150.0, 0.0, 0.5, 0.0,
                                                      200.0, 0.8, 0.5, 0.0, 277.0, 0.8, 0.5, 0.0]
rep.MaterialPreset = "bone"
rep.IrradianceScale = 0.5
view.CameraPosition = [3.0 * args.size, -2.0 * args.size, 1.5 * args.size]
view.CameraFocalPoint = [0.0, 0.0, 0.0]
view.CameraViewUp = [0.0, 0.0, 1.0]
start = time.perf_counter()
simple.Render(view)
first = time.perf_counter() - start

exchange, sent = [], 0
for r in range(args.reps):
    rep.IrradianceMemoryMB = 64.0 + (r % 2 + 1) * 0.5  # a new key, the same grid
    simple.Render(view)
    text = info(rep, "GlobalIrradianceInfo")
    match = re.search(r"(\d+) bytes sent per rank; ([0-9.e-]+) s", text)
    if match:
        sent = int(match.group(1))
        exchange.append(float(match.group(2)))
# Each rank estimating what its piece reads (PieceIrradianceOnly, the
# default) and the whole global grid, interleaved: a light move each time.
modes = {1: "piece", 0: "whole"}
irradiance = {m: [] for m in modes}
voxels = {m: [] for m in modes}
lightFrame = {m: [] for m in modes}
still = []
for r in range(args.reps):
    for mode in modes:
        rep.PieceIrradianceOnly = mode
        light.Position = [10.0 + 5.0 * (r + 1) + mode, 20.0, 100.0]
        start = time.perf_counter()
        simple.Render(view)
        lightFrame[mode].append(time.perf_counter() - start)
        irradiance[mode].append(info(rep, "LastIrradianceSeconds"))
        voxels[mode].append(info(rep, "LastEstimatedIrradianceVoxels"))
    start = time.perf_counter()
    simple.Render(view)
    still.append(time.perf_counter() - start)

grid = re.match(r"(\S+)", info(rep, "IrradianceResolutionInfo")).group(1)
header = ("ranks,size,irradiance_grid,mode,rank0_estimated_voxels,bytes_sent_per_rank,exchange_s,"
          "irradiance_update_s,light_move_frame_s,still_frame_s,first_frame_s")
print(header)
fresh = not os.path.exists(args.csv)
with open(args.csv, "a") as f:
    if fresh:
        f.write(header + "\n")
    for mode, name in modes.items():
        line = "%d,%d,%s,%s,%d,%d,%s,%.3f,%.3f,%.3f,%.2f" % (
            ranks, args.size, grid, name, median(voxels[mode]), sent,
            ("%.4f" % median(exchange)) if exchange else "", median(irradiance[mode]),
            median(lightFrame[mode]), median(still), first)
        print(line)
        f.write(line + "\n")
