# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# Analyses against closed forms: linearization, modes, equilibria, state transition, Lyapunov,
# sections, sweeps.
import math

import numpy as np
import pytest

import dalembert as dal
from conftest import PENDULUM, SCENES


def test_linearize_pendulum_with_an_input():
    sc = dal.Scene.parse(PENDULUM)
    m, l, g = 1.5, 0.7, 9.81
    lin = sc.linearize(inputs=["force:theta"], q=[0.0], qdot=[0.0])
    np.testing.assert_allclose(lin.M, [[m * l * l]], rtol=1e-15)
    np.testing.assert_allclose(lin.K, [[m * g * l]], rtol=1e-15)
    np.testing.assert_allclose(lin.C, [[0.0]], atol=1e-15)
    A, B = lin
    np.testing.assert_allclose(A, [[0, 1], [-g / l, 0]], rtol=1e-14, atol=1e-15)
    np.testing.assert_allclose(B, [[0], [1 / (m * l * l)]], rtol=1e-14, atol=1e-15)
    # away from the bottom: K = m g l cos(theta)
    lin = sc.linearize(q=[0.4], qdot=[0.0])
    np.testing.assert_allclose(lin.K, [[m * g * l * math.cos(0.4)]], rtol=1e-14)


def test_bead_modes_and_equilibria_closed_form():
    sc = dal.Scene.load(SCENES / "bead_ring_above.scene")
    g, R, w = 9.81, 1.0, 5.0
    th = math.acos(g / (R * w * w))
    e = sc.equilibrium(q=[1.5], max_step=0.1)
    assert e.q[0] == pytest.approx(th, abs=1e-12)
    assert e.modes.verdict == "neutral"
    np.testing.assert_allclose(e.modes.omega2, [w * w * math.sin(th) ** 2], rtol=1e-12)
    found = sc.equilibria(starts=[[1.5], [-1.5], [0.0], [3.0]], max_step=0.1)
    qs = sorted(f.q[0] for f in found)
    np.testing.assert_allclose(qs, [-th, 0.0, th, math.pi], atol=1e-10)
    verdicts = {round(f.q[0], 6): f.modes.verdict for f in found}
    assert verdicts[0.0] == "unstable" and verdicts[round(th, 6)] == "neutral"
    # the bottom below the critical rate: omega^2 = g/R - w^2
    below = dal.Scene.load(SCENES / "bead_ring_below.scene")
    wb = below.params["omega"]
    mb = below.modes(q=[0.0], here=True)
    np.testing.assert_allclose(mb.omega2, [g / R - wb * wb], rtol=1e-12)


def test_state_transition_of_the_oscillator():
    sc = dal.Scene.load(SCENES / "sicm_oscillator.scene")
    w, t = math.sqrt(0.5), 2.0
    Phi, S, y1 = sc.state_transition(t, params=["mass:p"], rtol=1e-11)
    c, s = math.cos(w * t), math.sin(w * t)
    P1 = np.array([[c, s / w], [-w * s, c]])
    ref = np.zeros((4, 4))
    ref[np.ix_([0, 2], [0, 2])] = P1
    ref[np.ix_([1, 3], [1, 3])] = P1
    np.testing.assert_allclose(Phi, ref, atol=1e-9)
    # dx/dm of x = x0 cos(wt) + v0/w sin(wt), w = sqrt(k/m): dw/dm = -w/(2m)
    x0, v0, m = 1.0, 3.0, 2.0
    dxdw = -x0 * t * s + v0 * (t * c / w - s / w ** 2)
    assert S[0, 0] == pytest.approx(dxdw * (-w / (2 * m)), abs=1e-8)


def test_lyapunov_of_the_oscillator_is_zero_within_its_error():
    sc = dal.Scene.load(SCENES / "sicm_oscillator.scene")
    ex, err = sc.lyapunov(t_end=200, renorm=1.0, nexp=2)
    assert np.all(np.abs(ex) < 0.05) and np.all(err >= 0)


def test_sections():
    sc = dal.Scene.load(SCENES / "driven_pendulum.scene")
    T = 2 * math.pi / sc.params["omega"]
    t, y = sc.section((0, 20 * T), rtol=1e-10)
    np.testing.assert_allclose(t, T * np.arange(t.size), rtol=1e-14)
    assert t.size == 21 and y.shape == (21, 2)
    ts, ys = sc.section((0, 30), surface=True, rtol=1e-10)
    assert ts.size > 3 and np.max(np.abs(np.sin(ys[:, 0]))) < 1e-9


def test_sweep_equilibrium_is_the_pitchfork():
    sc = dal.Scene.load(SCENES / "bead_ring_above.scene")
    ws = np.linspace(1.0, 6.0, 11)
    res1 = sc.sweep({"omega": ws}, what="equilibrium", y0=[1.5, 0.0], threads=1, max_step=0.1)
    res2 = sc.sweep({"omega": ws}, what="equilibrium", y0=[1.5, 0.0], threads=2, max_step=0.1)
    np.testing.assert_array_equal(res1.y, res2.y)
    g = 9.81
    ref = np.where(ws > math.sqrt(g), np.arccos(np.minimum(1, g / np.maximum(ws, 1e-9) ** 2)),
                   0.0)
    assert np.all(res1.status == 0)
    np.testing.assert_allclose(res1.y[:, 0], ref, atol=1e-10)
    assert res1.verdict[0] == "neutral" and res1.verdict[-1] == "neutral"


def test_sweep_final_states_both_routes():
    sc = dal.Scene.parse(PENDULUM)
    gs = [9.0, 9.81, 11.0]
    a = sc.sweep({"g": gs}, t1=1.0, threads=2)
    b = sc.sweep({"gravity:1": [-x for x in gs]}, t1=1.0, threads=2)
    np.testing.assert_allclose(a.y, b.y, rtol=1e-12, atol=1e-14)
    # the elliptic closed form: theta = 2 asin(k sn(K - w t | k^2)), k = sin(theta0 / 2)
    from scipy.special import ellipj, ellipk
    k = math.sin(0.15)
    w = np.sqrt(np.array(gs) / 0.7)
    sn = ellipj(ellipk(k * k) - w * 1.0, k * k)[0]
    np.testing.assert_allclose(a.y[:, 0], 2 * np.arcsin(k * sn), rtol=0, atol=1e-8)
    assert a.values.shape == (3, 1) and np.all(a.status == 0)


def test_a_failing_point_does_not_stop_the_sweep():
    sc = dal.Scene.parse(PENDULUM)
    s = sc.sweep({"m": [1.0, -1.0, 2.0]}, t1=0.5, threads=2)
    assert list(s.status == 0) == [True, False, True]
    assert "mass" in s.messages[1] and np.all(np.isnan(s.y[1]))
    # the mass does not change a pendulum's motion: the other points agree bit for bit
    np.testing.assert_array_equal(s.y[0], s.y[2])
