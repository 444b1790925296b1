"""An interrupted trace stops, raises, and leaves no file, partial or staged: by Ctrl-C
(SIGINT, to this process) or by an exception of the progress callable."""

import os
import signal
import threading

import pytest

import irsig
from conftest import MATERIALS, small_view

# Long enough that it is still tracing when stopped: 1024 x 768 pixels at 8 x 8 rays each
# (about 50 million rays, minutes in the test build).
HEAVY = dict(band="8-14", atmosphere="us-std-1976", supersample=8)


def no_files(folder):
    return [p.name for p in folder.iterdir() if p.name.startswith(("f.", ".irsig-"))] == []


def test_ctrl_c_stops_the_trace_and_writes_nothing(scene_raw, tmp_path):
    view = small_view(tmp_path, 1024, 768)
    timer = threading.Timer(0.5, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            irsig.trace(scene_raw, MATERIALS, view, output=tmp_path / "f", **HEAVY)
    finally:
        timer.cancel()
    assert no_files(tmp_path)


def test_an_exception_in_the_progress_callable_stops_the_trace(scene_raw, tmp_path):
    view = small_view(tmp_path, 1024, 768)
    calls = []

    class Enough(Exception):
        pass

    def progress(done, total):
        calls.append((done, total))
        raise Enough

    with pytest.raises(Enough):
        irsig.trace(scene_raw, MATERIALS, view, output=tmp_path / "f", progress=progress,
                    **HEAVY)
    assert len(calls) == 1 and calls[0][0] < calls[0][1] == 768
    assert no_files(tmp_path)
    # The process traces again afterwards.
    small = small_view(tmp_path, 16, 12, "small.ron")
    frame = irsig.trace(scene_raw, MATERIALS, small, band="8-14")
    assert frame.radiance.shape == (12, 16)
