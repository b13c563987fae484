#!/usr/bin/python3
"""Hostile and careless input through `geokiosk validate` and `geokiosk render` (issue 13).

Each case is written into a fresh folder, then run through validate and render. Every run must
exit 1 with exactly one line on stderr that names the culprit (file:line:col + JSON pointer, or
the store and tile) and contains the expected text kept with the case, within 5 s and 300 MB.

    corpus.py GEOKIOSK [DEMO_STORE]

DEMO_STORE (data/generated/rainier.gpkg) enables the cases that need a real store; without it
they are reported as skipped. Prints one line per run and exits non-zero on any failure.
"""
import json
import os
import shutil
import sqlite3
import struct
import subprocess
import sys
import tempfile
import time
import zlib

# CPU seconds (user + system) of the run: wall time on a shared CI machine measures the other
# jobs; a run that sleeps or blocks is caught by MAX_WALL_SECONDS.
MAX_SECONDS = 5.0
MAX_WALL_SECONDS = 60.0
MAX_RSS_MB = 300.0

GK = os.path.abspath(sys.argv[1])
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
STORE = os.path.abspath(sys.argv[2]) if len(sys.argv) > 2 and os.path.isfile(sys.argv[2]) else None


def base(**extra):
    """A scenario that is valid apart from what `extra` replaces (store s.gpkg next to it)."""
    doc = {"version": 1, "stores": {"s": "s.gpkg"}, "terrain": {"store": "s"},
           "layers": [{"id": "relief", "kind": "topographic",
                       "source": {"store": "s", "layer": "hillshade"}}]}
    doc.update(extra)
    return doc


def write(folder, name, content):
    path = os.path.join(folder, name)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    mode = "wb" if isinstance(content, bytes) else "w"
    with open(path, mode) as f:
        if isinstance(content, (dict, list)):
            json.dump(content, f, indent=1)
        else:
            f.write(content)
    return path


def lens(i):
    return {"id": "l%d" % i, "kind": "highlight", "center": [0, 0], "radius": 100}


def mapping(i):
    return {"id": "m%d" % i, "origin": [0, 0, 0], "u": [1, 0, 0], "v": [0, 1, 0],
            "image": "a.png"}


# --- the cases: (name, builder(folder) -> scenario path, expected text, needs store) ---------

def include_bomb(d):
    # Ten includes per level, six levels: 10^6 loads without a limit.
    for level in range(6):
        nxt = ["b%d.json" % (level + 1)] * 10 if level < 5 else []
        write(d, "b%d.json" % level, {"include": nxt, "title": "level %d" % level})
    return write(d, "main.json", base(include=["b0.json"] * 10))


def include_deep(d):
    for i in range(12):
        write(d, "c%d.json" % i, {"include": ["c%d.json" % (i + 1)]} if i < 11 else {})
    return write(d, "main.json", base(include=["c0.json"]))


def counted(key, n, make):
    return lambda d: write(d, "main.json", base(**{key: [make(i) for i in range(n)]}))


def many_layers(n):
    return lambda d: write(d, "main.json", base(layers=[
        {"id": "l%d" % i, "kind": "thematic", "source": {"store": "s", "layer": "hillshade"}}
        for i in range(n)]))


def many_sequences(d):
    layers = [{"id": "q%d" % i, "kind": "sequence", "transfer": "t",
               "source": {"store": "s", "sequence": "depth"}} for i in range(6)]
    return write(d, "main.json", base(layers=layers, transferFunctions={
        "t": {"preset": "viridis", "domain": [0, 1]}}))


def many_keys(d):
    keys = [{"time": "+%ds" % i, "radius": 10} for i in range(5000)]
    l = lens(0)
    l["keys"] = keys
    return write(d, "main.json", base(lenses=[l], clock={"start": "2026-03-14T00:00:00Z",
                                                         "end": "2026-03-15T00:00:00Z"}))


def many_stops(d):
    # About 14 MB: refused at the limit without keeping 660,000 positions (each within 300 MB).
    stops = [{"value": i * 0.001, "color": "#12345678"} for i in range(220000)]
    return write(d, "main.json", base(transferFunctions={"t": {"stops": stops}}))


def clock(start):
    return lambda d: write(d, "main.json", base(clock={"start": start,
                                                       "end": "2026-03-15T00:00:00Z"}))


def lens_time(t):
    l = lens(0)
    l["keys"] = [{"time": t, "radius": 5}]
    return lambda d: write(d, "main.json", base(lenses=[l], clock={
        "start": "2026-03-14T00:00:00Z", "end": "2026-03-15T00:00:00Z"}))


def layer_kind(kind):
    return lambda d: write(d, "main.json", base(layers=[
        {"id": "x", "kind": kind, "source": {"store": "s", "layer": "hillshade"}}]))


def unclosed_comment(d):
    return write(d, "main.json", '{ "version": 1, /* ' + "never closed " * 1_000_000)


def huge_key(d):
    text = json.dumps(base())
    return write(d, "main.json", text[:-1] + ', "' + "k" * (4 << 20) + '": 1}')


BOM_TEXT = ('{"version": 1, "stores": {"s": "s.gpkg"}, "layers": [], '
            '"terrain": {"store": "s", "tauGeom": 0}}')


def bom(d):
    return write(d, "main.json", b"\xef\xbb\xbf" + BOM_TEXT.encode())


def utf16(d):
    return write(d, "main.json", json.dumps(base()).encode("utf-16"))


def store_path(path):
    return lambda d: write(d, "main.json", base(stores={"s": path}))


def store_folder(d):
    os.mkdir(os.path.join(d, "s.gpkg"))
    return write(d, "main.json", base())


def store_fifo(d):
    os.mkfifo(os.path.join(d, "s.gpkg"))
    return write(d, "main.json", base())


def include_of(path):
    return lambda d: write(d, "main.json", base(include=[path]))


def colour_file(path):
    return lambda d: write(d, "main.json", base(
        transferFunctions={"t": {"gdal": path}},
        layers=[{"id": "x", "kind": "data", "transfer": "t",
                 "source": {"store": "s", "layer": "elevation"}}]))


def include_broken(d):
    write(d, "common.json", '{ "title": "x", }')
    return write(d, "main.json", base(include=["common.json"]))


def include_text(d):
    write(d, "notes.txt", "root:x:0:0:root:/root:/bin/bash\n" * 50)
    return write(d, "main.json", base(include=["notes.txt"]))


CASES = [
    # Named where the 65th inclusion is, with the chain back to the scenario in the hint.
    ("include-bomb", include_bomb, "more than 64 included files (each inclusion counts)", False),
    ("include-deep", include_deep, "/include/0: includes nested deeper than 8 files", False),
    ("lenses-1000", counted("lenses", 1000, lens), "/lenses: 1000 lenses exceed the limit of 16",
     False),
    ("mappings-1000", counted("projectiveMappings", 1000, mapping),
     "/projectiveMappings: 1000 projective mappings exceed the limit of 64", False),
    ("layers-1000", many_layers(1000), "/layers: 1000 layers exceed the limit of 12", False),
    ("texture-units", many_sequences, "/layers: the layers need 19 texture units; the limit is 16",
     False),
    ("keys-5000", many_keys, "/lenses/0/keys: 5000 keys exceed the limit of 4096", False),
    ("stops-220000", many_stops,
     "/transferFunctions/t/stops: 220000 entries exceed the limit of 4096", False),
    ("february-30", clock("2026-02-30T00:00:00Z"), '/clock/start: bad time "2026-02-30T00:00:00Z"',
     False),
    ("offset-400-digits", lens_time("+" + "9" * 400 + "s"), "/lenses/0/keys/0/time: bad time", False),
    ("newline-in-value", layer_kind("x\nmain.json:1:1: ok"),
     '/layers/0/kind: unknown kind "x\\nmain.json:1:1: ok"', False),
    ("escape-bell", layer_kind("\x1b[2J\x07"), '/layers/0/kind: unknown kind "\\x1b[2J\\x07"',
     False),
    ("unclosed-comment", unclosed_comment, "invalid comment; missing closing '*/'; last read: "
     "'1, /* never closed never\u2026'", False),
    ("key-4mib", huge_key, "unknown property \"kkkk", False),
    # The column an editor shows, not shifted by the byte-order mark.
    ("utf8-bom", bom, "main.json:1:%d: /terrain/tauGeom: tauGeom must be in (0, 64], got 0" %
     (BOM_TEXT.index('0}}') + 1), False),
    ("utf16", utf16, "main.json:1:1: the file is UTF-16 or UTF-32; scenarios are UTF-8", False),
    ("store-missing", store_path("none.gpkg"), 'none.gpkg": store file does not exist', False),
    ("store-folder", store_folder, "/stores/s: store \"", False),
    ("store-fifo", store_fifo, "is not a regular file (a device, FIFO or socket)", False),
    ("store-dev-zero", store_path("/dev/zero"),
     '/stores/s: file "/dev/zero" is outside the scenario\'s folder', False),
    ("include-etc-passwd", include_of("/etc/passwd"),
     '/include/0: included file "/etc/passwd" is outside the scenario\'s folder', False),
    ("include-dotdot", include_of("../../x.json"),
     '/include/0: included file "../../x.json" is outside', False),
    ("store-proc-environ", store_path("/proc/self/environ"),
     '/stores/s: file "/proc/self/environ" is outside', False),
    ("colour-file-outside", colour_file("../../etc/relief.clr"), '/transferFunctions/t/gdal: file "',
     False),
    ("include-broken", include_broken, "common.json:1:17: syntax error while parsing object key - "
     "unexpected '}'; expected string literal (JSON allows no comma before a closing bracket; "
     "included by ", False),
    ("include-not-json", include_text, "notes.txt:1:1: syntax error", False),
]


# --- corrupt stores: a copy of the demo store, changed with SQL, under the demo scenario -------

def png(width, height, bit_depth, colour_type, rows_bytes=None):
    """A minimal valid PNG; `rows_bytes` is the filtered image data (zeros when None)."""
    def chunk(kind, data):
        return (struct.pack(">I", len(data)) + kind + data +
                struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF))
    channels = {0: 1, 2: 3, 4: 2, 6: 4}[colour_type]
    if rows_bytes is None:
        row = b"\0" + bytes(width * channels * bit_depth // 8)
        rows_bytes = row * height
    ihdr = struct.pack(">IIBBBBB", width, height, bit_depth, colour_type, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) +
            chunk(b"IDAT", zlib.compress(rows_bytes, 9)) + chunk(b"IEND", b""))


def demo_scenario(d):
    with open(os.path.join(ROOT, "scenarios/demo/rainier.json")) as f:
        doc = json.load(f)
    doc.pop("$schema", None)
    doc["stores"] = {"rainier": "s.gpkg"}
    shutil.copy(STORE, os.path.join(d, "s.gpkg"))
    return write(d, "main.json", doc)


def corrupt(*statements, blob=None):
    def build(d):
        path = demo_scenario(d)
        db = sqlite3.connect(os.path.join(d, "s.gpkg"))
        for sql in statements:
            db.execute(sql, (blob,) if blob is not None and "?" in sql else ())
        db.commit()
        db.close()
        return path
    return build


# A 23 KB PNG whose header claims 60000 x 60000 16-bit grey (7.2 GB decoded).
BOMB = png(60000, 60000, 16, 0, rows_bytes=bytes(8 << 20))

# (name, builder, expected text of `validate --deep`, expected text of `render`, render exit)
# render exits 0 when the picture is drawn without the bad tiles, saying which (DEGRADED).
STORE_CASES = [
    # The control: the demo store unchanged is valid to the deepest check and renders silently.
    ("unchanged", corrupt(), "", "", 0),
    # The elevation cases drop the stored meshes too: the demo's stored meshes give every tier its
    # view needs (coarse tiers of edge tiles included), so render would never decode the bad
    # elevation tile; without them it meshes every tile from its posts.
    ("rgb8-in-elevation", corrupt("UPDATE elevation SET tile_data = ?",
                                  "DELETE FROM kiosk_tile_meshes", blob=png(256, 256, 8, 2)),
     ": tile is a 8-bit RGB PNG; this table holds 16-bit grey PNGs [STORE_TILE_FORMAT]",
     "terrain DEGRADED", 0),
    ("grey16-in-normals", corrupt("UPDATE normals SET tile_data = ?", blob=png(256, 256, 16, 0)),
     ": tile is a 16-bit grey PNG; this table holds 8-bit RGB or RGBA PNGs (a normal map) "
     "[STORE_TILE_FORMAT]",
     "layer shade DEGRADED", 0),
    ("png-bomb", corrupt("UPDATE elevation SET tile_data = ? WHERE zoom_level = 0",
                         "DELETE FROM kiosk_tile_meshes", blob=BOMB),
     "elevation/0/0/0: tile claims 60000x60000 pixels, the table's tiles are 256x256",
     "tile claims 60000x60000 pixels", 0),
    ("tile-ancillary-emptied", corrupt("DELETE FROM gpkg_2d_gridded_tile_ancillary"),
     "tiles without a gpkg_2d_gridded_tile_ancillary row", "no gpkg_2d_gridded_tile_ancillary row",
     0),
    ("tile-scale-1e308", corrupt("UPDATE gpkg_2d_gridded_tile_ancillary SET scale = 1e308"),
     "scale is 1e+308, wants (0, 1000000]", "scale is 1e+308, wants (0, 1000000]", 1),
    ("tile-stats-dropped", corrupt("DROP TABLE kiosk_tile_stats"),
     "/stores/rainier: store \"", "kiosk_tile_stats: table is missing", 1),
    ("half-the-frames-deleted", corrupt("DELETE FROM kiosk_sequence_frames WHERE frame_index % 2 = 1"),
     "kiosk_sequence_frames/flood_depth: frame 1 is missing (next is 2)",
     "kiosk_sequence_frames/flood_depth: frame 1 is missing", 1),
    ("contents-emptied", corrupt("DELETE FROM gpkg_contents"),
     "no gpkg_contents row with data_type", "no gpkg_contents row with data_type", 1),
    ("tile-matrix-emptied", corrupt("DELETE FROM gpkg_tile_matrix"),
     "gpkg_tile_matrix lacks levels", "gpkg_tile_matrix lacks levels", 1),
    ("srs-emptied", corrupt("DELETE FROM gpkg_spatial_ref_sys"),
     "gpkg_spatial_ref_sys: no row for the store's CRS", "gpkg_spatial_ref_sys: no row", 1),
]


def run_measured(cmd, env):
    start = time.monotonic()
    pid = os.fork()
    if pid == 0:
        err_fd = os.open(os.path.join(TMP, "stderr"), os.O_WRONLY | os.O_CREAT | os.O_TRUNC)
        out_fd = os.open(os.devnull, os.O_WRONLY)
        os.dup2(out_fd, 1)
        os.dup2(err_fd, 2)
        os.execve(cmd[0], cmd, env)
    deadline = start + MAX_WALL_SECONDS
    while True:
        wpid, status, usage = os.wait4(pid, os.WNOHANG)
        if wpid:
            break
        if time.monotonic() > deadline:
            os.kill(pid, 9)
        time.sleep(0.01)
    wall = time.monotonic() - start
    seconds = usage.ru_utime + usage.ru_stime
    if wall >= MAX_WALL_SECONDS:
        seconds = wall
    with open(os.path.join(TMP, "stderr"), "rb") as f:
        err = f.read(1 << 20)
    code = os.waitstatus_to_exitcode(status)
    return code, err, seconds, usage.ru_maxrss / 1024.0


TMP = tempfile.mkdtemp(prefix="kiosk-hostile-")


def run_case(name, command, scenario, env, check):
    """One run of one case: `check(code, text)` lists the case's own problems; the time and
    memory bounds are checked here. Returns True when it passed (and prints one line)."""
    code, err, seconds, rss = run_measured([GK, command[0], scenario] + command[1:], env)
    text = err.decode("utf-8", "replace")
    problems = check(code, text)
    if seconds > MAX_SECONDS:
        problems.append("%.1f s > %.0f s" % (seconds, MAX_SECONDS))
    if rss > MAX_RSS_MB:
        problems.append("%.0f MB > %.0f MB" % (rss, MAX_RSS_MB))
    label = "%s %s (%.2f s, %.0f MB)" % (command[0], name, seconds, rss)
    if problems:
        print("FAIL: %s: %s\n    %s" % (label, "; ".join(problems), text[:600].rstrip()))
        return False
    print("ok:   %s" % label)
    return True


def scenario_check(folder, expected):
    def check(code, text):
        problems = []
        if code != 1:
            problems.append("exit %d, want 1" % code)
        if len(text.splitlines()) != 1:
            problems.append("%d lines on stderr, want 1" % len(text.splitlines()))
        if expected not in text:
            problems.append("missing %r" % expected)
        if not text.startswith(folder + "/"):
            problems.append("does not start with the culprit file")
        return problems
    return check


def store_check(folder, expected, want):
    def check(code, text):
        problems = []
        if code != want:
            problems.append("exit %d, want %d" % (code, want))
        if expected not in text:
            problems.append("missing %r" % expected)
        if not expected and code == 0 and any(
                not l.startswith("render: wrote") for l in text.splitlines()):
            problems.append("a valid store should give no message")
        for line in text.splitlines():
            # Every line names the scenario or the store file and the culprit (render adds
            # "wrote N frames"; the log's warnings come with their "<4>" syslog prefix).
            if folder + "/" not in line:
                problems.append("line names no file: %r" % line[:120])
        return problems
    return check


def play_reload(env):
    """An include bomb saved into a running `play --display headless`, then a good edit: the bomb
    is refused with its message, the good edit is taken, play keeps running and stops cleanly.
    (Frame gaps are measured in-process by tests/scenario/ReloadGLTest.cpp.)"""
    if not STORE:
        print("skip: play-reload (no demo store)")
        return None
    folder = os.path.join(TMP, "play")
    os.makedirs(folder)
    scenario = demo_scenario(folder)
    with open(scenario) as f:
        good = json.load(f)
    os.chdir(folder)
    log = open(os.path.join(folder, "log"), "wb")
    start = time.monotonic()
    proc = subprocess.Popen([GK, "play", scenario, "--display", "headless", "--size", "64x36",
                             "--max-fps", "20", "--frames", "160"], stdout=log, stderr=log,
                            env=dict(env, GEOKIOSK_LOG="info"))
    # The bomb goes in once the first scenario plays (start-up is slow on a loaded machine).
    logged = os.path.join(folder, "log")
    while "playing, watching" not in open(logged, errors="replace").read():
        if proc.poll() is not None or time.monotonic() - start > 40:
            break
        time.sleep(0.1)
    time.sleep(0.5)
    include_bomb(folder)  # writes b*.json and a main.json that includes them
    time.sleep(2.0)
    good["title"] = "after the bomb"
    tmp = scenario + ".tmp"
    with open(tmp, "w") as f:
        json.dump(good, f)
    os.rename(tmp, scenario)
    try:
        code = proc.wait(timeout=50)
    except subprocess.TimeoutExpired:
        proc.kill()
        code = "timeout"
    wall = time.monotonic() - start
    log.close()
    text = open(os.path.join(folder, "log"), encoding="utf-8", errors="replace").read()
    problems = []
    if code != 0:
        problems.append("exit %s, want 0" % code)
    rejected = text.find("edit rejected, keeping the previous scenario")
    if rejected < 0 or "SCENARIO_LIMIT" not in text:
        problems.append("the bomb was not refused with SCENARIO_LIMIT")
    if text.find("reloaded", max(rejected, 0)) < 0:
        problems.append("the good edit after the bomb was not taken")
    if "stopped cleanly" not in text:
        problems.append("play did not stop cleanly")
    label = "play-reload (%.1f s for 160 frames at <= 20 fps)" % wall
    if problems:
        print("FAIL: %s: %s\n    %s" % (label, "; ".join(problems), text[-800:]))
        return False
    print("ok:   %s" % label)
    return True


def main():
    env = dict(os.environ)
    env.pop("GEOKIOSK_ALLOW_PATHS", None)
    env.setdefault("GALLIUM_DRIVER", "llvmpipe")
    results = []
    skips = 0
    only = os.environ.get("HOSTILE_ONLY")
    for name, build, expected, needs_store in CASES:
        if only and name != only:
            continue
        if needs_store and not STORE:
            print("skip: %s (no demo store)" % name)
            skips += 1
            continue
        folder = os.path.join(TMP, "cases", name, "a", "b")
        os.makedirs(folder)
        scenario = build(folder)
        os.chdir(folder)  # the working directory is an allowed root too
        for command in (["validate"],
                        ["render", "--size", "64x36", "--out", os.path.join(folder, "out.png")]):
            results.append(run_case(name, command, scenario, env,
                                    scenario_check(folder, expected)))
    for name, build, expect_validate, expect_render, render_exit in STORE_CASES:
        if only and name != only:
            continue
        if not STORE:
            print("skip: %s (no demo store)" % name)
            skips += 1
            continue
        folder = os.path.join(TMP, "stores", name)
        os.makedirs(folder)
        scenario = build(folder)
        os.chdir(folder)
        results.append(run_case(name, ["validate", "--deep"], scenario, env, store_check(
            folder, expect_validate, 1 if expect_validate else 0)))
        results.append(run_case(
            name, ["render", "--size", "96x54", "--out", os.path.join(folder, "out.png")],
            scenario, env, store_check(folder, expect_render, render_exit)))
    if not only or only == "play-reload":
        played = play_reload(env)
        if played is None:
            skips += 1
        else:
            results.append(played)
    shutil.rmtree(TMP, ignore_errors=True)
    failures = results.count(False)
    print("%d passed, %d failed, %d skipped" % (results.count(True), failures, skips))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
