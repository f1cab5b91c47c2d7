"""Atomic writes: ordinary permissions, nothing half-written, an old output kept when a write fails."""
import os
import stat

import pandas as pd
import pytest

from penetration.pipeline.io import atomic, write_csv, write_text


@pytest.mark.parametrize("umask", [0o022, 0o077])
def test_new_files_respect_the_umask(tmp_path, umask):
    old = os.umask(umask)
    try:
        write_csv(pd.DataFrame({"x": [1.0]}), tmp_path / "a.csv")
    finally:
        os.umask(old)
    assert stat.S_IMODE((tmp_path / "a.csv").stat().st_mode) == 0o666 & ~umask


def test_failed_write_keeps_the_old_file_and_leaves_no_temporary(tmp_path):
    target = tmp_path / "out.txt"
    write_text(target, "old\n")
    with pytest.raises(RuntimeError):
        with atomic(target) as tmp:
            tmp.write_text("half")
            raise RuntimeError("interrupted")
    assert target.read_text() == "old\n"
    assert [p.name for p in tmp_path.iterdir()] == ["out.txt"]
