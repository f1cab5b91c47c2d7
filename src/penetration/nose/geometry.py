"""Axisymmetric nose profiles.

Coordinates: x runs along the axis from the nose tip (x = 0) back to the
shank (x = length); y is the radius, from 0 (or a flat tip) up to the shank
radius ``radius``. Every nose is a frozen dataclass registered by name and is
drawn as a chain of segments (straight lines, circular arcs, Newton's
minimum-resistance curve). Each segment is parametrised so that position,
derivative and surface angle stay finite where dy/dx is infinite (flat faces,
the hemisphere tip): arcs by the angle of their normal, Newton's curve by its
inverse slope dx/dy, lines by a fraction along them.

The surface angle ``beta`` is the angle between the surface tangent and the
axis (tan beta = dy/dx); the paper's angle phi between the outward normal and
the axis is pi/2 - beta, so the normal velocity of Eq 3 is V cos phi = V sin beta.
"""
from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field, fields
from functools import cached_property
from pathlib import Path

import numpy as np

from ..errors import ParameterError
from ..units import NUMBER_FORM, parse_number

NOSES: dict[str, type] = {}


def register(name):
    """Class decorator: make a nose kind available by ``name``."""
    def wrap(cls):
        cls.kind = name
        NOSES[name] = cls
        return cls
    return wrap


SIZE = (1e-6, 1e3)  # m: the range of radii a nose may have
LENGTHS = (1e-6, 1e5)  # m: the range of nose lengths
PSI_MAX = 1e6  # largest CRH: N* within 3e-10 of the closed form; beyond, the arc angles lose digits


def _size(v):
    return SIZE[0] <= v <= SIZE[1]


def _size_text(name):
    return f"{SIZE[0]:g} <= {name} <= {SIZE[1]:g} m"


def _length(v):
    return LENGTHS[0] <= v <= LENGTHS[1]


def _length_text(name):
    return f"{LENGTHS[0]:g} <= {name} <= {LENGTHS[1]:g} m"


def _check(owner, name, value, ok, allowed):
    if not (isinstance(value, (int, float)) and math.isfinite(value) and ok(value)):
        raise ParameterError(owner, name, value, allowed)


# Gauss-Legendre rules on [-1, 1]; each segment type names the order that is
# exact (lines) or converged to round-off (arcs, Newton's curve) on its panels.
_GL = {n: np.polynomial.legendre.leggauss(n) for n in (2, 24)}


# ----------------------------------------------------------------- segments
@dataclass(frozen=True)
class Line:
    """Straight segment from (x0, y0) to (x1, y1); t in [0, 1]."""
    x0: float
    y0: float
    x1: float
    y1: float
    t0 = 0.0
    t1 = 1.0
    panels = 1
    order = 2  # the integrands along a line are polynomials of degree <= 3

    def point(self, t):
        t = np.asarray(t, float)
        return self.x0 + t * (self.x1 - self.x0), self.y0 + t * (self.y1 - self.y0)

    def derivative(self, t):
        one = np.ones_like(np.asarray(t, float))
        return one * (self.x1 - self.x0), one * (self.y1 - self.y0)

    def angle(self, t):
        beta = math.atan2(self.y1 - self.y0, self.x1 - self.x0)
        return np.full_like(np.asarray(t, float), beta)

    def t_at_x(self, x):
        return (np.asarray(x, float) - self.x0) / (self.x1 - self.x0)


@dataclass(frozen=True)
class Arc:
    """Circular arc of radius S about (xc, yc), convex side outwards.

    The point at normal angle phi is (xc - S cos phi, yc + S sin phi); phi is
    the angle between the outward normal and the axis (the paper's phi), so
    the tangent angle is beta = pi/2 - phi. t = phi in [phi0, phi1].
    """
    xc: float
    yc: float
    S: float
    phi0: float
    phi1: float
    panels = 2
    order = 24

    @property
    def t0(self):
        return self.phi0

    @property
    def t1(self):
        return self.phi1

    def point(self, t):
        t = np.asarray(t, float)
        return self.xc - self.S * np.cos(t), self.yc + self.S * np.sin(t)

    def derivative(self, t):
        t = np.asarray(t, float)
        return self.S * np.sin(t), self.S * np.cos(t)

    def angle(self, t):
        return 0.5 * np.pi - np.asarray(t, float)

    def t_at_x(self, x):
        c = (self.xc - np.asarray(x, float)) / self.S
        return np.arccos(np.clip(c, -1.0, 1.0))


@dataclass(frozen=True)
class NewtonCurve:
    """Newton's minimum-resistance curve, parametrised by p = dx/dy >= 1.

    y = c (1 + p^2)^2 / p and x = shift + c (3 p^4 / 4 + p^2 - ln p - 7/4),
    the Euler-Lagrange solution of min integral y / (1 + (dx/dy)^2) dy; p = 1
    at the rim of the flat front disc (radius 4c, at x = shift).
    """
    c: float
    p0: float
    p1: float
    shift: float
    panels = 4
    order = 24

    @property
    def t0(self):
        return self.p0

    @property
    def t1(self):
        return self.p1

    def point(self, t):
        p = np.asarray(t, float)
        x = self.shift + self.c * (0.75 * p**4 + p**2 - np.log(p) - 1.75)
        return x, self.c * (1 + p**2) ** 2 / p

    def derivative(self, t):
        p = np.asarray(t, float)
        dy = self.c * (1 + p**2) * (3 * p**2 - 1) / p**2
        return p * dy, dy

    def angle(self, t):
        return np.arctan2(1.0, np.asarray(t, float))

    def t_at_x(self, x):
        x = np.asarray(x, float)
        ps = np.linspace(self.p0, self.p1, 257)
        p = np.interp(x, self.point(ps)[0], ps)
        for _ in range(6):  # Newton on x(p) = x; x is smooth and increasing in p
            xp, _y = self.point(p)
            dx, _dy = self.derivative(p)
            p = np.clip(p - (xp - x) / dx, self.p0, self.p1)
        return p


@dataclass(frozen=True)
class Polyline:
    """Points joined by straight pieces; t in [0, n-1], piece i is t in [i, i+1]."""
    xs: tuple
    ys: tuple
    order = 2

    @property
    def t0(self):
        return 0.0

    @property
    def t1(self):
        return float(len(self.xs) - 1)

    @property
    def panels(self):
        return len(self.xs) - 1

    def _piece(self, t):
        return np.clip(np.floor(np.asarray(t, float)), 0, len(self.xs) - 2).astype(int)

    def point(self, t):
        t = np.asarray(t, float)
        i = np.arange(len(self.xs))
        return np.interp(t, i, self.xs), np.interp(t, i, self.ys)

    def derivative(self, t):
        i = self._piece(t)
        xs, ys = np.asarray(self.xs), np.asarray(self.ys)
        return xs[i + 1] - xs[i], ys[i + 1] - ys[i]

    def angle(self, t):
        dx, dy = self.derivative(t)
        return np.arctan2(dy, dx)

    def t_at_x(self, x):
        return np.interp(np.asarray(x, float), self.xs, np.arange(len(self.xs), dtype=float))

    def edges(self, ta, tb):
        inner = np.arange(np.floor(ta) + 1, np.ceil(tb))
        return np.concatenate(([ta], inner[(inner > ta) & (inner < tb)], [tb]))


def gauss_panels(seg, ta=None, tb=None):
    """Nodes t and weights w covering [ta, tb] of a segment (default: all of it).

    Panels never straddle a polyline's corners, so the rule stays exact there.
    """
    ta = seg.t0 if ta is None else ta
    tb = seg.t1 if tb is None else tb
    edges = seg.edges(ta, tb) if hasattr(seg, "edges") else np.linspace(ta, tb, seg.panels + 1)
    gx, gw = _GL[seg.order]
    half = 0.5 * np.diff(edges)[:, None]
    mid = 0.5 * (edges[1:] + edges[:-1])[:, None]
    return (mid + half * gx).ravel(), (half * gw).ravel()


# ------------------------------------------------------------- the protocol
class NoseShape:
    """Shared protocol: radius, length, segments, y(x), angle(x), volume.

    Subclasses are frozen dataclasses that define ``radius`` and
    ``segments`` (a tuple ordered from tip to shank).
    """

    def outline_length(self) -> float:
        """Axial length of the drawn outline (tip to shank)."""
        return float(self.segments[-1].point(self.segments[-1].t1)[0])

    def _locate(self, x):
        """Index of the non-vertical segment holding each x, or -1."""
        x = np.asarray(x, float)
        idx = np.full(x.shape, -1)
        for i, seg in enumerate(self.segments):
            xa = float(seg.point(seg.t0)[0])
            xb = float(seg.point(seg.t1)[0])
            if xb > xa:
                idx[(x >= xa) & (x <= xb) & (idx < 0)] = i
        return idx

    def y(self, x):
        """Radius of the nose at axial position x (0 outside [0, length]); radius_at for any nose (a table nose's
        ``y`` is its column of points)."""
        return self.radius_at(x)

    def radius_at(self, x):
        """Radius of the nose at axial position x (0 outside [0, length])."""
        return self._evaluate(x, lambda seg, t: seg.point(t)[1], fill_at_tip=True)

    def angle(self, x):
        """Surface angle beta(x) between tangent and axis, in radians."""
        return self._evaluate(x, lambda seg, t: seg.angle(t), fill_at_tip=False)

    def _evaluate(self, x, fn, fill_at_tip):
        x = np.asarray(x, float)
        out = np.zeros(x.shape)
        idx = self._locate(x)
        for i, seg in enumerate(self.segments):
            m = idx == i
            if m.any():
                out[m] = fn(seg, np.clip(seg.t_at_x(x[m]), min(seg.t0, seg.t1), max(seg.t0, seg.t1)))
        if fill_at_tip and self.length == 0.0:  # flat nose: the face is at x = 0
            out[x == 0.0] = self.radius
        return out

    def volume(self) -> float:
        """Volume of the solid nose, pi * integral y^2 dx."""
        total = 0.0
        for seg in self.segments:
            t, w = gauss_panels(seg)
            xd, _ = seg.derivative(t)
            total += np.sum(w * seg.point(t)[1] ** 2 * xd)
        return float(np.pi * total)

    def mass(self, density: float) -> float:
        """Mass of a solid nose of the given density."""
        return density * self.volume()

    def outline(self, n: int = 200):
        """Points (x, y) along the profile, n per segment, tip to shank."""
        pts = [seg.point(np.linspace(seg.t0, seg.t1, n)) for seg in self.segments]
        return np.concatenate([p[0] for p in pts]), np.concatenate([p[1] for p in pts])

    @classmethod
    def from_keywords(cls, **kw):
        """Build from string or number keywords (command line, config)."""
        names = [f.name for f in fields(cls)]
        for key, value in kw.items():
            if key not in names:
                raise ParameterError(cls.kind, key, value, f"a key among {names}")
        values = {}
        for key, value in kw.items():
            try:
                values[key] = None if value in (None, "none") else parse_number(value)
            except ValueError:
                raise ParameterError(cls.kind, key, value, f"a number in SI units: {NUMBER_FORM}") from None
        missing = [f.name for f in fields(cls) if f.name not in values
                   and f.default is dataclasses.MISSING]
        if missing:
            raise ParameterError(cls.kind, missing[0], None, f"required; give all of {missing}")
        return cls(**values)


def _flat_tip(r):
    return (Line(0.0, 0.0, 0.0, r),) if r > 0 else ()


# -------------------------------------------------------------------- noses
@register("ogive")
@dataclass(frozen=True)
class Ogive(NoseShape):
    """Tangent ogive of caliber-radius-head psi (ogive radius S = 2 psi a).

    psi = 0.5 is the hemisphere. ``tip_radius`` > 0 blunts the tip with a
    flat face (meplat) where the ogive reaches that radius, shortening the nose.
    """
    psi: float
    radius: float
    tip_radius: float = 0.0

    def __post_init__(self):
        _check("ogive", "psi", self.psi, lambda v: 0.5 <= v <= PSI_MAX, f"0.5 <= psi <= {PSI_MAX:g} (0.5 is the hemisphere)")
        _check("ogive", "radius", self.radius, _size, _size_text("radius"))
        _check("ogive", "tip_radius", self.tip_radius, lambda v: 0 <= v < self.radius,
               f"0 <= tip_radius < radius = {self.radius}")

    @property
    def S(self):
        return 2.0 * self.psi * self.radius

    length = property(NoseShape.outline_length)

    @cached_property
    def segments(self):
        a, S, rf = self.radius, self.S, self.tip_radius
        phi_f = math.asin(min(1.0, (rf + S - a) / S))
        length = S * math.cos(phi_f)
        return _flat_tip(rf) + (Arc(length, a - S, S, phi_f, 0.5 * math.pi),)


@register("cone")
@dataclass(frozen=True)
class Cone(NoseShape):
    """Cone of the given length, optionally truncated by a flat tip."""
    radius: float
    length: float
    tip_radius: float = 0.0

    def __post_init__(self):
        _check("cone", "radius", self.radius, _size, _size_text("radius"))
        _check("cone", "length", self.length, _length, _length_text("length"))
        _check("cone", "tip_radius", self.tip_radius, lambda v: 0 <= v < self.radius,
               f"0 <= tip_radius < radius = {self.radius}")

    @cached_property
    def segments(self):
        return _flat_tip(self.tip_radius) + (Line(0.0, self.tip_radius, self.length, self.radius),)


@register("flat")
@dataclass(frozen=True)
class Flat(NoseShape):
    """Flat (blunt) nose: a disc of the shank radius, length 0."""
    radius: float

    def __post_init__(self):
        _check("flat", "radius", self.radius, _size, _size_text("radius"))

    length = property(NoseShape.outline_length)

    @cached_property
    def segments(self):
        return (Line(0.0, 0.0, 0.0, self.radius),)


@register("double_ogive")
@dataclass(frozen=True)
class DoubleOgive(NoseShape):
    """Double-ogive nose (paper Figs 4 and 6): tip ogive, cone, base ogive.

    Region 1 is a circular arc of radius S1 from the tip to C (radius a1);
    region 2 a cone from C to D (radius a2) of half-angle alpha; region 3 an
    arc of radius S2 from D to the shank, tangent to the shank. ``alpha`` None
    makes the cone tangent to the base ogive at D; ``tip_length`` None makes
    the tip ogive tangent to the cone at C, otherwise C sits at x = tip_length
    and the arc through the tip and C may meet the cone at a corner.
    """
    radius: float
    S1: float
    S2: float
    a1: float
    a2: float
    alpha: float | None = None
    tip_length: float | None = None

    def __post_init__(self):
        o, a = "double_ogive", self.radius
        _check(o, "radius", a, _size, _size_text("radius"))
        for name in ("S1", "S2"):  # beyond, the arcs' angles lose every digit
            _check(o, name, getattr(self, name), lambda v: 0 < v <= 1e9 * a, f"0 < {name} <= 1e9 radius = {1e9 * a:g} m")
        _check(o, "a2", self.a2, lambda v: 0 < v < a, f"0 < a2 < radius = {a}")
        _check(o, "a1", self.a1, lambda v: 0 < v <= self.a2, f"0 < a1 <= a2 = {self.a2}")
        _check(o, "S2", self.S2, lambda v: v >= a - self.a2,
               f"S2 >= radius - a2 = {a - self.a2:.6g} m, or the base ogive cannot reach the shank from D")
        if self.alpha is not None:
            _check(o, "alpha", self.alpha, lambda v: 0 < v < 0.5 * math.pi, "0 < alpha < pi/2 rad")
        if self.tip_length is None:
            lo = self.a1 / math.cos(self.cone_angle)
            _check(o, "S1", self.S1, lambda v: v >= lo,
                   f"S1 >= a1 / cos(alpha) = {lo:.6g} m for a tip ogive tangent to the cone at C")
        else:
            _check(o, "tip_length", self.tip_length, lambda v: v > 0, "tip_length > 0 m")
            half = 0.5 * math.hypot(self.tip_length, self.a1)
            _check(o, "S1", self.S1, lambda v: v >= half, f"S1 >= half the chord tip-C = {half:.6g} m")
            arc = self._tip_arc_through_c()
            if not (arc.phi0 >= 0 and arc.phi1 <= 0.5 * math.pi):
                raise ParameterError(o, "tip_length", self.tip_length,
                                     "a tip ogive through the tip and C that rises monotonically (x_C <= centre x, centre below the axis)")
        _check(o, "length (from S1, S2, a1, a2)", self.length, _length, _length_text("length"))

    @property
    def phi_d(self):
        """Normal angle of the base ogive at D."""
        return math.asin(1.0 - (self.radius - self.a2) / self.S2)

    @property
    def cone_angle(self):
        """Half-angle alpha of the cone (region 2)."""
        return 0.5 * math.pi - self.phi_d if self.alpha is None else self.alpha

    def _tip_arc_tangent(self):
        al, S1, a1 = self.cone_angle, self.S1, self.a1
        phi0 = math.asin(max(-1.0, min(1.0, math.cos(al) - a1 / S1)))
        xc = S1 * (math.cos(phi0) - math.sin(al))
        return Arc(xc + S1 * math.sin(al), a1 - S1 * math.cos(al), S1, phi0, 0.5 * math.pi - al)

    def _tip_arc_through_c(self):
        xC, a1, S1 = self.tip_length, self.a1, self.S1
        chord = math.hypot(xC, a1)
        h = math.sqrt(max(0.0, S1 * S1 - 0.25 * chord * chord))
        xc, yc = 0.5 * xC + h * a1 / chord, 0.5 * a1 - h * xC / chord
        return Arc(xc, yc, S1, math.atan2(-yc, xc), math.atan2(a1 - yc, xc - xC))

    length = property(NoseShape.outline_length)

    @cached_property
    def segments(self):
        tip = self._tip_arc_tangent() if self.tip_length is None else self._tip_arc_through_c()
        xC = float(tip.point(tip.phi1)[0])
        mid = ()
        xD = xC
        if self.a2 > self.a1:
            xD = xC + (self.a2 - self.a1) / math.tan(self.cone_angle)
            mid = (Line(xC, self.a1, xD, self.a2),)
        length = xD + self.S2 * math.cos(self.phi_d)
        base = Arc(length, self.radius - self.S2, self.S2, self.phi_d, 0.5 * math.pi)
        return (tip,) + mid + (base,)

    @property
    def joints(self):
        """x of C and D, the ends of region 2."""
        segs = self.segments
        return float(segs[0].point(segs[0].t1)[0]), float(segs[-1].point(segs[-1].t0)[0])


@register("minimum_nstar")
@dataclass(frozen=True)
class MinimumNstar(NoseShape):
    """Nose of least N* for a given length and radius (Jones et al. 1998).

    N* (Eq 5 with the flat tip) is Newton's minimum-resistance functional, so
    the optimum is Newton's body: a flat front disc of radius 4c followed by
    the curve of :class:`NewtonCurve`, with p running from 1 to the p_end at
    which y = radius and x = length.
    """
    radius: float
    length: float

    def __post_init__(self):
        _check("minimum_nstar", "radius", self.radius, _size, _size_text("radius"))
        _check("minimum_nstar", "length", self.length, _length, _length_text("length"))

    @cached_property
    def segments(self):
        p_end = _newton_p_end(self.length / self.radius)
        c = self.radius * p_end / (1 + p_end**2) ** 2
        return (Line(0.0, 0.0, 0.0, 4 * c), NewtonCurve(c, 1.0, p_end, 0.0))


def _newton_p_end(fineness):
    """p at the shank for Newton's body of length/radius = fineness."""
    def ratio(p):
        return (0.75 * p**4 + p**2 - math.log(p) - 1.75) * p / (1 + p**2) ** 2
    lo, hi = 1.0, 2.0
    while ratio(hi) < fineness:
        hi *= 2.0
    for _ in range(200):  # bisection: ratio is increasing in p >= 1
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if ratio(mid) < fineness else (lo, mid)
        if hi - lo <= 4e-16 * hi:
            break
    return 0.5 * (lo + hi)


@register("table")
@dataclass(frozen=True)
class TabulatedNose(NoseShape):
    """Nose given as (x, y) points joined by straight lines.

    x and y must be non-decreasing; x is shifted so that the first point is
    at x = 0; a first y > 0 is closed by a flat tip face. N* of the polygon
    is exact; a smooth nose sampled at spacing h is approximated to O(h^2).
    """
    x: tuple = field(default=())
    y: tuple = field(default=())
    source: str = ""

    def __post_init__(self):
        x, y = np.asarray(self.x, float), np.asarray(self.y, float)
        where = f"table {self.source}".strip()
        if x.ndim != 1 or x.size < 2 or x.size != y.size:
            raise ParameterError(where, "x, y", (x.size, y.size), "two equal-length columns with at least 2 points")
        if not (np.all(np.isfinite(x)) and np.all(np.isfinite(y))):
            raise ParameterError(where, "x, y", "non-finite", "finite numbers only")
        for name, v in (("x", x), ("y", y)):
            k = first_decrease(v)
            if k is not None:
                raise ParameterError(where, f"{name} of point {k + 1}", float(v[k]), f"{name} non-decreasing from tip to "
                                     f"shank (point {k} of {v.size} has {name} = {v[k - 1]:g})")
        if y[0] < 0 or y[-1] <= 0:
            raise ParameterError(where, "y", (y[0], y[-1]), "y >= 0 at the tip and > 0 at the shank")
        _check(where, "y at the shank (radius)", float(y[-1]), _size, _size_text("radius"))
        _check(where, "x at the shank (length)", float(x[-1] - x[0]), lambda v: v <= LENGTHS[1], f"length <= {LENGTHS[1]:g} m")

    @property
    def radius(self):
        return float(self.y[-1])

    length = property(NoseShape.outline_length)

    @cached_property
    def segments(self):
        x = np.asarray(self.x, float) - self.x[0]
        y = np.asarray(self.y, float)
        keep = np.concatenate(([True], (np.diff(x) != 0) | (np.diff(y) != 0)))  # drop repeated points
        return _flat_tip(float(y[0])) + (Polyline(tuple(x[keep]), tuple(y[keep])),)

    MIN_POINTS = 2  # a tip and a shank point

    @classmethod
    def from_csv(cls, path):
        """Read a CSV with a header naming columns x and y (metres), one point a row.

        Rows are numbered as in a spreadsheet (the header is row 1). Refused, naming the row or column: a
        header without x and y or with a column twice, fewer than MIN_POINTS points, a row with more or fewer
        fields than the header, a number not in units.NUMBER_FORM, and x or y decreasing. A UTF-8 byte-order
        mark is read as such (as predict reads its shots).
        """
        import csv
        where = f"table {path}"
        try:
            with open(path, newline="", encoding="utf-8-sig") as fh:
                reader = csv.reader(fh)
                header = next(reader, [])
                rows = list(reader)
        except (UnicodeDecodeError, csv.Error) as err:
            raise ParameterError(where, "file", type(err).__name__, "a UTF-8 text CSV file") from None
        twice = sorted({c for c in header if header.count(c) > 1})
        if twice:
            raise ParameterError(where, "columns", header, f"each column once ({twice[0]!r} is given twice)")
        if not {"x", "y"} <= set(header):
            raise ParameterError(where, "columns", header, "a header with columns x and y")
        if sum(1 for r in rows if r) < cls.MIN_POINTS:
            raise ParameterError(where, "rows", sum(1 for r in rows if r),
                                 f"a header row and at least {cls.MIN_POINTS} rows of points (x, y in metres, tip to shank)")
        ix, iy = header.index("x"), header.index("y")
        x, y = [], []
        for number, row in enumerate(rows, start=2):
            if not row:
                continue  # a blank line (csv.DictReader skips them too)
            if len(row) != len(header):
                raise ParameterError(where, f"row {number}", row, f"{len(header)} fields, as the header {header} "
                                     f"(the row has {len(row)})")
            for name, i, out in (("x", ix, x), ("y", iy, y)):
                try:
                    out.append(parse_number(row[i]))
                except ValueError:
                    raise ParameterError(where, f"{name} in row {number}", row[i],
                                         f"a number in metres: {NUMBER_FORM}") from None
        for name, v in (("x", x), ("y", y)):
            k = first_decrease(v)
            if k is not None:
                raise ParameterError(where, f"{name} in row {k + 2}", v[k], f"{name} non-decreasing from tip to shank "
                                     f"(row {k + 1} has {name} = {v[k - 1]:g})")
        return cls(tuple(x), tuple(y), str(path))

    @classmethod
    def from_keywords(cls, path=None, **kw):
        if kw:
            raise ParameterError("table", ",".join(kw), "unexpected", "only path=FILE.csv")
        if path is None or not Path(path).is_file():
            raise ParameterError("table", "path", path, "an existing CSV file with columns x, y")
        return cls.from_csv(path)


def first_decrease(values):
    """Index of the first value smaller than the one before it, or None."""
    bad = np.nonzero(np.diff(np.asarray(values, float)) < 0)[0]
    return int(bad[0]) + 1 if bad.size else None


LENGTH_FIELDS = {"ogive": ("radius", "tip_radius"), "cone": ("radius", "length", "tip_radius"), "flat": ("radius",),
                 "double_ogive": ("radius", "S1", "S2", "a1", "a2", "tip_length"),
                 "minimum_nstar": ("radius", "length"), "table": ("x", "y")}


def scaled(nose, factor: float):
    """The same nose shape with every length multiplied by ``factor``."""
    def mul(v):
        if v is None:
            return None
        return tuple(factor * e for e in v) if isinstance(v, tuple) else factor * v
    return dataclasses.replace(nose, **{f: mul(getattr(nose, f)) for f in LENGTH_FIELDS[nose.kind]})


def with_radius(nose, radius: float):
    """The same nose shape scaled to shank radius ``radius``."""
    return scaled(nose, radius / nose.radius)


def make_nose(kind: str, **params):
    """Build a registered nose by kind name from keyword parameters (a nose by constraint: nose.solve.solve_nose)."""
    if kind not in NOSES:
        raise ParameterError("nose", "kind", kind, f"one of {sorted(NOSES)}")
    cls = NOSES[kind]
    return cls.from_keywords(**params)
