"""Creates, shows, renders and deletes 'Multi-Material Volume' representations
in a loop in pvpython. After every round the live instances of the project's
classes (multimaterialvolume.vtkMultiMaterialLiveObjects: representation,
mapper, render pass, tables, irradiance cache) and the proxies registered
with the proxy manager must be back where they were. Run through
scripts/pvpython, which puts the plugin and the package on the path."""

import gc

from paraview import servermanager, simple

import multimaterialvolume as m

import mmv_testing as mmv

LIVE = m.vtkMultiMaterialLiveObjects
CLASSES = ("vtkPVMultiMaterialVolumeRepresentation", "vtkMultiMaterialVolumeMapper",
           "vtkMultiMaterialShaderHook", "vtkPreIntegrationTable", "vtkIrradianceInputCache")
GROUPS = ("sources", "representations", "lookup_tables", "piecewise_functions", "views")
ROUNDS = 4


def census():
    """Live counted objects per class, and registered proxies per group."""
    gc.collect()
    pxm = servermanager.ProxyManager().SMProxyManager
    counts = {name: LIVE.GetCount(name) for name in CLASSES}
    counts["all counted"] = LIVE.GetCount()
    for group in GROUPS:
        counts["proxies in " + group] = pxm.GetNumberOfProxies(group)
    return counts


def differences(now, before):
    return {k: (before[k], now[k]) for k in before if now[k] != before[k]}


def one_round(view, keep=None):
    """Shows a new volume, renders it with materials and deletes it; `keep`
    (a list) receives the representation when the caller wants to leak it."""
    source = mmv.make_volume(extent=7)
    rep = mmv.show_volume(source, view, preset="bone")
    simple.Render(view)
    active = mmv.info(rep, "MultiMaterialActive") == 1
    if keep is not None:
        keep.append(rep.SMProxy)
    simple.Delete(source)
    del rep, source
    simple.Render(view)
    return active


checker = mmv.Checker()
errors = mmv.ErrorCapture()
view = mmv.make_view()
# The first round also makes what lives on by design (the view's colour map
# and opacity function for the array): count from after it.
checker.check(one_round(view), "warm-up round shades with materials")
start = census()
print("start: %s" % start)
checker.check(start["vtkPVMultiMaterialVolumeRepresentation"] == 0 and
              start["vtkMultiMaterialVolumeMapper"] == 0,
              "no representation or mapper alive after the warm-up round is deleted")
for r in range(ROUNDS):
    active = one_round(view)
    now = census()
    print("round %d: %s" % (r, now))
    checker.check(active, "round %d shades with materials" % r)
    checker.check(now == start, "round %d returns to the start: %s" % (r, differences(now, start)))

# The census sees a leak: a representation proxy kept by Python keeps its
# representation, mapper, pass, tables and cache alive; letting go frees them.
kept = []
one_round(view, keep=kept)
leaked = census()
print("one representation kept: %s" % leaked)
checker.check(leaked["vtkPVMultiMaterialVolumeRepresentation"] == 1 and
              leaked["vtkMultiMaterialVolumeMapper"] == 1 and
              leaked["vtkMultiMaterialShaderHook"] == 1,
              "the census sees the kept representation: %s" % differences(leaked, start))
del kept[:]
released = census()
checker.check(released == start, "letting it go returns to the start: %s"
              % differences(released, start))
log = errors.take_errors()
checker.check(log == "", "no VTK errors: %r" % log[:500])
simple.Delete(view)
checker.finish()
