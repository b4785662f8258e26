// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The library's SUNDIALS side (private): its own kernels for serial vectors (nvec.c) and the
// setup the ODE methods in ARKODE and CVODE share (sundials.c).
#ifndef DAL_INTEGRATE_NVEC_H
#define DAL_INTEGRATE_NVEC_H

#include <sundials/sundials_context.h>
#include <sundials/sundials_nvector.h>

#include "families.h"

/// Replace the element-wise operations of the serial vector v (N_VNew_Serial) by the library's
/// kernels, with the fused and vector-array operations SUNDIALS leaves unset by default.
/// Clones (N_VClone, as the integrators make their work vectors) inherit them. Same results
/// as SUNDIALS' serial operations (tests/test_nvec.c); the point is speed: a packaged
/// SUNDIALS built without optimization spends ~20 instructions per element of a linear sum
/// (measured in callgrind on Debian's 6.4.1), these ~2-4, and the fused forms sweep memory
/// once where the fallbacks sweep it once per term. Returns 0, or -1 when v is not a serial
/// vector (left unchanged).
int dal__nvec_fast(N_Vector v);

/// The context and vectors of an ODE method in ARKODE or CVODE: y (loaded with ig->y), the
/// local error estimate, the error weights and the interpolation output, all of size ny.
typedef struct dal_sun_vecs {
  SUNContext ctx;
  N_Vector y, ele, ewt, dky;
} dal_sun_vecs;
/// create them for ig (y and dky with the library's kernels; SUNDIALS clones its work
/// vectors from y); who names the integrator in the out-of-memory message. 0 or a status with
/// the state's message set; what was made is freed by dal__sun_vecs_free
int dal__sun_vecs_create(dal_ode_integ *ig, dal_sun_vecs *v, const char *who);
void dal__sun_vecs_free(dal_sun_vecs *v);

/// The setters of one SUNDIALS package (ERKStep..., CVode...) for dal__sun_set_tols
typedef struct dal_sun_setters {
  int (*tolerances)(void *mem, sunrealtype rtol, sunrealtype atol);
  int (*init_step)(void *mem, sunrealtype h);
  int (*min_step)(void *mem, sunrealtype h);
  int (*max_step)(void *mem, sunrealtype h);
} dal_sun_setters;
/// the local tolerances (ig->rtol, ig->atol) and the step bounds opts.h0, hmin, hmax (where
/// > 0) on the integrator mem; 0 or the first failing setter's code
int dal__sun_set_tols(void *mem, const dal_sun_setters *set, const dal_ode_integ *ig);

#endif
