#!/usr/bin/env python3
"""What a user does on the live pages, in headless Chromium over the DevTools protocol
(web/cdp.py), and what the pages then show, printed as one JSON object for
tests/web_page.rs to compare with the command line. Screenshots go to DIR/screens/.
    python3 web/page_checks.py DIR      (DIR: where web/build.sh wrote the pages)"""
import base64, json, math, os, shutil, sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cdp import Browser
from live import READY, TO_SCREEN, settle

DIR = os.path.abspath(sys.argv[1])
SHOTS = os.path.join(DIR, "screens")
shutil.rmtree(os.path.join(DIR, "downloads"), ignore_errors=True)
os.makedirs(SHOTS, exist_ok=True)
out = {}


def url(name):
    return "file://" + os.path.join(DIR, name + ".html")


def point(state, name):
    return next(p for p in state["points"] if p[0] == name)


def drag(page, name, model_targets):
    """Presses on point `name` of the frame shown and moves through the model targets;
    returns the pointer's last position in model units (as the page maps it) and the
    state the page reached."""
    st = json.loads(page.eval("live.points(+document.getElementById('slider').value)"))
    _, x, y = point(st, name)
    sx, sy = page.eval(f"{TO_SCREEN}({x}, {y})")
    page.mouse("mousePressed", sx, sy)
    for tx, ty in model_targets:
        qx, qy = page.eval(f"{TO_SCREEN}({tx}, {ty})")
        # Whole CSS pixels, as a real pointer gives them.
        qx, qy = round(qx), round(qy)
        page.mouse("mouseMoved", qx, qy)
    at = page.eval(f"(function () {{ const p = modelPoint({{clientX: {qx}, clientY: {qy}}}); return [p.x, p.y]; }})()")
    page.mouse("mouseReleased", qx, qy)
    return at, page.eval("window.lastDrag || null")


with Browser() as b:
    # The triad: its modes and the pattern method's angle.
    page = b.open(url("triad-popa"), READY)
    out["triad"] = {"modes": page.eval("document.getElementById('modes').textContent"),
                    "error": page.eval("document.getElementById('error').textContent")}
    page.screenshot(os.path.join(SHOTS, "triad-popa.png"))
    out["triad"]["sheets"] = page.eval("JSON.parse(live.sheets()).map(([n, s]) => n)")
    out["triad"]["modes_sheet"] = page.eval("document.querySelector('#sheets svg') ? document.querySelector('#sheets svg').outerHTML.length : 0")
    # Pick mode 3 with its button: the picture draws it (the CLI's picture for --set mode=3).
    page.eval("document.querySelector('#modes button[data-mode=\"3\"]').click()")
    settle(page)
    out["triad_pick"] = {"picture": page.eval("live.frame(0)"),
                         "drawn": page.eval("JSON.parse(live.summary()).primary"),
                         "disabled": page.eval("[...document.querySelectorAll('#modes button')].filter((b) => b.disabled).map((b) => b.dataset.mode)"),
                         "caption": page.eval("document.getElementById('stage').textContent"),
                         "error": page.eval("document.getElementById('error').textContent")}
    page.screenshot(os.path.join(SHOTS, "triad-popa-mode-3.png"))


    # The four-bar: drag the crank pin round to 123.4567° (off the crank circle, at twice the
    # crank's length: the pointer moves in whole CSS pixels, and at 1.3 times the crank's
    # length a pixel turned the crank by about a degree once the frame's panels had room
    # for LibreCAD's widths).
    page = b.open(url("fourbar-chebyshev"), READY)
    out["fourbar_diagrams"] = page.eval("[...document.querySelectorAll('#diagrams figcaption')].map((c) => c.textContent)")
    st = json.loads(page.eval("live.points(0)"))
    _, ox, oy = point(st, "O1")
    _, ax, ay = point(st, "A")
    l1 = math.hypot(ax - ox, ay - oy)
    th = math.radians(123.4567)
    path = [(ox + 2.0 * l1 * math.cos(th * f), oy + 2.0 * l1 * math.sin(th * f)) for f in (0.25, 0.5, 0.75, 1.0)]
    at, state = drag(page, "A", path)
    out["fourbar_drag"] = {"pointer": at, "o1": [ox, oy], "state": state,
                           "drive": page.eval("+document.getElementById('stage').dataset.drive"),
                           "label": page.eval("document.getElementById('frame-label').textContent"),
                           "status": page.eval("document.getElementById('status').textContent")}
    page.screenshot(os.path.join(SHOTS, "fourbar-drag.png"))

    # The same page: l_bc = 0.2 through its field (non-Grashof), then the JSON and warnings.
    page.eval("""(function () {
      const f = document.querySelector('input[type=number][data-path="l_bc"]');
      f.value = '0.2'; f.dispatchEvent(new Event('change'));
    })()""")
    settle(page)
    out["fourbar_lbc"] = {"summary": json.loads(page.eval("live.summary()")),
                          "warnings": page.eval("document.getElementById('warnings').textContent"),
                          "error": page.eval("document.getElementById('error').textContent")}
    page.screenshot(os.path.join(SHOTS, "fourbar-lbc-0.2.png"))

    # An invalid TOML edit (on the page as it opened): the CLI's message, and the picture stays.
    page = b.open(url("fourbar-chebyshev"), READY)
    before = page.eval("document.getElementById('stage').innerHTML")
    page.eval("""(function () {
      const area = document.getElementById('scene');
      area.value = area.value.replace('l_bc = 0.10', 'l_bc = = 0.10');
      document.getElementById('apply').click();
    })()""")
    out["fourbar_bad_toml"] = {"error": page.eval("document.getElementById('error').textContent"),
                               "picture_kept": page.eval("document.getElementById('stage').innerHTML") == before,
                               "text": page.eval("document.getElementById('scene').value")}
    page.screenshot(os.path.join(SHOTS, "fourbar-bad-toml.png"))

    # Downloads, for every page: every file it offers, as bytes.
    out["downloads"] = {}
    for name in sorted(f[:-5] for f in os.listdir(DIR) if f.endswith(".html") and f != "index.html"):
        page = b.open(url(name), READY)
        page.eval("document.getElementById('download').click()")
        files = page.eval("""(async function () {
          const out = {};
          for (const a of document.querySelectorAll('#files a')) {
            const bytes = new Uint8Array(await (await fetch(a.href)).arrayBuffer());
            let s = '';
            for (let i = 0; i < bytes.length; i += 0x8000) s += String.fromCharCode.apply(null, bytes.subarray(i, i + 0x8000));
            out[a.textContent] = btoa(s);
          }
          return out;
        })()""")
        # Written under DIR/downloads/<scene>/ as a browser would save them.
        for file, b64 in files.items():
            path = os.path.join(DIR, "downloads", name, file)
            os.makedirs(os.path.dirname(path), exist_ok=True)
            with open(path, "wb") as f:
                f.write(base64.b64decode(b64))
        out["downloads"][name] = sorted(files)

    # The shaper: drag the rocker's end B; every joint must hold.
    page = b.open(url("shaper"), READY)
    at, state = drag(page, "rocker.B", [(-100.0, 540.0), (-150.0, 520.0)])
    out["shaper_drag"] = {"pointer": at, "state": state}
    page.screenshot(os.path.join(SHOTS, "shaper-drag.png"))

print(json.dumps(out))
