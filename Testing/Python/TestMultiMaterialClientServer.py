"""Client/server: the information properties report the process that
renders. Connected to a pvserver (started by run_client_server.py, which
passes --server-port) with remote rendering on, the client's copy of the
representation never renders, so its counters are 0; the values read must
be the server's: a nonzero
IrradianceUpdateCount and RayCastCount, MultiMaterialActive 1, and they
grow with further renders."""

import argparse

from paraview import simple

import mmv_testing as mmv

parser = argparse.ArgumentParser()
parser.add_argument("--server-port", type=int, required=True)
known, _ = parser.parse_known_args()
args = mmv.parse_args()

simple.Connect("localhost", known.server_port)
checker = mmv.Checker()
checker.check(simple.servermanager.ActiveConnection.IsRemote(), "connected to a pvserver")
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

# A light change recomputes the irradiance on the server: the count grows.
display.MaterialPreset = "skin"
mmv.render_image(view, args.temp_dir + "/client_server_2.png")
checker.check(mmv.info(display, "IrradianceUpdateCount") > updates,
              "a preset change adds a server irradiance update")
checker.check(mmv.info(display, "RayCastCount") > casts, "another frame is counted")
nodes = mmv.info(display, "AppliedMaterialNodes")
checker.check(len(nodes) == 2 * 13, "AppliedMaterialNodes holds the server's preset nodes (%d numbers)"
              % len(nodes))

# A blend mode VTK shades makes the server's mapper fall back: 0.
display.BlendMode = display.GetProperty("BlendMode").Available[1]  # maximum intensity
mmv.render_image(view, args.temp_dir + "/client_server_3.png")
checker.check(mmv.info(display, "MultiMaterialActive") == 0,
              "Max Intensity falls back on the server (MultiMaterialActive 0)")
checker.finish()
