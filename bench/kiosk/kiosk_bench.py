#!/usr/bin/python3
"""Kiosk benchmarks (issue 15), each printing ONE JSON object with its same-run baseline:

  soak     FRAMES frames of the demo (looping clock and camera path) at 64x36 headless from a
           kiosk file with 16 MiB cache budgets, a scenario reload (POST /control/reload, taken at
           the next 0.5 s poll) every RELOAD frames; RSS after warm-up (the baseline) vs
           at the end. Goal: growth < 2 MB over 1,000,000 frames. --bound-mb makes it a test.
  restart  kill -9 of a running kiosk, then process start -> READY=1 (sd_notify), median of 5;
           same-run baseline: `geokiosk --version` (exec + shared libraries), median of 5; the
           first, cold start is reported too.
  scrape   frame time of the demo flight with /metrics scraped 50 times a second vs not scraped:
           PAIRS interleaved phases of SECONDS each (ABBA blocks, same run), median of the per-pair
           ratios of the render thread's CPU time per frame and of wall time per frame.
           Goal: change < 2 %.

usage: kiosk_bench.py soak|restart|scrape GEOKIOSK REPO_ROOT [--frames N] [--reload N]
       [--bound-mb MB] [--seconds S] [--pairs N]"""
import argparse
import json
import os
import re
import signal
import statistics
import sys
import threading
import time
import urllib.request

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "../../tests/service"))
from kiosk_common import Kiosk, NotifySocket, gl_env, temp_dir  # noqa: E402

DEMO = "scenarios/demo/rainier.json"


def scrape(port):
    with urllib.request.urlopen("http://127.0.0.1:%d/metrics" % port, timeout=10) as r:
        text = r.read().decode()
    out = {}
    for name in ("geokiosk_frames_total", "geokiosk_resident_memory_bytes",
                 "geokiosk_heap_in_use_bytes",
                 "geokiosk_frame_time_ms_sum", "geokiosk_frame_time_ms_count",
                 "geokiosk_reloads_total", "geokiosk_reload_failures_total"):
        m = re.search(r"^%s (\S+)$" % name, text, re.M)
        out[name] = float(m.group(1)) if m else None
    return out


def post(port, path, token):
    req = urllib.request.Request("http://127.0.0.1:%d%s" % (port, path), method="POST")
    req.add_header("Authorization", "Bearer " + token)
    urllib.request.urlopen(req, timeout=10).read()


def soak(a, tmp):
    token = os.path.join(tmp, "token")
    with open(token, "w") as f:
        f.write("bench\n")
    # A kiosk file with small per-kiosk cache budgets: the caches reach their budget during the
    # warm-up, so growth after it is what the budgets do not cover (leaks, unbounded lists).
    kiosk = os.path.join(tmp, "kiosk.json")
    with open(kiosk, "w") as f:
        json.dump({"playlist": [{"scenario": os.path.abspath(DEMO), "duration": "300d"}],
                   "listen": "127.0.0.1:0", "tokenFile": token,
                   "budgets": {"cacheBytes": a.budget_mb << 20, "gpuBytes": a.budget_mb << 20}}, f)
    k = Kiosk(a.geokiosk, [kiosk, "--display", "headless", "--size", "64x36", "--frames",
                           str(a.frames)], gl_env(), os.path.join(tmp, "log"))
    k.wait_port()
    warm_at = max(int(a.frames * 0.4), min(a.reload * 2, a.frames // 2))
    next_reload, warm, last = a.reload, None, None
    started = time.monotonic()
    while k.proc.poll() is None:
        try:
            m = scrape(k.port)
        except OSError:
            break
        last = m
        frames = m["geokiosk_frames_total"] or 0
        if frames >= next_reload:
            post(k.port, "/control/reload", "bench")
            next_reload += a.reload
        if warm is None and frames >= warm_at:
            warm = m
        if frames >= a.frames - max(50, a.frames // 200):
            break  # the end: read RSS while the process is still there
        time.sleep(0.02)
    end = last
    elapsed = time.monotonic() - started
    k.proc.wait(timeout=120)
    rc = k.stop()
    growth = (end["geokiosk_resident_memory_bytes"] - warm["geokiosk_resident_memory_bytes"]) / 2**20
    result = {"benchmark": "kiosk_soak", "frames": int(end["geokiosk_frames_total"]),
              "size": "64x36", "reload_every": a.reload, "cache_budgets_mb": a.budget_mb,
              "reloads": int(end["geokiosk_reloads_total"]),
              "reload_failures": int(end["geokiosk_reload_failures_total"]),
              "baseline_rss_mb_after_warmup": round(warm["geokiosk_resident_memory_bytes"] / 2**20, 2),
              "warmup_frames": int(warm["geokiosk_frames_total"]),
              "rss_mb_at_end": round(end["geokiosk_resident_memory_bytes"] / 2**20, 2),
              "rss_growth_mb": round(growth, 2), "goal_growth_mb": 2.0,
              # malloc'd bytes still in use: tells a leak (grows) from fragmentation (flat)
              "heap_mb_after_warmup": round(warm["geokiosk_heap_in_use_bytes"] / 2**20, 2),
              "heap_mb_at_end": round(end["geokiosk_heap_in_use_bytes"] / 2**20, 2),
              "mean_frame_ms": round(end["geokiosk_frame_time_ms_sum"] /
                                     end["geokiosk_frame_time_ms_count"], 3),
              "wall_seconds": round(elapsed, 1), "exit": rc}
    print(json.dumps(result))
    if a.bound_mb is not None:
        ok = rc == 0 and growth < a.bound_mb and result["reloads"] >= 1 and \
            result["reload_failures"] == 0
        print("%s: RSS growth %.2f MB (bound %.1f MB), %d reloads, exit %s" %
              ("ok" if ok else "FAIL", growth, a.bound_mb, result["reloads"], rc))
        return 0 if ok else 1
    return 0


def restart(a, tmp):
    # Same-run baseline of what every start pays before geokiosk's own work: loading the
    # executable and its shared libraries (`geokiosk --version`), median of 5.
    import subprocess
    exec_only = []
    for _ in range(5):
        t0 = time.monotonic()
        subprocess.run([a.geokiosk, "--version"], stdout=subprocess.DEVNULL, check=True)
        exec_only.append(time.monotonic() - t0)
    notify = NotifySocket(tmp)
    env = gl_env()
    env["NOTIFY_SOCKET"] = notify.path
    times = []
    for i in range(6):
        t0 = time.monotonic()
        k = Kiosk(a.geokiosk, [DEMO, "--display", "headless", "--size", "640x360"], env,
                  os.path.join(tmp, "log%d" % i))
        seen = notify.wait_for("READY=1", 120)
        t1 = time.monotonic()
        if seen is None:
            print(json.dumps({"benchmark": "kiosk_restart", "error": "no READY",
                              "log": k.log_text()[-500:]}))
            return 1
        times.append(t1 - t0)
        k.proc.send_signal(signal.SIGKILL)  # the crash systemd restarts from
        k.proc.wait()
        k.log.close()
    print(json.dumps({"benchmark": "kiosk_restart", "size": "640x360",
                      "baseline_exec_version_s_median_of_5": round(statistics.median(exec_only), 3),
                      "cold_start_to_ready_s": round(times[0], 3),
                      "restart_to_ready_s_median_of_5": round(statistics.median(times[1:]), 3),
                      "restart_to_ready_s": [round(t, 3) for t in times[1:]]}))
    return 0


def thread_cpu_ns(pid, tid):
    """CPU time of one thread in nanoseconds (schedstat: time on CPU, ns resolution)."""
    with open("/proc/%d/task/%d/schedstat" % (pid, tid)) as f:
        return int(f.read().split()[0])


def process_threads_cpu_ns(pid, skip):
    """CPU time of every thread of `pid` except `skip` (the HTTP server, loader...)."""
    total = 0
    for tid in os.listdir("/proc/%d/task" % pid):
        if int(tid) != skip:
            try:
                total += thread_cpu_ns(pid, int(tid))
            except OSError:
                pass  # a thread that ended
    return total


def scrape_bench(a, tmp):
    """Interleaved A/B: short phases with and without 50 Hz scraping alternate (ABBA, so a drift
    of the machine's load cancels within each block); each adjacent pair gives a ratio and the
    figure is the median of those ratios. Two measures: wall time per frame (what a viewer
    sees; moved by whatever else the shared machine runs) and the CPU time of the render thread
    per frame (/proc schedstat of the main thread, llvmpipe rasterising on it: LP_NUM_THREADS=0),
    which is what scraping could add to the frame loop: the snapshot copy and the mutex."""
    env = dict(gl_env(), LP_NUM_THREADS="0")
    k = Kiosk(a.geokiosk, [DEMO, "--display", "headless", "--size", a.size, "--listen",
                           "127.0.0.1:0"], env, os.path.join(tmp, "log"))
    k.wait_port()
    pid = k.proc.pid
    time.sleep(3)  # warm-up: tiles of the tour start loading
    phases = {"none": [], "scrape_50hz": []}  # (wall ms/frame, render CPU ms/frame)
    other_cpu = {"none": 0, "scrape_50hz": 0}
    scrapes = {"none": 0, "scrape_50hz": 0}
    order = []
    for rnd in range(a.pairs // 2):
        order += ["none", "scrape_50hz", "scrape_50hz", "none"] if rnd % 2 == 0 else \
                 ["scrape_50hz", "none", "none", "scrape_50hz"]
    seconds = {"none": 0.0, "scrape_50hz": 0.0}
    measured = []  # (mode, (wall, cpu)) in phase order
    for mode in order:
        m0 = scrape(k.port)
        c0, o0, t0 = thread_cpu_ns(pid, pid), process_threads_cpu_ns(pid, pid), time.monotonic()
        stop = t0 + a.seconds
        i = 0
        while time.monotonic() < stop:
            if mode == "scrape_50hz":
                scrape(k.port)
                scrapes[mode] += 1
            i += 1
            # 50 Hz on a schedule (a slow round trip does not lower the rate), idle otherwise.
            time.sleep(max(0.0, t0 + i * 0.02 - time.monotonic()))
        c1, o1, t1 = thread_cpu_ns(pid, pid), process_threads_cpu_ns(pid, pid), time.monotonic()
        m1 = scrape(k.port)
        n = m1["geokiosk_frames_total"] - m0["geokiosk_frames_total"]
        wall = (m1["geokiosk_frame_time_ms_sum"] - m0["geokiosk_frame_time_ms_sum"]) / n
        phases[mode].append((wall, (c1 - c0) / 1e6 / n))
        measured.append((mode, phases[mode][-1]))
        other_cpu[mode] += o1 - o0
        seconds[mode] += t1 - t0
    k.stop()

    def ratios(index):
        # ABBA order: phases 2j and 2j+1 are adjacent and of opposite modes.
        out = []
        for j in range(0, len(measured) - 1, 2):
            (ma, va), (mb, vb) = measured[j], measured[j + 1]
            none, with_s = (va, vb) if ma == "none" else (vb, va)
            out.append(with_s[index] / none[index])
        return out

    wall_r, cpu_r = ratios(0), ratios(1)

    def q(vals, p):
        return statistics.quantiles(vals, n=4)[p] if len(vals) >= 4 else None

    def summary(index, vals):
        return {"baseline_no_scrape_median":
                round(statistics.median(v[index] for v in phases["none"]), 3),
                "scraped_50hz_median":
                round(statistics.median(v[index] for v in phases["scrape_50hz"]), 3),
                "median_change_percent": round(100 * (statistics.median(vals) - 1), 2),
                "q1_change_percent": round(100 * (q(vals, 0) - 1), 2),
                "q3_change_percent": round(100 * (q(vals, 2) - 1), 2),
                "pairs": len(vals)}

    print(json.dumps({"benchmark": "kiosk_scrape", "size": a.size,
                      "phase_seconds": a.seconds, "phases_each": len(order) // 2,
                      "order": "ABBA blocks, A = no scraping (the same-run baseline)",
                      "render_thread_cpu_ms_per_frame": summary(1, cpu_r),
                      "wall_ms_per_frame": summary(0, wall_r),
                      "scrapes_per_second": round(scrapes["scrape_50hz"] /
                                                  seconds["scrape_50hz"], 1),
                      "other_threads_cpu_percent": {
                          m: round(100 * other_cpu[m] / 1e9 / seconds[m], 1) for m in other_cpu},
                      "load_average": os.getloadavg()[0],
                      "goal_change_percent": 2.0}))
    return 0


def main():
    p = argparse.ArgumentParser()
    p.add_argument("which", choices=["soak", "restart", "scrape"])
    p.add_argument("geokiosk")
    p.add_argument("root")
    p.add_argument("--frames", type=int, default=1000000)
    p.add_argument("--reload", type=int, default=10000)
    p.add_argument("--bound-mb", type=float)
    p.add_argument("--seconds", type=float, default=1.0)
    p.add_argument("--pairs", type=int, default=120, help="scrape: A/B phase pairs (ABBA)")
    p.add_argument("--size", default="320x180", help="scrape: output size")
    p.add_argument("--budget-mb", type=int, default=16)
    a = p.parse_args()
    a.geokiosk = os.path.abspath(a.geokiosk)
    os.chdir(a.root)
    with temp_dir() as tmp:
        return {"soak": soak, "restart": restart, "scrape": scrape_bench}[a.which](a, tmp)


if __name__ == "__main__":
    sys.exit(main())
