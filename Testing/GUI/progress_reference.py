"""The progress GUI test's reference (pvpython, offscreen): the same scene
and opacity edit as the client's (progress_scene.py), rendered where nothing
repaints during the update, and the PSNR of the client's image against it.

usage: pvpython progress_reference.py --plugin SO --out DIR --compare PNG
Raises (pvpython exits 1) below 40 dB; not sys.exit(), after which pvpython
5.11 crashes in its X11 teardown."""
import argparse
import math
import os
import sys

from paraview import simple
from vtkmodules.util import numpy_support
from vtkmodules.vtkIOImage import vtkPNGReader

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import progress_scene  # noqa: E402


def pixels(path):
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    scalars = image.GetPointData().GetScalars()
    return numpy_support.vtk_to_numpy(scalars)[:, :3].astype("float64"), image.GetDimensions()


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--plugin", required=True)
    p.add_argument("--out", required=True)
    p.add_argument("--compare", required=True)
    args = p.parse_args()
    simple.LoadPlugin(args.plugin, remote=False, ns=globals())
    view = simple.CreateRenderView()
    view.ViewSize = progress_scene.IMAGE_SIZE
    progress_scene.show(progress_scene.volume_path(args.out), view)
    progress_scene.edit_opacity()
    simple.Render(view)
    reference = os.path.join(args.out, "reference.png")
    simple.SaveScreenshot(reference, view, ImageResolution=progress_scene.IMAGE_SIZE)
    a, dims_a = pixels(reference)
    b, dims_b = pixels(args.compare)
    if dims_a != dims_b:
        raise RuntimeError("image sizes differ: %s and %s" % (dims_a, dims_b))
    mse = float(((a - b) ** 2).mean())
    psnr = float("inf") if mse == 0.0 else 10.0 * math.log10(255.0 ** 2 / mse)
    print("client's image against the pvpython reference: PSNR %s dB (max difference %d)"
          % ("inf" if math.isinf(psnr) else "%.1f" % psnr, int(abs(a - b).max())))
    if psnr < 40.0:
        raise RuntimeError("PSNR below 40 dB")


main()
