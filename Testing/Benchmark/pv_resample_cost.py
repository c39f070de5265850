"""Cost of resampling an unstructured grid in the Multi-Material Volume
representation: a tetrahedralized Wavelet (--extent E: (2E)^3 hexahedra, 5
tetrahedra each) shown with the default SamplingDimensions. Prints the
representation's ResampleInfo (cells, points, seconds) and the process's
peak resident memory before and after the first render.

    scripts/pvpython Testing/Benchmark/pv_resample_cost.py --extent 20
"""

import argparse
import resource

from paraview import simple

parser = argparse.ArgumentParser()
parser.add_argument("--extent", type=int, default=20)
parser.add_argument("--dims", type=int, nargs=3, default=None)
options = parser.parse_known_args()[0]


def peak_mb():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


e = options.extent
wavelet = simple.Wavelet(WholeExtent=[-e, e, -e, e, -e, e])
grid = simple.Tetrahedralize(Input=wavelet)
grid.UpdatePipeline()
before = peak_mb()
view = simple.CreateRenderView()
view.ViewSize = [400, 400]
rep = simple.Show(grid, view)
rep.Representation = "Multi-Material Volume"
simple.ColorBy(rep, ("POINTS", "RTData"))
if options.dims:
    rep.SamplingDimensions = options.dims
print("SamplingDimensions: %s" % list(rep.SamplingDimensions))
simple.Render(view)
rep.UpdatePropertyInformation()
print("ResampleInfo: %s" % rep.GetProperty("ResampleInfo").GetData())
print("MultiMaterialActive: %s" % rep.GetProperty("MultiMaterialActive").GetData())
print("peak resident memory: %.0f MB with the grid, %.0f MB after resampling and the "
      "first render" % (before, peak_mb()))
