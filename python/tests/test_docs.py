"""Every ```python block of docs/python.md runs, in order, in one namespace, in a fresh
folder with the repository's `python/examples` reachable and an empty `out/`."""

import os
import pathlib
import re
import shutil

from conftest import REPO


def blocks(page):
    text = (REPO / page).read_text()
    return re.findall(r"```python\n(.*?)```", text, re.S)


def test_the_python_page_runs_top_to_bottom(tmp_path, capsys):
    code = blocks("docs/python.md")
    assert len(code) >= 8, "docs/python.md lost its examples"
    (tmp_path / "out").mkdir()
    shutil.copytree(REPO / "python" / "examples", tmp_path / "python" / "examples")
    here = os.getcwd()
    os.chdir(tmp_path)
    try:
        scope = {"__name__": "docs"}
        for i, block in enumerate(code):
            try:
                exec(compile(block, f"docs/python.md block {i + 1}", "exec"), scope)
            except Exception as e:  # pragma: no cover - the message names the block
                raise AssertionError(f"docs/python.md block {i + 1} failed: {e!r}\n{block}") from e
    finally:
        os.chdir(here)
    for name in ("storm-py.tif", "storm-py.png", "storm-py.normal.png", "storm-py.exr", "storm-py.toml"):
        assert (tmp_path / "out" / name).is_file(), name
    assert len(list((tmp_path / "out" / "storm-seq").glob("frame_*.disp.exr"))) == 24
