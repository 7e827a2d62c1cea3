"""Type stubs of the native module (PyO3); use the documented wrapper, layertrace.vectorize."""

from typing import Any, Dict, List, Optional

__version__: str

class Error(ValueError):
    """Bad input or options: the message is the layertrace command line's."""

def vectorize(
    kind: str,
    data: Optional[bytes] = None,
    path: Optional[str] = None,
    width: int = 0,
    height: int = 0,
    channels: int = 0,
    *,
    model: str = "conic",
    threshold: Optional[str] = None,
    invert: bool = False,
    turdsize: int = 0,
    cover: str = "greedy",
    fidelity: bool = True,
    picture_scale: Optional[int] = None,
    max_pixels: int = 400_000_000,
    colors: Optional[int] = None,
    layout: str = "stack",
    alpha: bool = False,
    smooth: Optional[float] = None,
) -> Dict[str, Any]: ...

def recognize(
    inliers: List[List[int]],
    above: List[List[int]],
    below: List[List[int]],
    model: str,
) -> str: ...
