"""Why do two runs whose event sequences agree end far apart? Look at a few shots closely.

    python diagnose.py SHOTS.json OURS.json [--ball-ball default|frictionless] [--e-b E] SHOT...

For each shot, pooltool is run again (the mode and e_b as in pooltool_side.py) and:

* every ball-ball contact is listed with the state pooltool had just before it: the
  approach speed along the line of centres `v_n`, the relative speed `|v_rel|`, the cut
  `sin = |v_t| / |v_rel|` (1 = grazing), each ball's speed and its gap to the nearest
  rail (m, centre to rail line minus R), and the difference of our event time from
  pooltool's (`Δt`, matched by position in the ball/cushion/pocket sequence);
* the shot is run again in pooltool with inputs perturbed at the level of our f32 input
  (the shot's numbers rounded to f32; the cue ball's direction turned by ±1e-7 and
  ±1e-6 rad; its speed scaled by 1 ± 1e-7), and the largest final distance from the
  unperturbed pooltool run is reported in R, with whether the event sequence changed and
  where the event times part (compare.py's `parting`). A shot whose
  finals move by about R under these perturbations is chaotic at that level, so a
  difference of that size from ours says nothing about either simulator's physics.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import struct
import sys
from pathlib import Path

HOME = Path(__file__).resolve().parents[2] / "target" / "pooltool" / "home"
os.environ["HOME"] = str(HOME)  # before pooltool is imported; see pooltool_side.py
HOME.mkdir(parents=True, exist_ok=True)

import numpy as np  # noqa: E402
import pooltool as pt  # noqa: E402

from compare import collisions, final_distance, parting, sequence  # noqa: E402
from pooltool_side import KINDS, build, han_engine, result  # noqa: E402
from shots import TABLES  # noqa: E402


def f32(x: float) -> float:
    return struct.unpack("f", struct.pack("f", x))[0]


def perturbed(shot: dict) -> dict:
    """The shot's variants at the level of an f32 input."""
    vx, vy = shot["velocity"]
    out = {"f32 inputs": dict(shot, balls=[[f32(x), f32(y)] for x, y in shot["balls"]],
                              velocity=[f32(vx), f32(vy)], spin=[f32(w) for w in shot["spin"]])}
    for turn in (1e-7, -1e-7, 1e-6, -1e-6):
        c, s = math.cos(turn), math.sin(turn)
        out[f"turn {turn:+g} rad"] = dict(shot, velocity=[c * vx - s * vy, s * vx + c * vy])
    for scale in (1 + 1e-7, 1 - 1e-7):
        out[f"speed x {scale:.7f}"] = dict(shot, velocity=[scale * vx, scale * vy])
    return out


def run(shot: dict, engine, e_b: float) -> tuple[dict, pt.System]:
    system = build(shot, e_b)
    pt.simulate(system, engine=engine, inplace=True, max_events=20000)
    return result(shot, system, 0.0), system


def rail_gap(shot: dict, X: float, Y: float) -> float:
    """Gap (m) from a ball at pooltool (X, Y) to the nearest rail line, centre minus R."""
    t = TABLES[shot["table"]]
    x, y = Y, t["width"] - X
    return min(x, t["length"] - x, y, t["width"] - y) - t["R"]


def contacts(shot: dict, system: pt.System, ours: dict, theirs: dict) -> None:
    ours_ev, theirs_ev = collisions(ours), collisions(theirs)
    k = -1
    print("| # | time (s) | Δt ours (s) | balls | v_n (m/s) | abs v_rel (m/s) | sin cut "
          "| speeds (m/s) | rail gaps (m) |")
    print("|---|---|---|---|---|---|---|---|---|")
    for e in system.events:
        kind = KINDS.get(e.event_type)
        if kind in (None, "rest"):
            continue
        k += 1
        if kind != "ball":
            continue
        b1, b2 = (a.initial for a in e.agents)
        r1, v1 = b1.state.rvw[0], b1.state.rvw[1]
        r2, v2 = b2.state.rvw[0], b2.state.rvw[1]
        n = (r2 - r1) / np.linalg.norm(r2 - r1)
        v = v1 - v2
        vn = float(np.dot(v, n))
        vt = float(np.linalg.norm(v - vn * n))
        rel = float(np.linalg.norm(v))
        dt = (ours_ev[k]["time"] - theirs_ev[k]["time"]) if k < min(len(ours_ev),
                                                                   len(theirs_ev)) else math.nan
        print(f"| {k} | {e.time:.4f} | {dt:+.1e} | {b1.id}-{b2.id} | {vn:.3f} | {rel:.3f} "
              f"| {vt / rel if rel else math.nan:.3f} "
              f"| {np.linalg.norm(v1):.3f}, {np.linalg.norm(v2):.3f} "
              f"| {rail_gap(shot, *r1[:2]):.4f}, {rail_gap(shot, *r2[:2]):.4f} |")


def main() -> None:
    parser = argparse.ArgumentParser(usage=__doc__)
    parser.add_argument("shots")
    parser.add_argument("ours")
    parser.add_argument("index", nargs="+", type=int)
    parser.add_argument("--ball-ball", choices=("default", "frictionless"), default="default")
    parser.add_argument("--e-b", type=float, default=None)
    args = parser.parse_args()
    e_b = args.e_b if args.e_b is not None else (1.0 if args.ball_ball == "frictionless"
                                                  else 0.95)
    shots, ours = (json.load(open(p)) for p in (args.shots, args.ours))
    engine = han_engine(args.ball_ball)
    print(f"# pooltool {args.ball_ball}, e_b {e_b}\n")
    for i in args.index:
        shot = shots[i]
        theirs, system = run(shot, engine, e_b)
        d, ball = final_distance(shot, ours[i], theirs)
        same = sequence(ours[i]) == sequence(theirs)
        print(f"## shot {i} ({shot['table']}, {len(shot['balls'])} balls): sequences "
              f"{'agree' if same else 'differ'}, finals {d:.2f} R apart (ball {ball})\n")
        contacts(shot, system, ours[i], theirs)
        print(f"\nOurs against pooltool: times part at {parting(ours[i], theirs)}.\n")
        print("| pooltool, perturbed | sequence | max final distance from pooltool (R), ball "
              "| from ours (R) | times part from pooltool's |")
        print("|---|---|---|---|---|")
        for name, variant in perturbed(shot).items():
            other, _ = run(variant, engine, e_b)
            dp, bp = final_distance(shot, theirs, other)
            do, _ = final_distance(shot, ours[i], other)
            print(f"| {name} | {'same' if sequence(other) == sequence(theirs) else 'differs'} "
                  f"| {dp:.2f}, ball {bp} | {do:.2f} "
                  f"| {parting(other, theirs) if sequence(other) == sequence(theirs) else '-'} |")
        print()


if __name__ == "__main__":
    sys.exit(main())
