"""ParaView's default lighting (the light kit), a CT-sized volume, a mouse orbit:
what a ParaView user meets when dragging the camera (run with pvpython).

    xvfb-run -a -s "-noreset -screen 0 1280x1024x24" \\
        pvpython Testing/Benchmark/pv_lightkit_orbit.py [--quick] [--out DIR]

Scene: Testing/Data/headsq.vti (64x64x93 MR head) resampled with
ResampleToImage to 256x256x128 (--quick: 128x128x64), a 400x400 view, the
view's default light kit (5 camera lights, nothing added, nothing disabled),
one bone-like opacity ramp and one grey/bone colour map shared by all methods.

Methods, each in its own view, measured round-robin per orbit step (the order
rotates every step because the machine is shared):
  pv-volume-phong       ParaView "Volume", Shade = 1 (the reference)
  pv-volume-scattering  ParaView "Volume", Shade = 1, VolumetricScatteringBlending
                        1.0, GlobalIlluminationReach 0.5 (VTK's scattering)
  mmv-default           "Multi-Material Volume", default material
  mmv-skin              "Multi-Material Volume", MaterialPreset "skin"
  mmv-sky               the default material lit by the background too (EnvironmentLighting 1)
  mmv-skin-euler        the same with ExponentialDiffusion off (backward Euler)

Per orbit step and method: K interactive frames (Azimuth 10/K degrees, then
view.SMProxy.InteractiveRender(), timed), then one timed StillRender(). After
the orbit: a screenshot at rest against a fresh view and representation with
the same camera (PSNR), and the representation's counters. Before the orbit,
one untimed still render of every view once all exist (see settle_renders).

The first interactive frames after a still frame are slower for every method
(VTK and ParaView adapt the image sampling to the interactive budget over a
few frames), so with K=3 the interactive median is a frame of that transient;
interactive_settled_median_s is the median of the last 3 interactive frames of
each step, the fair interactive number with a long drag (--interactive-frames 8).

Writes OUT/lightkit_orbit.csv, OUT/lightkit_orbit.png (plot_lightkit_orbit.py),
OUT/frames.csv (every timed frame) and the screenshots.

ParaView's default LOD threshold (20 MB) makes interactive renders of the
256x256x128 resample draw the image's LOD geometry instead of the volume, so
the interactive frames would not measure volume rendering; this script raises
the threshold (no LOD) unless --paraview-lod is given, and records in the
notes whether LOD was used.
"""

import argparse
import csv
import math
import os
import re
import statistics
import sys
import time

from paraview import simple
from paraview import servermanager

import numpy

# The tests' helpers (Testing/Python): PNG reading.
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "Python"))
from mmv_testing import read_png  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
DEFAULT_PLUGIN = os.path.join(ROOT, "build", "lib", "paraview-plugins", "MultiMaterialVolume",
                              "MultiMaterialVolume.so")
ARRAY = "ImageFile"
MMV = "Multi-Material Volume"
REFERENCE = "pv-volume-phong"

# name, representation, extra properties, (interactive target, still target)
METHODS = [
    ("pv-volume-phong", "Volume", {"Shade": 1}, None),
    ("pv-volume-scattering", "Volume",
     {"Shade": 1, "VolumetricScatteringBlending": 1.0, "GlobalIlluminationReach": 0.5}, None),
    ("mmv-default", MMV, {}, (1.25, 1.25)),
    ("mmv-skin", MMV, {"MaterialPreset": "skin"}, (1.5, 2.0)),
    # The default material with the background as a sky (EnvironmentLighting 1).
    ("mmv-sky", MMV, {"EnvironmentLighting": 1.0}, None),
    # The same with the former default integrator (backward Euler, 4x the passes).
    ("mmv-skin-euler", MMV, {"MaterialPreset": "skin", "ExponentialDiffusion": 0}, (1.5, 2.0)),
]

# Opacity: air and noise 0, skin (~600-1000) translucent, bone (>= 1300) dense.
OPACITY_POINTS = [0.0, 0.0, 0.5, 0.0,
                  500.0, 0.0, 0.5, 0.0,
                  800.0, 0.12, 0.5, 0.0,
                  1100.0, 0.2, 0.5, 0.0,
                  1400.0, 0.8, 0.5, 0.0,
                  3926.0, 0.9, 0.5, 0.0]
# Grey/bone: dark below skin, warm grey skin, ivory bone.
RGB_POINTS = [0.0, 0.0, 0.0, 0.0,
              500.0, 0.35, 0.3, 0.28,
              900.0, 0.78, 0.68, 0.62,
              1400.0, 0.93, 0.9, 0.82,
              3926.0, 1.0, 1.0, 1.0]
SCALAR_RANGE = (0.0, 3926.0)
OPACITY_UNIT_DISTANCE = 2.0
BACKGROUND = [0.1, 0.1, 0.15]
INFO_INT = ["IrradianceUpdateCount", "DeferredIrradianceCount", "DiffusionPassCount", "RayCastCount",
            "NumberOfShadedLights", "MultiMaterialActive"]
# The interactive frames at the end of each step, once ParaView/VTK have adapted
# their image sampling to the interactive time budget (see --interactive-frames).
SETTLED_FRAMES = 3
INFO_OTHER = ["IrradianceResolutionInfo", "LastIrradianceSeconds"]


def parse_args():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--plugin", default=DEFAULT_PLUGIN)
    p.add_argument("--data", default=os.path.join(ROOT, "Testing", "Data", "headsq.vti"))
    p.add_argument("--out", default=os.path.join(os.getcwd(), "build", "benchmark_pv"))
    p.add_argument("--quick", action="store_true", help="N=2, K=2, 128x128x64")
    p.add_argument("--steps", type=int, default=None, help="orbit steps N (default 6)")
    p.add_argument("--interactive-frames", type=int, default=None,
                   help="K per step (default 3); ParaView and VTK adapt their image sampling to the "
                        "interactive time budget over successive frames, so a long drag (e.g. K=8) "
                        "gives the fair interactive ratio: see interactive_settled_median_s, the "
                        "median of the last %d interactive frames of each step" % SETTLED_FRAMES)
    p.add_argument("--step-degrees", type=float, default=10.0)
    p.add_argument("--dims", type=int, nargs=3, default=None, help="resample size (default 256 256 128)")
    p.add_argument("--view-size", type=int, default=400)
    p.add_argument("--zoom", type=float, default=1.3)
    p.add_argument("--max-frame-seconds", type=float, default=None,
                   help="stop a method's orbit after a slower frame (default 120, --quick 20)")
    p.add_argument("--methods", default=",".join(m[0] for m in METHODS),
                   help="comma-separated subset of: " + ", ".join(m[0] for m in METHODS))
    p.add_argument("--paraview-lod", action="store_true",
                   help="keep ParaView's LOD threshold (interactive frames may draw LOD geometry)")
    p.add_argument("--no-plot", action="store_true")
    args, _ = p.parse_known_args()
    quick = args.quick
    if args.steps is None:
        args.steps = 2 if quick else 6
    if args.interactive_frames is None:
        args.interactive_frames = 2 if quick else 3
    if args.dims is None:
        args.dims = [128, 128, 64] if quick else [256, 256, 128]
    if args.max_frame_seconds is None:
        args.max_frame_seconds = 20.0 if quick else 120.0
    return args


def log(text):
    print(text)
    sys.stdout.flush()


def head_parser(doc, out):
    """The options of a script on the MR head: --plugin, --data, --out
    (default `out`); its description is the first line of `doc`."""
    p = argparse.ArgumentParser(description=doc.split("\n")[0])
    p.add_argument("--plugin", default=DEFAULT_PLUGIN)
    p.add_argument("--data", default=os.path.join(ROOT, "Testing", "Data", "headsq.vti"))
    p.add_argument("--out", default=out)
    return p


def start(args):
    """A script's start: args.out made, the plugin loaded. False (and the
    reason printed) if the plugin does not load."""
    os.makedirs(args.out, exist_ok=True)
    problem = load_plugin(args.plugin)
    if problem:
        print("ERROR: " + problem)
    return problem is None


def load_plugin(path):
    """As mmv_testing.load_plugin: a path, or by name from PV_PLUGIN_PATH."""
    try:
        if path and os.path.exists(path):
            simple.LoadPlugin(path, remote=False)
            if servermanager.ActiveConnection and servermanager.ActiveConnection.IsRemote():
                simple.LoadPlugin(path, remote=True)
        elif os.environ.get("PV_PLUGIN_PATH"):
            simple.LoadDistributedPlugin("MultiMaterialVolume")
        else:
            return "plugin not found: %s" % path
    except Exception as e:  # noqa: BLE001 - reported in the CSV
        return "plugin failed to load: %s" % e
    return None


def psnr(a, b):
    if a.shape != b.shape:
        return float("nan")
    mse = float(numpy.mean((a - b) ** 2))
    return float("inf") if mse == 0.0 else 10.0 * math.log10(255.0 ** 2 / mse)


# The stages LastIrradianceStages reports, in its order.
STAGES = ("probe", "prefilter", "shadow table", "inputs", "setup", "shadows", "diffusion", "write",
          "keep", "pass", "total")


def stage_seconds(text):
    """{stage: seconds} from LastIrradianceStages ("probe 0.000 s, ...")."""
    out = {}
    for part in (text or "").split(","):
        m = re.match(r"\s*([a-z ]+?) ([0-9.eE+-]+) s\s*$", part)
        if m:
            out[m.group(1)] = float(m.group(2))
    return out


def read_info(rep, names=None):
    """The representation's information properties `names` (default: the
    orbit's) that exist (counters of the mapper on this process; the new ones
    may not exist yet)."""
    out = {}
    try:
        rep.SMProxy.UpdatePropertyInformation()
    except Exception:  # noqa: BLE001
        return out
    for name in names or INFO_INT + INFO_OTHER:
        try:
            prop = rep.SMProxy.GetProperty(name)
            if prop is None:
                continue
            if isinstance(prop, servermanager.vtkSMStringVectorProperty):
                out[name] = prop.GetElement(0) if prop.GetNumberOfElements() else ""
                continue
            helper = servermanager.vtkSMPropertyHelper(prop)
            if helper.GetNumberOfElements() < 1:
                continue
            if isinstance(prop, servermanager.vtkSMDoubleVectorProperty):
                out[name] = helper.GetAsDouble(0)
            else:
                out[name] = helper.GetAsInt(0)
        except Exception:  # noqa: BLE001
            pass
    return out


def volume_props(view):
    """Visible vtkVolume-derived props of the view's renderer (ParaView's
    vtkPVLODVolume passes its allocated render time to the vtkVolume the
    mapper receives)."""
    props = view.GetRenderer().GetViewProps()
    found = []
    props.InitTraversal()
    for _ in range(props.GetNumberOfItems()):
        p = props.GetNextProp()
        if p is not None and p.GetVisibility() and (p.IsA("vtkVolume") or p.IsA("vtkLODProp3D")):
            found.append(p)
    return found


def render_signal(view):
    """(desired update rate of the render window, allocated render time of the
    volume, whether the view used LOD) right after a render."""
    rate = view.GetRenderWindow().GetDesiredUpdateRate()
    vols = volume_props(view)
    alloc = min(v.GetAllocatedRenderTime() for v in vols) if vols else float("nan")
    try:
        lod = bool(view.GetClientSideObject().GetUsedLODForLastRender())
    except Exception:  # noqa: BLE001
        lod = None
    return rate, alloc, lod


class Method(object):
    def __init__(self, name, representation, props, targets):
        self.name = name
        self.representation = representation
        self.props = props
        self.targets = targets
        self.view = None
        self.rep = None
        self.notes = []
        self.interactive = []
        self.interactive_steps = []  # the interactive frames of each step
        self.still = []
        self.first_render = float("nan")
        self.stopped = False
        self.signal_interactive = []
        self.signal_still = []
        self.updates_interactive = 0
        self.updates_still = 0
        self.info_before = {}
        self.info_after = {}
        self.psnr = float("nan")


def resampled_head(args):
    """args.data resampled to args.dims (ResampleToImage, updated), and the
    centre of its bounds."""
    reader = simple.XMLImageDataReader(FileName=[args.data])
    source = simple.ResampleToImage(Input=reader)
    source.SamplingDimensions = args.dims
    source.UpdatePipeline()
    bounds = source.GetDataInformation().GetBounds()
    center = [0.5 * (bounds[2 * a] + bounds[2 * a + 1]) for a in range(3)]
    return source, bounds, center


def make_view(args):
    view = simple.CreateView("RenderView")
    view.ViewSize = [args.view_size, args.view_size]
    view.OrientationAxesVisibility = 0
    view.Background = BACKGROUND
    if view.GetProperty("UseColorPaletteForBackground") is not None:
        view.UseColorPaletteForBackground = 0
    if not args.paraview_lod:
        view.LODThreshold = 1.0e9  # MB: never draw LOD geometry instead of the volume
    return view


def setup_transfer_functions():
    lut = simple.GetColorTransferFunction(ARRAY)
    pwf = simple.GetOpacityTransferFunction(ARRAY)
    if lut.GetProperty("AutomaticRescaleRangeMode") is not None:
        lut.AutomaticRescaleRangeMode = "Never"
    if pwf.GetProperty("AllowDuplicateScalars") is not None:
        pwf.AllowDuplicateScalars = 1
    lut.ColorSpace = "RGB"
    lut.RGBPoints = RGB_POINTS
    lut.ScalarRangeInitialized = 1.0
    pwf.Points = OPACITY_POINTS
    pwf.ScalarRangeInitialized = 1
    return lut, pwf


def show(method, source, view):
    """Shows `source` in `view` with the method's representation; None and a
    note if the representation or a property does not exist."""
    rep = simple.Show(source, view)
    available = list(rep.GetProperty("Representation").Available)
    if method.representation not in available:
        simple.Hide(source, view)
        method.notes.append("representation '%s' not available" % method.representation)
        return None
    rep.Representation = method.representation
    simple.ColorBy(rep, ("POINTS", ARRAY))
    setup_transfer_functions()
    rep.ScalarOpacityUnitDistance = OPACITY_UNIT_DISTANCE
    for key, value in method.props.items():
        if rep.GetProperty(key) is None:
            method.notes.append("%s not exposed by ParaView %s: not measured"
                                % (key, servermanager.vtkSMProxyManager.GetParaViewSourceVersion()))
            simple.Hide(source, view)
            return None
        setattr(rep, key, value)
    return rep


def place_camera(view, args, position=None):
    cam = view.GetActiveCamera()
    if position is None:
        # Front view of the head (as README.md), reset, then a fixed zoom.
        view.CameraPosition = [100.8, 650.0, 69.0]
        view.CameraFocalPoint = [100.8, 100.8, 69.0]
        view.CameraViewUp = [0.0, 0.0, -1.0]
        view.CameraViewAngle = 30.0
        view.ResetCamera()
        cam.Zoom(args.zoom)
    else:
        pos, focal, up, angle = position
        cam.SetPosition(pos)
        cam.SetFocalPoint(focal)
        cam.SetViewUp(up)
        cam.SetViewAngle(angle)
    return cam


def camera_state(view):
    cam = view.GetActiveCamera()
    return (cam.GetPosition(), cam.GetFocalPoint(), cam.GetViewUp(), cam.GetViewAngle())


def settle_renders(methods):
    """One untimed still render of each view once all exist: showing the
    source in a new view touches the shared transfer functions (their MTime,
    not their values), which would otherwise make the first frame of the
    orbit of every earlier view recompute its lighting."""
    for m in methods:
        if m.view is not None and not m.stopped:
            m.view.SMProxy.StillRender()


def count_updates(method):
    return read_info(method.rep).get("IrradianceUpdateCount", 0)


def timed(fn):
    t0 = time.perf_counter()
    fn()
    return time.perf_counter() - t0


def timed_frame(method, step, kind, k, frames_writer):
    """One timed render of `kind` ("interactive" or "still"), logged to
    frames.csv: (seconds, render signal, irradiance updates it made)."""
    render = (method.view.SMProxy.InteractiveRender if kind == "interactive"
              else method.view.SMProxy.StillRender)
    before = count_updates(method)
    dt = timed(render)
    signal = render_signal(method.view)
    updates = count_updates(method) - before
    frames_writer.writerow([method.name, step, kind, k, "%.6f" % dt, signal[0],
                            "%.6g" % signal[1], signal[2], updates])
    return dt, signal, updates


def write_csv(path, rows):
    """Rows of dicts, the first row's keys as the header."""
    with open(path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        writer.writeheader()
        writer.writerows(rows)


def orbit_step(method, args, frames_writer, step):
    """K interactive frames while the camera moves, then the still frame."""
    if method.stopped:
        return
    cam = method.view.GetActiveCamera()
    azimuth = args.step_degrees / args.interactive_frames
    this_step = []
    method.interactive_steps.append(this_step)
    for k in range(args.interactive_frames):
        cam.Azimuth(azimuth)
        cam.OrthogonalizeViewUp()
        dt, signal, updates = timed_frame(method, step, "interactive", k, frames_writer)
        method.updates_interactive += updates
        method.interactive.append(dt)
        this_step.append(dt)
        method.signal_interactive.append(signal)
        if dt > args.max_frame_seconds:
            method.stopped = True
            method.notes.append("stopped at step %d: interactive frame %.1f s > %.0f s"
                                % (step, dt, args.max_frame_seconds))
            return
    dt, signal, updates = timed_frame(method, step, "still", 0, frames_writer)
    method.updates_still += updates
    method.still.append(dt)
    method.signal_still.append(signal)
    if dt > args.max_frame_seconds:
        method.stopped = True
        method.notes.append("stopped at step %d: still frame %.1f s > %.0f s"
                            % (step, dt, args.max_frame_seconds))


def rest_vs_fresh(method, source, args):
    """Screenshot of the view at rest against a fresh view and representation
    with the same camera; PSNR in dB (inf when identical)."""
    size = [args.view_size, args.view_size]
    rest = os.path.join(args.out, "%s_rest.png" % method.name)
    fresh = os.path.join(args.out, "%s_fresh.png" % method.name)
    simple.SaveScreenshot(rest, method.view, ImageResolution=size, TransparentBackground=0)
    view = make_view(args)
    try:
        rep = show(method, source, view)
        if rep is None:
            return float("nan")
        place_camera(view, args, camera_state(method.view))
        view.SMProxy.StillRender()
        simple.SaveScreenshot(fresh, view, ImageResolution=size, TransparentBackground=0)
    finally:
        simple.Delete(view)
        simple.SetActiveView(method.view)
    return psnr(read_png(rest), read_png(fresh))


def median(values):
    return statistics.median(values) if values else float("nan")


def settled(method):
    """The last SETTLED_FRAMES interactive frames of each step."""
    return [dt for step in method.interactive_steps for dt in step[-SETTLED_FRAMES:]]


def fmt(value, pattern="%.4f"):
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return ""
    if isinstance(value, float) and math.isinf(value):
        return "inf"
    return pattern % value


def signal_summary(signals):
    if not signals:
        return "n/a"
    rates = sorted(set(round(s[0], 6) for s in signals))
    allocs = [s[1] for s in signals if not math.isnan(s[1])]
    lods = sorted(set(str(s[2]) for s in signals))
    return "rate %s, allocated %s..%s s, LOD %s" % (
        "/".join("%g" % r for r in rates),
        fmt(min(allocs), "%.4g") if allocs else "?", fmt(max(allocs), "%.4g") if allocs else "?",
        "/".join(lods))


def main():
    args = parse_args()
    os.makedirs(args.out, exist_ok=True)
    wanted = [m.strip() for m in args.methods.split(",") if m.strip()]
    unknown = [m for m in wanted if m not in [x[0] for x in METHODS]]
    if unknown:
        raise RuntimeError("unknown method(s): %s" % ", ".join(unknown))
    methods = [Method(*m) for m in METHODS if m[0] in wanted]

    # paraview.simple resets the camera of the first view it renders: the views
    # here set their cameras themselves (and the fresh view copies one).
    simple._DisableFirstRenderCameraReset()
    version = servermanager.vtkSMProxyManager.GetParaViewSourceVersion()
    plugin_problem = None
    if any(m.representation == MMV for m in methods):
        plugin_problem = load_plugin(args.plugin)
        if plugin_problem:
            log("WARNING: " + plugin_problem)

    log("== %s; resample %s, view %dx%d, N=%d steps x %g deg, K=%d interactive frames/step, "
        "max frame %.0f s, LOD %s"
        % (version, "x".join(map(str, args.dims)), args.view_size, args.view_size, args.steps,
           args.step_degrees, args.interactive_frames, args.max_frame_seconds,
           "ParaView default" if args.paraview_lod else "off"))

    source, _, _ = resampled_head(args)

    for m in methods:
        if m.representation == MMV and plugin_problem:
            m.notes.append(plugin_problem)
            continue
        m.view = make_view(args)
        m.rep = show(m, source, m.view)
        if m.rep is None:
            simple.Delete(m.view)
            m.view = None
            continue
        place_camera(m.view, args)
        m.first_render = timed(m.view.SMProxy.StillRender)
        kit = m.view.UseLight
        log("%-22s first still render %.3f s (light kit UseLight=%s, %d volume prop(s))"
            % (m.name, m.first_render, kit, len(volume_props(m.view))))
        if m.first_render > args.max_frame_seconds:
            m.stopped = True
            m.notes.append("not orbited: first frame %.1f s > %.0f s" % (m.first_render, args.max_frame_seconds))

    active = [m for m in methods if m.rep is not None]
    settle_renders(active)
    for m in active:
        m.info_before = read_info(m.rep)
    frames_path = os.path.join(args.out, "frames.csv")
    with open(frames_path, "w", newline="") as f:
        frames = csv.writer(f)
        frames.writerow(["method", "step", "kind", "frame", "seconds", "desired_update_rate",
                         "volume_allocated_render_time", "used_lod", "irradiance_updates"])
        for step in range(args.steps):
            t0 = time.perf_counter()
            shift = step % len(active) if active else 0
            for m in active[shift:] + active[:shift]:
                orbit_step(m, args, frames, step)
            f.flush()
            log("step %d/%d done (%.1f s)" % (step + 1, args.steps, time.perf_counter() - t0))

    for m in active:
        try:
            m.psnr = rest_vs_fresh(m, source, args)
        except Exception as e:  # noqa: BLE001 - reported in the CSV
            m.notes.append("rest-vs-fresh failed: %s" % e)
        m.info_after = read_info(m.rep)

    ref = next((m for m in methods if m.name == REFERENCE and m.interactive), None)
    ref_i = median(ref.interactive) if ref else float("nan")
    ref_is = median(settled(ref)) if ref else float("nan")
    ref_s = median(ref.still) if ref else float("nan")

    rows = []
    for m in methods:
        mi, mis, ms = median(m.interactive), median(settled(m)), median(m.still)
        ri = mi / ref_i if ref else float("nan")
        ris = mis / ref_is if ref else float("nan")
        rs = ms / ref_s if ref else float("nan")
        # The plugin exposes its counters on every image representation; they
        # only mean something for its own.
        a, b = (m.info_before, m.info_after) if m.representation == MMV else ({}, {})
        delta = (lambda k: b[k] - a.get(k, 0) if k in b else None)
        notes = list(m.notes)
        if m.rep is not None:
            notes.append("interactive: " + signal_summary(m.signal_interactive))
            notes.append("still: " + signal_summary(m.signal_still))
            if m.representation == MMV:
                if m.rep.GetProperty("InteractiveIrradiance") is not None:
                    notes.append("InteractiveIrradiance=%s" % m.rep.InteractiveIrradiance)
                missing = [k for k in INFO_OTHER if k not in b]
                if missing:
                    notes.append("no property %s" % "/".join(missing))
        rows.append({
            "method": m.name,
            "representation": m.representation,
            "interactive_median_s": fmt(mi),
            "still_median_s": fmt(ms),
            "interactive_ratio": fmt(ri, "%.3f"),
            "still_ratio": fmt(rs, "%.3f"),
            "interactive_settled_median_s": fmt(mis),
            "interactive_settled_ratio": fmt(ris, "%.3f"),
            "interactive_target": fmt(m.targets[0], "%.2f") if m.targets else "",
            "still_target": fmt(m.targets[1], "%.2f") if m.targets else "",
            "rest_vs_fresh_psnr_db": fmt(m.psnr, "%.2f"),
            "irradiance_updates": (str(m.updates_interactive + m.updates_still)
                                   if "IrradianceUpdateCount" in b else ""),
            "irradiance_updates_total": fmt(delta("IrradianceUpdateCount"), "%d"),
            "irradiance_updates_interactive": str(m.updates_interactive) if "IrradianceUpdateCount" in b else "",
            "irradiance_updates_still": str(m.updates_still) if "IrradianceUpdateCount" in b else "",
            "deferred_irradiance": fmt(delta("DeferredIrradianceCount"), "%d"),
            "diffusion_passes": fmt(delta("DiffusionPassCount"), "%d"),
            "irradiance_resolution": str(b.get("IrradianceResolutionInfo", "")),
            "last_irradiance_s": fmt(b.get("LastIrradianceSeconds"), "%.4f"),
            "first_render_s": fmt(m.first_render, "%.3f"),
            "interactive_frames": str(len(m.interactive)),
            "still_frames": str(len(m.still)),
            "notes": "; ".join(notes),
        })

    csv_path = os.path.join(args.out, "lightkit_orbit.csv")
    write_csv(csv_path, rows)
    with open(os.path.join(args.out, "machine.txt"), "w") as f:
        f.write("paraview %s\n" % version)
        f.write("resample %s\n" % "x".join(map(str, args.dims)))
        f.write("view %d\n" % args.view_size)
        f.write("steps %d\ninteractive_frames %d\nstep_degrees %g\n"
                % (args.steps, args.interactive_frames, args.step_degrees))
        f.write("lod %s\n" % ("paraview-default" if args.paraview_lod else "off"))
        f.write("cores %d\n" % (os.cpu_count() or 0))

    # The table.
    log("")
    log("%-22s %10s %9s %12s %12s %12s %9s %8s %s" % (
        "method", "inter. s", "still s", "inter. x", "settled x", "still x", "PSNR dB", "irr.upd",
        "frames i/s"))
    for r in rows:
        def ratio(value, target):
            if not value:
                return ""
            if not target:
                return value
            ok = float(value) <= float(target)
            return "%s%s%s" % (value, "<=" if ok else ">", target)
        log("%-22s %10s %9s %12s %12s %12s %9s %8s %s/%s" % (
            r["method"], r["interactive_median_s"], r["still_median_s"],
            ratio(r["interactive_ratio"], r["interactive_target"]),
            ratio(r["interactive_settled_ratio"], r["interactive_target"]),
            ratio(r["still_ratio"], r["still_target"]), r["rest_vs_fresh_psnr_db"],
            r["irradiance_updates"], r["interactive_frames"], r["still_frames"]))
    log("targets: mmv-default interactive <= 1.25x, still <= 1.25x; "
        "mmv-skin interactive <= 1.5x, still <= 2x (ratios to %s, same run); PSNR >= 40 dB; "
        "settled: the last %d interactive frames of each step" % (REFERENCE, SETTLED_FRAMES))
    for r in rows:
        log("notes %s: %s" % (r["method"], r["notes"]))
        extra = ["%s=%s" % (k, r[k]) for k in ("irradiance_updates_interactive", "irradiance_updates_still",
                                                 "irradiance_updates_total", "deferred_irradiance",
                                                 "diffusion_passes", "irradiance_resolution",
                                                 "last_irradiance_s", "first_render_s") if r[k]]
        if extra:
            log("      %s  %s" % (" " * len(r["method"]), ", ".join(extra)))
    interactive_allocs = [s[1] for m in methods for s in m.signal_interactive if not math.isnan(s[1])]
    still_allocs = [s[1] for m in methods for s in m.signal_still if not math.isnan(s[1])]
    if interactive_allocs:
        log("interactive signal: during InteractiveRender() the render window's desired update rate is "
            "%s and the volume's allocated render time %.4g..%.4g s (< 1.0: %s); after StillRender() %s "
            "and %.4g..%.4g s"
            % ("/".join(sorted(set("%g" % s[0] for m in methods for s in m.signal_interactive))),
               min(interactive_allocs), max(interactive_allocs),
               "yes" if max(interactive_allocs) < 1.0 else "no",
               "/".join(sorted(set("%g" % s[0] for m in methods for s in m.signal_still))),
               min(still_allocs) if still_allocs else float("nan"),
               max(still_allocs) if still_allocs else float("nan")))
    log("wrote %s, %s" % (csv_path, frames_path))

    if not args.no_plot:
        sys.path.insert(0, HERE)
        try:
            import plot_lightkit_orbit
            log("wrote %s" % plot_lightkit_orbit.plot(csv_path, os.path.join(args.out, "lightkit_orbit.png")))
        except Exception as e:  # noqa: BLE001 - the CSV is the result
            log("WARNING: no chart: %s" % e)


if __name__ == "__main__":
    main()
