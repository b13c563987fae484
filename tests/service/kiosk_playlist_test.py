#!/usr/bin/python3
"""`geokiosk play kiosk.json` (docs/kiosk.md): a playlist whose middle entry is broken plays the
others in order, skips the broken one with one log line per distinct problem and a /health
warning, and reports its position in /metrics; a broken kiosk file is exit 1 with
file:line:col: /pointer.
usage: kiosk_playlist_test.py GEOKIOSK REPO_ROOT"""
import json
import os
import re
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from kiosk_common import Checks, Kiosk, demo_setup, gl_env, temp_dir  # noqa: E402

GK, ROOT, _ = demo_setup(sys.argv)
c = Checks()
demo = os.path.join(ROOT, "scenarios/demo/rainier.json")
broken = os.path.join(ROOT, "scenarios/broken/unknown-transfer.json")
route = os.path.join(ROOT, "scenarios/mappings/route.json")

with temp_dir() as tmp:
    kiosk_file = os.path.join(tmp, "kiosk.json")
    with open(kiosk_file, "w") as f:
        json.dump({"playlist": [{"scenario": demo, "duration": 1.5},
                                {"scenario": broken, "duration": 1.5},
                                {"scenario": route, "duration": 1.5}],
                   "transition": {"kind": "fade", "seconds": 0.5},
                   "listen": "127.0.0.1:0"}, f)
    k = Kiosk(GK, [kiosk_file, "--display", "headless", "--size", "64x36", "--max-fps", "30"],
              gl_env(), os.path.join(tmp, "log"))
    try:
        k.wait_port()
        positions = set()
        end = time.monotonic() + 25
        while time.monotonic() < end:
            text = k.log_text()
            if len(re.findall(r"entry \d/3: ", text)) >= 4:
                break
            code, body, _ = k.request("GET", "/metrics")
            m = re.search(r"^geokiosk_playlist_position (\S+)$", body, re.M)
            if m:
                positions.add(float(m.group(1)))
            time.sleep(0.1)
        code, body, _ = k.request("GET", "/health")
        health = json.loads(body)
    finally:
        rc = k.stop()
    log = k.log_text()
    order = re.findall(r"entry (\d)/3: (\S+)", log)
    c.check([i for i, _ in order[:4]] == ["1", "3", "1", "3"],
            "entries play in order, the broken middle one skipped: %s" % order[:4])
    c.check(order and order[0][1] == demo and order[1][1] == route, "right files")
    skips = re.findall(r"skipping /playlist/1 entry 1: .*unknown-transfer\.json:\d+:\d+: ", log)
    c.check(len(skips) == 1, "one log line for the broken entry (%d)" % len(skips))
    c.check(any("skipped /playlist/1" in w for w in health.get("warnings", [])),
            "/health warns about the skipped entry: %s" % health.get("warnings"))
    c.check(code == 200, "/health still 200")
    c.check({0.0, 2.0} <= positions and 1.0 not in positions,
            "/metrics playlist position went 0 and 2, never 1: %s" % sorted(positions))
    c.check(rc == 0, "exit 0 on SIGTERM (%s)" % rc)

    # A broken kiosk file: exit 1, file:line:col: /pointer.
    with open(kiosk_file, "w") as f:
        f.write('{\n  "playlist": [ { "scenario": "a.json", "loops": 0 } ]\n}\n')
    r = subprocess.run([GK, "play", kiosk_file, "--display", "headless"], env=gl_env(),
                       capture_output=True, text=True, timeout=60)
    c.check(r.returncode == 1, "broken kiosk file: exit 1 (%d)" % r.returncode)
    c.check(re.search(re.escape(kiosk_file) + r":2:\d+: /playlist/0/loops: ", r.stderr) is not None,
            "message names file:line:col: /pointer: %s" % r.stderr.strip())
c.exit()
