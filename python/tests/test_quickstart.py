"""The quickstart through Python gives the command line's bytes: the flattened scene, and
the trace's radiance, truth and interaction map (the first two stages of
pipelines/quickstart.ron, with its parameters)."""

import numpy as np

import irsig
from conftest import MATERIALS, QUICKSTART, VIEW, run_tool

TRACE = ["--band", "8-14", "--atmosphere", "us-std-1976", "--atmosphere-model", "table"]


def test_flatten_writes_the_command_lines_raw_scene(scene_raw, tmp_path):
    cli = tmp_path / "cli.raw"
    done = run_tool("flatten", QUICKSTART / "scene.ron", "--materials", MATERIALS, "-o", cli)
    assert done.returncode == 0, done.stderr
    assert scene_raw.read_bytes() == cli.read_bytes()


def test_the_quickstart_trace_writes_the_command_lines_bytes(scene_raw, tmp_path):
    py, cli = tmp_path / "py", tmp_path / "cli"
    py.mkdir()
    cli.mkdir()
    seen = []
    frame = irsig.trace(
        scene_raw,
        MATERIALS,
        VIEW,
        band="8-14",
        atmosphere="us-std-1976",
        atmosphere_model="table",
        radiance_exr=py / "radiance.exr",
        truth_exr=py / "truth.exr",
        map_png=py / "map.png",
        progress=lambda done, total: seen.append((done, total)),
    )
    done = run_tool(
        "trace", "--scene", scene_raw, "--materials", MATERIALS, "--view", VIEW, *TRACE,
        "--radiance-exr", cli / "radiance.exr", "--truth-exr", cli / "truth.exr",
        "--map-png", cli / "map.png",
    )
    assert done.returncode == 0, done.stderr
    for name in ["radiance.exr", "truth.exr", "map.png"]:
        assert (py / name).read_bytes() == (cli / name).read_bytes(), name
        assert frame.files[name] == (cli / name).read_bytes(), name
    # The array is the command line's file, sample for sample.
    from_cli = irsig.read_exr(cli / "radiance.exr").radiance.values
    assert from_cli.shape == (384, 512)
    assert np.array_equal(frame.radiance, from_cli)
    # Progress ends at every row of the 384.
    assert seen[-1] == (384, 384)
    assert all(a[0] <= b[0] for a, b in zip(seen, seen[1:]))
