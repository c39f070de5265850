"""Seconds of each irradiance stage after light-kit camera moves (run with pvpython).

    xvfb-run -a -s "-noreset -screen 0 1280x1024x24" scripts/pvpython \\
        Testing/Benchmark/pv_update_stages.py --data chest.vti [--plugin SO] [--frames 6] \\
        [--preset skin] [--series FILE... [--cache] [--loops 3]]

One Multi-Material Volume (default material, or --preset's) of --data in a 400 x 400 view
under ParaView's light kit, with pv_lightkit_orbit.py's colour and opacity
maps. Each frame turns the camera 10 degrees and calls StillRender(), so
every kit light moves and the whole irradiance is recomputed. With
--series, each frame instead shows the next of the given files (time steps
on one grid; --data is the first) with the camera fixed. Prints the
medians of the frame and of the stages LastIrradianceStages reports. With
--series and --loops N, plays the series N times instead (each step read
before its timed frame) and prints each loop's median frame and that of a
still frame with nothing changed. To
compare two builds, alternate runs with each build's --plugin (with
MMV_BUILD_DIR set for scripts/pvpython).
"""

import argparse
import os
import statistics
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

from paraview import simple  # noqa: E402

import pv_lightkit_orbit as orbit  # noqa: E402

def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--plugin", default=orbit.DEFAULT_PLUGIN)
    p.add_argument("--data", required=True, help="a .vti with one point array")
    p.add_argument("--frames", type=int, default=6)
    p.add_argument("--preset", default="", help="a MaterialPreset, e.g. skin")
    p.add_argument("--cache", action="store_true",
                   help="with --series: ParaView's animation caching on, as the scene sets it")
    p.add_argument("--series", nargs="*", default=[],
                   help="further time steps of --data: each frame shows the next")
    p.add_argument("--loops", type=int, default=0,
                   help="with --series: play it this many times, print each loop's median")
    p.add_argument("--cache-mb", type=float, default=None,
                   help="IrradianceCacheMB (the budget for kept steps; default the property's)")
    args, _ = p.parse_known_args()

    simple.LoadPlugin(args.plugin, remote=False, ns=globals())
    steps = [args.data] + args.series
    source = simple.XMLImageDataReader(FileName=steps)
    view = simple.CreateView("RenderView")
    view.ViewSize = [400, 400]
    view.OrientationAxesVisibility = 0
    rep = simple.Show(source, view)
    array = source.PointData.keys()[0]
    simple.ColorBy(rep, ("POINTS", array))
    rep.SetRepresentationType("Multi-Material Volume")
    if args.preset:
        rep.MaterialPreset = args.preset
    if args.cache_mb is not None:
        rep.IrradianceCacheMB = args.cache_mb
    simple.GetColorTransferFunction(array).RGBPoints = orbit.RGB_POINTS
    simple.GetOpacityTransferFunction(array).Points = orbit.OPACITY_POINTS
    simple.ResetCamera(view)
    simple.Render(view)

    camera = view.GetActiveCamera()
    rows = []
    times = source.TimestepValues or [0.0]
    if args.series and args.loops > 0:
        play_loops(view, rep, source, times, args)
        return
    for frame in range(args.frames):
        if args.series:
            view.ViewTime = times[(frame + 1) % len(times)]
            if args.cache:
                view.UseCache = 1
                view.CacheKey = view.ViewTime
        else:
            camera.Azimuth(10.0)
        start = time.perf_counter()
        view.SMProxy.StillRender()
        row = {"frame": time.perf_counter() - start}
        rep.UpdatePropertyInformation()
        row.update(orbit.stage_seconds(rep.GetProperty("LastIrradianceStages").GetData()))
        rows.append(row)
    for name in ("frame",) + orbit.STAGES:
        print("%-10s median %.3f s" % (name, statistics.median(r.get(name, 0.0) for r in rows)))
    print("grid: %s" % rep.GetProperty("IrradianceResolutionInfo").GetData())


def play_loops(view, rep, source, times, args):
    """Each loop's median frame over the series' steps (the first loop from
    its second step: the view shows the first), then a still frame's."""
    if args.cache:
        view.UseCache = 1
        view.CacheKey = times[0]
    view.SMProxy.StillRender()
    counters = ["IrradianceUpdateCount", "IrradianceCacheHitCount"]

    for loop in range(args.loops):
        frames = []
        before = orbit.read_info(rep, counters)
        for k, t in enumerate(times):
            if loop == 0 and k == 0:
                continue
            source.UpdatePipeline(t)
            if args.cache:
                view.CacheKey = t
            view.ViewTime = t
            start = time.perf_counter()
            view.SMProxy.StillRender()
            frames.append(time.perf_counter() - start)
        after = orbit.read_info(rep, counters)
        print("loop %d     median %.3f s  (%d updates, %d copies)" % (
            loop + 1, statistics.median(frames), *(after[c] - before[c] for c in counters)))
    still = []
    for _ in range(4):
        start = time.perf_counter()
        view.SMProxy.StillRender()
        still.append(time.perf_counter() - start)
    print("still      median %.3f s" % statistics.median(still))


if __name__ == "__main__":
    main()
