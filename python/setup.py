# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# pip install --no-build-isolation ./python: the package against an installed C library,
# found by pkg-config (dalembert.pc) or DALEMBERT_PREFIX; offline with Debian's setuptools/cffi.
from setuptools import setup

setup(
    name="dalembert",
    version="0.3.0",
    description="Point-particle mechanics with holonomic constraints (the dalembert C library)",
    license="MIT",
    packages=["dalembert"],
    cffi_modules=["dalembert/_build.py:ffi"],
    install_requires=["cffi>=1.12", "numpy>=1.17"],
    python_requires=">=3.8",
    zip_safe=False,
)
