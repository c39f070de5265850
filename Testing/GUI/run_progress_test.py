#!/usr/bin/env python3
"""GUI test driver: ParaView's progress bar moves during a long irradiance
update, and the image after it is right.

Runs the ParaView client on a private Xvfb (run_gui_test.py's), with
setup_progress.py and progress.xml: an opacity edit of a 256x256x128 chest
and its still render, from the Python shell. While the render runs, the
client's event loop is blocked; this driver reads the X server's framebuffer
(an XWD file, -fbdir) every 0.1 s and measures the progress bar in the status
bar: the width of its filled part.

Pass:
 - the client exits 0 and writes FINAL;
 - one irradiance update ran, and the progress handler (what the bar follows)
   reported increasing values of "Irradiance volume" from 0 to 100 %, at
   least one between;
 - the screen grabs during the render show the bar filled to at least two
   different widths (the bar moved while the client was busy);
 - the client logged no warning or error (a GL state out of VTK's cache
   shows as vtkOpenGLState warnings);
 - the image after the edit equals a render of the same scene and edit in
   pvpython, where nothing repaints during the update (PSNR >= 40 dB).
Writes into --out: paraview.log, grabs (status bar strips, PNG), after-edit.png,
reference.png, summary.txt.

usage: run_progress_test.py --paraview P --pvpython PV --plugin SO --out DIR
"""
import argparse
import json
import os
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from run_gui_test import (SCREEN, read_xwd, run_client,  # noqa: E402
                          start_client_display, write_png)

STRIP = 40  # rows of the screen's bottom holding the status bar


def grab_strip(fbdir):
    """The bottom STRIP rows of the screen as an XWD file's bytes: read in a
    few milliseconds, decoded after the render."""
    with open(os.path.join(fbdir, "Xvfb_screen0"), "rb") as f:
        return f.read()


def decode_strip(data, path):
    """Rows (r, g, b bytes) of the strip, written to `path` as a PNG."""
    tmp = path + ".xwd"
    with open(tmp, "wb") as f:
        f.write(data)
    width, height, rows = read_xwd(tmp)
    os.remove(tmp)
    strip = rows[-STRIP:]
    write_png(path, width, STRIP, strip)
    return width, strip


def bar_fill(width, strip):
    """Columns of the status bar strip drawn in the progress bar's fill
    colour (Qt's highlight: saturated blue)."""
    columns = 0
    for x in range(width):
        for row in strip:
            r, g, b = row[3 * x], row[3 * x + 1], row[3 * x + 2]
            if b > 150 and b - r > 80 and b - g > 20:
                columns += 1
                break
    return columns


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--paraview", required=True)
    parser.add_argument("--pvpython", required=True)
    parser.add_argument("--plugin", required=True)
    parser.add_argument("--out", required=True)
    parser.add_argument("--timeout", type=float, default=400)
    args = parser.parse_args()

    out = os.path.abspath(args.out)
    os.makedirs(os.path.join(out, "grabs"), exist_ok=True)
    results = os.path.join(out, "results.txt")
    log_path = os.path.join(out, "paraview.log")
    for stale in (results, os.path.join(out, "after-edit.png"), os.path.join(out, "reference.png")):
        if os.path.exists(stale):
            os.remove(stale)
    for name in os.listdir(os.path.join(out, "grabs")):
        os.remove(os.path.join(out, "grabs", name))

    xvfb, display, env, fbdir = start_client_display("mmv-progress-", {
        "MMV_PLUGIN": os.path.abspath(args.plugin),
        "MMV_SCENE": os.path.join(HERE, "progress_scene.py"),
        "MMV_OUT": out,
        "MMV_RESULTS": results,
    })
    command = [args.paraview, "-geometry", "%dx%d+0+0" % SCREEN, "--dr",
               "--script=" + os.path.join(HERE, "setup_progress.py"),
               "--test-script=" + os.path.join(HERE, "progress.xml"), "--exit"]
    print("running:", " ".join(command), "on", display, flush=True)
    raw = []  # (time, screen bytes), every 0.1 s of the render

    def lines():
        return open(results).read().splitlines() if os.path.exists(results) else []

    def watch(client):
        deadline = time.time() + args.timeout
        while time.time() < deadline and client.poll() is None:
            text = lines()
            if any(line.startswith("EDIT_END") for line in text):
                return
            if any(line.startswith("EDIT_START") for line in text):
                raw.append((time.time(), grab_strip(fbdir)))
            time.sleep(0.1)

    rc = run_client(command, env, log_path, args.timeout, xvfb, watch)

    failures = []
    summary = []
    if rc != 0:
        failures.append("paraview exited with %s" % rc)
    text = lines()
    if "FINAL" not in text:
        failures.append("the XML script did not reach finish()")
    record = [json.loads(line[len("REPORTS "):]) for line in text if line.startswith("REPORTS ")]
    if not record:
        failures.append("no REPORTS line: edit_and_render() did not run")
    else:
        record = record[0]
        values = [value for _, name, value in record["reports"] if name == "Irradiance volume"]
        summary.append("render %.2f s, irradiance update %.2f s (%s), %d update(s)" % (
            record["render_seconds"], record["irradiance_seconds"], record["stages"],
            record["updates"]))
        summary.append("progress handler: %s" % ", ".join(
            "%s %d%% at %.2f s" % (name, value, t) for t, name, value in record["reports"]))
        if record["updates"] != 1:
            failures.append("expected one irradiance update, got %d" % record["updates"])
        # ParaView's handler passes on at most a few reports a second, so a
        # short update shows one step between its start and end.
        inner = [v for v in values if 0 < v < 100]
        if not inner or values[0] != 0 or values[-1] != 100:
            failures.append("the progress handler reported %s for the update: no progress "
                            "between its start and end" % values)
        if values != sorted(values):
            failures.append("progress went back: %s" % values)
    start = None
    for line in text:
        if line.startswith("EDIT_START"):
            start = float(line.split()[1])
    grabs = []  # (time, filled columns)
    for k, (t, data) in enumerate(raw):
        width, strip = decode_strip(data, os.path.join(out, "grabs", "grab-%03d.png" % k))
        grabs.append((t, bar_fill(width, strip)))
    filled = sorted(set(columns for _, columns in grabs if columns > 0))
    summary.append("screen grabs during the render: %d, bar fill widths (px) %s" % (
        len(grabs), [(round(t - start, 2) if start else t, c) for t, c in grabs]))
    if len(filled) < 2:
        failures.append("the progress bar did not move on screen during the render "
                        "(fill widths %s)" % filled)

    output = open(log_path, errors="replace").read()
    bad = [line for line in output.splitlines()
           if "vtkOpenGLState" in line or "ERROR" in line or "Warning" in line
           or "Error" in line]
    if bad:
        failures.append("the client logged warnings or errors:\n    " + "\n    ".join(bad[:20]))

    after = os.path.join(out, "after-edit.png")
    if os.path.exists(after):
        reference = subprocess.run(
            [args.pvpython, "--force-offscreen-rendering",
             os.path.join(HERE, "progress_reference.py"), "--plugin", args.plugin,
             "--out", out, "--compare", after],
            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True,
            timeout=args.timeout)
        summary.append(reference.stdout.strip())
        if reference.returncode != 0:
            failures.append("reference comparison failed:\n" + reference.stdout[-2000:])
    else:
        failures.append("no image after the edit")

    with open(os.path.join(out, "summary.txt"), "w") as f:
        f.write("\n".join(summary) + "\n")
    print("\n".join(summary))
    if failures:
        print("FAILED:\n  " + "\n  ".join(failures))
        return 1
    print("PASSED")
    return 0


if __name__ == "__main__":
    sys.exit(main())
