#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# The Python route's costs (docs/performance.md "Python"): (1) its overhead over the same run
# in C (SICM's driven pendulum, 10 s, 1,000 outputs; and a small call), (2) against SymPy's
# LagrangesMethod + lambdify + SciPy's solve_ivp at its best method on the driven pendulum,
# the double pendulum and an 8-link chain, at position errors 1e-4, 1e-8, 1e-11 at t = 10.
# Timings are minima of interleaved repetitions (wall clock, one thread).
#   PYTHONPATH=build/python/pkg /usr/bin/python3 bench/python_bench.py [build dir] [--quick]
import math
import os
import pathlib
import subprocess
import sys
import time

import numpy as np

import dalembert as dal

ROOT = pathlib.Path(__file__).resolve().parents[1]
BUILD = pathlib.Path(next((a for a in sys.argv[1:] if not a.startswith("--")), ROOT / "build"))
QUICK = "--quick" in sys.argv
DRIVEN = ROOT / "examples" / "scenes" / "driven_pendulum.scene"


def best_of(fn, reps):
    b = math.inf
    for _ in range(reps):
        t0 = time.perf_counter()
        fn()
        b = min(b, time.perf_counter() - t0)
    return b


# ---------------------------------------------------------------------------------------------
# 1. overhead over the same run in C


def overhead():
    exe = BUILD / "python_overhead"
    subprocess.run(["cc", "-O2", "-std=c11", f"-I{ROOT / 'include'}",
                    str(ROOT / "bench" / "python_overhead.c"), f"-L{BUILD}", "-ldalembert",
                    f"-Wl,-rpath,{BUILD}", "-lm", "-o", str(exe)], check=True)
    sc = dal.Scene.load(DRIVEN)
    rounds, reps = (3, 5) if QUICK else (7, 20)
    print("# overhead: SICM's driven pendulum (Bulirsch-Stoer, rtol 1e-12 as its run line), "
          f"min of {rounds} interleaved rounds x {reps} repetitions")
    print("case,outputs,c_seconds,python_seconds,ratio")
    for case, t1, dt in (("10 s, 1,000 outputs", 10.0, 0.01), ("small call", 0.01, 0.01)):
        c, p = math.inf, math.inf
        for _ in range(rounds):
            out = subprocess.run([str(exe), str(DRIVEN), str(t1), str(dt), str(reps)],
                                 check=True, capture_output=True, text=True).stdout
            c = min(c, float(out))
            p = min(p, best_of(lambda: sc.solve((0, t1), dt=dt, events=[]), reps))
        r = sc.solve((0, t1), dt=dt, events=[])
        print(f"{case},{r.t.size},{c:.6g},{p:.6g},{p / c:.3f}")


# ---------------------------------------------------------------------------------------------
# 2. against SymPy + lambdify + solve_ivp


def chain_scene(n, th0):
    lines = ["dim 2", "param g = 9.81", "param l = 1"]
    lines += [f"coord p{k} q={th0} v=0" for k in range(n)]
    lines += [f"particle b{k} mass=1" for k in range(n)]
    lines.append("place b0 = l*sin(p0); -l*cos(p0)")
    lines += [f"place b{k} parent=b{k - 1} = x_b{k - 1} + l*sin(p{k}); y_b{k - 1} - l*cos(p{k})"
              for k in range(1, n)]
    lines.append("gravity 0 -g")
    return "\n".join(lines) + "\n"


DOUBLE = """dim 2
param g = 9.81
coord p0 q=0.5 v=0
coord p1 q=0.3 v=0
particle a mass=1
particle b mass=1
place a = sin(p0); -cos(p0)
place b = sin(p0) + sin(p1); -cos(p0) - cos(p1)
gravity 0 -g
"""


def sympy_model(nq, positions, masses, g, y0):
    """LagrangesMethod on L = T - U of the particles' positions(q, t); M and F lambdified."""
    import sympy as sp
    from sympy.physics.mechanics import LagrangesMethod, dynamicsymbols
    t = dynamicsymbols._t
    q = dynamicsymbols(f"q0:{nq}")
    pos = positions(q, t, sp)
    T = sum(m / 2 * (sp.diff(x, t) ** 2 + sp.diff(y, t) ** 2) for m, (x, y) in zip(masses, pos))
    U = sum(m * g * y for m, (x, y) in zip(masses, pos))
    lm = LagrangesMethod(T - U, q)
    lm.form_lagranges_equations()
    qs, us = sp.symbols(f"x0:{nq}"), sp.symbols(f"u0:{nq}")
    sub = {sp.diff(qi, t): ui for qi, ui in zip(q, us)}
    sub2 = dict(zip(q, qs))
    M = lm.mass_matrix.subs(sub).subs(sub2)
    F = lm.forcing.subs(sub).subs(sub2)
    Mf = sp.lambdify((t, qs, us), M, "numpy")
    Ff = sp.lambdify((t, qs, us), F, "numpy")

    def rhs(tt, y):
        qq, uu = y[:nq], y[nq:]
        acc = np.linalg.solve(np.asarray(Mf(tt, qq, uu), float),
                              np.asarray(Ff(tt, qq, uu), float).ravel())
        return np.concatenate([uu, acc])
    return rhs, np.asarray(y0, float)


def models():
    import math as m_
    w = 2 * m_.sqrt(9.8)
    out = []
    # SICM's driven pendulum: m = l = 1, g = 9.8, a = 0.1, omega = 2 sqrt(g), from 1 rad
    rhs, y0 = sympy_model(1, lambda q, t, sp: [(sp.sin(q[0]),
                                                 0.1 * sp.cos(w * t) - sp.cos(q[0]))],
                          [1], 9.8, [1.0, 0.0])
    out.append(("driven pendulum", dal.Scene.load(DRIVEN), rhs, y0))
    rhs, y0 = sympy_model(2, lambda q, t, sp: [
        (sp.sin(q[0]), -sp.cos(q[0])),
        (sp.sin(q[0]) + sp.sin(q[1]), -sp.cos(q[0]) - sp.cos(q[1]))], [1, 1], 9.81,
        [0.5, 0.3, 0, 0])
    out.append(("double pendulum", dal.Scene.parse(DOUBLE), rhs, y0))

    def chain(q, t, sp):
        x = y = 0
        ps = []
        for qi in q:
            x, y = x + sp.sin(qi), y - sp.cos(qi)
            ps.append((x, y))
        return ps
    rhs, y0 = sympy_model(8, chain, [1] * 8, 9.81, [0.3] * 8 + [0] * 8)
    out.append(("8-link chain", dal.Scene.parse(chain_scene(8, 0.3)), rhs, y0))
    return out


def compare():
    from scipy.integrate import solve_ivp
    T_END = 10.0
    targets = (1e-4, 1e-8, 1e-11)
    rtols = [10.0 ** (-k / 2) for k in range(6, 27)]
    methods = ("RK45", "DOP853", "LSODA")
    rounds = 3 if QUICK else 5
    print()
    print("# against SymPy LagrangesMethod + lambdify + SciPy solve_ivp, error = max |q(10) - "
          "q_ref(10)|; each side its cheapest setting reaching the error (SciPy: best of "
          f"{', '.join(methods)}; dalembert: method auto), min of {rounds} interleaved runs")
    print("scene,target,scipy_method,scipy_rtol,scipy_error,scipy_seconds,dal_rtol,dal_error,"
          "dal_seconds,ratio")
    for name, sc, rhs, y0 in models():
        n = y0.size // 2
        ref = sc.solve((0, T_END), y0=y0, method="bs", rtol=1e-14, t_eval=[T_END],
                       events=[]).q[:, -1]
        chk = solve_ivp(rhs, (0, T_END), y0, method="DOP853", rtol=2.3e-14, atol=1e-14).y[:n, -1]
        print(f"# {name}: reference (dalembert BS at rtol 1e-14) vs SciPy DOP853 at its tightest: "
              f"{np.max(np.abs(ref - chk)):.2g}")

        def run_scipy(meth, rt):
            return solve_ivp(rhs, (0, T_END), y0, method=meth, rtol=rt, atol=rt)

        def run_dal(rt):
            return sc.solve((0, T_END), y0=y0, method="auto", rtol=rt, t_eval=[T_END],
                            events=[])

        # the loosest tolerance of each kind that reaches each target (cost falls with it)
        pick_s, pick_d = {}, {}
        for meth in methods:
            first = {}
            for rt in rtols:
                t0 = time.perf_counter()
                r = run_scipy(meth, rt)
                el = time.perf_counter() - t0
                err = np.max(np.abs(r.y[:n, -1] - ref))
                for tg in targets:
                    if err <= tg and tg not in first:
                        first[tg] = (meth, rt, err, el)
                if err <= min(targets) or el > 20:
                    break
            for tg, v in first.items():
                if tg not in pick_s or v[3] < pick_s[tg][3]:
                    pick_s[tg] = v
        for rt in rtols:
            r = run_dal(rt)
            err = np.max(np.abs(r.q[:, -1] - ref))
            for tg in targets:
                if err <= tg and tg not in pick_d:
                    pick_d[tg] = (rt, err)
            if err <= min(targets):
                break
        for tg in targets:
            if tg not in pick_s or tg not in pick_d:
                print(f"{name},{tg:g},unreached,,,,,,,")
                continue
            meth, rs, es, _ = pick_s[tg]
            rd, ed = pick_d[tg]
            ts, td = math.inf, math.inf
            for _ in range(rounds):
                ts = min(ts, best_of(lambda: run_scipy(meth, rs), 1))
                td = min(td, best_of(lambda: run_dal(rd), 3))
            print(f"{name},{tg:g},{meth},{rs:.3g},{es:.2g},{ts:.4g},{rd:.3g},{ed:.2g},{td:.4g},"
                  f"{ts / td:.0f}", flush=True)


if __name__ == "__main__":
    overhead()
    compare()
