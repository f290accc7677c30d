"""docs/python.md's worked example, run as written (from a folder laid out like the repository
root, with the shared data beside it)."""

import os
import re

import hatchery


def test_the_worked_example_runs(repo, shared, tmp_path, monkeypatch):
    text = (repo / "docs" / "python.md").read_text()
    blocks = re.findall(r"```python\n(.*?)```", text, flags=re.S)
    assert blocks, "docs/python.md has a python example"
    work = tmp_path / "hatchery"
    work.mkdir()
    (work / "graphs").symlink_to(repo / "graphs")
    (tmp_path / "shared").symlink_to(shared.parent)
    monkeypatch.chdir(work)
    namespace = {}
    for block in blocks:
        exec(compile(block, str(repo / "docs" / "python.md"), "exec"), namespace)
    for name in ("brain.png", "iso_sweep.png", "mask.png"):
        assert os.path.getsize(work / name) > 1000, name
    assert isinstance(namespace["picture"], hatchery.Picture)
    assert namespace["picture"].shape == (300, 400, 4)
