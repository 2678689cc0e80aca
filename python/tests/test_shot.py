"""``cuesight.shot`` against the CLI: the dict is the JSON ``cuesight shot --json``
prints for the same scene file and flags (scene files of cli/scenes, the same
scenes as dicts, flags over them, no scene at all), the drawing is ``--svg``'s, and an
invalid shot raises ValueError with the CLI's message."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any, Dict, List, Tuple

import pytest

import cuesight

from conftest import REPO, f32_text

SCENES = REPO / "cli" / "scenes"
TOML = sorted(SCENES.glob("*.toml"))
JSON = sorted(SCENES.glob("*.json"))


def shot_args(scene: Any, kwargs: Dict[str, Any]) -> List[str]:
    """``cuesight shot --json`` flags for a scene file and ``shot``'s keyword arguments."""
    args = ["shot", "--json"]
    if scene is not None:
        args += ["--scene", str(scene)]
    for key, value in kwargs.items():
        flag = "--" + key.replace("_", "-")
        if key == "solve":
            if value:
                args.append(flag)
        elif key == "balls":
            args += ["--ball=" + ",".join(f32_text(v) for v in ball) for ball in value]
        elif key in ("cue", "tip"):
            args.append(flag + "=" + ",".join(f32_text(v) for v in value))
        elif key in ("table", "model", "pocket", "object", "params", "svg"):
            args += [flag, str(value)]
        else:
            args.append(flag + "=" + f32_text(value))
    return args


def cli_shot(cli, scene: Any, kwargs: Dict[str, Any]) -> Dict[str, Any]:
    code, out, err = cli(shot_args(scene, kwargs))
    assert code == 0 and err == "", f"{scene} {kwargs}: exit {code}: {err}"
    assert out.count("\n") == 1
    return json.loads(out)


def cli_error(cli, scene: Any, kwargs: Dict[str, Any]) -> Tuple[int, str]:
    code, out, err = cli(shot_args(scene, kwargs))
    assert code in (1, 2) and out == "", (code, out, err)
    assert err.startswith("error: ") and err.count("\n") == 1, err
    return code, err[len("error: "):].rstrip("\n")


@pytest.mark.parametrize("scene", TOML + JSON, ids=lambda p: p.name)
def test_scene_files_are_the_clis(cli, scene):
    theirs = cli_shot(cli, scene, {})
    assert theirs["mode"] == "solve"
    assert cuesight.shot(scene) == theirs
    assert cuesight.shot(str(scene)) == theirs


def scene_dict(path: Path) -> Dict[str, Any]:
    if path.suffix == ".json":
        return json.loads(path.read_text())
    tomllib = pytest.importorskip("tomllib", reason="tomllib (Python 3.11+) reads the TOML")
    return tomllib.loads(path.read_text())


@pytest.mark.parametrize("scene", TOML + JSON, ids=lambda p: p.name)
def test_scene_dicts_are_the_clis_files(cli, scene):
    """A scene given as a dict is the scene file it came from."""
    assert cuesight.shot(scene_dict(scene)) == cli_shot(cli, scene, {})


CUT = SCENES / "cut_to_corner.toml"
CUT_JSON = SCENES / "cut_to_corner.json"
SNOOKER = SCENES / "snooker_draw_to_middle.toml"

FLAGS: List[Tuple[Any, Dict[str, Any]]] = [
    (CUT, dict(aim=5.0)),
    (CUT, dict(aim=-12.5, speed=1.2, tip=(-0.2, -0.3))),
    (CUT_JSON, dict(speed=2.0, tip=(0.1, 0.2), model="exact")),
    (CUT_JSON, dict(tolerance=0.01)),
    (CUT_JSON, dict(model="kim")),
    (CUT, dict(object=2, pocket=4)),
    (CUT, dict(pocket="bottom-side", object=2)),
    (CUT, dict(cue=(0.5, 0.5), balls=[(1.9, 0.9)], object=1, pocket=3)),
    (SNOOKER, dict(mu=0.08, restitution=0.9, mu_s=0.2, mu_cloth=0.25, mu_roll=0.02,
                   cue_mass=0.6, tip_restitution=0.8)),
    (SNOOKER, dict(pocket=3)),
    (CUT, dict(radius=0.0262, mass=0.156)),
    (None, dict(table="snooker", cue=(1.0, 0.9), balls=[(1.5, 1.3)], pocket="top-side",
                speed=2.0)),
    (None, dict(table="carom", cue=(0.5, 0.5), balls=[(1.5, 0.7), (2.0, 1.0)], aim=10.0)),
    (None, dict(cue=(1.0, 0.6), aim=0.0)),
]


@pytest.mark.parametrize("scene, kwargs", FLAGS, ids=lambda x: getattr(x, "name", repr(x)))
def test_flags_are_the_clis(cli, scene, kwargs):
    assert cuesight.shot(scene, **kwargs) == cli_shot(cli, scene, kwargs)


def test_solve_ignores_the_scenes_aim(cli, tmp_path):
    scene = dict(scene_dict(CUT_JSON), aim=3.0)
    path = tmp_path / "aimed.json"
    path.write_text(json.dumps(scene))
    played = cli_shot(cli, path, {})
    solved = cli_shot(cli, path, dict(solve=True))
    assert played["mode"] == "play" and solved["mode"] == "solve"
    assert cuesight.shot(scene) == cuesight.shot(path) == played
    assert cuesight.shot(scene, solve=True) == solved


def test_params_file_is_the_clis(cli, tmp_path):
    """A params file (what ``calibrate`` returns, saved) between the scene and flags."""
    params = tmp_path / "params.json"
    params.write_text(json.dumps(dict(mu=0.01, mu_b=0.1, mu_c=1.2, restitution=0.93,
                                      fit="mu-v", rms_deg=0.4)))
    for kwargs in (dict(params=params), dict(params=params, mu=0.03)):
        theirs = cli_shot(cli, CUT, kwargs)
        assert cuesight.shot(CUT, **kwargs) == theirs
    assert cuesight.shot(CUT, params=params) != cuesight.shot(CUT)


def test_svg_is_the_clis_drawing(cli, tmp_path):
    ours, theirs = tmp_path / "ours.svg", tmp_path / "theirs.svg"
    expected = cli_shot(cli, SNOOKER, dict(svg=theirs))
    assert cuesight.shot(SNOOKER, svg=ours) == expected
    assert ours.read_bytes() == theirs.read_bytes()
    assert "<svg" in ours.read_text() and ours.read_text().rstrip().endswith("</svg>")


ERRORS: List[Tuple[Any, Dict[str, Any]]] = [
    (None, {}),  # no cue ball
    (CUT, dict(cue=(5.0, 0.5))),
    (CUT, dict(balls=[(0.92, 0.81)])),
    (CUT, dict(object=5)),
    (CUT, dict(object=0)),
    (CUT, dict(pocket=9)),
    (CUT, dict(pocket="middle")),
    (CUT, dict(pocket="top-left")),
    (CUT, dict(tip=(0.6, 0.0))),
    (CUT, dict(speed=-1.0)),
    (CUT, dict(mu=1.5)),
    (CUT, dict(model="kim", tolerance=0.01)),
    (CUT_JSON, dict(tolerance=2.0)),
    (None, dict(table="carom", cue=(0.5, 0.5), balls=[(1.5, 0.7)])),
    (None, dict(table="carom", cue=(0.5, 0.5), balls=[(1.5, 0.7)], pocket=0)),
    (None, dict(cue=(1.0, 0.6), pocket=3)),
    (SCENES / "missing.toml", {}),
    (SCENES / "missing.json", {}),
    (REPO / "README.md", {}),
    (CUT, dict(params=SCENES / "missing.json")),
]


@pytest.mark.parametrize("scene, kwargs", ERRORS, ids=lambda x: getattr(x, "name", repr(x)))
def test_errors_are_the_clis(cli, scene, kwargs):
    _, message = cli_error(cli, scene, kwargs)
    with pytest.raises(ValueError) as raised:
        cuesight.shot(scene, **kwargs)
    assert str(raised.value) == message


def test_scene_dict_errors_are_the_clis_file_errors(cli, tmp_path):
    """A dict is read as the JSON file of its ``json.dumps`` (the same line and column);
    the message names ``scene`` instead of the file."""
    path = tmp_path / "scene.json"
    for scene in (
        dict(cue=[0.9, 0.8], speeed=2.0),
        dict(cue=[0.9, 0.8], tip=[0.1]),
        dict(cue=[0.9, 0.8], pocket=-1),
        dict(cue=[0.9, 0.8], table=dict(length=2.0, width=1.0, pockets=6)),
        dict(cue="centre"),
    ):
        path.write_text(json.dumps(scene))
        code, message = cli_error(cli, path, {})
        assert code == 2
        prefix = f"scene file {path}: "
        assert message.startswith(prefix), message
        with pytest.raises(ValueError) as raised:
            cuesight.shot(scene)
        assert str(raised.value) == "scene: " + message[len(prefix):]


def test_python_side_errors():
    with pytest.raises(ValueError, match=r"^invalid value 'billiards' for table \[possible "
                       r"values: pool, snooker, carom\]$"):
        cuesight.shot(CUT, table="billiards")
    with pytest.raises(ValueError, match=r"^invalid value 'kimgrip' for model: unknown model"):
        cuesight.shot(CUT, model="kimgrip")
    with pytest.raises(ValueError, match=r"^invalid value '' for pocket: pocket needs"):
        cuesight.shot(CUT, pocket="")
    with pytest.raises(ValueError, match="cue needs 2 numbers, got 3"):
        cuesight.shot(CUT, cue=(1.0, 2.0, 3.0))
    with pytest.raises(TypeError, match="scene must be a dict or a path"):
        cuesight.shot(42)  # type: ignore[arg-type]
