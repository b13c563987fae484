#!/usr/bin/python3
"""Corrupt stores through `info --check`, `info --check --deep` and `render`.

A small store is imported here (elevation with stored meshes, a normal map, a two-frame
sequence), then each case changes a copy of it with SQL or by zeroing pages at their file
offsets. Every case keeps its expected outcome: the text each command prints (in one line for
the checks) and render's exit status; render exits 0 only when it draws the picture without the
bad tiles and names them (DEGRADED). No corrupt store may pass a check in silence.

    store_corpus.py GEOKIOSK

Prints one line per run and exits non-zero on any failure (CORPUS_ONLY=NAME runs one case).
"""
import json
import math
import os
import shutil
import sqlite3
import struct
import subprocess
import sys
import tempfile
import zlib

GK = os.path.abspath(sys.argv[1])
TMP = tempfile.mkdtemp(prefix="kiosk-stores-")
SIZE = 300  # posts of the elevation grid: two levels of 256-pixel tiles
CELL = 30.0


def asc(path, value):
    """An ESRI ASCII grid without a CRS (local metres) of SIZE x SIZE cells."""
    with open(path, "w") as f:
        f.write("ncols %d\nnrows %d\nxllcorner 0\nyllcorner 0\ncellsize %g\n"
                "NODATA_value -9999\n" % (SIZE, SIZE, CELL))
        for y in range(SIZE):
            f.write(" ".join("%.2f" % value(x, y) for x in range(SIZE)) + "\n")


def hill(x, y):
    return 400.0 + 300.0 * math.exp(-((x - 150) ** 2 + (y - 150) ** 2) / 4000.0)


def run(args, cwd=None):
    p = subprocess.run([GK] + args, capture_output=True, text=True, cwd=cwd, timeout=300)
    return p.returncode, p.stdout, p.stderr


def build_store():
    src = os.path.join(TMP, "src")
    os.makedirs(src)
    asc(os.path.join(src, "dem.asc"), hill)
    for i in range(2):
        asc(os.path.join(src, "depth_%d.asc" % i),
            lambda x, y, i=i: max(0.0, 470.0 + 40 * i - hill(x, y)))
    store = os.path.join(TMP, "base.gpkg")
    steps = [["import", "elevation", os.path.join(src, "dem.asc"), "--store", store, "--quiet"],
             ["import", "topographic", "--normals", "--store", store, "--quiet"],
             ["import", "sequence", os.path.join(src, "depth_0.asc"),
              os.path.join(src, "depth_1.asc"), "--store", store, "--name", "depth",
              "--start", "2026-03-14T00:00:00Z", "--step", "3600", "--units", "m", "--quiet"]]
    for args in steps:
        code, out, err = run(args)
        if code != 0:
            sys.exit("cannot build the base store: %s -> %d\n%s" % (" ".join(args), code, err))
    return store


SCENARIO = {
    "version": 1,
    "stores": {"s": "s.gpkg"},
    "terrain": {"store": "s", "elevation": "elevation"},
    "transferFunctions": {
        "relief": {"stops": [{"value": 400, "color": "#3f7f4f"},
                             {"value": 700, "color": "#e8e8e8"}]},
        "depth": {"stops": [{"value": 0, "color": "#c6ecf5"}, {"value": 120, "color": "#08306b"}],
                  "nodata": "transparent"}},
    "layers": [
        {"id": "relief", "kind": "data", "source": {"store": "s", "layer": "elevation"},
         "transfer": "relief"},
        {"id": "shade", "kind": "normals", "source": {"store": "s", "layer": "normals"},
         "operation": "modulate"},
        {"id": "flood", "kind": "sequence", "source": {"store": "s", "sequence": "depth"},
         "transfer": "depth"}],
    "clock": {"start": "2026-03-14T00:00:00Z", "end": "2026-03-14T01:00:00Z"},
    "viewpoints": {"top": {"target": [4500, 4500, 400], "heading": 0, "pitch": -60,
                           "range": 12000}},
    "camera": {"viewpoint": "top"},
}


def png(width, height, bit_depth, colour_type):
    """A valid PNG of zeros."""
    def chunk(kind, data):
        return (struct.pack(">I", len(data)) + kind + data +
                struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF))
    channels = {0: 1, 2: 3, 4: 2, 6: 4}[colour_type]
    row = b"\0" + bytes(width * channels * bit_depth // 8)
    ihdr = struct.pack(">IIBBBBB", width, height, bit_depth, colour_type, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) +
            chunk(b"IDAT", zlib.compress(row * height, 9)) + chunk(b"IEND", b""))


def sql(*statements, blob=None):
    def change(path):
        db = sqlite3.connect(path)
        for s in statements:
            db.execute(s, (blob,) if "?" in s else ())
        db.commit()
        db.close()
    return change


def page(table, kind, damage="zero"):
    """Damage one page of `table` whose dbstat type is `kind` ('leaf', 'internal', 'overflow';
    'chain': an overflow page with a successor, 'tail': the last of a chain), at its offset in
    the file: zeroed, or (damage 'header') its b-tree page header overwritten."""
    def change(path):
        db = sqlite3.connect(path)
        size = db.execute("PRAGMA page_size").fetchone()[0]
        rows = db.execute("SELECT pageno, path FROM dbstat WHERE name = ? AND pagetype = ? "
                          "ORDER BY pageno", (table, "overflow" if kind in ("chain", "tail")
                                                 else kind)).fetchall()
        db.close()
        if kind in ("chain", "tail"):
            # dbstat's path of overflow page k of a cell is "<cell path>+k" (k from 0).
            paths = {p for _, p in rows}
            def successor(p):
                cell, k = p.rsplit("+", 1)
                return "%s+%06x" % (cell, int(k, 16) + 1)
            rows = [r for r in rows if (successor(r[1]) in paths) == (kind == "chain")]
        if not rows:
            raise RuntimeError("no %s page of %s" % (kind, table))
        number = rows[len(rows) // 2][0]
        with open(path, "r+b") as f:
            f.seek((number - 1) * size)
            if damage == "zero":
                f.write(bytes(size))
            else:  # page type 0x42 is none of SQLite's, the cell count 0xFFFF beyond the page
                f.write(b"\x42\x00\x00\xff\xff")
    return change


ANY = "any"  # render exit 0 without a word is right: it reads none of the damage

# (name, change, expected `info --check` text or None when only --deep sees it, expected
#  `info --check --deep` text, expected `render` text, render exit status)
CASES = [
    ("unchanged", sql(), "", "", "", 0),
    # Silently wrong pictures.
    ("grey8-in-normals", sql("UPDATE normals SET tile_data = ? WHERE zoom_level = 0",
                             blob=png(256, 256, 8, 0)),
     None, "normals/0/0/0: tile is a 8-bit grey PNG; this table holds 8-bit RGB or RGBA PNGs "
     "(a normal map) [STORE_TILE_FORMAT]", "normals/0/0/0: tile is a 8-bit grey PNG", 0),
    ("stats-min-renamed", sql("ALTER TABLE kiosk_tile_stats RENAME COLUMN min_value TO minimum"),
     "kiosk_tile_stats: column min_value is missing", "kiosk_tile_stats: column min_value is "
     "missing", "kiosk_tile_stats: column min_value is missing", 1),
    ("stats-min-retyped", sql("ALTER TABLE kiosk_tile_stats RENAME COLUMN min_value TO m",
                              "ALTER TABLE kiosk_tile_stats ADD COLUMN min_value TEXT"),
     "kiosk_tile_stats: column min_value is declared TEXT; the store format has DOUBLE",
     "column min_value is declared TEXT", "column min_value is declared TEXT", 1),
    # Unreadable pages and columns.
    # Unreadable pages. The view draws the smooth hill's elevation from level 0 (its geometric
    # error allows it), so render never reads the damaged elevation and mesh pages: its picture
    # is right and it may say nothing (ANY); the normal map's level 1 it does read.
    ("mesh-chain-zeroed", page("kiosk_tile_meshes", "chain"), None,
     "SQLite quick_check: ", "", ANY),
    ("mesh-chain-tail-zeroed", page("kiosk_tile_meshes", "tail"), None,
     "[STORE_MESH_CORRUPT]", "", ANY),
    ("tile-leaf-zeroed", page("elevation", "leaf"), None,
     "elevation: cannot read row 4 (after 3 rows): database disk image is malformed "
     "[STORE_CORRUPT]", "", ANY),
    ("normals-leaf-zeroed", page("normals", "leaf"), None, "normals: cannot read row ",
     "normals/1/0/1: cannot read tile: database disk image is malformed [STORE_TILE_CORRUPT]", 0),
    ("tile-btree-header", page("elevation", "leaf", "header"), None,
     "elevation: cannot read row ", "", ANY),
    ("tile-data-renamed", sql("ALTER TABLE elevation RENAME COLUMN tile_data TO data"),
     "elevation: column tile_data is missing", "elevation: column tile_data is missing",
     "elevation: column tile_data is missing", 1),
    # Damaged metadata values.
    ("tms-extent-nan", sql("UPDATE gpkg_tile_matrix_set SET min_x = 'NaN' WHERE table_name = "
                           "'elevation'"),
     "gpkg_tile_matrix_set/elevation: min_x is text 'NaN', not a number", "", "", 1),
    ("tms-extent-1e308", sql("UPDATE gpkg_tile_matrix_set SET max_y = 1e308"),
     "gpkg_tile_matrix_set/", "", "", 1),
    ("matrix-width-0", sql("UPDATE gpkg_tile_matrix SET matrix_width = 0 WHERE zoom_level = 1"),
     "gpkg_tile_matrix/", "", "", 1),
    ("matrix-width-1e9", sql("UPDATE gpkg_tile_matrix SET matrix_width = 1000000000 WHERE "
                             "table_name = 'normals' AND zoom_level = 1"),
     "gpkg_tile_matrix/normals/1: wants matrix_width = matrix_height = 2^zoom_level", "", "", 1),
    ("pixel-size-nan", sql("UPDATE gpkg_tile_matrix SET pixel_y_size = 'NaN' WHERE "
                           "table_name = 'elevation' AND zoom_level = 0"),
     "gpkg_tile_matrix/elevation/0: pixel_y_size is text 'NaN'", "", "", 1),
    ("zoom-negative", sql("UPDATE gpkg_tile_matrix SET zoom_level = -1 WHERE zoom_level = 0 AND "
                          "table_name = 'elevation'"),
     "gpkg_tile_matrix/elevation/-1: zoom_level is -1", "", "", 1),
    ("coverage-scale-nan", sql("UPDATE gpkg_2d_gridded_coverage_ancillary SET scale = 'NaN' "
                               "WHERE tile_matrix_set_name = 'elevation'"),
     "gpkg_2d_gridded_coverage_ancillary/elevation: scale is text 'NaN'", "", "", 1),
    ("coverage-offset-1e308", sql("UPDATE gpkg_2d_gridded_coverage_ancillary SET offset = 1e308"),
     "offset is 1e+308", "", "", 1),
    ("tile-scale-nan", sql("UPDATE gpkg_2d_gridded_tile_ancillary SET scale = 'NaN' WHERE id = "
                           "(SELECT min(id) FROM gpkg_2d_gridded_tile_ancillary)"),
     "scale is text 'NaN', not a number", "", "", 1),
    ("tile-offset-1e308", sql("UPDATE gpkg_2d_gridded_tile_ancillary SET offset = 1e308"),
     "offset is 1e+308", "", "", 1),
    ("stats-min-nan", sql("UPDATE kiosk_tile_stats SET min_value = 'NaN' WHERE zoom_level = 0"),
     "kiosk_tile_stats/", "", "", 1),
    ("stats-max-nan", sql("UPDATE kiosk_tile_stats SET max_value = 'NaN' WHERE table_name = "
                          "'elevation' AND zoom_level = 1 AND tile_column = 1 AND tile_row = 1"),
     "kiosk_tile_stats/elevation/1/1/1: max_value is text 'NaN'", "", "", 1),
    ("geometric-error-nan", sql("UPDATE kiosk_tile_stats SET geometric_error = 'NaN' WHERE "
                                "table_name = 'elevation' AND zoom_level = 0"),
     "kiosk_tile_stats/elevation/0/0/0: geometric_error is text 'NaN'", "", "", 1),
    ("border-posts-truncated", sql("UPDATE kiosk_tile_stats SET border_posts = "
                                   "substr(border_posts, 1, 100) WHERE table_name = 'elevation' "
                                   "AND zoom_level = 1 AND tile_column = 0 AND tile_row = 0"),
     "kiosk_tile_stats/elevation/1/0/0: wants border_posts of 2052 bytes", "", "", 1),
    ("grid-extent-inf", sql("UPDATE kiosk_grid SET max_x = 1e999"),
     "kiosk_grid/grid: max_x is inf", "", "", 1),
    ("layers-row-deleted", sql("DELETE FROM kiosk_layers WHERE table_name = 'normals'"),
     "normals: tile table on the store's grid has no kiosk_layers row", "", "", 1),
]


def check_run(label, args, cwd, expected, want_exit, one_line):
    code, out, err = run(args, cwd)
    problems = []
    lines = err.splitlines()
    if want_exit not in (None, ANY) and code != want_exit:
        problems.append("exit %d, want %d" % (code, want_exit))
    if want_exit in (None, ANY) and code not in (0, 1):
        problems.append("exit %d, want 0 or 1" % code)
    if expected and expected not in err:
        problems.append("missing %r" % expected)
    if one_line and code != 0 and len(lines) != 1:
        problems.append("%d lines on stderr, want 1" % len(lines))
    if not expected and want_exit == 0 and any(not l.startswith("render: wrote") for l in lines):
        problems.append("a valid store should give no message")
    if code == 0 and args[0] == "render" and want_exit not in (0, ANY) and not any(
            "s.gpkg" in l for l in lines):
        problems.append("exit 0 in silence")
    if code == 0 and args[0] == "render" and want_exit == 0 and expected and (
            "DEGRADED" not in err):
        problems.append("the damaged tile is not reported DEGRADED")
    for line in lines:
        if ("s.gpkg" not in line and not line.startswith("main.json:") and
                not line.startswith("render: wrote")):
            problems.append("line names no store or scenario: %r" % line[:120])
    if problems:
        print("FAIL: %s: %s\n    %s" % (label, "; ".join(problems), err[:600].rstrip()))
        return False
    print("ok:   %s" % label)
    return True


def main():
    base = build_store()
    only = os.environ.get("CORPUS_ONLY")
    results = []
    for name, change, expect_check, expect_deep, expect_render, render_exit in CASES:
        if only and name != only:
            continue
        folder = os.path.join(TMP, name)
        os.makedirs(folder)
        store = os.path.join(folder, "s.gpkg")
        shutil.copy(base, store)
        change(store)
        with open(os.path.join(folder, "main.json"), "w") as f:
            json.dump(SCENARIO, f, indent=1)
        healthy = name == "unchanged"
        # --check alone: the cases it must see fail in one line; for the deep-only ones it may
        # or may not come upon the damage.
        check_exit = 0 if healthy else None if expect_check is None else 1
        results.append(check_run("info --check %s" % name, ["info", store, "--check"], folder,
                                 expect_check or "", check_exit, True))
        deep = expect_deep or expect_check
        results.append(check_run("info --check --deep %s" % name,
                                 ["info", store, "--check", "--deep"], folder, deep,
                                 0 if healthy else 1, True))
        render = expect_render or (expect_check if render_exit == 1 else "")
        results.append(check_run("render %s" % name,
                                 ["render", "main.json", "--size", "640x360", "--out",
                                  os.path.join(folder, "out.png")], folder, render, render_exit,
                                 False))
    shutil.rmtree(TMP, ignore_errors=True)
    failures = results.count(False)
    print("%d passed, %d failed" % (results.count(True), failures))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
