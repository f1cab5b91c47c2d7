"""Finite-element level: 2-D axisymmetric explicit Lagrangian solver with HJC, erosion and a rigid nose."""
from .materials import MATERIALS, Elastic, VonMises
from .mesh import Grid, MeshSpec, body_outline, build, graded
from .solver import Controls, Model, Projectile, Result, Unstable, run
