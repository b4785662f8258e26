# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# The builder writes the scene grammar: the same model as the scene text, bit for bit.
import numpy as np
import pytest

import dalembert as dal
from conftest import CART_PENDULUM, PENDULUM


def test_pendulum_by_the_builder_is_the_scene():
    b = (dal.Builder(2).param("m", 1.5).param("l", 0.7).param("g", 9.81)
         .coord("theta", q=0.3, v=0).particle("bob", mass="m")
         .place("bob", "l*sin(theta)", "-l*cos(theta)").gravity(0, "-g")
         .run(method="bs", rtol=1e-10, t1=5, dt=0.05))
    a, ref = b.build().solve(), dal.Scene.parse(PENDULUM).solve()
    np.testing.assert_array_equal(a.y, ref.y)


def test_constraint_spring_damper_events():
    b = (dal.Builder(2).param("m", 2).param("l", 1.3).param("g", 9.81)
         .coord("x", q=0.6, v=0.5).coord("y", q=-1.1532562594670797, v=0.2601344622133306)
         .particle("p", mass="m").place("p", "x", "y")
         .constraint("rod", "sqrt(x_p^2 + y_p^2) - l", parts=["p"]).gravity(0, "-g")
         .run(rtol=1e-9, t1=3, dt=0.01))
    np.testing.assert_array_equal(b.build().solve().y, dal.Scene.parse(CART_PENDULUM).solve().y)
    # a damped spring to an anchor, an event, a section: the model reads back and runs
    sc = (dal.Builder(2).coord("x", q=1).coord("y").particle("p", mass=1)
          .place("p", "x", "y").spring("p", anchor=(0, 0), k=4, L=0)
          .damper("p", anchor=(0, 0), c=0.1).event("cross", "x", direction=-1)
          .strobe("s", "pi").build())
    r = sc.solve((0, 5))
    # x = exp(-a t) (cos(wd t) + a / wd sin(wd t)), a = c / 2m, wd = sqrt(k/m - a^2): first
    # zero where tan(wd t) = -wd / a
    a, wd = 0.05, np.sqrt(4 - 0.05 ** 2)
    t0 = (np.pi - np.arctan(wd / a)) / wd
    assert r.event_names == ["cross"] and abs(r.t_events[0][0] - t0) < 1e-7


def test_builder_refuses_before_c():
    b = dal.Builder(2)
    with pytest.raises(ValueError, match="name"):
        b.param("2x", 1)
    with pytest.raises(ValueError, match="formula"):
        b.coord("x", q="1 + a")
    with pytest.raises(ValueError, match="finite"):
        b.param("a", float("nan"))
    with pytest.raises(ValueError, match="dim"):
        dal.Builder(4)
    with pytest.raises(ValueError, match="anchor"):
        b.spring("p", k=1)
    # what only the model can know comes back from the C reader, naming the line
    b = dal.Builder(2).coord("x").particle("p").place("p", "x", "yy")
    with pytest.raises(dal.ArgumentError, match=r"<builder>:4.*yy"):
        b.build()
