"""Type stubs of the extension module; the public API is in hodr/__init__.py."""

from typing import Any, Callable, Optional, Tuple

import numpy as np

def minimize_auto(
    fun: Callable[..., Any],
    x0: list[float],
    sigma0: list[float],
    bounds: Optional[Tuple[list[float], list[float]]],
    budget: Optional[int],
    seed: int,
    batch: bool,
    noisy: bool,
    callback: Optional[Callable[[np.ndarray, float], Any]],
    settings: Tuple[
        Optional[float], Optional[int], Optional[int], Optional[bool], Optional[bool],
        Optional[int], Optional[str], Optional[str],
    ],
) -> dict[str, Any]: ...
def gradient(
    fun: Callable[..., Any], x: list[float], sigma: float, pairs: int, method: str,
    seed: int, batch: bool, noisy: bool,
) -> Tuple[np.ndarray, int]: ...
def hessian(
    fun: Callable[..., Any], x: list[float], sigma: float, pairs: int, method: str,
    seed: int, batch: bool, noisy: bool,
) -> Tuple[np.ndarray, int]: ...
def hvp(
    fun: Callable[..., Any], x: list[float], v: list[float], sigma: float, pairs: int,
    method: str, seed: int, batch: bool, noisy: bool,
) -> Tuple[np.ndarray, int]: ...

class AskTell:
    def __init__(
        self, x0: list[float], sigma0: list[float],
        bounds: Optional[Tuple[list[float], list[float]]],
        budget: Optional[int], seed: int, noisy: bool,
        settings: Tuple[
            Optional[float], Optional[int], Optional[int], Optional[bool], Optional[bool],
            Optional[int], Optional[str], Optional[str],
        ],
    ) -> None: ...
    def ask(self) -> np.ndarray: ...
    def tell(self, values: np.ndarray) -> None: ...
    @property
    def seeds(self) -> np.ndarray: ...
    def stop(self) -> bool: ...
    def result(self) -> dict[str, Any]: ...
