"""Shared pieces of the pvpython/pvbatch tests of the Multi-Material Volume plugin.

Every test script takes:
  --plugin PATH        MultiMaterialVolume.so (or set PV_PLUGIN_PATH)
  --baseline-dir DIR   Testing/Baseline
  --temp-dir DIR       where screenshots and state files go
Set MMV_GENERATE_BASELINES=1 to write missing or mismatching baselines
instead of failing (then look at them before committing them).
"""

import argparse
import math
import os

from paraview import simple
from paraview import servermanager

from vtkmodules.vtkCommonCore import vtkOutputWindow
from vtkmodules.util.misc import calldata_type
from vtkmodules.util.vtkConstants import VTK_STRING
from vtkmodules.vtkIOImage import vtkPNGReader
from vtkmodules.util.numpy_support import vtk_to_numpy

import numpy

REPRESENTATION = "Multi-Material Volume"
IMAGE_SIZE = [300, 300]
# Mean absolute difference per 8-bit channel allowed against a baseline.
# Mesa llvmpipe is deterministic on one machine; the margin absorbs other
# rasterizers' rounding, while a changed material or light moves the mean by
# far more (see the property tests).
BASELINE_THRESHOLD = 1.5


def parse_args():
    parser = argparse.ArgumentParser()
    parser.add_argument("--plugin", default=None)
    parser.add_argument("--baseline-dir", default=None)
    parser.add_argument("--temp-dir", default=os.getcwd())
    args, _ = parser.parse_known_args()
    os.makedirs(args.temp_dir, exist_ok=True)
    return args


def load_plugin(args):
    """Loads the plugin from --plugin, or by name from PV_PLUGIN_PATH."""
    if args.plugin:
        simple.LoadPlugin(args.plugin, remote=False)
        if servermanager.ActiveConnection and servermanager.ActiveConnection.IsRemote():
            simple.LoadPlugin(args.plugin, remote=True)
    else:
        simple.LoadDistributedPlugin("MultiMaterialVolume")


class ErrorCapture(object):
    """Collects the VTK errors and warnings of this process (what a pvpython
    user sees on the terminal) so that tests can assert on them. It observes
    the output window rather than replacing it: pvpython prints Python's own
    output through that window too."""

    def __init__(self):
        self.errors = []
        self.warnings = []
        self.window = vtkOutputWindow.GetInstance()

        @calldata_type(VTK_STRING)
        def on_error(caller, event, text):
            self.errors.append(text)

        @calldata_type(VTK_STRING)
        def on_warning(caller, event, text):
            self.warnings.append(text)

        self.tags = [self.window.AddObserver("ErrorEvent", on_error),
                     self.window.AddObserver("WarningEvent", on_warning)]

    def take(self):
        """Errors and warnings since the last call, as one string."""
        text = "".join(self.errors + self.warnings)
        self.errors, self.warnings = [], []
        return text

    def take_errors(self):
        text = "".join(self.errors)
        self.errors = []
        return text

    def close(self):
        for tag in self.tags:
            self.window.RemoveObserver(tag)


def make_view():
    view = simple.CreateView("RenderView")
    view.ViewSize = IMAGE_SIZE
    view.OrientationAxesVisibility = 0
    view.Background = [0.1, 0.1, 0.15]
    # 5.11 takes the background from the colour palette unless told otherwise.
    if view.GetProperty("UseColorPaletteForBackground") is not None:
        view.UseColorPaletteForBackground = 0
    simple.SetActiveView(view)
    return view


def add_directional_light(view, position, intensity=1.0):
    """Replaces the view's light kit by one directional scene light from
    `position` toward the origin."""
    view.UseLight = 0
    light = simple.AddLight(view=view)
    light.Coords = "Scene"
    light.Type = "Directional"
    light.Position = position
    light.FocalPoint = [0.0, 0.0, 0.0]
    light.Intensity = intensity
    return light


def make_volume(extent=15):
    """A small synthetic volume: the Wavelet source, (2*extent+1)^3 points."""
    wavelet = simple.Wavelet()
    wavelet.WholeExtent = [-extent, extent, -extent, extent, -extent, extent]
    return wavelet


def show_volume(source, view, preset="bone"):
    """Shows `source` as a Multi-Material Volume with a fixed camera and a
    transfer function that leaves the volume's outer layer transparent."""
    rep = simple.Show(source, view)
    rep.Representation = REPRESENTATION
    simple.ColorBy(rep, ("POINTS", "RTData"))
    lut = simple.GetColorTransferFunction("RTData")
    lut.ApplyPreset("Cool to Warm", True)
    lut.RescaleTransferFunction(37.0, 277.0)
    pwf = simple.GetOpacityTransferFunction("RTData")
    pwf.Points = [37.0, 0.0, 0.5, 0.0, 160.0, 0.0, 0.5, 0.0, 200.0, 1.0, 0.5, 0.0, 277.0, 1.0, 0.5, 0.0]
    pwf.RescaleTransferFunction(37.0, 277.0)
    rep.ScalarOpacityUnitDistance = 1.0
    if preset:
        rep.MaterialPreset = preset
    view.CameraPosition = [60.0, -45.0, 40.0]
    view.CameraFocalPoint = [0.0, 0.0, 0.0]
    view.CameraViewUp = [0.0, 0.0, 1.0]
    view.CameraViewAngle = 30.0
    return rep


def info(rep, name):
    """An information-only property of the representation, fetched now."""
    rep.SMProxy.UpdatePropertyInformation()
    values = rep.SMProxy.GetProperty(name)
    helper = servermanager.vtkSMPropertyHelper(values)
    n = helper.GetNumberOfElements()
    if isinstance(values, servermanager.vtkSMDoubleVectorProperty):
        return [helper.GetAsDouble(i) for i in range(n)]
    if isinstance(values, servermanager.vtkSMStringVectorProperty):
        return helper.GetAsString(0) if n == 1 else [helper.GetAsString(i) for i in range(n)]
    if n == 1:
        return helper.GetAsInt(0)
    return [helper.GetAsInt(i) for i in range(n)]


def render_image(view, path):
    """Renders, saves a screenshot and returns it as an (h, w, 3) uint8 array."""
    simple.Render(view)
    simple.SaveScreenshot(path, view, ImageResolution=IMAGE_SIZE, TransparentBackground=0)
    return read_png(path)


def read_png(path):
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    w, h, _ = image.GetDimensions()
    scalars = vtk_to_numpy(image.GetPointData().GetScalars())
    return scalars.reshape(h, w, -1)[:, :, :3].astype(numpy.float64)


def psnr(a, b):
    """PSNR in dB of two images of 0-255 values (infinite when identical)."""
    mse = float(numpy.mean((numpy.asarray(a, float) - numpy.asarray(b, float)) ** 2))
    return float("inf") if mse == 0.0 else 10.0 * math.log10(255.0 ** 2 / mse)


def set_uniform_maps(name, rgb, opacity_points):
    """The colour map ParaView keeps for `name`: one colour over [0, 1]; its
    opacity function: the (value, opacity) pairs `opacity_points`."""
    lut = simple.GetColorTransferFunction(name)
    lut.RGBPoints = [0.0] + list(rgb) + [1.0] + list(rgb)
    pwf = simple.GetOpacityTransferFunction(name)
    pwf.Points = [x for value, opacity in opacity_points for x in (value, opacity, 0.5, 0.0)]
    return lut, pwf


def show_multi_material(source, view, array, preset="matte"):
    """`source` as a Multi-Material Volume coloured by point array `array`,
    opacity per unit length, material preset `preset`."""
    rep = simple.Show(source, view)
    simple.ColorBy(rep, ("POINTS", array))
    rep.SetRepresentationType(REPRESENTATION)
    rep.ScalarOpacityUnitDistance = 1.0
    rep.MaterialPreset = preset
    return rep


def mean_difference(a, b):
    if a.shape != b.shape:
        return float("inf")
    return float(numpy.mean(numpy.abs(a - b)))


def compare_with_baseline(args, image_path, baseline_name, threshold=BASELINE_THRESHOLD):
    """Fails (returns False) if the image differs from the baseline by more than
    `threshold` (mean absolute difference per 8-bit channel)."""
    baseline = os.path.join(args.baseline_dir, baseline_name)
    image = read_png(image_path)
    generate = os.environ.get("MMV_GENERATE_BASELINES") == "1"
    if not os.path.exists(baseline):
        if generate:
            import shutil
            shutil.copyfile(image_path, baseline)
            print("wrote baseline %s" % baseline)
            return True
        print("FAIL: no baseline %s (image: %s)" % (baseline, image_path))
        return False
    difference = mean_difference(image, read_png(baseline))
    print("%s: mean |difference| = %.3f (threshold %.2f)" % (baseline_name, difference, threshold))
    if difference > threshold:
        if generate:
            import shutil
            shutil.copyfile(image_path, baseline)
            print("rewrote baseline %s" % baseline)
            return True
        print("FAIL: %s differs from %s" % (image_path, baseline))
        return False
    return True


def check_not_blank(image, what):
    """The volume must cover a good part of the image with non-background pixels."""
    background = image[0, 0]
    covered = numpy.mean(numpy.any(numpy.abs(image - background) > 8, axis=2))
    print("%s: %.1f%% of the pixels show the volume" % (what, 100 * covered))
    return covered > 0.05


class Checker(object):
    """Counts failed checks and reports them all before exiting."""

    def __init__(self):
        self.failures = []

    def check(self, condition, message):
        print("%s: %s" % ("ok" if condition else "FAIL", message))
        if not condition:
            self.failures.append(message)
        return condition

    def finish(self):
        """Reports; a failure raises, which makes pvpython/pvbatch exit with 1.
        (Not sys.exit(): pvpython 5.11 then crashes in its X11 teardown, and
        under MPI pvbatch's other ranks are left waiting.)"""
        if self.failures:
            print("%d check(s) failed:" % len(self.failures))
            for f in self.failures:
                print("  - " + f)
            raise RuntimeError("%d check(s) failed" % len(self.failures))
        print("all checks passed")


def is_finite_list(values):
    return all(math.isfinite(v) for v in values)
