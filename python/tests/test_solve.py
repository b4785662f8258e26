# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# Scene.solve: bit for bit the command line's run, closed forms, events, dense output, failures.
import math
import subprocess

import numpy as np
import pytest

import dalembert as dal
from conftest import CART_PENDULUM, PENDULUM, PYEX, SCENES


def cli_run(cli, text, tmp_path):
    path = tmp_path / "s.scene"
    path.write_text(text)
    out = tmp_path / "s.csv"
    subprocess.run([cli, "run", str(path), "-o", str(out), "--no-progress"], check=True)
    return np.loadtxt(out, delimiter=",", skiprows=1, ndmin=2)


def shorten(text, t1):
    return "\n".join(
        " ".join(f"t1={t1}" if w.startswith("t1=") else w for w in ln.split(" "))
        if ln.startswith("run ") else ln for ln in text.splitlines()) + "\n"


SEEDS = [(SCENES / "driven_pendulum.scene", 10), (SCENES / "bead_ring_above.scene", 10),
         (SCENES / "bead_ring_below.scene", 10), (SCENES / "sicm_oscillator.scene", 10),
         (PYEX / "cartesian_double_pendulum.scene", 3)]


@pytest.mark.parametrize("path,t1", SEEDS, ids=[p[0].stem for p in SEEDS])
def test_bit_identical_to_the_command_line(cli, tmp_path, path, t1):
    text = shorten(path.read_text(), t1)
    ref = cli_run(cli, text, tmp_path)
    r = dal.Scene.parse(text).solve()
    n = r.q.shape[0]
    assert r.success and r.t.size == ref.shape[0]
    np.testing.assert_array_equal(r.t, ref[:, 0])
    np.testing.assert_array_equal(r.q, ref[:, 1:1 + n].T)
    np.testing.assert_array_equal(r.qdot, ref[:, 1 + n:1 + 2 * n].T)
    np.testing.assert_array_equal(r.energy, ref[:, 1 + 2 * n])
    np.testing.assert_array_equal(r.energies["h"], ref[:, 2 + 2 * n])


def test_oscillator_closed_form():
    sc = dal.Scene.load(SCENES / "sicm_oscillator.scene")
    te = np.linspace(0, 10, 37)
    r = sc.solve((0, 10), t_eval=te, rtol=1e-11)
    w = math.sqrt(1 / 2)  # k / m
    x0, v0 = np.array([1.0, 2.0]), np.array([3.0, 4.0])
    q = x0[:, None] * np.cos(w * te) + v0[:, None] / w * np.sin(w * te)
    qd = -x0[:, None] * w * np.sin(w * te) + v0[:, None] * np.cos(w * te)
    np.testing.assert_array_equal(r.t, te)
    assert np.max(np.abs(r.q - q)) < 16 * 1e-11 * 10
    assert np.max(np.abs(r.qdot - qd)) < 16 * 1e-11 * 10
    # positions are the coordinates; E = 1/2 m v^2 + 1/2 k x^2 at every output
    np.testing.assert_array_equal(r.positions[:, 0, :], r.q.T)
    E = 0.5 * 2 * np.sum(r.qdot ** 2, 0) + 0.5 * np.sum(r.q ** 2, 0)
    np.testing.assert_allclose(r.energy, E, rtol=1e-14)
    assert r.stats["method"] == "bs" and r.stats["formulation"] == "ode"
    assert r.stats["steps"] > 0 and r.status == 0 and r.message


def test_pendulum_positions_and_energy_identities():
    sc = dal.Scene.parse(PENDULUM)
    r = sc.solve()
    th, thd = r.q[0], r.qdot[0]
    m, l, g = 1.5, 0.7, 9.81
    np.testing.assert_allclose(r.positions[:, 0, 0], l * np.sin(th), rtol=0, atol=1e-15)
    np.testing.assert_allclose(r.positions[:, 0, 1], -l * np.cos(th), rtol=0, atol=1e-15)
    E = 0.5 * m * l ** 2 * thd ** 2 - m * g * l * np.cos(th)
    np.testing.assert_allclose(r.energy, E, rtol=1e-14)
    assert np.ptp(r.energy) < 1e-9 * abs(r.energy[0])
    assert r.multipliers.shape == (0, r.t.size)


def test_dae_multipliers_are_the_rod_tension():
    sc = dal.Scene.parse(CART_PENDULUM)
    r = sc.solve()
    assert r.stats["formulation"] == "ggl"
    x, y = r.q
    m, l, g = 2.0, 1.3, 9.81
    # tension m (|v|^2 / l + g cos theta), cos theta = -y / l; lambda = -tension
    tension = m * (np.sum(r.qdot ** 2, 0) / l - g * y / l)
    np.testing.assert_allclose(-r.multipliers[0], tension, rtol=1e-6)
    np.testing.assert_allclose(np.hypot(x, y), l, rtol=0, atol=1e-8)


def test_dense_output_matches_the_outputs():
    sc = dal.Scene.parse(PENDULUM)
    r = sc.solve(dense_output=True)
    y = r.sol(r.t)
    assert y.shape == (2, r.t.size)
    assert np.max(np.abs(y - r.y)) < 1e-12
    assert r.sol(1.234).shape == (2,)
    with pytest.raises(dal.ArgumentError, match="span"):
        r.sol(6.0)
    # recording changes no output (solve.h): bit for bit the run without it
    np.testing.assert_array_equal(sc.solve().y, r.y)


def test_t_eval_ends_at_t1_and_keeps_only_t_eval():
    sc = dal.Scene.parse(PENDULUM)
    r = sc.solve((0, 5), t_eval=[0.5, 1.0], dense_output=True)
    np.testing.assert_array_equal(r.t, [0.5, 1.0])
    assert r.t_final == 5.0 and r.sol.t_max == 5.0
    # the same steps as the grid run: the outputs agree with it within the dense output
    g = sc.solve((0, 5), dt=0.5)
    assert np.max(np.abs(g.y[:, 1:3] - r.y)) < 1e-12


def test_events_of_the_scene_and_by_formula():
    sc = dal.Scene.load(SCENES / "driven_pendulum.scene")
    r = sc.solve((0, 20), rtol=1e-10)
    assert r.event_names == ["up"] and r.t_events[0].size > 3
    # the section sin(theta) = 0 rising: sin(q) there is 0 and the rate is positive
    y = r.y_events[0]
    assert np.max(np.abs(np.sin(y[:, 0]))) < 1e-9
    assert np.all(np.cos(y[:, 0]) * y[:, 1] > 0)
    r2 = sc.solve((0, 20), rtol=1e-10, events=[{"g": "sin(theta)", "direction": 1,
                                                  "name": "mine"}])
    assert r2.event_names == ["mine"]
    np.testing.assert_array_equal(r2.t_events[0], r.t_events[0])


def test_terminal_event_stops_the_run():
    sc = dal.Scene.parse(PENDULUM)
    # released at 0.3 rad from rest: theta = 0 first at a quarter period, T/4 by the elliptic
    # integral: T = 4 sqrt(l/g) K(sin^2(theta0/2))
    from scipy.special import ellipk
    T = 4 * math.sqrt(0.7 / 9.81) * ellipk(math.sin(0.15) ** 2)
    r = sc.solve(events={"g": "theta", "terminal": True}, rtol=1e-12)
    assert r.status == 2 and r.success
    assert abs(r.t_final - T / 4) < 1e-10 and abs(r.t_events[0][0] - T / 4) < 1e-10
    assert r.t[-1] <= r.t_final


def test_failure_raises_with_the_partial_result():
    sc = dal.Scene.parse(PENDULUM)
    with pytest.raises(dal.IntegrationError) as ei:
        sc.solve((0, 5), method="dopri5", max_steps=3)
    e = ei.value
    assert e.status == -10 and e.name == "DAL_E_MAXSTEPS" and "step" in e.message
    r = e.result
    assert not r.success and r.t.size >= 1 and r.t_final > 0
    assert r.t[-1] <= r.t_final < 5


def test_methods_are_honoured():
    sc = dal.Scene.parse(PENDULUM)
    for name in ("dopri5", "fehlberg78", "bs", "adams", "bdf"):
        r = sc.solve((0, 1), method=name, rtol=1e-8)
        assert r.stats["method"] == name
    r = sc.solve((0, 1), method="rk4", fixed_step=1e-3)
    assert r.stats["method"] == "rk4"


def test_a_single_output_agrees_with_dal_advance():
    # the sweep advances each point by dal_advance without hooks; solve's run has a monitor
    # and the cancel hook (Bulirsch-Stoer in its dense mode): equal within the tolerance
    sc = dal.Scene.parse(PENDULUM)
    one = sc.solve((0, 2), t_eval=[2.0])
    swept = sc.sweep({"g": [9.81]}, t1=2.0)
    assert one.t.size == 1 and one.t[0] == 2.0
    assert np.max(np.abs(one.y[:, 0] - swept.y[0])) < 1e-9
    np.testing.assert_array_equal(one.y_final, one.y[:, 0])


def test_progress_bar(capsys):
    sc = dal.Scene.parse(PENDULUM)
    r = sc.solve((0, 5), progress=True)
    err = capsys.readouterr().err
    assert err.endswith("100.0%  t = 5\n") and r.success
    with pytest.raises(TypeError, match="progress"):
        sc.solve(progress=1)
