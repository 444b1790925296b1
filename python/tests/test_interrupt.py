"""An interrupted trace stops, raises, and leaves no file, partial or staged: by Ctrl-C
(SIGINT, to this process) or by an exception of the progress callable.

The tracer has no stopping point inside a frame (the rows already handed to its threads are
traced), so a run is stopped within the frame it is tracing: here a list of twelve views,
interrupted in the first, traces no further frame and writes none."""

import signal

import pytest

import irsig
from conftest import MATERIALS, VIEW

FRAMES = 12


def views(folder):
    """Twelve copies of the quickstart camera at 128 x 96, as one RON list of views."""
    one = "".join(l for l in VIEW.read_text().splitlines(keepends=True) if not l.startswith("//"))
    one = one.replace("pixels: (512, 384)", "pixels: (128, 96)").strip()
    path = folder / "views.ron"
    path.write_text("[\n" + ",\n".join([one] * FRAMES) + "\n]\n")
    return path


def no_files(folder):
    return [p.name for p in folder.iterdir() if p.name.startswith(("f.", ".irsig-"))] == []


def interrupted(scene_raw, tmp_path, act):
    calls = []

    def progress(done, total):
        calls.append((done, total))
        if len(calls) == 1:
            act()

    options = dict(band="8-14", atmosphere="us-std-1976", supersample=4)
    return calls, lambda: irsig.trace_frames(
        progress, scene=scene_raw, materials=MATERIALS, view=views(tmp_path),
        output=tmp_path / "f", **options)


def test_ctrl_c_stops_the_trace_and_writes_nothing(scene_raw, tmp_path):
    calls, run = interrupted(scene_raw, tmp_path, lambda: signal.raise_signal(signal.SIGINT))
    # Python's own handler, which turns Ctrl-C into KeyboardInterrupt. A process started in
    # the background by a shell without job control (`cmd &` in a script, nohup) inherits
    # SIGINT ignored, and Python then installs no handler: the signal would be dropped
    # before irsig could see it.
    before = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        with pytest.raises(KeyboardInterrupt):
            run()
    finally:
        signal.signal(signal.SIGINT, before)
    assert calls[-1][0] < calls[-1][1] == FRAMES * 96
    assert no_files(tmp_path)


def test_an_exception_in_the_progress_callable_stops_the_trace(scene_raw, tmp_path):
    class Enough(Exception):
        pass

    def stop():
        raise Enough

    calls, run = interrupted(scene_raw, tmp_path, stop)
    with pytest.raises(Enough):
        run()
    assert len(calls) == 1 and calls[0][0] < calls[0][1] == FRAMES * 96
    assert no_files(tmp_path)
    # The whole run, uninterrupted, writes every frame; and the process traces again.
    frames = irsig.trace_frames(scene=scene_raw, materials=MATERIALS, view=tmp_path / "views.ron",
                                band="8-14", atmosphere="us-std-1976", supersample=4,
                                output=tmp_path / "f")
    assert len(frames) == FRAMES
    assert (tmp_path / f"f.{FRAMES:04}.radiance.exr").read_bytes() == frames[-1].files["radiance.exr"]
