# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
"""dalembert: point-particle mechanics with holonomic constraints, from Python.

Scenes (the C library's scene files) are read, solved and analysed in C; Python checks the
arguments and hands back numpy arrays. docs/python.md is the guide.
"""
from ._core import (METHODS, FORMULATIONS, ArgumentError, Builder, CallbackError, Cancelled,
                    DenseSolution, Equations, Equilibrium, Error, IntegrationError,
                    Linearization, ModelError, Modes, Params, ResourceError, Result, Scene,
                    SweepResult, version)

__all__ = ["Scene", "Builder", "Params", "Result", "DenseSolution", "Equations", "Equilibrium", "Modes",
           "Linearization", "SweepResult", "Error", "ArgumentError", "ModelError",
           "IntegrationError", "CallbackError", "ResourceError", "Cancelled", "METHODS",
           "FORMULATIONS", "version"]
__version__ = "0.3.0"
