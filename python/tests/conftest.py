# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# Shared fixtures: the source tree, the command line built beside the package, scene texts.
import os
import pathlib

import pytest

SRC = pathlib.Path(os.environ.get("DALEMBERT_SOURCE",
                                  pathlib.Path(__file__).resolve().parents[2]))
SCENES = SRC / "examples" / "scenes"
PYEX = SRC / "examples" / "python"

PENDULUM = """dim 2
param m = 1.5
param l = 0.7
param g = 9.81
coord theta q=0.3 v=0
particle bob mass=m
place bob = l*sin(theta); -l*cos(theta)
gravity 0 -g
run method=bs rtol=1e-10 t1=5 dt=0.05
"""

CART_PENDULUM = """dim 2
param m = 2
param l = 1.3
param g = 9.81
coord x q=0.6 v=0.5
coord y q=-1.1532562594670797 v=0.2601344622133306
particle p mass=m
place p = x; y
constraint rod parts=p = sqrt(x_p^2 + y_p^2) - l
gravity 0 -g
run method=auto rtol=1e-9 t1=3 dt=0.01
"""


@pytest.fixture
def cli():
    path = os.environ.get("DALEMBERT_CLI")
    if not path:
        pytest.skip("DALEMBERT_CLI not set (run under ctest)")
    return path
