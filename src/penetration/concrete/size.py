"""The scale effect (a scene's ``size`` effect): the mechanisms that make concrete's resistance depend on calibre.

HJC as stated has no length and a weak rate term, so every level without this effect is scale-free: geometrically
similar shots give the same depth over calibre. Each mechanism is written once (a registry by name) and takes its
constants from published relations (``concrete.scale``); none is fitted on a penetration shot.

- ``rate``: the strength rises with the strain rate by fib Model Code 2010's factor for compression. Each level
  brings its own rate: V/d for the closed form (the striking velocity over the calibre), the local rate of the
  cavity expansion and of an element. The code states the factor up to 300 1/s; a penetration's rates are
  1e3-1e5 1/s, and ``beyond`` says which convention holds there (``cap``: no more increase; ``extrapolate``: the
  code's cube-root branch continued, which holds the specimen's inertia as well as the material's rate effect).
- ``fracture``: Bazant's size-effect law (type 2) on the resistance, sigma_N ~ (1 + d/D0)^(-1/2), with the
  transitional size D0 = lambda0 d_a (Bazant 1984): d_a the largest aggregate, lambda0 = 25 Bazant & Kim's value for
  the diagonal shear of beams (1984), a published geometry's, not a penetration's (none is published). At the FE
  level, where the element size is a length, a crack band instead (Bazant & Oh 1983): HJC's smallest fracture
  strain EFMIN becomes the strain 2 G_F / (f_t h) at which a band one element wide dissipates the fracture energy
  G_F (MC2010) under linear softening from the tensile strength f_t (the material's T), so that the energy a crack
  takes no longer falls with the element size.

The analytic level takes both as a factor on the static resistance (``resistance_factor``); the cavity level takes
``rate`` in the material (the strength surface times the factor at each point's rate) and ``fracture`` as the
factor; the FE level ``rate`` in the material and ``fracture`` as the crack band (``regularised``).
"""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from ..errors import ParameterError
from . import scale
from .hjc import HJC

SIZE_MECHANISMS = {}


def mechanism(name):
    """Register a mechanism: a function (effect, diameter, velocity) -> the factor on the static resistance."""
    def wrap(fn):
        SIZE_MECHANISMS[name] = fn
        return fn
    return wrap


@dataclass(frozen=True)
class SizeEffect:
    """The scale effect's mechanisms and their constants (SI): ``beyond`` the rate factor's convention above
    300 1/s, ``aggregate`` the largest aggregate d_a (m), ``lambda0`` the transitional size over d_a."""
    mechanisms: tuple = ("rate", "fracture")
    beyond: str = "extrapolate"
    aggregate: float = 0.016
    lambda0: float = 25.0

    def __post_init__(self):
        unknown = [m for m in self.mechanisms if m not in SIZE_MECHANISMS]
        if not self.mechanisms or unknown or len(set(self.mechanisms)) != len(self.mechanisms):
            raise ParameterError("size", "mechanisms", list(self.mechanisms),
                                 f"one or more distinct names of {sorted(SIZE_MECHANISMS)}")
        if self.beyond not in scale.BEYOND:
            raise ParameterError("size", "beyond", self.beyond, f"one of {scale.BEYOND}")
        if not (1e-3 <= self.aggregate <= 0.1):
            raise ParameterError("size", "aggregate", self.aggregate, "a largest aggregate of 1e-3 to 0.1 m")
        if not (0.0 < self.lambda0 <= 1e3):
            raise ParameterError("size", "lambda0", self.lambda0, "0 < lambda0 <= 1000")

    @property
    def transitional_size(self):
        """D0 = lambda0 d_a (m)."""
        return self.lambda0 * self.aggregate

    @classmethod
    def from_spec(cls, spec):
        """The effect of a settings mapping (a scene's ``size``, a variant of the config's scale_effect.variants;
        absent keys take the defaults); None for None (a variant without the effect)."""
        if spec is None:
            return None
        spec = dict(spec)
        if "mechanisms" in spec:
            spec["mechanisms"] = tuple(spec["mechanisms"])
        return cls(**spec)


@mechanism("rate")
def _rate(effect: SizeEffect, diameter, velocity):
    """MC2010's compressive factor at the closed form's rate V/d."""
    return scale.dif_compression_mc2010(scale.rate_at_nose(velocity, diameter), beyond=effect.beyond)


@mechanism("fracture")
def _fracture(effect: SizeEffect, diameter, velocity):
    """Bazant's law at the calibre: (1 + d/D0)^(-1/2)."""
    return scale.size_effect_factor(diameter, effect.transitional_size) * np.ones_like(np.asarray(velocity, float))


def material_rate_law(effect: SizeEffect | None) -> str:
    """The HJC rate law (concrete.hjc.RATE_LAWS) of a level that carries the rate mechanism in its material: MC2010's
    factor with the effect's convention beyond 300 1/s, or HJC's own where the effect has no rate mechanism."""
    if effect is None or "rate" not in effect.mechanisms:
        return "hjc"
    return f"mc2010_{effect.beyond}"


def with_rate_law(material: HJC, effect: SizeEffect | None) -> HJC:
    """The material with the effect's rate law (material_rate_law); unchanged where that is HJC's own."""
    law = material_rate_law(effect)
    return material if law == "hjc" else dataclasses.replace(material, rate_law=law)


def fracture_factor(effect: SizeEffect | None, diameter) -> float:
    """Bazant's factor on the resistance at calibre ``diameter`` (m) where the effect has the fracture mechanism (the
    cavity level's: on its strength scale), 1 otherwise."""
    if effect is None or "fracture" not in effect.mechanisms:
        return 1.0
    return float(SIZE_MECHANISMS["fracture"](effect, diameter, 1.0))


def resistance_factor(effect: SizeEffect | None, diameter, velocity, mechanisms=None):
    """The factor on the static resistance of a shot of calibre ``diameter`` (m) struck at ``velocity`` (m/s): the
    product over the effect's mechanisms (or over ``mechanisms``, a subset of them); 1 without the effect."""
    out = np.ones_like(np.asarray(velocity, float) * np.asarray(diameter, float))
    if effect is None:
        return out
    for name in effect.mechanisms if mechanisms is None else tuple(mechanisms):
        if name not in effect.mechanisms:
            raise ParameterError("size", "mechanisms", name, f"one of the effect's {list(effect.mechanisms)}")
        out = out * SIZE_MECHANISMS[name](effect, diameter, velocity)
    return out


def sized_target(target, effect: SizeEffect | None, diameter, velocity):
    """The closed forms' target (analytic.resistance.Target) with its S times resistance_factor at calibre
    ``diameter`` and ``velocity``; the target itself without the effect."""
    import dataclasses
    if effect is None:
        return target
    return dataclasses.replace(target, S=target.S * float(resistance_factor(effect, diameter, velocity)))


def crack_band_strain(material: HJC, element_size: float) -> float:
    """The strain at which a crack band of width ``element_size`` (m) has dissipated the fracture energy under linear
    softening from the tensile strength: 2 G_F / (f_t h), G_F = MC2010's at the material's fc, f_t its T."""
    if not (element_size > 0):
        raise ParameterError("size", "element_size", element_size, "> 0 (m)")
    return float(2.0 * scale.fracture_energy_mc2010(material.fc) / (material.T * element_size))


def regularised(material: HJC, effect: SizeEffect | None, element_size: float) -> HJC:
    """The FE level's material with the scale effect's crack band (EFMIN = crack_band_strain) where the effect has
    the fracture mechanism; unchanged otherwise."""
    if effect is None or "fracture" not in effect.mechanisms:
        return material
    return dataclasses.replace(material, efmin=crack_band_strain(material, element_size))
