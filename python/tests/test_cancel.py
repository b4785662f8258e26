# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# Long runs: Ctrl-C (SIGINT) stops a solve within 0.1 s and keeps what was computed; the GIL
# is released while C works.
import os
import signal
import subprocess
import sys
import textwrap
import threading
import time

import numpy as np

import dalembert as dal
from conftest import SCENES

CHILD = textwrap.dedent("""
    import sys, time
    import numpy as np
    import dalembert as dal
    sc = dal.Scene.load(sys.argv[1])
    what = sys.argv[2]
    print("start", flush=True)
    try:
        if what == "solve":
            sc.solve((0, 1e6), rtol=1e-12, dt=100.0)
        else:
            sc.lyapunov(t_end=1e6)
        print("not cancelled", flush=True)
    except dal.Cancelled as e:
        t = time.monotonic()
        if what == "solve":
            r = e.result
            # what was kept: the outputs up to the last accepted step, that step's state
            again = sc.solve((0, r.t_final), rtol=1e-12, dt=100.0)
            k = r.t.size
            ok = (r.status == dal._core.lib.DAL_CANCELLED and not r.success and k >= 1
                  and r.t[-1] <= r.t_final and np.array_equal(again.t[:k], r.t)
                  and np.max(np.abs(again.y[:, :k] - r.y)) < 1e-9
                  and np.max(np.abs(again.y_final - r.y_final)) < 1e-9)
            print(f"cancelled {t:.6f} {r.t_final} {k} {ok}", flush=True)
        else:
            print(f"cancelled {t:.6f} 1 1 True", flush=True)
""")


def run_and_interrupt(what):
    env = dict(os.environ)
    p = subprocess.Popen([sys.executable, "-c", CHILD, str(SCENES / "driven_pendulum.scene"),
                          what], stdout=subprocess.PIPE, text=True, env=env)
    try:
        assert p.stdout.readline().strip() == "start"
        time.sleep(0.5)
        t_sig = time.monotonic()
        p.send_signal(signal.SIGINT)
        line = p.stdout.readline().split()
    finally:
        p.kill()
        p.wait()
    assert line[0] == "cancelled", line
    return float(line[1]) - t_sig, float(line[2]), int(line[3]), line[4] == "True"


def test_ctrl_c_stops_a_solve_within_0_1_s_keeping_the_rows():
    dt, t_final, rows, ok = run_and_interrupt("solve")
    assert dt < 0.1, f"stopped {dt:.3f} s after SIGINT"
    assert t_final > 0 and rows >= 1 and ok


def test_ctrl_c_stops_lyapunov_within_0_1_s():
    dt, *_ = run_and_interrupt("lyapunov")
    assert dt < 0.1, f"stopped {dt:.3f} s after SIGINT"


def test_the_gil_is_released_during_a_solve():
    sc = dal.Scene.load(SCENES / "driven_pendulum.scene")
    ticks = []
    done = threading.Event()

    def ticker():
        while not done.is_set():
            ticks.append(time.monotonic())
            time.sleep(0.001)

    def solve():
        sc.solve((0, 300), rtol=1e-12, dt=1.0)

    t0 = time.monotonic()
    solve()
    alone = time.monotonic() - t0
    th = threading.Thread(target=ticker)
    th.start()
    w = threading.Thread(target=solve)  # a worker thread: the C call runs without the GIL
    w.start()
    w.join()
    done.set()
    th.join()
    # the ticker kept running during the solve: no gap near the solve's length
    gaps = np.diff(ticks)
    assert alone > 0.05 and gaps.max() < 0.5 * alone, (alone, gaps.max())
