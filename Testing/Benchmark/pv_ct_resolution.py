"""Irradiance resolution against still-frame time and image quality on the CT
scene of pv_lightkit_orbit.py (run with pvpython).

    xvfb-run -a -s "-noreset -screen 0 1280x1024x24" \\
        pvpython Testing/Benchmark/pv_ct_resolution.py [--quick] [--out DIR]
    pvpython Testing/Benchmark/pv_ct_resolution.py --plot-only OUT/ct_resolution.csv [PNG]

Scene, view, light kit, transfer functions and camera as pv_lightkit_orbit.py
(headsq.vti resampled to 256x256x128, 400x400, ParaView's default light kit).
For each material (mmv-default, mmv-skin) and IrradianceScale (0 = auto: the
coarser of the memory budget and the screen rule, then 1.0 ... 0.25): the
camera is reset, one untimed still render builds the irradiance at that scale,
then M camera moves (Azimuth 10 degrees each) each followed by a timed
StillRender() - the light kit follows the camera, so every still frame
recomputes the lighting. ParaView's Volume (Shade on) makes the same moves in
its own view, alternating with the method move by move, so every row has its
own reference median (the machine is shared).

The final still image of every row is saved and compared (PSNR) with the
IrradianceScale = 1.0 image of the same method and the same camera.

Writes OUT/ct_resolution.csv, OUT/ct_resolution.png, OUT/frames.csv and the
screenshots (OUT/<method>_scale<scale>.png).
"""

import argparse
import csv
import math
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

SCALES = [0.0, 1.0, 0.75, 0.5, 0.35, 0.25]
MATERIALS = ["mmv-default", "mmv-skin"]
PSNR_TARGET_DB = 40.0
# Still-frame targets of pv_lightkit_orbit.py: mmv-default 1.25x, mmv-skin 3x.
STILL_TARGETS = {"mmv-default": 1.25, "mmv-skin": 3.0}


def scale_label(scale):
    return "auto" if scale == 0.0 else "%g" % scale


def parse_args(orbit):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--plugin", default=orbit.DEFAULT_PLUGIN)
    p.add_argument("--data", default=os.path.join(orbit.ROOT, "Testing", "Data", "headsq.vti"))
    p.add_argument("--out", default=os.path.join(os.getcwd(), "build", "ct_resolution"))
    p.add_argument("--quick", action="store_true", help="128x128x64, 2 moves, scales auto/1/0.5")
    p.add_argument("--dims", type=int, nargs=3, default=None, help="resample size (default 256 256 128)")
    p.add_argument("--moves", type=int, default=None, help="timed camera moves per row (default 3)")
    p.add_argument("--move-degrees", type=float, default=10.0)
    p.add_argument("--scales", default=None,
                   help="comma-separated IrradianceScale values, 0 = auto (default %s)"
                        % ",".join("%g" % s for s in SCALES))
    p.add_argument("--materials", default=",".join(MATERIALS))
    p.add_argument("--view-size", type=int, default=400)
    p.add_argument("--zoom", type=float, default=1.3)
    p.add_argument("--no-plot", action="store_true")
    args, _ = p.parse_known_args()
    args.paraview_lod = False  # what orbit.make_view reads: still frames only, no LOD anyway
    if args.dims is None:
        args.dims = [128, 128, 64] if args.quick else [256, 256, 128]
    if args.moves is None:
        args.moves = 2 if args.quick else 3
    if args.scales is None:
        args.scales = "0,1,0.5" if args.quick else ",".join("%g" % s for s in SCALES)
    args.scales = [float(s) for s in args.scales.split(",") if s.strip()]
    if 1.0 not in args.scales:
        args.scales.append(1.0)  # the PSNR reference
    return args


def open_method(orbit, name, source, args):
    spec = next(m for m in orbit.METHODS if m[0] == name)
    m = orbit.Method(*spec)
    m.view = orbit.make_view(args)
    m.rep = orbit.show(m, source, m.view)
    if m.rep is None:
        raise RuntimeError("%s: %s" % (name, "; ".join(m.notes)))
    orbit.place_camera(m.view, args)
    m.first_render = orbit.timed(m.view.SMProxy.StillRender)
    return m


def measure_row(orbit, ref, m, scale, args, frames, out_png):
    """Resets both cameras, builds the irradiance at `scale` (untimed), then
    the timed moves, alternating reference and method; saves the final image."""
    from paraview import simple

    m.rep.IrradianceScale = scale
    for x in (ref, m):
        orbit.place_camera(x.view, args)
    build = orbit.timed(m.view.SMProxy.StillRender)
    ref.view.SMProxy.StillRender()
    before = orbit.read_info(m.rep)
    times = {ref.name: [], m.name: []}
    for move in range(args.moves):
        order = (ref, m) if move % 2 == 0 else (m, ref)
        for x in order:
            cam = x.view.GetActiveCamera()
            cam.Azimuth(args.move_degrees)
            cam.OrthogonalizeViewUp()
            dt = orbit.timed(x.view.SMProxy.StillRender)
            times[x.name].append(dt)
            frames.writerow([m.name, scale_label(scale), x.name, move, "%.6f" % dt])
    after = orbit.read_info(m.rep)
    simple.SaveScreenshot(out_png, m.view, ImageResolution=[args.view_size] * 2,
                          TransparentBackground=0)
    updates = after.get("IrradianceUpdateCount", 0) - before.get("IrradianceUpdateCount", 0)
    still = orbit.median(times[m.name])
    ref_still = orbit.median(times[ref.name])
    return {
        "method": m.name,
        "irradiance_scale": scale_label(scale),
        "still_median_s": orbit.fmt(still),
        "reference_still_median_s": orbit.fmt(ref_still),
        "still_ratio": orbit.fmt(still / ref_still, "%.3f"),
        "still_target": orbit.fmt(STILL_TARGETS.get(m.name), "%.2f"),
        "psnr_db_vs_scale_1": "",
        "irradiance_resolution": str(after.get("IrradianceResolutionInfo", "")),
        "last_irradiance_s": orbit.fmt(after.get("LastIrradianceSeconds"), "%.4f"),
        "build_render_s": orbit.fmt(build, "%.3f"),
        "irradiance_updates": str(updates),
        "moves": str(len(times[m.name])),
        "image": os.path.basename(out_png),
    }


def run(orbit):
    from paraview import servermanager, simple

    args = parse_args(orbit)
    os.makedirs(args.out, exist_ok=True)
    materials = [n.strip() for n in args.materials.split(",") if n.strip()]
    simple._DisableFirstRenderCameraReset()
    problem = orbit.load_plugin(args.plugin)
    if problem:
        raise RuntimeError(problem)
    version = servermanager.vtkSMProxyManager.GetParaViewSourceVersion()
    orbit.log("== %s; resample %s, view %dx%d, scales %s, %d moves x %g deg per row"
              % (version, "x".join(map(str, args.dims)), args.view_size, args.view_size,
                 "/".join(scale_label(s) for s in args.scales), args.moves, args.move_degrees))

    reader = simple.XMLImageDataReader(FileName=[args.data])
    source = simple.ResampleToImage(Input=reader)
    source.SamplingDimensions = args.dims
    source.UpdatePipeline()

    ref = open_method(orbit, orbit.REFERENCE, source, args)
    methods = [open_method(orbit, name, source, args) for name in materials]
    orbit.settle_renders([ref] + methods)

    rows = []
    with open(os.path.join(args.out, "frames.csv"), "w", newline="") as f:
        frames = csv.writer(f)
        frames.writerow(["row_method", "irradiance_scale", "view", "move", "seconds"])
        for m in methods:
            for scale in args.scales:
                t0 = time.perf_counter()
                png = os.path.join(args.out, "%s_scale%s.png" % (m.name, scale_label(scale)))
                row = measure_row(orbit, ref, m, scale, args, frames, png)
                rows.append(row)
                f.flush()
                orbit.log("%-12s scale %-5s still %s s (%sx), %s (%.0f s)"
                          % (m.name, row["irradiance_scale"], row["still_median_s"],
                             row["still_ratio"], row["irradiance_resolution"],
                             time.perf_counter() - t0))

    for row in rows:
        full = next(r for r in rows if r["method"] == row["method"] and r["irradiance_scale"] == "1")
        value = orbit.psnr(orbit.read_png(os.path.join(args.out, row["image"])),
                           orbit.read_png(os.path.join(args.out, full["image"])))
        row["psnr_db_vs_scale_1"] = orbit.fmt(value, "%.2f")

    csv_path = os.path.join(args.out, "ct_resolution.csv")
    orbit.write_csv(csv_path, rows)
    with open(os.path.join(args.out, "machine.txt"), "w") as f:
        f.write("paraview %s\nresample %s\nview %d\nmoves %d\nmove_degrees %g\ncores %d\n"
                % (version, "x".join(map(str, args.dims)), args.view_size, args.moves,
                   args.move_degrees, os.cpu_count() or 0))

    orbit.log("")
    orbit.log("%-12s %6s %9s %9s %9s %9s %8s  %s" % ("method", "scale", "still s", "ref s", "ratio",
                                                    "PSNR dB", "irr. s", "irradiance grid"))
    for r in rows:
        orbit.log("%-12s %6s %9s %9s %9s %9s %8s  %s" % (
            r["method"], r["irradiance_scale"], r["still_median_s"], r["reference_still_median_s"],
            r["still_ratio"], r["psnr_db_vs_scale_1"], r["last_irradiance_s"],
            r["irradiance_resolution"]))
    orbit.log("targets: still <= %s (ratio to %s, same row); PSNR >= %g dB against scale 1"
              % (", ".join("%s %gx" % kv for kv in STILL_TARGETS.items()), orbit.REFERENCE,
                 PSNR_TARGET_DB))
    orbit.log("wrote %s" % csv_path)
    if not args.no_plot:
        orbit.log("wrote %s" % plot(csv_path, os.path.join(args.out, "ct_resolution.png")))


def plot(csv_path, png_path):
    """PSNR against the still-frame ratio, one curve per material, points
    labelled by IrradianceScale; scale 1 (the reference, infinite PSNR) on
    the top edge."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import matplotlib.ticker  # noqa: F401 - used through matplotlib.ticker

    from plot_lightkit_orbit import load_results

    rows, machine = load_results(csv_path)

    def value(text):
        try:
            return float(text)
        except (TypeError, ValueError):
            return float("nan")

    finite = [value(r["psnr_db_vs_scale_1"]) for r in rows]
    finite = [v for v in finite if not math.isnan(v) and not math.isinf(v)]
    top = max(finite + [PSNR_TARGET_DB]) + 6.0
    colors = {"mmv-default": "tab:blue", "mmv-skin": "tab:red"}
    fig, ax = plt.subplots(figsize=(8.0, 5.2))
    for name in [n for n in MATERIALS if any(r["method"] == n for r in rows)] + sorted(
            set(r["method"] for r in rows) - set(MATERIALS)):
        mine = [r for r in rows if r["method"] == name]
        color = colors.get(name, "tab:green")
        pts = []
        for r in mine:
            x = value(r["still_ratio"])
            y = value(r["psnr_db_vs_scale_1"])
            y = top if math.isinf(y) else y
            pts.append((r["irradiance_scale"], x, y))
        fixed = sorted([p for p in pts if p[0] != "auto"], key=lambda p: -float(p[0]))
        ax.plot([p[1] for p in fixed], [p[2] for p in fixed], "o-", color=color, label=name)
        for label, x, y in pts:
            grid = next((r["irradiance_resolution"].split(" ")[0] for r in mine
                         if r["irradiance_scale"] == label), "")
            if label == "auto":
                ax.plot([x], [y], "D", color=color, markerfacecolor="white", markersize=8)
                text = "auto (%s)" % grid
            else:
                text = label
            ax.annotate(text, (x, y), xytext=(6, -10 if name == "mmv-skin" else 5),
                        textcoords="offset points", fontsize=8, color=color)
    ax.axhline(PSNR_TARGET_DB, color="gray", ls="--", lw=1.2)
    ax.annotate("%g dB" % PSNR_TARGET_DB, (0.01, PSNR_TARGET_DB), xycoords=("axes fraction", "data"),
                xytext=(0, 3), textcoords="offset points", fontsize=8, color="gray")
    for name, target in STILL_TARGETS.items():
        color = colors.get(name, "gray")
        ax.axvline(target, color=color, ls="--", lw=1.2)
        ax.annotate("%s still target %gx" % (name, target), (target, 0.97),
                    xycoords=("data", "axes fraction"), xytext=(3, 0), textcoords="offset points",
                    fontsize=8, color=color, rotation=90, va="top")
    xs = [value(r["still_ratio"]) for r in rows] + list(STILL_TARGETS.values())
    xs = [x for x in xs if not math.isnan(x) and x > 0]
    # Log scale: the ratios span from below 1x (coarse grids) to ~20x.
    ax.set_xscale("log")
    ax.set_xlim(min(xs) / 1.25, max(xs) * 1.6)
    ax.xaxis.set_major_locator(matplotlib.ticker.FixedLocator(
        [t for t in (0.5, 0.75, 1, 1.5, 2, 3, 5, 7.5, 10, 15, 20, 30, 50)
         if min(xs) / 1.25 <= t <= max(xs) * 1.6]))
    ax.xaxis.set_major_formatter(matplotlib.ticker.FuncFormatter(lambda v, _: "%gx" % v))
    ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    ax.set_ylim(min(finite + [PSNR_TARGET_DB]) - 4.0, top + 3.0)
    ticks = [t for t in ax.get_yticks() if t < top - 2.0]
    ax.set_yticks(ticks + [top])
    ax.set_yticklabels(["%g" % t for t in ticks] + ["scale 1\n(ref.)"], fontsize=8)
    ax.set_xlabel("median still frame after a camera move / ParaView Volume (Shade on), same row (log)")
    ax.set_ylabel("PSNR of the final still image vs IrradianceScale 1 (dB)")
    ax.set_title("Irradiance resolution on the CT scene: resample %s, %s px view, light kit, "
                 "%s moves, %s cores" % (machine.get("resample", "?"), machine.get("view", "?"),
                                         machine.get("moves", "?"), machine.get("cores", "?")),
                 fontsize=9)
    ax.grid(True, which="major", alpha=0.3)
    ax.legend(fontsize=8, loc="lower right")
    fig.tight_layout()
    fig.savefig(png_path, dpi=100)
    plt.close(fig)
    return png_path


if __name__ == "__main__":
    if len(sys.argv) > 2 and sys.argv[1] == "--plot-only":
        src = sys.argv[2]
        dst = sys.argv[3] if len(sys.argv) > 3 else os.path.splitext(src)[0] + ".png"
        print("wrote " + plot(src, dst))
    else:
        import pv_lightkit_orbit
        run(pv_lightkit_orbit)
