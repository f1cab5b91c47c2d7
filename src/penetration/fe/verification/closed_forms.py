"""Closed-form references of the FE level's verification problems (``fe.verification``), each derived in its
docstring from the physics; SI units. Independent of the solver: numpy and the standard library only."""
from __future__ import annotations

import math

import numpy as np


def noh(gamma, u0, rho0, t, dimension):
    """Noh's implosion (Noh 1987; ExactPack ``noh``) in ``dimension`` 1, 2 (cylindrical) or 3 (spherical): a cold
    ideal gas flowing in at u0 stagnates behind a shock moving out at D = (gamma - 1) u0/2; the gas ahead has
    density rho0 (1 + u0 t/r)^(dimension - 1), the gas behind rho0 ((gamma + 1)/(gamma - 1))^dimension and
    specific internal energy u0^2/2. Returns (shock radius, post-shock density, post-shock pressure, the
    pre-shock density as a function of r)."""
    D = 0.5 * (gamma - 1.0) * u0
    rho_post = rho0 * ((gamma + 1.0) / (gamma - 1.0)) ** dimension
    return D * t, rho_post, (gamma - 1.0) * rho_post * 0.5 * u0 ** 2, \
        lambda r: rho0 * (1.0 + u0 * t / np.asarray(r)) ** (dimension - 1)


def collapse_work(a0, a1, b0, Y):
    """Plastic work per unit length (J/m) of an incompressible rigid-perfectly-plastic (von Mises, yield Y)
    cylindrical shell collapsing in plane strain from inner radius a0 (outer b0) to a1 (Verney's problem in
    its cylindrical form). The flow v = v_a a/r has the equivalent strain rate (2/sqrt 3)|v_a| a/r^2, so the
    dissipation rate is (4 pi/sqrt 3) Y |v_a| a ln(b/a); with b^2 = a^2 + c, c = b0^2 - a0^2, and x = a^2,
    W = (pi/sqrt 3) Y [x ln(1 + c/x) + c ln(x + c)] between x1 and x0."""
    c = b0 ** 2 - a0 ** 2

    def F(x):
        return x * math.log(1.0 + c / x) + c * math.log(x + c)
    return math.pi / math.sqrt(3.0) * Y * (F(a0 ** 2) - F(a1 ** 2))


def collapse_kinetic_energy(rho, a0, b0, v0):
    """Kinetic energy per unit length (J/m) of the incompressible flow v = v0 a0/r in a shell a0 < r < b0:
    pi rho v0^2 a0^2 ln(b0/a0)."""
    return math.pi * rho * v0 ** 2 * a0 ** 2 * math.log(b0 / a0)


def collapse_speed(rho, a0, a1, b0, Y):
    """Inner-wall speed v0 at which the shell of ``collapse_work`` stops at a1: kinetic energy = plastic work."""
    return math.sqrt(collapse_work(a0, a1, b0, Y) / (math.pi * rho * a0 ** 2 * math.log(b0 / a0)))


def hertz_force(d, R, E, nu):
    """Hertz (1882): a rigid sphere of radius R pressed to depth d into an elastic half-space (E, nu) needs
    F = (4/3) E* R^(1/2) d^(3/2), E* = E/(1 - nu^2); the contact radius is a = sqrt(R d)."""
    return 4.0 / 3.0 * E / (1.0 - nu ** 2) * math.sqrt(R) * np.asarray(d) ** 1.5


def boussinesq_axis_displacement(F, E, nu, depth):
    """Boussinesq (1885): a point force F on an elastic half-space displaces the point at ``depth`` below it on
    the axis by F (1 + nu)(3 - 2 nu)/(2 pi E depth) (towards the inside). A layer held at that depth misses this
    displacement: its indentation is the half-space's less this amount."""
    return F * (1.0 + nu) * (3.0 - 2.0 * nu) / (2.0 * math.pi * E * depth)


def indentation_force(d, R, E, nu, depth):
    """The force that presses a rigid sphere to depth d into an elastic layer of ``depth`` held at its base: Hertz
    with the base's Boussinesq displacement taken off, d = (3F/(4 E* sqrt R))^(2/3) - u_B(F), solved for F by
    bisection (the right side grows with F for any layer deeper than the contact radius)."""
    def depth_of(F):
        return (3.0 * F * (1.0 - nu ** 2) / (4.0 * E * math.sqrt(R))) ** (2.0 / 3.0) - boussinesq_axis_displacement(F, E, nu, depth)
    lo, hi = 0.0, 2.0 * float(hertz_force(d, R, E, nu))
    while depth_of(hi) < d:
        hi *= 2.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if depth_of(mid) < d else (lo, mid)
    return 0.5 * (lo + hi)


def sleeve_contact_pressure(p_out, R, b):
    """Contact pressure between a rigid shaft of radius R and an elastic sleeve (nu = 0, inner radius R, outer b)
    pressed on it by a pressure p_out on its outer face (Lame): with nu = 0 the hoop strain is sigma_t/E = u/r,
    u(R) = 0 gives sigma_t(R) = 0, and sigma_r = A - B/r^2, sigma_t = A + B/r^2 with sigma_r(b) = -p_out give
    p_c = 2 p_out b^2/(b^2 + R^2)."""
    return 2.0 * p_out * b ** 2 / (b ** 2 + R ** 2)


def rigid_mass_on_bar(t, V0, M, Z):
    """A rigid mass M striking the end of a semi-infinite elastic bar of impedance Z = rho c A at V0 (Saint-Venant,
    Boussinesq): the end force is Z V and M dV/dt = -Z V, so V = V0 exp(-Z t/M)."""
    return V0 * np.exp(-Z * np.asarray(t) / M)


def uniaxial_strain_energy(M, V0, strain):
    """Internal energy (J) of an element of initial volume V0 compressed in uniaxial strain to the logarithmic
    strain e (< 0) by the solver's elastic law (p = K ln(V0/V), hypo-elastic deviator: sigma_zz = M e with
    M = K + 4G/3): the work of sigma_zz over d e V0 exp(e), V0 M (e exp(e) - exp(e) + 1)."""
    return V0 * M * (strain * math.exp(strain) - math.exp(strain) + 1.0)


def viscous_front_share(Q2, length, bar):
    """Energy share dissipated by a linear bulk viscosity q = rho l Q2 c |tr D| (active in compression only) as a
    step of particle velocity runs once along a bar of length L: a Kelvin-Voigt viscosity eta = rho c l Q2
    spreads the front diffusively (width sqrt(2 D t), D = eta/(2 rho)) and dissipates eta v^2/(2 sqrt(pi)
    sqrt(2 D t)) per unit area and time; over the transit L/c, against the kinetic energy rho L v^2/2 per unit
    area, 2 sqrt(Q2 l/(pi L)): it vanishes as the square root of the element size."""
    return 2.0 * math.sqrt(Q2 * length / (math.pi * bar))
