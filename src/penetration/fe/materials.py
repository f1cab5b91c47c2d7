"""Materials of the finite-element level, by registry.

Every material is a frozen dataclass that gives the compiled kernels a kind
code and a parameter array. HJC is ``penetration.hjc.HJC`` itself: its point
update (``hjc.update_voigt``, which ``hjc.update_point`` wraps for arrays)
is the one the kernels call, the same code as the HJC drivers and tests use.

Elastic and von Mises materials use a hypo-elastic deviatoric update (Jaumann
rate) and the pressure p = K ln(V0/V); they serve the verification problems.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import ParameterError
from ..hjc import HJC

ELASTIC, VON_MISES, HJC_KIND = 0, 1, 2
MATERIALS: dict[str, type] = {}


def register(name):
    def wrap(cls):
        MATERIALS[name] = cls
        cls.name = name
        return cls
    return wrap


def _positive(owner, **values):
    for key, v in values.items():
        if not (math.isfinite(v) and v > 0):
            raise ParameterError(owner, key, v, f"{key} > 0 (SI units)")


@register("elastic")
@dataclass(frozen=True)
class Elastic:
    """Linear elastic: density rho0, Young's modulus E, Poisson's ratio nu."""
    rho0: float
    E: float
    nu: float

    def __post_init__(self):
        _positive("elastic", rho0=self.rho0, E=self.E)
        if not -1.0 < self.nu < 0.5:
            raise ParameterError("elastic", "nu", self.nu, "-1 < nu < 0.5")

    @property
    def G(self):
        return self.E / (2 * (1 + self.nu))

    @property
    def K(self):
        return self.E / (3 * (1 - 2 * self.nu))

    kind = ELASTIC

    def as_array(self):
        return np.array([self.rho0, self.G, self.K, math.inf, 0.0])


@register("von_mises")
@dataclass(frozen=True)
class VonMises(Elastic):
    """Elastic-plastic, von Mises yield Y + H eps_p (linear isotropic hardening, H the plastic modulus)."""
    yield_stress: float = 1.0
    hardening: float = 0.0

    def __post_init__(self):
        super().__post_init__()
        _positive("von_mises", yield_stress=self.yield_stress)
        if not self.hardening >= 0:
            raise ParameterError("von_mises", "hardening", self.hardening, "hardening >= 0 (Pa)")

    kind = VON_MISES

    @classmethod
    def bilinear(cls, rho0, E, nu, yield_stress, tangent_modulus):
        """From the tangent modulus Et of a bilinear stress-strain curve: H = E Et/(E - Et)."""
        return cls(rho0, E, nu, yield_stress, E * tangent_modulus / (E - tangent_modulus))

    def as_array(self):
        return np.array([self.rho0, self.G, self.K, self.yield_stress, self.hardening])


def kind_of(material):
    """(kind code, parameter array, reference density) of a material for the kernels."""
    if isinstance(material, HJC):
        return HJC_KIND, material.as_array(), material.rho0
    if type(material) in MATERIALS.values():
        return material.kind, material.as_array(), material.rho0
    raise ParameterError("fe", "material", type(material).__name__, f"one of {sorted(MATERIALS)} or hjc.HJC")


MATERIALS["hjc"] = HJC
