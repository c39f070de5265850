"""Shared pieces of the tests of the `multimaterialvolume` Python package.
They run in pvpython and in a plain Python that has ParaView's `vtkmodules`,
so nothing here imports `paraview`."""

import os

import numpy
from vtkmodules.util.misc import calldata_type
from vtkmodules.util.numpy_support import numpy_to_vtk
from vtkmodules.util.vtkConstants import VTK_STRING
from vtkmodules.vtkCommonDataModel import vtkImageData


def expected_package_dir():
    """The build tree's package directory, from MMV_PYTHON_PACKAGE_DIR (set by
    ctest), so that a test never passes on a stale installed copy."""
    return os.environ.get("MMV_PYTHON_PACKAGE_DIR")


class ErrorObserver(object):
    """Collects the vtkErrorMacro messages of the observed objects (observed
    errors are not printed)."""

    def __init__(self, *objects):
        self.messages = []
        for obj in objects:
            obj.AddObserver("ErrorEvent", self.on_error)

    @calldata_type(VTK_STRING)
    def on_error(self, obj, event, message):
        self.messages.append(message)

    def take(self):
        messages, self.messages = self.messages, []
        return messages


def image_from_array(values, name="scalars", spacing=(1.0, 1.0, 1.0)):
    """vtkImageData whose point scalars are `values`, indexed [z, y, x] or
    [z, y, x, component]."""
    values = numpy.ascontiguousarray(values)
    dims = values.shape[:3][::-1]
    components = values.shape[3] if values.ndim == 4 else 1
    image = vtkImageData()
    image.SetDimensions(*dims)
    image.SetSpacing(*spacing)
    array = numpy_to_vtk(values.reshape(-1, components), deep=True)
    array.SetName(name)
    image.GetPointData().SetScalars(array)
    return image


class CubeScene(object):
    """The closed-form scene of the C++ mapper and reference tests: a
    homogeneous cube of `size` points a side (side D = size - 1, spacing 1),
    extinction MU per unit length, colour COLOR, ambient-only material
    (ka = 1) with the given attenuation, and a renderer without automatic
    lights whose parallel camera looks down -z at the cube's centre."""

    MU = 0.05
    COLOR = (1.0, 0.6, 0.3)

    def __init__(self, attenuation=1.0, size=33):
        import math
        import multimaterialvolume as m
        from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction
        from vtkmodules.vtkRenderingCore import vtkColorTransferFunction, vtkRenderer, vtkVolumeProperty

        self.depth = size - 1.0
        self.image = image_from_array(numpy.ones((size, size, size), dtype=numpy.float32))
        colors = vtkColorTransferFunction()
        opacity = vtkPiecewiseFunction()
        for value in (0.0, 2.0):
            colors.AddRGBPoint(value, *self.COLOR)
            opacity.AddPoint(value, 1.0 - math.exp(-self.MU))  # unit distance 1
        self.property = vtkVolumeProperty()
        self.property.SetColor(colors)
        self.property.SetScalarOpacity(opacity)
        self.property.SetScalarOpacityUnitDistance(1.0)
        self.property.SetInterpolationTypeToLinear()
        self.materials = m.vtkMaterialTransferFunction()
        self.materials.AddNode(1.0, 1.0, 0.0, 0.0, 1.0, attenuation, 0.0, 0.0)

        self.renderer = vtkRenderer()
        self.renderer.AutomaticLightCreationOff()
        self.renderer.SetBackground(0.0, 0.0, 0.0)
        self.center = (self.depth / 2.0,) * 3
        camera = self.renderer.GetActiveCamera()
        camera.ParallelProjectionOn()
        camera.SetFocalPoint(*self.center)
        camera.SetPosition(self.center[0], self.center[1], self.center[2] + 10.0 * size)
        camera.SetViewUp(0.0, 1.0, 0.0)
        camera.SetParallelScale(0.75 * self.depth)
        self.renderer.ResetCameraClippingRange(self.image.GetBounds())

    def add_directional_light(self, from_point):
        """A white directional light of intensity 1 from `from_point` toward
        the cube's centre."""
        from vtkmodules.vtkRenderingCore import vtkLight
        light = vtkLight()
        light.SetLightTypeToSceneLight()
        light.PositionalOff()
        light.SetPosition(*from_point)
        light.SetFocalPoint(*self.center)
        light.SetColor(1.0, 1.0, 1.0)
        light.SetIntensity(1.0)
        self.renderer.AddLight(light)
        return light
