"""What the FE level's verification problems share: the registry of a problem module, the energy check, Richardson's
extrapolation of three meshes, the axial stress of a column."""
from __future__ import annotations

import functools

from ...checks import below as _below
from ...studies.stats import richardson
from .. import state as fe_state


def problems():
    """A problem module's registry and its decorator: ``PROBLEMS, problem = problems()``; ``@problem(label, **kwargs)``
    registers a problem function under ``label`` (with ``kwargs`` bound: one function, several problems)."""
    registry = {}

    def problem(label, **kwargs):
        def wrap(fn):
            registry[label] = functools.partial(fn, **kwargs) if kwargs else fn
            return fn
        return wrap
    return registry, problem


def _energy(name, result, bound):
    return _below(name, "|energy error| at the end (share of the energy put in)", abs(result.audit[-1]["energy_error"]),
                  bound, "1", "conservation (the audit)")


def _order_limit_gci(f, ratio=2.0):
    """Observed order, extrapolated value and the fine grid's relative GCI (Roache; safety 1.25) of three results f
    on meshes refined by ``ratio`` (coarse first)."""
    p, limit, band, _ = richardson(f[0], f[1], f[2], ratio)
    return p, limit, 1.25 * band / abs(f[2])


def _stress(m, e=slice(None)):
    """Axial stress (Pa, tension positive) of elements e: deviator less pressure and viscosity."""
    return m.E[fe_state.SZZ, e] - m.E[fe_state.P, e] - m.E[fe_state.QV, e]
