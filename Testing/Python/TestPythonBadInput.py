"""Bad input from Python: wrong types raise TypeError, invalid values are
VTK errors with a failed return and an unchanged object, never a crash."""

import math
import unittest

import numpy
from vtkmodules.vtkCommonDataModel import vtkImageData, vtkPiecewiseFunction
from vtkmodules.vtkRenderingCore import vtkLight, vtkRenderer

import multimaterialvolume as m

import mmv_python_testing as mmv


class BadInputTest(unittest.TestCase):
    def test_wrong_types_raise(self):
        f = m.vtkMaterialTransferFunction()
        with self.assertRaises(TypeError):
            f.AddNode("ten", 0.1, 0.8, 0.2, 20.0, 1.0, 0.0, 0.0)
        with self.assertRaises(TypeError):
            f.AddNode(1.0)
        with self.assertRaises(TypeError):
            m.vtkMultiMaterialVolumeMapper().SetMaterialTransferFunction(m.vtkMaterialLibrary())
        with self.assertRaises(TypeError):
            m.vtkImageErrorMetrics().Compute("image", "image")

    def test_invalid_material_values_are_errors(self):
        f = m.vtkMaterialTransferFunction()
        errors = mmv.ErrorObserver(f)
        f.AddNode(0.0, 0.1, 0.8, 0.2, 20.0, 1.0, 0.0, 0.0)
        mtime = f.GetMTime()
        self.assertEqual(f.AddNode(5.0, 0.1, 0.8, 0.2, 20.0, -1.0, 0.0, 0.0), -1)
        self.assertEqual(f.AddNode(5.0, math.nan, 0.8, 0.2, 20.0, 1.0, 0.0, 0.0), -1)
        self.assertFalse(f.FromJSON("{not json"))
        self.assertFalse(f.ApplyPreset("no such preset", 0.0, 1.0))
        self.assertEqual(len(errors.take()), 4)
        self.assertEqual(f.GetSize(), 1)
        self.assertEqual(f.GetMTime(), mtime)
        self.assertFalse(f.GetNode(7, [0.0] * 13))

    def test_mismatched_images_are_errors(self):
        metrics = m.vtkImageErrorMetrics()
        errors = mmv.ErrorObserver(metrics)
        small = mmv.image_from_array(numpy.zeros((1, 4, 4, 3)))
        large = mmv.image_from_array(numpy.zeros((1, 8, 8, 3)))
        self.assertFalse(metrics.Compute(small, large))
        self.assertFalse(metrics.Compute(None, small))
        self.assertFalse(metrics.Compute(small, vtkImageData()))
        self.assertEqual(len(errors.take()), 3)
        self.assertTrue(math.isnan(metrics.GetRMSE()))

    def test_reference_renderer_rejects_invalid_input(self):
        reference = m.vtkMultiMaterialReferenceRenderer()
        errors = mmv.ErrorObserver(reference)
        self.assertIsNone(reference.Render(vtkRenderer(), 16, 16))  # no input
        reference.SetInputData(mmv.image_from_array(numpy.ones((4, 4, 4), dtype=numpy.float32)))
        self.assertIsNone(reference.Render(None, 16, 16))
        self.assertIsNone(reference.Render(vtkRenderer(), 0, 16))
        self.assertEqual(len(errors.take()), 3)

    def test_irradiance_filter_without_opacity_fails_cleanly(self):
        irradiance = m.vtkIrradianceVolumeFilter()
        errors = mmv.ErrorObserver(irradiance, irradiance.GetExecutive())
        irradiance.SetInputData(mmv.image_from_array(numpy.ones((4, 4, 4), dtype=numpy.float32)))
        light = vtkLight()
        light.SetPositional(False)
        irradiance.AddLight(light)
        self.assertEqual(irradiance.GetExecutive().Update(), 0)
        self.assertGreaterEqual(len(errors.take()), 1)
        self.assertIsNone(irradiance.GetOutput().GetPointData().GetArray("Irradiance_0"))

        irradiance.SetScalarOpacity(vtkPiecewiseFunction())
        irradiance.SetInputData(vtkImageData())  # no points, no scalars
        self.assertEqual(irradiance.GetExecutive().Update(), 0)
        self.assertGreaterEqual(len(errors.take()), 1)


if __name__ == "__main__":
    unittest.main()
