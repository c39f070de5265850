#!/usr/bin/env python3
"""GUI test of the Properties panel and of first use, in the real ParaView
client on a private Xvfb (run_gui_test.py's display handling).

panel.xml opens the data with File > Open, presses Apply, switches the
representation in the toolbar to Multi-Material Volume and triggers the
panel probe (a test-only plugin, PanelProbe/) in the default and the
advanced view, and with Use Cropping on and the inverse-square falloff.

Pass: the client exits 0, the Python checks in results.txt all say OK
(first use: coloured by the active point array, the view differs from its
background, no error or warning), and each probe record lists exactly the
property widgets of Testing/Python/mmv_panel_sets.py. Writes <out>/screen.png
(whole screen), <out>/probe/panel-<record>-<page>.png (the panel on screen,
scrolled page by page), <out>/first-use.png and <out>/paraview.log.

usage: run_panel_test.py --paraview P --plugin-path DIRS --data VTI --out DIR
"""
import argparse
import os
import shutil
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "Python"))
from run_gui_test import (SCREEN, finish, grab_when_final, run_client,  # noqa: E402
                          start_client_display)
import mmv_panel_sets as sets  # noqa: E402


def read_records(path):
    """The probe's records: [(advanced, image, {name, ...}, [labels])]."""
    records = []
    if not os.path.exists(path):
        return records
    current = None
    for line in open(path).read().splitlines():
        words = line.split(" ")
        if words[0] == "record":
            current = (words[3] == "1", words[5], set(), [], int(words[7]), int(words[9]))
        elif words[0] == "widget" and current is not None:
            current[2].add(sets.gui_name(words[1], words[2], words[3]))
        elif words[0] == "label" and current is not None:
            current[3].append(" ".join(words[1:]))
        elif words[0] == "end" and current is not None:
            records.append(current)
            current = None
    return records


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--paraview", required=True)
    parser.add_argument("--plugin-path", required=True,
                        help="PV_PLUGIN_PATH: the plugin's folder and the probe's")
    parser.add_argument("--data", required=True)
    parser.add_argument("--out", required=True)
    parser.add_argument("--timeout", type=float, default=240)
    args = parser.parse_args()

    os.makedirs(args.out, exist_ok=True)
    results = os.path.join(args.out, "results.txt")
    probe = os.path.join(args.out, "probe")
    screenshot = os.path.join(args.out, "screen.png")
    log_path = os.path.join(args.out, "paraview.log")
    shutil.rmtree(probe, ignore_errors=True)
    for stale in (results, screenshot):
        if os.path.exists(stale):
            os.remove(stale)

    # QtTesting takes the file dialog's path literally.
    xml = os.path.join(args.out, "panel.xml")
    with open(os.path.join(HERE, "panel.xml")) as source, open(xml, "w") as target:
        target.write(source.read().replace("@DATA@", os.path.abspath(args.data)))

    xvfb, display, env, fbdir = start_client_display("mmv-gui-", {
        "PV_PLUGIN_PATH": args.plugin_path,
        "MMV_RESULTS": results,
        "MMV_PANEL_PROBE": probe,
    })
    command = [args.paraview, "-geometry", "%dx%d+0+0" % SCREEN, "--dr",
               "--script=" + os.path.join(HERE, "setup_panel.py"),
               "--test-script=" + xml, "--exit"]
    print("running:", " ".join(command), "on", display, flush=True)
    grabbed = {}
    rc = run_client(command, env, log_path, args.timeout, xvfb,
                    grab_when_final(results, fbdir, 2.0, args.timeout, grabbed))

    failures = []
    output = open(log_path, errors="replace").read()
    if rc != 0:
        failures.append("paraview exited with %s" % rc)
    lines = open(results).read().splitlines() if os.path.exists(results) else []
    for name in ("check_applied", "check_first_use", "check_no_messages"):
        if not any(name in line for line in lines):
            failures.append("%s never ran" % name)
    failures += ["check: " + line for line in lines if line.startswith("FAIL")]

    records = read_records(os.path.join(probe, "panel.txt"))
    expected = [(False, sets.DEFAULT, "default view"),
                (True, sets.ADVANCED, "advanced view"),
                (True, sets.ADVANCED | sets.WITH_CROPPING_AND_RADIUS,
                 "advanced view, Use Cropping, Inverse Square Beyond Radius")]
    if len(records) != len(expected):
        failures.append("the probe wrote %d records, expected %d" % (len(records), len(expected)))
    for record, (advanced, names, what) in zip(records, expected):
        shown = record[2]
        print("%s (%s): %s" % (what, record[1], sorted(shown)))
        print("  labels: %s" % record[3])
        print("  rows need %d px, the dock gives %d (ParaView's Volume needs 330 here too)"
              % (record[4], record[5]))
        if record[0] != advanced:
            failures.append("%s: the gear is %s" % (what, "on" if record[0] else "off"))
        if shown != names:
            failures.append("%s: extra %s, missing %s"
                            % (what, sorted(shown - names), sorted(names - shown)))
        if shown & (sets.DEAD | sets.INTERNALS):
            failures.append("%s shows dead controls or internals %s"
                            % (what, sorted(shown & (sets.DEAD | sets.INTERNALS))))

    return finish(grabbed, screenshot, failures, lines, output, (fbdir, env["HOME"]))


if __name__ == "__main__":
    sys.exit(main())
