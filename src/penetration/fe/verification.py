"""Verification problems of the finite-element level, each against a closed form, a published solution or an
independent reference computation.

Each problem sets up and runs small models and returns Checks (``penetration.checks``): the quantity we
compute, the reference and the interval accepted around it. The problems are registered in ``PROBLEMS`` by
the ``problem`` decorator: ``all_checks`` runs every one (the pipeline's rule ``fe_verification`` writes them to
``figures/fe_verification.csv``), ``tests/test_verification.py`` runs each (and each again with a wrong
reference). SI units throughout (the ``unit`` column names them). The meshes, initial states and drivers are in
``setups``; the independent references live beside this module: closed forms
(``closed_forms``), the 1-D lumped chain (``chain_reference``), the HJC point model written from the equations
(``hjc_reference``) and the 1-D spherical cavity on it (``cavity_reference``); the ideal gas of Noh's problem
runs on the solver's kernels through ``gas``. A row whose reference is met exactly by the discrete algebra says
so in its source ("exact ...") or names round-off as its reference; every other row's quantity differs from
its reference (``tests/test_verification.py`` asserts both).
"""
from __future__ import annotations

import functools
import math

from ..checks import below as _below, run_all
from . import state as fe_state

PROBLEMS: dict = {}


def problem(label, **kwargs):
    """Register a problem function under ``label`` (with ``kwargs`` bound: one function, several problems)."""
    def wrap(fn):
        PROBLEMS[label] = functools.partial(fn, **kwargs) if kwargs else fn
        return fn
    return wrap


def _energy(name, result, bound):
    return _below(name, "|energy error| at the end (share of the energy put in)", abs(result.audit[-1]["energy_error"]),
                  bound, "1", "conservation (the audit)")


def _richardson(f, ratio=2.0):
    """Observed order, extrapolated value and the fine grid's GCI (Roache; safety 1.25) of three results f on
    meshes refined by ``ratio`` (coarse first)."""
    p = math.log(abs((f[0] - f[1]) / (f[1] - f[2]))) / math.log(ratio)
    gain = ratio ** p - 1.0
    return p, f[2] + (f[2] - f[1]) / gain, 1.25 * abs((f[2] - f[1]) / f[2]) / gain


def _stress(m, e=slice(None)):
    """Axial stress (Pa, tension positive) of elements e: deviator less pressure and viscosity."""
    return m.E[fe_state.SZZ, e] - m.E[fe_state.P, e] - m.E[fe_state.QV, e]


def all_checks(log=None):
    """The checks of every registered problem."""
    return run_all(list(PROBLEMS.items()), log)


# the problems register themselves in PROBLEMS, in this order (the order of the verification table's rows)
from . import verification_mechanics, verification_contact, verification_erosion_free  # noqa: E402,F401
