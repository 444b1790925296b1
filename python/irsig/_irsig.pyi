"""Type stubs of the extension module ``irsig._irsig`` (python/src/, Rust).

The package ``irsig`` wraps these; call them through it.
"""

from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple

class IrsigError(Exception):
    """An input irsig refuses, or a run that failed.

    ``args`` is ``(message, file, line, column, usage)``: the message the command line
    prints; the file, line and column (from 1) it points at, or None; and whether the call
    is malformed as written (the command line's exit code 2).
    """

    message: str
    file: Optional[str]
    line: Optional[int]
    column: Optional[int]
    usage: bool

STAGES: List[str]

def trace(
    args: Sequence[str], progress: Optional[Callable[[int, int], Any]] = None
) -> List[Dict[str, Any]]:
    """Traces ``irsig-trace ARGS`` in this process, the GIL released.

    One dict per frame: ``files`` (suffix to bytes), ``decision`` (RON or None), ``band``,
    ``atmosphere``, ``angles_x_deg``, ``angles_y_deg``, ``notes``, ``warnings``.
    ``progress(done_rows, total_rows)`` is called from the calling thread about every 50
    ms; an exception it raises, or ``KeyboardInterrupt``, stops the trace within the frame
    it is tracing, and nothing is written.
    """

def run_stage(stage: str, args: Sequence[str]) -> None:
    """Runs ``irsig-<stage> ARGS`` (``stage`` one of ``STAGES``) in this process."""

def read_exr(
    name: str, data: bytes
) -> Tuple[int, int, List[Tuple[str, str, bytes]], Optional[str], Optional[str]]:
    """An EXR's bytes as ``(width, height, [(layer, unit, float32 samples)], provenance, run)``."""
