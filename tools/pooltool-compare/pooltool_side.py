"""Run shots.json through pooltool 0.6 with Han 2005 cushions; write cuesight's result format.

    python pooltool_side.py SHOTS.json OUT.json [--ball-ball default|frictionless] [--e-b E]

--ball-ball default (the default): pooltool 0.6's own ball-ball model, frictional_inelastic
with Alciatore's friction, e_b 0.95. --ball-ball frictionless: the same FrictionalInelastic
resolver with AlciatoreBallBallFriction(a=0, b=0), so u_b = 0: a purely normal impulse
with Newton restitution e_b and both spins unchanged; e_b is 1 by default in this mode,
as in cuesight's `ideal` model (see README.md, "The two modes"). --e-b sets every ball's
e_b in either mode.

OUT.json: one result per shot, in order: {"final": [[x, y] | null (pocketed), ...],
"events": [{"time", "kind": "ball"|"cushion"|"pocket"|"rest", "balls": [i] | [i, j]}],
"error": null | str, "seconds": wall time of pooltool's `simulate` call,
"pooltool_events": every event pooltool stepped through, transitions included}.
A summary of the timing goes to OUT-timing.json and stderr.

Frames: pooltool puts a table's width along x and its length along y. A shot is carried
into pooltool by the +90 degree turn about z (a proper rotation, so spin keeps its sense)
and back by its inverse:
    pooltool (X, Y) = (W - y, x),   vectors (vX, vY, vZ) = (-vy, vx, vz),
    cuesight (x, y) = (Y, W - X).
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import sys
import time
from pathlib import Path


def arguments() -> argparse.Namespace:
    parser = argparse.ArgumentParser(usage=__doc__)
    parser.add_argument("shots")
    parser.add_argument("out")
    parser.add_argument("--ball-ball", choices=("default", "frictionless"), default="default")
    parser.add_argument("--e-b", type=float, default=None,
                        help="every ball's e_b (default 0.95; 1 with --ball-ball frictionless)")
    args = parser.parse_args()
    if args.e_b is None:
        args.e_b = 1.0 if args.ball_ball == "frictionless" else 0.95
    return args


# pooltool reads (and writes) ~/.config/pooltool at import time, and the default engine
# comes from a resolver.yaml there. Point HOME at a private directory before the import
# so no user configuration is read or changed; the engine below is built explicitly.
# (A script importing this module, diagnose.py, sets HOME itself first.)
if __name__ == "__main__":
    ARGS = arguments()
    OUT_DIR = Path(ARGS.out).resolve().parent
    os.environ["HOME"] = str(OUT_DIR / "home")
    (OUT_DIR / "home").mkdir(parents=True, exist_ok=True)

import attrs  # noqa: E402
import pooltool as pt  # noqa: E402
from pooltool.objects.table.specs import BilliardTableSpecs, PocketTableSpecs  # noqa: E402
from pooltool.physics.engine import PhysicsEngine  # noqa: E402
from pooltool.physics.resolve.ball_ball.frictional_inelastic import (  # noqa: E402
    FrictionalInelastic,
)
from pooltool.physics.resolve.ball_ball.friction import AlciatoreBallBallFriction  # noqa: E402
from pooltool.physics.resolve.ball_cushion.han_2005 import (  # noqa: E402
    Han2005Circular,
    Han2005Linear,
)
from pooltool.physics.resolve.resolver import default_resolver  # noqa: E402

from shots import TABLES  # noqa: E402

# Cloth, cushions and balls as cuesight's tables have them. u_sp_proportionality is
# pooltool's default (10/9 g spin decay for any R); e_b 0.95 is pooltool's default.
COMMON = dict(u_s=0.2, u_r=0.01, u_sp_proportionality=10 * 2 / 5 / 9, e_b=0.95, e_c=0.85, g=9.81)
BALL = {
    "pool": dict(COMMON, m=0.170097, R=TABLES["pool"]["R"], f_c=0.2),      # POOL_GENERIC
    "carom": dict(COMMON, m=0.210, R=TABLES["carom"]["R"], f_c=0.15),      # BILLIARD_GENERIC
}
# Pocket jaws, angles, depths and radii stay pooltool's 7-ft Showood defaults.
SPECS = {
    "pool": PocketTableSpecs(l=TABLES["pool"]["length"], w=TABLES["pool"]["width"],
                             cushion_height=0.036576,
                             corner_pocket_width=TABLES["pool"]["corner_mouth"],
                             side_pocket_width=TABLES["pool"]["side_mouth"]),
    "carom": BilliardTableSpecs(l=TABLES["carom"]["length"], w=TABLES["carom"]["width"],
                                cushion_height=0.037),
}
MAX_EVENTS = 20000  # pooltool's events, transitions included; a 9-ball break takes ~500

KINDS = {
    pt.EventType.BALL_BALL: "ball",
    pt.EventType.BALL_LINEAR_CUSHION: "cushion",
    pt.EventType.BALL_CIRCULAR_CUSHION: "cushion",
    pt.EventType.BALL_POCKET: "pocket",
    # The transitions where a ball stops translating: cuesight's "rest".
    pt.EventType.ROLLING_STATIONARY: "rest",
    pt.EventType.ROLLING_SPINNING: "rest",
}


def han_engine(ball_ball: str = "default") -> PhysicsEngine:
    """pooltool 0.6's default resolver (not the YAML one) with Han 2005 cushions.

    ball_ball "frictionless": FrictionalInelastic with Alciatore's u_b = a + b exp(-c v)
    at a = b = 0. With u_b = 0 its slip branch adds no tangential impulse (and, the slip
    being unchanged, is always kept; the no-slip branch runs only when the contact slip
    is already below 1e-14 m/s, where it changes nothing), so the collision is the
    normal-only v_n' = ((1 -+ e_b) v1n + (1 +- e_b) v2n) / 2, spins untouched, v_z 0.
    pooltool's FrictionlessElastic would do for e_b = 1 but has no e_b; this one keeps
    the default mode's code path (make_kiss, the continually-touching rule) and takes any
    e_b.
    """
    changes = dict(ball_linear_cushion=Han2005Linear(), ball_circular_cushion=Han2005Circular())
    if ball_ball == "frictionless":
        changes["ball_ball"] = FrictionalInelastic(
            friction=AlciatoreBallBallFriction(a=0.0, b=0.0))
    return PhysicsEngine(resolver=attrs.evolve(default_resolver(), **changes))


def build(shot: dict, e_b: float = 0.95) -> pt.System:
    W = TABLES[shot["table"]]["width"]
    table = pt.Table.from_table_specs(SPECS[shot["table"]])
    balls = {}
    for i, (x, y) in enumerate(shot["balls"]):
        balls[str(i)] = pt.Ball.create(str(i), xy=(W - y, x),
                                       **dict(BALL[shot["table"]], e_b=e_b))
    vx, vy = shot["velocity"]
    wx, wy, wz = shot["spin"]
    cue_ball = balls["0"]
    cue_ball.state.rvw[1] = [-vy, vx, 0.0]
    cue_ball.state.rvw[2] = [-wy, wx, wz]
    cue_ball.state.s = pt.constants.sliding
    # The cue stick is never used: the cue ball already moves, so no stick-ball event.
    return pt.System(cue=pt.Cue(cue_ball_id="0"), table=table, balls=balls)


def result(shot: dict, system: pt.System, seconds: float) -> dict:
    W = TABLES[shot["table"]]["width"]
    final = []
    for i in range(len(shot["balls"])):
        state = system.balls[str(i)].state
        X, Y = state.rvw[0][0], state.rvw[0][1]
        final.append(None if state.s == pt.constants.pocketed else [float(Y), float(W - X)])
    events = []
    for e in system.events:
        kind = KINDS.get(e.event_type)
        if kind is None:
            continue
        # Agents: (ball, ball) for ball-ball, else (ball, cushion | pocket) or (ball,).
        balls = e.ids[:2] if kind == "ball" else e.ids[:1]
        events.append(dict(time=float(e.time), kind=kind, balls=[int(b) for b in balls]))
    counted = sum(e.event_type != pt.EventType.NONE for e in system.events)
    return dict(final=final, events=events, error=None, seconds=seconds,
                pooltool_events=counted)


def main() -> None:
    shots = json.loads(Path(ARGS.shots).read_text())
    engine = han_engine(ARGS.ball_ball)
    assert isinstance(engine.resolver.ball_linear_cushion, Han2005Linear)
    assert isinstance(engine.resolver.ball_circular_cushion, Han2005Circular)
    assert isinstance(engine.resolver.ball_ball, FrictionalInelastic)
    friction = engine.resolver.ball_ball.friction
    assert isinstance(friction, AlciatoreBallBallFriction)
    if ARGS.ball_ball == "frictionless":
        assert friction.a == 0.0 and friction.b == 0.0

    # JIT warm-up, not timed: numba compiles each function on its first call, and some
    # only on rarer paths (with a single warm-up shot, two later shots took 0.4-0.5 s
    # instead of 0.02 s). So every shot is simulated once untimed, then again timed.
    t0 = time.perf_counter()
    for shot in shots:
        try:
            pt.simulate(build(shot, ARGS.e_b), engine=engine, inplace=True,
                        max_events=MAX_EVENTS)
        except Exception:  # noqa: BLE001 - recorded in the timed pass
            pass
    warmup = time.perf_counter() - t0

    results = []
    for shot in shots:
        system = build(shot, ARGS.e_b)
        t0 = time.perf_counter()
        try:
            pt.simulate(system, engine=engine, inplace=True, max_events=MAX_EVENTS)
        except Exception as exc:  # noqa: BLE001 - recorded per shot
            results.append(dict(final=None, events=[], error=f"{type(exc).__name__}: {exc}",
                                seconds=time.perf_counter() - t0, pooltool_events=0))
            continue
        results.append(result(shot, system, time.perf_counter() - t0))
        if results[-1]["pooltool_events"] > MAX_EVENTS:
            results[-1]["error"] = f"more than {MAX_EVENTS} pooltool events (stopped)"
    Path(ARGS.out).write_text(json.dumps(results, indent=1))

    ok = [r for r in results if r["error"] is None]
    per_shot = [r["seconds"] for r in ok]
    per_event = [r["seconds"] / r["pooltool_events"] for r in ok if r["pooltool_events"]]
    kept = [r["seconds"] / n for r in ok
            if (n := sum(e["kind"] != "rest" for e in r["events"]))]
    summary = dict(
        pooltool=pt.__version__,
        resolver={k: type(getattr(engine.resolver, k)).__name__
                  for k in ("ball_ball", "ball_linear_cushion", "ball_circular_cushion")},
        ball_ball=ARGS.ball_ball,
        e_b=ARGS.e_b,
        ball_ball_friction=dict(model=type(friction).__name__, a=friction.a, b=friction.b,
                                c=friction.c),
        shots=len(results), errors=len(results) - len(ok), warmup_seconds=warmup,
        total_simulate_seconds=sum(per_shot),
        per_shot_seconds=dict(median=statistics.median(per_shot), mean=statistics.mean(per_shot)),
        per_event_seconds=dict(median=statistics.median(per_event),
                               mean=statistics.mean(per_event),
                               note="over every pooltool event, transitions included"),
        per_collision_event_seconds=dict(median=statistics.median(kept),
                                         mean=statistics.mean(kept),
                                         note="over ball/cushion/pocket events only"),
        events=dict(mean_pooltool=statistics.mean(r["pooltool_events"] for r in ok),
                    mean_collisions=statistics.mean(
                        sum(e["kind"] != "rest" for e in r["events"]) for r in ok)),
    )
    timing = Path(ARGS.out).with_name(Path(ARGS.out).stem + "-timing.json")
    timing.write_text(json.dumps(summary, indent=1))
    print(json.dumps(summary, indent=1), file=sys.stderr)


if __name__ == "__main__":
    main()
