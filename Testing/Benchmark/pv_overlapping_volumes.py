"""How ParaView composites two Multi-Material Volume representations whose
boxes overlap, against the same data as one volume with two fields
(FieldArrays), which integrates both along one ray: a red ball and a blue
slab through it on one 48^3 grid, one directional light. Prints the PSNR of
the two representations against the two fields, and of each against the
ball or the slab alone (how much the other adds), and writes the images.

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
parser.add_argument("--plugin", default=os.path.join(
    HERE, "..", "..", "build", "lib", "paraview-plugins", "MultiMaterialVolume",
    "MultiMaterialVolume.so"))
args = parser.parse_args()
os.makedirs(args.out, exist_ok=True)
simple.LoadPlugin(args.plugin, remote=True)

N = 48
SCRIPT = """
import numpy
from vtkmodules.util.numpy_support import numpy_to_vtk
n = %d
out = self.GetOutput()
out.SetDimensions(n, n, n)
out.SetOrigin(-(n - 1) / 2.0, -(n - 1) / 2.0, -(n - 1) / 2.0)
k, j, i = numpy.meshgrid(range(n), range(n), range(n), indexing='ij')
c = (n - 1) / 2.0
ball = numpy.clip(1.0 - numpy.sqrt((i - c) ** 2 + (j - c) ** 2 + (k - c) ** 2) / 14.0, 0, 1)
slab = ((abs(k - c - 2) <= 3) & (abs(i - c) <= 20) & (abs(j - c) <= 20)).astype('f4')
for name, values in %s:
    array = numpy_to_vtk(values.astype('f4').ravel(), deep=1)
    array.SetName(name)
    out.GetPointData().AddArray(array)
"""


def make_source(arrays):
    source = simple.ProgrammableSource(OutputDataSetType="vtkImageData",
                                       Script=SCRIPT % (N, arrays))
    source.ScriptRequestInformation = (
        "executive = self.GetExecutive()\n"
        "executive.GetOutputInformation(0).Set(executive.WHOLE_EXTENT(), 0, %d, 0, %d, 0, %d)\n"
        % (N - 1, N - 1, N - 1))
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

both = make_source("(('ball', ball), ('slab', slab))")
fields = mmv.show_multi_material(both, view, "ball")
fields.FieldArrays = ["slab"]
fields.FieldMaterialPresets = ["matte"]
one_ray = render("two_fields")
simple.Hide(both, view)

ball_source = make_source("(('ball', ball),)")
slab_source = make_source("(('slab', slab),)")
mmv.show_multi_material(ball_source, view, "ball")
ball_alone = render("ball_alone")
mmv.show_multi_material(slab_source, view, "slab")
two_reps = render("two_representations")
simple.Hide(ball_source, view)
slab_alone = render("slab_alone")

print("two representations against two fields (one ray): PSNR %.1f dB"
      % mmv.psnr(two_reps, one_ray))
print("two fields against the ball alone: PSNR %.1f dB" % mmv.psnr(one_ray, ball_alone))
print("two fields against the slab alone: PSNR %.1f dB" % mmv.psnr(one_ray, slab_alone))
print("images in %s" % args.out)
