"""Dim lights on a coarser grid: the still frame after a light-kit camera
move with the kit's fill, back and head lights strided (the representation's
DimLightCoarsening, default on) and with every light on the irradiance grid,
in one view, interleaved; the image error between the two (run with
pvpython).

    xvfb-run -a -s "-noreset -screen 0 1280x1024x24" \\
        scripts/pvpython Testing/Benchmark/pv_dim_lights.py --out DIR [--quick]

Volumes as pv_lighting_changes.py's (head: smooth, chest: fine structure),
400 x 400, ParaView's light kit; materials default, `skin` and `smoke`; each setting
in its own view. Each of --changes camera moves (Azimuth 10 degrees) is made
in both views and rendered once in each (the order alternates). Writes
OUT/dim_lights.csv: per volume and material the median still frame, shadow
and diffusion seconds of each setting, the shadow rays cast (voxel-lights)
and the PSNR of the strided image against the exact one (the minimum over
the moves).
"""

import argparse
import csv
import math
import os
import statistics
import sys
import tempfile
import time

from paraview import simple
import multimaterialvolume  # noqa: F401 (the mapper's own methods from Python)

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import pv_lighting_changes as changes  # noqa: E402
import pv_lightkit_orbit as orbit  # noqa: E402


def parse_args():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--data", default=os.path.join(HERE, "..", "Data", "headsq.vti"))
    p.add_argument("--out", default=os.path.join(os.getcwd(), "build", "benchmark_dim_lights"))
    p.add_argument("--quick", action="store_true", help="128x128x64, 2 moves")
    p.add_argument("--volumes", default="head,chest")
    p.add_argument("--presets", default="default,skin,smoke")
    p.add_argument("--changes", type=int, default=None, help="camera moves (default 4)")
    p.add_argument("--view-size", type=int, default=400)
    args, _ = p.parse_known_args()
    args.dims = [128, 128, 64] if args.quick else [256, 256, 128]
    args.steps = 1
    args.paraview_lod = False
    args.zoom = 1.3
    args.changes = args.changes or (2 if args.quick else 4)
    return args


def grab(view):
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkRenderingCore import vtkWindowToImageFilter
    w = vtkWindowToImageFilter()
    w.SetInput(view.GetRenderWindow())
    w.ReadFrontBufferOff()
    w.Update()
    return vtk_to_numpy(w.GetOutput().GetPointData().GetScalars()).astype("float64")


def psnr(a, b):
    mse = ((a - b) ** 2).mean()
    return float("inf") if mse == 0 else 10.0 * math.log10(255.0 * 255.0 / mse)


def make_method(path, preset, strided, args):
    """A view of its own showing the volume, DimLightCoarsening on or off."""
    reader = simple.XMLImageDataReader(FileName=[path])
    view = orbit.make_view(args)
    rep = simple.Show(reader, view)
    rep.Representation = orbit.MMV
    simple.ColorBy(rep, ("POINTS", orbit.ARRAY))
    orbit.setup_transfer_functions()
    rep.ScalarOpacityUnitDistance = orbit.OPACITY_UNIT_DISTANCE
    if preset != "default":
        rep.MaterialPreset = preset
    rep.DimLightCoarsening = int(strided)
    orbit.place_camera(view, args)
    view.SMProxy.StillRender()
    return reader, view, rep


def run(name, preset, path, args, writer):
    methods = {strided: make_method(path, preset, strided, args) for strided in (True, False)}
    frames = {True: [], False: []}
    shadows = {True: [], False: []}
    diffusion = {True: [], False: []}
    rays = {}
    errors = []
    for change in range(args.changes):
        images = {}
        for strided in ((True, False) if change % 2 == 0 else (False, True)):
            _, view, _ = methods[strided]
            view.GetActiveCamera().Azimuth(10.0)
            start = time.time()
            view.SMProxy.StillRender()
            frames[strided].append(time.time() - start)
            irradiance = orbit.volume_props(view)[0].GetMapper().GetIrradianceEstimator()
            shadows[strided].append(irradiance.GetLastEstimationSeconds())
            diffusion[strided].append(irradiance.GetLastDiffusionSeconds())
            rays[strided] = irradiance.GetLastEstimatedVoxels()
            images[strided] = grab(view)
        errors.append(psnr(images[True], images[False]))
    mapper = orbit.volume_props(methods[True][1])[0].GetMapper()
    row = {
        "volume": name, "material": preset,
        "grid": "x".join(str(d) for d in mapper.GetIrradianceDimensions()),
        "frame_strided_s": statistics.median(frames[True]),
        "frame_exact_s": statistics.median(frames[False]),
        "shadows_strided_s": statistics.median(shadows[True]),
        "shadows_exact_s": statistics.median(shadows[False]),
        "diffusion_strided_s": statistics.median(diffusion[True]),
        "diffusion_exact_s": statistics.median(diffusion[False]),
        "voxel_lights_strided": rays[True], "voxel_lights_exact": rays[False],
        "psnr_db_min": min(errors),
    }
    row["frame_ratio"] = row["frame_strided_s"] / row["frame_exact_s"]
    writer.writerow(row)
    print(", ".join("%s %s" % (k, ("%.3f" % v) if isinstance(v, float) else v)
                    for k, v in row.items()))
    sys.stdout.flush()
    for reader, view, rep in methods.values():
        simple.Delete(rep)
        simple.Delete(view)
        simple.Delete(reader)


def main():
    args = parse_args()
    os.makedirs(args.out, exist_ok=True)
    folder = tempfile.mkdtemp(prefix="mmv_dim_lights_")
    fields = ["volume", "material", "grid", "frame_strided_s", "frame_exact_s", "frame_ratio",
              "shadows_strided_s", "shadows_exact_s", "diffusion_strided_s",
              "diffusion_exact_s", "voxel_lights_strided",
              "voxel_lights_exact", "psnr_db_min"]
    with open(os.path.join(args.out, "dim_lights.csv"), "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=fields)
        writer.writeheader()
        for name in args.volumes.split(","):
            path = changes.write_series(name, args, folder)[0]
            for preset in args.presets.split(","):
                run(name, preset, path, args, writer)


if __name__ == "__main__":
    main()
