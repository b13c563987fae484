#!/usr/bin/python3
"""Per-kiosk memory budgets (docs/kiosk.md `budgets`) in a running `geokiosk play kiosk.json`:
an entry needing more transfer-function LUT bytes than the kiosk allows is skipped with one line
naming the kiosk file:line:col, the JSON pointer and the figures; a hot edit that would exceed
the budget is refused and the last good picture stays; the font atlas is drawn smaller to fit;
/metrics (parsed with prometheus_client from the real server on loopback) reports every budget
and what is held against it.
usage: kiosk_budgets_test.py GEOKIOSK REPO_ROOT"""
import json
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from kiosk_common import Checks, Kiosk, demo_setup, gl_env, skip_or_fail, temp_dir, wait_until  # noqa: E402

try:
    from prometheus_client.parser import text_string_to_metric_families
except ImportError:
    skip_or_fail("python3-prometheus-client missing")

GK, ROOT, STORE = demo_setup(sys.argv)
c = Checks()

LUT_BUDGET = 32816        # 4 layer LUTs of 8204 bytes (ramp + the stack's copy); the demo has 2
FONT_BUDGET = 131072      # 1200 px high output wants 30 px text: its atlas is larger
PAGE_CACHE = 131072       # per store connection


def save(path, obj):
    with open(path + ".tmp", "w") as f:
        json.dump(obj, f)
    os.rename(path + ".tmp", path)


def with_layers(demo, extra):
    """The demo plus `extra` data layers, each through its own transfer function."""
    s = json.loads(json.dumps(demo))
    relief = next(l for l in s["layers"] if l["id"] == "relief")
    for i in range(extra):
        s["transferFunctions"]["t%d" % i] = s["transferFunctions"]["relief"]
        s["layers"].append(dict(relief, id="relief%d" % i, transfer="t%d" % i))
    return s


def samples(k):
    """{(name, frozenset(labels)): value} from /metrics through a real Prometheus parser."""
    code, body, _ = k.request("GET", "/metrics")
    out = {}
    for fam in text_string_to_metric_families(body):
        for s in fam.samples:
            out[(s.name, frozenset(s.labels.items()))] = s.value
    return out


def gauge(m, name, kind=None):
    return m.get((name, frozenset({("kind", kind)} if kind else set())))


with temp_dir() as tmp:
    with open("scenarios/demo/rainier.json") as f:
        demo = json.load(f)
    demo.pop("$schema", None)
    demo["stores"] = {"rainier": STORE}
    good = os.path.join(tmp, "good.json")
    many = os.path.join(tmp, "many.json")
    save(good, demo)
    save(many, with_layers(demo, 4))  # 6 LUTs: 49224 bytes
    kiosk_file = os.path.join(tmp, "kiosk.json")
    with open(kiosk_file, "w") as f:
        f.write('{\n  "playlist": [ { "scenario": "many.json", "duration": 600 },\n'
                '                { "scenario": "good.json", "duration": 600 } ],\n'
                '  "listen": "127.0.0.1:0",\n'
                '  "budgets": {\n'
                '    "lutBytes": %d,\n'
                '    "fontAtlasBytes": %d,\n'
                '    "sqlitePageCacheBytes": %d\n  }\n}\n' % (LUT_BUDGET, FONT_BUDGET, PAGE_CACHE))
    env = dict(gl_env(), GEOKIOSK_LOG="info")
    k = Kiosk(GK, [kiosk_file, "--display", "headless", "--size", "320x1200", "--max-fps", "10"],
              env, os.path.join(tmp, "log"))
    try:
        k.wait_port()
        c.check(wait_until(lambda: (gauge(samples(k), "geokiosk_frames_total") or 0) > 3, 60),
                "frames drawn")
        m = samples(k)
        log = k.log_text()
        skips = [l for l in log.splitlines() if "skipping /playlist/0" in l]
        c.check(len(skips) == 1 and re.search(
            re.escape(kiosk_file) + r":6:17: /budgets/lutBytes: scenario " + re.escape(many) +
            r" needs 48\.1 KiB \(49224 bytes\) of transfer-function LUTs \(6 LUTs\), over this "
            r"kiosk's budget of 32\.0 KiB \(32816 bytes\) \[BUDGET_LUTS\]", skips[0]) is not None,
            "the over-budget entry skipped with one line naming file:line:col, pointer and "
            "figures: %r" % skips)
        c.check(gauge(m, "geokiosk_playlist_position") == 1.0, "the entry within budget plays")
        c.check(gauge(m, "geokiosk_cache_budget_bytes", "luts") == LUT_BUDGET, "LUT budget reported")
        c.check(gauge(m, "geokiosk_cache_bytes", "luts") == 16408,
                "LUT bytes held: the demo's 2 LUTs (%s)" % gauge(m, "geokiosk_cache_bytes", "luts"))
        font = gauge(m, "geokiosk_cache_bytes", "font_atlas") or 0
        c.check(gauge(m, "geokiosk_cache_budget_bytes", "font_atlas") == FONT_BUDGET
                and 0 < font <= FONT_BUDGET, "font atlas held %d within its budget" % font)
        c.check(re.search(re.escape(kiosk_file) + r":7:\d+: /budgets/fontAtlasBytes: overlay text "
                          r"at 30 px needs a font atlas of \d+ bytes, over the budget of "
                          r"128\.0 KiB \(131072 bytes\): drawn at \d+ px", log) is not None,
                "font degraded with one line naming the budget")
        conns = gauge(m, "geokiosk_store_connections") or 0
        c.check(conns >= 1 and gauge(m, "geokiosk_cache_budget_bytes", "sqlite_page_cache")
                == PAGE_CACHE * conns, "page cache budget = %d per connection x %d" %
                (PAGE_CACHE, conns))
        c.check(gauge(m, "geokiosk_cache_budget_bytes", "mappings") > 0
                and gauge(m, "geokiosk_cache_bytes", "mappings") == 0,
                "mapping budget reported (default), nothing held")

        # A hot edit that would exceed the LUT budget: refused, the last good picture stays.
        frames = gauge(m, "geokiosk_frames_total")
        save(good, with_layers(demo, 3))  # 5 LUTs: 41020 bytes
        c.check(wait_until(lambda: "edit rejected" in k.log_text(), 30), "over-budget edit refused")
        rejected = [l for l in k.log_text().splitlines() if "edit rejected" in l]
        c.check(len(rejected) == 1 and "/budgets/lutBytes: " in rejected[0]
                and "41020 bytes" in rejected[0] and "BUDGET_LUTS" in rejected[0],
                "one line naming the budget: %r" % rejected)
        # Published with the next frame after the refusal.
        c.check(wait_until(lambda: gauge(samples(k), "geokiosk_reload_failures_total") == 1, 10),
                "counted as a failed reload")
        m = samples(k)
        c.check(("geokiosk_layer_state", frozenset({("layer", "relief0"), ("state", "ready")}))
                not in m and gauge(m, "geokiosk_cache_bytes", "luts") == 16408,
                "the previous scenario is still on screen")
        c.check(wait_until(lambda: gauge(samples(k), "geokiosk_frames_total") > frames + 3, 20),
                "frames keep coming")
    finally:
        rc = k.stop()
    c.check(rc == 0, "exit 0 on SIGTERM (%s)" % rc)
c.exit()
