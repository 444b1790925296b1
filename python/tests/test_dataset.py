"""A trace as an xarray.Dataset: the radiance and every truth layer the truth EXR holds, x
and y in pixels with the pixels' angles, and the band, units, decision and provenance."""

import math

import numpy as np

import irsig
from conftest import MATERIALS


def test_the_dataset_holds_every_layer_with_coordinates_and_attributes(scene_raw, view_64):
    frame = irsig.trace(scene_raw, MATERIALS, view_64, band="8-14", atmosphere="us-std-1976")
    ds = frame.dataset()
    truth = irsig.read_exr(frame.files["truth.exr"])
    assert set(ds.data_vars) == {"radiance"} | set(truth.data_vars)
    # The truth layers formats/images.md lists, among them.
    for layer in ["apparent_temperature", "material_primary", "range", "emissivity"]:
        assert layer in ds.data_vars, layer
    assert ds.radiance.dims == ("y", "x") and ds.radiance.shape == (48, 64)
    assert ds.radiance.dtype == np.float32
    assert ds.radiance.attrs["units"] == "W m^-2 sr^-1"
    assert ds.apparent_temperature.attrs["units"] == "K"
    assert list(ds.x.values) == list(range(64)) and list(ds.y.values) == list(range(48))
    assert ds.attrs["band"] == "8-14" and ds.attrs["atmosphere"] == "us-std-1976"
    assert ds.attrs["radiance_units"] == "W m^-2 sr^-1"
    assert ds.attrs["decision"] == ""
    assert ds.attrs["provenance"].startswith("irsig provenance")
    assert ds.attrs["run"].startswith("sha256:")
    # A blackbody-like scene between a cold sky and a 325 K panel: every apparent
    # temperature is a temperature the scene can show.
    assert 150.0 < float(ds.apparent_temperature.min()) < float(ds.apparent_temperature.max()) < 330.0


def test_the_pixel_angles_are_the_pinhole_cameras(scene_raw, view_64):
    # A pinhole camera of full fields of view 47 x 36 deg over 64 x 48 pixels: the centre
    # of column c is atan((2 (c + 1/2) / 64 - 1) tan 23.5 deg) from the axis (by hand).
    frame = irsig.trace(scene_raw, MATERIALS, view_64, band="8-14")
    ds = frame.dataset()
    for c in [0, 31, 32, 63]:
        u = (2 * (c + 0.5) / 64 - 1) * math.tan(math.radians(23.5))
        assert math.isclose(ds.angle_x_deg.values[c], math.degrees(math.atan(u)), abs_tol=1e-9)
    for r in [0, 47]:
        v = (1 - 2 * (r + 0.5) / 48) * math.tan(math.radians(18.0))
        assert math.isclose(ds.angle_y_deg.values[r], math.degrees(math.atan(v)), abs_tol=1e-9)


def test_a_tolerance_puts_its_decision_in_the_attributes(scene_raw, tmp_path):
    from conftest import small_view

    view = small_view(tmp_path, 32, 24)
    frame = irsig.trace(scene_raw, MATERIALS, view, band="8-14", atmosphere="us-std-1976",
                        tolerance=0.5, output=tmp_path / "f")
    ds = frame.dataset()
    assert ds.attrs["decision"] == frame.decision != ""
    # Written beside the outputs, as the command line writes it.
    assert (tmp_path / "f.decision.ron").read_text() == frame.decision
