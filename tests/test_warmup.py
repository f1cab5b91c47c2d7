"""The install's warm-up (penetration.warmup): its helper compiles the very signatures the FE step calls, so that the
step finds them in the cache instead of compiling a second version."""
import numpy as np
from numba import typeof
from numba.core import compiler, typed_passes
from numba.core.registry import cpu_target

from penetration import warmup
from penetration.fe import model as fe_model
from penetration.fe import solver
from penetration.fe.contact import contact
from penetration.fe.erosion_free import rezone as remap
from penetration.fe.nodes import external, guide, move, node_pass
from penetration.fe.state import HISTORY, N_ACC, Record
from penetration.fe.timestep import next_step


def _type(func, args):
    """Numba's type inference of func's body for these arguments (no code generated): resolving each call types, and
    so loads or compiles, the callee for the argument types the body passes it."""
    tc, tg = cpu_target.typing_context, cpu_target.target_context
    tc.refresh()
    tg.refresh()
    typed_passes.type_inference_stage(tc, tg, compiler.run_frontend(func.py_func), tuple(typeof(a) for a in args),
                                      None)


def test_the_helper_compiles_the_signatures_the_step_calls():
    """After the helper's calls, typing the step and the time loop as ``fe.solver.run`` calls them adds no signature
    to a node-side kernel: had the helper passed an argument of another type (an int for a float, a list for a
    tuple), the step would need, and the install compile, a second version. The helper's stand-in for the first
    stable step is undone afterwards."""
    warmup.node_kernels()
    kernels = (node_pass, external, contact, guide, move, next_step)
    helper = {k.py_func.__name__: list(k.signatures) for k in kernels}
    assert all(len(s) == 1 for s in helper.values()), helper
    model, st, proj = warmup.step_state()
    acc = np.zeros(N_ACC)
    _type(solver.step, (st, proj, model.ctl, acc, 1e-9, 1e-9))
    rec = Record(np.zeros((len(HISTORY), 8)), acc, np.array([0, -1], np.int64))
    _type(solver.advance, (st, proj, model.ctl, rec, 0.0, 1e-9, 1e-6, 0.5, 0, np.iinfo(np.int64).max))
    assert {k.py_func.__name__: list(k.signatures) for k in kernels} == helper
    assert fe_model.Model._initial_dt.__name__ == "_initial_dt"
    # the erosion-free target's ejection and remap, called from Python as its time loop calls them (fe.model.rezone)
    assert len(remap.eject.signatures) == 1 and len(remap.rezone.signatures) == 1
