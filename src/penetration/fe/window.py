"""The moving window: only the element rows near the projectile are computed.

Rows further than ``Controls.window_ahead`` ahead of the tip are not yet active (their elements INACTIVE, their
nodes WAITING); rows further than ``Controls.window_behind`` behind it are retired (elements RETIRED, nodes
DROPPED), their internal energy, kinetic energy and momentum booked (``E_window``, ``dropped_momentum_z``). A
non-reflecting dashpot sits on the bottom node row of the window while it is above the domain's bottom. The
element and node passes, the move and the contact run over the window's rows only (``Model.span``).
"""
from __future__ import annotations

import numpy as np

from .state import ACTIVE, DROPPED, IE, INACTIVE, LIVE, MASS, RETIRED, WAITING
from .timestep import NO_STEP


def follow(m, Zt):
    """Activate rows down to window_ahead below the tip Zt, retire rows more than window_behind above it."""
    c, g = m.controls, m.grid
    if c.window_ahead is None and c.window_behind is None:
        return
    z0 = g.Z[:, 0]  # initial depth of each node row (the mesh is a tensor grid)
    nn_row = g.nr + 1
    changed = False
    if c.window_ahead is not None:
        j1 = int(min(g.nz, np.searchsorted(z0, Zt + c.window_ahead) + 1))
        if not m.window_started:
            m.alive[j1 * g.nr:][m.alive[j1 * g.nr:] == LIVE] = INACTIVE
            m.nstate[(j1 + 1) * nn_row:][m.nstate[(j1 + 1) * nn_row:] == ACTIVE] = WAITING
            m.j1 = j1
            changed = True
        elif j1 > m.j1:
            el = slice(m.j1 * g.nr, j1 * g.nr)
            m.alive[el][m.alive[el] == INACTIVE] = LIVE
            nodes = slice((m.j1 + 1) * nn_row, (j1 + 1) * nn_row)
            m.nstate[nodes][m.nstate[nodes] == WAITING] = ACTIVE
            m.j1 = j1
            changed = True
    if c.window_behind is not None:
        j0 = int(np.searchsorted(z0, Zt - c.window_behind) - 1)
        if j0 > m.j0:
            _retire_rows(m, j0)
            changed = True
    if changed or not m.window_started:
        m.window_started = True
        rows = m.rows
        rows.dt[m.j1:] = NO_STEP
        for a in (rows.hg, rows.ero):
            a[:m.j0] = 0.0
            a[m.j1:] = 0.0
        rows.fail[:] = -1
        for a in (rows.power, rows.impulse):
            a[:m.j0] = 0.0
            a[m.j1 + 1:] = 0.0
        m.dash[:] = m.dash_base
        m.mark_dashpot_rows()
        if m.j1 < g.nz:
            m.add_dashpots(m.j1 * nn_row + np.arange(nn_row))


def _retire_rows(m, j0):
    """Retire the element rows m.j0 <= j < j0 and their nodes, booking what they carry."""
    g = m.grid
    el = np.arange(m.j0 * g.nr, j0 * g.nr)
    live = el[m.alive[el] == LIVE]
    m.ledger.window += float(m.E[IE, live].sum())
    m.ledger.window_mass += float(m.E[MASS, live].sum())
    m.alive[live] = RETIRED
    nodes = np.arange(m.j0 * (g.nr + 1), j0 * (g.nr + 1))
    m.ledger.window += m.drop_nodes(nodes[m.nstate[nodes] < DROPPED])[0]
    m.rows.dt[m.j0:j0] = NO_STEP
    m.j0 = j0
