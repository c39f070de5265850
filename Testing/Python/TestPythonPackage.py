"""`import multimaterialvolume` gives the project's classes, from this build,
as VTK objects of the right types."""

import importlib
import os
import unittest

import multimaterialvolume as m
from vtkmodules.vtkCommonExecutionModel import vtkImageAlgorithm
from vtkmodules.vtkRenderingVolume import vtkGPUVolumeRayCastMapper

import mmv_python_testing as mmv

CLASSES = [
    "vtkMaterialTransferFunction",
    "vtkMaterialLibrary",
    "vtkMultiMaterialReferenceRenderer",
    "vtkMultiMaterialPathTracer",
    "vtkImageErrorMetrics",
    "vtkIrradianceVolumeFilter",
    "vtkMultiMaterialVolumeMapper",
]

# Every wrapped class, by the module (library) that holds it: the CPU module
# (Filters/, no OpenGL) and the OpenGL rendering module (Rendering/).
MODULE_CLASSES = {
    "vtkMultiMaterialVolumeFilters": [
        "vtkGlobalPrefilteredVolume",
        "vtkImageErrorMetrics",
        "vtkIrradianceVolumeFilter",
        "vtkMaterialLibrary",
        "vtkMaterialTransferFunction",
        "vtkMultiMaterialLiveObjects",
        "vtkMultiMaterialPathTracer",
        "vtkMultiMaterialReferenceRenderer",
        "vtkMultiMaterialVolumeScene",
        "vtkPreIntegrationTable",
    ],
    "vtkMultiMaterialVolume": [
        "vtkIrradianceComputeProgram",
        "vtkIrradianceEstimator",
        "vtkMultiMaterialShaderHook",
        "vtkMultiMaterialTextures",
        "vtkMultiMaterialVolumeMapper",
    ],
}


class PackageTest(unittest.TestCase):
    def test_package_comes_from_this_build(self):
        expected = mmv.expected_package_dir()
        self.assertIsNotNone(expected, "MMV_PYTHON_PACKAGE_DIR is not set")
        self.assertEqual(os.path.realpath(os.path.dirname(os.path.dirname(m.__file__))),
                         os.path.realpath(expected))

    def test_both_modules_wrap_all_their_classes(self):
        for module_name, names in MODULE_CLASSES.items():
            module = importlib.import_module("multimaterialvolume." + module_name)
            for name in names:
                with self.subTest(module=module_name, name=name):
                    self.assertTrue(hasattr(module, name))
                    self.assertIs(getattr(m, name), getattr(module, name))

    def test_every_class_constructs(self):
        for name in CLASSES:
            with self.subTest(name=name):
                cls = getattr(m, name)
                obj = cls()
                self.assertEqual(obj.GetClassName(), name)
                self.assertTrue(obj.IsA("vtkObject"))
                self.assertEqual(obj.GetReferenceCount(), 1)

    def test_classes_keep_their_vtk_bases(self):
        self.assertIsInstance(m.vtkIrradianceVolumeFilter(), vtkImageAlgorithm)
        self.assertIsInstance(m.vtkMultiMaterialVolumeMapper(), vtkGPUVolumeRayCastMapper)

    def test_objects_pass_between_classes(self):
        materials = m.vtkMaterialTransferFunction()
        mapper = m.vtkMultiMaterialVolumeMapper()
        mapper.SetMaterialTransferFunction(materials)
        self.assertIs(mapper.GetMaterialTransferFunction(), materials)
        irradiance = m.vtkIrradianceVolumeFilter()
        irradiance.SetMaterialTransferFunction(materials)
        self.assertIs(irradiance.GetMaterialTransferFunction(), materials)


if __name__ == "__main__":
    unittest.main()
