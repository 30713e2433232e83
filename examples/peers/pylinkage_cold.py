#!/usr/bin/env python3
"""pylinkage's cold sweep, timed the way `mechdraw bench` times its own "Assur groups (cold)"
rows: a fresh linkage for every sweep (its components built, compiled to pylinkage's solver
data, then 360 positions by `Linkage.step_fast`, numba's path when numba is installed),
nanoseconds per position, on the two problems of docs/bench.md:

- the Chebyshev four-bar (templates/fourbar-chebyshev.toml): crank O1A about O1, coupler
  A-B-M (an RRR dyad for B, a fixed point M on the line A->B), rocker CB; crank angle
  0, 1, ..., 359 degrees;
- the shaper (templates/shaper.toml): crank O1A, the rocker O3B through the slider at A
  (pylinkage has no RPR dyad; the rocker's end B is a fixed point on the line O3->A, which is
  what the RPR dyad gives for B), the link BE and the ram point E on the line y = 600 mm (an
  RRP dyad); crank angle 0, 1, ..., 359 degrees.

It prints one JSON object on stdout: pylinkage's and numba's versions, and per problem the
time per position and every position's points (A, B, M; A, B, E), which `mechdraw bench`
measures against its independent references (the error column; src/bench/peers/).

Run it alone (a venv with `pip install pylinkage numba`):

    python3 examples/peers/pylinkage_cold.py            # the full timing
    python3 examples/peers/pylinkage_cold.py --quick    # a smoke run

`mechdraw bench` runs it with the Python that imports pylinkage (`python3`, or
`--peers-python PATH`) and adds the rows "pylinkage (cold)". The geometry can be given as JSON
(`--geometry`, what `mechdraw bench` passes, read from its templates); without it the
templates' numbers below are used.
"""

import argparse
import json
import math
import statistics
import sys
import time

# The templates' numbers (SI for the four-bar, mm for the shaper), used without --geometry.
DEFAULT_GEOMETRY = {
    "fourbar": {
        "o1": [0.0, 0.0],
        "c": [0.08, 0.0],
        "l1": 0.04,
        "l_ab": 0.10,
        "l_bc": 0.10,
        # M on the coupler: |AM| and the angle of A->M from A->B (rad).
        "l_am": 0.20,
        "angle_am": 0.0,
        # B at crank angle 0 (which of the two intersections: left of A->C).
        "b0": [0.06, 0.09797958971132713],
    },
    "shaper": {
        "o1": [0.0, 300.0],
        "o3": [0.0, 0.0],
        "r": 125.0,
        "l": 600.0,
        "l_be": 150.0,
        "y_ram": 600.0,
        # E at crank angle 0 (x_E > x_B).
        "e0": [None, 600.0],
    },
}

POSITIONS = 360


def fourbar(g):
    """A fresh four-bar: ground O1 and C, crank O1A, B by an RRR dyad, M fixed on A->B."""
    from pylinkage import Crank, FixedDyad, Ground, Linkage, RRRDyad

    step = math.tau / POSITIONS
    o1 = Ground(*g["o1"], name="O1")
    c = Ground(*g["c"], name="C")
    # step_fast moves the crank before it solves a position: start one step early, so the
    # positions are at 0, 1, ..., 359 degrees.
    crank = Crank(anchor=o1, radius=g["l1"], angular_velocity=step, initial_angle=-step, name="A")
    b = RRRDyad(crank.output, c, distance1=g["l_ab"], distance2=g["l_bc"], x=g["b0"][0], y=g["b0"][1], name="B")
    m = FixedDyad(crank.output, b, distance=g["l_am"], angle=g["angle_am"], name="M")
    return Linkage([o1, c, crank, b, m], name="fourbar-chebyshev"), {"A": 2, "B": 3, "M": 4}


def shaper(g):
    """A fresh shaper: crank O1A, rocker end B fixed on O3->A, E by an RRP dyad on the ram's line."""
    from pylinkage import Crank, FixedDyad, Ground, Linkage, RRPDyad

    step = math.tau / POSITIONS
    o1 = Ground(*g["o1"], name="O1")
    o3 = Ground(*g["o3"], name="O3")
    g1 = Ground(0.0, g["y_ram"], name="guide1")
    g2 = Ground(1.0, g["y_ram"], name="guide2")
    crank = Crank(anchor=o1, radius=g["r"], angular_velocity=step, initial_angle=-step, name="A")
    b = FixedDyad(o3, crank.output, distance=g["l"], angle=0.0, name="B")
    # E's start hint: right of B on the ram's line (the template's branch, x_E > x_B).
    ex = g["e0"][0]
    if ex is None:
        ex = b.x + g["l_be"]
    e = RRPDyad(b, g1, g2, distance=g["l_be"], x=ex, y=g["e0"][1], name="E")
    return Linkage([o1, o3, g1, g2, crank, b, e], name="shaper"), {"A": 4, "B": 5, "E": 6}


def sweep(build, g):
    """One cold sweep: a fresh linkage, compiled and run over every position."""
    linkage, _ = build(g)
    return linkage.step_fast(iterations=POSITIONS)


def time_cold(build, g, batches, min_batch_s):
    """Median nanoseconds per position over `batches` batches of whole cold sweeps."""
    sweep(build, g)  # numba's JIT compile (once a process) stays out of the figure
    n = 1
    while True:
        t0 = time.perf_counter_ns()
        for _ in range(n):
            sweep(build, g)
        if (time.perf_counter_ns() - t0) * 1e-9 >= min_batch_s or n >= 1 << 20:
            break
        n *= 2
    per = []
    for _ in range(batches):
        t0 = time.perf_counter_ns()
        for _ in range(n):
            sweep(build, g)
        per.append((time.perf_counter_ns() - t0) / (n * POSITIONS))
    return statistics.median(per), n


def points(build, g):
    """Every position's named points of one cold sweep, [[x, y], ...] per name; None where
    pylinkage assembled nothing (its NaN, which JSON cannot carry)."""
    _, idx = build(g)
    traj = sweep(build, g)

    def point(k, i):
        x, y = float(traj[k, i, 0]), float(traj[k, i, 1])
        return [x, y] if math.isfinite(x) and math.isfinite(y) else None

    return {name: [point(k, i) for k in range(POSITIONS)] for name, i in idx.items()}


def main(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--quick", action="store_true", help="fewer, shorter batches (a smoke run)")
    p.add_argument("--geometry", help="the problems' numbers as JSON (default: the templates')")
    a = p.parse_args(argv)
    try:
        import pylinkage
        from pylinkage._numba_compat import HAS_NUMBA
    except ImportError as e:
        print(f"pylinkage not found: {e}", file=sys.stderr)
        return 3
    geometry = json.loads(a.geometry) if a.geometry else DEFAULT_GEOMETRY
    batches, min_batch = (3, 0.02) if a.quick else (7, 0.2)
    problems = []
    for name, build in (("four-bar", fourbar), ("shaper", shaper)):
        g = geometry[name.replace("-", "")]
        ns, sweeps = time_cold(build, g, batches, min_batch)
        problems.append(
            {
                "problem": name,
                "positions": POSITIONS,
                "sweeps_per_batch": sweeps,
                "batches": batches,
                "ns_per_position": ns,
                "points": points(build, g),
            }
        )
    numba = None
    if HAS_NUMBA:
        import numba as nb

        numba = nb.__version__
    out = {
        "peer": "pylinkage",
        "version": getattr(pylinkage, "__version__", "unknown"),
        "numba": numba,
        "python": sys.version.split()[0],
        "problems": problems,
    }
    json.dump(out, sys.stdout)
    print()
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
