"""Keep numba's on-disk caches consistent across modules.

numba invalidates a cached function when its own file changes, not when a
jitted function it calls (and inlines) from another file changes: the FE
kernels inline ``concrete.hjc.update_voigt``, the FE time loop inlines the kernels, the
cavity solver inlines ``concrete.hjc``'s EOS and strength. Before any of these modules
is imported, ``check()`` fingerprints the sources of every module with
compiled kernels and, when the fingerprint differs from the one recorded with
the caches, deletes the package's numba cache files (they are rebuilt on the
next call).

``configure_llvm()`` raises LLVM's limit on the run-time alias checks a loop
may need before it is vectorised (default 8): numba passes every array as a
separate pointer, so the FE element pass (a dozen arrays) would otherwise stay
scalar. It changes which loops vectorise, not the arithmetic of any loop.
"""
from __future__ import annotations

import hashlib
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[1]
KERNEL_SOURCES = ("concrete/hjc.py", "cavity/expansion.py", *(f"fe/{m}.py" for m in ("state", "constitutive", "element", "timestep", "erosion",
                                                           "element_pass", "nodes", "contact", "solver")))
STAMP = "numba_sources.sha256"


def fingerprint() -> str:
    h = hashlib.sha256()
    h.update(" ".join(LLVM_OPTIONS).encode())
    for rel in KERNEL_SOURCES:
        h.update(rel.encode())
        h.update((PACKAGE / rel).read_bytes())
    return h.hexdigest()


LLVM_OPTIONS = ("-runtime-memory-check-threshold=4096", "-vectorize-memory-check-threshold=4096")


def configure_llvm():
    """Set the LLVM options above (before any kernel of the package is compiled)."""
    import llvmlite.binding as llvm

    for option in LLVM_OPTIONS:
        llvm.set_option("penetration", option)


def check():
    """Delete stale numba cache files of the package (returns how many were deleted)."""
    want = fingerprint()
    stamp = PACKAGE / "__pycache__" / STAMP
    try:
        if stamp.read_text() == want:
            return 0
    except OSError:
        pass
    removed = 0
    for folder in sorted(PACKAGE.rglob("__pycache__")):   # every folder: a kernel may inline one of another folder
        for f in list(folder.glob("*.nbi")) + list(folder.glob("*.nbc")):
            try:
                f.unlink()
                removed += 1
            except OSError:
                pass
    try:
        stamp.parent.mkdir(exist_ok=True)
        stamp.write_text(want)
    except OSError:
        pass
    return removed
