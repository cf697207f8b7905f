#!/usr/bin/env python3
"""make bench, the viewer (tests/bench/viewer.sh).

    viewer_bench.py open PAGE [RUNS]   open a `--html` page in headless Chromium
                                       through the DevTools protocol (tests/cli/cdp.py)
    viewer_bench.py totals PAGE        "layers L vectors V": the run element's totals
                                       (read from the page's end: no block decoded)

open: each of RUNS fresh browsers (default 3) navigates to the page and prints one line

    first_ms F ready_ms R steps_ms S1,S2,... layers L

F: lamina.firstDrawn, performance.now() when the viewer drew its first layer,
counted from the navigation's start (docs/viewer.md); R: lamina.loadedAt, when
the viewer had read the run's JSON at the page's end (else when lamina.ready was
first seen true, to the poll's 20 ms), on the same clock; S: what lamina.show(K)
returned (the milliseconds it took to decode and draw layer K) for the last
layer, the middle one, a quarter and three quarters up, once the page is in. A page without the interface prints "first_ms none" and the browser's
load time instead. Waits poll the page (cdp.Browser.wait), never a fixed sleep;
the timeout (600 s) only bounds a hung browser."""
import json
import os
import shutil
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "cli"))
import cdp  # noqa: E402


def chrome():
    for name in ("chromium", "chromium-browser", "google-chrome"):
        p = shutil.which(name)
        if p:
            return p
    sys.exit("viewer_bench.py: no chromium")


def once(page):
    user = tempfile.mkdtemp(prefix="viewer-bench-")
    b = cdp.Browser(chrome(), user, 1200, 900)
    try:
        s = b.page()
        b.send("Page.enable", session=s)
        b.send("Page.navigate", {"url": "file://" + os.path.abspath(page)}, session=s)
        # the first layer drawn, or a page done without the interface (-1)
        first = b.wait(s, "(window.lamina && lamina.firstDrawn) || (document.readyState == 'complete' && "
                          "!(window.lamina && 'firstDrawn' in lamina) && -1)", timeout=600)
        if first < 0:
            load = b.eval(s, "performance.now()")
            return "first_ms none load_ms %.0f (no lamina.firstDrawn in this page)" % load
        ready = b.wait(s, "lamina.ready && (lamina.loadedAt || performance.now())", timeout=600)
        n = b.eval(s, "JSON.parse(document.getElementById('lamina-head').textContent).layers")
        # far layers, none shown before (so none decoded yet): the last, the middle, a quarter, three quarters
        steps = [b.eval(s, "lamina.show(%d)" % k) for k in (n, (n + 1) // 2, max(1, n // 4), max(1, 3 * n // 4))]
        return "first_ms %.0f ready_ms %.0f steps_ms %s layers %d" % (
            first, ready, ",".join("%.0f" % x for x in steps), n)
    finally:
        b.close()
        shutil.rmtree(user, ignore_errors=True)


def totals(page):
    """the run element's job and totals; it is the page's last element but
    loaded(), so its end is read, more of it until the element is whole"""
    size = os.path.getsize(page)
    tail = 1 << 20
    while True:
        with open(page, "rb") as f:
            f.seek(max(0, size - tail))
            s = f.read().decode("utf-8", "replace")
        i = s.find('<script type="application/json" id="lamina-run">')
        if i >= 0:
            run = json.loads(s[s.index(">", i) + 1:s.index("</script>", i)])
            return "layers %d vectors %d" % (run["totals"]["layers"], run["totals"]["vectors"])
        if tail >= size:
            sys.exit("viewer_bench.py: no lamina-run element in " + page)
        tail *= 4


def main():
    if sys.argv[1] == "totals":
        print(totals(sys.argv[2]))
        return
    page = sys.argv[2]
    runs = int(sys.argv[3]) if len(sys.argv) > 3 else 3
    for _ in range(runs):
        print(once(page), flush=True)


if __name__ == "__main__":
    main()
