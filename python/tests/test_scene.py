# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# Scene.load / Scene.parse / params: against the scene text and the library's own messages.
import numpy as np
import pytest

import dalembert as dal
from conftest import PENDULUM, SCENES


def test_load_names_and_run_line():
    sc = dal.Scene.load(SCENES / "driven_pendulum.scene")
    assert sc.coords == ["theta"] and sc.particles == ["bob"] and sc.constraints == []
    assert sc.dim == 2
    r = sc.run
    assert (r["t0"], r["t1"], r["dt"], r["method"], r["rtol"]) == (0.0, 100.0, 0.01, "bs", 1e-12)
    np.testing.assert_array_equal(sc.y0, [1.0, 0.0])


def test_params_mapping():
    sc = dal.Scene.parse(PENDULUM)
    assert dict(sc.params.items()) == {"m": 1.5, "l": 0.7, "g": 9.81}
    assert "l" in sc.params and len(sc.params) == 3
    sc.params["l"] = 2.0
    assert sc.params["l"] == 2.0
    # the rebuilt model uses it: the bob hangs at -l
    r = sc.solve((0, 0), y0=[0, 0], t_eval=[0.0], events=[])
    np.testing.assert_array_equal(r.positions[0, 0], [0.0, -2.0])


def test_unknown_param_lists_known():
    sc = dal.Scene.parse(PENDULUM)
    with pytest.raises(KeyError, match=r"'omega'.*known: m, l, g"):
        sc.params["omega"] = 6.0
    with pytest.raises(KeyError, match="known: m, l, g"):
        sc.params["omega"]


def test_param_refused_by_the_model_keeps_the_old():
    sc = dal.Scene.parse(PENDULUM)
    with pytest.raises(dal.ArgumentError, match="mass"):
        sc.params["m"] = -1.0
    assert sc.params["m"] == 1.5
    with pytest.raises(ValueError, match="finite"):
        sc.params["m"] = float("nan")
    with pytest.raises(TypeError):
        sc.params["m"] = "1"


def test_old_results_survive_a_rebuild():
    sc = dal.Scene.parse(PENDULUM)
    r = sc.solve(dense_output=True)
    y = r.sol(1.0)
    sc.params["l"] = 3.0
    np.testing.assert_array_equal(r.sol(1.0), y)


def test_parse_error_names_line_and_symbol():
    with pytest.raises(dal.ArgumentError, match=r"bad\.scene:7.*thet"):
        dal.Scene.parse(PENDULUM.replace("l*sin(theta)", "l*sin(thet)"), "bad.scene")


def test_load_missing_file():
    with pytest.raises(FileNotFoundError):
        dal.Scene.load("/nonexistent/x.scene")


def test_text_round_trip():
    sc = dal.Scene.load(SCENES / "bead_ring_above.scene")
    again = dal.Scene.parse(sc.text)
    assert again.text.splitlines()[1:] == sc.text.splitlines()[1:]
    a, b = sc.solve((0, 1)), again.solve((0, 1))
    np.testing.assert_array_equal(a.y, b.y)


def test_equations_text_and_latex():
    sc = dal.Scene.parse(PENDULUM)
    eq = sc.equations()
    assert "thetaddot = -g*sin(theta)/l" in eq.text
    latex = eq._repr_latex_()
    assert latex.startswith("$$") and "\\ddot{\\theta}" in latex and "\\sin" in latex


def test_params_given_by_formulas():
    sc = dal.Scene.parse(PENDULUM.replace("param g = 9.81", "param g = 9.81\nparam w = sqrt(g/l)"))
    assert sc.params["w"] == np.sqrt(9.81 / 0.7)
    sc.params["l"] = 2.0
    assert sc.params["w"] == np.sqrt(9.81 / 2.0)
