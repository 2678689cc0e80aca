"""Seeded shots with cushions for the pooltool comparison, in cuesight's format.

    python shots.py OUT.json [--seed 17]

Each shot: {"table": "pool" | "carom", "balls": [[x, y], ...] (ball 0 is the cue ball),
"velocity": [vx, vy], "spin": [wx, wy, wz]}, in cuesight's table frame: origin at a
corner of the playing surface, x along the length, y along the width, z up, metres,
m/s, rad/s (follow on a ball moving along +x is wy > 0).

The set: 100 carom shots (3 balls), 100 pool shots (2-6 balls) and 40 9-ball-break-like
racks on pool. Everything random comes from one `random.Random(seed)`, rack jitter
included, so the file is the same on every run.
"""

from __future__ import annotations

import json
import math
import random
import sys

# Playing surface (length along x, width along y), ball radius, pocket mouths (m).
TABLES = {
    "pool": dict(length=2.54, width=1.27, R=0.028575, corner_mouth=0.116, side_mouth=0.13),
    "carom": dict(length=2.84, width=1.42, R=0.03075, corner_mouth=0.0, side_mouth=0.0),
}

RACK_GAP = 4e-4     # between neighbouring rack balls before the jitter (m)
RACK_JITTER = 1e-4  # each rack ball moves up to this far (m), so the rack never overlaps


def free_spot(rng: random.Random, t: dict, balls: list) -> list:
    """A spot on the cloth clear of the other balls and of the pocket mouths."""
    L, W, R = t["length"], t["width"], t["R"]
    while True:
        x = rng.uniform(R + 0.02, L - R - 0.02)
        y = rng.uniform(R + 0.02, W - R - 0.02)
        if t["corner_mouth"] > 0:
            # Away from the corner mouths and the side mouths.
            if min(x, L - x) + min(y, W - y) < 0.2:
                continue
            if abs(x - L / 2) < 0.1 and min(y, W - y) < 0.08:
                continue
        if all(math.dist((x, y), b) > 2 * R + 0.005 for b in balls):
            return [x, y]


def cue_motion(rng: random.Random, R: float, speed: float, direction: float,
               tip: tuple[float, float]) -> tuple[list, list]:
    """Velocity and spin after a centred-mass cue strike at tip offset (side, height)·R:
    the spin is r x J / I, so |w| = (5/2) offset v / R; height > 0 is follow, side > 0
    right english (w_z > 0)."""
    ux, uy = math.cos(direction), math.sin(direction)
    side, height = tip
    k = 2.5 * speed / R
    # Follow: w along z x u = (-uy, ux, 0), as for rolling (w = z x v / R).
    spin = [-uy * k * height, ux * k * height, k * side]
    return [speed * ux, speed * uy], spin


def random_tip(rng: random.Random, limit: float = 0.5) -> tuple[float, float]:
    while True:
        a, b = rng.uniform(-limit, limit), rng.uniform(-limit, limit)
        if a * a + b * b <= limit * limit:
            return a, b


def aimed_direction(rng: random.Random, cue: list, target: list, R: float) -> float:
    """Towards `target` with a lateral offset of up to 1.6 R (full ball to thin cut)."""
    dx, dy = target[0] - cue[0], target[1] - cue[1]
    d = math.hypot(dx, dy)
    offset = rng.uniform(-1.6 * R, 1.6 * R)
    return math.atan2(dy, dx) + math.asin(max(-1.0, min(1.0, offset / d)))


def open_shot(rng: random.Random, table: str, n_balls: int, speeds: tuple) -> dict:
    t = TABLES[table]
    balls: list = []
    for _ in range(n_balls):
        balls.append(free_spot(rng, t, balls))
    if rng.random() < 0.6:
        direction = aimed_direction(rng, balls[0], balls[rng.randrange(1, n_balls)], t["R"])
    else:
        direction = rng.uniform(-math.pi, math.pi)
    velocity, spin = cue_motion(rng, t["R"], rng.uniform(*speeds), direction, random_tip(rng))
    return dict(table=table, balls=balls, velocity=velocity, spin=spin)


def break_shot(rng: random.Random) -> dict:
    """A 9-ball diamond (rows 1-2-3-2-1) with its apex on the foot spot, the cue ball
    behind the head string, hit hard at the apex ball."""
    t = TABLES["pool"]
    L, W, R = t["length"], t["width"], t["R"]
    d = 2 * R + RACK_GAP
    rack = []
    for row, count in enumerate((1, 2, 3, 2, 1)):
        for j in range(count):
            x = 0.75 * L + row * d * math.sqrt(3) / 2
            y = W / 2 + (j - (count - 1) / 2) * d
            r, a = RACK_JITTER * math.sqrt(rng.random()), rng.uniform(0, 2 * math.pi)
            rack.append([x + r * math.cos(a), y + r * math.sin(a)])
    cue = [rng.uniform(0.45, 0.25 * L), rng.uniform(0.2, W - 0.2)]
    apex = rack[0]
    offset = rng.uniform(-0.3 * R, 0.3 * R)
    direction = math.atan2(apex[1] - cue[1], apex[0] - cue[0]) + offset / math.dist(cue, apex)
    tip = (rng.uniform(-0.1, 0.1), rng.uniform(-0.3, 0.1))
    velocity, spin = cue_motion(rng, R, rng.uniform(6.0, 9.0), direction, tip)
    return dict(table="pool", balls=[cue] + rack, velocity=velocity, spin=spin)


def make_shots(seed: int) -> list:
    rng = random.Random(seed)
    shots = [open_shot(rng, "carom", 3, (1.0, 5.0)) for _ in range(100)]
    shots += [open_shot(rng, "pool", rng.randint(2, 6), (0.5, 4.0)) for _ in range(100)]
    shots += [break_shot(rng) for _ in range(40)]
    return shots


def main() -> None:
    args = sys.argv[1:]
    seed = 17
    if "--seed" in args:
        i = args.index("--seed")
        seed = int(args[i + 1])
        del args[i:i + 2]
    if len(args) != 1:
        sys.exit(__doc__)
    shots = make_shots(seed)
    with open(args[0], "w") as f:
        json.dump(shots, f, indent=1)
    print(f"{len(shots)} shots (seed {seed}) -> {args[0]}", file=sys.stderr)


if __name__ == "__main__":
    main()
