"""Type stubs of the Rust extension ``cuesight._cuesight`` (python/src/). Use the
typed wrappers of ``cuesight`` instead; tests/test_api.py holds these stubs to the
module's real signatures."""

from typing import Any, Dict, List, Optional, Sequence, Tuple

import numpy as np
import numpy.typing as npt

__version__: str
MODELS: Tuple[str, ...]
REGIMES: Tuple[str, ...]

def _collide(
    speed: float,
    cut_deg: float,
    spin: Optional[Sequence[float]],
    roll: bool,
    tip: Optional[Sequence[float]],
    mu: Optional[float],
    mu_b: Optional[float],
    mu_c: Optional[float],
    restitution: Optional[float],
    mu_s: Optional[float],
    radius: Optional[float],
    mass: Optional[float],
    model: str,
    tolerance: Optional[float],
) -> Dict[str, Any]: ...
def _collide_many(
    n: int,
    speed: npt.NDArray[np.float32],
    cut_deg: npt.NDArray[np.float32],
    spin: Optional[npt.NDArray[np.float32]],
    roll: npt.NDArray[np.bool_],
    tip: Optional[npt.NDArray[np.float32]],
    mu: Optional[npt.NDArray[np.float32]],
    mu_b: Optional[npt.NDArray[np.float32]],
    mu_c: Optional[npt.NDArray[np.float32]],
    restitution: Optional[npt.NDArray[np.float32]],
    mu_s: Optional[npt.NDArray[np.float32]],
    radius: Optional[npt.NDArray[np.float32]],
    mass: Optional[npt.NDArray[np.float32]],
    model: str,
    tolerance: Optional[float],
    raise_errors: bool,
) -> Dict[str, npt.NDArray[Any]]: ...
def _shot(
    scene_file: Optional[str],
    scene_json: Optional[str],
    params: Optional[str],
    table: Optional[str],
    cue: Optional[Sequence[float]],
    balls: Optional[Sequence[Sequence[float]]],
    object: Optional[int],
    pocket: Optional[str],
    speed: Optional[float],
    tip: Optional[Sequence[float]],
    aim: Optional[float],
    solve: bool,
    model: Optional[str],
    tolerance: Optional[float],
    mu: Optional[float],
    restitution: Optional[float],
    mu_s: Optional[float],
    mu_cloth: Optional[float],
    mu_roll: Optional[float],
    radius: Optional[float],
    mass: Optional[float],
    cue_mass: Optional[float],
    tip_restitution: Optional[float],
    svg: Optional[str],
) -> str: ...
def _calibrate(
    throw_file: Optional[str],
    throw_points: Optional[List[str]],
    fit: str,
    model: str,
    restitution: float,
    mu_s: float,
    default_uncertainty: float,
    cross_validate: bool,
    max_evaluations: int,
) -> str: ...
def _defaults() -> Dict[str, Any]: ...
