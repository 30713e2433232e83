#!/usr/bin/env python3
"""Shaper positions: SolveSpace's solver (PyPI `slvs`) against mechdraw's linkage solver.

Usage: benches/slvs_compare.sh (creates target/slvs-venv with `slvs`, builds the Rust
timing example in release mode, runs this script).

Both solve the shaper of templates/shaper.toml (design.md §3) at 360 crank positions per
turn, each position starting from the previous answer:

- slvs: the crank pin A is given by the driver (A = O1 + 125·(cos φ1, sin φ1)); B and E are
  unknowns with |O3B| = 600, A on the line O3B, |BE| = 150, E on the ram's line y = 600.
  As the issue notes, slvs's PT_ON_LINE constraint breaks re-solving from a previous
  answer, so "A on O3B" and "E on the ram's line" are point-to-line distances of 0.
  The sketch is rebuilt for every position (the Python API keeps one global sketch)
  with the previous answer as the start; the time per position is reported both for the
  whole rebuild + solve and for the solve_sketch call alone.
- mechdraw: one time step of the general solver (positions by Newton–Raphson from the
  extrapolated previous step, then velocities and accelerations), from
  examples/linkage_shaper_timing.rs.

Residual: the largest |constraint equation| at the answer divided by the mechanism's
length scale (the same scale mechdraw uses for its relative residual).
"""
import json
import math
import subprocess
import sys
import time

import slvs

O1 = (0.0, 300.0)
O3 = (0.0, 0.0)
R, L, LBE, Y = 125.0, 600.0, 150.0, 600.0
STEPS = 360


def start_guess():
    a = (R, 300.0)
    th = math.atan2(a[1], a[0])
    b = (L * math.cos(th), L * math.sin(th))
    dy = Y - b[1]
    e = (b[0] + math.sqrt(LBE * LBE - dy * dy), Y)
    return b, e


def solve_position(phi, b, e):
    """Rebuilds the sketch with B, E at the previous answer and solves; returns (B, E, ok, solve_s)."""
    slvs.clear_sketch()
    g1, g2 = 1, 2
    wp = slvs.add_base_2d(g1)
    a = (O1[0] + R * math.cos(phi), O1[1] + R * math.sin(phi))
    o3 = slvs.add_point_2d(g1, O3[0], O3[1], wp)
    pa = slvs.add_point_2d(g1, a[0], a[1], wp)
    g_a = slvs.add_point_2d(g1, -150.0, Y, wp)
    g_b = slvs.add_point_2d(g1, 450.0, Y, wp)
    guide = slvs.add_line_2d(g1, g_a, g_b, wp)
    pb = slvs.add_point_2d(g2, b[0], b[1], wp)
    pe = slvs.add_point_2d(g2, e[0], e[1], wp)
    rocker = slvs.add_line_2d(g2, o3, pb, wp)
    slvs.distance(g2, o3, pb, L, wp)
    slvs.distance(g2, pa, rocker, 0.0, wp)  # A on the rocker line (point-line distance 0)
    slvs.distance(g2, pb, pe, LBE, wp)
    slvs.distance(g2, pe, guide, 0.0, wp)  # E on the ram's line
    t0 = time.perf_counter()
    res = slvs.solve_sketch(g2, False)
    solve_s = time.perf_counter() - t0
    bx, by = slvs.get_param_value(pb["param"][0]), slvs.get_param_value(pb["param"][1])
    ex, ey = slvs.get_param_value(pe["param"][0]), slvs.get_param_value(pe["param"][1])
    return (bx, by), (ex, ey), res["result"] == 0, solve_s, a


def residual(a, b, e, scale):
    nb = math.hypot(b[0], b[1])
    eqs = [
        nb - L,
        (b[0] * a[1] - b[1] * a[0]) / nb,  # distance of A from the line O3B
        math.hypot(e[0] - b[0], e[1] - b[1]) - LBE,
        e[1] - Y,
    ]
    return max(abs(v) for v in eqs) / scale


def main():
    ours = json.loads(sys.argv[1]) if len(sys.argv) > 1 else None
    scale = ours["length_scale"] if ours else 1000.0
    turns = 5
    b, e = start_guess()
    worst = 0.0
    failures = 0
    solve_total = 0.0
    t_start = time.perf_counter()
    cpu_start = time.process_time()
    n = 0
    for turn in range(turns):
        for k in range(STEPS):
            phi = 2.0 * math.pi * (k + 1) / STEPS
            b, e, ok, solve_s, a = solve_position(phi, b, e)
            # A failed solve, or a jump to the other assembly mode (E left of B), counts.
            failures += 0 if ok and e[0] > b[0] else 1
            solve_total += solve_s
            worst = max(worst, residual(a, b, e, scale))
            n += 1
    total = time.perf_counter() - t_start
    cpu_total = time.process_time() - cpu_start
    rows = [
        ("slvs (rebuild + solve_sketch)", total / n * 1e6, cpu_total / n * 1e6, worst, "positions"),
        ("slvs (solve_sketch only)", solve_total / n * 1e6, None, worst, "positions"),
    ]
    if ours:
        cpu = ours.get("cpu_ns_per_step")
        rows.append(
            (
                "mechdraw linkage solver",
                ours["ns_per_step"] / 1000.0,
                cpu / 1000.0 if cpu is not None else None,
                ours["max_residual"],
                "positions + velocities + accelerations",
            )
        )
    print(f"shaper, {n} positions per solver ({turns} turns of {STEPS}), slvs failures: {failures}")
    print()
    print("| solver | µs per position (wall) | µs per position (CPU) | max relative residual | what one step solves |")
    print("|---|---:|---:|---:|---|")
    for name, us, cpu, res, what in rows:
        cpu_s = f"{cpu:.2f}" if cpu is not None else "–"
        print(f"| {name} | {us:.2f} | {cpu_s} | {res:.1e} | {what} |")
    if ours:
        print()
        print(
            f"wall-clock speed-up against slvs's solve_sketch alone: {rows[1][1] / rows[2][1]:.1f}×; "
            f"against rebuild + solve: {rows[0][1] / rows[2][1]:.1f}×"
        )
        if rows[0][2] is not None and rows[2][2] is not None:
            print(f"CPU-time speed-up against rebuild + solve: {rows[0][2] / rows[2][2]:.1f}×")


if __name__ == "__main__":
    main()
