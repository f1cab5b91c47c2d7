"""Triaxial strength criteria of concrete with an fc dependence: the material data the HJC scaling rule is set against.

Each gives the normalised equivalent stress q* = (sigma_1 - sigma_3)/fc on the compressive meridian
(sigma_2 = sigma_3, compression positive) at the normalised pressure p* = (sigma_1 + 2 sigma_3)/(3 fc):

- ``ottosen_mc90``: Ottosen's four-parameter criterion as CEB-FIP MC90 and EN 1992-2 Annex LL (Eq LL.101)
  calibrate it, k = fctm/fcm, alpha = 1/(9 k^1.4), beta = 1/(3.7 k^1.1), lambda = c1 cos(pi/3 - acos(c2)/3)
  on the compressive meridian with c1 = 1/(0.7 k^0.9), c2 = 1 - 6.8 (k - 0.07)^2; fctm of the fib Model Code
  2010 (``concrete.tensile_strength_mc2010``);
- ``attard_setunge``: Attard & Setunge (1996, ACI Mater. J. 93(5) 432-442), sigma_1 = fc (sigma_3/ft + 1)^k,
  k = 1.25 (1 + 0.062 sigma_3/fc) fc^-0.21, ft = 0.9 * 0.32 fc^0.67 (MPa); their tests confined to at most
  about 20 MPa (``ATTARD_SETUNGE_MAX_CONFINEMENT``), beyond which it is an extrapolation;
- ``hjc``: the HJC surface itself, q* = A + B p*^N capped at SFMAX (undamaged, quasi-static).
"""
from __future__ import annotations

import math

from scipy.optimize import brentq

from ..units import MPA
from .material import tensile_strength_mc2010

ATTARD_SETUNGE_MAX_CONFINEMENT = 20e6   # Pa: the largest confinement of the tests behind the fit


def ottosen_mc90(p_star, fc):
    """q* of the Ottosen criterion (MC90 / EN 1992-2 Annex LL) on the compressive meridian at p* (fc in Pa)."""
    k = tensile_strength_mc2010(fc) / fc
    alpha, beta = 1.0 / (9.0 * k ** 1.4), 1.0 / (3.7 * k ** 1.1)
    c1, c2 = 1.0 / (0.7 * k ** 0.9), 1.0 - 6.8 * (k - 0.07) ** 2
    lam = c1 * math.cos(math.pi / 3.0 - math.acos(c2) / 3.0)
    # alpha J2/fc^2 + lam sqrt(J2)/fc + beta I1/fc - 1 = 0 with J2 = q^2/3, I1 = -3 p (tension positive)
    a, b, c = alpha / 3.0, lam / math.sqrt(3.0), -(1.0 + 3.0 * beta * p_star)
    return (-b + math.sqrt(b * b - 4.0 * a * c)) / (2.0 * a)


def attard_setunge_sigma1(sigma3, fc):
    """sigma_1 (Pa) at confinement sigma3 (Pa) of Attard & Setunge (1996), no silica fume."""
    f, s3 = fc / MPA, sigma3 / MPA
    ft = 0.9 * 0.32 * f ** 0.67
    k = 1.25 * (1.0 + 0.062 * s3 / f) * f ** -0.21
    return MPA * f * (s3 / ft + 1.0) ** k


def attard_setunge(p_star, fc):
    """(q*, confinement in Pa) of Attard & Setunge on the compressive meridian at p* >= 1/3 (fc in Pa)."""
    if p_star < 1.0 / 3.0:
        raise ValueError(f"p* = {p_star} below uniaxial compression (1/3): the criterion is for confined compression")

    def miss(s3):
        return (attard_setunge_sigma1(s3, fc) + 2.0 * s3) / 3.0 - p_star * fc

    hi = p_star * fc
    s3 = 0.0 if miss(0.0) >= 0 else brentq(miss, 0.0, hi, xtol=1e-6)
    return (attard_setunge_sigma1(s3, fc) - s3) / fc, s3


def hjc(p_star, A, B, N, smax):
    """q* of the undamaged, quasi-static HJC surface."""
    return min(A + B * p_star ** N, smax)
