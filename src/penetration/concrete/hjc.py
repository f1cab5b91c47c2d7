"""Holmquist-Johnson-Cook (HJC) concrete (paper Eqs 12-18, Table 1).

Sign convention: pressure p and volumetric strain mu = rho/rho0 - 1 are
positive in compression; stresses are positive in tension (so the mean
stress is -p). SI units.

Decisions where the paper (and published codes) are ambiguous; each is a
parameter where codes disagree:

- Elastic constants: Table 1's "K" = 14.86 GPa is the shear modulus G of
  the 1993 HJC set; the elastic bulk modulus is Ke = pc/muc (Eq 12).
  Table 1's "E" is unused.
- Lock strain (``lock``), three conventions. "offset" (default; no open
  code found that does exactly this) makes the fully dense curve of Eq 15
  pass through (mul, pl): mu_lock solves k1 x + k2 x^2 + k3 x^3 = pl with
  mu_lock = (mul - x)/(1 + x) = 0.0895, and crushing ends at mul = 0.10 as
  Table 1 reads. "literal" (the paper's Eq 15 as printed; OpenRadioss
  LAW126 is close to it) uses mu_lock = mul, which drops the pressure from
  pl to 0 at mul (negative tangent band up to mu = 0.1106). "extended"
  (SPHinXsys ``HJCSolid`` and, as far as known, HJC 1993) keeps mu_lock =
  mul as the permanent offset of the dense curve and extends the crushing
  line from (muc, pc) to where that curve reaches pl, mu = mul + x (1 + mul)
  = 0.1106 (``mu_crush_end``).
- Unloading in the crushing stage (Eq 14) uses the fully dense modulus k1
  for the paper's "plastic volume modulus" K.
- Tension branch of the strength surface (``tension``): "openradioss"
  sigma* = A (1 + p/T)(1 - D), zero at p = -T; "sphinxsys"
  sigma* = A max(0, 1 - D + p/T), zero at the damaged cutoff -T(1 - D).
- Rate term (``rate_floor``): eps_dot* is floored at 1 so that the rate
  term never weakens the material (OpenRadioss, SPHinXsys); Smax caps the
  normalised strength after the rate factor. ``rate_law`` replaces the
  factor 1 + C ln(eps_dot*) by fib Model Code 2010's compressive factor
  (concrete.scale), capped at the code's 300 1/s or continued beyond: the
  scale effect's rate mechanism (concrete.size), off by default.
- Damage: D += (d eps_p + d mu_p)/max(EFMIN, D1 (P* + T*)^D2), with mu_p the
  permanent crush strain mu_max - p_max/K_unload, frozen once fully dense.
- Tension cut-off p >= -T(1 - D) in every region, re-applied after the
  damage update.
- Switches for ablation studies: ``rate`` (C term), ``damage`` (D frozen at
  0) and ``strength_scale``, a factor on the whole strength surface: a
  lumped factor that stands for whatever makes the target weaker than the
  laboratory set in a given model (cracking, erosion, a near rear face),
  not an in-situ strength; the one parameter calibrated on the DO1 shot at
  the cavity level.
- ``hoop_cutoff`` (default off): radial cracking. In spherical symmetry the
  hoop stress is limited to the damaged tensile strength T (1 - D) by a
  deviatoric return at fixed pressure (the pressure cut-off alone caps the
  mean stress, not the largest principal stress, so without it the hoop
  stress outside the damaged zone reaches several T where real concrete
  cracks radially; Forrestal & Tzou 1997 model that region with zero hoop
  stress). Used by the spherical cavity solver only.
- ``erosion_strain`` (default inf: off): once the accumulated equivalent
  plastic strain reaches it, the point keeps its pressure but carries no
  deviatoric stress. A continuum stand-in for LS-DYNA's element erosion at
  the paper's failure strain fs, which deletes the element; the cavity
  level can calibrate it instead of ``strength_scale``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from ..errors import ParameterError
from .scale import dif_compression_mc2010_point

# indices into the parameter array used by the compiled kernels
(I_RHO0, I_G, I_A, I_B, I_C, I_N, I_FC, I_T, I_EPS0, I_EFMIN, I_SMAX, I_PC, I_MUC, I_PL, I_MUL, I_D1, I_D2,
 I_K1, I_K2, I_K3, I_KE, I_MULOCK, I_TENSION, I_RATEFLOOR, I_SCALE, I_DAMAGE, I_EROSION,
 I_HOOP, I_RATELAW) = range(29)
I_MUCRUSH = I_MUL  # the slot of mul holds the end of crushing (mul, or 0.1106 for the extended convention)
LOCKS = ("offset", "literal", "extended")
TENSIONS = ("openradioss", "sphinxsys")
# the strength's rate factor: HJC's 1 + C ln(eps_dot*) (Eq 17), or fib MC2010's compressive factor (concrete.scale)
# capped at 300 1/s or with its cube-root branch continued (the scale effect's rate mechanism, concrete.size)
RATE_LAWS = ("hjc", "mc2010_cap", "mc2010_extrapolate")


@dataclass(frozen=True)
class HJC:
    """HJC parameters (SI) and the convention switches; defaults are Table 1."""
    rho0: float = 2440.0
    G: float = 14.86e9
    A: float = 0.79
    B: float = 1.60
    C: float = 0.007
    N: float = 0.61
    fc: float = 48e6
    T: float = 4e6
    eps0: float = 1.0
    efmin: float = 0.01
    smax: float = 7.0
    pc: float = 16e6
    muc: float = 0.001
    pl: float = 0.80e9
    mul: float = 0.10
    D1: float = 0.04
    D2: float = 1.0
    k1: float = 85e9
    k2: float = -171e9
    k3: float = 208e9
    lock: str = "offset"
    tension: str = "openradioss"
    rate_floor: bool = True
    rate: bool = True
    damage: bool = True
    strength_scale: float = 1.0
    erosion_strain: float = math.inf
    hoop_cutoff: bool = False
    rate_law: str = "hjc"

    def __post_init__(self):
        positive = ("rho0", "G", "A", "fc", "T", "eps0", "efmin", "smax", "pc", "muc", "pl", "mul", "D1", "k1")
        for name in positive:
            v = getattr(self, name)
            if not (math.isfinite(v) and v > 0):
                raise ParameterError("hjc", name, v, f"{name} > 0 (SI units)")
        if not (math.isfinite(self.strength_scale) and self.strength_scale > 0):
            raise ParameterError("hjc", "strength_scale", self.strength_scale, "strength_scale > 0")
        if not self.erosion_strain > 0:
            raise ParameterError("hjc", "erosion_strain", self.erosion_strain, "erosion_strain > 0 (inf: off)")
        for name in ("B", "C", "N", "D2"):
            if not getattr(self, name) >= 0:
                raise ParameterError("hjc", name, getattr(self, name), f"{name} >= 0")
        if not (self.pc < self.pl and self.muc < self.mul):
            raise ParameterError("hjc", "pl, mul", (self.pl, self.mul), "pc < pl and muc < mul")
        if self.lock not in LOCKS:
            raise ParameterError("hjc", "lock", self.lock, f"one of {LOCKS}")
        if self.tension not in TENSIONS:
            raise ParameterError("hjc", "tension", self.tension, f"one of {TENSIONS}")
        if self.rate_law not in RATE_LAWS:
            raise ParameterError("hjc", "rate_law", self.rate_law, f"one of {RATE_LAWS}")

    @property
    def Ke(self):
        """Elastic bulk modulus pc/muc (Eq 12)."""
        return self.pc / self.muc

    @property
    def mu_lock(self):
        """Volumetric strain at which the fully dense curve has zero pressure."""
        if self.lock in ("literal", "extended"):
            return self.mul
        x = _dense_root(self.k1, self.k2, self.k3, self.pl)
        return (self.mul - x) / (1.0 + x)

    @property
    def mu_crush_end(self):
        """Volumetric strain where crushing ends and the fully dense curve takes over."""
        if self.lock != "extended":
            return self.mul
        return self.mul + _dense_root(self.k1, self.k2, self.k3, self.pl) * (1.0 + self.mul)

    @property
    def E(self):
        """Young's modulus implied by Ke and G."""
        return 9 * self.Ke * self.G / (3 * self.Ke + self.G)

    @property
    def nu(self):
        """Poisson's ratio implied by Ke and G."""
        return (3 * self.Ke - 2 * self.G) / (2 * (3 * self.Ke + self.G))

    def as_array(self) -> np.ndarray:
        vals = [self.rho0, self.G, self.A, self.B, self.C if self.rate else 0.0, self.N, self.fc, self.T, self.eps0, self.efmin, self.smax,
                self.pc, self.muc, self.pl, self.mu_crush_end, self.D1, self.D2, self.k1, self.k2, self.k3, self.Ke,
                self.mu_lock, float(TENSIONS.index(self.tension)), float(self.rate_floor),
                self.strength_scale, float(self.damage), min(self.erosion_strain, 1e300),
                float(self.hoop_cutoff), float(RATE_LAWS.index(self.rate_law)) if self.rate else 0.0]
        return np.array(vals, float)


# HJC field -> the quantity of the paper's Table 1 it is read from. Table 1's
# "K" column is the shear modulus G (see the module docstring); the
# reference strain rate is the text's 1/s, not the table's misprinted 6.
TABLE1_FIELDS = {"rho0": "rho", "G": "K", "A": "A", "B": "B", "C": "C", "N": "N", "fc": "fc", "T": "T",
                 "eps0": "eps0_text", "efmin": "efmin", "smax": "smax", "pc": "pc", "muc": "muc", "pl": "pl",
                 "mul": "mul", "D1": "D1", "D2": "D2", "k1": "k1", "k2": "k2", "k3": "k3"}


def from_table1(value, **fields) -> HJC:
    """HJC material from the paper's Table 1; ``value(quantity)`` returns a Table 1 quantity in SI units.

    ``fields`` set the switches (lock, tension, ...) or replace a Table 1 value (e.g. smax for ablation).
    """
    return HJC(**{**{field: value(quantity) for field, quantity in TABLE1_FIELDS.items()}, **fields})

def _dense_root(k1, k2, k3, p):
    """Smallest positive x with k1 x + k2 x^2 + k3 x^3 = p (Newton from p/k1)."""
    x = p / k1
    for _ in range(100):
        f = k1 * x + k2 * x * x + k3 * x**3 - p
        x_new = x - f / (k1 + 2 * k2 * x + 3 * k3 * x * x)
        if abs(x_new - x) < 1e-16:
            break
        x = x_new
    return x


# ------------------------------------------------------- compiled kernels
# The point update and the functions it calls evaluate every branch of a piecewise law and select one
# (a if c else b on values already computed): the FE level calls them for scattered elements, whose
# regions a branch predictor cannot guess. Each select keeps the comparison of the piecewise law as
# written in the paper's regions, so that NaN inputs take the same side as a branch would. Branches
# remain only on the parameter switches (the same for every point).
@njit(cache=True, inline="always")
def dense_pressure(mu, q):
    """Fully dense curve (Eq 15); linear k1 in tension."""
    mb = (mu - q[I_MULOCK]) / (1.0 + q[I_MULOCK])
    cubic = q[I_K1] * mb + q[I_K2] * mb * mb + q[I_K3] * mb * mb * mb
    linear = q[I_K1] * mb
    return linear if mb <= 0.0 else cubic


@njit(cache=True, inline="always")
def _crush_pressure(mu, q):
    """The crush line between (mu_c, p_c) and (mu_l, p_l), Eq 13."""
    return q[I_PC] + (q[I_PL] - q[I_PC]) * (mu - q[I_MUC]) / (q[I_MUCRUSH] - q[I_MUC])


@njit(cache=True, inline="always")
def loading_pressure(mu, q):
    """Virgin loading curve p(mu): Eqs 12, 13, 15."""
    elastic, crush, dense = q[I_KE] * mu, _crush_pressure(mu, q), dense_pressure(mu, q)
    muc, mul = q[I_MUC], q[I_MUCRUSH]
    return elastic if mu <= muc else (crush if mu <= mul else dense)


@njit(cache=True, inline="always")
def unloading_modulus(mu_max, q):
    """(1 - F) Ke + F k1 with F = (mu_max - muc)/(mul - muc), Eq 14."""
    F = (mu_max - q[I_MUC]) / (q[I_MUCRUSH] - q[I_MUC])
    F = min(max(F, 0.0), 1.0)
    return (1.0 - F) * q[I_KE] + F * q[I_K1]


@njit(cache=True, inline="always")
def longitudinal_modulus(mu, mu_max, q):
    """K + 4G/3 of the longitudinal wave speed: the unloading bulk modulus (Eq 14), or the fully dense curve's
    tangent where it is stiffer (mu beyond the end of crushing)."""
    K = unloading_modulus(mu_max, q)
    mb = (mu - q[I_MULOCK]) / (1.0 + q[I_MULOCK])
    dense = q[I_K1] + 2.0 * q[I_K2] * mb + 3.0 * q[I_K3] * mb * mb   # computed, then selected (as in quick_update)
    K = max(K, dense) if mu > q[I_MUCRUSH] else K
    return K + 4.0 * q[I_G] / 3.0


@njit(cache=True, inline="always")
def deviatoric_trial(s0, s1, s2, s3, d0, d1, d2, d3, G):
    """Elastic predictor of the deviatoric stress (rr/xx, zz/yy, tt/zz normal, rz/xy shear as a tensor component):
    s + 2G dev(d) for the strain increment d."""
    tr = (d0 + d1 + d2) / 3.0
    return s0 + 2.0 * G * (d0 - tr), s1 + 2.0 * G * (d1 - tr), s2 + 2.0 * G * (d2 - tr), s3 + 2.0 * G * d3


@njit(cache=True, inline="always")
def eos(mu, mu_max, q):
    """Pressure, new mu_max and permanent crush strain mu_p (before the cut-off).

    Loading beyond mu_max follows the virgin curve; below it the path is
    elastic (region I), the Eq 14 line (region II) or the dense curve.
    """
    loading = mu >= mu_max
    elastic = q[I_KE] * mu
    unload = _crush_pressure(mu_max, q) - unloading_modulus(mu_max, q) * (mu_max - mu)
    dense = dense_pressure(mu, q)
    crush = _crush_pressure(mu, q)
    muc, mul = q[I_MUC], q[I_MUCRUSH]   # read before the selects: a conditional load keeps a loop from vectorising
    load = elastic if mu <= muc else (crush if mu <= mul else dense)
    p = load if loading else (elastic if mu_max <= muc else (unload if mu_max <= mul else dense))
    mu_max = mu if loading else mu_max
    return p, mu_max, permanent_strain(mu_max, q)


@njit(cache=True, inline="always")
def permanent_strain(mu_max, q):
    """Crush (plastic volumetric) strain left after unloading from mu_max."""
    m = min(mu_max, q[I_MUCRUSH])
    # m > mu_c wherever the result is used: loading_pressure(m) is the crush line there
    left = m - loading_pressure(m, q) / unloading_modulus(m, q)
    muc = q[I_MUC]
    return 0.0 if mu_max <= muc else left


@njit(cache=True, inline="always")
def cutoff(p, D, q):
    return max(p, -q[I_T] * (1.0 - D))


@njit(cache=True, inline="always")
def strength(p, D, rate, q):
    """Yield stress sigma_y (Pa) at pressure p, damage D, equivalent strain rate (1/s)."""
    fc = q[I_FC]
    r = rate / q[I_EPS0]
    r = max(r, 1.0) if q[I_RATEFLOOR] > 0.5 else r
    # ln 1 = 0 exactly: r = 1 (or r <= 0, NaN) gives the factor 1, and C = 0 switches the rate term off
    factor = 1.0 + q[I_C] * math.log(r if ((r > 0.0) & (r != 1.0)) else 1.0)
    if q[I_RATELAW] > 0.5:   # a parameter switch, the same for every point
        factor = dif_compression_mc2010_point(rate, q[I_RATELAW] > 1.5)
    ps = p / fc
    comp = q[I_A] * (1.0 - D) + q[I_B] * max(ps, 0.0) ** q[I_N]
    # both tensile branches computed, one selected (parameters read before a select, & for and: numba's reference
    # counting of q on short-circuit branches, and loads under a condition, keep a loop over points scalar)
    tens_linear = q[I_A] * (1.0 + p / q[I_T]) * (1.0 - D)
    tens_offset = q[I_A] * max(0.0, 1.0 - D + p / q[I_T])
    tens = tens_linear if q[I_TENSION] < 0.5 else tens_offset
    s = comp if ps >= 0.0 else tens
    s = max(s, 0.0) * factor
    return q[I_SCALE] * fc * min(s, q[I_SMAX])


@njit(cache=True, inline="always")
def yield_stress(p, D, eps_p, rate, q):
    """strength(), or 0 once the accumulated plastic strain eps_p reaches erosion_strain."""
    sy = strength(p, D, rate, q)
    return 0.0 if eps_p >= q[I_EROSION] else sy


@njit(cache=True, inline="always")
def fracture_strain(p, q):
    """eps_p^f + mu_p^f = max(EFMIN, D1 (P* + T*)^D2), Eq 18."""
    x = (p + q[I_T]) / q[I_FC]
    # IEEE pow gives x ** 1.0 = x exactly: the paper's D2 = 1 needs no power
    xd = x if q[I_D2] == 1.0 else x ** q[I_D2]
    floor, grown = q[I_EFMIN], q[I_D1] * xd
    return floor if x <= 0.0 else max(floor, grown)


N_CHORDS = 14


@njit(cache=True)
def power_chords(q):
    """Chords of x^N between the breakpoints 0, 2^-8, 2^-7, ..., 2^5 (slopes row 0, intercepts row 1).

    For N <= 1 (x^N concave) the smallest chord at x in [0, 32] is the chord of
    x's own interval, so min_k(slope_k x + icpt_k) is a lower bound of x^N
    (exact at the breakpoints); for N > 1 every chord is set to 0 (bound 0).
    """
    out = np.zeros((2, N_CHORDS))
    if q[I_N] > 1.0:
        return out
    x0, f0 = 0.0, 0.0
    for k in range(N_CHORDS):
        x1 = 2.0 ** (k - 8)
        f1 = x1 ** q[I_N]
        slope = (f1 - f0) / (x1 - x0)
        out[0, k] = slope
        out[1, k] = f0 - slope * x0
        x0, f0 = x1, f1
    return out


@njit(cache=True, inline="always")
def _chord_min(c, x):
    """min_k (c[0, k] x + c[1, k]) over the N_CHORDS chords, written out: a loop here would keep LLVM from
    vectorising the caller's loop over elements."""
    m0 = min(c[0, 0] * x + c[1, 0], c[0, 1] * x + c[1, 1])
    m1 = min(c[0, 2] * x + c[1, 2], c[0, 3] * x + c[1, 3])
    m2 = min(c[0, 4] * x + c[1, 4], c[0, 5] * x + c[1, 5])
    m3 = min(c[0, 6] * x + c[1, 6], c[0, 7] * x + c[1, 7])
    m4 = min(c[0, 8] * x + c[1, 8], c[0, 9] * x + c[1, 9])
    m5 = min(c[0, 10] * x + c[1, 10], c[0, 11] * x + c[1, 11])
    m6 = min(c[0, 12] * x + c[1, 12], c[0, 13] * x + c[1, 13])
    return min(min(min(m0, m1), min(m2, m3)), min(min(m4, m5), m6))


@njit(cache=True, inline="always")
def quick_update(s0, s1, s2, s3, mu, mu_max, D, eps_p, de0, de1, de2, de3, rate, q, chords):
    """update_point for a plane-shear state (s4 = s5 = 0) in its commonest cases, without branches.

    Two cases, both without new crush (the EOS in region I, max(mu, mu_max)
    <= mu_c, or unloading below mu_max, so mu_p does not grow):
    (a) no plastic flow: the trial deviator lies below a lower bound of the
        strength surface: x^N by its chords (power_chords), the rate factor
        1 + C ln r by 1 + C (1 - 1/r) (the rate floor on, or C = 0), MC2010's
        factor (rate_law) by 1;
    (b) fully damaged (D = 1) and not in compression: the strength is 0, the
        deviator returns to 0 and the plastic strain grows by seq/3G; the damage
        stays 1.
    Returns (valid, s0..s3, p, mu_max, dep, c2) with c2 the unloading (or dense,
    whichever is stiffer) bulk modulus + 4G/3 as in the FE wave speed; where
    valid is false the result is meaningless and the caller must call
    update_point. Written with selects only, so that a loop over elements can
    be vectorised.
    """
    G = q[I_G]
    tr = (de0 + de1 + de2) / 3.0
    s0 += 2.0 * G * (de0 - tr)
    s1 += 2.0 * G * (de1 - tr)
    s2 += 2.0 * G * (de2 - tr)
    s3 += 2.0 * G * de3
    mm = max(mu, mu_max)
    # EOS (eos() when mu < mu_max or in region I)
    F = min(max((mu_max - q[I_MUC]) / (q[I_MUCRUSH] - q[I_MUC]), 0.0), 1.0)
    Ku = (1.0 - F) * q[I_KE] + F * q[I_K1]
    p_unload = q[I_PC] + (q[I_PL] - q[I_PC]) * (mu_max - q[I_MUC]) / (q[I_MUCRUSH] - q[I_MUC]) - Ku * (mu_max - mu)
    mb = (mu - q[I_MULOCK]) / (1.0 + q[I_MULOCK])
    p_dense = q[I_K1] * mb + q[I_K2] * mb * mb + q[I_K3] * mb * mb * mb if mb > 0.0 else q[I_K1] * mb
    p_eos = q[I_KE] * mu if mm <= q[I_MUC] else (p_unload if mu_max <= q[I_MUCRUSH] else p_dense)
    p = max(p_eos, -q[I_T] * (1.0 - D))
    K = max(Ku, q[I_K1] + 2.0 * q[I_K2] * mb + 3.0 * q[I_K3] * mb * mb) if mu > q[I_MUCRUSH] else Ku
    seq = math.sqrt(3.0 * (0.5 * (s0 * s0 + s1 * s1 + s2 * s2) + s3 * s3))
    # (a) a lower bound of the strength surface (Eq 16 and its tensile branch, as in strength())
    ps = p / q[I_FC]
    x = min(max(ps, 0.0), 32.0)
    xn = _chord_min(chords, x)
    comp = q[I_A] * (1.0 - D) + q[I_B] * xn
    tens = q[I_A] * (1.0 + p / q[I_T]) * (1.0 - D) if q[I_TENSION] < 0.5 else q[I_A] * max(0.0, 1.0 - D + p / q[I_T])
    lower = comp if ps >= 0.0 else max(tens, 0.0)
    factor = 1.0 + q[I_C] * max(0.0, 1.0 - q[I_EPS0] / max(rate, 1e-300)) if q[I_RATEFLOOR] > 0.5 else 1.0
    factor = factor if q[I_RATELAW] < 0.5 else 1.0       # MC2010's factor is >= 1: 1 bounds it below
    no_flow = ((eps_p < q[I_EROSION]) & ((q[I_RATEFLOOR] > 0.5) | (q[I_C] == 0.0) | (q[I_RATELAW] > 0.5))
               & (seq <= q[I_SCALE] * q[I_FC] * min(lower * factor, q[I_SMAX])))
    # (b) fully damaged outside compression
    spent = (D >= 1.0) & (p_eos <= 0.0)
    valid = ((mm <= q[I_MUC]) | (mu < mu_max)) & (no_flow | spent)
    keep = 1.0 if no_flow else 0.0
    dep = 0.0 if no_flow else seq / (3.0 * G)
    return valid, s0 * keep, s1 * keep, s2 * keep, s3 * keep, p, mm, dep, K + 4.0 * G / 3.0


@njit(cache=True, inline="always")
def update_voigt(s0, s1, s2, s3, s4, s5, mu, mu_max, mu_p, D, eps_p, d0, d1, d2, d3, d4, d5, rate, q):
    """One HJC stress update of a material point (hypo-elastic, radial return), on scalars.

    s0..s5: deviatoric stress (Voigt xx, yy, zz, xy, yz, zx; shear as tensor
    components), already rotated (Jaumann) by the caller; eps_p: plastic
    strain accumulated so far (erosion criterion); d0..d5: total strain
    increment (same layout, tensor shear). Returns the new s0..s5, p, mu_max,
    mu_p, D and the plastic strain increment. Without data-dependent branches:
    the yield surface is evaluated at every call and the return selected.
    """
    G = q[I_G]
    s0, s1, s2, s3 = deviatoric_trial(s0, s1, s2, s3, d0, d1, d2, d3, G)
    s4 += 2.0 * G * d4
    s5 += 2.0 * G * d5
    p, mu_max, mu_p_new = eos(mu, mu_max, q)
    p = cutoff(p, D, q)
    seq = math.sqrt(3.0 * (0.5 * (s0 * s0 + s1 * s1 + s2 * s2) + s3 * s3 + s4 * s4 + s5 * s5))
    # below a lower bound of the surface there is no flow (with a rate factor >= 1 and p >= 0,
    # sigma_y >= scale fc min(A (1 - D), Smax)); the surface is evaluated anyway, the bound only decides
    below = ((p >= 0.0) & (eps_p < q[I_EROSION]) & ((q[I_RATEFLOOR] > 0.5) | (q[I_C] == 0.0))
             & (seq <= q[I_SCALE] * q[I_FC] * min(q[I_A] * (1.0 - D), q[I_SMAX])))
    sy = yield_stress(p, D, eps_p, rate, q)
    ef = fracture_strain(p, q)
    flow = (not below) & (seq > sy)
    ratio = sy / seq
    scale = (ratio if seq > 0.0 else 0.0) if flow else 1.0
    excess = (seq - sy) / (3.0 * G)
    dep = excess if flow else 0.0
    dmu_p = max(mu_p_new - mu_p, 0.0)
    grow = (q[I_DAMAGE] > 0.5) & (dep + dmu_p > 0.0)
    grown = min(1.0, D + (dep + dmu_p) / ef)
    D = grown if grow else D
    p = cutoff(p, D, q)
    return s0 * scale, s1 * scale, s2 * scale, s3 * scale, s4 * scale, s5 * scale, p, mu_max, mu_p_new, D, dep


@njit(cache=True, error_model="numpy")   # the selects divide by zero where they then take the other value
def update_point(s, mu, mu_max, mu_p, D, eps_p, deps, rate, q):
    """update_voigt on an array s (updated in place); returns p, mu_max, mu_p, D and the plastic strain increment."""
    s[0], s[1], s[2], s[3], s[4], s[5], p, mu_max, mu_p, D, dep = update_voigt(
        s[0], s[1], s[2], s[3], s[4], s[5], mu, mu_max, mu_p, D, eps_p,
        deps[0], deps[1], deps[2], deps[3], deps[4], deps[5], rate, q)
    return p, mu_max, mu_p, D, dep


def jaumann(s, w, dt):
    """Rotate a Voigt deviatoric stress by the spin w (3x3, antisymmetric) over dt.

    Hughes-Winget: R = (I - w dt/2)^-1 (I + w dt/2) is orthogonal, so the
    stress invariants are kept exactly; it is the Jaumann rate to second order.
    """
    eye = np.eye(3)
    R = np.linalg.solve(eye - 0.5 * dt * w, eye + 0.5 * dt * w)
    S = voigt_to_matrix(s)
    return matrix_to_voigt(R @ S @ R.T)


def voigt_to_matrix(s):
    return np.array([[s[0], s[3], s[5]], [s[3], s[1], s[4]], [s[5], s[4], s[2]]])


def matrix_to_voigt(S):
    return np.array([S[0, 0], S[1, 1], S[2, 2], S[0, 1], S[1, 2], S[0, 2]])


@dataclass
class PointState:
    """History of one material point for single-element drivers."""
    s: np.ndarray
    p: float = 0.0
    mu_max: float = 0.0
    mu_p: float = 0.0
    D: float = 0.0
    eps_p: float = 0.0
    strain: np.ndarray = None

    @classmethod
    def new(cls):
        return cls(np.zeros(6), strain=np.zeros(6))


def drive(material: HJC, increments, rate=1.0, state: PointState | None = None, spin=None, dt=1.0):
    """Single-element driver: apply total strain increments (Voigt, tensor shear).

    mu follows from the accumulated volumetric strain as exp(-eps_v) - 1
    (compression positive). Returns arrays of p, mu, the equivalent stress,
    D, eps_p and the Voigt stress history (tension positive).
    """
    q = material.as_array()
    st = state or PointState.new()
    out = {k: [] for k in ("p", "mu", "seq", "D", "eps_p", "sigma")}
    for de in np.atleast_2d(np.asarray(increments, float)):
        if spin is not None:
            st.s = jaumann(st.s, spin, dt)
        st.strain = st.strain + de
        mu = math.exp(-(st.strain[0] + st.strain[1] + st.strain[2])) - 1.0
        st.p, st.mu_max, st.mu_p, st.D, dep = update_point(st.s, mu, st.mu_max, st.mu_p, st.D, st.eps_p, de, rate, q)
        st.eps_p += dep
        sig = st.s.copy()
        sig[:3] -= st.p
        j2 = 0.5 * (st.s[:3] @ st.s[:3]) + st.s[3:] @ st.s[3:]
        for k, v in (("p", st.p), ("mu", mu), ("seq", math.sqrt(3 * j2)), ("D", st.D), ("eps_p", st.eps_p),
                     ("sigma", sig)):
            out[k].append(v)
    return {k: np.array(v) for k, v in out.items()}, st
