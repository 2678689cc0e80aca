"""The Python layer against the reference of identity, the ``cuesight`` CLI: every
number of ``collide(...).to_dict()`` has the f32 bits ``cuesight collide --json``
prints, for every model and input kind; ``collide_many`` rows have them too; invalid
values raise ValueError with the CLI's message."""

from __future__ import annotations

import json
from typing import Any, Dict, List, Optional

import numpy as np
import pytest

import cuesight

from conftest import assert_same, cli_args

CASES: List[Dict[str, Any]] = [
    # The README's worked example.
    dict(speed=2.0, cut_deg=30.0, spin=(0.0, 40.0, 0.0), mu=0.06),
    dict(speed=2.0, cut_deg=30.0),
    dict(speed=1.5, cut_deg=-45.0, roll=True),
    dict(speed=3.0, cut_deg=20.0, tip=(0.3, -0.2)),
    dict(speed=3.0, cut_deg=20.0, tip=(0.0, 0.4), model="exact"),
    dict(speed=2.5, cut_deg=10.0, spin=(5.0, -60.0, 30.0), mu=0.01, mu_b=0.1, mu_c=1.1),
    dict(speed=0.8, cut_deg=60.0, spin=(0.0, 20.0, -80.0), restitution=0.9, mu_s=0.2,
         radius=0.02625, mass=0.142),
    # Exact gearing: grips.
    dict(speed=1.0, cut_deg=0.0, spin=(0.0, 0.0, 0.0), mu=0.3, model="kim-grip"),
    dict(speed=4.0, cut_deg=35.0, spin=(0.0, 100.0, 50.0), model="auto"),
    dict(speed=4.0, cut_deg=35.0, spin=(0.0, 100.0, 50.0), model="auto", tolerance=0.01),
    dict(speed=4.0, cut_deg=35.0, spin=(0.0, 100.0, 50.0), model="auto", tolerance=1e-5),
] + [
    dict(speed=2.0, cut_deg=30.0, spin=(0.0, 40.0, 10.0), mu=0.06, model=model)
    for model in cuesight.MODELS
]


def random_cases(n: int, seed: int) -> List[Dict[str, Any]]:
    """Seeded scenes over the models, spin kinds and parameters (f32 values)."""
    rng = np.random.default_rng(seed)
    cases = []
    for i in range(n):
        f = lambda lo, hi: float(np.float32(rng.uniform(lo, hi)))  # noqa: E731
        case: Dict[str, Any] = dict(
            speed=f(0.05, 8.0), cut_deg=f(-85.0, 85.0), model=cuesight.MODELS[i % 6]
        )
        kind = i % 4
        if kind == 0:
            case["spin"] = tuple(f(-300.0, 300.0) for _ in range(3))
        elif kind == 1:
            case["roll"] = True
        elif kind == 2:
            case["tip"] = (f(-0.3, 0.3), f(-0.35, 0.35))
        if rng.random() < 0.7:
            case["mu"] = f(0.0, 0.3)
        if rng.random() < 0.3:
            case["mu_b"], case["mu_c"] = f(0.0, 0.2), f(0.0, 5.0)
        if rng.random() < 0.3:
            case["restitution"], case["mu_s"] = f(0.5, 1.0), f(0.0, 0.8)
        if rng.random() < 0.2:
            case["radius"], case["mass"] = f(0.02, 0.04), f(0.1, 0.3)
        cases.append(case)
    return cases


RANDOM = random_cases(48, seed=18)

#: ``model="reference"``, the host's f64 solver (the CLI's ``--model reference``): fixed
#: cases over the spin kinds and a μ(v), and seeded scenes.
REFERENCE: List[Dict[str, Any]] = [
    dict(speed=2.0, cut_deg=30.0, spin=(0.0, 40.0, 10.0), mu=0.06, model="reference"),
    dict(speed=1.5, cut_deg=-45.0, roll=True, model="reference"),
    dict(speed=3.0, cut_deg=20.0, tip=(0.3, -0.2), model="reference"),
    dict(speed=2.5, cut_deg=10.0, spin=(5.0, -60.0, 30.0), mu=0.01, mu_b=0.1, mu_c=1.1,
         model="reference"),
] + [dict(c, model="reference") for c in random_cases(12, seed=1800)]


def cli_json(cli, kwargs: Dict[str, Any]) -> Dict[str, Any]:
    code, out, err = cli(cli_args(kwargs))
    assert code == 0, f"{kwargs}: exit {code}: {err}"
    return json.loads(out)


def cli_refusal(cli, kwargs: Dict[str, Any]) -> Optional[str]:
    """The CLI's message when the model refuses the scene outside its validity domain
    (``kim`` where the contact grips, ``kim-grip`` outside its parameters' domain), else
    None."""
    code, _, err = cli(cli_args(kwargs))
    if code == 1 and " is valid only where " in err:
        return err.strip().removeprefix("error: ")
    return None


@pytest.mark.parametrize("kwargs", CASES + RANDOM + REFERENCE, ids=lambda k: repr(k))
def test_collide_is_the_clis(cli, kwargs):
    refusal = cli_refusal(cli, kwargs)
    if refusal is not None:
        # The same refusal, word for word.
        with pytest.raises(ValueError) as raised:
            cuesight.collide(**kwargs)
        assert str(raised.value) == refusal
        return
    theirs = cli_json(cli, kwargs)
    ours = cuesight.collide(**kwargs).to_dict()
    assert_same(ours, theirs)


def test_collide_many_rows_are_the_clis(cli):
    """One batch per model over the random scenes (spin, roll and tip mixed per row)."""
    for model in cuesight.MODELS + ("reference",):
        cases = [c for c in RANDOM + REFERENCE if c["model"] == model]
        n = len(cases)
        spin = np.array([c.get("spin", (0.0, 0.0, 0.0)) for c in cases])
        has_spin = np.array(["spin" in c for c in cases])
        # Rows without spin: stun (zeros), roll or tip; give spin per row only where the
        # scene has one by splitting on the kind.
        groups = {
            "spin": [i for i, c in enumerate(cases) if "spin" in c],
            "roll": [i for i, c in enumerate(cases) if c.get("roll")],
            "tip": [i for i, c in enumerate(cases) if "tip" in c],
            "stun": [
                i for i, c in enumerate(cases)
                if "spin" not in c and "tip" not in c and not c.get("roll")
            ],
        }
        assert sum(len(g) for g in groups.values()) == n and has_spin.sum() == len(groups["spin"])
        for kind, rows in groups.items():
            if not rows:
                continue
            sub = [cases[i] for i in rows]
            kwargs: Dict[str, Any] = dict(
                speed=[c["speed"] for c in sub], cut_deg=[c["cut_deg"] for c in sub]
            )
            defaults = cuesight.DEFAULTS
            for key in ("mu", "mu_b", "mu_c", "restitution", "mu_s", "radius", "mass"):
                # A scene without the key takes the default, which is what None gives.
                kwargs[key] = [c.get(key, defaults[key]) for c in sub]
            if kind == "spin":
                kwargs["spin"] = spin[rows]
            elif kind == "roll":
                kwargs["roll"] = True
            elif kind == "tip":
                kwargs["tip"] = [c["tip"] for c in sub]
            many = cuesight.collide_many(**kwargs, model=model, errors="nan")
            for j, case in enumerate(sub):
                # A row the CLI refuses (outside the model's validity domain) is invalid.
                if cli_refusal(cli, case) is not None:
                    assert not many.valid[j], f"{model} {kind} {case}"
                    continue
                assert many.valid[j], f"{model} {kind} {case}"
                theirs = cli_json(cli, case)
                row = {
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
                    "spin": many.spin[j].tolist(),
                }
                expected = {k: theirs[k] for k in row if k != "spin"}
                expected["spin"] = theirs["input"]["spin"]
                assert_same(row, expected, f"{model} {kind} {case}")
                if model == "auto":
                    assert cuesight.MODELS[many.model_used[j]] == theirs["model_used"]
                    assert_same(float(many.error_estimate[j]), theirs["error_estimate"])


INVALID: List[Dict[str, Any]] = [
    dict(speed=2.0, cut_deg=30.0, mu=-0.1),
    dict(speed=-1.0, cut_deg=30.0),
    dict(speed=0.0, cut_deg=30.0),
    dict(speed=101.0, cut_deg=30.0),
    dict(speed=2.0, cut_deg=90.0),
    dict(speed=2.0, cut_deg=-90.0, roll=True),
    dict(speed=2.0, cut_deg=30.0, spin=(0.0, 2e4, 0.0)),
    dict(speed=2.0, cut_deg=30.0, spin=(float("nan"), 0.0, 0.0)),
    dict(speed=2.0, cut_deg=30.0, mu=0.5, mu_b=0.6, mu_c=1.0),
    dict(speed=2.0, cut_deg=30.0, mu_c=200.0, mu_b=0.1),
    dict(speed=2.0, cut_deg=30.0, restitution=1.5),
    dict(speed=2.0, cut_deg=30.0, mu_s=float("inf")),
    dict(speed=2.0, cut_deg=30.0, radius=0.0),
    dict(speed=2.0, cut_deg=30.0, mass=1e6),
    dict(speed=2.0, cut_deg=30.0, tip=(0.0, 0.6)),
    dict(speed=2.0, cut_deg=30.0, model="auto", tolerance=0.0),
    dict(speed=2.0, cut_deg=30.0, model="auto", tolerance=2.0),
    dict(speed=2.0, cut_deg=30.0, mu=-0.1, model="reference"),
    dict(speed=2.0, cut_deg=30.0, tip=(0.0, 0.6), model="reference"),
]


@pytest.mark.parametrize("kwargs", INVALID, ids=lambda k: repr(k))
def test_invalid_values_raise_the_clis_message(cli, kwargs):
    code, out, err = cli(cli_args(kwargs))
    assert code == 1 and out == "", (code, out, err)
    assert err.startswith("error: ") and err.count("\n") == 1, err
    with pytest.raises(ValueError) as raised:
        cuesight.collide(**kwargs)
    assert str(raised.value) == err[len("error: "):].rstrip("\n")
    with pytest.raises(ValueError) as raised_many:
        cuesight.collide_many(**{k: [v] if k not in ("spin", "tip", "roll", "model", "tolerance") else v
                                 for k, v in kwargs.items()})
    assert str(raised_many.value) == "scene 0: " + str(raised.value)


def test_tolerance_with_another_model_is_the_clis_usage_error(cli):
    """Refused as the CLI refuses it (exit 2), by collide and once for a batch."""
    for model in ("kim-grip", "exact", "reference"):
        kwargs = dict(speed=2.0, cut_deg=30.0, model=model, tolerance=0.01)
        code, out, err = cli(cli_args(kwargs))
        assert code == 2 and out == "" and err.startswith("error: "), (code, out, err)
        message = err[len("error: "):].rstrip("\n")
        with pytest.raises(ValueError) as raised:
            cuesight.collide(**kwargs)
        assert str(raised.value) == message
        with pytest.raises(ValueError) as raised_many:
            cuesight.collide_many([2.0, 3.0], 30.0, model=model, tolerance=0.01)
        assert str(raised_many.value) == message


def test_unknown_model_is_the_clis_message(cli):
    """The CLI's ``--model`` parser: clap says ``for '--model <MODEL>'``, Python ``for
    model``; the message after it is the same."""
    code, out, err = cli(["collide", "--speed", "1", "--cut", "0", "--model", "kimgrip"])
    assert code == 2 and out == ""
    head, theirs = err.rstrip("\n").split("': ", 1)
    assert head == "error: invalid value 'kimgrip' for '--model <MODEL>"
    for call in (cuesight.collide, cuesight.collide_many):
        with pytest.raises(ValueError) as raised:
            call(1.0, 0.0, model="kimgrip")
        assert str(raised.value) == "invalid value 'kimgrip' for model: " + theirs
    assert "reference" in theirs
