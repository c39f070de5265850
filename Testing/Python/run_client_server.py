"""Runs a pvpython test script against a pvserver on localhost: starts
pvserver on a free port (on this display, or a private Xvfb with -noreset
when there is none), waits until it accepts connections, runs
`pvpython SCRIPT --server-port N ARGS...`, stops the server and returns the
script's exit status.

With --mpiexec M --ranks N the server is `M -np N pvserver` (a parallel
render server); the script is passed --ranks N.

usage: run_client_server.py --pvserver P --pvpython P [--mpiexec M --ranks N] SCRIPT [ARGS...]
"""
import argparse
import os
import socket
import subprocess
import sys
import time


def free_port():
    with socket.socket() as s:
        s.bind(("localhost", 0))
        return s.getsockname()[1]


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--pvserver", required=True)
    parser.add_argument("--pvpython", required=True)
    parser.add_argument("--mpiexec")
    parser.add_argument("--ranks", type=int, default=1)
    parser.add_argument("script")
    args, rest = parser.parse_known_args()

    port = free_port()
    server_command = [args.pvserver, "--server-port=%d" % port]
    if args.mpiexec:
        server_command = [args.mpiexec, "--allow-run-as-root", "--oversubscribe",
                          "-np", str(args.ranks)] + server_command
        rest += ["--ranks", str(args.ranks)]
    if not os.environ.get("DISPLAY"):
        server_command = ["xvfb-run", "-a", "-s", "-noreset -screen 0 1280x1024x24"] + server_command
    server = subprocess.Popen(server_command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                              text=True, start_new_session=True)
    try:
        deadline = time.time() + 60
        for line in server.stdout:
            print("pvserver:", line.rstrip(), flush=True)
            if "Accepting connection" in line:
                break
            if time.time() > deadline:
                print("pvserver did not accept connections within 60 s")
                return 1
        else:
            print("pvserver exited before accepting connections")
            return 1
        client = subprocess.run([args.pvpython, args.script, "--server-port", str(port)] + rest)
        return client.returncode
    except BaseException:
        raise
    finally:
        # The server and, with xvfb-run, its X server: the session this started.
        try:
            os.killpg(server.pid, 15)
        except ProcessLookupError:
            pass
        remaining = server.stdout.read()
        if remaining.strip():
            print("pvserver:", remaining.rstrip())
        server.wait(timeout=30)


if __name__ == "__main__":
    sys.exit(main())
