"""Several fields on one grid, in pvpython: a plate array and a floor array,
the plate coloured, the floor added with FieldArrays.
- FieldArrays gives the floor the colour map and opacity function ParaView
  keeps for its name (FieldLookupTables, FieldScalarOpacityFunctions);
- two fields render as the same scene made of one array with the same maps
  (PSNR >= 40 dB), and the plate's shadow on the floor matches it;
- two overlapping sources, the plate's box inside the floor's, merged by
  Volumes To Fields render as the two fields made on one grid;
- each field keeps its own colour map and material preset;
- an unknown array, too many arrays or an unknown preset give an error, and
  the coloured array is still drawn."""

import os

from paraview import simple

import mmv_testing as mmv

args = mmv.parse_args()
mmv.load_plugin(args)
checker = mmv.Checker()
errors = mmv.ErrorCapture()

SCRIPT = """
import numpy
from vtkmodules.util.numpy_support import numpy_to_vtk
n = 32
out = self.GetOutput()
out.SetDimensions(n, n, n)
out.SetOrigin(-15.5, -15.5, -15.5)
k, j, i = numpy.meshgrid(range(n), range(n), range(n), indexing='ij')
plate = ((k >= 19) & (k <= 22) & (i >= 9) & (i <= 22) & (j >= 9) & (j <= 22)).astype('f4')
floor = ((k >= 3) & (k <= 6) & (i >= 3) & (i <= 28) & (j >= 3) & (j <= 28)).astype('f4')
for name, values in (('plate', plate), ('floor', floor), ('both', plate + floor)):
    array = numpy_to_vtk(values.ravel(), deep=1)
    array.SetName(name)
    out.GetPointData().AddArray(array)
"""


def maps(name, rgb):
    """One colour for `name`, opacity from 0 at 0 to 0.5 at 1."""
    return mmv.set_uniform_maps(name, rgb, [(0.0, 0.0), (1.0, 0.5)])


simple._DisableFirstRenderCameraReset()
# Not named `source`: ParaView runs the source's script in this module's
# namespace, where it defines a function of that name.
arrays = simple.ProgrammableSource(OutputDataSetType="vtkImageData", Script=SCRIPT)
arrays.ScriptRequestInformation = (
    "executive = self.GetExecutive()\n"
    "info = executive.GetOutputInformation(0)\n"
    "info.Set(executive.WHOLE_EXTENT(), 0, 31, 0, 31, 0, 31)\n"
    "info.Set(self.GetOutput().ORIGIN(), -15.5, -15.5, -15.5)\n"
    "info.Set(self.GetOutput().SPACING(), 1.0, 1.0, 1.0)\n")
view = mmv.make_view()
view.OrientationAxesVisibility = 0
view.CameraPosition = [0.0, 0.0, 120.0]
view.CameraFocalPoint = [0.0, 0.0, 0.0]
view.CameraViewUp = [0.0, 1.0, 0.0]
view.CameraParallelProjection = 1
view.CameraParallelScale = 17.0
mmv.add_directional_light(view, [4.0, 2.0, 100.0])

# --- The same scene as one array ---------------------------------------------
maps("both", (1.0, 0.9, 0.8))
one = mmv.show_multi_material(arrays, view, "both")
single = mmv.render_image(view, os.path.join(args.temp_dir, "PVFieldsOne.png"))
checker.check(mmv.info(one, "NumberOfFields") == 1, "one array is one field")

# --- Two fields (the same display, coloured by the plate) ---------------------
maps("plate", (1.0, 0.9, 0.8))
maps("floor", (1.0, 0.9, 0.8))
two = one
simple.ColorBy(two, ("POINTS", "plate"))
two.FieldArrays = ["floor"]
tables = [t.GetXMLName() for t in two.FieldLookupTables]
checker.check(len(two.FieldLookupTables) == 1 and
              two.FieldLookupTables[0] == simple.GetColorTransferFunction("floor"),
              "FieldArrays gives the floor its own colour map (%s)" % tables)
checker.check(len(two.FieldScalarOpacityFunctions) == 1 and
              two.FieldScalarOpacityFunctions[0] == simple.GetOpacityTransferFunction("floor"),
              "FieldArrays gives the floor its own opacity function")
two.FieldMaterialPresets = ["matte"]
fields = mmv.render_image(view, os.path.join(args.temp_dir, "PVFieldsTwo.png"))
checker.check(mmv.info(two, "NumberOfFields") == 2, "plate and floor are two fields (%s)"
              % mmv.info(two, "NumberOfFields"))
checker.check(mmv.info(two, "MultiMaterialActive") == 1, "two fields are shaded with materials")
same = mmv.psnr(fields, single)
print("two fields against one array: %.1f dB" % same)
checker.check(same >= 40.0, "two fields render as one array with the same maps (%.1f dB)" % same)
checker.check(errors.take_errors() == "", "no error so far")

# --- Two overlapping sources merged into one image's fields -------------------
simple.Hide(arrays, view)
plate_box = simple.ExtractSubset(
    Input=simple.PassArrays(Input=arrays, PointDataArrays=["plate"]), VOI=[6, 25, 6, 25, 16, 25])
floor_box = simple.PassArrays(Input=arrays, PointDataArrays=["floor"])
merged = simple.VolumesToFields(Input=[plate_box, floor_box])
merged_rep = mmv.show_multi_material(merged, view, "plate")
merged_rep.FieldArrays = ["floor"]
merged_rep.FieldMaterialPresets = ["matte"]
merged_image = mmv.render_image(view, os.path.join(args.temp_dir, "PVFieldsMerged.png"))
extent = merged.GetDataInformation().GetExtent()
checker.check(list(extent) == [0, 31, 0, 31, 0, 31], "the merged grid is the floor's (%s)"
              % list(extent))
merged_psnr = mmv.psnr(merged_image, fields)
print("two sources merged against two fields on one grid: %.1f dB" % merged_psnr)
checker.check(merged_psnr >= 60.0,
              "merged sources render as the fields made on one grid (%.1f dB)" % merged_psnr)
simple.Hide(merged, view)
simple.Show(arrays, view)
checker.check(errors.take_errors() == "", "no error so far")

# --- Each field its own colour ------------------------------------------------
maps("plate", (1.0, 0.1, 0.1))
maps("floor", (0.1, 0.1, 1.0))
coloured = mmv.render_image(view, os.path.join(args.temp_dir, "PVFieldsColours.png"))
h, w, _ = coloured.shape
plate = coloured[h // 2, w // 2]
floor = coloured[int(h * 0.15), int(w * 0.15)]
print("plate pixel %s, floor pixel %s" % (plate, floor))
checker.check(plate[0] > 40 and plate[0] > 3 * plate[2], "the plate is red (%s)" % plate)
checker.check(floor[2] > 40 and floor[2] > 3 * floor[0], "the floor is blue (%s)" % floor)

# --- Bad input ------------------------------------------------------------------
two.FieldArrays = ["nothing"]
two.FieldLookupTables = [simple.GetColorTransferFunction("floor")]
two.FieldScalarOpacityFunctions = [simple.GetOpacityTransferFunction("floor")]
mmv.render_image(view, os.path.join(args.temp_dir, "PVFieldsMissing.png"))
text = errors.take_errors()
checker.check("nothing" in text or "field" in text, "a missing array is an error (%s)" % text)
checker.check(mmv.info(two, "NumberOfFields") == 1, "the plate is drawn alone")
checker.check(mmv.info(two, "MultiMaterialActive") == 1, "and shaded with materials")

two.FieldArrays = ["floor", "both", "plate", "both"]
mmv.render_image(view, os.path.join(args.temp_dir, "PVFieldsTooMany.png"))
text = errors.take_errors()
checker.check("at most 3" in text, "four field arrays: an error (%s)" % text)

two.FieldArrays = ["floor"]
two.FieldMaterialPresets = ["no such preset"]
mmv.render_image(view, os.path.join(args.temp_dir, "PVFieldsPreset.png"))
text = errors.take_errors()
checker.check("no such preset" in text, "an unknown preset is an error (%s)" % text)
checker.check(mmv.info(two, "NumberOfFields") == 2, "the floor is still drawn")
errors.take()
errors.close()
checker.finish()
