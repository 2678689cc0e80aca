"""The reference of identity: the ``cuesight`` CLI (``cuesight collide --json``).

The binary is ``$CUESIGHT_CLI`` when set (``cargo xtask test`` sets it to the one it
built); otherwise it is built here with cargo from the repository this package sits in.
Without either, the tests that need it are skipped (an installed package alone cannot
run them).
"""

from __future__ import annotations

import json
import os
import shutil
import struct
import subprocess
from pathlib import Path
from typing import Any, Callable, Dict, List, Optional, Tuple

import numpy as np
import pytest

REPO = Path(__file__).resolve().parents[2]


def _build_cli() -> Optional[Path]:
    cargo = shutil.which("cargo")
    if cargo is None or not (REPO / "cli").is_dir():
        return None
    subprocess.run(
        [cargo, "build", "-q", "--bin", "cuesight"],
        cwd=REPO,
        check=True,
    )
    meta = subprocess.run(
        [cargo, "metadata", "--format-version", "1", "--no-deps", "-q"],
        cwd=REPO,
        check=True,
        capture_output=True,
        text=True,
    )
    return Path(json.loads(meta.stdout)["target_directory"]) / "debug" / "cuesight"


@pytest.fixture(scope="session")
def cli_path() -> Path:
    given = os.environ.get("CUESIGHT_CLI")
    if given:
        path = Path(given)
        assert path.is_file(), f"CUESIGHT_CLI={given} is not a file"
        return path
    path = _build_cli()
    if path is None:
        pytest.skip("no cuesight CLI: set CUESIGHT_CLI or run from the repository with cargo")
    return path


Run = Callable[[List[str]], Tuple[int, str, str]]


@pytest.fixture(scope="session")
def cli(cli_path: Path) -> Run:
    def run(args: List[str]) -> Tuple[int, str, str]:
        done = subprocess.run(
            [str(cli_path), *args], capture_output=True, text=True, timeout=60
        )
        return done.returncode, done.stdout, done.stderr

    return run


def f32_text(x: float) -> str:
    """The shortest decimal that reads back as the f32 nearest ``x`` (what the CLI
    parses to exactly the f32 that Python rounds ``x`` to)."""
    return np.format_float_positional(np.float32(x), unique=True, trim="-")


def bits(x: float) -> int:
    """The f32 bit pattern of ``x`` (a widened f32, or the JSON decimal of one)."""
    return struct.unpack("<I", struct.pack("<f", x))[0]


def assert_same(ours: Any, theirs: Any, where: str = "") -> None:
    """Same keys, same strings and bools, and numbers with the same f32 bits."""
    if isinstance(theirs, dict):
        assert isinstance(ours, dict), where
        assert ours.keys() == theirs.keys(), f"{where}: {ours.keys()} != {theirs.keys()}"
        for key in theirs:
            assert_same(ours[key], theirs[key], f"{where}.{key}")
    elif isinstance(theirs, list):
        assert len(ours) == len(theirs), where
        for i, (a, b) in enumerate(zip(ours, theirs)):
            assert_same(a, b, f"{where}[{i}]")
    elif isinstance(theirs, bool) or isinstance(theirs, str):
        assert ours == theirs, f"{where}: {ours!r} != {theirs!r}"
    else:
        assert isinstance(theirs, (int, float)), where
        assert bits(ours) == bits(theirs), f"{where}: {ours!r} != {theirs!r} (f32 bits)"


def cli_args(kwargs: Dict[str, Any]) -> List[str]:
    """``cuesight collide`` flags for the keyword arguments of ``cuesight.collide``."""
    args = ["collide", "--json"]
    for key, value in kwargs.items():
        flag = "--" + {"cut_deg": "cut"}.get(key, key).replace("_", "-")
        if key == "roll":
            if value:
                args.append(flag)
        elif key == "model":
            args += [flag, value]
        elif key in ("spin", "tip"):
            args.append(flag + "=" + ",".join(f32_text(v) for v in value))
        else:
            args.append(flag + "=" + f32_text(value))
    return args
