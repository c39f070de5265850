"""Point and spot lights outside or inside the data: piecewise rays swept
toward the light against one full ray per voxel (run with pvpython).

    xvfb-run -a -s "-noreset -screen 0 1280x1024x24" \\
        scripts/pvpython Testing/Benchmark/pv_point_light_sweep.py [--out DIR] [--edits N] \\
        [--distance 600] [--lights spot,point]

Volumes (256 x 256 x 128): the MR head (Testing/Data/headsq.vti resampled)
and the fine chest of mmv_fine_volume.py, with pv_lightkit_orbit.py's colour
and opacity maps, a front camera, 400 x 400, the light kit off. Lights, one
at a time, as the Light Inspector adds them --distance units from the data's
centre (600: outside the data; 30: inside it): a spot light (cone 25
degrees) and a point light (cone 120: wider than 90 degrees, VTK shines it as
a point light).

Methods, each in its own view, rendered in turn after every change:
Multi-Material Volume at its defaults (ShadowEstimation 1: piecewise rays,
which a point or spot light beyond the data sweeps toward itself) and with
ShadowEstimation 0 (full rays). A light inside the data is swept in six
pyramids around it. Each opacity edit (+0.02 on the 1100 point,
as pv_lighting_changes.py drags it) recomputes the light's irradiance.

Writes OUT/point_light_sweep.csv: per volume, light and method, the median
frame and shadow-stage seconds of --edits edits, and the PSNR of the image at
rest against the full rays' image.
"""

import argparse
import csv
import os
import statistics
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "..", "Python"))

from paraview import simple  # noqa: E402

import mmv_fine_volume  # noqa: E402
import pv_lightkit_orbit as orbit  # noqa: E402
import pv_spot_light  # noqa: E402
from mmv_testing import read_png  # noqa: E402

METHODS = [("piecewise", {}), ("full rays", {"ShadowEstimation": 0})]
LIGHTS = [("spot", 25.0), ("point", 120.0)]


def parse_args():
    p = orbit.head_parser(__doc__, os.path.join(os.getcwd(), "build", "point_light_sweep"))
    p.add_argument("--edits", type=int, default=3)
    p.add_argument("--distance", type=float, default=600.0,
                   help="the light's distance from the data's centre")
    p.add_argument("--lights", default="spot,point", help="of spot,point")
    args, _ = p.parse_known_args()
    args.dims = [256, 256, 128]
    args.view_size = 400
    args.zoom = 1.3
    args.paraview_lod = False
    return args


def shadow_seconds(rep):
    rep.UpdatePropertyInformation()
    stages = orbit.stage_seconds(rep.GetProperty("LastIrradianceStages").GetData())
    return stages.get("shadows", float("nan"))


def run(volume, source, center, light_name, cone, args, writer, folder):
    views = []
    for name, props in METHODS:
        view = orbit.make_view(args)
        view.UseLight = 0
        rep = orbit.show(orbit.Method(name, orbit.MMV, props, None), source, view)
        orbit.place_camera(view, args)
        pv_spot_light.add_spot(view, center, argparse.Namespace(distance=args.distance, cone=cone))
        view.SMProxy.StillRender()
        views.append((name, view, rep, [], []))
    _, pwf = orbit.setup_transfer_functions()
    for edit in range(args.edits):
        points = list(pwf.Points)
        points[13] = points[13] + 0.02  # the 1100 point's opacity
        pwf.Points = points
        for name, view, rep, frames, shadows in views[edit % 2:] + views[:edit % 2]:
            start = time.perf_counter()
            view.SMProxy.StillRender()
            frames.append(time.perf_counter() - start)
            shadows.append(shadow_seconds(rep))
    images = {}
    for name, view, _, _, _ in views:
        path = os.path.join(folder, "%s_%s_%s.png" % (volume, light_name, name.replace(" ", "_")))
        simple.SaveScreenshot(path, view, ImageResolution=[args.view_size] * 2,
                              TransparentBackground=0)
        images[name] = read_png(path)
    for name, view, rep, frames, shadows in views:
        row = {"volume": volume, "light": light_name, "method": name,
               "frame_s": "%.3f" % statistics.median(frames),
               "shadows_s": "%.3f" % statistics.median(shadows),
               "psnr_vs_full_rays_db": "%.1f" % orbit.psnr(images[name], images["full rays"])}
        writer.writerow(row)
        print("%-5s %-5s %-9s frame %s s, shadows %s s, PSNR vs full rays %s dB"
              % (volume, light_name, name, row["frame_s"], row["shadows_s"],
                 row["psnr_vs_full_rays_db"]))
        sys.stdout.flush()
        simple.Delete(rep)
        simple.Delete(view)
    pwf.Points = orbit.OPACITY_POINTS


def main():
    args = parse_args()
    if not orbit.start(args):
        return 1
    folder = tempfile.mkdtemp(prefix="mmv-point-sweep-")
    head, bounds, head_center = orbit.resampled_head(args)
    chest_path = mmv_fine_volume.write_vti(os.path.join(folder, "chest.vti"),
                                           mmv_fine_volume.chest(tuple(args.dims)))
    chest = simple.XMLImageDataReader(FileName=[chest_path])
    chest.UpdatePipeline()
    b = chest.GetDataInformation().GetBounds()
    chest_center = [0.5 * (b[2 * a] + b[2 * a + 1]) for a in range(3)]
    with open(os.path.join(args.out, "point_light_sweep.csv"), "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=["volume", "light", "method", "frame_s",
                                               "shadows_s", "psnr_vs_full_rays_db"])
        writer.writeheader()
        for volume, source, center in (("head", head, head_center),
                                       ("chest", chest, chest_center)):
            for light_name, cone in LIGHTS:
                if light_name not in args.lights.split(","):
                    continue
                run(volume, source, center, light_name, cone, args, writer, folder)
    return 0


if __name__ == "__main__":
    sys.exit(main())
