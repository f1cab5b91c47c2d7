"""Finite-element level: 2-D axisymmetric explicit Lagrangian solver with HJC, erosion and a rigid nose.

The names below are loaded on first use, so that importing a light module of the package (``spec``, ``state``)
does not compile or import the solver.
"""
import importlib

_NAMES = {"MATERIALS": "constitutive", "Elastic": "constitutive", "VonMises": "constitutive", "Grid": "mesh",
          "MeshSpec": "mesh", "body_outline": "mesh", "build": "mesh", "graded": "mesh", "Projectile": "contact",
          "Controls": "spec", "Model": "model", "Result": "solver", "Unstable": "solver", "run": "solver"}


def __getattr__(name):
    if name in _NAMES:
        return getattr(importlib.import_module(f".{_NAMES[name]}", __name__), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
