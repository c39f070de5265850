"""An irradiance update reports VTK progress (issue 12: applying a preset or
adding a light froze ParaView for 14-16 s on llvmpipe with no feedback).

The mapper reports ProgressEvent 0 when an update starts and 1 when it ends,
with the text "Irradiance volume", and the representation forwards them
(its own pipeline progress, also 0 and 1, has no text: those are told apart
by the text); a frame that reuses the irradiance reports nothing. ParaView's
progress bar follows the session's progress handler, so they must reach it
too."""

from paraview import servermanager, simple
from vtkmodules.vtkCommonCore import vtkCommand

import mmv_testing as mmv

args = mmv.parse_args()
mmv.load_plugin(args)
checker = mmv.Checker()
errors = mmv.ErrorCapture()

view = mmv.make_view()
rep = mmv.show_volume(mmv.make_volume(), view, preset="bone")
# The Multi-Material Volume sub-representation (rep is ParaView's composite;
# Python sees it as its wrapped base class, vtkImageVolumeRepresentation).
representation = rep.GetClientSideObject().GetActiveRepresentation()
events = []


def on_progress(caller, event):
    if caller.GetProgressText():
        events.append((round(caller.GetProgress(), 6), caller.GetProgressText()))


representation.AddObserver(vtkCommand.ProgressEvent, on_progress)
handler = servermanager.ActiveConnection.Session.GetProgressHandler()
handler_events = []
handler.AddObserver(vtkCommand.ProgressEvent,
                    lambda caller, event: handler_events.append(caller.GetLastProgressText()))


def render(what):
    del events[:]
    del handler_events[:]
    before = mmv.info(rep, "IrradianceUpdateCount")
    simple.Render(view)
    updates = mmv.info(rep, "IrradianceUpdateCount") - before
    print("%s: %d irradiance update(s), representation progress %s, handler %s"
          % (what, updates, events, handler_events))
    return updates


START_END = [(0.0, "Irradiance volume"), (1.0, "Irradiance volume")]
updates = render("first frame")
checker.check(updates >= 1, "the first frame computes the irradiance (%d updates)" % updates)
checker.check(events == START_END * updates,
              "each update's start and end are reported as progress 0 and 1: %s" % events)
checker.check(any(text and "Irradiance volume" in text for text in handler_events),
              "the session's progress handler (ParaView's progress bar) receives them: %s"
              % handler_events)

updates = render("same frame again")
checker.check(updates == 0 and events == [] and handler_events == [],
              "a frame that reuses the irradiance reports no progress (%d updates, %s)"
              % (updates, events))

light = simple.AddLight(view=view)
light.Coords = "Scene"
light.Position = [40.0, 40.0, 40.0]
updates = render("a light added")
checker.check(updates == 1 and events == START_END,
              "adding a light updates the irradiance with progress 0 .. 1 (%d updates, %s)"
              % (updates, events))
checker.check("Irradiance volume" in handler_events,
              "and the progress handler receives it: %s" % handler_events)

log = errors.take_errors()
checker.check(log == "", "no VTK errors: %r" % log[:500])
checker.finish()
