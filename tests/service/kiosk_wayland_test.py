#!/usr/bin/python3
"""`geokiosk play --display wayland` as a Wayland kiosk client (docs/platform.md): under a private
`weston --backend=headless-backend.so --use-gl` it goes fullscreen at the output size, frames are presented (swapBuffers waits for the compositor's frame callbacks, so
/metrics frames_total only grows while weston shows them) and SIGTERM ends it with exit 0.
Frames are checked under desktop-shell: weston 10's kiosk-shell on the headless backend maps the
first buffer and then never sends another frame callback (seen with WAYLAND_DEBUG=1: one
wl_surface.frame, no wl_callback.done), with the GL and the pixman renderer alike, so no client
can present a second frame there (docs/kiosk.md). Under kiosk-shell the test checks what does
work: fullscreen at the output size, no frame counted as presented (so no READY, no watchdog
ping: systemd would restart such a kiosk), /health 503, and a clean exit on SIGTERM while the
swap waits for the compositor (before, Mesa's own wait inside eglSwapBuffers held it forever).
usage: kiosk_wayland_test.py GEOKIOSK REPO_ROOT"""
import os
import re
import shutil
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from kiosk_common import Checks, Kiosk, demo_setup, gl_env, skip_or_fail, temp_dir  # noqa: E402

GK, ROOT, _ = demo_setup(sys.argv)
weston = shutil.which("weston")
if not weston:
    skip_or_fail("weston is not installed (apt-get install weston)")
c = Checks()

def start_weston(tmp, env, shell, tag):
    """A private headless weston (GL renderer); returns (process, socket name) or (None, None)."""
    socket_name = "geokiosk-test-%d-%s" % (os.getpid(), tag)
    log = open(os.path.join(tmp, "weston-%s.log" % tag), "w")
    server = subprocess.Popen([weston, "--backend=headless-backend.so", "--use-gl",
                               "--shell=" + shell, "--socket=" + socket_name, "--width=320",
                               "--height=200", "--idle-time=0", "--no-config"],
                              stdout=log, stderr=subprocess.STDOUT, env=env)
    path = os.path.join(env["XDG_RUNTIME_DIR"], socket_name)
    end = time.monotonic() + 30
    while time.monotonic() < end and not os.path.exists(path) and server.poll() is None:
        time.sleep(0.05)
    if not os.path.exists(path):
        with open(os.path.join(tmp, "weston-%s.log" % tag)) as f:
            print(f.read()[-2000:])
        stop_weston(server)
        return None, None
    return server, socket_name


def stop_weston(server):
    server.terminate()
    try:
        server.wait(timeout=10)
    except subprocess.TimeoutExpired:
        server.kill()
        server.wait()


def wait_for_frames(k, seconds):
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        if frames_total(k) > 0:
            return True
        time.sleep(0.1)
    return False


def frames_total(k):
    code, body, _ = k.request("GET", "/metrics")
    m = re.search(r"^geokiosk_frames_total (\S+)$", body, re.M)
    return float(m.group(1)) if m else 0.0


with temp_dir() as tmp:
    runtime = os.path.join(tmp, "xdg")
    os.mkdir(runtime, 0o700)
    env = gl_env()
    env["XDG_RUNTIME_DIR"] = runtime

    # desktop-shell: frames presented and progressing, clean exit.
    server, socket_name = start_weston(tmp, env, "desktop-shell.so", "desktop")
    c.check(server is not None, "weston (desktop-shell) started")
    if server:
        try:
            env["WAYLAND_DISPLAY"] = socket_name
            k = Kiosk(GK, ["scenarios/demo/rainier.json", "--display", "wayland", "--listen",
                           "127.0.0.1:0"], env, os.path.join(tmp, "log"))
            try:
                k.wait_port()
                deadline = time.monotonic() + 60
                frames = []
                while time.monotonic() < deadline and len(frames) < 2:
                    f = frames_total(k)
                    if f > 0:
                        frames.append(f)
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
            stop_weston(server)

    # kiosk-shell: fullscreen, first frame, frames stop (compositor), SIGTERM still clean.
    server, socket_name = start_weston(tmp, env, "kiosk-shell.so", "kiosk")
    c.check(server is not None, "weston (kiosk-shell) started")
    if server:
        try:
            env["WAYLAND_DISPLAY"] = socket_name
            k = Kiosk(GK, ["scenarios/demo/rainier.json", "--display", "wayland", "--listen",
                           "127.0.0.1:0"], env, os.path.join(tmp, "log-kiosk"))
            try:
                k.wait_port()
                end = time.monotonic() + 60  # display created (slow under load)
                while time.monotonic() < end and "fullscreen" not in k.log_text():
                    time.sleep(0.1)
                # The frame waits for weston's frame callback, which never comes: no frame counts
                # as presented, so no READY, no watchdog ping, /health 503.
                c.check(not wait_for_frames(k, 3), "kiosk-shell: no frame counted as presented")
                code, body, _ = k.request("GET", "/health")
                c.check(code == 503 and "no frame yet" in body,
                        "kiosk-shell: /health 503 'no frame yet' (%s)" % code)
                c.check(re.search(r"wayland 320x200 fullscreen", k.log_text()) is not None,
                        "kiosk-shell: fullscreen at the output size (320x200)")
                t0 = time.monotonic()
                rc = k.stop()
                took = time.monotonic() - t0
            finally:
                k.stop()
            c.check(rc == 0 and took < 5, "kiosk-shell: exit 0 on SIGTERM in %.1f s (%s)" %
                    (took, rc))
        finally:
            stop_weston(server)
c.exit()
