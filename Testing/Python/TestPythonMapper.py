"""vtkMultiMaterialVolumeMapper from Python: the GPU ray caster renders the
closed-form cube (light from the camera side: c/2 (1 - exp(-2 mu D))) in an
offscreen VTK window, as in TestMultiMaterialVolumeMapper.cxx. Needs an
OpenGL display (ctest runs under Xvfb)."""

import math
import unittest

from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkRenderingCore import vtkRenderWindow, vtkVolume, vtkWindowToImageFilter
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (OpenGL object factories)

import multimaterialvolume as m

import mmv_python_testing as mmv

SIZE = 64


class MapperTest(unittest.TestCase):
    def test_light_from_camera_side_matches_closed_form(self):
        scene = mmv.CubeScene(attenuation=1.0)
        scene.add_directional_light((scene.center[0], scene.center[1], 1000.0))
        mapper = m.vtkMultiMaterialVolumeMapper()
        mapper.SetInputData(scene.image)
        mapper.SetMaterialTransferFunction(scene.materials)
        mapper.AutoAdjustSampleDistancesOff()
        mapper.SetSampleDistance(0.25)
        mapper.SetIrradianceScale(1.0)
        volume = vtkVolume()
        volume.SetMapper(mapper)
        volume.SetProperty(scene.property)
        scene.renderer.AddVolume(volume)
        window = vtkRenderWindow()
        window.SetOffScreenRendering(1)
        window.SetSize(SIZE, SIZE)
        window.SetMultiSamples(0)
        window.AddRenderer(scene.renderer)
        window.Render()

        self.assertTrue(mapper.GetMultiMaterialActive())
        self.assertEqual(mapper.GetNumberOfShadedLights(), 1)
        grab = vtkWindowToImageFilter()
        grab.SetInput(window)
        grab.SetInputBufferTypeToRGB()
        grab.ReadFrontBufferOff()
        grab.Update()
        pixels = vtk_to_numpy(grab.GetOutput().GetPointData().GetScalars()).reshape(SIZE, SIZE, 3)
        centre = pixels[SIZE // 2, SIZE // 2]
        expected = 0.5 * (1.0 - math.exp(-2.0 * scene.MU * scene.depth))
        for c in range(3):
            target = scene.COLOR[c] * expected
            self.assertAlmostEqual(centre[c] / 255.0, target, delta=0.03 * target + 1.0 / 255,
                                   msg="channel %d" % c)
        window.Finalize()


if __name__ == "__main__":
    unittest.main()
