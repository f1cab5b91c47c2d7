"""Structured axisymmetric meshes of the target and the rigid projectile's outline.

The target is a cylinder r in [r0, radius], z in [0, depth] (z grows into the
target, the struck face is z = 0). Logical grid: node (i, j) has index
j (nr + 1) + i, element (i, j) has index j nr + i and nodes (i, j), (i+1, j),
(i+1, j+1), (i, j+1), counter-clockwise in the (r, z) plane. A uniform core
of square elements of size h surrounds the path (r <= core_radius,
z <= core_depth); outside it the sizes grow geometrically by ``grading``.
With ``pilot_hole`` > 0 the target starts at r0 = pilot_hole (a hole along
the axis; no axis nodes). With ``opened_radius`` > pilot_hole too, the first
node columns are spaced for the tunnel the nose opens (``opened_columns``).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import ParameterError
from .state import VECTOR_WIDTH


@dataclass(frozen=True)
class MeshSpec:
    element_size: float
    core_radius: float
    core_depth: float
    radius: float
    depth: float
    grading: float = 1.1
    pilot_hole: float = 0.0
    opened_radius: float = 0.0

    def __post_init__(self):
        for key in ("element_size", "core_radius", "core_depth", "radius", "depth"):
            v = getattr(self, key)
            if not (math.isfinite(v) and v > 0):
                raise ParameterError("mesh", key, v, f"{key} > 0 (m)")
        if not 1.0 <= self.grading <= 1.5:
            raise ParameterError("mesh", "grading", self.grading, "1 <= grading <= 1.5 (size ratio of neighbours)")
        if not 0.0 <= self.pilot_hole < self.core_radius:
            raise ParameterError("mesh", "pilot_hole", self.pilot_hole, f"0 <= pilot_hole < core_radius = {self.core_radius} m")
        if self.opened_radius and not 0.0 < self.pilot_hole < self.opened_radius < self.core_radius:
            raise ParameterError("mesh", "opened_radius", self.opened_radius,
                                 f"0, or 0 < pilot_hole = {self.pilot_hole} m < opened_radius < core_radius = {self.core_radius} m")
        if self.element_size > min(self.core_radius - self.pilot_hole, self.core_depth):
            raise ParameterError("mesh", "element_size", self.element_size,
                                 "element_size <= core_radius - pilot_hole and <= core_depth")
        cells = ((self.radius - self.pilot_hole) / self.element_size) * (self.depth / self.element_size)
        if cells > 5e7:
            raise ParameterError("mesh", "element_size", self.element_size, "a size giving at most 5e7 elements")


def graded(x0, core, extent, h, ratio, multiple=1, offset=0):
    """Node coordinates from x0: uniform cells of size h up to >= core, then growing by ``ratio`` up to extent.

    multiple > 1: where graded cells are needed, their number is raised until the total count of cells (with
    ``offset`` cells before x0) is a multiple of ``multiple``, and they grow by the ratio <= ``ratio`` that fills the extent with them (when
    even uniform cells of size h would overfill it, the count is left as it is).
    """
    n_core = max(1, int(math.ceil((min(core, extent) - x0) / h - 1e-9)))
    x = list(x0 + h * np.arange(n_core + 1))
    if x[-1] >= extent - 1e-12 * extent:
        x[-1] = extent
        return np.array(x)
    span = extent - x[-1]
    size, grown = h, []
    while sum(grown) < span:
        size *= ratio
        grown.append(size)
    n = -(-(offset + n_core + len(grown)) // multiple) * multiple - n_core - offset
    if n > len(grown) and n * h < span:
        # h (q + q^2 + ... + q^n) grows with q from n h < span (q = 1) to > span (q = ratio): bisect for q
        lo, hi = 1.0, ratio
        for _ in range(100):
            q = 0.5 * (lo + hi)
            if h * sum(q ** k for k in range(1, n + 1)) < span:
                lo = q
            else:
                hi = q
        grown = [h * hi ** k for k in range(1, n + 1)]
    grown = np.array(grown) * span / sum(grown)  # last cells scaled to end exactly at extent
    return np.concatenate([x, x[-1] + np.cumsum(grown)])


@dataclass(frozen=True)
class Grid:
    """Nodes of a logically rectangular mesh: R[j, i], Z[j, i] for node (i, j).

    Elements (i, j) are counter-clockwise in (r, z) when R grows with i and Z
    with j (a rectangle) or for the polar grid of ``polar``.
    """
    R: np.ndarray
    Z: np.ndarray

    @classmethod
    def tensor(cls, r, z):
        R, Z = np.meshgrid(np.asarray(r, float), np.asarray(z, float))
        return cls(R, Z)

    @property
    def nr(self):
        return self.R.shape[1] - 1

    @property
    def nz(self):
        return self.R.shape[0] - 1

    @property
    def r(self):
        return self.R[0]

    @property
    def z(self):
        return self.Z[:, 0]

    @property
    def elements(self):
        return self.nr * self.nz

    def nodes(self):
        """Flattened node coordinates (r, z), node (i, j) at j (nr + 1) + i."""
        return self.R.ravel().copy(), self.Z.ravel().copy()

    def connectivity(self):
        """Element -> its four node indices (counter-clockwise), for plotting and checks."""
        i, j = np.meshgrid(np.arange(self.nr), np.arange(self.nz))
        n1 = (j * (self.nr + 1) + i).ravel()
        return np.stack([n1, n1 + 1, n1 + self.nr + 2, n1 + self.nr + 1], axis=1)


def polar(radii, n_theta):
    """Half-annulus about the origin for spherical problems: radii[i] along the ray, theta = pi j/n_theta from +z.

    Node (i, j) at r = radii[i] sin(theta_j), z = -radii[i] cos(theta_j) (counter-clockwise elements);
    the rows j = 0 and j = n_theta lie on the axis.
    """
    th = np.linspace(0.0, np.pi, n_theta + 1)
    rad = np.asarray(radii, float)
    R = np.outer(np.sin(th), rad)
    R[0] = 0.0
    R[-1] = 0.0
    return Grid(R, -np.outer(np.cos(th), rad))


def opened_columns(r_hole, a, h):
    """Radii of the node columns next to a pilot hole of radius r_hole that a nose of radius a opens: the ring
    between column i and the hole keeps its volume when the hole becomes the tunnel, so that column i then lies
    at a + i h (r_i^2 - r_hole^2 = (a + i h)^2 - a^2); the columns stop where their spacing is back to about h."""
    r = [r_hole]
    i = 1
    while True:
        x = math.sqrt((a + i * h) ** 2 - a * a + r_hole * r_hole)
        if x - r[-1] <= 1.05 * h:
            return np.array(r)
        r.append(x)
        i += 1


def node_lines(spec: MeshSpec):
    """(r, z): the node coordinates of the grid's columns and rows (cheap: no 2-D array is made)."""
    # columns in a multiple of the element kernels' vector width: no element of a row falls to a scalar remainder loop
    h = spec.element_size
    if spec.opened_radius:
        first = opened_columns(spec.pilot_hole, spec.opened_radius, h)
        rest = graded(first[-1], spec.core_radius, spec.radius, h, spec.grading, VECTOR_WIDTH, offset=first.size - 1)
        r = np.concatenate([first[:-1], rest])
    else:
        r = graded(spec.pilot_hole, spec.core_radius, spec.radius, h, spec.grading, VECTOR_WIDTH)
    return r, graded(0.0, spec.core_depth, spec.depth, h, spec.grading)


def build(spec: MeshSpec) -> Grid:
    return Grid.tensor(*node_lines(spec))


# Decimals of a metre the rigid body's outline is rounded to (1 pm): far below any length of the model, but a
# length all the same, so a shot scaled by two is not exactly the same shot (None: no rounding).
OUTLINE_DIGITS = 12


def body_outline(nose, body_length, points_per_segment=400):
    """Outline of the rigid projectile in body axes: (zeta, rho), zeta from the tip backwards, rho the radius.

    The nose outline (``nose.outline``) is followed by the shank up to
    ``body_length``; zeta never decreases along the outline (a flat face is a
    vertical piece at zeta = 0). The points are rounded to OUTLINE_DIGITS
    decimals of a metre (None: not rounded): numpy's vector maths (log,
    arccos, ...) differ in the last bit between CPUs, and the erosion would
    amplify the difference. The grid is the level's one length that is not
    the shot's.
    """
    if not body_length > nose.length:
        raise ParameterError("fe projectile", "length", body_length, f"length > nose length {nose.length} m")
    x, y = nose.outline(points_per_segment)
    if OUTLINE_DIGITS is not None:
        x, y = np.round(x, OUTLINE_DIGITS), np.round(y, OUTLINE_DIGITS)
    keep = np.concatenate(([True], (np.diff(x) != 0) | (np.diff(y) != 0)))
    x, y = x[keep], y[keep]
    x = np.maximum.accumulate(x)
    return np.append(x, body_length), np.append(y, nose.radius)
