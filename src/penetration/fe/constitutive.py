"""How a material behaves in the FE level: its parameters, stress update, wave speed and impedance, by kind.

Every material is a frozen dataclass; ``KINDS`` gives each class its kind code and the compiled kernels dispatch
on that code (``update``, ``longitudinal_modulus``). HJC is ``penetration.concrete.hjc.HJC`` itself: its point update
(``hjc.update_voigt``, which ``hjc.update_point`` wraps for arrays, and its branch-free shortcut
``hjc.quick_update``) is the one the element pass calls, the same code as the HJC drivers and tests use.

Elastic and von Mises materials use a hypo-elastic deviatoric update (Jaumann rate, the predictor
``hjc.deviatoric_trial`` that HJC uses too) and the pressure p = K ln(V0/V); they serve the verification
problems. Parameter arrays: ``Q_RHO``, ``Q_G``, ``Q_K``, ``Q_YIELD``, ``Q_HARDENING`` for them, the ``hjc.I_*``
slots for HJC (both start with the density).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from ..concrete.hjc import HJC, deviatoric_trial, longitudinal_modulus as hjc_modulus, update_voigt
from ..errors import ParameterError
from .state import DMG, EPSP, MUMAX, MUP, SRR, SRZ, STT, SZZ, Material, P

ELASTIC, VON_MISES, HJC_KIND = 0, 1, 2
Q_RHO, Q_G, Q_K, Q_YIELD, Q_HARDENING = range(5)


def _positive(owner, **values):
    for key, v in values.items():
        if not (math.isfinite(v) and v > 0):
            raise ParameterError(owner, key, v, f"{key} > 0 (SI units)")


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

    def as_array(self):
        return np.array([self.rho0, self.G, self.K, math.inf, 0.0])


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

    @classmethod
    def bilinear(cls, rho0, E, nu, yield_stress, tangent_modulus):
        """From the tangent modulus Et of a bilinear stress-strain curve: H = E Et/(E - Et)."""
        return cls(rho0, E, nu, yield_stress, E * tangent_modulus / (E - tangent_modulus))

    def as_array(self):
        return np.array([self.rho0, self.G, self.K, self.yield_stress, self.hardening])


# class -> (kind code, elastic moduli (K, G) of its impedance: HJC's elastic bulk modulus Ke)
KINDS = {Elastic: (ELASTIC, lambda m: (m.K, m.G)), VonMises: (VON_MISES, lambda m: (m.K, m.G)),
         HJC: (HJC_KIND, lambda m: (m.Ke, m.G))}
MATERIALS = {"elastic": Elastic, "von_mises": VonMises, "hjc": HJC}


def _kind(material):
    try:
        return KINDS[type(material)]
    except KeyError:
        raise ParameterError("fe", "material", type(material).__name__, f"one of {sorted(MATERIALS)}") from None


def material_of(material) -> Material:
    """The kernels' view of a material: its kind code and parameter array."""
    return Material(_kind(material)[0], material.as_array())


def impedances(material):
    """Longitudinal and shear impedances rho0 c_p, rho0 c_s (kg/m^2/s) of the undisturbed material (the
    non-reflecting boundary's dashpots)."""
    Kb, G = _kind(material)[1](material)
    rho0 = material.rho0
    return rho0 * math.sqrt((Kb + 4 * G / 3) / rho0), rho0 * math.sqrt(G / rho0)


# ------------------------------------------------------------------ compiled
@njit(cache=True, inline="always", error_model="numpy")
def wave_speed(modulus, rho):
    """Longitudinal wave speed from the modulus K + 4G/3 and the density."""
    return math.sqrt(modulus / rho)


@njit(cache=True, inline="always", error_model="numpy")
def longitudinal_modulus(kind, q, mu, mumax):
    """K + 4G/3 (loading or unloading, whichever is stiffer) of a material point at volumetric strain mu."""
    if kind == HJC_KIND:
        return hjc_modulus(mu, mumax, q)
    return q[Q_K] + 4.0 * q[Q_G] / 3.0


@njit(cache=True, inline="always", error_model="numpy")
def _elastic_plastic(kind, q, E, e, de, mu_ratio):
    """Elastic / von Mises update of element e's deviatoric stress and pressure p = K ln(V0/V); returns d eps_p."""
    G, K = q[Q_G], q[Q_K]
    de0, de1, de2, de3 = de
    E[SRR, e], E[SZZ, e], E[STT, e], E[SRZ, e] = deviatoric_trial(E[SRR, e], E[SZZ, e], E[STT, e], E[SRZ, e],
                                                                  de0, de1, de2, de3, G)
    E[P, e] = K * math.log(mu_ratio)
    if kind == ELASTIC:
        return 0.0
    s0, s1, s2, s3 = E[SRR, e], E[SZZ, e], E[STT, e], E[SRZ, e]
    seq = math.sqrt(1.5 * (s0 * s0 + s1 * s1 + s2 * s2) + 3.0 * s3 * s3)
    sy = q[Q_YIELD] + q[Q_HARDENING] * E[EPSP, e]
    if seq <= sy:
        return 0.0
    dep = (seq - sy) / (3.0 * G + q[Q_HARDENING])
    scale = (sy + q[Q_HARDENING] * dep) / seq
    E[SRR, e] = s0 * scale
    E[SZZ, e] = s1 * scale
    E[STT, e] = s2 * scale
    E[SRZ, e] = s3 * scale
    return dep


@njit(cache=True, inline="always", error_model="numpy")
def update(kind, q, E, e, de, mu_ratio, rate):
    """The full stress update of element e (its deviator in E already rotated) for the strain increment
    de = (rr, zz, tt, rz) at volume ratio V0/V and equivalent strain rate ``rate``; stores stress, pressure and
    the state variables in E, returns the plastic strain increment."""
    if kind == HJC_KIND:
        de0, de1, de2, de3 = de
        n0, n1, n2, n3, _, _, pn, mumax, mup, dmg, dep = update_voigt(
            E[SRR, e], E[SZZ, e], E[STT, e], E[SRZ, e], 0.0, 0.0, mu_ratio - 1.0, E[MUMAX, e],
            E[MUP, e], E[DMG, e], E[EPSP, e], de0, de1, de2, de3, 0.0, 0.0, rate, q)
        E[SRR, e], E[SZZ, e], E[STT, e], E[SRZ, e] = n0, n1, n2, n3
        E[P, e], E[MUMAX, e], E[MUP, e], E[DMG, e] = pn, mumax, mup, dmg
        return dep
    return _elastic_plastic(kind, q, E, e, de, mu_ratio)
