# Startup script of the progress GUI test (paraview --script=...): loads the
# plugin, shows the chest (progress_scene.py) and records what the session's
# progress handler, which ParaView's progress bar follows, reports. The XML
# test script then calls edit_and_render() and finish() from the Python shell;
# run_progress_test.py watches the screen meanwhile.
import builtins
import json
import os
import sys
import time

from paraview import servermanager, simple
from vtkmodules.vtkCommonCore import vtkCommand

sys.path.insert(0, os.path.dirname(os.environ["MMV_SCENE"]))
import progress_scene  # noqa: E402

simple.LoadPlugin(os.environ["MMV_PLUGIN"], remote=False, ns=globals())
OUT = os.environ["MMV_OUT"]
RESULTS = os.environ["MMV_RESULTS"]

view = simple.GetActiveViewOrCreate("RenderView")
display = progress_scene.show(progress_scene.volume_path(OUT), view)

handler = servermanager.ActiveConnection.Session.GetProgressHandler()
reports = []


def _on_progress(caller, event):
    reports.append((time.time(), caller.GetLastProgressText() or "", caller.GetLastProgress()))


handler.AddObserver(vtkCommand.ProgressEvent, _on_progress)


def _info(name):
    display.SMProxy.UpdatePropertyInformation()
    return display.GetProperty(name).GetData()


def _write(line):
    with open(RESULTS, "a") as f:
        f.write(line + "\n")


def edit_and_render():
    """The opacity edit and its still render, bracketed by EDIT_START and
    EDIT_END lines (the driver grabs the screen in between), then what the
    progress handler reported during it (one JSON line)."""
    updates = _info("IrradianceUpdateCount")
    del reports[:]
    _write("EDIT_START %.3f" % time.time())
    start = time.time()
    progress_scene.edit_opacity()
    simple.Render(view)
    seconds = time.time() - start
    _write("EDIT_END %.3f" % time.time())
    _write("REPORTS " + json.dumps({
        "render_seconds": seconds,
        "updates": _info("IrradianceUpdateCount") - updates,
        "irradiance_seconds": _info("LastIrradianceSeconds"),
        "stages": _info("LastIrradianceStages"),
        "reports": [(t - start, text, value) for t, text, value in reports]}))


def finish():
    """The image after the edit, at the reference's size, then FINAL."""
    simple.SaveScreenshot(os.path.join(OUT, "after-edit.png"), view,
                          ImageResolution=progress_scene.IMAGE_SIZE)
    _write("FINAL")


builtins.edit_and_render = edit_and_render
builtins.finish = finish
