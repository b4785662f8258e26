// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The library's own kernels for SUNDIALS serial vectors (private; nvec.c).
#ifndef DAL_NVEC_H
#define DAL_NVEC_H

#include <sundials/sundials_nvector.h>

/// Replace the element-wise operations of the serial vector v (N_VNew_Serial) by the library's
/// kernels, with the fused and vector-array operations SUNDIALS leaves unset by default.
/// Clones (N_VClone, as the integrators make their work vectors) inherit them. Same results
/// as SUNDIALS' serial operations (tests/test_nvec.c); the point is speed: a packaged
/// SUNDIALS built without optimization spends ~20 instructions per element of a linear sum
/// (measured in callgrind on Debian's 6.4.1), these ~2-4, and the fused forms sweep memory
/// once where the fallbacks sweep it once per term. Returns 0, or -1 when v is not a serial
/// vector (left unchanged).
int dal__nvec_fast(N_Vector v);

#endif
