# Startup script of the GUI test (paraview --script=...): loads the plugin,
# shows a small Wavelet as 'Multi-Material Volume' with two known material
# nodes and leaves it active, so the Properties panel builds the material
# editor. The XML test script then drives the editor and calls check_nodes().
import os

from paraview.simple import *  # noqa: F401,F403 (the GUI's own Python shell idiom)

LoadPlugin(os.environ["MMV_PLUGIN"], remote=False, ns=globals())

wavelet = Wavelet(registrationName="Wavelet1")
wavelet.WholeExtent = [-8, 8, -8, 8, -8, 8]
view = GetActiveViewOrCreate("RenderView")
display = Show(wavelet, view)
display.SetRepresentationType("Multi-Material Volume")
ColorBy(display, ("POINTS", "RTData"))
# A ramp to 0.6 keeps the volume see-through and gives the editor's track a
# clear opacity curve to draw.
lo, hi = wavelet.PointData["RTData"].GetRange()
GetOpacityTransferFunction("RTData").Points = [lo, 0.0, 0.5, 0.0, hi, 0.6, 0.5, 0.0]
# Nodes outside the data range widen the track to [0, 400], so the XML's
# clicks land at known values whatever the panel width.
display.MaterialNodes = [0.0, 0.2, 0.7, 0.2, 20.0, 1.0, 0.0, 0.0,
                         400.0, 0.3, 0.6, 0.1, 10.0, 1.0, 2.0, 0.0]
SetActiveSource(wavelet)
view.ResetCamera()
Render(view)


def check_nodes(expected_count, preset_node=None, preset="metal", preset_expected=True,
                material_preset="Custom", final=False):
    """Appends 'OK ...' or 'FAIL ...' to $MMV_RESULTS: the MaterialNodes property
    as the server manager holds it, after the XML's edits went through the
    widget. The last call adds a FINAL line (the driver then grabs the screen)."""
    display = GetDisplayProperties(wavelet, view)
    nodes = list(display.MaterialNodes)
    problems = []
    if display.MaterialPreset != material_preset:
        problems.append("MaterialPreset is %r, not %r" % (display.MaterialPreset, material_preset))
    stride = 13  # value + 12 parameters
    if len(nodes) != stride * expected_count:
        problems.append("expected %d nodes, property holds %d numbers" % (expected_count, len(nodes)))
    values = nodes[0::stride]
    if values != sorted(values):
        problems.append("node values not sorted: %s" % values)
    if preset_node is not None and len(nodes) >= stride * (preset_node + 1):
        params = _preset_parameters(preset)
        got = nodes[stride * preset_node + 1: stride * preset_node + stride]
        matches = all(abs(a - b) <= 1e-9 for a, b in zip(got, params))
        if matches != preset_expected:
            problems.append("node %d is %s, %s preset %s %s" % (
                preset_node, got, "not" if preset_expected else "still", preset, params))
    with open(os.environ["MMV_RESULTS"], "a") as f:
        f.write(("FAIL " + "; ".join(problems) if problems else "OK") + " " + repr(nodes) + "\n")
        if final:
            f.write("FINAL\n")


# The Python shell the XML types into may not share this script's namespace.
import builtins  # noqa: E402

builtins.check_nodes = check_nodes


def _report(problems, detail, final=False):
    with open(os.environ["MMV_RESULTS"], "a") as f:
        f.write(("FAIL " + "; ".join(problems) if problems else "OK") + " " + detail + "\n")
        if final:
            f.write("FINAL\n")


def _preset_parameters(name):
    import json
    with open(os.path.join(os.environ["MMV_MATERIALS_DIR"], name + ".json")) as f:
        spec = json.load(f)
    keys = ["ambient", "diffuse", "specular", "shininess", "attenuation", "scattering",
            "reflection", "anisotropy", "emission"]
    return [float(spec.get(k, 0.0)) for k in keys]


def _view_pixels():
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOImage import vtkPNGReader
    path = os.path.join(os.path.dirname(os.environ["MMV_RESULTS"]), "view.png")
    Render(view)
    SaveScreenshot(path, view)
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    return vtk_to_numpy(reader.GetOutput().GetPointData().GetScalars()).astype(float)


def _applied_nodes(display):
    """AppliedMaterialNodes (information only, not a Python attribute)."""
    from paraview import servermanager
    display.SMProxy.UpdatePropertyInformation()
    helper = servermanager.vtkSMPropertyHelper(display.SMProxy.GetProperty("AppliedMaterialNodes"))
    return [helper.GetAsDouble(i) for i in range(helper.GetNumberOfElements())]


_recorded = {}


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
            _report(["%s raised" % check.__name__], traceback.format_exc().replace("\n", " | "),
                    kwargs.get("final", False))

    return wrapper


@_reported
def record_preset(preset="skin"):
    """While `preset` is the MaterialPreset: the nodes the representation
    applied (AppliedMaterialNodes) and the rendered image."""
    display = GetDisplayProperties(wavelet, view)
    pixels = _view_pixels()
    _recorded.update(preset=preset, applied=_applied_nodes(display), pixels=pixels)
    problems = [] if display.MaterialPreset == preset else [
        "MaterialPreset is %r" % display.MaterialPreset]
    _report(problems, "record_preset applied=%r" % _recorded["applied"])


@_reported
def check_preset_add():
    """After a click on the track while the recorded preset showed: Custom,
    and MaterialNodes = the preset's nodes (as the representation applied
    them, over the colour map's range) plus the new node, which carries the
    preset's material (the preset interpolated at its value), numerically;
    the rendered image is unchanged."""
    import numpy
    display = GetDisplayProperties(wavelet, view)
    nodes = list(display.MaterialNodes)
    stride = 13  # value + 12 parameters
    problems = []
    if display.MaterialPreset != "Custom":
        problems.append("MaterialPreset is %r, not Custom" % display.MaterialPreset)
    applied = _recorded["applied"]
    params = _preset_parameters(_recorded["preset"])
    rgb = GetColorTransferFunction("RTData").RGBPoints
    expected_ends = [rgb[0], rgb[-4]]
    if [applied[0], applied[stride]] != expected_ends or len(applied) != 2 * stride:
        problems.append("applied preset nodes %r are not at the colour map range %r"
                        % (applied, expected_ends))
    if len(nodes) != 3 * stride:
        problems.append("expected 3 nodes, got %d numbers" % len(nodes))
    else:
        kept = nodes[0:stride] + nodes[2 * stride:3 * stride]
        if any(abs(a - b) > 1e-9 * (1 + abs(b)) for a, b in zip(kept, applied)):
            problems.append("end nodes %r differ from the preset's %r" % (kept, applied))
        added = nodes[stride:2 * stride]
        if not applied[0] < added[0] < applied[stride]:
            problems.append("new node value %r not inside the range" % added[0])
        if any(abs(a - b) > 1e-9 for a, b in zip(added[1:], params)):
            problems.append("new node material %r is not the preset's %r" % (added[1:], params))
    difference = numpy.abs(_view_pixels() - _recorded["pixels"])
    if difference.max() > 0:
        problems.append("the image changed: max difference %g, mean %g"
                        % (difference.max(), difference.mean()))
    _report(problems, "check_preset_add nodes=%r image max diff %g"
            % (nodes, difference.max()))


# The 9-number layout (before emission), which still loads.
NAN_NODES = [60.0, float("nan"), 0.7, 0.2, 20.0, 1.0, 0.0, 0.0, 0.0,
             float("nan"), 0.2, 0.7, 0.2, 20.0, 1.0, 0.0, 0.0, 0.0,
             200.0, 0.1, 0.3, 0.9, 120.0, 1.0, 0.0, 0.6, 0.0]


@_reported
def set_nan_nodes():
    """A NaN ambient in the node at 60 and a node at value NaN, as a state
    file or a script may hold them."""
    GetDisplayProperties(wavelet, view).MaterialNodes = NAN_NODES
    Render(view)


@_reported
def check_nan_edit(final=False):
    """After diffuse = 0.5 was typed into the node at 60: the property holds
    the stand-ins (ambient 0.2 = the default, the NaN-valued node left out),
    no NaN, and the representation applies it."""
    import math
    display = GetDisplayProperties(wavelet, view)
    nodes = list(display.MaterialNodes)
    # Written back in today's layout: 13 numbers a node, emission 0, grey.
    expected = [60.0, 0.2, 0.5, 0.2, 20.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0,
                200.0, 0.1, 0.3, 0.9, 120.0, 1.0, 0.0, 0.6, 0.0, 0.0, 1.0, 1.0, 1.0]
    problems = []
    if any(math.isnan(v) for v in nodes):
        problems.append("a NaN was written back")
    if len(nodes) != len(expected) or any(abs(a - b) > 1e-12 for a, b in zip(nodes, expected)):
        problems.append("MaterialNodes %r, expected %r" % (nodes, expected))
    Render(view)
    applied = _applied_nodes(display)
    if applied != nodes:
        problems.append("the representation applies %r" % applied)
    _report(problems, "check_nan_edit nodes=%r" % nodes, final)


builtins.record_preset = record_preset
builtins.check_preset_add = check_preset_add
builtins.set_nan_nodes = set_nan_nodes
builtins.check_nan_edit = check_nan_edit
