#!/usr/bin/python3
"""`geokiosk play --display wayland` as a Wayland kiosk client (docs/platform.md): under a private
`weston --backend=headless-backend.so --use-gl` it goes fullscreen at the output size, frames are presented (swapBuffers waits for the compositor's frame callbacks, so
/metrics frames_total only grows while weston shows them) and SIGTERM ends it with exit 0.
The shell is desktop-shell: weston 10's kiosk-shell on the headless backend maps the first
buffer and then never sends another frame callback (seen with WAYLAND_DEBUG=1: one
wl_surface.frame, no wl_callback.done), with the GL and the pixman renderer alike, so no client
can present a second frame there (docs/kiosk.md).
usage: kiosk_wayland_test.py GEOKIOSK REPO_ROOT"""
import os
import re
import shutil
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from kiosk_common import Checks, Kiosk, gl_env, skip_or_fail, temp_dir  # noqa: E402

GK, ROOT = sys.argv[1], sys.argv[2]
os.chdir(ROOT)
if not os.path.exists("data/generated/rainier.gpkg"):
    skip_or_fail("demo store missing (run tools/prepare-demo.sh)")
weston = shutil.which("weston")
if not weston:
    skip_or_fail("weston is not installed (apt-get install weston)")
c = Checks()

with temp_dir() as tmp:
    runtime = os.path.join(tmp, "xdg")
    os.mkdir(runtime, 0o700)
    env = gl_env()
    env["XDG_RUNTIME_DIR"] = runtime
    socket_name = "geokiosk-test-%d" % os.getpid()
    wlog = open(os.path.join(tmp, "weston.log"), "w")
    server = subprocess.Popen([weston, "--backend=headless-backend.so", "--use-gl",
                               "--shell=desktop-shell.so", "--socket=" + socket_name,
                               "--width=320", "--height=200", "--idle-time=0", "--no-config"],
                              stdout=wlog, stderr=subprocess.STDOUT, env=env)
    try:
        end = time.monotonic() + 30
        while time.monotonic() < end and not os.path.exists(os.path.join(runtime, socket_name)):
            if server.poll() is not None:
                break
            time.sleep(0.05)
        if not os.path.exists(os.path.join(runtime, socket_name)):
            with open(os.path.join(tmp, "weston.log")) as f:
                print(f.read()[-2000:])
            c.check(False, "weston started")
            c.exit()
        env["WAYLAND_DISPLAY"] = socket_name
        k = Kiosk(GK, ["scenarios/demo/rainier.json", "--display", "wayland", "--listen",
                       "127.0.0.1:0"], env, os.path.join(tmp, "log"))
        try:
            k.wait_port()
            deadline = time.monotonic() + 60
            frames = []
            while time.monotonic() < deadline and len(frames) < 2:
                code, body, _ = k.request("GET", "/metrics")
                m = re.search(r"^geokiosk_frames_total (\S+)$", body, re.M)
                if m and float(m.group(1)) > 0:
                    frames.append(float(m.group(1)))
                    time.sleep(1.0)
                else:
                    time.sleep(0.1)
            c.check(len(frames) == 2 and frames[1] > frames[0] > 0,
                    "frames presented and progressing: %s" % frames)
            c.check(re.search(r"wayland 320x200 fullscreen", k.log_text()) is not None,
                    "fullscreen at the output size (320x200)")
        finally:
            rc = k.stop()
        c.check(rc == 0, "exit 0 on SIGTERM (%s)" % rc)
        if rc != 0 or c.failed:
            print(k.log_text()[-2000:])
    finally:
        server.terminate()
        try:
            server.wait(timeout=10)
        except subprocess.TimeoutExpired:
            server.kill()
        wlog.close()
c.exit()
