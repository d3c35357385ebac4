#!/usr/bin/python3
"""Tests of `mote replay --viewer` on the Intel log, run by ctest.

browser: opens viewer.html in headless Chromium at three updates (viewer.html#t=N), checks that
         the page drew without a script error (its title says "mote viewer: update N of M", an
         error sets "mote viewer: error: ..."; Chromium's log holds no uncaught exception) and
         that the estimate marker (the only #ff00ff pixels) moves between the screenshots; then
         opens it without #t= in a 1400 x 900 window: it must show the last update, with the six
         timelines' lowest pixel row (the page's data-timelines-bottom, from
         getBoundingClientRect) inside the viewport (data-viewport-height, at most 900 rows).
size:    the page for the whole log with every update at the particle cap stays under 20 MB.

Exits 77 (ctest's SKIP_RETURN_CODE) with a message when ../shared/data or chromium is absent.
"""
import argparse
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
TIMELINES = 6
MIN_TIMELINES_BOTTOM = 6 * 30  # six timelines of at least 30 px each end below this row


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


def check_opening_state(browser, profile, url):
    """Without #t= at 1400 x 900: the last update, and the timelines above the fold."""
    dom = chromium(browser, profile, url, "--dump-dom", size=f"{FOLD_WIDTH},{FOLD_HEIGHT}")
    title = re.search(r"<title>mote viewer: update (\d+) of (\d+)</title>", dom)
    assert title, "the page has no 'update N of M' title: " + dom[:300]
    shown, total = int(title.group(1)), int(title.group(2))
    assert shown == total - 1, f"the page opens at update {shown}, not at the last, {total - 1}"
    bottom = re.search(r'data-timelines-bottom="(\d+)"', dom)
    assert bottom, "the page sets no data-timelines-bottom"
    # Headless Chromium's viewport is the window less its (emulated) browser frame.
    viewport = re.search(r'data-viewport-height="(\d+)"', dom)
    assert viewport and 0 < int(viewport.group(1)) <= FOLD_HEIGHT, "no or a wrong viewport height"
    charts = dom.count("<canvas")
    assert charts >= TIMELINES + 1, f"{charts} canvases: the map and {TIMELINES} timelines expected"
    print(f"opening state: update {shown} of {total}, timelines end at row {bottom.group(1)} "
          f"of a {viewport.group(1)}-pixel viewport")
    assert MIN_TIMELINES_BOTTOM <= int(bottom.group(1)) <= int(viewport.group(1)), \
        f"the timelines end at row {bottom.group(1)}, below the {viewport.group(1)}-row viewport"


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
    check_opening_state(browser, profile, url)


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
