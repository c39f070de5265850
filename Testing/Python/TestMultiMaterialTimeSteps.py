"""A series played twice with ParaView's animation caching (the view's
UseCache and CacheKey, as the animation scene sets them): the second loop is
lit from the kept irradiance (IrradianceCacheHitCount), with no update and
the same images; without caching every step is new data and recomputes. The
animation scene's own loops keep their steps through a render between them."""

import os

from paraview import simple
from vtkmodules.vtkIOXML import vtkXMLImageDataWriter
from vtkmodules.vtkImagingCore import vtkRTAnalyticSource

import mmv_testing as mmv

args = mmv.parse_args()
mmv.load_plugin(args)
checker = mmv.Checker()
errors = mmv.ErrorCapture()

# Three steps on one grid: the Wavelet with its maximum moved.
paths = []
for k in range(3):
    source = vtkRTAnalyticSource()
    source.SetWholeExtent(-15, 15, -15, 15, -15, 15)
    source.SetCenter(3.0 * k, 0.0, 0.0)
    writer = vtkXMLImageDataWriter()
    writer.SetInputConnection(source.GetOutputPort())
    paths.append(os.path.join(args.temp_dir, "mmv_step_%d.vti" % k))
    writer.SetFileName(paths[-1])
    writer.Write()
reader = simple.XMLImageDataReader(FileName=paths)
reader.UpdatePipelineInformation()
times = list(reader.TimestepValues)
checker.check(len(times) == 3, "three time steps (%s)" % times)

view = mmv.make_view()
rep = mmv.show_volume(reader, view)
# A colour range that grows with the steps would re-spread the preset's
# materials, and a step lit under other materials is rightly not reused.
simple.GetColorTransferFunction("RTData").AutomaticRescaleRangeMode = "Never"
checker.check(rep.IrradianceCacheMB == 1024.0, "IrradianceCacheMB defaults to 1024")


# pvpython resets the camera at a view's first render; the light kit
# follows the camera, so the loops start after it.
simple.Render(view)


def play(use_cache, tag):
    """One loop through the series: each step's image path."""
    images = []
    for t in times:
        view.UseCache = use_cache
        view.CacheKey = t
        view.ViewTime = t
        images.append(mmv.render_image(view, os.path.join(args.temp_dir, "%s_%g.png" % (tag, t))))
    return images


first = play(1, "first")
updates = mmv.info(rep, "IrradianceUpdateCount")
checker.check(updates >= 3, "the first loop updates every step (%d updates)" % updates)
checker.check(mmv.info(rep, "IrradianceCacheHitCount") == 0, "no copies in the first loop")
second = play(1, "second")
hits = mmv.info(rep, "IrradianceCacheHitCount")
checker.check(hits == 3, "the second loop is lit by copies (%d of 3)" % hits)
checker.check(mmv.info(rep, "IrradianceUpdateCount") == updates,
              "no update in the second loop (%d -> %d)" % (updates, mmv.info(rep, "IrradianceUpdateCount")))
for k in range(3):
    difference = mmv.mean_difference(first[k], second[k])
    checker.check(difference == 0.0, "step %d: the same image (mean difference %g)" % (k, difference))
    checker.check(mmv.check_not_blank(first[k], "step %d" % k), "step %d is drawn" % k)

# Without caching the reader delivers new arrays: no copy can serve them.
play(0, "uncached")
checker.check(mmv.info(rep, "IrradianceCacheHitCount") == hits, "no copies without caching")
checker.check(mmv.info(rep, "IrradianceUpdateCount") > updates, "without caching the steps update")

# As the animation scene plays the series with Cache Geometry For Animation
# on, in a view of its own: the scene turns the view's cache on for its own
# frames only, and a render between two loops (a screenshot, the GUI's
# repaint) keeps the kept steps.
simple.Delete(rep)
simple.Delete(view)
settings = simple.GetSettingsProxy("GeneralSettings")
settings.CacheGeometryForAnimation = 1
played_reader = simple.XMLImageDataReader(FileName=paths)
view = mmv.make_view()
rep = mmv.show_volume(played_reader, view)
scene = simple.GetAnimationScene()
scene.UpdateAnimationUsingDataTimeSteps()
scene.Play()
simple.Render(view)
hits = mmv.info(rep, "IrradianceCacheHitCount")
updates = mmv.info(rep, "IrradianceUpdateCount")
scene.Play()
played = mmv.info(rep, "IrradianceCacheHitCount") - hits
checker.check(played == 3, "the scene's second loop is lit by copies (%d of 3)" % played)
checker.check(mmv.info(rep, "IrradianceUpdateCount") == updates,
              "no update in the scene's second loop (%d -> %d)" % (
                  updates, mmv.info(rep, "IrradianceUpdateCount")))
settings.CacheGeometryForAnimation = 0

reported = errors.take_errors()
checker.check(reported == "", "no VTK error (%r)" % reported)
checker.finish()
