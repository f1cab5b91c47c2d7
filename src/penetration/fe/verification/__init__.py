"""Verification problems of the finite-element level, each against a closed form, a published solution or an
independent reference computation.

Each problem sets up and runs small models and returns Checks (``penetration.checks``): the quantity we
compute, the reference and the interval accepted around it. The problems are registered in ``PROBLEMS``, joined here from
the problem modules (``mechanics``, ``contact``, ``erosion_free``: each registers its own with ``common.problems``'s
decorator, so that none imports this package): ``all_checks`` runs every one (the pipeline's rule ``fe_verification`` writes them to
``figures/fe_verification.csv``), ``tests/test_verification.py`` runs each (and each again with a wrong
reference). SI units throughout (the ``unit`` column names them). The meshes, initial states and drivers are in
``setups``, the helpers the problems share in ``common``; the independent references live beside them: closed forms
(``closed_forms``), the 1-D lumped chain (``chain_reference``), the HJC point model written from the equations
(``hjc_reference``) and the 1-D spherical cavity on it (``cavity_reference``); the ideal gas of Noh's problem
runs on the solver's kernels through ``gas``. A row whose reference is met exactly by the discrete algebra says
so in its source ("exact ...") or names round-off as its reference; every other row's quantity differs from
its reference (``tests/test_verification.py`` asserts both).
"""
from __future__ import annotations

from ...checks import run_all
from . import contact, erosion_free, mechanics

# the order of the verification table's rows
PROBLEMS: dict = {**mechanics.PROBLEMS, **contact.PROBLEMS, **erosion_free.PROBLEMS}


def all_checks(log=None):
    """The checks of every registered problem."""
    return run_all(list(PROBLEMS.items()), log)
