"""What a change costs in ParaView: camera moves under the light kit, an
opacity-point drag, colour-only edits and time steps, on the smooth MR head
and on a fine-structured chest (run with pvpython).

    xvfb-run -a -s "-noreset -screen 0 1280x1024x24" \\
        scripts/pvpython Testing/Benchmark/pv_lighting_changes.py --out DIR [--quick]

Volumes (256 x 256 x 128, --quick 128 x 128 x 64):
  head   Testing/Data/headsq.vti resampled: smooth, the error probe coarsens it
  chest  Testing/Benchmark/mmv_fine_volume.py: a 2-voxel skin, ribs and
         vessels 1-2 voxels thick, which keep the full irradiance grid

Methods, each in its own 400 x 400 view with ParaView's default light kit
(--spot: the light kit off and one Light Inspector spot light in scene
coordinates, as pv_spot_light.py adds it, 600 units away, cone 25 degrees),
rendered round-robin (the order rotates at every change):
  pv-volume   ParaView "Volume", Shade on (the reference of every ratio)
  mmv-default "Multi-Material Volume", default material
  mmv-skin    the same, MaterialPreset "skin" (multiple scattering)
  mmv-sky     the default material lit by the background too (EnvironmentLighting 1)
  mmv-smoke   the same, MaterialPreset "smoke" (time steps only)

Sequences, each change followed by one timed StillRender() per view:
  still     nothing changed (the camera fixed): a ray cast alone
  orbit     Azimuth 10 degrees: the light kit follows the camera
  opacity   one opacity point's value dragged (+0.02 per change)
  colour    the colour map edited (no opacity change)
  series    a generated series of 8 steps on the same grid with ParaView's
            animation caching on: the first loop also keeps each step for
            the next (series-2: the second loop, whose target is one ray
            cast per step)
  steps     the same series played once more, as ParaView plays it by
            default (animation caching off: every step is new)
  (each step is read before the timed renders, so no method pays for the
  reader)

Writes OUT/changes.csv (one row per volume, sequence and method: medians,
ratios to pv-volume, irradiance updates, probes, the median seconds of each
irradiance stage and of the sky's estimation), OUT/frames.csv (every frame), OUT/changes.png, and
OUT/grid_check.csv: after the sequences, the irradiance grid each method kept
against the one a fresh representation's probe chooses for the final
transfer functions and time step.
"""

import argparse
import csv
import os
import statistics
import sys
import tempfile
import time

from paraview import simple
from paraview import servermanager

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import mmv_fine_volume  # noqa: E402
import pv_lightkit_orbit as orbit  # noqa: E402
import pv_spot_light  # noqa: E402

MMV = orbit.MMV
ARRAY = orbit.ARRAY
REFERENCE = "pv-volume"
METHODS = [
    ("pv-volume", "Volume", {"Shade": 1}),
    ("mmv-default", MMV, {}),
    ("mmv-skin", MMV, {"MaterialPreset": "skin"}),
    ("mmv-sky", MMV, {"EnvironmentLighting": 1.0}),
    ("mmv-smoke", MMV, {"MaterialPreset": "smoke"}),
]
SEQUENCES = ["still", "orbit", "opacity", "colour", "series", "steps"]
# Targets (ratio to pv-volume's median of the same sequence; colour: to the
# method's own still frame).
TARGETS = {
    ("orbit", "mmv-default"): 1.25, ("orbit", "mmv-skin"): 2.0,
    ("opacity", "mmv-default"): 1.25, ("opacity", "mmv-skin"): 1.5,
    ("steps", "mmv-default"): 1.25, ("steps", "mmv-smoke"): 1.5,
    ("colour", "mmv-default"): 1.05, ("colour", "mmv-skin"): 1.05,
    ("series-2", "mmv-default"): 1.05, ("series-2", "mmv-smoke"): 1.05,
}
# The sequences of time steps (the other methods skip them).
TIME_STEPS = ("steps", "series", "series-2")
# Sequences whose target is a ratio to the method's own still frame.
OWN_STILL = ("colour", "series-2")
STAGES = orbit.STAGES
INFO = ["IrradianceUpdateCount", "IrradianceProbeCount", "IrradianceCacheHitCount",
        "LastIrradianceStages", "IrradianceResolutionInfo", "SkyUpdateCount", "LastSkySeconds"]


def parse_args():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--plugin", default=orbit.DEFAULT_PLUGIN)
    p.add_argument("--data", default=os.path.join(HERE, "..", "Data", "headsq.vti"))
    p.add_argument("--out", default=os.path.join(os.getcwd(), "build", "benchmark_changes"))
    p.add_argument("--quick", action="store_true", help="128x128x64, 2 changes per sequence")
    p.add_argument("--volumes", default="head,chest")
    p.add_argument("--methods", default=",".join(m[0] for m in METHODS))
    p.add_argument("--sequences", default=",".join(SEQUENCES))
    p.add_argument("--changes", type=int, default=None, help="changes per sequence (default 4)")
    p.add_argument("--steps", type=int, default=8, help="time steps of the series")
    p.add_argument("--view-size", type=int, default=400)
    p.add_argument("--no-plot", action="store_true")
    p.add_argument("--spot", action="store_true",
                   help="one scene spot light instead of the light kit")
    args, _ = p.parse_known_args()
    args.dims = [128, 128, 64] if args.quick else [256, 256, 128]
    args.paraview_lod = False  # never LOD geometry instead of the volume
    args.zoom = 1.3  # pv_lightkit_orbit.place_camera's framing
    if args.changes is None:
        args.changes = 2 if args.quick else 4
    return args


def log(text):
    print(text)
    sys.stdout.flush()


def head_values(args):
    """The MR head resampled to args.dims, as a numpy array [z, y, x]."""
    from vtkmodules.util import numpy_support
    reader = simple.XMLImageDataReader(FileName=[args.data])
    resample = simple.ResampleToImage(Input=reader)
    resample.SamplingDimensions = args.dims
    image = servermanager.Fetch(resample)
    values = numpy_support.vtk_to_numpy(image.GetPointData().GetArray(ARRAY))
    simple.Delete(resample)
    simple.Delete(reader)
    return values.reshape(args.dims[::-1]).astype("float32")


def write_series(name, args, folder):
    """args.steps files of the volume `name` on one grid; the first is the
    still volume."""
    import numpy
    paths = []
    if name == "head":
        base = head_values(args)
        for k in range(args.steps):
            # A slow pulse of the values: the same grid, new values.
            gain = 1.0 + 0.04 * numpy.sin(2.0 * numpy.pi * k / args.steps)
            paths.append(mmv_fine_volume.write_vti(
                os.path.join(folder, "head_%d.vti" % k), (base * gain).astype("float32")))
    else:
        paths = mmv_fine_volume.write_series(os.path.join(folder, "chest"), args.steps,
                                             tuple(args.dims))
    return paths


class Method(object):
    def __init__(self, name, representation, props):
        self.name, self.representation, self.props = name, representation, props
        self.view = self.rep = None


def info(representation, rep):
    """The information properties of INFO (none for ParaView's own
    representations)."""
    return orbit.read_info(rep, INFO) if representation == MMV else {}


def frame(method, volume, sequence, change, writer, records):
    before = info(method.representation, method.rep)
    t0 = time.perf_counter()
    method.view.SMProxy.StillRender()
    seconds = time.perf_counter() - t0
    after = info(method.representation, method.rep)
    updates = after.get("IrradianceUpdateCount", 0) - before.get("IrradianceUpdateCount", 0)
    probes = after.get("IrradianceProbeCount", 0) - before.get("IrradianceProbeCount", 0)
    copies = after.get("IrradianceCacheHitCount", 0) - before.get("IrradianceCacheHitCount", 0)
    stages = orbit.stage_seconds(after.get("LastIrradianceStages")) if updates else {}
    if after.get("SkyUpdateCount", 0) != before.get("SkyUpdateCount", 0):
        stages["sky"] = after.get("LastSkySeconds", 0.0)
    row = [volume, sequence, method.name, change, "%.4f" % seconds, updates, probes, copies]
    row += ["%.4f" % stages.get(s, 0.0) if updates else "" for s in STAGES]
    row += [after.get("IrradianceResolutionInfo", "").split(";")[0]]
    writer.writerow(row)
    records.append({"volume": volume, "sequence": sequence, "method": method.name,
                    "seconds": seconds, "updates": updates, "probes": probes, "copies": copies,
                    "stages": stages})
    return seconds


def light_view(view, source, args):
    """With --spot: the light kit off and the spot light in its place."""
    if not args.spot:
        return
    view.UseLight = 0
    bounds = source.GetDataInformation().GetBounds()
    center = [0.5 * (bounds[2 * a] + bounds[2 * a + 1]) for a in range(3)]
    pv_spot_light.add_spot(view, center, argparse.Namespace(distance=600.0, cone=25.0))


def run_volume(name, args, methods, folder, writer, records, checks):
    paths = write_series(name, args, folder)
    source = simple.XMLImageDataReader(FileName=paths)
    source.UpdatePipelineInformation()
    times = list(source.TimestepValues) or [0.0]
    source.UpdatePipeline(times[0])
    active = []
    for m in methods:
        m.view = orbit.make_view(args)
        m.view.ViewTime = times[0]
        rep = orbit.show(orbit.Method(m.name, m.representation, m.props, None), source, m.view)
        if rep is None:
            log("%s: %s not available" % (name, m.name))
            simple.Delete(m.view)
            continue
        m.rep = rep
        orbit.place_camera(m.view, args)
        light_view(m.view, source, args)
        active.append(m)
    lut, pwf = orbit.setup_transfer_functions()
    for m in active:
        m.view.SMProxy.StillRender()
    for m in active:  # once all exist (see pv_lightkit_orbit.settle_renders)
        m.view.SMProxy.StillRender()
    wanted = [s.strip() for s in args.sequences.split(",")]
    count = [0]

    def each(sequence, change, apply):
        """Apply one change (to every view), then render each view once."""
        apply()
        shift = count[0] % len(active)
        count[0] += 1
        for m in active[shift:] + active[:shift]:
            if sequence in TIME_STEPS and m.name not in ("pv-volume", "mmv-default", "mmv-smoke",
                                                         "mmv-sky"):
                continue
            if sequence not in ("still",) + TIME_STEPS and m.name == "mmv-smoke":
                continue
            frame(m, name, sequence, change, writer, records)

    if "still" in wanted:
        for c in range(args.changes):
            each("still", c, lambda: None)
    if "orbit" in wanted:
        for c in range(args.changes):
            def turn():
                for m in active:
                    m.view.GetActiveCamera().Azimuth(10.0)
                    m.view.GetActiveCamera().OrthogonalizeViewUp()
            each("orbit", c, turn)
    if "opacity" in wanted:
        for c in range(args.changes):
            def drag():
                points = list(pwf.Points)
                points[13] = points[13] + 0.02  # the 1100 point's opacity
                pwf.Points = points
            each("opacity", c, drag)
    if "colour" in wanted:
        for c in range(args.changes):
            def recolour(c=c):
                points = list(lut.RGBPoints)
                points[9] = 0.6 + 0.04 * (c % 4)  # the 900 point's green
                lut.RGBPoints = points
            each("colour", c, recolour)
    def play(sequence, steps):
        for k, t in steps:
            def step(t=t):
                # Read the step untimed, so that no method pays for
                # reading it by rendering first.
                source.UpdatePipeline(t)
                for m in active:
                    m.view.CacheKey = t
                    m.view.ViewTime = t
            each(sequence, k, step)

    if "series" in wanted:
        # ParaView's animation caching on (what the animation scene sets on
        # each view), from the step the views show, untimed.
        for m in active:
            m.view.UseCache = 1
            m.view.CacheKey = times[0]
            m.view.SMProxy.StillRender()
        # The views already show step 0.
        play("series", list(enumerate(times))[1:])
        play("series-2", list(enumerate(times)))
    if "steps" in wanted:
        # ParaView's default: no animation caching, so nothing is kept and
        # every step is new (from the last one shown, the first again).
        for m in active:
            m.view.UseCache = 0
        play("steps", list(enumerate(times)) if "series" in wanted else list(enumerate(times))[1:])
    # The grid the kept probe choice gives against a fresh probe of the
    # final transfer functions and step (a new representation measures).
    for m in active:
        if m.representation != MMV:
            continue
        kept = info(m.representation, m.rep).get("IrradianceResolutionInfo", "").split(" ")[0]
        view = orbit.make_view(args)
        view.ViewTime = m.view.ViewTime
        rep = orbit.show(orbit.Method(m.name, m.representation, m.props, None), source, view)
        orbit.place_camera(view, args)
        light_view(view, source, args)
        view.SMProxy.StillRender()
        fresh = info(m.representation, rep).get("IrradianceResolutionInfo", "").split(" ")[0]
        checks.append({"volume": name, "method": m.name, "kept_grid": kept, "fresh_grid": fresh,
                       "same": "yes" if kept == fresh else "no"})
        log("%s %s: kept grid %s, fresh probe %s" % (name, m.name, kept, fresh))
        simple.Delete(rep)
        simple.Delete(view)
    for m in active:
        simple.Delete(m.rep)
        simple.Delete(m.view)
        m.view = m.rep = None
    simple.Delete(source)
    # Restore the shared transfer functions for the next volume.
    pwf.Points = orbit.OPACITY_POINTS
    lut.RGBPoints = orbit.RGB_POINTS


def summarise(records):
    rows = []
    groups = {}
    for r in records:
        key = (r["volume"], r["sequence"], r["method"])
        groups.setdefault(key, []).append(r)
    for (volume, sequence, method), rs in groups.items():
        seconds = [r["seconds"] for r in rs]
        ref = groups.get((volume, sequence, REFERENCE))
        still = groups.get((volume, "still", method))
        median = statistics.median(seconds)
        ratio = median / statistics.median([r["seconds"] for r in ref]) if ref else float("nan")
        own = (median / statistics.median([r["seconds"] for r in still])
               if still and sequence in OWN_STILL else float("nan"))
        target = TARGETS.get((sequence, method))
        measured = own if sequence in OWN_STILL else ratio
        row = {
            "volume": volume, "sequence": sequence, "method": method, "frames": len(rs),
            "median_s": "%.4f" % median, "ratio_to_pv_volume": "%.3f" % ratio,
            "ratio_to_own_still": "" if own != own else "%.3f" % own,
            "target": "" if target is None else "%.2f" % target,
            "met": "" if target is None else ("yes" if measured <= target else "no"),
            "irradiance_updates": sum(r["updates"] for r in rs),
            "probes": sum(r["probes"] for r in rs),
            "irradiance_copies": sum(r["copies"] for r in rs),
        }
        updated = [r["stages"] for r in rs if r["updates"]]
        skies = [r["stages"]["sky"] for r in rs if "sky" in r["stages"]]
        row["sky_updates"] = len(skies)
        row["sky_s"] = "%.4f" % statistics.median(skies) if skies else ""
        for s in STAGES:
            values = [st.get(s, 0.0) for st in updated]
            row["%s_s" % s.replace(" ", "_")] = "%.4f" % statistics.median(values) if values else ""
        rows.append(row)
    return rows


def main():
    args = parse_args()
    os.makedirs(args.out, exist_ok=True)
    simple._DisableFirstRenderCameraReset()
    problem = orbit.load_plugin(args.plugin)
    if problem:
        raise RuntimeError(problem)
    wanted = [m.strip() for m in args.methods.split(",")]
    methods = [Method(*m) for m in METHODS if m[0] in wanted]
    records = []
    checks = []
    folder = tempfile.mkdtemp(prefix="mmv_changes_")
    with open(os.path.join(args.out, "frames.csv"), "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["volume", "sequence", "method", "change", "seconds",
                         "irradiance_updates", "probes", "irradiance_copies"] + ["%s_s" % s.replace(" ", "_") for s in STAGES]
                        + ["irradiance_grid"])
        for volume in [v.strip() for v in args.volumes.split(",")]:
            t0 = time.perf_counter()
            run_volume(volume, args, methods, folder, writer, records, checks)
            f.flush()
            log("== %s done (%.0f s)" % (volume, time.perf_counter() - t0))
    rows = summarise(records)
    path = os.path.join(args.out, "changes.csv")
    orbit.write_csv(path, rows)
    log("%-6s %-8s %-12s %9s %8s %8s %6s %4s %4s %4s  %s" % (
        "volume", "sequence", "method", "median s", "x Volume", "x still", "target", "upd", "prb",
        "cpy",
        "stages (median s): probe/prefilter/table/inputs/setup/shadows/diffusion/write/keep/total"))
    for r in rows:
        log("%-6s %-8s %-12s %9s %8s %8s %6s %4s %4s %4s  %s" % (
            r["volume"], r["sequence"], r["method"], r["median_s"], r["ratio_to_pv_volume"],
            r["ratio_to_own_still"], (r["target"] + (" " + r["met"] if r["met"] else "")),
            r["irradiance_updates"], r["probes"], r["irradiance_copies"],
            "/".join(r["%s_s" % s.replace(" ", "_")] or "-" for s in STAGES if s != "pass") +
            (" sky %s s x%d" % (r["sky_s"], r["sky_updates"]) if r["sky_updates"] else "")))
    for r in rows:
        if r["sequence"] in ("steps", "series") and r["method"] != "pv-volume" and \
                r["irradiance_updates"] < r["frames"]:
            # The chest moves by sin(2 pi k / steps): with steps = 2 mod 4
            # two neighbouring steps hold the same values.
            log("warning: %s %s: %d of %d first-loop steps updated nothing (the same values "
                "as the step before); the median mixes them in (--steps 8 has none)" % (
                    r["volume"], r["method"], r["frames"] - r["irradiance_updates"], r["frames"]))
    log("wrote %s" % path)
    if checks:
        orbit.write_csv(os.path.join(args.out, "grid_check.csv"), checks)
    if not args.no_plot:
        try:
            import plot_lighting_changes
            log("wrote %s" % plot_lighting_changes.plot(path, os.path.join(args.out, "changes.png")))
        except Exception as e:  # noqa: BLE001 - the CSV is the result
            log("WARNING: no chart: %s" % e)


if __name__ == "__main__":
    main()
