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
    stride = 10  # value + 9 parameters
    if len(nodes) != stride * expected_count:
        problems.append("expected %d nodes, property holds %d numbers" % (expected_count, len(nodes)))
    values = nodes[0::stride]
    if values != sorted(values):
        problems.append("node values not sorted: %s" % values)
    if preset_node is not None and len(nodes) >= stride * (preset_node + 1):
        import json
        with open(os.path.join(os.environ["MMV_MATERIALS_DIR"], preset + ".json")) as f:
            spec = json.load(f)
        keys = ["ambient", "diffuse", "specular", "shininess", "attenuation", "scattering",
                "reflection", "anisotropy", "emission"]
        params = [float(spec.get(k, 0.0)) for k in keys]
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
