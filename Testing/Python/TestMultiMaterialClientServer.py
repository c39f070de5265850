"""Client/server: the information properties report the process that
renders. Connected to a pvserver (started by run_client_server.py, which
passes --server-port) with remote rendering on, the client's copy of the
representation never renders, so its counters are 0; the values read must
be the server's: a nonzero
IrradianceUpdateCount and RayCastCount, MultiMaterialActive 1, and they
grow with further renders.

With --ranks N > 1 (a parallel pvserver, mpiexec -np N) every rank renders
its piece and the client reads one value per number, the largest over the
ranks (vtkPVMultiMaterialInformation): the counts equal those of one rank,
which renders every frame as the serial server does. So they must equal the
serial run's (written to --counts by the serial variant, read by the
parallel one); a sum over the ranks would be N times larger."""

import argparse
import json
import os

from paraview import simple

import mmv_testing as mmv

parser = argparse.ArgumentParser()
parser.add_argument("--server-port", type=int, required=True)
parser.add_argument("--ranks", type=int, default=1)
known, _ = parser.parse_known_args()
args = mmv.parse_args()

simple.Connect("localhost", known.server_port)
checker = mmv.Checker()
connection = simple.servermanager.ActiveConnection
checker.check(connection.IsRemote(), "connected to a pvserver")
checker.check(connection.GetNumberOfDataPartitions() == known.ranks,
              "the server has %d rank(s) (expected %d)"
              % (connection.GetNumberOfDataPartitions(), known.ranks))
counts_file = os.path.join(args.temp_dir, "client_server_counts.json")
counts = {}
mmv.load_plugin(args)  # on the client and, remote=True, on the server

# The server renders (remote rendering for any data size): the client's
# copy of the representation then draws nothing and counts nothing.
simple.GetSettingsProxy("RenderViewSettings").RemoteRenderThreshold = 0
view = mmv.make_view()
display = mmv.show_volume(mmv.make_volume(), view, preset="bone")
image = mmv.render_image(view, args.temp_dir + "/client_server.png")
mmv.check_not_blank(image, "the client/server image")

updates = mmv.info(display, "IrradianceUpdateCount")
casts = mmv.info(display, "RayCastCount")
active = mmv.info(display, "MultiMaterialActive")
lights = mmv.info(display, "NumberOfShadedLights")
print("server: IrradianceUpdateCount %s, RayCastCount %s, MultiMaterialActive %s, lights %s"
      % (updates, casts, active, lights))
checker.check(updates >= 1, "IrradianceUpdateCount comes from the server (%s)" % updates)
checker.check(casts >= 1, "RayCastCount comes from the server (%s)" % casts)
checker.check(active == 1, "MultiMaterialActive comes from the server (%s)" % active)
checker.check(lights >= 1, "NumberOfShadedLights comes from the server (%s)" % lights)
checker.check(mmv.info(display, "IrradianceResolutionInfo") != "",
              "IrradianceResolutionInfo comes from the server")
counts["first"] = {"IrradianceUpdateCount": updates, "RayCastCount": casts,
                   "NumberOfShadedLights": lights}
if known.ranks > 1:
    # Shadows crossed the ranks: every rank took part in the exchange.
    global_info = mmv.info(display, "GlobalIrradianceInfo")
    print("global irradiance: %s" % global_info)
    checker.check(("over %d ranks" % known.ranks) in global_info,
                  "the ranks rendered one global irradiance (%s)" % global_info)

# A light change recomputes the irradiance on the server: the count grows.
display.MaterialPreset = "skin"
mmv.render_image(view, args.temp_dir + "/client_server_2.png")
checker.check(mmv.info(display, "IrradianceUpdateCount") > updates,
              "a preset change adds a server irradiance update")
checker.check(mmv.info(display, "RayCastCount") > casts, "another frame is counted")
nodes = mmv.info(display, "AppliedMaterialNodes")
checker.check(len(nodes) == 2 * 13, "AppliedMaterialNodes holds the server's preset nodes (%d numbers)"
              % len(nodes))
counts["preset"] = {"IrradianceUpdateCount": mmv.info(display, "IrradianceUpdateCount"),
                    "RayCastCount": mmv.info(display, "RayCastCount")}

# A blend mode VTK shades makes the server's mapper fall back: 0.
display.BlendMode = display.GetProperty("BlendMode").Available[1]  # maximum intensity
mmv.render_image(view, args.temp_dir + "/client_server_3.png")
checker.check(mmv.info(display, "MultiMaterialActive") == 0,
              "Max Intensity falls back on the server (MultiMaterialActive 0)")

# The largest over the ranks, not their sum: the serial server's counts.
print("counts: %s" % counts)
if known.ranks == 1:
    with open(counts_file, "w") as f:
        json.dump(counts, f)
else:
    with open(counts_file) as f:
        serial = json.load(f)
    for step in serial:
        for name, value in serial[step].items():
            checker.check(counts[step][name] == value,
                          "%s after '%s' is one rank's count, as the serial server's: %s "
                          "(serial %s; the sum over %d ranks would be %s)"
                          % (name, step, counts[step][name], value, known.ranks,
                             known.ranks * value))
checker.finish()
