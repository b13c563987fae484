#!/usr/bin/python3
"""Local TINs in the grid (issue 20, Baumann et al. 2000): what they cost.

    bench/tins/tins_bench.py BUILD [--dir DIR] [--frames N] [--keep]

Two cases, each against its own grid-only store as the baseline of the same run:
  levee  -- a SYNTHETIC 1 m DEM (1920 x 1600 posts) with a sharp levee along a diagonal and its
            crest as a 3D GeoJSON line (`import breaklines`);
  cairns -- ../shared/data/anuga_sww_flood_timeseries/cairns.sww: `import elevation` of the bed,
            then `import model-mesh` of the same file (the model's own triangles).
Per case: import wall time and peak RSS of the TIN import, store size with and without the TINs,
TIN tiles and their triangles against the stored grid meshes of the same tiles (tier 0), and
bench-frame (--no-fullres, 1280x720) over the TIN store and the grid-only store, alternating,
best of two each. Prints one JSON object on stdout; progress on stderr.
"""
import argparse
import json
import os
import shutil
import sqlite3
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
from osgeo import gdal, osr

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
import procstat  # noqa: E402
X0, Y1 = 550000.0, 5200000.0
W, H = 1920, 1600
A = (X0 + 240.3, Y1 - 282.7)
B = (X0 + 1680.2, Y1 - 1323.9)


def measured(argv):
    """An import: wall seconds and its own peak RSS (procstat)."""
    r = procstat.run(argv)
    if r["exit"] != 0:
        sys.exit(f"tins_bench: {' '.join(map(str, argv))} exited {r['exit']}:\n{r['stderr'][-2000:]}")
    return {"seconds": round(r["wall_s"], 3), "peak_rss_mb": r["peak_rss_mb"]}


def json_of(argv):
    """A benchmark's one JSON object (stdout)."""
    p = subprocess.run([str(a) for a in argv], env=procstat.MESA_ENV, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"tins_bench: {' '.join(map(str, argv))} exited {p.returncode}:\n{p.stderr[-2000:]}")
    return json.loads(p.stdout)


def ground(x, y):
    return 20.0 + 0.01 * (x - X0) + 0.005 * (Y1 - y)


def levee_inputs(d):
    xs = X0 + np.arange(W) + 0.5
    ys = Y1 - np.arange(H) - 0.5
    x, y = np.meshgrid(xs, ys)
    dx, dy = B[0] - A[0], B[1] - A[1]
    t = np.clip(((x - A[0]) * dx + (y - A[1]) * dy) / (dx * dx + dy * dy), 0, 1)
    dist = np.hypot(x - (A[0] + t * dx), y - (A[1] + t * dy))
    z = ground(x, y) + 3.0 * np.maximum(0.0, 1.0 - dist / 5.0)
    drv = gdal.GetDriverByName("GTiff")
    ds = drv.Create(str(d / "levee.tif"), W, H, 1, gdal.GDT_Float32)
    ds.SetGeoTransform((X0, 1.0, 0.0, Y1, 0.0, -1.0))
    srs = osr.SpatialReference()
    srs.ImportFromEPSG(32610)
    ds.SetProjection(srs.ExportToWkt())
    ds.GetRasterBand(1).WriteArray(z.astype(np.float32))
    ds = None
    line = {"type": "FeatureCollection",
            "crs": {"type": "name", "properties": {"name": "urn:ogc:def:crs:EPSG::32610"}},
            "features": [{"type": "Feature", "properties": {}, "geometry": {
                "type": "LineString",
                "coordinates": [[A[0], A[1], ground(*A) + 3.0], [B[0], B[1], ground(*B) + 3.0]]}}]}
    (d / "crest.geojson").write_text(json.dumps(line))
    return d / "levee.tif", d / "crest.geojson"


def scenario(path, store):
    path.write_text(json.dumps({"version": 1, "title": "TIN benchmark", "stores": {"s": str(store)},
                                "terrain": {"store": "s", "tauGeom": 1, "tauTex": 1}, "layers": []}))


def tin_figures(store):
    db = sqlite3.connect(store)
    rows = db.execute(
        "SELECT t.zoom_level, t.triangle_count, t.vertex_count, length(t.tin), t.max_error, "
        "(SELECT m.triangle_count FROM kiosk_tile_meshes m WHERE m.table_name = t.table_name AND "
        "m.zoom_level = t.zoom_level AND m.tile_column = t.tile_column AND m.tile_row = t.tile_row "
        "AND m.tier = 0) FROM kiosk_tile_tins t").fetchall()
    db.close()
    return {
        "tin_tiles": len(rows),
        "levels": sorted({r[0] for r in rows}),
        "tin_triangles": sum(r[1] for r in rows),
        "grid_triangles_same_tiles": sum(r[5] or 0 for r in rows),
        "per_tile": [{"level": r[0], "tin_triangles": r[1], "grid_triangles": r[5],
                      "tin_bytes": r[3], "max_error_m": round(r[4], 4)} for r in rows],
        "tin_blob_bytes": sum(r[3] for r in rows),
    }


def frames(build, d, name, n):
    best = {}
    for _ in range(2):
        for variant in ("tin", "grid"):
            j = json_of([build / "bench" / "bench-frame", d / f"{name}-{variant}.json",
                         "--sizes", "1280x720", "--frames", str(n), "--no-fullres"])
            r = j["results"][0]
            cur = best.get(variant)
            if cur is None or r["frame_ms"]["p50"] < cur["frame_ms"]["p50"]:
                best[variant] = {"frame_ms": r["frame_ms"], "triangles_mean": r["triangles_mean"],
                                 "tiles_mean": r["tiles_mean"]}
    return best


def case(build, d, name, elevation_src, tin_args, n):
    gk = str(build / "geokiosk")
    grid, tin = d / f"{name}-grid.gpkg", d / f"{name}-tin.gpkg"
    print(f"tins_bench: {name}: import elevation", file=sys.stderr)
    measured([gk, "import", "elevation", str(elevation_src), "--store", str(grid), "--quiet"])
    shutil.copy(grid, tin)
    print(f"tins_bench: {name}: import {tin_args[0]}", file=sys.stderr)
    imp = measured([gk, "import", *tin_args, "--store", str(tin), "--quiet"])
    scenario(d / f"{name}-tin.json", tin)
    scenario(d / f"{name}-grid.json", grid)
    out = {"tin_import": imp, "store_bytes": tin.stat().st_size,
           "store_bytes_without_tins": grid.stat().st_size}
    out.update(tin_figures(tin))
    print(f"tins_bench: {name}: frames", file=sys.stderr)
    out["frames"] = frames(build, d, name, n)
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("build")
    ap.add_argument("--dir")
    ap.add_argument("--frames", type=int, default=40)
    ap.add_argument("--keep", action="store_true")
    a = ap.parse_args()
    build = Path(a.build).resolve()
    d = Path(a.dir or tempfile.mkdtemp(prefix="kiosk-tins-bench-"))
    d.mkdir(parents=True, exist_ok=True)
    result = {"benchmark": "local_tins", "frames": a.frames, "size": "1280x720"}
    dem, crest = levee_inputs(d)
    result["levee"] = case(build, d, "levee", dem, ["breaklines", str(crest)], a.frames)
    sww = Path(__file__).resolve().parents[2] / ".." / "shared" / "data" / "anuga_sww_flood_timeseries" / "cairns.sww"
    if sww.exists():
        result["cairns"] = case(build, d, "cairns", sww, ["model-mesh", str(sww)], a.frames)
    else:
        result["cairns"] = {"skipped": "../shared/data not present"}
    if not a.keep:
        shutil.rmtree(d, ignore_errors=True)
    print(json.dumps(result))


if __name__ == "__main__":
    main()
