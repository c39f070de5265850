#!/usr/bin/env python3
"""GUI test driver: runs the ParaView client on a private Xvfb, plays a
QtTesting XML script against the material editor and grabs the whole screen.

The private X server is started with -fbdir, so its framebuffer is an XWD file
that can be read at any moment: no screenshot tool is needed, and the test does
not depend on the display it was started from (ctest may run it under
xvfb-run; that display is simply not used).

Pass: the client exits 0 (QtTesting's <pqcheck>s passed), the widget logged its
creation, the server-manager checks in results.txt all say OK, and the
screenshot has real content, and the NaN list the script sets is reported by
the renderer exactly once. Writes <out>/material-editor.png (whole screen)
and <out>/paraview.log.

usage: run_gui_test.py --paraview P --plugin SO --materials DIR --out DIR
"""
import argparse
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import threading
import time
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
SCREEN = (1400, 900)


def read_xwd(path):
    """Returns (width, height, rows of (r, g, b) bytes) of a 24/32-bit XWD file."""
    with open(path, "rb") as f:
        data = f.read()
    header = struct.unpack(">25I", data[:100])
    header_size, _, _, depth, width, height = header[0:6]
    byte_order, bits_per_pixel, bytes_per_line = header[7], header[11], header[12]
    red_mask, green_mask, blue_mask = header[14:17]
    ncolors = header[19]
    if bits_per_pixel != 32 or depth < 24:
        raise ValueError("unsupported XWD: %d bpp, depth %d" % (bits_per_pixel, depth))
    offset = header_size + 12 * ncolors
    fmt = "<" if byte_order == 0 else ">"

    def shift(mask):
        s = 0
        while mask and not mask & 1:
            mask >>= 1
            s += 1
        return s

    rs, gs, bs = shift(red_mask), shift(green_mask), shift(blue_mask)
    rows = []
    for y in range(height):
        line = data[offset + y * bytes_per_line: offset + y * bytes_per_line + 4 * width]
        pixels = struct.unpack(fmt + "%dI" % width, line)
        row = bytearray(3 * width)
        row[0::3] = bytes((p >> rs) & 0xFF for p in pixels)
        row[1::3] = bytes((p >> gs) & 0xFF for p in pixels)
        row[2::3] = bytes((p >> bs) & 0xFF for p in pixels)
        rows.append(bytes(row))
    return width, height, rows


def write_png(path, width, height, rows):
    def chunk(tag, body):
        return (struct.pack(">I", len(body)) + tag + body +
                struct.pack(">I", zlib.crc32(tag + body) & 0xFFFFFFFF))

    raw = b"".join(b"\x00" + r for r in rows)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n")
        f.write(chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)))
        f.write(chunk(b"IDAT", zlib.compress(raw, 9)))
        f.write(chunk(b"IEND", b""))


def content_stats(width, height, rows):
    """Grey-level variance and number of distinct colours over a sample grid."""
    grey, colours = [], set()
    for y in range(0, height, 4):
        row = rows[y]
        for x in range(0, width, 4):
            r, g, b = row[3 * x: 3 * x + 3]
            grey.append((r + g + b) / 3.0)
            colours.add((r, g, b))
    mean = sum(grey) / len(grey)
    return sum((v - mean) ** 2 for v in grey) / len(grey), len(colours)


def start_xvfb(fbdir):
    read_fd, write_fd = os.pipe()
    xvfb = subprocess.Popen(
        ["Xvfb", "-noreset", "-displayfd", str(write_fd), "-screen", "0", "%dx%dx24" % SCREEN,
         "-fbdir", fbdir, "-nolisten", "tcp", "+extension", "GLX"],
        pass_fds=(write_fd,), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    os.close(write_fd)
    with os.fdopen(read_fd) as pipe:
        display = pipe.readline().strip()
    if not display:
        xvfb.kill()
        raise RuntimeError("Xvfb did not report a display")
    return xvfb, ":" + display




def start_client_display(prefix, settings):
    """A private Xvfb and the client's environment on it: an empty HOME (no
    user settings or saved window layouts leak in) and `settings`. Returns
    (xvfb, display, env, fbdir); the scratch folders are `fbdir` and
    env["HOME"]."""
    fbdir = tempfile.mkdtemp(prefix=prefix)
    home = tempfile.mkdtemp(prefix=prefix + "home-")
    xvfb, display = start_xvfb(fbdir)
    env = dict(os.environ)
    env.update({"DISPLAY": display, "HOME": home, "XDG_RUNTIME_DIR": home})
    env.update(settings)
    return xvfb, display, env, fbdir


def run_client(command, env, log_path, timeout, xvfb, watch):
    """Runs the ParaView client with `watch(client)` on a thread beside it
    (it polls the results file and the screen while the client runs), then
    stops Xvfb; returns the client's exit code, or "timeout"."""
    try:
        with open(log_path, "w") as log:
            client = subprocess.Popen(command, env=env, stdout=log, stderr=subprocess.STDOUT)
            watcher = threading.Thread(target=watch, args=(client,))
            watcher.start()
            try:
                rc = client.wait(timeout=timeout)
            except subprocess.TimeoutExpired:
                client.kill()
                rc = "timeout"
            watcher.join()
    finally:
        xvfb.terminate()
        xvfb.wait()
    return rc


def grab_when_final(results, fbdir, settle, timeout, grabbed):
    """A watch for run_client: once the test script writes FINAL to
    `results` (then holds the window still), waits `settle` seconds and
    copies Xvfb's framebuffer to grabbed["xwd"]."""
    def watch(client):
        deadline = time.time() + timeout
        while time.time() < deadline and client.poll() is None:
            if os.path.exists(results) and "FINAL" in open(results).read():
                time.sleep(settle)
                shutil.copy(os.path.join(fbdir, "Xvfb_screen0"), os.path.join(fbdir, "grab.xwd"))
                grabbed["xwd"] = os.path.join(fbdir, "grab.xwd")
                return
            time.sleep(0.2)
    return watch



def finish(grabbed, screenshot, failures, lines, output, scratch, min_bytes=0):
    """The screenshot (saved as PNG; "looks empty" without content or under
    `min_bytes`), the removal of the `scratch` folders, the report; the exit
    code."""
    if "xwd" in grabbed:
        width, height, rows = read_xwd(grabbed["xwd"])
        write_png(screenshot, width, height, rows)
        variance, colours = content_stats(width, height, rows)
        print("screenshot %s: %dx%d, %d bytes, grey variance %.0f, %d colours"
              % (screenshot, width, height, os.path.getsize(screenshot), variance, colours))
        if variance < 200 or colours < 50 or os.path.getsize(screenshot) < min_bytes:
            failures.append("screenshot looks empty")
    else:
        failures.append("no screenshot taken")
    for folder in scratch:
        shutil.rmtree(folder, ignore_errors=True)
    print("\n".join(lines))
    if failures:
        print("---- paraview output (tail) ----")
        print(output[-6000:])
        print("FAILED:\n  " + "\n  ".join(failures))
        return 1
    print("PASSED")
    return 0


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--paraview", required=True)
    parser.add_argument("--plugin", required=True)
    parser.add_argument("--materials", required=True)
    parser.add_argument("--out", required=True)
    # A deadlock guard: a loaded 2-core machine has taken 150 s.
    parser.add_argument("--timeout", type=float, default=300)
    parser.add_argument("--setup", default=os.path.join(HERE, "setup_material_editor.py"),
                        help="startup script (defines check_nodes() for the XML)")
    args = parser.parse_args()

    os.makedirs(args.out, exist_ok=True)
    results = os.path.join(args.out, "results.txt")
    screenshot = os.path.join(args.out, "material-editor.png")
    log_path = os.path.join(args.out, "paraview.log")
    for stale in (results, screenshot):
        if os.path.exists(stale):
            os.remove(stale)

    xvfb, display, env, fbdir = start_client_display("mmv-gui-", {
        "MMV_PLUGIN": os.path.abspath(args.plugin),
        "MMV_MATERIALS_DIR": os.path.abspath(args.materials),
        "MMV_RESULTS": results,
        # The widget logs its creation and edits at this level.
        "PARAVIEW_LOG_APPLICATION_VERBOSITY": "INFO",
    })
    # -geometry is Qt's (xcb) option for the first window: there is no window
    # manager on Xvfb to maximise it, and the default window is small.
    command = [args.paraview, "-geometry", "%dx%d+0+0" % SCREEN, "--dr", "--script=" + os.path.abspath(args.setup),
               "--test-script=" + os.path.join(HERE, "material_editor.xml"), "--exit"]
    print("running:", " ".join(command), "on", display, flush=True)
    grabbed = {}
    # The XML writes results.txt as its last check, then holds the window
    # still (process events, then a frozen pause) while this grabs it.
    rc = run_client(command, env, log_path, args.timeout, xvfb,
                    grab_when_final(results, fbdir, 3.0, args.timeout, grabbed))

    failures = []
    output = open(log_path, errors="replace").read()
    if rc != 0:
        failures.append("paraview exited with %s" % rc)
    if "pqMaterialNodesPropertyWidget created" not in output:
        failures.append("the material editor was never created")
    lines = open(results).read().splitlines() if os.path.exists(results) else []
    if not any(line.startswith("FINAL") for line in lines):
        failures.append("the XML script did not reach its final check")
    failures += ["server manager check: " + line for line in lines if line.startswith("FAIL")]
    # The script sets one NaN list from Python: the renderer must report it
    # once, and editing afterwards must not write the NaN back (a second
    # report).
    nan_reports = [line for line in output.splitlines() if "SetNodes:" in line]
    if len(nan_reports) != 1:
        failures.append("expected the NaN MaterialNodes reported once, got %d:\n    %s"
                        % (len(nan_reports), "\n    ".join(nan_reports)))

    return finish(grabbed, screenshot, failures, lines, output, (fbdir, env["HOME"]), min_bytes=20000)


if __name__ == "__main__":
    sys.exit(main())
