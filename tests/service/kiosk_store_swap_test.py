#!/usr/bin/python3
"""Store swap and deletion under a running kiosk (docs/kiosk.md): a store replaced by atomic
rename is checked in the background and taken over (same scenario re-opened on the new file);
a broken replacement is logged once and the old picture stays; deleting the store keeps the
picture (frames go on) and reports degraded in /health and /metrics. No crash throughout.
usage: kiosk_store_swap_test.py GEOKIOSK REPO_ROOT"""
import json
import os
import re
import shutil
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from kiosk_common import Checks, Kiosk, demo_setup, gl_env, temp_dir  # noqa: E402

GK, ROOT, STORE = demo_setup(sys.argv)
c = Checks()


def metric(k, name):
    code, body, _ = k.request("GET", "/metrics")
    m = re.search(r"^%s (\S+)$" % name, body, re.M)
    return float(m.group(1)) if m else None


def wait_until(pred, seconds):
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        if pred():
            return True
        time.sleep(0.1)
    return False


with temp_dir() as tmp:
    store = os.path.join(tmp, "run.gpkg")
    shutil.copyfile(STORE, store)
    with open("scenarios/demo/rainier.json") as f:
        scenario = json.load(f)
    scenario.pop("$schema", None)
    scenario["stores"] = {"rainier": store}
    scenario_path = os.path.join(tmp, "scenario.json")
    with open(scenario_path, "w") as f:
        json.dump(scenario, f)
    k = Kiosk(GK, [scenario_path, "--display", "headless", "--size", "64x36", "--max-fps", "30",
                   "--listen", "127.0.0.1:0"], gl_env(), os.path.join(tmp, "log"))
    try:
        k.wait_port()
        c.check(wait_until(lambda: (metric(k, "geokiosk_frames_total") or 0) > 5, 60),
                "playing")

        # 1. A new model run: written next to it, renamed over it.
        shutil.copyfile(STORE, os.path.join(tmp, "next.gpkg"))
        os.rename(os.path.join(tmp, "next.gpkg"), store)
        new_inode = os.stat(store).st_ino
        c.check(wait_until(lambda: metric(k, "geokiosk_store_swaps_total") == 1, 20),
                "replaced store taken over (store_swaps_total = 1)")
        health = json.loads(k.request("GET", "/health")[1])
        c.check(any(s["inode"] == new_inode for s in health.get("stores", [])),
                "the session now reads the new file (inode %d): %s" % (new_inode,
                                                                      health.get("stores")))
        c.check(metric(k, "geokiosk_reloads_total") == 1, "counted as a reload")
        f0 = metric(k, "geokiosk_frames_total")

        # 2. A broken replacement: logged once, old picture kept.
        with open(os.path.join(tmp, "bad.gpkg"), "wb") as f:
            f.write(b"this is not a GeoPackage" * 100)
        os.rename(os.path.join(tmp, "bad.gpkg"), store)
        time.sleep(3.5)
        c.check(metric(k, "geokiosk_store_swaps_total") == 1, "broken replacement not taken")
        c.check(metric(k, "geokiosk_frames_total") > f0, "frames go on after the broken store")
        broken_lines = re.findall(r"replaced by a broken store", k.log_text())
        c.check(len(broken_lines) == 1, "logged once (%d lines)" % len(broken_lines))
        c.check(k.request("GET", "/health")[0] == 200, "/health 200 with the old picture")

        # 3. The store deleted under the running kiosk.
        os.remove(store)
        c.check(wait_until(lambda: metric(k, "geokiosk_store_degraded") == 1, 10),
                "deletion reported degraded in /metrics")
        code, body, _ = k.request("GET", "/health")
        health = json.loads(body)
        c.check(code == 200 and health["store_degraded"] is True and
                any("store file is gone" in w for w in health["warnings"]),
                "/health: still drawing, store degraded: %s" % body[:200])
        f1 = metric(k, "geokiosk_frames_total")
        time.sleep(1.0)
        c.check(metric(k, "geokiosk_frames_total") > f1, "frames go on without the file")
        c.check(k.proc.poll() is None, "no crash")
    finally:
        rc = k.stop()
    c.check(rc == 0, "exit 0 on SIGTERM (%s)" % rc)
    if c.failed:
        print(k.log_text()[-3000:])
c.exit()
