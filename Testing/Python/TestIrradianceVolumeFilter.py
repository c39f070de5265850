"""The Irradiance Volume filter from pvpython: Irradiance_0 (directional) and
Irradiance_1 (point light) exist, lie in [0, 1], and shadows show."""

from paraview import simple
from paraview import servermanager

import numpy
from vtkmodules.util.numpy_support import vtk_to_numpy

import mmv_testing as mmv

args = mmv.parse_args()
mmv.load_plugin(args)
checker = mmv.Checker()
errors = mmv.ErrorCapture()

wavelet = mmv.make_volume(extent=10)
irradiance = simple.IrradianceVolume(Input=wavelet)
irradiance.OpacityPoints = [37.0, 0.0, 160.0, 0.0, 200.0, 1.0, 277.0, 1.0]
irradiance.MaterialNodes = [37.0, 0.1, 0.8, 0.2, 20.0, 1.0, 0.0, 0.0,
                            277.0, 0.1, 0.8, 0.2, 20.0, 1.0, 0.0, 0.0]
irradiance.LightDirection = [0.0, 0.0, -1.0]
irradiance.UsePointLight = 1
irradiance.PointLightPosition = [0.0, -15.0, 0.0]
irradiance.IrradianceScale = 1.0
irradiance.UpdatePipeline()

data = servermanager.Fetch(irradiance)
checker.check(data.GetDimensions() == (21, 21, 21), "full resolution: %s" % (data.GetDimensions(),))
for name in ("Irradiance_0", "Irradiance_1"):
    array = data.GetPointData().GetArray(name)
    if not checker.check(array is not None, "%s exists" % name):
        continue
    values = vtk_to_numpy(array)
    checker.check(values.min() >= 0.0 and values.max() <= 1.0,
                  "%s in [0, 1]: [%.4f, %.4f]" % (name, values.min(), values.max()))

# Light from +z: the top of the blob is lit, its centre (opaque) is shadowed.
top = vtk_to_numpy(data.GetPointData().GetArray("Irradiance_0")).reshape(21, 21, 21)
checker.check(top[20, 10, 10] > 0.9, "unoccluded voxel at the top sees the light (%.3f)" % top[20, 10, 10])
checker.check(top[2, 10, 10] < top[20, 10, 10], "voxel under the blob is in shadow (%.3f)" % top[2, 10, 10])

# Settings reach the filter: a coarser grid, and no point light.
irradiance.IrradianceScale = 0.5
irradiance.UsePointLight = 0
irradiance.UpdatePipeline()
data = servermanager.Fetch(irradiance)
checker.check(data.GetDimensions()[0] < 21, "IrradianceScale 0.5 coarsens: %s" % (data.GetDimensions(),))
checker.check(data.GetPointData().GetArray("Irradiance_1") is None, "no point light: one array")

irradiance.MaterialNodes = [1.0, 2.0, 3.0]
checker.check("13 numbers per node" in errors.take_errors(), "bad MaterialNodes are reported")
checker.check(errors.take_errors() == "", "no other errors")
checker.finish()
