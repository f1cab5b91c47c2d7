"""Speed of the finite-element level: time per element-step against this machine's memory-bandwidth floor.

Prints the machine, a STREAM-triad bandwidth measured in this run before and
after the timings (numba, parallel, arrays far larger than the caches; the
higher of the two is used), the bytes one element-step moves (every array the
step reads or writes, once: a floor that assumes perfect caching), the floor
(bytes / bandwidth), and the measured time per element-step of one full
explicit step (node pass, move, element pass; no contact) on a DO1-like HJC
target in motion, as a ratio to the floor, each the best of --repeat batches
of --steps steps (noise on a shared host only adds time; the states that
evolve start every batch from the same state), and how that step divides
between its three passes. The same elastic state on a mesh deep enough that one
step moves at least twice the last-level cache (16 times the benchmark mesh's
depth or more; the cache size as the kernel reports it, /sys/devices/system/cpu)
shows what moving the arrays from memory rather than from the cache costs.
Optionally (--do1) the wall time of the pipeline's DO1 shot (its mesh and
calibrated failure strain, from results/fe/full/do1/, which
`snakemake -c2 results/fe/full/do1/double_ogive_835.json` builds; the depth is
checked against the pipeline's bit for bit), and the time per
element-step in the state of that shot at 6 ms (the window around the
nose: crushed, damaged, yielding and elastic elements as they come).

    python workflow/benchmarks/fe_speed.py [--threads 2] [--size 0.00875] [--steps 200] [--repeat 3] [--do1]
"""
from __future__ import annotations

import argparse
import json
import math
import time
from pathlib import Path

import numba
import numpy as np
from nstar_speed import machine
from numba import njit, prange

from penetration.concrete.hjc import HJC, strength
from penetration.fe import state as fe_state
from penetration.fe.element_pass import element_pass
from penetration.fe.mesh import MeshSpec, build
from penetration.fe.model import Controls, Model
from penetration.fe.nodes import move as move_nodes, node_pass

DO1 = "results/fe/full/do1/double_ogive_835.json"


@njit(parallel=True, cache=True)
def _triad(a, b, c, s):
    for i in prange(a.size):
        a[i] = b[i] + s * c[i]


def stream_triad(n=40_000_000, repeat=8):
    a, b, c = np.zeros(n), np.random.rand(n), np.random.rand(n)
    _triad(a, b, c, 3.0)
    best = min(_timed(lambda: _triad(a, b, c, 3.0)) for _ in range(repeat))
    return 3 * 8 * n / best  # bytes/s (STREAM's convention: two reads and one write per element)


def _timed(fn):
    t0 = time.perf_counter()
    fn()
    return time.perf_counter() - t0


def _snapshot(arrays):
    """A callable that puts `arrays` back to their present values (untimed, before each batch)."""
    saved = [a.copy() for a in arrays]

    def restore():
        for a, b in zip(arrays, saved):
            a[:] = b
    return restore


def _best_split(passes, steps, repeat, restore=None):
    """Seconds per step of each of `passes` (callables run in order as one step) in the batch whose total was the
    best of `repeat` batches of `steps` steps (the host's noise only ever adds time), and every batch's seconds per
    step (the runs, printed beside the best). With `restore`, every batch
    starts from the same state (restore(), untimed), for a state that evolves: the DO1 window's crushed zone
    relaxes once no projectile pushes it, and batches carried on would time ever cheaper states. The elastic
    states are stationary (small waves) and carry on: restoring the deep mesh's 105 MiB before a batch would
    time its write-back as well."""
    best, runs = None, []
    for _ in range(repeat):
        if restore is not None:
            restore()
        spent = [0.0] * len(passes)
        for _ in range(steps):
            for k, p in enumerate(passes):
                t0 = time.perf_counter()
                p()
                spent[k] += time.perf_counter() - t0
        runs.append(sum(spent) / steps)
        if best is None or sum(spent) < sum(best):
            best = spent
    return [x / steps for x in best], runs


def _best(step, steps, repeat, restore=None):
    """Seconds per step of `step`, the best of `repeat` batches of `steps` steps (each from restore()'s state), and
    every batch's."""
    split, runs = _best_split((step,), steps, repeat, restore)
    return split[0], runs


def _runs(runs, per=1.0):
    """The batches' times per element-step, in ns, as printed: 'a, b, c'."""
    return ", ".join(f"{x / per * 1e9:.1f}" for x in runs)


@njit(parallel=True, cache=True)
def _strengths(p, D, rate, q, out):
    for i in prange(p.size):
        out[i] = strength(p[i], D[i], rate[i], q)


def transcendental_time(m: Model, repeat):
    """Seconds per element of HJC's strength surface alone (hjc.strength: a logarithm for the rate and a power for the
    pressure, libm's, scalar: numba's LLVM has no vector library for them) over the elements' pressures, damages and
    equivalent rates of the present state, best of `repeat`, on the threads set: a bound below which the yielding
    state's element pass cannot go while each yielding element evaluates the surface."""
    ne = m.grid.elements
    p = np.ascontiguousarray(m.E[fe_state.P])
    D = np.ascontiguousarray(m.E[fe_state.DMG])
    rate = np.full(ne, 600.0)   # the plastic state's equivalent rate: sqrt(2/3 d:d) with d = a (1, 1, -2), a = 300/s
    out = np.empty(ne)
    _strengths(p, D, rate, m.q, out)
    n = max(20, int(2e6 / ne))
    best = min(_timed(lambda: [_strengths(p, D, rate, m.q, out) for _ in range(n)]) for _ in range(repeat))
    return best / n / ne


def last_level_cache():
    """Size in bytes of the largest cache of cpu0 as the kernel reports it, or None."""
    sizes = []
    for f in Path("/sys/devices/system/cpu/cpu0/cache").glob("index*/size"):
        text = f.read_text().strip()
        unit = {"K": 2**10, "M": 2**20, "G": 2**30}.get(text[-1:], 1)
        try:
            sizes.append(int(text.rstrip("KMG")) * unit)
        except ValueError:
            pass
    return max(sizes) if sizes else None


def vector_isa():
    """The widest x86 vector extension /proc/cpuinfo lists (numba's LLVM targets the host), or 'unknown'."""
    try:
        flags = next(line for line in Path("/proc/cpuinfo").read_text().splitlines() if line.startswith("flags")).split()
    except (OSError, StopIteration):
        return "unknown"
    return next((isa for isa in ("avx512f", "avx2", "avx", "sse4_2") if isa in flags), "unknown")


def step_bytes(m: Model):
    """Bytes one explicit step reads and writes, each array once (element pass, node pass, move): every row of
    E read, the rows the element pass stores for every element (state.STEP_STORES) written."""
    nodes = [m.r, m.z, m.vr, m.vz]
    element = m.E.nbytes + m.E[list(fe_state.STEP_STORES)].nbytes + m.F.nbytes + m.alive.nbytes + sum(a.nbytes for a in nodes)
    # the dashpot arrays are read on the grid's edges and in rows flagged in rowdash only
    g = m.grid
    edge = np.zeros((g.nz + 1, g.nr + 1), bool)
    edge[[0, -1], :] = True
    edge[:, [0, -1]] = True
    edge[m.rowdash != 0, :] = True
    # the velocities read and written, and the old ones stored (vr0, vz0, the size of vr, vz)
    node = m.F.nbytes + m.alive.nbytes + 3 * (m.vr.nbytes + m.vz.nbytes) + m.mass.nbytes + m.nstate.nbytes + m.fix.nbytes \
        + m.dash[:, edge.ravel()].nbytes + m.rowdash.nbytes
    move = 2 * (m.r.nbytes + m.z.nbytes) + m.vr.nbytes + m.vz.nbytes + m.nstate.nbytes
    return element + node + move


def _elastic_state(m: Model):
    """Random velocities of 0.05 m/s (no element yields, half of them in tension), on the axis v_r = 0."""
    rng = np.random.default_rng(0)
    m.vz[:] = 0.05 * rng.standard_normal(m.vz.size)
    m.vr[:] = 0.05 * rng.standard_normal(m.vr.size)
    m.vr[m.on_axis] = 0.0


def _elastic_time(spec: MeshSpec, repeat, element_steps=6e6):
    """Seconds per element-step of one full step (node pass, move, element pass), elastic state, best of repeat;
    the number of elements; the bytes one step moves."""
    m = Model(build(spec), HJC(), Controls())
    dt = 0.5 * m.dt
    m.ctl[fe_state.C_DT] = dt
    _elastic_state(m)
    span = m.span()

    def step():
        node_pass(span, m.F, m.alive, m.mass, m.nstate, m.fix, m.dash, m.rowdash, (m.zp, m.zs), dt, m.V, m.rows.f)
        move_nodes(span, m.X, m.V, m.nstate, dt)
        element_pass(span, m.X, m.V, m.kind, m.q, m.ctl, m.E, m.F, m.alive, m.rows.f, m.rows.i)

    step()
    ne = m.grid.elements
    n = max(20, int(element_steps / ne))
    best, runs = _best(step, n, repeat)
    return best / ne, [x / ne for x in runs], ne, step_bytes(m)


def _window_step_time(m: Model, steps, repeat):
    """Seconds per element-step of one explicit step over the active window of a copy of m (no contact), and the
    fraction of the window's live elements whose plastic strain or crush (mu_p) grows in the first such step:
    those take the scalar HJC update, the others the vectorised elastic one."""
    X, V, E, alive, F = (a.copy() for a in (m.X, m.V, m.E, m.alive, m.F))
    r, z, vr, vz = X[0], X[1], V[fe_state.VR], V[fe_state.VZ]
    rows = m.rows.copy()
    ctl = m.ctl.copy()
    dt = float(ctl[fe_state.C_DT])
    span = m.span()

    def step():
        node_pass(span, F, alive, m.mass, m.nstate, m.fix, m.dash, m.rowdash, (m.zp, m.zs), dt, V, rows.f)
        move_nodes(span, X, V, m.nstate, dt)
        element_pass(span, X, V, m.kind, m.q, ctl, E, F, alive, rows.f, rows.i)

    step()
    w = slice(m.j0 * m.nr, m.j1 * m.nr)
    grow = (E[fe_state.EPSP, w] > m.E[fe_state.EPSP, w]) | (E[fe_state.MUP, w] > m.E[fe_state.MUP, w])
    live = m.alive[w] == fe_state.LIVE
    flowing = float((grow & live).sum() / max(live.sum(), 1))
    per = (m.j1 - m.j0) * m.nr
    best, runs = _best(step, steps, repeat, _snapshot((r, z, vr, vz, E, alive, F)))
    return best / per, [x / per for x in runs], flowing


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--threads", type=int, default=2, help="numba threads (default 2)")
    ap.add_argument("--size", type=float, default=0.00875, help="element size in m (default 0.00875: 8 per shank radius)")
    ap.add_argument("--steps", type=int, default=200, help="steps per timed batch (default 200)")
    ap.add_argument("--repeat", type=int, default=3, help="batches per state; the best is printed (default 3)")
    ap.add_argument("--do1", action="store_true", help="also time the DO1 shot at the default mesh (needs results/fe/full)")
    ap.add_argument("--record", default="figures/timing/fe_speed.csv",
                    help="CSV the run's figures are appended to, one row per state (default figures/timing/fe_speed.csv; "
                         "'' for none)")
    args = ap.parse_args()
    numba.set_num_threads(args.threads)
    llc = last_level_cache()
    print(f"machine: {machine()}, {vector_isa()}, last-level cache "
          f"{'unknown' if llc is None else f'{llc / 2**20:.0f} MiB'}, numba {numba.__version__}, threads {numba.get_num_threads()}")
    if args.do1 and not Path(DO1).exists():
        raise SystemExit(f"--do1 times the pipeline's DO1 shot and needs {DO1}: "
                         f"run `snakemake -c2 {DO1}` first (its failure-strain calibration takes a few minutes)")
    bw0 = stream_triad()
    print(f"STREAM triad: {bw0 / 1e9:.1f} GB/s (measured again at the end)")
    # a DO1-like target (the core and graded far field of the default mesh, 2.5 m deep) in motion
    m = Model(build(MeshSpec(args.size, 0.21, 2.5, 1.2, 2.5, 1.1)), HJC(), Controls())
    base = (m.r.copy(), m.z.copy(), m.E.copy())
    dt = 0.5 * m.dt
    m.ctl[fe_state.C_DT] = dt
    span = m.span()

    def node():
        node_pass(span, m.F, m.alive, m.mass, m.nstate, m.fix, m.dash, m.rowdash, (m.zp, m.zs), dt, m.V, m.rows.f)

    def move():
        move_nodes(span, m.X, m.V, m.nstate, dt)

    def element():
        element_pass(span, m.X, m.V, m.kind, m.q, m.ctl, m.E, m.F, m.alive, m.rows.f, m.rows.i)

    def step():
        node()
        move()
        element()

    ne = m.grid.elements
    bytes_total = step_bytes(m)
    b = bytes_total / ne
    print(f"mesh: {ne} elements (h = {args.size * 1e3:.3g} mm); bytes per element-step {b:.0f}")
    # two states: elastic (random velocities of 0.05 m/s: no element yields, half of them in tension) and
    # plastic (a smooth deviatoric flow v_r = a r, v_z = -2 a z at a = 300/s: every element yields and
    # none erodes, the worst case: the full HJC update with its powers and logarithm in every element)
    times = {}
    for label in ("elastic", "plastic"):
        m.r[:], m.z[:], m.E[:] = base[0], base[1], base[2]
        m.alive[:] = fe_state.LIVE
        if label == "elastic":
            _elastic_state(m)
        else:
            m.vr[:] = 300.0 * m.r
            m.vz[:] = -600.0 * (m.z - m.z.mean())
            m.vr[m.on_axis] = 0.0
        step()
        restore = _snapshot((m.r, m.z, m.vr, m.vz, m.E, m.alive, m.F)) if label == "plastic" else None
        split, runs = _best_split((node, move, element), args.steps, args.repeat, restore)
        split = [x / ne for x in split]
        per = times[label] = sum(split)
        yielded = float((m.E[fe_state.EPSP] > 0).mean())
        live = float((m.alive == fe_state.LIVE).mean())
        print(f"{label} ({yielded:.0%} of the elements yielded, {live:.0%} live): {per * 1e9:.1f} ns per element-step "
              f"(runs {_runs(runs, ne)}); node pass {split[0] * 1e9:.1f}, move {split[1] * 1e9:.1f}, element pass "
              f"{split[2] * 1e9:.1f} ns")
        if label == "plastic":
            surface = times["strength surface alone (log, pow)"] = transcendental_time(m, args.repeat)
            print(f"  of which HJC's strength surface alone (libm log and pow, scalar) takes {surface * 1e9:.1f} ns per "
                  "element")
    # cache or memory? The arrays of the benchmark mesh (and of the DO1 window) fit in the last-level cache of the
    # hosts seen; the same elastic state over the same columns made deep enough to move at least twice that cache
    # (16 times as deep or more) moves them from and to memory every step
    deeper = max(16, math.ceil(2 * (llc or 0) / bytes_total))
    deep, deep_runs, nd, bd = _elastic_time(MeshSpec(args.size, 0.21, 2.5 * deeper, 1.2, 2.5 * deeper, 1.1), args.repeat)
    label = f"elastic, {deeper} times as deep"
    times[label] = deep
    print(f"{label} ({nd} elements, {bd / 2**20:.0f} MiB moved per step): {deep * 1e9:.1f} ns per "
          f"element-step (runs {_runs(deep_runs)}), {deep / times['elastic']:.2f} x the benchmark mesh's "
          f"({bytes_total / 2**20:.0f} MiB)")
    if args.do1:
        from penetration.fe import shot as fe_shot
        from penetration.fe.shot import run_shot

        spec, ref = do1_spec()
        # the DO1 state: at t = 6 ms of the shot, one full step (node pass, move, element pass over the window's
        # rows; no contact) timed on a copy of the model, per element of the window
        snap = {}
        solver_run = fe_shot.run

        def run_with_snapshot(model, projectile=None, callback=None):
            def cb(mm, t):
                callback(mm, t)
                if "t" not in snap and t >= 6e-3:
                    per, runs, flowing = _window_step_time(mm, args.steps, args.repeat)
                    snap.update(t=t, per=per, runs=runs, flowing=flowing, window=(mm.j1 - mm.j0) * mm.nr, yielded=float((mm.E[fe_state.EPSP, mm.j0 * mm.nr:mm.j1 * mm.nr] > 0).mean()))
            return solver_run(model, projectile, callback=cb)

        fe_shot.run = run_with_snapshot
        r = run_shot(spec)
        fe_shot.run = solver_run
        print(f"DO1 state at t = {snap['t'] * 1e3:.1f} ms ({snap['window']} elements in the window, {snap['yielded']:.0%} of them "
              f"yielded so far, {snap['flowing']:.1%} of the live ones flowing or crushing in a step): "
              f"{snap['per'] * 1e9:.1f} ns per element-step (runs {_runs(snap['runs'])})")
        times["DO1 window"] = snap["per"]
        s = r.summary()
        same = "the same bit for bit" if r.depth == ref["depth_m"] else f"DIFFERENT from the pipeline's {ref['depth_m']!r} m"
        print(f"DO1 at h = {ref['element_size'] * 1e3:.3g} mm, fs = {ref['failure_strain']:.4g}: depth {r.depth!r} m ({same} as "
              f"results/fe/full/do1), wall {r.wall_time:.1f} s "
              f"(target 60 s: {r.wall_time / 60:.2f} of it), {r.steps} steps, {r.elements} elements in the mesh, "
              f"{s['element_steps'] / r.wall_time / 1e6:.1f} M mesh element-steps/s")
        shares = ", ".join(f"{k} {v:.1%}" for k, v in r.dt_shares.items())
        print(f"DO1's time step: controlled by {shares} of the steps (solver.timestep criteria); the last step by "
              f"{r.dt_control}")
    # the floor from the higher of two bandwidths, one before and one after the timings (a neighbour's load on a
    # shared host lowers a STREAM measurement, and a lower bandwidth would flatter the ratio)
    bw1 = stream_triad()
    bw = max(bw0, bw1)
    floor = b / bw
    print(f"STREAM triad at the end: {bw1 / 1e9:.1f} GB/s; floor {floor * 1e9:.1f} ns (bytes per element-step over the higher "
          f"bandwidth, {bw / 1e9:.1f} GB/s). Targets: <= 30 ns and <= 2 x the floor")
    for label, per in times.items():
        if label.startswith("strength surface"):
            print(f"  {label}: {per * 1e9:.1f} ns = {per / floor:.2f} x the floor (a part of the plastic state's step)")
            continue
        met = [target for target, hit in (("30 ns", per <= 30e-9), ("2 x the floor", per <= 2 * floor)) if hit]
        print(f"  {label}: {per * 1e9:.1f} ns = {per / floor:.2f} x the floor (met: {', '.join(met) or 'neither'})")
    if args.record:
        record(args.record, times, floor, bw0, bw1, b, do1_wall=r.wall_time if args.do1 else None, threads=args.threads)


def do1_spec(path=DO1):
    """(the run spec, the record) of the pipeline's DO1 shot at ``path``: its element size, calibrated failure strain
    and mesh extent, to run it again."""
    from penetration.fe.level import run_spec
    from penetration.fe.shot import Settings, TargetSpec
    from penetration.pipeline.io import read_inference

    ref = json.loads(Path(path).read_text())
    nose = read_inference("results/geometry/double_ogive_table4.json")["nose"]
    return run_spec(nose, ref["mass"], ref["velocity"], HJC(), Settings(element_size=ref["element_size"]), TargetSpec(),
                    ref["expected_depth_m"], failure_strain=ref["failure_strain"]), ref


def record(path, times, floor, bw0, bw1, bytes_per, do1_wall, threads):
    """Append the run's figures to the CSV at path: one row per state, with the machine, date and commit."""
    import csv
    import datetime
    import subprocess

    commit = subprocess.run(["git", "rev-parse", "--short=12", "HEAD"], capture_output=True, text=True).stdout.strip()
    date = datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds")
    fields = ["date", "commit", "machine", "isa", "threads", "state", "ns_per_element_step", "floor_ns", "times_floor",
              "stream_before_GBs", "stream_after_GBs", "bytes_per_element_step", "do1_wall_s"]
    new = not Path(path).exists()
    with open(path, "a", newline="") as fh:
        w = csv.DictWriter(fh, fields, lineterminator="\n")
        if new:
            w.writeheader()
        for label, per in times.items():
            w.writerow({"date": date, "commit": commit, "machine": machine(), "isa": vector_isa(), "threads": threads,
                        "state": label, "ns_per_element_step": f"{per * 1e9:.2f}", "floor_ns": f"{floor * 1e9:.2f}",
                        "times_floor": f"{per / floor:.3f}", "stream_before_GBs": f"{bw0 / 1e9:.2f}",
                        "stream_after_GBs": f"{bw1 / 1e9:.2f}", "bytes_per_element_step": f"{bytes_per:.0f}",
                        "do1_wall_s": f"{do1_wall:.2f}" if do1_wall is not None and label == "DO1 window" else ""})
    print(f"recorded in {path}")


if __name__ == "__main__":
    main()
