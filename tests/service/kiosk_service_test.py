#!/usr/bin/python3
"""geokiosk play as a systemd service, end to end (docs/kiosk.md):
  - a fake NOTIFY_SOCKET gets READY=1 after the first frame, WATCHDOG=1 while frames progress and
    none while a test hook stalls the frame loop (GEOKIOSK_TEST_STALL_FILE);
  - /metrics parses with prometheus_client's text parser and its counters increase;
  - /health is 200 while frames progress and 503 with the reason while stalled;
  - control: 401 without or with a wrong token, 200 with it, seek changes the drawn data time,
    403 when no token file is configured.
usage: kiosk_service_test.py GEOKIOSK REPO_ROOT"""
import json
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from kiosk_common import Checks, Kiosk, demo_setup, NotifySocket, gl_env, skip_or_fail, temp_dir  # noqa: E402

GK, ROOT, _ = demo_setup(sys.argv)
DEMO = "scenarios/demo/rainier.json"
try:
    from prometheus_client.parser import text_string_to_metric_families
except ImportError:
    skip_or_fail("python3-prometheus-client is not installed")

c = Checks()


def metrics(kiosk):
    status, text, headers = kiosk.request("GET", "/metrics")
    assert status == 200, status
    out = {}
    for fam in text_string_to_metric_families(text):
        for s in fam.samples:
            out[(s.name, tuple(sorted(s.labels.items())))] = s.value
    return out, headers


def value(m, name, **labels):
    return m.get((name, tuple(sorted(labels.items()))))


with temp_dir() as tmp:
    notify = NotifySocket(tmp)
    token_file = os.path.join(tmp, "token")
    with open(token_file, "w") as f:
        f.write("correct-horse\n")
    stall = os.path.join(tmp, "stall")
    env = gl_env()
    env["NOTIFY_SOCKET"] = notify.path
    env["WATCHDOG_USEC"] = "1000000"  # pings every 0.5 s while frames progress
    env["GEOKIOSK_TEST_STALL_FILE"] = stall
    k = Kiosk(GK, [DEMO, "--display", "headless", "--size", "64x36", "--max-fps", "30",
                   "--listen", "127.0.0.1:0", "--token-file", token_file], env,
              os.path.join(tmp, "log"))
    try:
        k.wait_port()
        seen = notify.wait_for("READY=1", 60)
        c.check(seen is not None, "READY=1 received")
        c.check(seen is not None and seen.index("READY=1") == 0, "READY=1 before any WATCHDOG")
        status = [l for l in (seen or []) if l.startswith("STATUS=")]
        c.check(bool(status) and "rainier.json" in status[-1] and "fps" in status[-1],
                "STATUS names the scenario and fps: %s" % (status[-1] if status else None))
        lines = notify.collect(4.0)
        pings = sum(1 for l in lines if l == "WATCHDOG=1")
        c.check(pings >= 2, "WATCHDOG=1 while frames progress (%d in 4 s)" % pings)

        m1, headers = metrics(k)
        c.check(headers.get("Content-Type", "").startswith("text/plain; version=0.0.4"),
                "Content-Type is the 0.0.4 text format")
        time.sleep(0.5)
        m2, _ = metrics(k)
        f1, f2 = value(m1, "geokiosk_frames_total"), value(m2, "geokiosk_frames_total")
        c.check(f1 is not None and f2 > f1 > 0, "frames_total increases (%s -> %s)" % (f1, f2))
        h1 = value(m1, "geokiosk_frame_time_ms_count")
        h2 = value(m2, "geokiosk_frame_time_ms_count")
        c.check(h1 is not None and h2 > h1, "frame-time histogram count increases")
        c.check(value(m2, "geokiosk_frame_time_ms_bucket", le="+Inf") == h2,
                "+Inf bucket equals the count")
        c.check((value(m2, "geokiosk_cache_bytes", kind="gpu_meshes") or 0) > 0,
                "GPU mesh bytes reported")
        c.check(value(m2, "geokiosk_layer_state", layer="flood", state="ready") is not None,
                "layer state per layer")
        c.check((value(m2, "geokiosk_resident_memory_bytes") or 0) > 1e6, "RSS reported")
        c.check((value(m2, "geokiosk_uptime_seconds") or 0) > 0, "uptime reported")

        code, body, _ = k.request("GET", "/health")
        c.check(code == 200 and json.loads(body)["status"] == "ok", "/health 200 while playing")

        # Control: the token guard, then pause + seek change the drawn data time.
        c.check(k.request("POST", "/control/pause")[0] == 401, "control without token: 401")
        c.check(k.request("POST", "/control/pause", "wrong")[0] == 401, "wrong token: 401")
        c.check(k.request("POST", "/control/pause", "correct-horse")[0] == 200, "pause: 200")
        c.check(k.request("POST", "/control/seek?t=%2B0", "correct-horse")[0] == 200, "seek +0")
        time.sleep(0.5)
        t0 = value(metrics(k)[0], "geokiosk_data_time_seconds")
        c.check(k.request("POST", "/control/seek?t=%2B2h", "correct-horse")[0] == 200, "seek +2h")
        time.sleep(0.5)
        t1 = value(metrics(k)[0], "geokiosk_data_time_seconds")
        c.check(t0 is not None and abs((t1 - t0) - 7200) < 1e-3,
                "seek moved the drawn data time by 2 h (%s -> %s)" % (t0, t1))
        c.check(k.request("POST", "/control/seek?t=soon", "correct-horse")[0] == 400,
                "bad seek time: 400")
        c.check(k.request("POST", "/control/explode", "correct-horse")[0] == 404,
                "unknown control: 404")

        # Stall the frame loop: the pings stop, /health turns 503; resume: both come back.
        open(stall, "w").close()
        time.sleep(0.3)
        notify.collect(0.3)  # drop what was sent before the stall took hold
        lines = notify.collect(2.0)
        c.check(not any(l == "WATCHDOG=1" for l in lines),
                "no WATCHDOG while the frame loop is stalled (%d lines)" % len(lines))
        time.sleep(3.5)  # /health's stall limit is 5 s
        code, body, _ = k.request("GET", "/health")
        c.check(code == 503 and "no frame for" in json.loads(body).get("reason", ""),
                "/health 503 with the reason while stalled: %s %s" % (code, body[:120]))
        os.remove(stall)
        c.check(notify.wait_for("WATCHDOG=1", 10) is not None, "WATCHDOG resumes")
        c.check(k.request("GET", "/health")[0] == 200, "/health 200 again")
    finally:
        rc = k.stop()
    c.check(rc == 0, "exit 0 on SIGTERM (got %s)" % rc)
    c.check("STOPPING=1" in notify.collect(0.5), "STOPPING=1 sent")

    # Without a token file control is disabled: 403.
    k = Kiosk(GK, [DEMO, "--display", "headless", "--size", "32x18", "--max-fps", "10",
                   "--listen", "127.0.0.1:0"], gl_env(), os.path.join(tmp, "log2"))
    try:
        k.wait_port()
        c.check(k.request("POST", "/control/pause", "anything")[0] == 403, "no token file: 403")
    finally:
        k.stop()
c.exit()
