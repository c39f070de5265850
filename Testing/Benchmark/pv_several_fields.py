"""What a second field costs: the same volume with one field and with two
(the data and a smooth "temperature" cloud, each with its own colour map,
opacity function and material), under ParaView's default light kit, against
ParaView's Volume (Shade on) of the data alone (run with pvpython).

    xvfb-run -a -s "-noreset -screen 0 1280x1024x24" \\
        scripts/pvpython Testing/Benchmark/pv_several_fields.py [--quick] [--out DIR]

Volumes: the MR head resampled to 256x256x128 (smooth) and the chest of
mmv_fine_volume.py (thin ribs and shells), each with a second array "cloud":
a Gaussian blob over a third of the box. Methods, each in its own 400x400
view, measured round-robin per change:
  pv-volume  ParaView "Volume", Shade on, the data
  mmv-one    "Multi-Material Volume", the data
  mmv-two    "Multi-Material Volume", the data and FieldArrays ["cloud"]
             (its own colour map and opacity, material preset "smoke", which
             scatters, or --cloud-preset)
Sequences: a light-kit camera move (Azimuth 10 degrees, one still frame) and
an opacity edit of the data (one point moved, one still frame).

Writes OUT/several_fields.csv (every frame) and prints the medians and the
ratios to pv-volume and of mmv-two to mmv-one.
"""

import argparse
import csv
import os
import statistics
import sys
import time

from paraview import simple

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import mmv_fine_volume  # noqa: E402
import pv_lightkit_orbit as orbit  # noqa: E402

MMV = "Multi-Material Volume"
METHODS = [("pv-volume", "Volume", {"Shade": 1}, False),
           ("mmv-one", MMV, {}, False),
           ("mmv-two", MMV, {}, True)]


def parse_args():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--plugin", default=orbit.DEFAULT_PLUGIN)
    p.add_argument("--data", default=os.path.join(HERE, "..", "Data", "headsq.vti"))
    p.add_argument("--out", default=os.path.join(os.getcwd(), "build", "benchmark_fields"))
    p.add_argument("--quick", action="store_true", help="128x128x64, 2 changes")
    p.add_argument("--volumes", default="head,chest")
    p.add_argument("--changes", type=int, default=None)
    p.add_argument("--view-size", type=int, default=400)
    p.add_argument("--cloud-preset", default="smoke",
                   help="the cloud's material preset (smoke scatters; matte does not)")
    p.add_argument("--cloud-opacity", type=float, default=0.05,
                   help="the cloud's largest opacity (0: an invisible second field, which "
                   "measures what the second field costs by itself)")
    args, _ = p.parse_known_args()
    args.dims = [128, 128, 64] if args.quick else [256, 256, 128]
    args.changes = args.changes or (2 if args.quick else 4)
    args.paraview_lod = False
    args.zoom = 1.3
    return args


def with_cloud(values, dims):
    """The volume and a smooth cloud (0 to 1000) as a two-array .vti."""
    import numpy
    nx, ny, nz = dims
    z, y, x = numpy.meshgrid(numpy.linspace(0, 1, nz), numpy.linspace(0, 1, ny),
                             numpy.linspace(0, 1, nx), indexing="ij")
    r2 = (x - 0.4) ** 2 + (y - 0.55) ** 2 + (z - 0.6) ** 2
    return values.astype("float32"), (1000.0 * numpy.exp(-r2 / 0.03)).astype("float32")


def write_volume(name, args, folder):
    from vtkmodules.util import numpy_support
    from vtkmodules.vtkCommonDataModel import vtkImageData
    from vtkmodules.vtkIOXML import vtkXMLImageDataWriter
    if name == "head":
        import pv_lighting_changes
        values = pv_lighting_changes.head_values(args)
    else:
        values = mmv_fine_volume.chest(tuple(args.dims))
    data, cloud = with_cloud(values, args.dims)
    image = vtkImageData()
    image.SetDimensions(*args.dims)
    for array_name, array in ((orbit.ARRAY, data), ("cloud", cloud)):
        vtk_array = numpy_support.numpy_to_vtk(array.ravel(), deep=1)
        vtk_array.SetName(array_name)
        image.GetPointData().AddArray(vtk_array)
    path = os.path.join(folder, name + "_fields.vti")
    writer = vtkXMLImageDataWriter()
    writer.SetFileName(path)
    writer.SetInputData(image)
    writer.Write()
    return path


def add_cloud(rep, preset, opacity):
    lut = simple.GetColorTransferFunction("cloud")
    lut.RGBPoints = [0.0, 1.0, 0.5, 0.1, 1000.0, 1.0, 0.8, 0.3]
    pwf = simple.GetOpacityTransferFunction("cloud")
    pwf.Points = [0.0, 0.0, 0.5, 0.0, 300.0, 0.0, 0.5, 0.0, 1000.0, opacity, 0.5, 0.0]
    rep.FieldArrays = ["cloud"]
    rep.FieldMaterialPresets = [preset]


def median(values):
    return statistics.median(values) if values else float("nan")


def main():
    args = parse_args()
    orbit.load_plugin(args.plugin)
    os.makedirs(args.out, exist_ok=True)
    rows = []
    summary = []
    for volume in args.volumes.split(","):
        path = write_volume(volume, args, args.out)
        source = simple.XMLImageDataReader(FileName=[path])
        methods = []
        for name, representation, props, cloud in METHODS:
            view = orbit.make_view(args)
            rep = orbit.show(orbit.Method(name, representation, props, None), source, view)
            if cloud:
                add_cloud(rep, args.cloud_preset, args.cloud_opacity)
            orbit.place_camera(view, args)
            methods.append((name, view, rep))
        lut, pwf = orbit.setup_transfer_functions()
        for _, view, _ in methods:
            view.SMProxy.StillRender()
        points = list(pwf.Points)
        times = {}
        for sequence in ("orbit", "opacity"):
            for change in range(args.changes):
                if sequence == "opacity":
                    edited = list(points)
                    edited[-3] = edited[-3] * (0.9 if change % 2 == 0 else 1.0)
                    pwf.Points = edited
                order = methods[change % len(methods):] + methods[:change % len(methods)]
                for name, view, rep in order:
                    if sequence == "orbit":
                        view.GetActiveCamera().Azimuth(10.0)
                    t0 = time.perf_counter()
                    view.SMProxy.StillRender()
                    seconds = time.perf_counter() - t0
                    times.setdefault((sequence, name), []).append(seconds)
                    rows.append([volume, sequence, name, change, "%.4f" % seconds])
        for name, _, rep in methods:
            if name != "pv-volume":
                info = orbit.read_info(rep, ["NumberOfFields", "MultiMaterialActive",
                                             "LastIrradianceStages", "IrradianceResolutionInfo"])
                print("%s %s: %s" % (volume, name, info))
        for sequence in ("orbit", "opacity"):
            base = median(times[(sequence, "pv-volume")])
            one = median(times[(sequence, "mmv-one")])
            two = median(times[(sequence, "mmv-two")])
            line = ("%s %s: Volume %.3f s, one field %.3f s (%.2fx), two fields %.3f s (%.2fx); "
                    "two / one %.2f" % (volume, sequence, base, one, one / base, two, two / base,
                                        two / one))
            print(line)
            summary.append(line)
        for _, view, _ in methods:
            simple.Delete(view)
        simple.Delete(source)
    with open(os.path.join(args.out, "several_fields.csv"), "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["volume", "sequence", "method", "change", "seconds"])
        writer.writerows(rows)
    print("\n".join(summary))


if __name__ == "__main__":
    main()
