#!/usr/bin/env python3
"""What a student and a teacher do on the live pages, in headless Chromium over the DevTools
protocol (web/cdp.py), and what the pages then show, printed as one JSON object for
tests/web_page.rs to compare with the command line. Screenshots go to DIR/screens/.
    python3 web/page_checks.py DIR      (DIR: where web/build.sh wrote the pages)"""
import base64, json, math, os, shutil, subprocess, sys, tempfile, time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cdp import Browser
from live import READY, TO_SCREEN, settle

DIR = os.path.abspath(sys.argv[1])
SHOTS = os.path.join(DIR, "screens")
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
shutil.rmtree(os.path.join(DIR, "downloads"), ignore_errors=True)
os.makedirs(SHOTS, exist_ok=True)
out = {"console_errors": {}}


def url(name):
    return "file://" + os.path.join(DIR, name + ".html")


def laptop(page):
    """The window a student's laptop has: 1366 × 768 CSS pixels."""
    page.call("Emulation.setDeviceMetricsOverride", width=1366, height=768, deviceScaleFactor=1, mobile=False)


def phone(page):
    """A phone: 390 × 844 CSS pixels at 3 device pixels each, touch."""
    page.call("Emulation.setDeviceMetricsOverride", width=390, height=844, deviceScaleFactor=3, mobile=True)
    page.call("Emulation.setTouchEmulationEnabled", enabled=True, maxTouchPoints=5)


def open_page(b, name, setup=laptop, fresh=True, link=None):
    """Opens a page as a student would on a laptop; `fresh` forgets the edits kept in the
    browser (file:// pages share one storage)."""
    page = b.open(link or url(name), READY, setup=setup)
    if fresh and page.eval("localStorage.length") and link is None:
        page.eval("localStorage.clear()")
        page = b.open(url(name), READY, setup=setup)
    return page


def note_errors(name, page):
    errs = page.errors()
    if errs:
        out["console_errors"].setdefault(name, []).extend(errs)


def point(state, name):
    return next(p for p in state["points"] if p[0] == name)


def screen(page, x, y):
    return page.eval(f"{TO_SCREEN}({x}, {y})")


def drag(page, name, model_targets, edit=False):
    """Presses on point `name` of the picture and moves through the model targets; returns the
    pointer's last position in model units (as the page maps it) and the drag's state."""
    grips = "JSON.parse(live.edit_points(+slider.value))" if edit else "JSON.parse(live.points(+slider.value)).points"
    _, x, y = next(p for p in page.eval(grips) if p[0] == name)
    sx, sy = screen(page, x, y)
    page.mouse("mousePressed", sx, sy)
    for tx, ty in model_targets:
        qx, qy = screen(page, tx, ty)
        # Whole CSS pixels, as a real pointer gives them.
        qx, qy = round(qx), round(qy)
        page.mouse("mouseMoved", qx, qy)
    at = page.eval(f"(function () {{ const p = toModel({{clientX: {qx}, clientY: {qy}}}); return [p.x, p.y]; }})()")
    page.mouse("mouseReleased", qx, qy)
    return at, page.eval("window.lastDrag || null")


def click_model(page, x, y):
    sx, sy = screen(page, x, y)
    sx, sy = round(sx), round(sy)
    page.mouse("mousePressed", sx, sy)
    page.mouse("mouseReleased", sx, sy)


def set_field(page, path, value):
    """Types `value` into the field of `path` and leaves it (a change event)."""
    return page.eval(f"""(function () {{
      const f = document.querySelector('input[type=number][data-path="{path}"]');
      if (!f) return 'no field ' + {json.dumps(path)};
      f.value = {json.dumps(str(value))}; f.dispatchEvent(new Event('change'));
      return '';
    }})()""")


def text(page, id_):
    return page.eval(f"document.getElementById('{id_}').textContent")


with Browser() as b:
    # ---- The triad: its modes and the pattern method's angle; pick mode 3. ----
    page = open_page(b, "triad-popa")
    out["triad"] = {"modes": text(page, "modes"), "error": text(page, "error"),
                    "sheets": page.eval("JSON.parse(live.sheets()).map(([n, s]) => n)"),
                    "modes_sheet": page.eval("document.querySelector('#sheets svg') ? document.querySelector('#sheets svg').outerHTML.length : 0")}
    page.screenshot(os.path.join(SHOTS, "triad-popa.png"))
    page.eval("document.querySelector('#modes button[data-mode=\"3\"]').click()")
    settle(page)
    out["triad_pick"] = {"picture": page.eval("live.frame(0)"),
                         "drawn": page.eval("JSON.parse(live.summary()).primary"),
                         "disabled": page.eval("[...document.querySelectorAll('#modes button')].filter((b) => b.disabled).map((b) => b.dataset.mode)"),
                         "caption": text(page, "stage"), "error": text(page, "error"),
                         "toml": page.eval("document.getElementById('scene').value")}
    page.screenshot(os.path.join(SHOTS, "triad-popa-mode-3.png"))
    note_errors("triad-popa", page)

    # ---- The four-bar as it opens on a laptop: sizes of what a student sees. ----
    page = open_page(b, "fourbar-chebyshev")
    st = json.loads(page.eval("live.points(0)"))
    _, ox, oy = point(st, "O1")
    _, ax, ay = point(st, "A")
    (s0x, s0y), (s1x, s1y) = screen(page, ox, oy), screen(page, ax, ay)
    out["fourbar_open"] = {
        "crank_px": math.hypot(s1x - s0x, s1y - s0y),
        "stage": page.eval("(r => [r.left, r.top, r.width, r.height])(document.getElementById('stage').getBoundingClientRect())"),
        "diagrams_top": page.eval("(f => f ? f.getBoundingClientRect().top : null)(document.querySelector('#diagrams figure'))"),
        "error_top": page.eval("document.getElementById('error').getBoundingClientRect().top"),
        "hint": text(page, "hint"),
        "status": text(page, "status"),
        "viewport": page.eval("document.querySelector('meta[name=viewport]').content"),
        "first_picture_ms": page.eval("window.mechdrawFirstPicture"),
        # Tab stops before Play and before the picture (what Tab reaches: not the items of a
        # closed menu, only its summary).
        "tab_order": page.eval("""[...document.querySelectorAll('button, input, select, textarea, summary, [tabindex]')]
            .filter((e) => e.tabIndex >= 0 && !e.disabled && e.offsetParent !== null)
            .filter((e) => e.tagName === 'SUMMARY' || !e.closest('details:not([open])'))
            .map((e) => e.id || e.textContent.trim().slice(0, 12))"""),
        "markers": page.eval("document.querySelectorAll('#diagrams .marker').length"),
        "diagrams": page.eval("document.querySelectorAll('#diagrams figure').length"),
    }
    out["fourbar_diagrams"] = page.eval("[...document.querySelectorAll('#diagrams figcaption')].map((c) => c.textContent)")
    page.screenshot(os.path.join(SHOTS, "fourbar-open-1366x768.png"))
    # Hovering the crank pin: a pointer and a ring show it can be dragged.
    page.mouse("mouseMoved", s1x, s1y, buttons=0)
    out["fourbar_hover"] = {"cursor": page.eval("getComputedStyle(document.getElementById('stage')).cursor"),
                            "ring": page.eval("document.querySelectorAll('#overlay circle').length")}

    # Drag the crank pin round to 123.4567° (off the crank circle, at twice its length): the
    # scrubber and the diagrams' markers follow.
    l1 = math.hypot(ax - ox, ay - oy)
    th = math.radians(123.4567)
    path = [(ox + 2.0 * l1 * math.cos(th * f), oy + 2.0 * l1 * math.sin(th * f)) for f in (0.25, 0.5, 0.75, 1.0)]
    at, state = drag(page, "A", path)
    out["fourbar_drag"] = {"pointer": at, "o1": [ox, oy], "state": state,
                           "drive": page.eval("+document.getElementById('stage').dataset.drive"),
                           "label": text(page, "frame-label"), "status": text(page, "status"),
                           "slider": page.eval("+slider.value"),
                           "marker": page.eval("(m => m ? m.querySelector('circle').getAttribute('cx') : null)(document.querySelector('#diagrams .marker'))"),
                           "marker_expected": page.eval(f"JSON.parse(live.diagram_markers({state['position'] if state else 0}))[0]")}
    page.screenshot(os.path.join(SHOTS, "fourbar-drag.png"))
    # Play goes on from where the drag left the crank.
    page.eval("document.getElementById('play').click()")
    time.sleep(0.3)
    page.eval("document.getElementById('play').click()")
    out["fourbar_drag"]["after_play"] = page.eval("+slider.value")

    # l_bc = 0.2 through its field (non-Grashof): the JSON and the warnings.
    set_field(page, "l_bc", "0.2")
    settle(page)
    out["fourbar_lbc"] = {"summary": json.loads(page.eval("live.summary()")), "warnings": text(page, "warnings"),
                          "error": text(page, "error")}
    page.screenshot(os.path.join(SHOTS, "fourbar-lbc-0.2.png"))
    note_errors("fourbar-chebyshev", page)

    # ---- A refused field: the CLI's words at the field, the field back to the model's value. ----
    page = open_page(b, "fourbar-chebyshev")
    set_field(page, "l1", "-0.04")
    out["refused_field"] = page.eval("""(function () {
      const f = document.querySelector('input[type=number][data-path="l1"]');
      const row = f.closest('.field');
      return {value: f.value, message: row.querySelector('.msg').textContent, refused: row.classList.contains('refused'),
              model: JSON.parse(live.parameters()).find((p) => p.path === 'l1').value,
              label: row.querySelector('label').textContent, top_error: document.getElementById('error').textContent};
    })()""")
    page.screenshot(os.path.join(SHOTS, "fourbar-refused-field.png"))

    # ---- Edit mode: drag the pivot C by (+0.01, +0.005) m; then undo and redo. ----
    page = open_page(b, "fourbar-chebyshev")
    before = page.eval("document.getElementById('scene').value")
    page.eval("document.querySelector('header [data-mode=edit]').click()")
    grid = page.eval("grid()")
    _, cx, cy = next(p for p in page.eval("JSON.parse(live.edit_points(+slider.value))") if p[0] == "C")
    # A known offset on the page's grid: 5 steps right, 2 up.
    step = grid["step"]
    target = (round(cx + 5 * step, 9), round(cy + 2 * step, 9))
    drag(page, "C", [(cx + 2 * step, cy + step), target], edit=True)
    settle(page)
    after = page.eval("document.getElementById('scene').value")
    fields = page.eval("Object.fromEntries([...document.querySelectorAll('input[type=number][data-path]')].map((f) => [f.dataset.path, +f.value]))")
    out["edit_c"] = {"before": before, "after": after, "grid": grid, "target": target, "c": [fields.get("c[0]"), fields.get("c[1]")],
                     "error": text(page, "error"), "session_text": page.eval("live.scene_text()")}
    page.screenshot(os.path.join(SHOTS, "fourbar-edit-c.png"))
    page.eval("document.getElementById('undo').click()")
    settle(page)
    out["undo"] = {"text": page.eval("document.getElementById('scene').value"), "session": page.eval("live.scene_text()"),
                   "c0": page.eval("+document.querySelector('input[data-path=\"c[0]\"]').value")}
    # Ctrl+Shift+Z redoes (outside the editor).
    page.eval("document.getElementById('stage').focus()")
    page.key("Z", code="KeyZ", modifiers=2 | 8)
    settle(page)
    out["redo"] = {"text": page.eval("document.getElementById('scene').value"), "session": page.eval("live.scene_text()")}

    # ---- The share link: copy it, open it in a fresh tab: the same text, the same picture. ----
    page.eval("document.getElementById('share').click()")
    link = page.eval("document.getElementById('share-link').value")
    frames = page.eval("[0, 90, 200].map((k) => live.frame(k))")
    shared = b.open(link, READY, setup=laptop)
    out["share"] = {"link_length": len(link), "link_prefix": link.split("#", 1)[1][:9],
                    "same_text": shared.eval("document.getElementById('scene').value") == out["redo"]["text"],
                    "same_session": shared.eval("live.scene_text()") == out["redo"]["session"],
                    # The page that was edited holds its polygons' scales (Session::replace);
                    # the fresh tab draws the text as the command line does.
                    "same_frames": shared.eval("[0, 90, 200].map((k) => live.frame(k))") == frames,
                    "frames": shared.eval("[0, 90, 200].map((k) => live.frame(k))"),
                    "notice": text(shared, "notice"), "error": text(shared, "error")}
    shared.screenshot(os.path.join(SHOTS, "fourbar-shared.png"))
    # A link cut short: the page says so and opens its own scene.
    cut = b.open(link[:-9], READY, setup=laptop)
    out["share_cut"] = {"error": text(cut, "error"), "text_is_original": cut.eval("live.scene_text()") == before}
    # From a newer mechdraw.
    newer = b.open(link.replace("#scene=v1.", "#scene=v7."), READY, setup=laptop)
    out["share_newer"] = {"error": text(newer, "error")}
    note_errors("share", shared)

    # ---- Saved in the browser: the edit is back after a reload; a saved text that no longer opens. ----
    again = b.open(url("fourbar-chebyshev"), READY, setup=laptop)
    out["reload"] = {"text": again.eval("document.getElementById('scene').value"), "notice": text(again, "notice")}
    broken = before.replace("l_bc = 0.10", "l_bc = -0.10")
    again.eval(f"localStorage.setItem('mechdraw/fourbar-chebyshev.toml', {json.dumps(broken)})")
    bad = b.open(url("fourbar-chebyshev"), READY, setup=laptop)
    out["saved_broken"] = {"error": text(bad, "error"), "editor": bad.eval("document.getElementById('scene').value"),
                           "session": bad.eval("live.scene_text()")}
    bad.screenshot(os.path.join(SHOTS, "fourbar-saved-broken.png"))
    bad.eval("localStorage.clear()")

    # ---- Open a .toml that is not a scene, and one that is not text. ----
    page = open_page(b, "fourbar-chebyshev")
    tmp = tempfile.mkdtemp()
    not_scene = os.path.join(tmp, "notes.toml")
    with open(not_scene, "w") as f:
        f.write("title = \"my notes\"\n")
    binary = os.path.join(tmp, "picture.toml")
    with open(binary, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n\x00\x00\x00\rIHDR\xff\xfe")
    picture = page.eval("live.frame(0)")
    results = {}
    for name, path_ in [("not_scene", not_scene), ("not_text", binary)]:
        node = page.call("DOM.getDocument")["root"]["nodeId"]
        inp = page.call("DOM.querySelector", nodeId=node, selector="#open-file")["nodeId"]
        page.call("DOM.setFileInputFiles", nodeId=inp, files=[path_])
        time.sleep(0.5)
        results[name] = {"error": text(page, "error"), "picture_kept": page.eval("live.frame(0)") == picture,
                         "editor": page.eval("document.getElementById('scene').value")}
    out["open_file"] = results
    # The bad file is in the editor and in the history: Undo brings the scene back.
    page.eval("document.getElementById('undo').click()")
    out["open_file"]["undo"] = page.eval("document.getElementById('scene').value") == before
    shutil.rmtree(tmp, ignore_errors=True)

    # ---- An invalid TOML edit: the CLI's message at the top, its line marked, the picture kept. ----
    page = open_page(b, "fourbar-chebyshev")
    before_picture = page.eval("document.getElementById('stage').innerHTML")
    page.eval("""(function () {
      document.querySelector('[data-tab=toml-tab]').click();
      const area = document.getElementById('scene');
      area.value = area.value.replace('l_bc = 0.10', 'l_bc = = 0.10');
      document.getElementById('apply').click();
    })()""")
    out["fourbar_bad_toml"] = {"error": text(page, "error"),
                               "picture_kept": page.eval("document.getElementById('stage').innerHTML") == before_picture,
                               "text": page.eval("document.getElementById('scene').value"),
                               "marked_line": page.eval("(e => e ? +e.textContent : 0)(document.querySelector('#gutter .bad'))")}
    page.screenshot(os.path.join(SHOTS, "fourbar-bad-toml.png"))

    # ---- Build the Chebyshev four-bar from an empty page by clicks. ----
    page = open_page(b, "fourbar-chebyshev")
    page.eval("document.getElementById('new-si').click()")
    settle(page)
    steps = []

    def tool(name):
        page.eval(f"document.querySelector('#tools [data-tool={name}]').click()")

    def click(x, y):
        click_model(page, x, y)
        steps.append({"at": [x, y], "grid": page.eval("grid().step"), "error": text(page, "error"),
                      "notice": text(page, "notice")})

    tool("pivot"); click(0.0, 0.0); click(0.08, 0.0)
    tool("link"); click(0.0, 0.0); click(0.04, 0.0)
    tool("ternary"); click(0.04, 0.0); click(0.06, 0.1); click(0.08, 0.2)
    tool("link"); click(0.06, 0.1); click(0.08, 0.0)
    page.eval("document.getElementById('omega').value = '20'")
    tool("driver"); click(0.02, 0.0)
    tool("trace"); click(0.08, 0.2)
    page.screenshot(os.path.join(SHOTS, "build-sketch.png"))
    out["build_sketch"] = {"steps": steps, "toml": page.eval("document.getElementById('scene').value"),
                           "error": text(page, "error")}
    # The lengths typed in their fields, as a student would after drawing roughly.
    page.eval("document.querySelector('header [data-mode=move]').click()")
    typed = {}
    for path_, value in [("body[1].points.B[0]", "0.1"), ("body[1].points.C[0]", "0.2"), ("body[1].points.C[1]", "0"),
                         ("body[2].points.O2[0]", "0.1")]:
        typed[path_] = set_field(page, path_, value) or text(page, "error")
    settle(page)
    page.eval("document.querySelector('#download').click()")
    csv = page.eval("""(async function () {
      const a = [...document.querySelectorAll('#files a')].find((a) => a.dataset.file.endsWith('.csv'));
      return a ? await (await fetch(a.href)).text() : '';
    })()""")
    out["build"] = {"typed": typed, "toml": page.eval("live.scene_text()"), "error": text(page, "error"),
                    "points_90": json.loads(page.eval("live.points(90)") or "null"), "csv": csv,
                    "labels": page.eval("[...document.querySelectorAll('#fields label')].map((l) => l.textContent)")}
    page.eval("slider.value = 90; slider.dispatchEvent(new Event('input'))")
    page.screenshot(os.path.join(SHOTS, "build-chebyshev-solved.png"))
    # A step that leaves the mechanism unsolvable (a link hanging from B): the CLI's words,
    # the picture kept, the draft in the editor and the history.
    picture = page.eval("live.frame(0)")
    page.eval("document.querySelector('header [data-mode=build]').click()")
    tool("link"); click(0.06, 0.1); click(0.12, 0.15)
    out["build_bad_step"] = {"error": text(page, "error"), "picture_kept": page.eval("live.frame(0)") == picture,
                             "draft_kept": "link4" in page.eval("document.getElementById('scene').value")}
    page.screenshot(os.path.join(SHOTS, "build-bad-step.png"))
    note_errors("build", page)

    # ---- A phone: 390 × 844, touch; the picture full width, a touch-drag turns the crank. ----
    page = open_page(b, "fourbar-chebyshev", setup=phone)
    st = json.loads(page.eval("live.points(0)"))
    _, ax, ay = point(st, "A")
    _, ox, oy = point(st, "O1")
    sx, sy = screen(page, ax, ay)
    out["phone"] = {"stage_width": page.eval("document.getElementById('stage').getBoundingClientRect().width"),
                    "inner_width": page.eval("innerWidth"),
                    "stage_top": page.eval("document.getElementById('stage').getBoundingClientRect().top")}
    page.screenshot(os.path.join(SHOTS, "phone-390x844.png"))
    qx, qy = screen(page, ox, oy + 1.5 * math.hypot(ax - ox, ay - oy))
    page.touch("touchStart", [(sx, sy)])
    for f in (0.3, 0.6, 1.0):
        page.touch("touchMove", [(sx + (qx - sx) * f, sy + (qy - sy) * f)])
    page.touch("touchEnd", [])
    out["phone"]["drive"] = page.eval("+document.getElementById('stage').dataset.drive")
    out["phone"]["expected"] = math.degrees(math.atan2(1.0, 0.0))
    page.screenshot(os.path.join(SHOTS, "phone-touch-drag.png"))
    note_errors("phone", page)

    # ---- The keyboard: Tab to the picture, N picks a joint, an arrow key moves it. ----
    page = open_page(b, "fourbar-chebyshev")
    page.eval("document.getElementById('stage').focus()")
    page.key("n", code="KeyN", text="n")
    page.key("n", code="KeyN", text="n")
    picked = page.eval("selected && selected.name")
    for _ in range(3):
        page.key("ArrowUp")
    out["keyboard"] = {"picked": picked, "drive": page.eval("document.getElementById('stage').dataset.drive || null"),
                       "label": text(page, "frame-label")}

    # ---- Downloads, for every page: every file it offers, as bytes; no console error. ----
    out["downloads"] = {}
    out["download_sizes"] = {}
    for name in sorted(f[:-5] for f in os.listdir(DIR) if f.endswith(".html") and f != "index.html"):
        page = open_page(b, name)
        page.eval("document.getElementById('download').click()")
        files = page.eval("""(async function () {
          const out = {};
          for (const a of document.querySelectorAll('#files a')) {
            const bytes = new Uint8Array(await (await fetch(a.href)).arrayBuffer());
            let s = '';
            for (let i = 0; i < bytes.length; i += 0x8000) s += String.fromCharCode.apply(null, bytes.subarray(i, i + 0x8000));
            out[a.dataset.file] = [btoa(s), a.querySelector('.size').textContent];
          }
          return out;
        })()""")
        for file, (b64, _) in files.items():
            path_ = os.path.join(DIR, "downloads", name, file)
            os.makedirs(os.path.dirname(path_), exist_ok=True)
            with open(path_, "wb") as f:
                f.write(base64.b64decode(b64))
        out["downloads"][name] = sorted(files)
        out["download_sizes"][name] = {k: v[1] for k, v in files.items()}
        note_errors(name, page)

    # ---- The report download: A3, two chosen positions; a position outside the motion. ----
    page = open_page(b, "fourbar-chebyshev")
    page.eval("document.getElementById('download').click()")
    page.eval("document.getElementById('report-paper').value = 'a3'")
    page.eval("document.getElementById('report-positions').value = '0,90'")
    page.eval("document.getElementById('report-make').click()")
    report = page.eval("""(async function () {
      const out = {};
      for (const a of document.querySelectorAll('#report-files a')) {
        const bytes = new Uint8Array(await (await fetch(a.href)).arrayBuffer());
        let s = '';
        for (let i = 0; i < bytes.length; i += 0x8000) s += String.fromCharCode.apply(null, bytes.subarray(i, i + 0x8000));
        out[a.dataset.file] = btoa(s);
      }
      return out;
    })()""")
    out["report"] = {"files": sorted(report), "error": text(page, "report-error"),
                     "order": page.eval("[...document.querySelectorAll('#report-files a')].map((a) => a.download)")}
    for file, b64 in report.items():
        path_ = os.path.join(DIR, "downloads", "report", file)
        os.makedirs(os.path.dirname(path_), exist_ok=True)
        with open(path_, "wb") as f:
            f.write(base64.b64decode(b64))
    page.screenshot(os.path.join(SHOTS, "report-download.png"))
    page.eval("document.getElementById('report-positions').value = '400'")
    page.eval("document.getElementById('report-make').click()")
    out["report"]["bad"] = {"error": text(page, "report-error"),
                            "files": page.eval("document.querySelectorAll('#report-files a').length")}
    note_errors("report", page)

    # ---- The shaper: drag the rocker's end B; every joint must hold. ----
    page = open_page(b, "shaper")
    at, state = drag(page, "rocker.B", [(-100.0, 540.0), (-150.0, 520.0)])
    out["shaper_drag"] = {"pointer": at, "state": state}
    page.screenshot(os.path.join(SHOTS, "shaper-drag.png"))
    page = open_page(b, "slider-crank")
    page.screenshot(os.path.join(SHOTS, "slider-crank-open.png"))
    note_errors("slider-crank", page)

    # ---- A synthesis: drag the required position P2 (no mode to pick), change ψ in its field,
    # open the design, come back with Undo. ----
    page = open_page(b, "synthesis-motion")
    grips = page.eval("JSON.parse(live.edit_points(0))")
    _, px, py = next(p for p in grips if p[0] == "P2")
    grid = page.eval("grid()")
    step = grid["step"]
    # A grid point 5 steps right and 2 up of the one nearest P2 (P2 itself need not be on the
    # grid): the pointer lands on it, not half-way between two, so its snap is not a coin toss.
    on_grid = lambda v: math.floor(v / step + 0.5) * step
    target = (round(on_grid(px) + 5 * step, 9), round(on_grid(py) + 2 * step, 9))
    drag(page, "P2", [(px + 2 * step, py + step), target], edit=True)
    settle(page)
    out["synthesis_drag"] = {
        "grips": [p[0] for p in grips], "grid": grid, "grid_after": page.eval("grid()"), "target": target,
        "hint": text(page, "hint"), "design_shown": page.eval("!document.getElementById('design').hidden"),
        "mode": page.eval("document.body.dataset.mode"), "text": page.eval("document.getElementById('scene').value"),
        "p2": next(p[1:] for p in page.eval("JSON.parse(live.edit_points(0))") if p[0] == "P2"),
        "fields": [page.eval(f"+document.querySelector('input[data-path=\"positions[1].at[{i}]\"]').value") for i in (0, 1)],
        "picture": page.eval("live.frame(0)"), "error": text(page, "error")}
    page.screenshot(os.path.join(SHOTS, "synthesis-motion-drag.png"))
    note_errors("synthesis-motion", page)

    page = open_page(b, "synthesis-crank-rocker")
    refused = set_field(page, "psi_deg", "45")
    settle(page)
    synthesis_text = page.eval("live.scene_text()")
    out["synthesis_psi"] = {"refused": refused, "error": text(page, "error"), "picture": page.eval("live.frame(0)"),
                            "design": page.eval("live.design()"), "text": synthesis_text,
                            "stage": page.eval("document.getElementById('stage').innerHTML.length")}
    page.screenshot(os.path.join(SHOTS, "synthesis-crank-rocker-psi45.png"))
    page.eval("document.getElementById('design').click()")
    settle(page)
    out["synthesis_open"] = {"text": page.eval("live.scene_text()"), "editor": page.eval("document.getElementById('scene').value"),
                             "positions": page.eval("live.positions()"), "error": text(page, "error"),
                             "design_shown": page.eval("!document.getElementById('design').hidden"),
                             "frame0": page.eval("live.frame(0)"), "title": page.eval("document.title"),
                             "heading": text(page, "title"), "file": page.eval("live.file()"),
                             "stored_design": page.eval("localStorage.getItem('mechdraw/synthesis-crank-rocker-design.toml')"),
                             "stored_synthesis": page.eval("localStorage.getItem('mechdraw/synthesis-crank-rocker.toml')")}
    page.screenshot(os.path.join(SHOTS, "synthesis-crank-rocker-design.png"))
    page.eval("document.getElementById('undo').click()")
    settle(page)
    out["synthesis_back"] = {"text": page.eval("live.scene_text()"), "design_shown": page.eval("!document.getElementById('design').hidden"),
                             "title": page.eval("document.title"), "file": page.eval("live.file()")}
    note_errors("synthesis-crank-rocker", page)

    # ---- The gallery: every page from file:// and from a static web server. ----
    gallery = os.path.join(DIR, "gallery")
    out["gallery"] = {"file": {}, "http": {}}
    server = subprocess.Popen([sys.executable, "-m", "http.server", "0", "--bind", "127.0.0.1", "--directory", gallery],
                              stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    try:
        line = server.stdout.readline()
        port = int(line.split("port ")[1].split()[0])
        for name in sorted(f[:-5] for f in os.listdir(gallery) if f.endswith(".html") and f != "index.html"):
            for how, base in [("file", "file://" + gallery), ("http", f"http://127.0.0.1:{port}")]:
                page = b.open(f"{base}/{name}.html", READY, setup=laptop)
                out["gallery"][how][name] = {"positions": page.eval("live.positions()"), "error": text(page, "error")}
                note_errors(f"gallery {how} {name}", page)
    finally:
        server.terminate()
        server.wait()

print(json.dumps(out))
