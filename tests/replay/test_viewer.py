#!/usr/bin/python3
"""Tests of `mote replay --viewer`, run by ctest.

browser: on the Intel log, opens viewer.html in headless Chromium at three updates
         (viewer.html#t=N, N counted from 1), checks that the page drew without a script error
         (its title says "mote viewer: update N of M", an error sets "mote viewer: error: ...";
         Chromium's log holds no uncaught exception) and that the estimate marker (the only
         #ff00ff pixels) moves between the screenshots; then opens it without #t= in a
         1400 x 900 window: it must show the last update as "update M of M", with the seven
         timelines and their time axis inside the viewport (the page's data-timelines-bottom,
         from getBoundingClientRect, against data-viewport-height); the state band under the map
         with its key naming tracking, uncertain and lost in colours that stay apart under
         simulated protanopia, deuteranopia and tritanopia; the trajectory drawn in the tracking
         colour; map axes in metres within the map's extent and a time axis in seconds. In a
         900 px wide window the page must be no wider than the window. On the Intel log kidnapped by
         `mote kidnap` (tracking, lost, one re-localization): the band shows all three states (a
         single uncertain update among hundreds of tracking ones, and at a re-localization) and the
         re-localization mark, the map the lost and the tracking colours, and at the
         re-localization the page gives the re-localized count of updates.csv.
size:    the page for the whole log with every update at the particle cap stays under 20 MB.

Exits 77 (ctest's SKIP_RETURN_CODE) with a message when ../shared/data or chromium is absent.
"""
import argparse
import csv
import itertools
import math
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import zlib

SKIP = 77
MAGENTA_MIN_PIXELS = 20  # the marker is a disc of radius >= 6 px: ~100 px
MIN_MOVE_PX = 5.0
FOLD_WIDTH, FOLD_HEIGHT = 1400, 900  # the window the timelines must fit without scrolling
NARROW_WIDTH = 900  # a window that puts the timelines under the map
TIMELINES = 7
MIN_TIMELINES_BOTTOM = 7 * 30  # seven timelines of at least 30 px each end below this row
STATES = ("tracking", "uncertain", "lost")
MIN_CVD_DISTANCE = 20.0  # CIELAB Delta E76 between any two state colours, with any colour vision
COLOUR_TOLERANCE = 24  # per channel: a line's antialiased core still counts as its colour


def skip(message):
    print("SKIP: " + message)
    sys.exit(SKIP)


def replay(args, out, extra):
    intel = os.path.join(args.data, "intel")
    cmd = [args.mote, "replay", "--map", os.path.join(intel, "intel.yaml"),
           "--log", os.path.join(intel, "intel.clf"),
           "--reference", os.path.join(intel, "intel.gt.tum"),
           "--out", out, "--viewer", "--quiet", "--threads", "2"] + extra
    subprocess.run(cmd, check=True)
    return os.path.join(out, "viewer.html")


def read_png_rgb(path):
    """(width, height, rows of RGB bytes) of an 8-bit RGB or RGBA non-interlaced PNG."""
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", path + ": not a PNG"
    pos, idat, header = 8, b"", None
    while pos < len(data):
        (length,) = struct.unpack(">I", data[pos:pos + 4])
        kind, body = data[pos + 4:pos + 8], data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    width, height, depth, color, _, _, interlace = header
    assert depth == 8 and color in (2, 6) and interlace == 0, f"{path}: unexpected PNG {header}"
    channels = 3 if color == 2 else 4
    raw, stride = zlib.decompress(idat), width * channels
    rows, prev = [], bytearray(stride)
    for y in range(height):
        start = y * (stride + 1)
        kind, line = raw[start], bytearray(raw[start + 1:start + 1 + stride])
        for i in range(stride):  # PNG filters (RFC 2083 section 6)
            a = line[i - channels] if i >= channels else 0
            b, c = prev[i], prev[i - channels] if i >= channels else 0
            if kind == 1:
                line[i] = (line[i] + a) & 255
            elif kind == 2:
                line[i] = (line[i] + b) & 255
            elif kind == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line) if channels == 3 else
                    bytes(v for k, v in enumerate(line) if k % 4 != 3))
        prev = line
    return width, height, rows


def marker_centre(path):
    """Centroid and count of the exactly-magenta pixels (the estimate marker)."""
    width, _, rows = read_png_rgb(path)
    xs, ys = [], []
    for y, row in enumerate(rows):
        for x in range(width):
            r, g, b = row[3 * x:3 * x + 3]
            if r >= 250 and g <= 5 and b >= 250:
                xs.append(x)
                ys.append(y)
    assert len(xs) >= MAGENTA_MIN_PIXELS, f"{path}: estimate marker not drawn ({len(xs)} px)"
    return sum(xs) / len(xs), sum(ys) / len(ys), len(xs)


def chromium(browser, profile, url, *how, size="1100,1350"):
    cmd = [browser, "--headless", "--disable-gpu", "--no-sandbox", "--hide-scrollbars",
           "--no-first-run", "--user-data-dir=" + profile, "--window-size=" + size,
           "--enable-logging=stderr", "--v=0", *how, url]
    done = subprocess.run(cmd, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, f"chromium failed ({done.returncode}): {done.stderr[-2000:]}"
    assert "Uncaught" not in done.stderr, "script error in the page: " + done.stderr[-2000:]
    return done.stdout


def body_data(dom):
    """The page's data-* attributes on <body>, by name (data-map-rect -> "map-rect")."""
    body = re.search(r"<body([^>]*)>", dom)
    assert body, "the page has no body"
    return dict(re.findall(r'data-([a-z-]+)="([^"]*)"', body.group(1)))


def rect(data, name):
    x, y, w, h = (int(v) for v in data[name].split(","))
    assert w > 0 and h > 0, f"{name} is empty: {data[name]}"
    return x, y, w, h


def state_colours(dom):
    """The state band's key: colour by state, from its data-key and data-color attributes."""
    key = re.search(r'<div id="state-key">(.*?)</div>', dom, re.S)
    assert key, "the page has no state key under the map"
    colours = dict(re.findall(r'data-key="([a-z]+)" data-color="(#[0-9a-f]{6})"', key.group(1)))
    assert set(colours) == set(STATES), f"the state key names {sorted(colours)}, not {STATES}"
    return {name: tuple(int(c[i:i + 2], 16) for i in (1, 3, 5)) for name, c in colours.items()}


# Machado, Oliveira and Fernandes (2009), severity 1, on linear RGB.
CVD = {"protanopia": ((0.152286, 1.052583, -0.204868), (0.114503, 0.786281, 0.099216),
                      (-0.003882, -0.048116, 1.051998)),
       "deuteranopia": ((0.367322, 0.860646, -0.227968), (0.280085, 0.672501, 0.047413),
                        (-0.011820, 0.042940, 0.968881)),
       "tritanopia": ((1.255528, -0.076749, -0.178779), (-0.078411, 0.930809, 0.147602),
                      (0.004733, 0.691367, 0.303900)),
       "normal vision": ((1, 0, 0), (0, 1, 0), (0, 0, 1))}


def lab(rgb, matrix):
    """CIELAB (D65) of an sRGB colour as someone with the vision `matrix` sees it."""
    lin = [c / 255 / 12.92 if c <= 10 else ((c / 255 + 0.055) / 1.055) ** 2.4 for c in rgb]
    r, g, b = (min(1.0, max(0.0, sum(m * c for m, c in zip(row, lin)))) for row in matrix)
    xyz = (0.4124 * r + 0.3576 * g + 0.1805 * b) / 0.95047, 0.2126 * r + 0.7152 * g + 0.0722 * b, \
        (0.0193 * r + 0.1192 * g + 0.9505 * b) / 1.08883
    fx, fy, fz = (t ** (1 / 3) if t > 0.008856 else 7.787 * t + 16 / 116 for t in xyz)
    return 116 * fy - 16, 500 * (fx - fy), 200 * (fy - fz)


def check_colour_blind_safe(colours):
    for vision, matrix in CVD.items():
        for (a, ca), (b, cb) in itertools.combinations(colours.items(), 2):
            distance = math.dist(lab(ca, matrix), lab(cb, matrix))
            assert distance >= MIN_CVD_DISTANCE, \
                f"{a} and {b} are {distance:.1f} apart with {vision} (at least {MIN_CVD_DISTANCE})"


def count_colour(shot, box, colour):
    """Pixels of the screenshot inside box (x, y, w, h) within COLOUR_TOLERANCE of colour."""
    width, height, rows = shot
    x0, y0, w, h = box
    n = 0
    for y in range(max(0, y0), min(height, y0 + h)):
        row = rows[y]
        for x in range(max(0, x0), min(width, x0 + w)):
            if all(abs(row[3 * x + i] - colour[i]) <= COLOUR_TOLERANCE for i in range(3)):
                n += 1
    return n


def check_ticks(labels, lo, hi, what):
    """Tick labels: at least three numbers, evenly spaced, increasing, inside [lo, hi]."""
    values = [float(v) for v in labels.split()]
    assert len(values) >= 3, f"{what}: {len(values)} ticks ('{labels}')"
    steps = {round(b - a, 6) for a, b in zip(values, values[1:])}
    assert len(steps) == 1 and min(steps) > 0, f"{what}: uneven ticks '{labels}'"
    assert lo <= values[0] and values[-1] <= hi, f"{what}: ticks '{labels}' outside [{lo}, {hi}]"


def map_extent(yaml_path):
    """(x0, x1, y0, y1) in metres of a map_server map with an unturned origin."""
    text = open(yaml_path).read()
    resolution = float(re.search(r"resolution:\s*([-0-9.e]+)", text).group(1))
    ox, oy = (float(v) for v in re.search(r"origin:\s*\[([^,]+),([^,]+),", text).groups())
    image = os.path.join(os.path.dirname(yaml_path), re.search(r"image:\s*(\S+)", text).group(1))
    width, height = struct.unpack(">II", open(image, "rb").read()[16:24])  # PNG IHDR
    return ox, ox + width * resolution, oy, oy + height * resolution


def last_stamp(page):
    """s after the first scan of the last update, from the page's data block."""
    stamps = re.search(r'"estimate_t":\[([^\]]*)\]', open(page).read()).group(1)
    return float(stamps.split(",")[-1])


def check_opening_state(browser, profile, url, page, extent, work):
    """Without #t= at 1400 x 900: the last update, timelines above the fold, band and axes."""
    dom = chromium(browser, profile, url, "--dump-dom", size=f"{FOLD_WIDTH},{FOLD_HEIGHT}")
    title = re.search(r"<title>mote viewer: update (\d+) of (\d+)</title>", dom)
    assert title, "the page has no 'update N of M' title: " + dom[:300]
    shown, total = int(title.group(1)), int(title.group(2))
    assert shown == total, f"the page opens at update {shown} of {total}, not at the last"
    data = body_data(dom)
    assert "timelines-bottom" in data, "the page sets no data-timelines-bottom"
    # Headless Chromium's viewport is the window less its (emulated) browser frame.
    viewport = int(data.get("viewport-height", 0))
    assert 0 < viewport <= FOLD_HEIGHT, "no or a wrong viewport height"
    charts = dom.count("<canvas")
    assert charts >= TIMELINES + 3, \
        f"{charts} canvases: the map, the state band, {TIMELINES} timelines and their time axis"
    bottom = int(data["timelines-bottom"])
    print(f"opening state: update {shown} of {total}, timelines end at row {bottom} "
          f"of a {viewport}-pixel viewport")
    assert MIN_TIMELINES_BOTTOM <= bottom <= viewport, \
        f"the timelines end at row {bottom}, below the {viewport}-row viewport"
    colours = state_colours(dom)
    check_colour_blind_safe(colours)
    assert data.get("map-x-title") == "x (m)" and data.get("map-y-title") == "y (m)", \
        f"map axes titled '{data.get('map-x-title')}' and '{data.get('map-y-title')}'"
    x0, x1, y0, y1 = extent
    check_ticks(data["map-x-ticks"], x0, x1, "map x axis")
    check_ticks(data["map-y-ticks"], y0, y1, "map y axis")
    assert re.fullmatch(r"[0-9.]+ m", data.get("map-scale-bar", "")), "no scale bar"
    end = last_stamp(page)
    check_ticks(data["time-ticks"], 0.0, end * 1.05, "time axis")
    assert float(data["time-ticks"].split()[-1]) >= end / 2, "the time axis ends early"
    print(f"map axes x {data['map-x-ticks']}, y {data['map-y-ticks']} m, scale bar "
          f"{data['map-scale-bar']}; time axis {data['time-ticks']} s")
    shot = os.path.join(work, "opening.png")
    chromium(browser, profile, url, "--screenshot=" + shot, size=f"{FOLD_WIDTH},{FOLD_HEIGHT}")
    image = read_png_rgb(shot)
    on_map = count_colour(image, rect(data, "map-rect"), colours["tracking"])
    band = rect(data, "band-rect")
    on_band = count_colour(image, band, colours["tracking"])
    print(f"tracking colour: {on_map} px of trajectory, {on_band} of {band[2] * band[3]} px of band")
    assert on_map >= 500, f"the trajectory has {on_map} px in the tracking colour"
    assert on_band >= 0.9 * band[2] * band[3], "the Intel run tracks throughout: the band shows not"


def check_narrow(browser, profile, url):
    """In a 900 px wide window: no wider than the window, the state band still there."""
    dom = chromium(browser, profile, url, "--dump-dom", size=f"{NARROW_WIDTH},{FOLD_HEIGHT}")
    data = body_data(dom)
    page, window = int(data["page-width"]), int(data["viewport-width"])
    print(f"at {NARROW_WIDTH} px: the page is {page} px wide in a {window} px viewport")
    assert 0 < window <= NARROW_WIDTH and page <= window, \
        f"the page is {page} px wide, wider than the {window} px window"
    state_colours(dom)
    rect(data, "band-rect")


def check_relocalization(args, browser, profile, work):
    """The Intel log kidnapped by `mote kidnap`: tracking, lost, a re-localization, uncertain
    while the new place has not held (single updates on this run, one at a re-localization),
    then tracking."""
    intel = os.path.join(args.data, "intel")
    if not os.path.isfile(os.path.join(intel, "intel.clf")):
        print(f"SKIP the re-localization checks: {intel} is absent")
        return
    kidnap = os.path.join(work, "kidnap")
    subprocess.run([args.mote, "kidnap", "--log", os.path.join(intel, "intel.clf"),
                    "--reference", os.path.join(intel, "intel.gt.tum"), "--out", kidnap],
                   check=True, stdout=subprocess.DEVNULL)
    out = os.path.join(work, "kidnapped")
    subprocess.run([args.mote, "replay", "--map", os.path.join(intel, "intel.yaml"),
                    "--log", os.path.join(kidnap, "kidnap.clf"), "--out", out, "--viewer",
                    "--quiet", "--threads", "2"], check=True)
    rows = list(csv.DictReader(open(os.path.join(out, "updates.csv"))))
    found = [k for k, r in enumerate(rows) if int(r["relocalized"]) > 0]
    assert found, "the kidnapped run did not re-localize: nothing to check"
    row = rows[found[0]]
    url = "file://" + os.path.abspath(os.path.join(out, "viewer.html"))
    dom = chromium(browser, profile, f"{url}#t={found[0] + 1}", "--dump-dom")
    counts = re.search(r'<div id="counts">(.*?)</div>', dom, re.S).group(1)
    expected = f"{row['relocalized']} of them added by a re-localization"
    assert f"weighed {row['weighed']} by the scan" in counts and expected in counts, \
        f"update {found[0] + 1}: the counts say '{counts}', not '{expected}'"
    assert f"\u2014 {row['relocalized']} re-localized, {row['injected']} injected" in dom, \
        "the particles-added timeline does not give the re-localized count"
    now = re.search(r'<span id="state-now">([^<]*)</span>', dom)
    assert now and now.group(1) == row["state"] + ", re-localized", \
        f"the band says '{now and now.group(1)}' at the re-localization, updates.csv {row['state']}"
    print(f"kidnapped Intel update {found[0] + 1}: {row['relocalized']} re-localized of {row['weighed']} "
          f"weighed, state {row['state']}")
    dom = chromium(browser, profile, url, "--dump-dom", size=f"{FOLD_WIDTH},{FOLD_HEIGHT}")
    data, colours = body_data(dom), state_colours(dom)
    shot = os.path.join(work, "kidnapped.png")
    chromium(browser, profile, url, "--screenshot=" + shot, size=f"{FOLD_WIDTH},{FOLD_HEIGHT}")
    image = read_png_rgb(shot)
    band, on_map = rect(data, "band-rect"), rect(data, "map-rect")
    shares = {s: count_colour(image, band, colours[s]) for s in STATES}
    marks = count_colour(image, (band[0], band[1] - 10, band[2], 10), (0, 0, 0))
    trajectory = {s: count_colour(image, on_map, colours[s]) for s in ("tracking", "lost")}
    print(f"kidnapped Intel band px by state {shares}, re-localization mark {marks} px; "
          f"trajectory px {trajectory}")
    for state in STATES:
        assert shares[state] >= band[3], f"the band shows no '{state}' ({shares[state]} px)"
    assert marks >= 10, "the band does not mark the re-localization"
    assert trajectory["tracking"] >= 100 and trajectory["lost"] >= 30, \
        f"the trajectory's colours: {trajectory} px"


def test_browser(args, work):
    browser = shutil.which("chromium") or shutil.which("chromium-browser")
    if browser is None:
        skip("chromium is not installed (scripts/install-deps installs Debian's chromium)")
    page = replay(args, os.path.join(work, "run"), [])
    url = "file://" + os.path.abspath(page)
    profile = os.path.join(work, "profile")
    centres = []
    for t in (100, 400, 700):
        dom = chromium(browser, profile, f"{url}#t={t}", "--dump-dom")
        title = re.search(r"<title>(.*?)</title>", dom, re.S)
        assert title, "the page has no title after loading"
        assert re.fullmatch(rf"mote viewer: update {t} of \d+", title.group(1)), \
            f"#t={t}: page title '{title.group(1)}'"
        shot = os.path.join(work, f"t{t}.png")
        chromium(browser, profile, f"{url}#t={t}", "--screenshot=" + shot)
        centres.append(marker_centre(shot))
        print(f"t={t}: {title.group(1)}, estimate marker at {centres[-1][:2]} "
              f"({centres[-1][2]} px)")
    for (a, b) in ((0, 1), (1, 2), (0, 2)):
        move = ((centres[a][0] - centres[b][0]) ** 2 + (centres[a][1] - centres[b][1]) ** 2) ** 0.5
        assert move >= MIN_MOVE_PX, f"the estimate marker moved {move:.1f} px between shots"
    extent = map_extent(os.path.join(args.data, "intel", "intel.yaml"))
    check_opening_state(browser, profile, url, page, extent, work)
    check_narrow(browser, profile, url)
    check_relocalization(args, browser, profile, work)


def test_size(args, work):
    # --particles 3000: every update has more than the 2000 the viewer keeps, the largest page.
    page = replay(args, os.path.join(work, "size"), ["--particles", "3000"])
    size = os.path.getsize(page)
    print(f"viewer.html: {size / 1e6:.2f} MB")
    assert size < 20e6, f"viewer.html is {size / 1e6:.2f} MB, the bound is 20 MB"
    updates = len(re.search(r'"total_ms":\[([^\]]*)\]', open(page).read()).group(1).split(","))
    assert updates >= 900, f"the page holds {updates} updates, the Intel log has about 910"


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("what", choices=["browser", "size"])
    parser.add_argument("--mote", required=True)
    parser.add_argument("--data", required=True, help="../shared/data")
    args = parser.parse_args()
    if not os.path.isfile(os.path.join(args.data, "intel", "intel.clf")):
        skip(f"{args.data}/intel is absent (see its README)")
    with tempfile.TemporaryDirectory(prefix="mote_viewer_") as work:
        (test_browser if args.what == "browser" else test_size)(args, work)
    print("ok")


if __name__ == "__main__":
    main()
