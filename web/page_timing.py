#!/usr/bin/env python3
"""The live page's speed (issues 17 and 32's targets), measured in headless Chromium with the page's
own performance.now(): run it on a quiet machine, it is a benchmark, not a test.

    python3 web/page_timing.py DIR [ROUNDS]     (DIR: where web/build.sh wrote the pages)

For the four-bar and the shaper pages it reports, as medians (and the slowest tenth):
- first picture: from the navigation's start to the first picture drawn (the page's
  `window.mechdrawFirstPicture`, its status line), with the page's size;
- drag: real pointer events on the crank pin (the shaper: its crank pin too), each
  re-solving the mechanism and redrawing its frame (polygons and forces) — the handler's
  time, then the same with the browser's style and layout forced, which a user also waits for;
- a length change through its number field: the whole sweep solved again with polygons and
  forces and the picture redrawn (the page's `change`), and the rest that follows when the
  fields pause (summary, sheets, diagrams).
"""
import json, math, os, statistics, sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cdp import Browser
from live import READY, TO_SCREEN, settle

DIR = os.path.abspath(sys.argv[1])
ROUNDS = int(sys.argv[2]) if len(sys.argv) > 2 else 40
# One drag step as the page's pointermove handler does it, then style and layout forced.
DRAG_WITH_LAYOUT = """(function (name, points) {
  const out = [];
  for (const [x, y] of points) {
    const t0 = performance.now();
    live.drag(name, x, y);
    paint(live.dragged_moving(), () => live.dragged_frame());
    document.getElementById('stage').getBoundingClientRect();
    document.body.offsetHeight;
    out.push(performance.now() - t0);
  }
  return out;
})"""


def stats(xs):
    xs = sorted(xs)
    return {"median_ms": round(statistics.median(xs), 2), "p90_ms": round(xs[int(0.9 * (len(xs) - 1))], 2), "n": len(xs)}


def measure(b, name, point, radius, field, factor):
    page = b.open("file://" + os.path.join(DIR, name + ".html"), READY)
    out = {"page_bytes": os.path.getsize(os.path.join(DIR, name + ".html")),
           "first_picture_ms": round(page.eval("window.mechdrawFirstPicture"), 1),
           "status": page.eval("document.getElementById('status').textContent")}
    st = json.loads(page.eval("live.points(+document.getElementById('slider').value)"))
    _, x, y = next(p for p in st["points"] if p[0] == point)
    # Real pointer events: press on the point, move round a circle about it.
    sx, sy = page.eval(f"{TO_SCREEN}({x}, {y})")
    page.mouse("mousePressed", sx, sy)
    targets = [(x + radius * math.sin(2 * math.pi * i / ROUNDS), y + radius * (1 - math.cos(2 * math.pi * i / ROUNDS)))
               for i in range(1, ROUNDS + 1)]
    for tx, ty in targets:
        qx, qy = page.eval(f"{TO_SCREEN}({tx}, {ty})")
        page.mouse("mouseMoved", qx, qy)
    page.mouse("mouseReleased", qx, qy)
    out["drag_handler"] = stats(page.eval("window.mechdrawTimes.drag"))
    out["drag_with_layout"] = stats(page.eval(f"{DRAG_WITH_LAYOUT}({json.dumps(point)}, {json.dumps(targets)})"))
    # Length changes through the field, each followed by the rest once the fields pause.
    value = page.eval(f"+document.querySelector('input[type=number][data-path=\"{field}\"]').value")
    page.eval("window.mechdrawTimes.change = []; window.mechdrawTimes.rest = []")
    for i in range(ROUNDS // 4):
        v = value * (1 + factor * ((i % 2) * 2 - 1) * (1 + i) / ROUNDS)
        page.eval(f"""(function () {{
          const f = document.querySelector('input[type=number][data-path="{field}"]');
          f.value = '{v!r}'; f.dispatchEvent(new Event('change'));
        }})()""")
        settle(page)
    out["length_change"] = stats(page.eval("window.mechdrawTimes.change"))
    out["rest_after_change"] = stats(page.eval("window.mechdrawTimes.rest"))
    out["error"] = page.eval("document.getElementById('error').textContent")
    return out


with Browser() as b:
    result = {
        "fourbar-chebyshev": measure(b, "fourbar-chebyshev", "A", 0.005, "l_bc", 0.02),
        "shaper": measure(b, "shaper", "crank.A", 10.0, "body[0].points.A[0]", 0.02),
    }
print(json.dumps(result, indent=1))
