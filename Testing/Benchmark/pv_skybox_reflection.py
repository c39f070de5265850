"""A skybox reflection in ParaView: the head with the metal preset in a
"Skybox" background with environment lighting, and the same with
ReflectionSource "Background" (run with pvpython).

    xvfb-run -a -s "-noreset -screen 0 1280x1024x24" \\
        pvpython Testing/Benchmark/pv_skybox_reflection.py [--quick] [--out DIR]

Scene as pv_spot_light.py (headsq.vti resampled to 256x256x128, a fixed
front camera, 400x400), light kit on. The sky is an equirectangular image
written here (OUT/sky.png, 256x128): blue above the horizon, warm orange
below, a white band at the horizon and a dark red meridian facing the
camera, so where reflections come from is easy to read. The view's
BackgroundColorMode is "Skybox" with that texture and UseEnvironmentLighting
on, which gives the renderer its environment texture (what the mapper
reflects). Writes OUT/skybox_<name>.png and prints the mean colour of the
foreground of each.
"""

import argparse
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "..", "Python"))

import numpy  # noqa: E402
from matplotlib import image as mpimage  # noqa: E402
from paraview import simple  # noqa: E402

import pv_lightkit_orbit as orbit  # noqa: E402
from mmv_testing import read_png  # noqa: E402


def parse_args():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--plugin", default=orbit.DEFAULT_PLUGIN)
    p.add_argument("--data", default=os.path.join(orbit.ROOT, "Testing", "Data", "headsq.vti"))
    p.add_argument("--out", default=os.path.join(os.getcwd(), "build", "skybox_reflection"))
    p.add_argument("--quick", action="store_true", help="128x128x64")
    args, _ = p.parse_known_args()
    args.dims = [128, 128, 64] if args.quick else [256, 256, 128]
    args.view_size = 400
    args.zoom = 1.3
    args.paraview_lod = False
    return args


def write_sky(path, width=256, height=128):
    """Equirectangular sky, row 0 at the top of the PNG (the bottom of the
    image VTK reads: latitude -90 there after the reader's flip)."""
    v = (numpy.arange(height)[:, None] + 0.5) / height  # 0 at the top row
    u = (numpy.arange(width)[None, :] + 0.5) / width
    latitude = numpy.broadcast_to((0.5 - v) * numpy.pi, (height, width))
    u = numpy.broadcast_to(u, (height, width))
    sky = numpy.where((latitude > 0)[..., None], [0.25, 0.45, 0.95], [0.85, 0.45, 0.15])
    horizon = numpy.abs(latitude) < 0.08
    sky[horizon] = [1.0, 1.0, 1.0]
    sky[(numpy.abs(u - 0.5) < 0.02) & ~horizon] = [0.5, 0.0, 0.0]
    mpimage.imsave(path, numpy.clip(sky, 0.0, 1.0))


def main():
    args = parse_args()
    if not orbit.start(args):
        return 1
    sky_path = os.path.join(args.out, "sky.png")
    write_sky(sky_path)
    source, bounds, center = orbit.resampled_head(args)
    texture = simple.CreateTexture(sky_path)
    for name, reflection_source in (("environment", "Environment Texture"),
                                    ("background", "Background")):
        view = orbit.make_view(args)
        view.BackgroundColorMode = "Skybox"
        view.BackgroundTexture = texture
        view.UseEnvironmentLighting = 1
        m = orbit.Method(name, orbit.MMV, {"MaterialPreset": "metal",
                                           "ReflectionSource": reflection_source}, None)
        rep = orbit.show(m, source, view)
        if rep is None:
            print("ERROR: %s: %s" % (name, "; ".join(m.notes)))
            return 1
        orbit.place_camera(view, args, (
            [center[0], center[1] + 520.0, center[2]], center, [0.0, 0.0, -1.0], 30.0))
        view.SMProxy.StillRender()
        path = os.path.join(args.out, "skybox_%s.png" % name)
        simple.SaveScreenshot(path, view, ImageResolution=[args.view_size] * 2,
                              TransparentBackground=0)
        pixels = read_png(path)
        centre = pixels[150:250, 150:250].reshape(-1, 3)
        print("%-12s mean colour of the central 100x100 pixels: %s"
              % (name, numpy.round(centre.mean(axis=0), 1)))
        simple.Delete(view)
    return 0


if __name__ == "__main__":
    sys.exit(main())
