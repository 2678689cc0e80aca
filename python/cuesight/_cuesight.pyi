"""Type stubs of the Rust extension ``cuesight._cuesight`` (python/src/lib.rs). Use the
typed wrappers of ``cuesight`` instead; tests/test_api.py holds these stubs to the
module's real signatures."""

from typing import Any, Dict, Optional, Sequence, Tuple

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
def _defaults() -> Dict[str, Any]: ...
