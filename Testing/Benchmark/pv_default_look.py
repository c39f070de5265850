"""The default image beside ParaView's Volume, and the environment light's look.

    xvfb-run -a -s "-noreset -screen 0 1280x1024x24" \\
        scripts/pvpython Testing/Benchmark/pv_default_look.py [--out DIR]

The head (Testing/Data/headsq.vti resampled to 256 x 256 x 128) with the
colour and opacity maps of pv_lightkit_orbit.py, a front view, 320 x 320,
ParaView's default light kit and background colour. Five panels, left to
right:
  Volume                 ParaView's Volume, Shade on
  default                Multi-Material Volume at its defaults
  no shadows             the default material with attenuation 0
  sky                    the same with EnvironmentLighting 1
  sky, ka x 0.35, kd x 0.3
                         EnvironmentLighting 1 and the default material's
                         ka and kd scaled as the physical calibration's
                         single scale for every scene (docs/performance.md)
Writes OUT/default_look.png and OUT/default_look.csv (per panel: the mean
luminance 0-255 over the pixels Volume draws, its ratio to Volume's, and
the 95th percentile: the lit surfaces) and prints the CSV.
"""

import csv
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "..", "Python"))

from paraview import simple  # noqa: E402
from paraview.vtk.util import numpy_support  # noqa: E402
from vtkmodules.vtkIOImage import vtkPNGWriter  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkImageData  # noqa: E402
import numpy  # noqa: E402

import pv_gallery  # noqa: E402
import pv_lightkit_orbit as orbit  # noqa: E402
from mmv_testing import read_png  # noqa: E402

# ParaView 5.11's default background colour.
BACKGROUND = [0.32, 0.34, 0.43]
# The default material's 12 parameters (Filters/vtkMultiMaterialParameters.h)
# with ka and kd scaled by the calibration's 0.35 and 0.3.
SCALED_DEFAULT = [0.2 * 0.35, 0.7 * 0.3, 0.2, 20.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0]
# The default material without shadows (attenuation 0).
UNSHADOWED_DEFAULT = [0.2, 0.7, 0.2, 20.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0]

PANELS = [
    ("Volume", "Volume", {"Shade": 1}),
    ("default", orbit.MMV, {}),
    ("no shadows", orbit.MMV,
     {"MaterialPreset": "Custom", "MaterialNodes": [orbit.SCALAR_RANGE[0]] + UNSHADOWED_DEFAULT}),
    ("sky", orbit.MMV, {"EnvironmentLighting": 1.0}),
    ("sky, ka x 0.35, kd x 0.3", orbit.MMV,
     {"EnvironmentLighting": 1.0, "MaterialPreset": "Custom",
      "MaterialNodes": [orbit.SCALAR_RANGE[0]] + SCALED_DEFAULT}),
]


def write_png(path, rgb):
    h, w, _ = rgb.shape
    image = vtkImageData()
    image.SetDimensions(w, h, 1)
    flat = numpy.ascontiguousarray(rgb.reshape(-1, 3).astype(numpy.uint8))
    array = numpy_support.numpy_to_vtk(flat, deep=1)
    image.GetPointData().SetScalars(array)
    writer = vtkPNGWriter()
    writer.SetFileName(path)
    writer.SetInputData(image)
    writer.Write()


def luminance(rgb):
    return 0.2126 * rgb[:, :, 0] + 0.7152 * rgb[:, :, 1] + 0.0722 * rgb[:, :, 2]


def main():
    args = pv_gallery.parse_args(__doc__, view_size=320)
    if not orbit.start(args):
        return 1
    source, _, _ = orbit.resampled_head(args)
    images = []
    for name, representation, props in PANELS:
        view = orbit.make_view(args)
        view.Background = BACKGROUND
        method = orbit.Method(name, representation, props, None)
        rep = orbit.show(method, source, view)
        if rep is None:
            print("ERROR: %s: %s" % (name, "; ".join(method.notes)))
            return 1
        orbit.place_camera(view, args)
        view.SMProxy.StillRender()
        path = os.path.join(args.out, "default_look_panel.png")
        simple.SaveScreenshot(path, view, ImageResolution=[args.view_size] * 2,
                              TransparentBackground=0)
        images.append(read_png(path))
        os.remove(path)
        simple.Delete(view)

    # The volume's pixels: where Volume's image differs from the background.
    background = numpy.array(BACKGROUND) * 255.0
    mask = numpy.abs(images[0] - background).max(axis=2) > 2.0
    reference = luminance(images[0])[mask].mean()
    rows = []
    for (name, _, _), rgb in zip(PANELS, images):
        values = luminance(rgb)[mask]
        mean = values.mean()
        rows.append({"panel": name, "mean_luminance": "%.1f" % mean,
                     "over_volume": "%.2f" % (mean / reference),
                     "p95_luminance": "%.1f" % numpy.percentile(values, 95)})
    with open(os.path.join(args.out, "default_look.csv"), "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        writer.writeheader()
        writer.writerows(rows)
    for row in rows:
        print("%-26s mean luminance %s (%s x Volume's), 95th percentile %s"
              % (row["panel"], row["mean_luminance"], row["over_volume"], row["p95_luminance"]))
    # vtkPNGReader's rows run bottom-up; the writer takes them back the same way.
    write_png(os.path.join(args.out, "default_look.png"), numpy.concatenate(images, axis=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
