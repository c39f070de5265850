"""A Light Inspector spot light on the CT-sized head: foreground luminance of
ParaView's Volume and of Multi-Material Volume (the measured case of docs/paraview.md;
run with pvpython).

    xvfb-run -a -s "-noreset -screen 0 1280x1024x24" \\
        pvpython Testing/Benchmark/pv_spot_light.py [--quick] [--out DIR]

Scene as pv_lightkit_orbit.py (headsq.vti resampled to 256x256x128, its
opacity and colour maps, a fixed front camera, 400x400) with the light kit off and one light added as the Light Inspector adds it: a scene
light, Type Positional, ConeAngle 25, 600 units from the data's centre, aimed at
it, default AttenuationValues (1, 0, 0) and Exponent 1.

Methods: ParaView's "Volume" (Shade 1); "Multi-Material Volume" with
MaterialPreset bone and PointLightRadius 0 (the default: the light's
attenuation); the same with PointLightRadius = the smallest data spacing (the
former default: eq. 12 falloff from one voxel); the same with PointLightRadius
1e6 (eq. 12 without falloff over the data, as a user might try).

Foreground: the pixels of ParaView's Volume image that differ from the
background by more than 3 levels in some channel; every method's mean
luminance (0.2126 R + 0.7152 G + 0.0722 B, 0-255) is taken over that mask.
Writes OUT/spot_light.csv and OUT/spot_<method>.png.
"""

import csv
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "..", "Python"))

import numpy  # noqa: E402
from paraview import simple  # noqa: E402

import pv_lightkit_orbit as orbit  # noqa: E402
from mmv_testing import read_png  # noqa: E402


def parse_args():
    p = orbit.head_parser(__doc__, os.path.join(os.getcwd(), "build", "spot_light"))
    p.add_argument("--quick", action="store_true", help="128x128x64")
    p.add_argument("--distance", type=float, default=600.0)
    p.add_argument("--cone", type=float, default=25.0)
    args, _ = p.parse_known_args()
    args.dims = [128, 128, 64] if args.quick else [256, 256, 128]
    args.view_size = 400
    args.zoom = 1.3
    args.paraview_lod = False
    return args


def add_spot(view, center, args):
    """The light as the Light Inspector makes it, from the camera's side,
    up and to the left."""
    direction = numpy.array([-0.35, 1.0, -0.45])
    direction /= numpy.linalg.norm(direction)
    light = simple.AddLight(view=view)
    light.Coords = "Scene"
    light.Type = "Positional"
    light.ConeAngle = args.cone
    light.Position = list(numpy.array(center) + args.distance * direction)
    light.FocalPoint = list(center)
    light.Intensity = 1.0
    return light


def main():
    args = parse_args()
    if not orbit.start(args):
        return 1
    source, bounds, center = orbit.resampled_head(args)
    spacing = min((bounds[2 * a + 1] - bounds[2 * a]) / (args.dims[a] - 1) for a in range(3))

    methods = [
        ("pv-volume", "Volume", {"Shade": 1}),
        ("mmv-bone", orbit.MMV, {"MaterialPreset": "bone"}),
        ("mmv-bone-eq12-one-voxel", orbit.MMV,
         {"MaterialPreset": "bone", "LightFalloff": "Inverse Square Beyond Radius",
          "PointLightRadius": spacing}),
        ("mmv-bone-eq12-huge-radius", orbit.MMV,
         {"MaterialPreset": "bone", "LightFalloff": "Inverse Square Beyond Radius",
          "PointLightRadius": 1.0e6}),
    ]
    images = {}
    for name, representation, props in methods:
        view = orbit.make_view(args)
        view.UseLight = 0  # no light kit (ParaView 5.11 has no separate headlight)
        m = orbit.Method(name, representation, props, None)
        rep = orbit.show(m, source, view)
        if rep is None:
            print("ERROR: %s: %s" % (name, "; ".join(m.notes)))
            return 1
        # A fixed front camera (ResetCamera can see different bounds per
        # representation), the head filling most of the view.
        orbit.place_camera(view, args, (
            [center[0], center[1] + 520.0, center[2]], center, [0.0, 0.0, -1.0], 30.0))
        add_spot(view, center, args)
        view.SMProxy.StillRender()  # not simple.Render: it resets the camera on a first render
        path = os.path.join(args.out, "spot_%s.png" % name)
        simple.SaveScreenshot(path, view, ImageResolution=[args.view_size] * 2,
                              TransparentBackground=0)
        images[name] = read_png(path)
        simple.Delete(view)

    background = numpy.array(orbit.BACKGROUND) * 255.0
    reference = images["pv-volume"]
    mask = numpy.any(numpy.abs(reference - background) > 3.0, axis=2)
    weights = numpy.array([0.2126, 0.7152, 0.0722])
    rows = []
    for name, _, _ in methods:
        luminance = float(numpy.mean((images[name] @ weights)[mask]))
        rows.append({"method": name, "foreground_pixels": int(mask.sum()),
                     "foreground_luminance": round(luminance, 1)})
        print("%-26s foreground luminance %.1f of 255 over %d pixels"
              % (name, luminance, int(mask.sum())))
    with open(os.path.join(args.out, "spot_light.csv"), "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        writer.writeheader()
        writer.writerows(rows)
    return 0


if __name__ == "__main__":
    sys.exit(main())
