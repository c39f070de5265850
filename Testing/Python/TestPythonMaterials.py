"""vtkMaterialTransferFunction and vtkMaterialLibrary from Python: nodes read
back as set, linear interpolation between nodes and clamping outside them,
presets applied exactly, JSON round trip."""

import unittest

import multimaterialvolume as m

# value, ka, kd, ks, shininess, attenuation, scattering, reflection, anisotropy,
# emission, transmission r, g, b
LOW = [10.0, 0.1, 0.8, 0.2, 20.0, 1.0, 0.5, 0.3, 0.2, 0.0, 1.0, 1.0, 1.0]
HIGH = [30.0, 0.3, 0.4, 0.6, 40.0, 2.0, 1.5, 0.1, -0.2, 2.5, 0.9, 0.5, 0.25]


class MaterialTransferFunctionTest(unittest.TestCase):
    def setUp(self):
        self.f = m.vtkMaterialTransferFunction()
        self.assertEqual(self.f.AddNode(*HIGH), 0)
        # The 10-number AddNode (before the transmission colour) makes a grey node.
        self.assertEqual(self.f.AddNode(*LOW[:10]), 0)  # index in value order

    def test_nodes_read_back_as_set(self):
        self.assertEqual(self.f.GetSize(), 2)
        for index, expected in enumerate((LOW, HIGH)):
            node = [0.0] * 13
            self.assertTrue(self.f.GetNode(index, node))
            self.assertEqual(node, expected)
        value_range = [0.0, 0.0]
        self.f.GetRange(value_range)
        self.assertEqual(value_range, [10.0, 30.0])

    def test_evaluate_interpolates_linearly_and_clamps(self):
        for value, weight in ((10.0, 0.0), (15.0, 0.25), (20.0, 0.5), (30.0, 1.0)):
            parameters = [0.0] * 12
            self.f.Evaluate(value, parameters)
            for p in range(12):
                expected = (1.0 - weight) * LOW[p + 1] + weight * HIGH[p + 1]
                self.assertAlmostEqual(parameters[p], expected, places=12,
                                       msg="value %g parameter %d" % (value, p))
                self.assertAlmostEqual(self.f.EvaluateParameter(value, p), expected, places=12)
        below, above = [0.0] * 12, [0.0] * 12
        self.f.Evaluate(-100.0, below)
        self.f.Evaluate(1000.0, above)
        self.assertEqual(below, LOW[1:])
        self.assertEqual(above, HIGH[1:])

    def test_json_round_trip(self):
        copy = m.vtkMaterialTransferFunction()
        self.assertTrue(copy.FromJSON(self.f.ToJSON()))
        self.assertEqual(copy.GetSize(), 2)
        node = [0.0] * 13
        copy.GetNode(1, node)
        self.assertEqual(node, HIGH)

    def test_remove_node(self):
        self.assertEqual(self.f.RemoveNode(10.0), 0)
        self.assertEqual(self.f.GetSize(), 1)
        self.f.RemoveAllNodes()
        self.assertEqual(self.f.GetSize(), 0)


class MaterialLibraryTest(unittest.TestCase):
    def test_presets_apply_exactly(self):
        library = m.vtkMaterialLibrary()
        self.assertGreater(library.GetNumberOfPresets(), 0)
        names = [library.GetPresetName(i) for i in range(library.GetNumberOfPresets())]
        f = m.vtkMaterialTransferFunction()
        for name in names:
            with self.subTest(preset=name):
                self.assertTrue(library.HasPreset(name))
                preset = [0.0] * 12
                self.assertTrue(library.GetPreset(name, preset))
                self.assertTrue(f.ApplyPreset(name, 0.0, 100.0))
                for value in (0.0, 37.5, 100.0):
                    parameters = [0.0] * 12
                    f.Evaluate(value, parameters)
                    self.assertEqual(parameters, preset)

    def test_added_preset_reads_back(self):
        library = m.vtkMaterialLibrary()
        count = library.GetNumberOfPresets()
        parameters = [0.2, 0.6, 0.3, 12.0, 1.25, 0.5, 0.05, 0.1, 1.5, 0.5, 0.75, 1.0]
        self.assertTrue(library.AddPreset("python test", parameters, [0.25, 0.5, 0.75]))
        self.assertEqual(library.GetNumberOfPresets(), count + 1)
        preset, rgb = [0.0] * 12, [0.0] * 3
        self.assertTrue(library.GetPreset("python test", preset))
        self.assertTrue(library.GetPresetColor("python test", rgb))
        self.assertEqual(preset, parameters)
        self.assertEqual(rgb, [0.25, 0.5, 0.75])
        self.assertTrue(library.RemovePreset("python test"))
        self.assertFalse(library.HasPreset("python test"))


class PhysicalMediumNodeTest(unittest.TestCase):
    """physical_medium_node: the MaterialNodes numbers of a known medium."""

    def test_node_is_the_library_preset_of_the_same_medium(self):
        # The `tissue` preset is the mapping of albedo 0.9, g 0.8, extinction
        # 0.25 per voxel (Filters/vtkMultiMaterialPhysicalMedium.h), stored
        # with 6 significant digits.
        node = m.physical_medium_node(600.0, 0.9, 0.8, 0.25)
        self.assertEqual(len(node), 13)
        self.assertEqual(node[0], 600.0)
        preset = [0.0] * 12
        self.assertTrue(m.vtkMaterialLibrary().GetPreset("tissue", preset))
        for p in range(12):
            self.assertAlmostEqual(node[p + 1], preset[p], delta=1e-5 * abs(preset[p]) + 1e-12,
                                   msg="parameter %d" % p)

    def test_nodes_load_as_material_nodes(self):
        nodes = m.physical_medium_node(600.0, 0.9, 0.8, 0.25) + \
            m.physical_medium_node(1300.0, 0.3, 0.6, 0.5)
        f = m.vtkMaterialTransferFunction()
        self.assertTrue(f.SetNodes(len(nodes), nodes))
        self.assertEqual(f.GetSize(), 2)
        self.assertEqual(f.EvaluateParameter(1300.0, 7), 0.6)  # anisotropy g

    def test_outside_the_domain_raises_with_the_reason(self):
        for albedo, g, extinction, word in ((1.0, 0.0, 0.25, "albedo"),
                                            (0.5, -0.3, 0.25, "anisotropy"),
                                            (0.5, 0.3, 0.0, "extinction"),
                                            (0.5, 0.3, float("nan"), "extinction")):
            with self.subTest(albedo=albedo, g=g, extinction=extinction):
                with self.assertRaises(ValueError) as raised:
                    m.physical_medium_node(600.0, albedo, g, extinction)
                self.assertIn(word, str(raised.exception))


if __name__ == "__main__":
    unittest.main()
