"""cuesight against pooltool's ball-ball resolvers, on the same collisions.

    pip install ./python pooltool-billiards
    python python/examples/pooltool_compare.py

pooltool (https://github.com/ekiefl/pooltool) is optional and not installed by CI.
Both see the same scene: a cue ball at the origin, the object ball at rest 2R along
+x (cuesight's collision frame: x along the line of centres, z up), the cue ball at
speed U and cut angle φ with spin ω (rad/s; right english is ω_z > 0, counter-clockwise from above), the same ball mass and radius, e* 0.95,
and the same speed-dependent ball-ball friction μ(v) = a + b·exp(−c·v) (Alciatore's
TP A.14 fit, pooltool's default; cuesight's mu, mu_b, mu_c). pooltool's Mathavan model
also gives both balls table friction u_s (0.2); cuesight's μ_s (the object ball's table
friction) is set to the same. The printed angles: the object ball's throw from the line
of centres and the cue ball's direction after the impact, degrees counter-clockwise.

Where they differ: cuesight's `kim-grip` and `exact` evaluate μ(v) at the slip speed
as it falls during the impact (μ rises as the slip slows; docs/physics.md §8), while
pooltool's resolvers, like cuesight's `kim` and TP A.24, take μ at the initial slip; and
`kim-grip`/`exact` let the contact grip once the slip vanishes.
"""

from __future__ import annotations

import math
import sys

import numpy as np

import cuesight

try:
    from pooltool.objects.ball.datatypes import Ball
    from pooltool.physics.resolve.ball_ball.friction import AlciatoreBallBallFriction
    from pooltool.physics.resolve.ball_ball.frictional_inelastic import FrictionalInelastic
    from pooltool.physics.resolve.ball_ball.frictional_mathavan import FrictionalMathavan
except ImportError:
    sys.exit("this example needs pooltool: pip install pooltool-billiards")

FRICTION = AlciatoreBallBallFriction()
MASS, RADIUS, RESTITUTION, TABLE_FRICTION = 0.170097, 0.028575, 0.95, 0.2
CONTACT = dict(mu=FRICTION.a, mu_b=FRICTION.b, mu_c=FRICTION.c, restitution=RESTITUTION,
               mu_s=TABLE_FRICTION, radius=RADIUS, mass=MASS)


def pooltool_collide(model, speed: float, cut_deg: float, spin) -> tuple:
    """Object ball throw and cue-ball direction (degrees) from a pooltool resolver."""
    params = dict(m=MASS, R=RADIUS, e_b=RESTITUTION, u_s=TABLE_FRICTION)
    cue = Ball.create("cue", xy=(0.0, 0.0), **params)
    obj = Ball.create("1", xy=(2 * RADIUS, 0.0), **params)
    phi = math.radians(cut_deg)
    cue.state.rvw[1] = [speed * math.cos(phi), speed * math.sin(phi), 0.0]
    cue.state.rvw[2] = list(spin)
    cue.state.s = 2  # sliding
    cue_after, obj_after = model.resolve(cue, obj, inplace=False)
    v_obj, v_cue = obj_after.state.rvw[1], cue_after.state.rvw[1]
    return (math.degrees(math.atan2(v_obj[1], v_obj[0])),
            math.degrees(math.atan2(v_cue[1], v_cue[0])))


def main() -> None:
    speed = 2.0
    models = {"mathavan": FrictionalMathavan(friction=FRICTION),
              "inelastic": FrictionalInelastic(friction=FRICTION)}
    spins = {"stun": (0.0, 0.0, 0.0), "roll": None, "draw": (0.0, -60.0, 0.0),
             "right": (0.0, 0.0, 40.0), "left": (0.0, 0.0, -40.0)}
    header = (f"{'cut':>5} {'spin':>6} | {'throw: kim':>10} {'kim-grip':>8} {'exact':>7} "
              f"{'mathavan':>9} {'inelastic':>9} | {'cue dir: exact':>14} "
              f"{'mathavan':>9} {'inelastic':>9}")
    print(f"U = {speed} m/s; mu(v) = {FRICTION.a} + {FRICTION.b} exp(-{FRICTION.c} v); "
          f"angles in degrees")
    print(header)
    print("-" * len(header))
    for cut in (0.0, 15.0, 30.0, 45.0, 60.0):
        for name, spin in spins.items():
            kwargs = dict(roll=True) if spin is None else dict(spin=spin)
            kim = cuesight.collide(speed, cut, **kwargs, model="kim", **CONTACT)
            grip = cuesight.collide(speed, cut, **kwargs, **CONTACT)
            exact = cuesight.collide(speed, cut, **kwargs, model="exact", **CONTACT)
            w = exact.input.spin
            ours_cue = math.degrees(math.atan2(exact.cue.v[1], exact.cue.v[0]))
            theirs = {k: pooltool_collide(m, speed, cut, w) for k, m in models.items()}
            print(f"{cut:5.0f} {name:>6} | {kim.throw_deg:10.3f} {grip.throw_deg:8.3f} "
                  f"{exact.throw_deg:7.3f} "
                  f"{theirs['mathavan'][0]:9.3f} {theirs['inelastic'][0]:9.3f} | "
                  f"{ours_cue:14.3f} {theirs['mathavan'][1]:9.3f} "
                  f"{theirs['inelastic'][1]:9.3f}")
    # The batch form over the same grid, for scale.
    cuts = np.repeat(np.linspace(0.0, 60.0, 61), 3)
    many = cuesight.collide_many(speed, cuts, np.tile([[0, 0, 0], [0, 40, 0], [0, 0, 40]],
                                                      (61, 1)), **CONTACT)
    print(f"\ncollide_many: {len(many)} scenes, throw from {many.throw_deg.min():.3f} "
          f"to {many.throw_deg.max():.3f} deg")


if __name__ == "__main__":
    main()
