"""``cuesight.calibrate`` against the CLI: the dict is the JSON ``cuesight calibrate
--throw FILE --json`` prints (the shared measured-throw set, a small CSV, the same
points given as a list of dicts), and an invalid input raises ValueError with the CLI's
message."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any, Dict, List

import pytest

import cuesight

from conftest import REPO

#: The shared calibration set; CI provides ../shared beside the repository.
SHARED = REPO.parent / "shared" / "data" / "measured_throw_calibration.json"

needs_shared = pytest.mark.skipif(
    not SHARED.is_file(),
    reason=f"the shared measured-throw set is not here ({SHARED}; CI provides ../shared)",
)


def calibrate_args(throw: Path, kwargs: Dict[str, Any]) -> List[str]:
    """``cuesight calibrate --json`` flags for ``calibrate``'s keyword arguments."""
    args = ["calibrate", "--throw", str(throw), "--json"]
    for key, value in kwargs.items():
        flag = "--" + key.replace("_", "-")
        if key == "cross_validate":
            if value:
                args.append(flag)
        else:
            args.append(f"{flag}={value}")
    return args


def cli_calibrate(cli, throw: Path, kwargs: Dict[str, Any]) -> Dict[str, Any]:
    code, out, err = cli(calibrate_args(throw, kwargs))
    assert code == 0, f"{throw} {kwargs}: exit {code}: {err}"
    assert out.count("\n") == 1
    return json.loads(out)


def cli_error(cli, throw: Path, kwargs: Dict[str, Any]) -> str:
    code, out, err = cli(calibrate_args(throw, kwargs))
    assert code in (1, 2) and out == "", (code, out, err)
    assert err.startswith("error: ") and err.count("\n") == 1, err
    return err[len("error: "):].rstrip("\n")


SHARED_FLAGS: List[Dict[str, Any]] = [
    {},
    dict(fit="mu"),
    dict(fit="mu-v-e", model="exact"),
    dict(fit="mu", model="reference"),
    dict(cross_validate=True),
    dict(restitution=0.9, mu_s=0.2, default_uncertainty=0.5),
]


@needs_shared
@pytest.mark.parametrize("kwargs", SHARED_FLAGS, ids=repr)
def test_shared_set_is_the_clis(cli, kwargs):
    theirs = cli_calibrate(cli, SHARED, kwargs)
    assert theirs["points"] == 36
    assert cuesight.calibrate(SHARED, **kwargs) == theirs


@needs_shared
def test_no_convergence_is_the_clis_error(cli):
    message = cli_error(cli, SHARED, dict(max_evaluations=50))
    assert message.startswith("the fit did not converge"), message
    with pytest.raises(ValueError) as raised:
        cuesight.calibrate(SHARED, max_evaluations=50)
    assert str(raised.value) == message


@needs_shared
def test_shared_points_as_dicts_are_the_clis_file(cli):
    """The file's points, given as a list of dicts (every key of the file's points, the
    ones calibrate ignores too), fit to what the CLI fits on the file."""
    points = json.loads(SHARED.read_text())["points"]
    for kwargs in ({}, dict(fit="mu", cross_validate=True)):
        assert cuesight.calibrate(points, **kwargs) == cli_calibrate(cli, SHARED, kwargs)


CSV = """# cut, speed, spin, throw: a small set for the test (near TP A.14's mu(v), sliding)
id,cut_deg,speed_mps,spin,throw_deg,uncertainty_deg,series
a,30,3.0,stun,2.5,0.3,fast
b,45,1.0,stun,3.9,0.3,slow
c,50,1.0,follow,1.2,,slow
d,45,3.0,stun,1.4,0.4,fast
e,60,0.5,stun,4.6,0.4,slow
f,60,2.0,stun,1.7,,medium
g,40,2.0,-0.5,1.5,0.3,medium
"""


def csv_points() -> List[Dict[str, Any]]:
    """CSV's rows as the JSON point schema (spin names and ratios as they are)."""
    lines = [l for l in CSV.splitlines() if l and not l.startswith("#")]
    names = lines[0].split(",")
    points = []
    for line in lines[1:]:
        row = dict(zip(names, line.split(",")))
        point: Dict[str, Any] = dict(id=row["id"], series=row["series"])
        for key in ("cut_deg", "speed_mps", "throw_deg"):
            point[key] = float(row[key])
        if row["uncertainty_deg"]:
            point["uncertainty_deg"] = float(row["uncertainty_deg"])
        spin = row["spin"]
        point["spin"] = spin if spin.isalpha() else float(spin)
        points.append(point)
    return points


@pytest.mark.parametrize("kwargs", [{}, dict(fit="mu", cross_validate=True)], ids=repr)
def test_small_csv_is_the_clis(cli, tmp_path, kwargs):
    path = tmp_path / "throw.csv"
    path.write_text(CSV)
    theirs = cli_calibrate(cli, path, kwargs)
    assert theirs["points"] == 7
    assert cuesight.calibrate(path, **kwargs) == theirs
    assert cuesight.calibrate(str(path), **kwargs) == theirs
    assert cuesight.calibrate(csv_points(), **kwargs) == theirs


def test_file_errors_are_the_clis(cli, tmp_path):
    cases = {
        "missing.json": None,
        "bad.csv": "cut_deg,speed_mps,throw_deg\n10,1.0,2.0\n95,1.0,2.0\n",
        "short.csv": "cut_deg,speed_mps,throw_deg\n10,1.0,2.0\n20,1.0,2.5\n30,1.0,3.0\n",
        "nothing.csv": "cut_deg,speed_mps,throw_deg\n",
        "empty.csv": "",
        "columns.csv": "cut_deg,speed,throw_deg\n10,1,2\n",
        "bad.json": '{"points": [{"cut_deg": 10, "speed_mps": 1, "throw_deg": 2},\n'
                    ' {"cut_deg": 10, "speed_mps": 0, "throw_deg": 2}]}',
        "nothing.json": "[]",
        "broken.json": '{"points": [',
    }
    for name, text in cases.items():
        path = tmp_path / name
        if text is not None:
            path.write_text(text)
        message = cli_error(cli, path, {})
        with pytest.raises(ValueError) as raised:
            cuesight.calibrate(path)
        assert str(raised.value) == message, name


@pytest.mark.parametrize(
    "kwargs",
    [dict(restitution=1.5), dict(mu_s=-0.1), dict(default_uncertainty=0.0), dict(fit="mu-v-e")],
    ids=repr,
)
def test_flag_errors_are_the_clis(cli, tmp_path, kwargs):
    """Flag values out of range, and too few points for four parameters."""
    path = tmp_path / "four.csv"
    path.write_text("cut_deg,speed_mps,throw_deg\n10,1,2\n20,1,2.5\n30,2,3\n40,2,2\n")
    message = cli_error(cli, path, kwargs)
    for throw in (path, csv_rows(path)):
        with pytest.raises(ValueError) as raised:
            cuesight.calibrate(throw, **kwargs)
        assert str(raised.value) == message


def csv_rows(path: Path) -> List[Dict[str, float]]:
    lines = path.read_text().splitlines()
    names = lines[0].split(",")
    return [dict(zip(names, map(float, l.split(",")))) for l in lines[1:]]


def test_list_errors_name_the_point_as_the_cli_names_the_line(cli, tmp_path):
    """A bad point of a list: the CLI's message for the same point in a JSON file, with
    ``throw list: point N: `` for the file name and its place."""
    good = dict(cut_deg=10.0, speed_mps=1.0, throw_deg=2.0)
    for bad in (
        dict(good, cut_deg=95.0),
        dict(good, speed_mps=0.0),
        dict(good, spin="sideways"),
        dict(good, uncertainty_deg=-1.0),
        {k: v for k, v in good.items() if k != "throw_deg"},
        dict(good, spin_rad_s=[0.0, 1e5, 0.0]),
    ):
        points = [good, dict(good, cut_deg=20.0), bad]
        path = tmp_path / "points.json"
        path.write_text("[" + ",\n".join(json.dumps(p) for p in points) + "]")
        message = cli_error(cli, path, {})
        prefix = f"{path}: "
        assert message.startswith(prefix) and " at line 3 column " in message, message
        expected = "throw list: point 3: " + message[len(prefix):].rsplit(" at line ", 1)[0]
        with pytest.raises(ValueError) as raised:
            cuesight.calibrate(points)
        assert str(raised.value) == expected


def test_empty_list_and_other_python_errors(cli, tmp_path):
    path = tmp_path / "none.json"
    path.write_text("[]")
    message = cli_error(cli, path, {})
    assert message == f"{path}: no points"
    with pytest.raises(ValueError) as raised:
        cuesight.calibrate([])
    assert str(raised.value) == "throw list: no points"
    with pytest.raises(ValueError, match=r"^invalid value 'mu-e' for fit \[possible values: "
                       r"mu, mu-v, mu-v-e, mu-v-k\]$"):
        cuesight.calibrate([], fit="mu-e")
    with pytest.raises(ValueError, match=r"^invalid value 'kim' for model \[possible values: "
                       r"kim-grip, exact, reference\]$"):
        cuesight.calibrate([], model="kim")
    with pytest.raises(TypeError, match="throw must be a path or a list of point dicts"):
        cuesight.calibrate(dict(points=[]))  # type: ignore[arg-type]
