#!/usr/bin/python3
"""Out-of-core terrain at the seed paper's scale (Wahl et al. 2004 fly 16k x 16k grids).

    bench/outofcore/outofcore_bench.py BUILD [--dir DIR] [--sizes 4096,16384] [--frames N]
                                             [--size WxH] [--keep]

For each size: a SYNTHETIC DEM (BUILD/make-synthetic-dem, 10 m posts, the same relief scale at
every size), `geokiosk import elevation` (wall time, peak RSS, store size; only when the store is
made), the time to the first complete frame (`render` of an overview and of each flight's first
view: process start to PNG written, all tiles loaded), and two low flights (`play --display
headless --max-fps 30 --stats`; the cap only paces the cheap frames drawn before the first tiles
arrive): "ground" looks 35 degrees down (the same content at every size), "horizon" 15 degrees
down (the 16k grid fills the view for tens of kilometres). Per flight: frame times, triangles,
peak RSS, resident tile bytes against the cache budgets the runtime chose. The 4k run is
the baseline of the same run. Prints one JSON object on stdout; progress on stderr.
"""
import argparse
import json
import os
import statistics
import sys
from pathlib import Path

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
import procstat  # noqa: E402

ENV = procstat.MESA_ENV
POST = 10.0
WEST, NORTH = 500000.0, 5300000.0


def run(argv, cwd=None):
    """Run one process; wall seconds and its own peak RSS (MB) from wait4."""
    r = procstat.run(argv, cwd=cwd, env=ENV)
    if r["exit"] != 0:
        sys.exit(f"outofcore_bench: {' '.join(map(str, argv))} exited {r['exit']}:\n{r['stderr'][-2000:]}")
    return {"seconds": round(r["wall_s"], 3), "peak_rss_mb": r["peak_rss_mb"]}


def scenario(store, n, pitch):
    """Terrain coloured by elevation; an overview of the whole grid and a low flight that starts
    at the centre and flies 20 km south-east at 2 km range, `pitch` degrees below the horizon."""
    w = n * POST
    cx, cy = WEST + w / 2, NORTH - w / 2
    d = 20000 / 2 ** 0.5
    return {
        "version": 1,
        "title": f"SYNTHETIC {n}x{n} DEM (out-of-core benchmark)",
        "stores": {"dem": str(store)},
        "terrain": {"store": "dem", "elevation": "elevation", "tauGeom": 2, "tauTex": 1},
        "transferFunctions": {"relief": {"label": "Elevation", "units": "m", "stops": [
            {"value": -500, "color": "#3f7f4f"}, {"value": 1500, "color": "#c9b98a"},
            {"value": 3000, "color": "#9c8a78"}, {"value": 4600, "color": "#ffffff"}]}},
        "layers": [{"id": "relief", "kind": "data",
                    "source": {"store": "dem", "layer": "elevation"}, "transfer": "relief"}],
        "clock": {"start": "2026-01-01T00:00:00Z", "end": "2026-01-01T01:00:00Z",
                  "rate": 120, "range": "loop"},
        "viewpoints": {
            "overview": {"target": [cx, cy, 2000], "heading": 20, "pitch": -45, "range": 1.4 * w},
            "low_start": {"target": [cx, cy, 2000], "heading": 135, "pitch": pitch,
                          "range": 2000},
            "low_end": {"target": [cx + d, cy - d, 2000], "heading": 135, "pitch": pitch,
                        "range": 2000},
        },
        "cameraPaths": {"flight": {"interpolation": "linear", "keys": [
            {"time": "+0s", "viewpoint": "low_start"}, {"time": "+1h", "viewpoint": "low_end"}]}},
        "camera": {"viewpoint": "low_start", "path": "flight"},
    }


# "ground": 35 degrees down, the view ends about 6 km ahead, inside the 4k grid all along the
# path, so both sizes draw the same kind of content. "horizon": 15 degrees down, the 16k grid
# fills the view out to tens of kilometres (the 4k grid ends inside the view).
FLIGHTS = {"ground": -35, "horizon": -15}


def flight(gk, scen, stats, a):
    r = run([gk, "play", scen, "--display", "headless", "--size", a.size,
             "--frames", str(a.frames), "--max-fps", "30", "--stats", stats])
    j = json.loads(stats.read_text())
    f, b = j["frames"], j["budgets"]
    # play draws from the first frame on, with nothing until the first tiles arrive (no
    # waitForData): frame times count only frames that drew terrain.
    drawn = [i for i, t in enumerate(f["tiles_drawn"]) if t > 0]
    if not drawn:
        sys.exit(f"outofcore_bench: {scen} drew no terrain in {a.frames} frames")
    ms = [f["frame_ms"][i] for i in drawn]
    budget = b["cache_cpu_bytes"] + b["cache_gpu_bytes"]
    r.update({
        "frames_drawn": len(drawn),
        "first_drawn_frame_after_ms": round(sum(f["frame_ms"][:drawn[0]]), 1),
        "frame_ms_median": round(statistics.median(ms), 1),
        "frame_ms_p95": round(sorted(ms)[int(0.95 * (len(ms) - 1))], 1),
        "fps_median": round(1000.0 / statistics.median(ms), 2),
        "tiles_drawn_median": statistics.median(f["tiles_drawn"][i] for i in drawn),
        "tiles_from_ancestor_median": statistics.median(f["tiles_from_ancestor"][i] for i in drawn),
        "triangles_median": statistics.median(f["triangles"][i] for i in drawn),
        "triangles_max": max(f["triangles"]),
        "held_frames": j["summary"].get("held_frames", 0),
        "resident_mb_max": round(max(f["resident_bytes"]) / 2**20, 1),
        "cache_budget_mb": round(budget / 2**20, 1),
        "within_cache_budget": max(f["resident_bytes"]) <= budget,
    })
    return r


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("build")
    ap.add_argument("--dir", default="/tmp/geokiosk-bench-outofcore")
    ap.add_argument("--sizes", default="4096,16384")
    ap.add_argument("--frames", type=int, default=200)
    ap.add_argument("--size", default="1920x1080")
    ap.add_argument("--keep", action="store_true", help="keep DEMs and stores for the next run")
    a = ap.parse_args()
    build = Path(a.build).resolve()
    gk, maker = build / "geokiosk", build / "make-synthetic-dem"
    work = Path(a.dir)
    work.mkdir(parents=True, exist_ok=True)
    out = {"benchmark": "outofcore", "view": a.size, "frames": a.frames,
           "cores": os.cpu_count(), "load_at_start": os.getloadavg()[0], "runs": []}
    for n in (int(s) for s in a.sizes.split(",")):
        dem, store = work / f"dem_{n}.tif", work / f"s_{n}.gpkg"
        r = {"size": n, "source_mb": round(n * n * 4 / 1e6, 1)}
        if not dem.exists():
            print(f"outofcore_bench: {n}^2 DEM", file=sys.stderr)
            r["make_dem"] = run([maker, str(n), dem])
        if not store.exists():
            print(f"outofcore_bench: import {n}^2", file=sys.stderr)
            r["import"] = run([gk, "import", "elevation", dem, "--store", store, "--quiet"])
        r["store_mb"] = round(store.stat().st_size / 1e6, 1)
        first, r["flight"] = {}, {}
        for name, pitch in FLIGHTS.items():
            scen = work / f"flight_{n}_{name}.json"
            scen.write_text(json.dumps(scenario(store, n, pitch), indent=1))
            print(f"outofcore_bench: first frame {n}^2 overview/{name}", file=sys.stderr)
            if name == "ground":
                first["overview"] = run([gk, "render", scen, "--out", work / f"first_{n}_overview.png",
                                         "--time", "+0", "--viewpoint", "overview", "--size",
                                         a.size, "--quiet"])
            first[name] = run([gk, "render", scen, "--out", work / f"first_{n}_{name}.png",
                               "--time", "+0", "--viewpoint", "low_start", "--size", a.size,
                               "--quiet"])
            print(f"outofcore_bench: {name} flight {n}^2", file=sys.stderr)
            r["flight"][name] = flight(gk, scen, work / f"flight_{n}_{name}.stats.json", a)
        r["first_complete_frame"] = first
        out["runs"].append(r)
        if not a.keep:
            for p in (dem, store):
                p.unlink(missing_ok=True)
    if len(out["runs"]) >= 2:
        base, big = out["runs"][0], out["runs"][-1]
        ratio = {"data": (big["size"] / base["size"]) ** 2}
        for k in ("overview", *FLIGHTS):
            ratio[f"first_frame_{k}"] = round(big["first_complete_frame"][k]["seconds"] /
                                              base["first_complete_frame"][k]["seconds"], 2)
        for k in FLIGHTS:
            for m in ("peak_rss_mb", "frame_ms_median", "triangles_median"):
                ratio[f"{k}_flight_{m}"] = round(big["flight"][k][m] / base["flight"][k][m], 2)
        out["ratios_largest_vs_smallest"] = ratio
    out["load_at_end"] = os.getloadavg()[0]
    print(json.dumps(out))


if __name__ == "__main__":
    main()
