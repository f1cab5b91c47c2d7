"""Replication of Liu, Pi & Huang (2015), penetration of double-ogive noses.

Stages import one way: geometry -> nstar -> resistance -> (dop | trajectory |
hjc -> cavity) -> reference -> figures. Physics modules do no file I/O; the
``tasks`` package (one module per stage) and ``io`` read and write files.
"""
__version__ = "0.1.0"

from .pipeline import numba_cache as _numba_cache  # noqa: E402

_numba_cache.configure_llvm()
_numba_cache.check()  # before any module with compiled kernels is imported
