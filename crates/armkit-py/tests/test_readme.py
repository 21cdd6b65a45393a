"""Every Python block of the README runs and its assertions hold (as the
Rust example runs as a doctest and the CLI suite's `readme` module runs every
`armkit ...` command), in a scratch working folder."""

import re

import pytest

from conftest import REPO

BLOCKS = re.findall(r"^```python\n(.*?)^```", (REPO / "README.md").read_text(), re.S | re.M)


def test_the_readme_has_python_blocks():
    assert BLOCKS, "no ```python block found in README.md"


@pytest.mark.parametrize("index", range(len(BLOCKS)))
def test_readme_python_block_runs(index, tmp_path, monkeypatch):
    # Blocks of the optional extras run where they are installed (scripts/test-all.sh installs them).
    if "dask" in BLOCKS[index]:
        pytest.importorskip("distributed", reason="dask.distributed is not installed (the dask extra)")
    monkeypatch.chdir(tmp_path)
    exec(compile(BLOCKS[index], f"README.md, python block {index + 1}", "exec"), {})


def test_the_first_python_example_is_short():
    assert len(BLOCKS[0].strip().splitlines()) <= 10
