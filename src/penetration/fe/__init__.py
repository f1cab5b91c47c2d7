"""Finite-element level: 2-D axisymmetric explicit Lagrangian solver with HJC, erosion and a rigid nose."""
from .constitutive import MATERIALS, Elastic, VonMises
from .mesh import Grid, MeshSpec, body_outline, build, graded
from .contact import Projectile
from .model import Controls, Model
from .solver import Result, Unstable, run
