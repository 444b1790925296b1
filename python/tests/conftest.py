"""Shared inputs of the Python package's tests: the quickstart's scene flattened once, a
small copy of its camera, and the command-line tools the same runs are compared with.

The tools come from IRSIG_BIN (scripts/test.sh builds irsig-flatten and irsig-trace and
sets it); without it the tests that need them fail and say so: nothing is skipped.
"""

import os
import re
import subprocess
from pathlib import Path

import pytest

import irsig

REPO = Path(__file__).resolve().parents[2]
QUICKSTART = REPO / "pipelines" / "quickstart"
MATERIALS = QUICKSTART / "materials.ron"
VIEW = QUICKSTART / "view.ron"


def tool(name: str) -> Path:
    """The command-line tool `irsig-NAME` of IRSIG_BIN."""
    folder = os.environ.get("IRSIG_BIN")
    if not folder:
        pytest.fail(
            "IRSIG_BIN is not set: run the tests through scripts/test.sh, which builds "
            "irsig-flatten and irsig-trace and names their folder"
        )
    path = Path(folder) / f"irsig-{name}"
    if not path.is_file():
        pytest.fail(f"{path} does not exist: build it with `cargo build -p irsig-{name}`")
    return path


def run_tool(name: str, *args) -> subprocess.CompletedProcess:
    return subprocess.run(
        [str(tool(name)), *map(str, args)], capture_output=True, text=True, check=False
    )


@pytest.fixture(scope="session")
def scene_raw(tmp_path_factory) -> Path:
    """The quickstart scene, flattened through Python."""
    out = tmp_path_factory.mktemp("scene") / "scene.raw"
    irsig.flatten(QUICKSTART / "scene.ron", materials=MATERIALS, output=out)
    return out


def small_view(folder: Path, columns: int, rows: int, name: str = "view.ron") -> Path:
    """The quickstart's camera with fewer pixels (the same fields of view)."""
    text = VIEW.read_text()
    text, n = re.subn(r"pixels: \(512, 384\)", f"pixels: ({columns}, {rows})", text)
    assert n == 1, "the quickstart view's pixels moved: update small_view"
    path = folder / name
    path.write_text(text)
    return path


@pytest.fixture()
def view_64(tmp_path) -> Path:
    return small_view(tmp_path, 64, 48)
