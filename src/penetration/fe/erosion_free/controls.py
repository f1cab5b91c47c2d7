"""The controls of the erosion-free target (``ErosionFree``): its rezone, the ejection of the lip, and the crater and
wall debris rules. Checked values with their defaults in one place, like the solver's ``spec.Controls``."""
from __future__ import annotations

from dataclasses import dataclass

from ...errors import ParameterError


@dataclass(frozen=True)
class ErosionFree:
    """The erosion-free target's controls: it is rezoned and its guard ejects elements, never erodes them."""
    rezone_every: int = 5               # steps between its rezones
    rezone_quality: float = 0.95        # a node is rezoned when one of its elements' quality is below this
    rezone_weight: float = 0.5          # share of the way to the smoothed place a rezoned node moves
    rezone_radius: float | None = None  # m: the zone's extent from the axis (None: the whole width)
    eject_length: float = 0.25          # an element above the struck face thinner than this many element sizes is ejected
    eject_height: float | None = None   # m: one whose centre is farther above the face than this too (None: no
    #                                     ejection at all: a problem without a struck face)
    pilot_guide: bool = False           # a rigid frictionless guide fills the pilot hole: its wall nodes keep r >= r0
    crater_depth: float | None = None   # m: an element that loses its shape less than this below the struck face is
    #                                     crater debris, ejected like the lip (None: none; deeper ones stop the run)
    crater_thin_after: float | None = None  # m: once the tip is deeper than this, an element of the crater thinner
    #                                     than eject_length element sizes is crater debris too (None: never)
    wall_debris_behind: float | None = None  # m: an element deeper than the crater that loses its shape with every
    #                                     node more than this above the tip (behind the projectile's tail, out of its
    #                                     reach) is wall debris, ejected like the crater's (None: it stops the run)

    def __post_init__(self):
        where = "fe erosion-free controls"
        if not (isinstance(self.rezone_every, int) and 1 <= self.rezone_every <= 1000):
            raise ParameterError(where, "rezone_every", self.rezone_every, "an integer 1 <= rezone_every <= 1000 (steps)")
        if not 0.0 < self.rezone_quality <= 1.0:
            raise ParameterError(where, "rezone_quality", self.rezone_quality, "0 < rezone_quality <= 1")
        if not 0.0 < self.rezone_weight <= 1.0:
            raise ParameterError(where, "rezone_weight", self.rezone_weight, "0 < rezone_weight <= 1")
        if not 0.0 < self.eject_length <= 1.0:
            raise ParameterError(where, "eject_length", self.eject_length, "0 < eject_length <= 1 (element sizes)")
        if self.eject_height is not None and not self.eject_height > 0:
            raise ParameterError(where, "eject_height", self.eject_height, "> 0 (m) or None")
        for key in ("crater_depth", "crater_thin_after", "wall_debris_behind"):
            value = getattr(self, key)
            if value is not None and not value >= 0:
                raise ParameterError(where, key, value, ">= 0 (m) or None")
        if self.rezone_radius is not None and not self.rezone_radius > 0:
            raise ParameterError(where, "rezone_radius", self.rezone_radius, "> 0 (m) or None")
