"""Helpers for the kiosk end-to-end tests: start `geokiosk play` with a fake NOTIFY_SOCKET,
find its HTTP port in the log, talk HTTP, stop it. Standard library only (prometheus_client is
imported by the tests that parse /metrics)."""
import os
import re
import signal
import socket
import subprocess
import sys
import tempfile
import time
import urllib.error
import urllib.request

SKIP = 77  # ctest SKIP_RETURN_CODE


def skip_or_fail(message):
    """Missing prerequisites fail under KIOSK_REQUIRE_GL=1 (CI), else skip."""
    if os.environ.get("KIOSK_REQUIRE_GL") == "1":
        print("FAIL: " + message)
        sys.exit(1)
    print("SKIP: " + message)
    sys.exit(SKIP)


def demo_setup(argv):
    """`SCRIPT GEOKIOSK REPO_ROOT`: work from the repository root; skip (or fail under
    KIOSK_REQUIRE_DATA) when the demo store is missing. Returns (geokiosk, root, demo store)."""
    gk, root = argv[1], os.path.abspath(argv[2])
    os.chdir(root)
    store = os.path.join(root, "data/generated/rainier.gpkg")
    if not os.path.exists(store):
        skip_or_fail("demo store missing (run tools/prepare-demo.sh)")
    return gk, root, store


def gl_env():
    env = dict(os.environ)
    env["__EGL_VENDOR_LIBRARY_FILENAMES"] = "/usr/share/glvnd/egl_vendor.d/50_mesa.json"
    env["GALLIUM_DRIVER"] = "llvmpipe"
    env.pop("DISPLAY", None)
    env.pop("WAYLAND_DISPLAY", None)
    return env


class NotifySocket:
    """The systemd side of sd_notify: a Unix datagram socket collecting messages."""

    def __init__(self, directory):
        self.path = os.path.join(directory, "notify")
        self.sock = socket.socket(socket.AF_UNIX, socket.SOCK_DGRAM)
        self.sock.bind(self.path)
        self.sock.settimeout(0.1)

    def collect(self, seconds):
        """All messages received within `seconds`, each split into its lines."""
        out, end = [], time.monotonic() + seconds
        while time.monotonic() < end:
            try:
                out.extend(self.sock.recv(4096).decode().splitlines())
            except socket.timeout:
                pass
        return out

    def wait_for(self, prefix, seconds):
        """Lines up to and including the message with a line starting with `prefix`, or None."""
        seen, end = [], time.monotonic() + seconds
        while time.monotonic() < end:
            try:
                lines = self.sock.recv(4096).decode().splitlines()
                seen.extend(lines)
                if any(line.startswith(prefix) for line in lines):
                    return seen
            except socket.timeout:
                pass
        return None


class Kiosk:
    """A running `geokiosk play ... --listen 127.0.0.1:0` whose port is read from its log."""

    def __init__(self, geokiosk, args, env, log_path):
        self.log_path = log_path
        self.log = open(log_path, "w")
        self.proc = subprocess.Popen([geokiosk, "play"] + args, stdout=self.log,
                                     stderr=subprocess.STDOUT, env=env)
        self.port = None

    def log_text(self):
        with open(self.log_path) as f:
            return f.read()

    def wait_port(self, seconds=60):
        end = time.monotonic() + seconds
        while time.monotonic() < end:
            m = re.search(r"listening on 127\.0\.0\.1:(\d+)", self.log_text())
            if m:
                self.port = int(m.group(1))
                return self.port
            if self.proc.poll() is not None:
                break
            time.sleep(0.05)
        raise AssertionError("no 'listening on' line; log:\n" + self.log_text()[-2000:])

    def request(self, method, path, token=None):
        req = urllib.request.Request("http://127.0.0.1:%d%s" % (self.port, path), method=method)
        if token is not None:
            req.add_header("Authorization", "Bearer " + token)
        try:
            with urllib.request.urlopen(req, timeout=10) as r:
                return r.status, r.read().decode(), dict(r.headers)
        except urllib.error.HTTPError as e:
            return e.code, e.read().decode(), dict(e.headers)

    def stop(self):
        if self.proc.poll() is None:
            self.proc.send_signal(signal.SIGTERM)
            try:
                self.proc.wait(timeout=20)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
        self.log.close()
        return self.proc.returncode


class Checks:
    def __init__(self):
        self.failed = 0

    def check(self, ok, what):
        print(("ok:   " if ok else "FAIL: ") + what)
        if not ok:
            self.failed += 1
        return ok

    def exit(self):
        print("%d failed" % self.failed)
        sys.exit(1 if self.failed else 0)


def temp_dir():
    return tempfile.TemporaryDirectory(prefix="geokiosk-svc-")


def wait_until(pred, seconds, step=0.05):
    """True once pred() holds, polled every `step` seconds; False after `seconds`."""
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        if pred():
            return True
        time.sleep(step)
    return False
