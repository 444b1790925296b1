"""The frame's error paths the command line tests for raise irsig.IrsigError, naming the
file, line and column where the input is at fault, and write nothing."""

import pytest

import irsig
from conftest import MATERIALS, QUICKSTART, run_tool


def test_a_missing_file_names_it(scene_raw, view_64, tmp_path):
    missing = tmp_path / "no-such-materials.ron"
    with pytest.raises(irsig.IrsigError) as e:
        irsig.trace(scene_raw, missing, view_64, output=tmp_path / "f")
    assert "no-such-materials.ron" in e.value.message
    assert not list(tmp_path.glob("f.*"))


def test_a_bad_view_names_its_line_and_column(scene_raw, tmp_path):
    bad = tmp_path / "bad-view.ron"
    # Line 3: `pixels` is misspelt.
    bad.write_text(
        "LookAt(\n  position_m: (0.0, -22.7, 5.0), target_m: (1.5, 0.0, 1.0),\n"
        "  pixls: (64, 48),\n  fov_deg: (47.0, 36.0),\n)\n"
    )
    with pytest.raises(irsig.IrsigError) as e:
        irsig.trace(scene_raw, MATERIALS, bad, output=tmp_path / "f")
    assert e.value.file.endswith("bad-view.ron")
    assert e.value.line == 3 and e.value.column >= 3
    cli = run_tool("trace", "--scene", scene_raw, "--materials", MATERIALS, "--view", bad,
                   "-o", tmp_path / "g")
    assert cli.returncode == 1
    assert f"bad-view.ron:{e.value.line}:{e.value.column}:" in cli.stderr
    assert not list(tmp_path.glob("f.*")) and not list(tmp_path.glob("g.*"))


def test_a_malformed_materials_file_names_its_place(scene_raw, view_64, tmp_path):
    bad = tmp_path / "bad.ron"
    bad.write_text('(materials: [(id: 1 name: "x")])')
    with pytest.raises(irsig.IrsigError) as e:
        irsig.trace(scene_raw, bad, view_64, output=tmp_path / "f")
    assert e.value.file.endswith("bad.ron") and e.value.line == 1
    assert not list(tmp_path.glob("f.*"))


def test_a_band_outside_a_materials_table_names_the_material(scene_raw, view_64, tmp_path):
    # The quickstart's emissivity tables are 8-14 um ones: 3-5 um is refused, not
    # extrapolated.
    with pytest.raises(irsig.IrsigError) as e:
        irsig.trace(scene_raw, MATERIALS, view_64, band="3-5", atmosphere="us-std-1976",
                    output=tmp_path / "f")
    cli = run_tool("trace", "--scene", scene_raw, "--materials", MATERIALS, "--view",
                   view_64, "--band", "3-5", "--atmosphere", "us-std-1976", "-o",
                   tmp_path / "g")
    assert cli.returncode == 1
    assert e.value.file is not None and e.value.file.endswith("materials.ron")
    assert f"materials.ron:{e.value.line}:{e.value.column}:" in cli.stderr
    assert not list(tmp_path.glob("f.*"))


def test_a_malformed_call_is_a_usage_error():
    with pytest.raises(irsig.IrsigError) as e:
        irsig.trace_frames(scene="s.raw", materials="m.ron", view="v.ron", bounces="many")
    assert e.value.usage
    assert "--bounces" in e.value.message


def test_a_stage_refuses_as_its_command_line_does(tmp_path):
    with pytest.raises(irsig.IrsigError) as e:
        irsig.flatten(QUICKSTART / "no-such-scene.ron", output=tmp_path / "s.raw")
    assert "no-such-scene.ron" in e.value.message
    assert not (tmp_path / "s.raw").exists()
