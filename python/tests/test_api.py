"""The Python API itself: ``collide_many`` rows against ``collide`` (whose numbers
test_cli_identity.py holds to the CLI), broadcasting, errors, defaults, stubs."""

from __future__ import annotations

import ast
import inspect
from pathlib import Path
from typing import Any, Dict

import numpy as np
import pytest

import cuesight
from cuesight import _cuesight

from conftest import assert_same, bits


def row_dict(many: cuesight.Collisions, j: int) -> Dict[str, Any]:
    """Row ``j`` with the keys of ``Collision.to_dict`` that a batch has."""
    return {
        "regime": cuesight.REGIMES[many.regime[j]],
        "cue": {"v": many.cue_v[j].tolist(), "w": many.cue_w[j].tolist()},
        "object": {"v": many.object_v[j].tolist(), "w": many.object_w[j].tolist()},
        "throw_deg": float(many.throw_deg[j]),
        "cue_deflection_deg": float(many.cue_deflection_deg[j]),
        "separation_deg": float(many.separation_deg[j]),
        "impulses": {
            "normal": float(many.impulse_normal[j]),
            "friction": many.impulse_friction[j].tolist(),
            "table_friction": float(many.table_friction[j]),
        },
    }


def single_dict(c: cuesight.Collision) -> Dict[str, Any]:
    d = c.to_dict()
    keys = ("regime", "cue", "object", "throw_deg", "cue_deflection_deg", "separation_deg",
            "impulses")
    return {k: d[k] for k in keys}


@pytest.mark.parametrize("model", cuesight.MODELS)
def test_batch_rows_equal_single_calls(model):
    rng = np.random.default_rng(7)
    n = 150
    speed = rng.uniform(0.05, 10.0, n)
    cut = rng.uniform(-89.0, 89.0, n)
    spin = rng.uniform(-500.0, 500.0, (n, 3))
    mu = rng.uniform(0.0, 0.4, n)
    mu_b = rng.uniform(0.0, 0.3, n)
    mu_c = rng.uniform(0.0, 3.0, n)
    mu_s = rng.uniform(0.0, 1.0, n)
    many = cuesight.collide_many(speed, cut, spin, mu=mu, mu_b=mu_b, mu_c=mu_c, mu_s=mu_s,
                                 model=model, errors="nan")
    assert len(many) == n
    assert many.throw_deg.dtype == np.float32 and many.cue_v.shape == (n, 3)
    # kim and kim-grip refuse scenes outside their validity domains (kim where the contact
    # grips, kim-grip above mu * mu_s 0.08, ...); the other models answer every row.
    assert many.valid.all() or model in ("kim", "kim-grip")
    assert many.valid.any()
    for j in range(n):
        args = (float(speed[j]), float(cut[j]), tuple(spin[j]))
        kwargs = dict(mu=float(mu[j]), mu_b=float(mu_b[j]), mu_c=float(mu_c[j]),
                      mu_s=float(mu_s[j]), model=model)
        if not many.valid[j]:
            # The single call refuses the same row, with the validity message.
            with pytest.raises(ValueError, match=" is valid only where "):
                cuesight.collide(*args, **kwargs)
            continue
        one = cuesight.collide(*args, **kwargs)
        assert_same(row_dict(many, j), single_dict(one), f"{model} row {j}")
        assert_same(many.spin[j].tolist(), list(one.input.spin))
        if model == "auto":
            assert cuesight.MODELS[many.model_used[j]] == one.model_used
            assert bits(float(many.error_estimate[j])) == bits(one.error_estimate)
        else:
            assert many.model_used is None and one.model_used is None


def test_roll_and_tip_per_row():
    speed = np.array([1.0, 2.0, 3.0])
    roll = np.array([True, False, True])
    many = cuesight.collide_many(speed, 25.0, roll=roll)
    for j in range(3):
        one = cuesight.collide(float(speed[j]), 25.0, roll=bool(roll[j]))
        assert_same(row_dict(many, j), single_dict(one))
    tips = np.array([[0.1, 0.2], [-0.3, 0.0], [0.0, -0.4]])
    many = cuesight.collide_many(speed, -15.0, tip=tips)
    for j in range(3):
        one = cuesight.collide(float(speed[j]), -15.0, tip=tuple(tips[j]))
        assert_same(row_dict(many, j), single_dict(one))
        assert_same(many.spin[j].tolist(), list(one.input.spin))


def test_scalars_broadcast_like_arrays():
    n = 5
    speed = np.linspace(0.5, 4.0, n)
    as_scalars = cuesight.collide_many(speed, 30.0, (0.0, 40.0, 0.0), mu=0.06)
    as_arrays = cuesight.collide_many(speed, np.full(n, 30.0), np.tile([0.0, 40.0, 0.0], (n, 1)),
                                      mu=np.full(n, 0.06))
    as_length_one = cuesight.collide_many(speed, [30.0], [[0.0, 40.0, 0.0]], mu=[0.06])
    for other in (as_arrays, as_length_one):
        for j in range(n):
            assert_same(row_dict(other, j), row_dict(as_scalars, j))
    single = cuesight.collide_many(2.0, 30.0)
    assert len(single) == 1
    assert_same(row_dict(single, 0), single_dict(cuesight.collide(2.0, 30.0)))
    empty = cuesight.collide_many(np.zeros(0), 30.0)
    assert len(empty) == 0 and empty.cue_v.shape == (0, 3)


def test_float64_inputs_round_to_f32_as_collide_does():
    x = 2.0000001192092896  # not an f32: rounds to 2.0000002 (nearest)
    many = cuesight.collide_many([x], [30.1])
    one = cuesight.collide(x, 30.1)
    assert_same(row_dict(many, 0), single_dict(one))
    assert one.input.speed == float(np.float32(x)) != x


@pytest.mark.parametrize(
    "kwargs, message, single",
    [
        (dict(speed=[1.0, 2.0], cut_deg=[1.0, 2.0, 3.0]),
         "arrays of different lengths: speed 2, cut_deg 3", False),
        (dict(speed=[[1.0]], cut_deg=0.0), "speed must be a number or a 1-D array", False),
        (dict(speed=1.0, cut_deg=0.0, spin=[1.0, 2.0]), "spin must have shape (3,) or (n, 3)",
         False),
        (dict(speed=1.0, cut_deg=0.0, tip=[[1.0, 2.0, 3.0]]), "tip must have shape (2,) or (n, 2)",
         False),
        (dict(speed=1.0, cut_deg=0.0, errors="ignore"), "errors must be 'raise' or 'nan'", False),
        (dict(speed=1.0, cut_deg=0.0, spin=[0.0, 1.0, 0.0], roll=True),
         "spin and roll=True are exclusive", True),
        (dict(speed=1.0, cut_deg=0.0, tip=[0.0, 0.1], roll=True),
         "tip is exclusive with spin and roll=True", True),
    ],
)
def test_usage_errors(kwargs, message, single):
    with pytest.raises(ValueError) as raised:
        cuesight.collide_many(**kwargs)
    prefix = "scene 0: " if single else ""
    assert str(raised.value).startswith(prefix + message), raised.value
    if single:
        with pytest.raises(ValueError) as raised_single:
            cuesight.collide(**kwargs)
        assert str(raised_single.value).startswith(message), raised_single.value
    with pytest.raises(ValueError, match="spin needs 3 numbers, got 2"):
        cuesight.collide(1.0, 0.0, spin=(1.0, 2.0))


def test_errors_nan_marks_the_refused_scenes_only():
    mu = np.array([0.05, -0.1, 0.2, 2.0])
    with pytest.raises(ValueError, match=r"^scene 1: mu = -0.1 is outside \[0, 1\]$"):
        cuesight.collide_many(2.0, 30.0, mu=mu)
    many = cuesight.collide_many(2.0, 30.0, mu=mu, model="auto", errors="nan")
    assert many.valid.tolist() == [True, False, True, False]
    assert many.regime[1] == many.regime[3] == -1
    assert many.model_used[1] == -1 and np.isnan(many.error_estimate[1])
    assert np.isnan(many.cue_v[1]).all() and np.isnan(many.throw_deg[3])
    assert many.regime_names()[1] == "invalid"
    for j in (0, 2):
        one = cuesight.collide(2.0, 30.0, mu=float(mu[j]), model="auto")
        assert_same(row_dict(many, j), single_dict(one))
        assert many.regime_names()[j] == one.regime


def test_defaults_are_what_none_gives():
    d = cuesight.DEFAULTS
    assert d["model"] == "kim-grip"
    assert [bits(d[k]) for k in ("mu", "restitution", "mu_s", "radius", "mass", "tolerance")] == [
        bits(v) for v in (0.05, 0.95, 0.3, 0.028575, 0.17, 1e-3)
    ]
    implicit = cuesight.collide(2.0, 30.0, (0.0, 40.0, 0.0))
    explicit = cuesight.collide(2.0, 30.0, (0.0, 40.0, 0.0),
                                **{k: d[k] for k in ("mu", "mu_b", "mu_c", "restitution", "mu_s",
                                                     "radius", "mass")}, model=d["model"])
    assert implicit == explicit
    assert implicit.input.mu == d["mu"] and implicit.model == "kim-grip"
    auto = cuesight.collide(2.0, 30.0, model="auto")
    assert auto.tolerance == d["tolerance"]


def test_collision_round_trips_through_its_dict():
    c = cuesight.collide(2.0, 30.0, tip=(0.1, 0.3), model="auto", tolerance=0.01)
    assert cuesight.Collision.from_dict(c.to_dict()) == c
    assert isinstance(c.cue.v, tuple) and c.model_used in cuesight.MODELS


def test_stubs_match_the_extension():
    """cuesight/_cuesight.pyi names every function of the extension with its parameters."""
    stub = ast.parse((Path(cuesight.__file__).parent / "_cuesight.pyi").read_text())
    stubbed = {
        node.name: [a.arg for a in node.args.args]
        for node in stub.body
        if isinstance(node, ast.FunctionDef)
    }
    real = {
        name: list(inspect.signature(getattr(_cuesight, name)).parameters)
        for name in dir(_cuesight)
        if callable(getattr(_cuesight, name)) and not name.startswith("__")
    }
    assert stubbed == real
    names = {
        target.id
        for node in stub.body
        if isinstance(node, ast.AnnAssign)
        for target in [node.target]
        if isinstance(target, ast.Name)
    }
    assert names == {n for n in dir(_cuesight) if not callable(getattr(_cuesight, n))
                     and not n.startswith("__")} | {"__version__"}
