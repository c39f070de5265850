# Startup script of the panel GUI test (paraview --script=...): defines the
# checks the XML (which opens the volume with File > Open and Apply) calls
# from the Python shell. Each writes
# "OK ..." or "FAIL ..." to $MMV_RESULTS. The plugin and the panel probe are
# loaded from PV_PLUGIN_PATH, as a user loads them.
import builtins
import os

from paraview.simple import *  # noqa: F401,F403 (the GUI's own Python shell idiom)
from vtkmodules.util.misc import calldata_type
from vtkmodules.util.vtkConstants import VTK_STRING
from vtkmodules.vtkCommonCore import vtkOutputWindow

# Errors and warnings of this process, what the Output Messages window shows.
_messages = []


@calldata_type(VTK_STRING)
def _on_message(caller, event, text):
    _messages.append(text)


for _event in ("ErrorEvent", "WarningEvent"):
    vtkOutputWindow.GetInstance().AddObserver(_event, _on_message)


def _report(problems, detail, final=False):
    with open(os.environ["MMV_RESULTS"], "a") as f:
        f.write(("FAIL " + "; ".join(problems) if problems else "OK") + " " + detail + "\n")
        if final:
            f.write("FINAL\n")


def _reported(check):
    """An exception in a check is a FAIL line too (the Python shell would
    only show it in its own console)."""
    import functools
    import traceback

    @functools.wraps(check)
    def wrapper(*args, **kwargs):
        try:
            return check(*args, **kwargs)
        except Exception:  # noqa: BLE001 (reported, then the test fails)
            _report(["%s raised" % check.__name__],
                    traceback.format_exc().replace("\n", " | "), kwargs.get("final", False))

    builtins.__dict__[check.__name__] = wrapper
    return wrapper


def _view_pixels(view, name):
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOImage import vtkPNGReader
    path = os.path.join(os.path.dirname(os.environ["MMV_RESULTS"]), name)
    SaveScreenshot(path, view, ImageResolution=[400, 400])
    png = vtkPNGReader()
    png.SetFileName(path)
    png.Update()
    return vtk_to_numpy(png.GetOutput().GetPointData().GetScalars()).astype(float)[:, :3]


@_reported
def check_applied():
    """After Apply: the default display of a 3D image, Solid Color."""
    reader = FindSource("headsq.vti")
    display = GetDisplayProperties(reader, GetActiveView())
    coloring = list(display.ColorArrayName)
    problems = []
    if not display.Visibility:
        problems.append("Apply did not show the data")
    if display.Representation == "Multi-Material Volume":
        problems.append("the default representation is already ours")
    if coloring[1]:
        problems.append("coloured by %r before the switch (not Solid Color)" % coloring)
    _report(problems, "check_applied representation=%r coloring=%r"
            % (display.Representation, coloring))


# The mean |difference| per channel between the view and its background
# (the display hidden) must exceed this: the head covers about a third of a
# 400 x 400 view and a drawn volume differs by 14.5 on average (llvmpipe);
# a blank view differs by 0.
MIN_MEAN_DIFFERENCE = 5.0
# A pixel differing by more than this from the background is drawn.
DRAWN_PIXEL = 10.0


@_reported
def check_first_use():
    """After the toolbar switched the display to Multi-Material Volume: it
    is coloured by the active point array (ImageFile) with the colour map
    over its range, the view is not blank, and no error or warning came."""
    import numpy
    view = GetActiveView()
    reader = FindSource("headsq.vti")
    display = GetDisplayProperties(reader, view)
    problems = []
    if display.Representation != "Multi-Material Volume":
        problems.append("representation is %r" % display.Representation)
    coloring = list(display.ColorArrayName)
    if coloring != ["POINTS", "ImageFile"]:
        problems.append("coloured by %r, not the point array ImageFile" % coloring)
    lut = GetColorTransferFunction("ImageFile")
    data_range = reader.PointData["ImageFile"].GetRange()
    lut_range = (lut.RGBPoints[0], lut.RGBPoints[-4])
    if abs(lut_range[0] - data_range[0]) > 1e-6 or abs(lut_range[1] - data_range[1]) > 1e-6:
        problems.append("colour map range %r is not the data range %r" % (lut_range, data_range))
    drawn = _view_pixels(view, "first-use.png")
    Hide(reader, view)
    background = _view_pixels(view, "first-use-background.png")
    Show(reader, view)
    # Not simple.Render: its first call in a session resets the camera, and
    # the camera must stay as the GUI left it.
    view.StillRender()
    difference = numpy.abs(drawn - background)
    mean = difference.mean()
    covered = (difference.max(axis=1) > DRAWN_PIXEL).mean()
    if mean <= MIN_MEAN_DIFFERENCE:
        problems.append("the view is blank: mean |difference| %.2f <= %.1f"
                        % (mean, MIN_MEAN_DIFFERENCE))
    if _messages:
        problems.append("messages: %r" % _messages)
    _report(problems, "check_first_use mean |difference| from the background %.2f (bound %.1f), "
            "%.1f%% of the pixels drawn, coloring %r, colour map %r"
            % (mean, MIN_MEAN_DIFFERENCE, 100 * covered, coloring, lut_range))


@_reported
def check_no_messages(final=False):
    """At the end: no error or warning was reported while the panel was used."""
    _report(["messages: %r" % _messages] if _messages else [],
            "check_no_messages (%d messages)" % len(_messages), final)
