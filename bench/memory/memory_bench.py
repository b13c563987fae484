#!/usr/bin/python3
"""Peak memory, frame rate and startup of the geokiosk process (issue 14).

Prints ONE JSON object per workload, each with the same workload measured in the same run on a
baseline binary (an older build, e.g. main's first commit) when --baseline is given:

  version      geokiosk --version
  validate     geokiosk validate of the demo
  flight_720p  play the demo headless at 1280x720 (camera tour, flood replay), --frames N
  flight_1080p the same at 1920x1080
  replay       render the demo's whole flood sequence at 1280x720 (frames to a folder)
  startup_1080p  process start to the first complete frame of the demo at 1920x1080 written
               (render --time +3h waits until every tile of the view is resident); warm: the
               median of 3 runs after one unmeasured run; cold (first_frame_cold_s): one run
               after the binary, its libraries, Mesa's driver and the demo store were dropped
               from the page cache (posix_fadvise DONTNEED: this process's files only, nothing
               machine-wide) with an empty Mesa shader cache. Both binaries read the same demo
               store (data/generated, made by tools/prepare-demo.sh with the current importer), so
               a gain from the store (e.g. stored mesh tiers) shows in both; compare stores with a
               scenario copy naming each store

Peak RSS is the kernel's ru_maxrss of the process; peak PSS is the largest Pss of
/proc/PID/smaps_rollup sampled every 20 ms (shared libraries counted by share). Frame rate is
frames / wall seconds of the whole play run, start-up included (the baseline binary has no
`play --stats`, so both are timed from outside the same way).

usage: memory_bench.py BUILD/geokiosk [--baseline OLD/geokiosk] [--frames N]
"""
import glob
import json
import os
import statistics
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
import procstat  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DEMO = os.path.join(ROOT, "scenarios/demo/rainier.json")
ENV = procstat.MESA_ENV


def measure(cmd):
    """Run cmd; return peak RSS/PSS (MB), wall seconds, exit status."""
    r = procstat.run(cmd, cwd=ROOT, env=ENV, sample=procstat.pss_kb)
    err = r["stderr"].strip()
    return {"peak_rss_mb": r["peak_rss_mb"],
            "peak_pss_mb": round((r["sampled_max"] or 0) / 1024.0, 1),
            "wall_s": round(r["wall_s"], 3),
            "exit": r["exit"],
            "stderr_tail": err.splitlines()[-1:] if err else []}


def workloads(binary, frames, tmp):
    play = [binary, "play", DEMO, "--display", "headless", "--frames", str(frames)]
    return {
        "version": [binary, "--version"],
        "validate": [binary, "validate", DEMO],
        "flight_720p": play + ["--size", "1280x720"],
        "flight_1080p": play + ["--size", "1920x1080"],
        "replay": [binary, "render", DEMO, "--out", os.path.join(tmp, "replay") + "/",
                   "--from", "+0", "--to", "+9h", "--fps", "1", "--size", "1280x720"],
        "startup_1080p": [binary, "render", DEMO, "--out", os.path.join(tmp, "first.png"),
                          "--time", "+3h", "--size", "1920x1080"],
    }


def files_of(binary):
    """The files a start-up reads: the binary, its libraries, Mesa's driver, the demo store."""
    out = subprocess.run(["ldd", binary], capture_output=True, text=True).stdout
    files = [binary, os.path.join(ROOT, "data/generated/rainier.gpkg")]
    files += [w for line in out.splitlines() for w in line.split() if w.startswith("/")]
    files += glob.glob("/usr/lib/*/dri/swrast_dri.so") + glob.glob("/usr/lib/*/libLLVM*.so*")
    files += glob.glob("/usr/lib/*/libEGL_mesa.so*") + glob.glob("/usr/lib/*/libglapi.so*")
    return [f for f in files if os.path.isfile(f)]


def measure_cold(binary, cmd):
    """One run with its files out of the page cache and an empty Mesa shader cache."""
    for f in files_of(binary):
        fd = os.open(f, os.O_RDONLY)
        try:
            os.posix_fadvise(fd, 0, 0, os.POSIX_FADV_DONTNEED)
        finally:
            os.close(fd)
    with tempfile.TemporaryDirectory() as cache:
        global ENV
        saved = ENV
        ENV = dict(saved, MESA_SHADER_CACHE_DIR=cache)
        try:
            return measure(cmd)
        finally:
            ENV = saved


def run(binary, name, cmd, frames):
    if name == "startup_1080p":
        cold = measure_cold(binary, cmd)
        measure(cmd)  # warm the page cache and Mesa's shader cache
        runs = [measure(cmd) for _ in range(3)]
        r = dict(runs[1])
        r["first_frame_s"] = round(statistics.median(x["wall_s"] for x in runs), 3)
        r["first_frame_cold_s"] = round(cold["wall_s"], 3)
        return r
    r = measure(cmd)
    if name.startswith("flight"):
        r["frames"] = frames
        r["fps"] = round(frames / r["wall_s"], 2) if r["wall_s"] > 0 else 0.0
    return r


GOALS = {"version": {"peak_rss_mb": 15}, "flight_1080p": {"peak_rss_mb": 150},
         "startup_1080p": {"first_frame_s": 0.5}}


def main():
    args = sys.argv[1:]
    if not args:
        print(__doc__, file=sys.stderr)
        return 2
    binary = os.path.abspath(args[0])
    baseline = None
    frames = 120
    if "--baseline" in args:
        baseline = os.path.abspath(args[args.index("--baseline") + 1])
    if "--frames" in args:
        frames = int(args[args.index("--frames") + 1])
    only = None
    if "--only" in args:
        only = args[args.index("--only") + 1].split(",")
    with tempfile.TemporaryDirectory() as tmp:
        new = workloads(binary, frames, tmp)
        old = workloads(baseline, frames, tmp) if baseline else {}
        for name, cmd in new.items():
            if only and name not in only:
                continue
            # Alternate after/baseline per workload so machine load hits both alike.
            out = {"benchmark": "memory", "workload": name, "binary": binary}
            out.update(run(binary, name, cmd, frames))
            if baseline:
                out["baseline"] = dict(binary=baseline, **run(baseline, name, old[name], frames))
            else:
                out["baseline"] = "none (pass --baseline OLD/geokiosk)"
            if name in GOALS:
                out["goal"] = GOALS[name]
            print(json.dumps(out), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
