"""The README's gallery, from real pvpython runs of the plugin.

    xvfb-run -a -s "-noreset -screen 0 1280x1024x24" \\
        scripts/pvpython Testing/Benchmark/pv_gallery.py [--out DIR]

The head (Testing/Data/headsq.vti resampled to 256 x 256 x 128), the colour
and opacity maps of pv_lightkit_orbit.py, a front view, 400 x 400:
  gallery_lightkit.png    ParaView's default lighting (the light kit),
                          MaterialPreset skin, GradientSmoothing 1
  gallery_spot.png        the light kit off, one Light Inspector spot light
                          (as pv_spot_light.py adds it), MaterialPreset bone
  gallery_reflection.png  MaterialPreset metal (reflection 0.6) in a gradient
                          background, which the reflection mirrors
all with GradientSmoothing 3 (3.3 mm here, the original 3.2 mm voxel: the
resample keeps the coarse sampling's stripes otherwise, docs/stability.md, "Stripes on thin shells").
Writes OUT/gallery_*.png and prints each image's render time.
"""

import argparse
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

from paraview import simple  # noqa: E402

import pv_lightkit_orbit as orbit  # noqa: E402
import pv_spot_light  # noqa: E402


def parse_args(doc=__doc__, view_size=400):
    """The head's options (written to docs/ by default) for a script
    described by `doc`, whose views are `view_size` pixels square."""
    p = orbit.head_parser(doc, os.path.join(orbit.ROOT, "docs"))
    p.add_argument("--dims", type=int, nargs=3, default=[256, 256, 128])
    args, _ = p.parse_known_args()
    args.view_size = view_size
    args.zoom = 1.3
    args.paraview_lod = False
    return args


def main():
    args = parse_args()
    if not orbit.start(args):
        return 1
    source, _, center = orbit.resampled_head(args)

    shots = [
        ("lightkit", {"MaterialPreset": "skin", "GradientSmoothing": 3.0}),
        ("spot", {"MaterialPreset": "bone", "GradientSmoothing": 3.0}),
        ("reflection", {"MaterialPreset": "metal", "GradientSmoothing": 3.0}),
    ]
    for name, props in shots:
        view = orbit.make_view(args)
        if name == "spot":
            view.UseLight = 0  # the light kit off: the spot light alone
        if name == "reflection":
            view.BackgroundColorMode = "Gradient"
            view.Background = [0.05, 0.07, 0.15]
            view.Background2 = [0.95, 0.75, 0.45]
        method = orbit.Method(name, orbit.MMV, props, None)
        rep = orbit.show(method, source, view)
        if rep is None:
            print("ERROR: %s: %s" % (name, "; ".join(method.notes)))
            return 1
        orbit.place_camera(view, args)
        if name == "spot":
            # The light pv_spot_light.py adds: 600 units up and to the left, cone 25.
            pv_spot_light.add_spot(view, center, argparse.Namespace(distance=600.0, cone=25.0))
        start = time.time()
        view.SMProxy.StillRender()
        seconds = time.time() - start
        path = os.path.join(args.out, "gallery_%s.png" % name)
        simple.SaveScreenshot(path, view, ImageResolution=[args.view_size] * 2,
                              TransparentBackground=0)
        print("%-10s %s: first still render %.2f s -> %s" % (name, props, seconds, path))
        simple.Delete(view)
    return 0


if __name__ == "__main__":
    sys.exit(main())
