"""cuesight: what happens when a spinning cue ball hits a resting object ball.

Python bindings of the cuesight engine (the Rust crate ``cuesight``): throw, cue-ball
deflection, spin transfer and hop, with the models of ``cuesight collide``; shot
guidance (``cuesight shot``) and the friction-law fit to measured throw
(``cuesight calibrate``). Each function calls the CLI's own code and returns what the
CLI prints with ``--json``.

Frame (the collision frame of ``cuesight collide``): ``x`` from the cue-ball centre to
the object-ball centre, ``z`` up, ``y = z × x``. SI units (m, s, kg, rad/s); angles in
degrees. Every result is the engine's single-precision (f32) number, widened exactly:
``numpy.float32(result.throw_deg)`` is bit for bit what ``cuesight collide --json``
prints, and inputs are rounded to f32 as the CLI's are.

>>> import cuesight
>>> c = cuesight.collide(speed=2.0, cut_deg=30.0, spin=(0.0, 40.0, 0.0), mu=0.06)
>>> c.model, c.regime, round(c.throw_deg, 3)
('kim-grip', 'sliding', 2.171)
"""

from __future__ import annotations

import json
import os
from collections.abc import Mapping
from dataclasses import asdict, dataclass
from typing import Any, Dict, Iterable, Optional, Sequence, Tuple, Union

import numpy as np

from . import _cuesight

__all__ = [
    "MODELS",
    "REGIMES",
    "DEFAULTS",
    "Ball",
    "Impulses",
    "Inputs",
    "Collision",
    "Collisions",
    "collide",
    "collide_many",
    "shot",
    "calibrate",
]

__version__: str = _cuesight.__version__

#: The core's models, cheapest first (``auto`` picks among the others); the names of
#: ``cuesight collide --model``. ``model="reference"``, the host's f64
#: first-principles solver (about 0.3 ms a scene), is accepted besides.
#: ``Collisions.model_used`` holds indices into this tuple.
MODELS: Tuple[str, ...] = tuple(_cuesight.MODELS)

#: Contact regimes; ``Collisions.regime`` holds indices into this tuple (−1: refused).
REGIMES: Tuple[str, ...] = tuple(_cuesight.REGIMES)

#: What a parameter left out (``None``) takes: the pool defaults of
#: ``cuesight collide`` (μ 0.05, e* 0.95, μ_s 0.3, R 0.028575 m, M 0.17 kg,
#: model ``kim-grip``; ``auto``'s tolerance 1e-3), as the engine's f32 values.
DEFAULTS: Dict[str, Any] = dict(_cuesight._defaults())

Vec3 = Tuple[float, float, float]


@dataclass(frozen=True)
class Ball:
    """One ball just after the impact."""

    v: Vec3
    """Centre velocity (m/s)."""
    w: Vec3
    """Angular velocity (rad/s)."""


@dataclass(frozen=True)
class Impulses:
    """The impulses of the impact on the object ball (N·s)."""

    normal: float
    """Ball–ball normal impulse, along ``+x``."""
    friction: Vec3
    """Ball–ball friction impulse ``(0, y, z)``."""
    table_friction: float
    """Magnitude of the object ball's table friction impulse."""


@dataclass(frozen=True)
class Inputs:
    """The inputs as the engine used them (``input`` of ``collide --json``)."""

    speed: float
    cut_deg: float
    spin: Vec3
    """Cue-ball spin before the impact (rad/s): as given, or derived from ``roll``
    or ``tip``."""
    roll: bool
    mu: float
    """Ball–ball friction μ (a speed-dependent law's high-speed limit ``a``)."""
    mu_b: float
    mu_c: float
    restitution: float
    mu_s: float
    radius: float
    mass: float


@dataclass(frozen=True)
class Collision:
    """One prediction: the fields of ``cuesight collide --json``."""

    model: str
    """The model asked for."""
    regime: str
    """``frictionless``, ``sliding`` or ``gripping``."""
    input: Inputs
    cue: Ball
    object: Ball
    throw_deg: float
    """Throw of the object ball from the line of centres (degrees, towards ``+y``)."""
    cue_deflection_deg: float
    """Cue-ball deflection from the tangent line towards the line of centres (degrees)."""
    separation_deg: float
    """Angle between the balls' horizontal directions (degrees)."""
    impulses: Impulses
    tolerance: Optional[float] = None
    """``auto`` only: the tolerance asked for."""
    model_used: Optional[str] = None
    """``auto`` only: the tier it evaluated."""
    error_estimate: Optional[float] = None
    """``auto`` only: that tier's a-priori error estimate, relative to the speed."""

    @classmethod
    def from_dict(cls, d: Dict[str, Any]) -> "Collision":
        """The result from the dict of ``collide --json`` (as ``to_dict`` gives)."""
        return cls(
            model=d["model"],
            regime=d["regime"],
            input=Inputs(**{k: _tuple(v) for k, v in d["input"].items()}),
            cue=Ball(v=_tuple(d["cue"]["v"]), w=_tuple(d["cue"]["w"])),
            object=Ball(v=_tuple(d["object"]["v"]), w=_tuple(d["object"]["w"])),
            throw_deg=d["throw_deg"],
            cue_deflection_deg=d["cue_deflection_deg"],
            separation_deg=d["separation_deg"],
            impulses=Impulses(
                normal=d["impulses"]["normal"],
                friction=_tuple(d["impulses"]["friction"]),
                table_friction=d["impulses"]["table_friction"],
            ),
            tolerance=d.get("tolerance"),
            model_used=d.get("model_used"),
            error_estimate=d.get("error_estimate"),
        )

    def to_dict(self) -> Dict[str, Any]:
        """The keys and nesting of ``cuesight collide --json`` (vectors as lists; the
        ``auto`` keys only for ``auto``)."""
        d = asdict(self)
        for key in ("tolerance", "model_used", "error_estimate"):
            if d[key] is None:
                del d[key]
        return _lists(d)


def _tuple(value: Any) -> Any:
    return tuple(value) if isinstance(value, (list, tuple)) else value


def _lists(value: Any) -> Any:
    if isinstance(value, dict):
        return {k: _lists(v) for k, v in value.items()}
    if isinstance(value, tuple):
        return [_lists(v) for v in value]
    return value


def collide(
    speed: float,
    cut_deg: float,
    spin: Optional[Sequence[float]] = None,
    *,
    roll: bool = False,
    tip: Optional[Sequence[float]] = None,
    mu: Optional[float] = None,
    mu_b: Optional[float] = None,
    mu_c: Optional[float] = None,
    restitution: Optional[float] = None,
    mu_s: Optional[float] = None,
    radius: Optional[float] = None,
    mass: Optional[float] = None,
    model: str = "kim-grip",
    tolerance: Optional[float] = None,
) -> Collision:
    """Predict one collision, as ``cuesight collide --json`` does.

    speed: cue-ball speed before the impact U (m/s), in (0, 100].
    cut_deg: cut angle φ (degrees), |φ| < 90: the cue ball moves at U (cos φ, sin φ, 0).
    spin: cue-ball angular velocity ``(ω_x, ω_y, ω_z)`` (rad/s; topspin is ω_y > 0);
        stun when absent. Or ``roll=True`` (natural roll for the velocity), or
        ``tip=(side, height)``: the spin a cue strike at that tip offset gives (ball
        radii, side > 0 right english, height > 0 follow, |b| ≤ 0.5; (0, 0.4) is
        natural roll), as ``collide --tip``.
    mu: ball–ball friction μ (default 0.05); with ``mu_b``/``mu_c`` the high-speed
        limit a of μ(v) = a + b·exp(−c·v), v the slip speed (``mu_b`` = b, default 0;
        ``mu_c`` = c in s/m, default 0).
    restitution: energetic coefficient of restitution e* (default 0.95).
    mu_s: object-ball/table static friction μ_s (default 0.3).
    radius, mass: ball radius R (m, default 0.028575) and mass M (kg, default 0.17).
    model: one of ``MODELS`` (default ``kim-grip``), or ``reference``: the f64
        first-principles solver of ``collide --model reference`` (about 0.3 ms).
    tolerance: with ``model="auto"``: the accepted error of the tier it picks, relative
        to U, in (0, 1] (default 1e-3); the result then has ``model_used`` and
        ``error_estimate``.

    Raises ValueError with the engine's message (naming the field) on invalid input.
    """
    return Collision.from_dict(
        _cuesight._collide(
            speed,
            cut_deg,
            None if spin is None else _floats(spin, 3, "spin"),
            roll,
            None if tip is None else _floats(tip, 2, "tip"),
            mu,
            mu_b,
            mu_c,
            restitution,
            mu_s,
            radius,
            mass,
            model,
            tolerance,
        )
    )


def _floats(values: Sequence[float], n: int, name: str) -> Tuple[float, ...]:
    out = tuple(float(v) for v in values)
    if len(out) != n:
        raise ValueError(f"{name} needs {n} numbers, got {len(out)}")
    return out


@dataclass(frozen=True)
class Collisions:
    """Many predictions (``collide_many``): one row per scene, f32 arrays; vectors are
    ``(n, 3)``. Row ``i`` holds the numbers ``collide`` gives for scene ``i``."""

    throw_deg: np.ndarray
    cue_deflection_deg: np.ndarray
    separation_deg: np.ndarray
    cue_v: np.ndarray
    """Cue-ball velocity after the impact (m/s), ``(n, 3)``."""
    cue_w: np.ndarray
    """Cue-ball angular velocity after the impact (rad/s), ``(n, 3)``."""
    object_v: np.ndarray
    object_w: np.ndarray
    impulse_normal: np.ndarray
    impulse_friction: np.ndarray
    table_friction: np.ndarray
    spin: np.ndarray
    """The cue-ball spin used (rad/s), ``(n, 3)``: as given, or from ``roll``/``tip``."""
    regime: np.ndarray
    """int8 indices into ``REGIMES``; −1 for a refused scene."""
    valid: np.ndarray
    """Whether the scene was predicted (always all true with ``errors="raise"``)."""
    model_used: Optional[np.ndarray] = None
    """``auto`` only: int8 indices into ``MODELS`` of the tier evaluated."""
    error_estimate: Optional[np.ndarray] = None
    """``auto`` only: that tier's error estimate, relative to the speed."""

    def __len__(self) -> int:
        return len(self.throw_deg)

    def regime_names(self) -> np.ndarray:
        """The regimes as strings (``"invalid"`` for a refused scene)."""
        names = np.array(REGIMES + ("invalid",))
        return names[self.regime.astype(np.intp)]


ArrayLike = Union[float, Sequence[float], np.ndarray]


def collide_many(
    speed: ArrayLike,
    cut_deg: ArrayLike,
    spin: Optional[ArrayLike] = None,
    *,
    roll: Union[bool, Sequence[bool], np.ndarray] = False,
    tip: Optional[ArrayLike] = None,
    mu: Optional[ArrayLike] = None,
    mu_b: Optional[ArrayLike] = None,
    mu_c: Optional[ArrayLike] = None,
    restitution: Optional[ArrayLike] = None,
    mu_s: Optional[ArrayLike] = None,
    radius: Optional[ArrayLike] = None,
    mass: Optional[ArrayLike] = None,
    model: str = "kim-grip",
    tolerance: Optional[float] = None,
    errors: str = "raise",
) -> Collisions:
    """Predict many collisions: ``collide`` over arrays, on one core, without the GIL.

    Each scalar input is a number (the same for every scene) or a 1-D array of n values;
    ``spin`` is ``(3,)`` or ``(n, 3)``, ``tip`` ``(2,)`` or ``(n, 2)``, ``roll`` a bool
    or n bools. Inputs are rounded to f32. ``model`` and ``tolerance`` are one for the
    batch; ``model="reference"`` works too, at about 0.3 ms a scene (with it, one
    batch runs at a time in the process). ``errors="raise"`` (default): the first
    invalid scene raises ValueError (``scene i: <the engine's message>``);
    ``errors="nan"``: it gets NaN, regime −1 and ``valid`` false, and the others are
    predicted.
    """
    if errors not in ("raise", "nan"):
        raise ValueError(f"errors must be 'raise' or 'nan', not {errors!r}")
    scalars = {
        "speed": speed,
        "cut_deg": cut_deg,
        "mu": mu,
        "mu_b": mu_b,
        "mu_c": mu_c,
        "restitution": restitution,
        "mu_s": mu_s,
        "radius": radius,
        "mass": mass,
    }
    columns: Dict[str, Optional[np.ndarray]] = {}
    lengths = []
    for name, value in scalars.items():
        if value is None:
            columns[name] = None
            continue
        a = np.ascontiguousarray(value, dtype=np.float32)
        if a.ndim > 1:
            raise ValueError(f"{name} must be a number or a 1-D array, got shape {a.shape}")
        a = a.reshape(-1)
        if len(a) != 1:
            lengths.append((name, len(a)))
        columns[name] = a
    roll_a = np.ascontiguousarray(roll, dtype=np.bool_)
    if roll_a.ndim > 1:
        raise ValueError(f"roll must be a bool or a 1-D array, got shape {roll_a.shape}")
    roll_a = roll_a.reshape(-1)
    if len(roll_a) != 1:
        lengths.append(("roll", len(roll_a)))
    vectors: Dict[str, Optional[np.ndarray]] = {}
    for name, value, width in (("spin", spin, 3), ("tip", tip, 2)):
        if value is None:
            vectors[name] = None
            continue
        a = np.ascontiguousarray(value, dtype=np.float32)
        if a.shape == (width,):
            pass
        elif a.ndim == 2 and a.shape[1] == width:
            if a.shape[0] != 1:
                lengths.append((name, a.shape[0]))
        else:
            raise ValueError(f"{name} must have shape ({width},) or (n, {width}), got {a.shape}")
        vectors[name] = a.reshape(-1)
    sizes = {length for _, length in lengths}
    if len(sizes) > 1:
        shown = ", ".join(f"{name} {length}" for name, length in lengths)
        raise ValueError(f"arrays of different lengths: {shown}")
    n = sizes.pop() if sizes else 1
    out = _cuesight._collide_many(
        n,
        columns["speed"],
        columns["cut_deg"],
        vectors["spin"],
        roll_a,
        vectors["tip"],
        columns["mu"],
        columns["mu_b"],
        columns["mu_c"],
        columns["restitution"],
        columns["mu_s"],
        columns["radius"],
        columns["mass"],
        model,
        tolerance,
        errors == "raise",
    )
    return Collisions(**out)


PathLike = Union[str, "os.PathLike[str]"]


def _path(value: Any) -> Optional[str]:
    """``value`` as a file name if it is one (str or os.PathLike), else None."""
    if isinstance(value, (str, os.PathLike)):
        return os.fspath(value)
    return None


def _json_value(value: Any) -> Any:
    """numpy scalars and arrays as plain numbers and lists (for ``json.dumps``)."""
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, np.ndarray):
        return value.tolist()
    raise TypeError(f"{type(value).__name__} is not a JSON value")


def _dumps(value: Any) -> str:
    return json.dumps(value, default=_json_value, allow_nan=False)


def shot(
    scene: Union[Mapping, PathLike, None] = None,
    *,
    params: Optional[PathLike] = None,
    table: Optional[str] = None,
    cue: Optional[Sequence[float]] = None,
    balls: Optional[Sequence[Sequence[float]]] = None,
    object: Optional[int] = None,
    pocket: Union[int, str, None] = None,
    speed: Optional[float] = None,
    tip: Optional[Sequence[float]] = None,
    aim: Optional[float] = None,
    solve: bool = False,
    model: Optional[str] = None,
    tolerance: Optional[float] = None,
    mu: Optional[float] = None,
    restitution: Optional[float] = None,
    mu_s: Optional[float] = None,
    mu_cloth: Optional[float] = None,
    mu_roll: Optional[float] = None,
    radius: Optional[float] = None,
    mass: Optional[float] = None,
    cue_mass: Optional[float] = None,
    tip_restitution: Optional[float] = None,
    svg: Optional[PathLike] = None,
) -> Dict[str, Any]:
    """Shot guidance, as ``cuesight shot --json`` gives it: the dict of its JSON.

    scene: a scene as a dict (the keys of a scene file, docs/shot-cli.md: ``table``,
        ``cue``, ``balls``, ``object``, ``pocket``, ``speed``, ``tip``, ``aim``,
        ``model``, ``mu``, ...), or the path of a ``.toml`` or ``.json`` scene file
        (``--scene``), or None (the keyword arguments alone).
    The keyword arguments are ``shot``'s flags and override the scene's keys: ``params``
    (a JSON file of contact parameters, e.g. what ``calibrate`` returns saved with
    ``json.dump``; between the scene and the flags), ``table`` (``pool``, ``snooker``,
    ``carom``), ``cue`` (x, y) and ``balls`` [(x, y), ...] (m, table frame; a non-empty
    ``balls`` replaces the scene's), ``object``, ``pocket`` (index or name), ``speed``
    (cue speed, m/s), ``tip`` (side, height in ball radii), ``aim`` (degrees; none:
    solve for the pocket), ``solve`` (ignore the scene's aim), ``model`` and
    ``tolerance``, ``mu``, ``restitution``, ``mu_s``, ``mu_cloth``, ``mu_roll``,
    ``radius``, ``mass``, ``cue_mass``, ``tip_restitution``. ``svg``: also write the
    drawing of ``shot --svg`` to that file.

    Numbers are those of the JSON: the engine's f32 printed as the shortest decimal
    that reads back to it (``numpy.float32(v)`` has its bits). Raises ValueError with
    the CLI's message (off the table, no aim found, unknown key, ...).
    """
    scene_file = scene_json = None
    if scene is None:
        pass
    elif isinstance(scene, Mapping):
        scene_json = _dumps(dict(scene))
    else:
        scene_file = _path(scene)
        if scene_file is None:
            raise TypeError(
                f"scene must be a dict or a path, not {type(scene).__name__}"
            )
    text = _cuesight._shot(
        scene_file,
        scene_json,
        None if params is None else os.fspath(params),
        table,
        None if cue is None else _floats(cue, 2, "cue"),
        None if balls is None else [_floats(b, 2, "balls[]") for b in balls],
        object,
        None if pocket is None else str(pocket),
        speed,
        None if tip is None else _floats(tip, 2, "tip"),
        aim,
        solve,
        model,
        tolerance,
        mu,
        restitution,
        mu_s,
        mu_cloth,
        mu_roll,
        radius,
        mass,
        cue_mass,
        tip_restitution,
        None if svg is None else os.fspath(svg),
    )
    return json.loads(text)


def calibrate(
    throw: Union[PathLike, Iterable[Mapping]],
    *,
    fit: str = "mu-v",
    model: str = "kim-grip",
    restitution: float = 0.95,
    mu_s: float = 0.3,
    default_uncertainty: float = 1.0,
    cross_validate: bool = False,
    max_evaluations: int = 100_000,
) -> Dict[str, Any]:
    """Fit the ball–ball friction law to measured throw, as ``cuesight calibrate --json``
    does: the dict of its JSON (the parameters under ``collide``'s names, their
    ``stderr``, ``ci95`` and ``interval95``, ``rms_deg``, ``max_deg``, per-point
    ``residuals`` and, with ``cross_validate``, ``cross_validation``).

    throw: a file as ``--throw`` reads it (JSON, or CSV with columns ``cut_deg``,
        ``speed_mps``, ``spin``, ``throw_deg``[, ``uncertainty_deg``]), or the points
        themselves: dicts of the JSON point schema of docs/calibration.md
        (``cut_deg``, ``speed_mps``, ``throw_deg``, optional ``spin``, ``spin_rad_s``,
        ``uncertainty_deg``, ``id``, ``series``).
    fit: ``mu`` (constant μ), ``mu-v`` (μ(v) = mu + mu_b·exp(−mu_c·v)), ``mu-v-e``
        (μ(v) and e*) or ``mu-v-k`` (μ(v) and the contact's tangential compliance,
        always by the reference solver).
    model: the model of the throw: ``kim-grip``, ``exact`` or ``reference`` (slower).
    restitution, mu_s: e* when not fitted (the start value with ``mu-v-e``) and the
        object-ball/table friction.
    default_uncertainty: the uncertainty (degrees) of points that give none.
    cross_validate: also fit each series left out in turn and predict it.
    max_evaluations: give up after this many model evaluations.

    The fit runs without the GIL. Like the CLI, a fit longer than a second prints a
    progress line on stderr every second. Raises ValueError with the CLI's message
    (unreadable file, a value out of range naming its line or point, too few points,
    no convergence).
    """
    path = _path(throw)
    points = None
    if path is None:
        if isinstance(throw, Mapping):
            raise TypeError("throw must be a path or a list of point dicts, not a dict")
        points = [_dumps(p) for p in throw]
    return json.loads(
        _cuesight._calibrate(
            path,
            points,
            fit,
            model,
            restitution,
            mu_s,
            default_uncertainty,
            cross_validate,
            max_evaluations,
        )
    )
