"""Closed-form depth of penetration (paper Eq 9; Forrestal; Li & Chen).

Crater phase F = c z for z < 4a, tunnelling F = pi a^2 (S fc + N* rho V^2)
beyond. Vectorised over arrays of shots (numpy broadcasting). Shots too slow
to leave the crater (V1^2 <= 0) stop at z = vs sqrt(m / c) < 4a, which joins
Eq 9 continuously at V1 = 0.
"""
from __future__ import annotations

import math

import numpy as np

from .resistance import Target, crater_coefficient, crater_velocity_squared


def penetration_depth(mass, radius, nstar, target: Target, vs):
    """Final depth Pd (m), paper Eq 9 with V1^2 from Forrestal (a^3 term).

    All arguments broadcast; target fields may be arrays too.
    """
    mass, radius, nstar, vs = (np.asarray(q, float) for q in (mass, radius, nstar, vs))
    v1sq = crater_velocity_squared(mass, radius, nstar, target, vs)
    tunnel = v1sq > 0
    ratio = np.where(tunnel, nstar * target.rho * np.where(tunnel, v1sq, 0.0) / target.R, 0.0)
    deep = mass / (2 * math.pi * radius**2 * target.rho * nstar) * np.log1p(ratio) + 4 * radius
    c = crater_coefficient(mass, radius, nstar, target, vs)
    shallow = vs * np.sqrt(mass / c)
    return np.where(tunnel, deep, shallow)


def impact_function(mass, diameter, target: Target, vs):
    """Li & Chen's impact function I = m V^2 / (d^3 S fc)."""
    return mass * np.asarray(vs, float) ** 2 / (diameter**3 * target.R)


def geometry_function(mass, diameter, nstar, target: Target):
    """Li & Chen's geometry function N = m / (N* rho d^3)."""
    return mass / (nstar * target.rho * diameter**3)


def li_chen_depth(I, N, k=2.0):
    """Dimensionless depth X/d of Li & Chen (2003) for crater depth k d.

    X/d = sqrt((1 + k pi/4N)/(1 + I/N) * 4 k I / pi) when X/d <= k, else
    (2/pi) N ln[(1 + I/N)/(1 + k pi/4N)] + k. With k = 2 (crater 4a) it is
    Eq 9 written in I and N.
    """
    I, N = np.asarray(I, float), np.asarray(N, float)
    gain = (1 + I / N) / (1 + k * math.pi / (4 * N))
    deep = 2 / math.pi * N * np.log(np.maximum(gain, 1.0)) + k
    shallow = np.sqrt(4 * k * I / (math.pi * gain))
    return np.where(gain > 1.0, deep, shallow)
