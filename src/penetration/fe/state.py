"""The named state of the explicit solver: fields, codes, controls and the grouped arrays the kernels take.

Arrays are grouped in named tuples (numba compiles their field access to a plain load, so a kernel takes a few
groups instead of dozens of arrays):

- ``Span``: the grid's shape (nr x nz elements) and the active rows j0 <= j < j1 (the moving window);
- ``Nodes``: positions, velocities (and those before the node pass, for the work of the contact), lumped
  masses, node states and the axis flag;
- ``Material``: the material's kind code and parameter array (``fe.constitutive``);
- ``Boundary``: fixities, boundary dashpots and the dashpot impedances;
- ``Loads``: prescribed velocities and constant external forces;
- ``Rows``: what each element row reduces to per step, in a float array ``f`` (stable step, hourglass work, eroded
  energy, dashpot power and axial force per node row) and an integer array ``i`` (the step's element and criterion,
  the first failure's element and code), each row of them named;
- ``Body``: the rigid projectile's outline and the contact's work buffers;
- ``Record``: the step histories, the accumulators and the last step's controlling element.

Codes are named constants, not bare numbers; ``FAILURES``, ``CRITERIA`` and ``STEP_STATUS`` name them for
people.

The parallel kernels (element pass, node pass, move) take the arrays they write as arguments of their own and
read everything else through the named tuples: numba drops the stores a parallel loop makes to an array it got
from a named tuple's field, and it marks a parallel loop's array arguments as not aliasing each other only when
no argument is written through another (the row loops vectorise only then). The node velocities are one array
``V`` (rows VR, VZ, VR0, VZ0) for the same reason: the node pass writes them all.
"""
from __future__ import annotations

import math
from collections import namedtuple

import numpy as np

# ---- element fields (rows of the element array E; F holds each element's corner forces, alive its state)
SRR, SZZ, STT, SRZ, P, QV, MUMAX, MUP, DMG, EPSP, EPSEFF, IE, V0, MASS = range(14)
N_FIELDS = 14
# the rows the element pass stores for every element, each step (the others are stored only where the scalar
# phase updates an element: MUP, DMG; or never: V0, MASS); the speed benchmark counts the bytes a step moves by them
STEP_STORES = (SRR, SZZ, STT, SRZ, P, MUMAX, QV, IE, EPSEFF, EPSP)

# ---- scratch rows of one element row (kinematics phase -> scalar phase -> force phase), and the scratch states
(S_DRR, S_DZZ, S_DTT, S_DRZ, S_RATE, S_MU, S_TV, S_VH, S_STATE, S_R0, S_R1, S_R3, S_LC, S_C, S_DT, S_HG,
 N_SCRATCH) = range(17)
# S_STATE: SKIP the element is not live; DONE live, completed by the kinematics phase (hjc.quick_update) and
# through the scalar phase's checks; SCALAR live, needs the scalar material update; BAD_SHAPE live with an inverted
# or degenerate geometry; CHECK live, completed by the kinematics phase but caught by a check (non-finite, eroding,
# step below the floor): the scalar phase deals with it
SKIP, DONE, SCALAR, BAD_SHAPE, CHECK = 0.0, 1.0, 2.0, 3.0, 4.0

# ---- element states (the array alive)
ERODED, LIVE, ERODING, INACTIVE, RETIRED, EJECTED = 0, 1, 2, 3, 4, 5   # ERODING: eroded in this pass (bookkept after it)
# EJECTED: an element of the erosion-free target thrown out above the struck face that lost its shape: it carries
# no stress from then on, its mass stays on its nodes (fe.erosion_free.debris)
# ---- node states (Nodes.state); a node at DROPPED or beyond keeps its velocity and is not moved
ACTIVE, FREE, DROPPED, WAITING = 0, 1, 2, 3   # FREE: no element left but kept; WAITING: below the window

# ---- failures of an element pass (Rows.fail holds the element, Rows.code the code)
OK, NON_FINITE, INVERTED, DT_COLLAPSE = 0, 1, 2, 3
FAILURES = {NON_FINITE: "non-finite stress or geometry", INVERTED: "inverted element (a corner Jacobian <= 0)",
            DT_COLLAPSE: "element time step below the floor"}

# ---- what controls the time step (Rows.crit per row; GROWTH and INITIAL are the driver's)
INITIAL, CFL, VISCOSITY, GROWTH = 0, 1, 2, 3
CRITERIA = {INITIAL: "initial", CFL: "cfl", VISCOSITY: "viscosity", GROWTH: "growth"}
N_CRITERIA = 4

# ---- status of a stretch of steps (solver.advance)
REACHED, EROSION, AT_REST, FAILED, HISTORY_FULL, PERFORATED, PAUSED = range(7)
STEP_STATUS = {REACHED: "reached the stop time", EROSION: "an element eroded", AT_REST: "the projectile is at rest",
               FAILED: "failed", HISTORY_FULL: "history full", PERFORATED: "the projectile's tail left the target",
               PAUSED: "made the steps asked for (a rezone is due)"}

# ---- controls (the array ctl)
C_DT, C_QH, C_Q1, C_Q2, C_EROSION, C_EROSION_VALUE, C_GUARD, C_DTMIN = range(8)
N_CTL = 8
EROSION_KINDS = {"none": 0, "plastic_strain": 1, "effective_strain": 2, "volumetric_tension": 3, "damage": 4}
NO_EROSION, PLASTIC_STRAIN, EFFECTIVE_STRAIN, VOLUMETRIC_TENSION, DAMAGE = range(5)
BOUNDARIES = {"free": 0, "roller": 1, "non_reflecting": 2}
FIX_R, FIX_Z = 1, 2   # bits of Boundary.fix: v_r held, v_z held

# ---- the projectile's state (the array proj)
B_TIP, B_VELOCITY, B_MASS, B_FRICTION, B_ACTIVE, B_EXIT, B_STOP_AT_REST, B_REST_VELOCITY = range(8)
N_BODY = 8

# ---- accumulators (Record.acc): booked work, impulse, and steps per time-step criterion since the last record
A_HOURGLASS, A_BOUNDARY, A_CONTACT, A_ERODED, A_EXTERNAL, A_BOUNDARY_IMPULSE = range(6)
A_STEPS = 6                         # A_STEPS + criterion: steps it controlled
N_ACC = A_STEPS + N_CRITERIA

# ---- step histories (rows of Record.hist)
HISTORY = ("t", "depth", "velocity", "contact_force", "contacts", "max_node_force")
H_T, H_DEPTH, H_VELOCITY, H_FORCE, H_CONTACTS, H_MAX_FORCE = range(6)

TWO_PI = 2.0 * math.pi
# Constant divisors as multiplications by their reciprocals (each rounded once, here): a division costs the
# vector loops several times a multiplication. Deterministic like the rest (not IEEE-equal to dividing).
SIXTH = 1.0 / 6.0
THIRD = 1.0 / 3.0
# No fast-math: with contraction, reassociation or reciprocal approximations LLVM's choices depend on the
# compilation context, and a kernel loaded from numba's cache then gave a different (chaotic) DO1 depth
# (5.18 m) from the same kernel compiled afresh (5.10 m). Without them every operation is IEEE-exact in
# source order, vectorised or not; the loops vectorise all the same (no reductions inside them).
FAST = False
# Doubles per vector of the row loops as LLVM emits them here (AVX2: 4); a row whose length is not a multiple
# of it leaves its last elements to a scalar remainder loop (fe.mesh.build sizes the rows to avoid that).
VECTOR_WIDTH = 4
ROWS_PER_CHUNK = 8   # element or node rows per parallel task

Span = namedtuple("Span", "nr nz j0 j1")
Nodes = namedtuple("Nodes", "r z vr vz vr0 vz0 mass state on_axis")
Material = namedtuple("Material", "kind q")
Boundary = namedtuple("Boundary", "fix dash rowdash zp zs guide")
Loads = namedtuple("Loads", "presc_i presc_v load_i load_f")
RF_DT, RF_HG, RF_ERO, RF_POWER, RF_IMPULSE = range(5)     # rows of Rows.f (nz + 1 columns: node rows for the last two)
RI_ARG, RI_CRIT, RI_FAIL, RI_CODE = range(4)              # rows of Rows.i (nz columns)
VR, VZ, VR0, VZ0 = range(4)                               # rows of the node velocity array V


class Rows:
    """Per-row reductions of the passes: the arrays ``f`` and ``i`` the kernels write, and named views of their rows
    (dt, hg, ero, power, impulse; arg, crit, fail, code)."""

    def __init__(self, nz):
        self.f = np.zeros((5, nz + 1))
        self.i = np.zeros((4, nz), np.int64)
        self.i[RI_ARG] = -1
        self.i[RI_FAIL] = -1
        self.dt, self.hg, self.ero = self.f[RF_DT, :nz], self.f[RF_HG, :nz], self.f[RF_ERO, :nz]
        self.power, self.impulse = self.f[RF_POWER], self.f[RF_IMPULSE]
        self.arg, self.crit, self.fail, self.code = self.i

    def copy(self):
        other = Rows(self.dt.size)
        other.f[:], other.i[:] = self.f, self.i
        return other

Body = namedtuple("Body", "zeta rho rho_max buf_i buf")
Record = namedtuple("Record", "hist acc ctrl")
