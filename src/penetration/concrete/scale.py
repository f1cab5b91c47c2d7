"""Published relations for concrete's dependence on strain rate and on size.

Every constant here is a published one; nothing is fitted on a penetration shot.

- Strain rate: the dynamic increase factor (DIF) of the compressive and tensile strengths, fib Model Code 2010
  and CEB-FIP Model Code 1990 (the relations of CEB Bulletin 187, 1988, as restated by Malvar & Crawford 1998).
  Both codes state them up to 300 1/s; a penetration loads the concrete at 1e3-1e5 1/s, so a caller names what
  happens beyond (``beyond``): ``cap`` holds the value at 300 1/s,
  ``extrapolate`` continues the code's cube-root branch. Both codes say that the steep branch holds lateral
  inertia of the test specimen as well as the material's rate dependence: a level that resolves inertia itself
  counts part of it twice, which the studies show by running both conventions.
- Fracture: the mean tensile strength, fracture energy and tangent modulus of fib Model Code 2010 (Eqs 5.1-3a/b,
  5.1-9, 5.1-21), Hillerborg's characteristic length (Hillerborg, Modeer & Petersson 1976) and Bazant's size-effect
  law for geometrically similar structures failing after stable crack growth (Bazant 1984, type 2).

Strengths in Pa, rates in 1/s, lengths in m, energies in N/m (J/m^2). The codes write their relations with the
strengths in MPa; the conversion is done here, once.
"""
from __future__ import annotations

import numpy as np
from numba import njit

from ..errors import ParameterError
from ..units import GPA, MPA

RATE_LIMIT = 300.0          # 1/s, the top of both codes' stated range
BEYOND = ("cap", "extrapolate")
DELTA_F = 8.0 * MPA         # fcm - fck, MC2010 Eq 5.1-1 (and MC90)
FCM0 = 10.0 * MPA           # the codes' reference strength


def _rates(rate, beyond, owner):
    if beyond not in BEYOND:
        raise ParameterError(owner, "beyond", beyond, f"one of {BEYOND} (what the relation does above "
                                                      f"{RATE_LIMIT:g} 1/s, the top of the code's range)")
    r = np.asarray(rate, float)
    if not np.all(np.isfinite(r) & (r >= 0)):
        raise ParameterError(owner, "rate", rate, "finite strain rates >= 0 (1/s)")
    return np.minimum(r, RATE_LIMIT) if beyond == "cap" else r


def _positive(value, owner, name, unit):
    v = np.asarray(value, float)
    if not np.all(np.isfinite(v) & (v > 0)):
        raise ParameterError(owner, name, value, f"finite values > 0 ({unit})")
    return v


@njit(cache=True, inline="always")
def two_branch(r, r0, knee, low_exponent, high_coefficient):
    """(r/r0)^low_exponent up to the knee, high_coefficient (r/r0)^(1/3) above; held at 1 below r0 (slower than
    the codes' quasi-static reference, which no penetration is). One point: the material kernels call it."""
    x = max(r / r0, 1.0)
    return x ** low_exponent if r <= knee else high_coefficient * x ** (1.0 / 3.0)


@njit(cache=True)
def _two_branch_many(r, r0, knee, low_exponent, high_coefficient):
    out = np.empty(r.size)
    for i in range(r.size):
        out[i] = two_branch(r[i], r0, knee, low_exponent[i], high_coefficient[i])
    return out


def _two_branch(r, r0, knee, low_exponent, high_coefficient):
    """two_branch over arrays (the coefficients may vary with the strength: broadcast with the rates)."""
    r, lo, hi = np.broadcast_arrays(np.asarray(r, float), np.asarray(low_exponent, float),
                                    np.asarray(high_coefficient, float))
    out = _two_branch_many(r.ravel().copy(), r0, knee, lo.ravel().copy(), hi.ravel().copy()).reshape(r.shape)
    return out if r.ndim else float(out)


# fib MC2010's compressive and tensile factors: reference rate, knee, low exponent, high coefficient
MC2010_COMPRESSION = (30e-6, 30.0, 0.014, 0.012)
MC2010_TENSION = (1e-6, 10.0, 0.018, 0.0062)


@njit(cache=True, inline="always")
def dif_compression_mc2010_point(rate, extrapolate):
    """dif_compression_mc2010 at one rate, for the material kernels (``extrapolate``: beyond 300 1/s; else cap)."""
    c = MC2010_COMPRESSION
    return two_branch(rate if extrapolate else min(rate, RATE_LIMIT), c[0], c[1], c[2], c[3])


def dif_compression_mc2010(rate, beyond="cap"):
    """f_c,imp / f_cm: (rate/30e-6)^0.014 up to 30 1/s, 0.012 (rate/30e-6)^(1/3) above (fib MC2010, strain-rate
    effects in compression)."""
    return _two_branch(_rates(rate, beyond, "dif_compression_mc2010"), *MC2010_COMPRESSION)


def dif_tension_mc2010(rate, beyond="cap"):
    """f_ct,imp / f_ctm: (rate/1e-6)^0.018 up to 10 1/s, 0.0062 (rate/1e-6)^(1/3) above (fib MC2010,
    strain-rate effects in tension)."""
    return _two_branch(_rates(rate, beyond, "dif_tension_mc2010"), *MC2010_TENSION)


def dif_compression_ceb1990(rate, fcm, beyond="cap"):
    """f_c,imp / f_cm of CEB-FIP MC90: (rate/30e-6)^(1.026 alpha_s) up to 30 1/s, gamma_s (rate/30e-6)^(1/3) above,
    alpha_s = 1 / (5 + 9 fcm/fcm0), log10 gamma_s = 6.156 alpha_s - 2, fcm0 = 10 MPa (the constants make the two
    branches meet at 30 1/s)."""
    a = 1.0 / (5.0 + 9.0 * _positive(fcm, "dif_compression_ceb1990", "fcm", "Pa") / FCM0)
    return _two_branch(_rates(rate, beyond, "dif_compression_ceb1990"), 30e-6, 30.0, 1.026 * a,
                       10.0 ** (6.156 * a - 2.0))


def dif_tension_ceb1990(rate, fcm, beyond="cap"):
    """f_ct,imp / f_ctm of CEB-FIP MC90: (rate/3e-6)^(1.016 delta_s) up to 30 1/s, beta_s (rate/3e-6)^(1/3) above,
    delta_s = 1 / (10 + 6 fcm/fcm0), log10 beta_s = 7.11 delta_s - 2.33 (the branches meet to within 1 %)."""
    d = 1.0 / (10.0 + 6.0 * _positive(fcm, "dif_tension_ceb1990", "fcm", "Pa") / FCM0)
    return _two_branch(_rates(rate, beyond, "dif_tension_ceb1990"), 3e-6, 30.0, 1.016 * d,
                       10.0 ** (7.11 * d - 2.33))


def tensile_strength_mc2010(fcm):
    """Mean tensile strength f_ctm (Pa) from the mean compressive strength: 0.3 fck^(2/3) for fck <= 50 MPa,
    2.12 ln(1 + fcm/10) above (fib MC2010 Eqs 5.1-3a/b, strengths in MPa, fck = fcm - 8 MPa)."""
    fcm = _positive(fcm, "tensile_strength_mc2010", "fcm", "Pa")
    if np.any(fcm <= DELTA_F):
        raise ParameterError("tensile_strength_mc2010", "fcm", fcm.tolist(), "> 8 MPa (fck = fcm - 8 MPa > 0)")
    fck = (fcm - DELTA_F) / MPA
    return MPA * np.where(fck <= 50.0, 0.3 * fck ** (2.0 / 3.0), 2.12 * np.log1p(0.1 * fcm / MPA))


def fracture_energy_mc2010(fcm):
    """Fracture energy G_F = 73 fcm^0.18 (N/m, fcm in MPa), fib MC2010 Eq 5.1-9 (no aggregate term)."""
    return 73.0 * (_positive(fcm, "fracture_energy_mc2010", "fcm", "Pa") / MPA) ** 0.18


AGGREGATE_MODULUS_FACTOR = {"basalt": 1.2, "quartzite": 1.0, "limestone": 0.9, "sandstone": 0.7}  # MC2010 Table 5.1-6


def elastic_modulus_mc2010(fcm, aggregate="quartzite"):
    """Tangent modulus E_ci = 21.5 GPa alpha_E (fcm / 10 MPa)^(1/3), fib MC2010 Eq 5.1-21."""
    if aggregate not in AGGREGATE_MODULUS_FACTOR:
        raise ParameterError("elastic_modulus_mc2010", "aggregate", aggregate, f"one of {sorted(AGGREGATE_MODULUS_FACTOR)}")
    return 21.5 * GPA * AGGREGATE_MODULUS_FACTOR[aggregate] * np.cbrt(
        _positive(fcm, "elastic_modulus_mc2010", "fcm", "Pa") / FCM0)


def characteristic_length(E, GF, ft):
    """Hillerborg's characteristic length l_ch = E G_F / f_t^2 (m): the scale of the fracture process zone's
    length (Hillerborg, Modeer & Petersson 1976)."""
    return (_positive(E, "characteristic_length", "E", "Pa") * _positive(GF, "characteristic_length", "GF", "N/m")
            / _positive(ft, "characteristic_length", "ft", "Pa") ** 2)


def size_effect_factor(size, transitional_size):
    """Bazant's size-effect law (type 2) for geometrically similar structures: sigma_N / (B f_t) =
    (1 + D / D0)^(-1/2), D the structure's size and D0 its transitional size (Bazant 1984): the nominal strength
    of small structures (D << D0) is the strength criterion's, that of large ones (D >> D0) falls as D^(-1/2), the
    law of linear elastic fracture mechanics."""
    D = _positive(size, "size_effect_factor", "size", "m")
    D0 = _positive(transitional_size, "size_effect_factor", "transitional_size", "m")
    return 1.0 / np.sqrt(1.0 + D / D0)


def rate_at_nose(velocity, diameter):
    """The strain rate's scale in a penetration, V/d (1/s): it grows as the calibre shrinks at equal velocity."""
    return _positive(velocity, "rate_at_nose", "velocity", "m/s") / _positive(diameter, "rate_at_nose", "diameter", "m")


def size_exponent(factor, sizes):
    """d ln(factor) / d ln(size) between consecutive sizes: the local power of a size law."""
    f, s = np.asarray(factor, float), np.asarray(sizes, float)
    return np.diff(np.log(f)) / np.diff(np.log(s))

