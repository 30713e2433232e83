"""Reads the vectors, texts and circles of a DXF with ezdxf (the independent reader of the
tests), for tests/dxf_measure.rs to measure them against the CSV.

usage: python ezdxf_vectors.py FILE.dxf

Prints JSON: "layers" (name: [is on, is frozen]), "texts" (layer, text as ezdxf decodes
it), "circles" (layer, centre, radius) and "arrows": every LINE directly followed by a
SOLID on the same layer in the same colour whose base (the middle of its second and third
corners) is the LINE's end, i.e. the vector from the LINE's start to the SOLID's first
corner (its tip), with its layer and colour. Coordinates in the file's units (mm)."""
import json
import sys

from ezdxf import recover

doc, _ = recover.readfile(sys.argv[1])
msp = doc.modelspace()


def xy(v):
    return [v[0], v[1]]


out = {
    "units": doc.header.get("$INSUNITS", 0),
    "layers": {l.dxf.name: [l.is_on(), l.is_frozen()] for l in doc.layers},
    "texts": [],
    "circles": [],
    "arrows": [],
}
previous = None
for e in msp:
    kind = e.dxftype()
    if kind == "TEXT":
        out["texts"].append({"layer": e.dxf.layer, "text": e.plain_text(), "insert": xy(e.dxf.insert)})
    elif kind == "CIRCLE":
        out["circles"].append({"layer": e.dxf.layer, "center": xy(e.dxf.center), "radius": e.dxf.radius})
    elif kind == "SOLID" and previous is not None and previous.dxftype() == "LINE":
        same = previous.dxf.layer == e.dxf.layer and previous.dxf.get("color", 256) == e.dxf.get("color", 256)
        base = [(e.dxf.vtx1[k] + e.dxf.vtx2[k]) / 2 for k in (0, 1)]
        end = previous.dxf.end
        size = max(abs(e.dxf.vtx0[0] - base[0]), abs(e.dxf.vtx0[1] - base[1]), 1e-300)
        if same and abs(base[0] - end[0]) <= 1e-6 * size and abs(base[1] - end[1]) <= 1e-6 * size:
            out["arrows"].append({
                "layer": e.dxf.layer,
                "color": e.dxf.get("color", 256),
                "tail": xy(previous.dxf.start),
                "tip": xy(e.dxf.vtx0),
            })
    previous = e
print(json.dumps(out))
