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


def test_a_read_only_target_or_folder_is_refused_before_anything_is_computed(tmp_path):
    """A read-only file is never replaced, and a read-only folder cannot take the finished file: both refused up front
    (a mode without write bits counts as read-only even for root, who may write anything)."""
    import os

    from penetration.pipeline.io import TargetError, check_target
    kept = tmp_path / "kept.csv"
    kept.write_text("x\n")
    os.chmod(kept, 0o444)
    with pytest.raises(TargetError, match="read-only; allowed: a writable file"):
        check_target(kept)
    folder = tmp_path / "locked"
    folder.mkdir()
    os.chmod(folder, 0o555)
    try:
        for target in (folder / "new.csv", folder / "deeper" / "new.csv"):
            with pytest.raises(TargetError, match="folder .* is read-only"):
                check_target(target)
    finally:
        os.chmod(folder, 0o755)
    check_target(folder / "new.csv")
    check_target(tmp_path / "new" / "deeper.csv")
