"""The CPU numerics from Python against closed forms: image metrics of two
arrays, Beer-Lambert irradiance through a homogeneous slab
(vtkIrradianceVolumeFilter), and the ambient emission of a homogeneous cube
(vtkMultiMaterialReferenceRenderer)."""

import math
import unittest

import numpy
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction
from vtkmodules.vtkRenderingCore import vtkLight

import multimaterialvolume as m

import mmv_python_testing as mmv


class ImageErrorMetricsTest(unittest.TestCase):
    def test_known_rmse_and_psnr(self):
        y, x = numpy.mgrid[0:12, 0:16]
        reference = numpy.stack([(x + y) / 30.0, x / 16.0, y / 12.0], axis=-1)[numpy.newaxis]
        # +0.125 on even columns, -0.25 on odd ones: RMSE = sqrt((1/64 + 1/16) / 2).
        offset = numpy.where(x % 2 == 0, 0.125, -0.25)[numpy.newaxis, :, :, numpy.newaxis]
        test = reference + offset
        metrics = m.vtkImageErrorMetrics()
        self.assertTrue(metrics.Compute(mmv.image_from_array(test.astype(numpy.float32)),
                                        mmv.image_from_array(reference.astype(numpy.float32))))
        rmse = math.sqrt((0.125 ** 2 + 0.25 ** 2) / 2.0)
        self.assertAlmostEqual(metrics.GetRMSE(), rmse, delta=1e-7)
        self.assertAlmostEqual(metrics.GetPSNR(), 20.0 * math.log10(1.0 / rmse), delta=1e-5)
        self.assertAlmostEqual(metrics.GetMaximumError(), 0.25, delta=1e-7)
        self.assertEqual(metrics.GetPeakUsed(), 1.0)

        metrics.SetPeak(4.0)
        metrics.Compute(mmv.image_from_array(test), mmv.image_from_array(reference))
        self.assertAlmostEqual(metrics.GetPSNR(), 20.0 * math.log10(4.0 / rmse), places=9)

    def test_identical_images(self):
        # SSIM needs at least 11 x 11 pixels.
        image = mmv.image_from_array(numpy.linspace(0.0, 1.0, 432).reshape(1, 12, 12, 3))
        metrics = m.vtkImageErrorMetrics()
        self.assertTrue(metrics.Compute(image, image))
        self.assertEqual(metrics.GetRMSE(), 0.0)
        self.assertEqual(metrics.GetPSNR(), math.inf)
        self.assertAlmostEqual(metrics.GetSSIM(), 1.0, places=12)


class IrradianceVolumeFilterTest(unittest.TestCase):
    def test_homogeneous_slab_is_beer_lambert(self):
        # Opacity alpha per unit distance u and attenuation c_t give the
        # extinction sigma = c_t * -ln(1 - alpha) / u; a light along +x makes
        # the irradiance exp(-sigma * (x_max - x)).
        alpha, u, attenuation, spacing = 0.3, 2.0, 1.5, 0.5
        dims = (12, 6, 5)
        image = mmv.image_from_array(numpy.ones(dims[::-1], dtype=numpy.float32),
                                     spacing=(spacing,) * 3)
        opacity = vtkPiecewiseFunction()
        opacity.AddPoint(0.0, alpha)
        opacity.AddPoint(2.0, alpha)
        materials = m.vtkMaterialTransferFunction()
        materials.AddNode(1.0, 0.2, 0.7, 0.2, 20.0, attenuation, 0.0, 0.0)
        light = vtkLight()
        light.SetPositional(False)
        light.SetFocalPoint(0.0, 0.0, 0.0)
        light.SetPosition(1.0, 0.0, 0.0)

        irradiance = m.vtkIrradianceVolumeFilter()
        irradiance.SetInputData(image)
        irradiance.SetScalarOpacity(opacity)
        irradiance.SetScalarOpacityUnitDistance(u)
        irradiance.SetMaterialTransferFunction(materials)
        irradiance.SetIrradianceScale(1.0)
        irradiance.SetShadowEstimation(0)  # full shadow rays
        irradiance.AddLight(light)
        irradiance.Update()

        output = irradiance.GetOutput()
        self.assertEqual(output.GetDimensions(), dims)
        values = vtk_to_numpy(output.GetPointData().GetArray("Irradiance_0")).reshape(dims[::-1])
        sigma = attenuation * -math.log(1.0 - alpha) / u
        x = numpy.arange(dims[0]) * spacing
        expected = numpy.exp(-sigma * (x[-1] - x))
        error = numpy.abs(values - expected[numpy.newaxis, numpy.newaxis, :]) / expected
        self.assertLess(error.max(), 1e-3)
        self.assertLess(values.min(), 0.25)  # the slab really shadows: exp(-sigma 5.5) = 0.23
        self.assertEqual(values.max(), 1.0)  # the face toward the light
        self.assertEqual(irradiance.GetNumberOfComputedVoxels(), output.GetNumberOfPoints())


class ReferenceRendererTest(unittest.TestCase):
    PIXELS = 16

    def render(self, scene):
        """Unclamped radiance of the scene, indexed [row, column, channel]."""
        reference = m.vtkMultiMaterialReferenceRenderer()
        reference.SetInputData(scene.image)
        reference.SetVolumeProperty(scene.property)
        reference.SetMaterialTransferFunction(scene.materials)
        output = reference.Render(scene.renderer, self.PIXELS, self.PIXELS)
        self.assertIsNotNone(output)
        self.assertEqual(output.GetDimensions(), (self.PIXELS, self.PIXELS, 1))
        radiance = vtk_to_numpy(output.GetPointData().GetArray("Radiance"))
        return radiance.reshape(self.PIXELS, self.PIXELS, 3)

    def test_ambient_only_cube_without_lights(self):
        # No light: each ray through the cube gathers the ambient emission
        # c * (1 - exp(-mu D)).
        scene = mmv.CubeScene()
        radiance = self.render(scene)
        expected = numpy.array(scene.COLOR) * (1.0 - math.exp(-scene.MU * scene.depth))
        numpy.testing.assert_allclose(radiance[self.PIXELS // 2, self.PIXELS // 2], expected, rtol=0.005)
        # The corners miss the cube: black background.
        self.assertEqual(radiance[0, 0].tolist(), [0.0, 0.0, 0.0])

    def test_light_from_behind(self):
        # A light behind the cube (attenuation 1): c * mu D exp(-mu D).
        scene = mmv.CubeScene()
        scene.add_directional_light((scene.center[0], scene.center[1], -1000.0))
        radiance = self.render(scene)
        mu_d = scene.MU * scene.depth
        numpy.testing.assert_allclose(radiance[self.PIXELS // 2, self.PIXELS // 2],
                                      numpy.array(scene.COLOR) * mu_d * math.exp(-mu_d), rtol=0.005)


if __name__ == "__main__":
    unittest.main()
