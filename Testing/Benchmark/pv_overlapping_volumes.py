"""How ParaView composites two Multi-Material Volume representations whose
boxes overlap, against the same data as one volume with two fields
(FieldArrays), which integrates both along one ray: a red ball and a blue
slab through it, one directional light. Prints the PSNR of the two
representations, and of the two sources merged by the Volumes To Fields
filter, against the two fields made on one grid; and of those against the
ball or the slab alone (how much the other adds). The slab comes on a grid
of its own, its box inside the ball's; with --fine-slab on a grid twice as
fine (the merge then interpolates the ball). Writes the images.

    xvfb-run -a -s "-noreset -screen 0 1280x1024x24" scripts/pvpython \\
        Testing/Benchmark/pv_overlapping_volumes.py --out OUT
"""

import argparse
import os
import sys

from paraview import simple

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "Python"))
import mmv_testing as mmv  # noqa: E402

parser = argparse.ArgumentParser()
parser.add_argument("--out", default=os.path.join(os.getcwd(), "build", "overlapping_volumes"))
parser.add_argument("--fine-slab", action="store_true",
                    help="the slab's grid twice as fine as the ball's")
parser.add_argument("--plugin", default=os.path.join(
    HERE, "..", "..", "build", "lib", "paraview-plugins", "MultiMaterialVolume",
    "MultiMaterialVolume.so"))
args = parser.parse_args()
os.makedirs(args.out, exist_ok=True)
simple.LoadPlugin(args.plugin, remote=True)

N = 48
HALF = (N - 1) / 2.0
# Each source samples the ball and the slab at its own points: `lo` its
# lower corner, `n` its points per axis, `step` its spacing.
SCRIPT = """
import numpy
from vtkmodules.util.numpy_support import numpy_to_vtk
lo, n, step = %r, %r, %r
out = self.GetOutput()
out.SetDimensions(*n)
out.SetOrigin(*lo)
out.SetSpacing(step, step, step)
z, y, x = numpy.meshgrid(*[lo[a] + step * numpy.arange(n[a]) for a in (2, 1, 0)], indexing='ij')
ball = numpy.clip(1.0 - numpy.sqrt(x ** 2 + y ** 2 + z ** 2) / 14.0, 0, 1)
slab = ((abs(z - 2) <= 3) & (abs(x) <= 20) & (abs(y) <= 20)).astype('f4')
for name, values in %s:
    array = numpy_to_vtk(values.astype('f4').ravel(), deep=1)
    array.SetName(name)
    out.GetPointData().AddArray(array)
"""


def make_source(arrays, lo=(-HALF,) * 3, n=(N,) * 3, step=1.0):
    source = simple.ProgrammableSource(OutputDataSetType="vtkImageData",
                                       Script=SCRIPT % (lo, n, step, arrays))
    source.ScriptRequestInformation = (
        "executive = self.GetExecutive()\n"
        "info = executive.GetOutputInformation(0)\n"
        "info.Set(executive.WHOLE_EXTENT(), 0, %d, 0, %d, 0, %d)\n"
        "info.Set(self.GetOutput().ORIGIN(), %r, %r, %r)\n"
        "info.Set(self.GetOutput().SPACING(), %r, %r, %r)\n"
        % (n[0] - 1, n[1] - 1, n[2] - 1, lo[0], lo[1], lo[2], step, step, step))
    return source


def render(name):
    return mmv.render_image(view, os.path.join(args.out, name + ".png"))


simple._DisableFirstRenderCameraReset()
view = mmv.make_view()
view.CameraPosition = [60.0, -70.0, 45.0]
view.CameraFocalPoint = [0.0, 0.0, 0.0]
view.CameraViewUp = [0.0, 0.0, 1.0]
view.CameraViewAngle = 30.0
mmv.add_directional_light(view, [20.0, 10.0, 100.0])
for name, rgb, opacity in (("ball", (0.9, 0.2, 0.15), 0.5), ("slab", (0.2, 0.35, 0.9), 0.3)):
    mmv.set_uniform_maps(name, rgb, [(0.0, 0.0), (0.05, 0.0), (1.0, opacity)])

# The slab's own grid: its box (with a margin of zeros) inside the ball's,
# on the ball's lattice, or twice as fine with --fine-slab.
SLAB_STEP = 0.5 if args.fine_slab else 1.0
SLAB_LO = (-HALF + 1.0, -HALF + 1.0, -HALF + 19.0)
SLAB_N = tuple(int(round(extent / SLAB_STEP)) + 1 for extent in (N - 3.0, N - 3.0, 10.0))
# The one-grid reference: both fields on the merged grid (the ball's box at
# the finest spacing).
REF_N = (int(round((N - 1) / SLAB_STEP)) + 1,) * 3

both = make_source("(('ball', ball), ('slab', slab))", n=REF_N, step=SLAB_STEP)
fields = mmv.show_multi_material(both, view, "ball")
fields.FieldArrays = ["slab"]
fields.FieldMaterialPresets = ["matte"]
one_ray = render("two_fields")
simple.Hide(both, view)

ball_source = make_source("(('ball', ball),)")
slab_source = make_source("(('slab', slab),)", lo=SLAB_LO, n=SLAB_N, step=SLAB_STEP)
mmv.show_multi_material(ball_source, view, "ball")
ball_alone = render("ball_alone")
mmv.show_multi_material(slab_source, view, "slab")
two_reps = render("two_representations")
simple.Hide(ball_source, view)
slab_alone = render("slab_alone")
simple.Hide(slab_source, view)

merged = simple.VolumesToFields(Input=[ball_source, slab_source])
merged_rep = mmv.show_multi_material(merged, view, "ball")
merged_rep.FieldArrays = ["slab"]
merged_rep.FieldMaterialPresets = ["matte"]
merged_ray = render("volumes_to_fields")
info = merged.GetDataInformation()
print("slab grid %s, spacing %.1f; merged grid %s"
      % ("x".join(map(str, SLAB_N)), SLAB_STEP,
         "x".join(str(info.GetExtent()[2 * a + 1] + 1) for a in range(3))))

print("two representations against two fields (one ray): PSNR %.1f dB"
      % mmv.psnr(two_reps, one_ray))
print("Volumes To Fields against two fields (one ray): PSNR %.1f dB"
      % mmv.psnr(merged_ray, one_ray))
print("two fields against the ball alone: PSNR %.1f dB" % mmv.psnr(one_ray, ball_alone))
print("two fields against the slab alone: PSNR %.1f dB" % mmv.psnr(one_ray, slab_alone))
print("images in %s" % args.out)
