"""The README's Python block runs as written: read from README.md (the ```python block whose
first line is `import irsig`), run from a folder that holds the quickstart's inputs where
its paths put them, and leaving the files it names.

Its last lines plot with matplotlib (xarray's `.plot()`), which scripts/test.sh installs
into the test environment; the plot is drawn off screen (MPLBACKEND=Agg).
"""

import re

from conftest import REPO, QUICKSTART


def readme_block(first_line: str) -> str:
    text = (REPO / "README.md").read_text(encoding="utf-8")
    blocks = [
        b for b in re.findall(r"^```python\n(.*?)^```", text, re.S | re.M)
        if b.splitlines()[0] == first_line
    ]
    assert len(blocks) == 1, f"README.md: {len(blocks)} python blocks start with {first_line!r}"
    return blocks[0]


def test_the_readmes_python_block_runs_as_written(tmp_path, monkeypatch):
    block = readme_block("import irsig")
    (tmp_path / "pipelines").mkdir()
    (tmp_path / "pipelines" / "quickstart").symlink_to(QUICKSTART, target_is_directory=True)
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("MPLBACKEND", "Agg")
    exec(compile(block, "README.md (the python block)", "exec"), {"__name__": "readme"})
    for name in ["scene.raw", "radiance.exr", "sensor.exr"]:
        assert (tmp_path / name).stat().st_size > 0, name
