"""Frame time and error of each Lighting Quality level of the Multi-Material
Volume representation, against Exact, in ParaView (pvpython).

For each data set and level: the level is set, one still frame is rendered
to warm up, then the light kit is turned (the camera orbits 10 degrees, so
every light's irradiance is recomputed) and the still frame after it is
timed, three times; the median is reported with the PSNR (dB, 8-bit RGB)
of the last frame against the Exact level's frame of the same camera.

    scripts/pvpython Testing/Benchmark/pv_lighting_quality.py DATA.vti [DATA2.vti ...]
"""

import argparse
import math
import os
import statistics
import time

import numpy
from paraview import simple
from vtkmodules.util.numpy_support import vtk_to_numpy

LEVELS = ["Fast", "Balanced", "Exact"]


def frame(view):
    path = "/tmp/mmv_lq_frame.png"
    simple.SaveScreenshot(path, view, ImageResolution=view.ViewSize)
    from vtkmodules.vtkIOImage import vtkPNGReader
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    data = reader.GetOutput()
    return vtk_to_numpy(data.GetPointData().GetScalars())[:, :3].astype(numpy.float64)


def psnr(a, b):
    mse = float(numpy.mean((a - b) ** 2))
    return float("inf") if mse == 0 else 10.0 * math.log10(255.0 ** 2 / mse)


def measure(path, size):
    reader = simple.XMLImageDataReader(FileName=[path])
    view = simple.CreateView("RenderView")
    view.ViewSize = [size, size]
    view.OrientationAxesVisibility = 0
    if view.GetProperty("UseColorPaletteForBackground") is not None:
        view.UseColorPaletteForBackground = 0
    view.Background = [0.1, 0.1, 0.15]
    display = simple.Show(reader, view)
    array = reader.PointData.keys()[0]
    simple.ColorBy(display, ("POINTS", array))
    display.SetRepresentationType("Multi-Material Volume")
    lo, hi = reader.PointData[array].GetRange()
    simple.GetOpacityTransferFunction(array).Points = [
        lo, 0.0, 0.5, 0.0, lo + 0.3 * (hi - lo), 0.0, 0.5, 0.0, hi, 0.8, 0.5, 0.0]
    display.MaterialPreset = "skin"
    view.ResetCamera()
    results = {}
    for level in reversed(LEVELS):  # Exact first: the reference
        display.LightingQuality = level
        camera = view.GetActiveCamera()
        simple.Render(view)
        times = []
        for _ in range(3):
            camera.Azimuth(10.0)
            start = time.perf_counter()
            simple.Render(view)
            times.append(time.perf_counter() - start)
        image = frame(view)
        for _ in range(3):
            camera.Azimuth(-10.0)
        results[level] = (statistics.median(times), image)
    simple.Delete(display)
    simple.Delete(view)
    simple.Delete(reader)
    reference = results["Exact"][1]
    for level in LEVELS:
        seconds, image = results[level]
        print("%-28s %-9s %7.2f s  %s" % (os.path.basename(path), level, seconds,
              "reference" if level == "Exact" else "%.1f dB" % psnr(image, reference)), flush=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("data", nargs="+")
    parser.add_argument("--size", type=int, default=400)
    args = parser.parse_args()
    simple.LoadDistributedPlugin("MultiMaterialVolume")
    for path in args.data:
        measure(path, args.size)


if __name__ == "__main__":
    main()
