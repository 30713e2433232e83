"""Strict DXF audit with ezdxf, the independent reader used by the tests.

usage: python ezdxf_audit.py FILE.dxf [...]
Exit 0 only if every file recovers with 0 errors and 0 fixes, audits with 0 errors and
0 fixes, and every DIMENSION has its own existing, non-empty anonymous geometry block."""
import sys

import ezdxf
from ezdxf import recover

rc = 0
for path in sys.argv[1:]:
    doc, auditor = recover.readfile(path)
    audit = doc.audit()
    problems = []
    problems += [f"recover error {e.code}: {e.message}" for e in auditor.errors]
    problems += [f"recover fix {f.code}: {f.message}" for f in auditor.fixes]
    problems += [f"audit error {e.code}: {e.message}" for e in audit.errors]
    problems += [f"audit fix {f.code}: {f.message}" for f in audit.fixes]
    msp = doc.modelspace()
    for dim in msp.query("DIMENSION"):
        name = dim.dxf.get("geometry", "")
        if not name.startswith("*D"):
            problems.append(f"DIMENSION {dim.dxf.handle}: geometry block {name!r} is not an anonymous *D block")
            continue
        block = doc.blocks.get(name)
        if block is None or len(block) == 0:
            problems.append(f"DIMENSION {dim.dxf.handle}: geometry block {name!r} missing or empty")
    print(f"{path}: DXF {doc.dxfversion}, {len(msp)} entities, {len(doc.layers)} layers: "
          + ("clean" if not problems else f"{len(problems)} problems"))
    for p in problems[:50]:
        print("   ", p)
    if problems:
        rc = 1
sys.exit(rc)
