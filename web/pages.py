#!/usr/bin/env python3
"""Writes the live pages from web/page.html, the module and its glue (web/build.sh runs it;
src/run/page.rs writes the same pages from the binary):

    python3 web/pages.py DIR SCENE.toml ...

- DIR/<scene>.html: the page `mechdraw run` writes, self-contained (the module inline, base64);
- DIR/gallery/: the gallery `mechdraw web` writes: index.html, one page per scene and
  mechdraw-module.js, the module once (a script beside the pages: file:// and any server);
- DIR/mechdraw_bg.wasm.b64: the module deflated, in base64, for web/dist (no run encodes it
  again).
"""
import base64, html, json, pathlib, sys, zlib

out = pathlib.Path(sys.argv[1])
scenes = [pathlib.Path(s) for s in sys.argv[2:]]
template = pathlib.Path("web/page.html").read_text()
glue = (out / "mechdraw.js").read_text()
# The module deflated (raw deflate, zlib level 9: the page inflates it with the browser's
# DecompressionStream), in base64: what every page carries.
packer = zlib.compressobj(9, zlib.DEFLATED, -15, 9)
packed = packer.compress((out / "mechdraw_bg.wasm").read_bytes()) + packer.flush()
wasm = base64.b64encode(packed).decode()
(out / "mechdraw_bg.wasm.b64").write_text(wasm)
MODULE_SCRIPT = "mechdraw-module.js"


def module_inline():
    return f"<script>\n{glue}\n</script>\n<script>window.MECHDRAW_WASM = \"{wasm}\";</script>"


def page(text, file, module):
    out = template
    for key, value in [
        ("__SCENE_TOML__", text.replace("</", "<\\/")),
        ("__SCENE_SETS__", "[]"),
        ("<!--__MODULE__-->", module),
        ("__SCENE_FILE__", json.dumps(file)),
    ]:
        out = out.replace(key, value, 1)
    return out


def field(text, key, default):
    return next((l.split("=", 1)[1].strip().strip('"') for l in text.splitlines() if l.startswith(key)), default)


gallery = out / "gallery"
gallery.mkdir(exist_ok=True)
(gallery / MODULE_SCRIPT).write_text(f"{glue}\nwindow.MECHDRAW_WASM = \"{wasm}\";\n")
links = []
for scene in scenes:
    text = scene.read_text()
    own = out / (scene.stem + ".html")
    own.write_text(page(text, scene.name, module_inline()))
    (gallery / own.name).write_text(page(text, scene.name, f'<script src="{MODULE_SCRIPT}"></script>'))
    name, kind = field(text, "name", scene.stem), field(text, "kind", "")
    links.append(f'<li><a href="{html.escape(own.name)}">{html.escape(name)}</a> ({html.escape(kind)}, {html.escape(scene.name)})</li>')
    print(f"{own}: {own.stat().st_size} bytes")
index = ("<!DOCTYPE html>\n<html lang=\"en\">\n<head><meta charset=\"utf-8\"><meta name=\"viewport\" content=\"width=device-width, "
         "initial-scale=1\"><link rel=\"icon\" href=\"data:,\"><title>mechdraw live</title></head>\n<body>\n<h1>mechdraw live</h1>\n<p>Each page solves and draws "
         "its scene in the browser, with no server: drag a joint, change any number, edit the TOML, download the files the "
         "command line writes.</p>\n<ul>\n" + "\n".join(links) + "\n</ul>\n</body>\n</html>\n")
(gallery / "index.html").write_text(index)
total = sum(f.stat().st_size for f in gallery.iterdir())
print(f"{gallery}: {len(links)} pages, {total} bytes")
