"""Empirical penetration formulas that carry a size term: the comparisons of the scale effect, not a model here.

Each is written once, in the units its authors fitted it in (lb, in, ft/s, psi), with the shot converted at the
edge; the SI forms of the reviews (Kennedy 1976; Li, Reid, Wen & Telford 2005) follow from the conversion.

- Modified NDRC (NDRC 1946, as modified by Kennedy 1966): G = (180 / sqrt(fc)) N (W/d) (V / 1000 d)^1.8,
  x/d = 2 sqrt(G) for G <= 1, G + 1 above; N the nose factor (0.72 flat, 0.84 hemispherical, 1.0 blunt, 1.14
  very sharp).
- Army Corps of Engineers (ACE, 1946): x/d = (282 / sqrt(fc)) (W/d^3) d^0.215 (V/1000)^1.5 + 0.5.
- Ballistic Research Laboratory (BRL, 1941; Chelapati, Kennedy & Wall 1972): x/d = (427 / sqrt(fc)) (W/d^3) d^0.2
  (V/1000)^1.33.
- Young's light-penetrator factor (Sandia, SAND97-2426, 1997): K = 0.4 W^0.15 for W < 400 lb, 1 above: a factor
  on the depth of a light penetrator.

Under geometric similarity at one velocity (W/d^3 fixed), BRL's x/d grows as d^0.2, ACE's (x/d - 0.5) as d^0.215 and
NDRC's G as d^0.2: the formulas fitted on large calibres hold a size effect that Forrestal's and Li & Chen's do not.
"""
from __future__ import annotations

import numpy as np

from ..errors import ParameterError

LB = 0.45359237            # kg
INCH = 0.0254              # m
FOOT = 0.3048              # m
PSI = 6894.757293168361    # Pa (lbf/in^2)
NDRC_NOSE_FACTORS = {"flat": 0.72, "hemispherical": 0.84, "blunt": 1.0, "very_sharp": 1.14}


def _imperial(mass, diameter, fc, velocity, owner):
    values = {"mass": mass, "diameter": diameter, "fc": fc, "velocity": velocity}
    for name, value in values.items():
        v = np.asarray(value, float)
        if not np.all(np.isfinite(v) & (v > 0)):
            raise ParameterError(owner, name, value, f"finite {name} > 0 (SI units)")
    return (np.asarray(mass, float) / LB, np.asarray(diameter, float) / INCH, np.asarray(fc, float) / PSI,
            np.asarray(velocity, float) / FOOT)


def ndrc_g(mass, diameter, fc, velocity, nose_factor):
    """The modified NDRC formula's G (dimensionless)."""
    if not np.all(np.asarray(nose_factor, float) > 0):
        raise ParameterError("ndrc", "nose_factor", nose_factor, f"> 0 (published: {NDRC_NOSE_FACTORS})")
    W, d, fc, V = _imperial(mass, diameter, fc, velocity, "ndrc")
    return 180.0 / np.sqrt(fc) * nose_factor * (W / d) * (V / (1000.0 * d)) ** 1.8


def ndrc_depth(mass, diameter, fc, velocity, nose_factor):
    """Depth (m) of the modified NDRC formula: x/d = 2 sqrt(G) for G <= 1, G + 1 above."""
    G = ndrc_g(mass, diameter, fc, velocity, nose_factor)
    return np.asarray(diameter, float) * np.where(G <= 1.0, 2.0 * np.sqrt(G), G + 1.0)


def ace_depth(mass, diameter, fc, velocity):
    """Depth (m) of the ACE formula."""
    W, d, fc, V = _imperial(mass, diameter, fc, velocity, "ace")
    return np.asarray(diameter, float) * (282.0 / np.sqrt(fc) * (W / d ** 3) * d ** 0.215 * (V / 1000.0) ** 1.5 + 0.5)


def brl_depth(mass, diameter, fc, velocity):
    """Depth (m) of the BRL formula."""
    W, d, fc, V = _imperial(mass, diameter, fc, velocity, "brl")
    return np.asarray(diameter, float) * (427.0 / np.sqrt(fc) * (W / d ** 3) * d ** 0.2 * (V / 1000.0) ** 1.33)


def young_mass_factor(mass):
    """Young's factor K on a light penetrator's depth: 0.4 W^0.15 (W in lb) below 400 lb, 1 above."""
    m = np.asarray(mass, float)
    if not np.all(np.isfinite(m) & (m > 0)):
        raise ParameterError("young", "mass", mass, "finite mass > 0 (kg)")
    W = m / LB
    return np.where(W < 400.0, 0.4 * W ** 0.15, 1.0)


EMPIRICAL_DEPTHS = {"ndrc": ndrc_depth, "ace": ace_depth, "brl": brl_depth}
