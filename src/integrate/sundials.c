// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The SUNDIALS setup the ODE methods in ARKODE and CVODE share: the context and the serial
// vectors with the library's kernels, the tolerances and the step bounds.
#include <nvector/nvector_serial.h>
#include <string.h>

#include "integrate.h"
#include "nvec.h"

int dal__sun_vecs_create(dal_ode_integ *ig, dal_sun_vecs *v, const char *who) {
  dal_state *st = ig->st;
  int flag = SUNContext_Create(NULL, &v->ctx);
  if (flag) return DAL_FAIL(st, DAL_E_SOLVER, "SUNContext_Create failed (%d)", flag);
  v->y = N_VNew_Serial(ig->ny, v->ctx);
  v->ele = N_VNew_Serial(ig->ny, v->ctx);
  v->ewt = N_VNew_Serial(ig->ny, v->ctx);
  v->dky = N_VNew_Serial(ig->ny, v->ctx);
  if (!v->y || !v->ele || !v->ewt || !v->dky)
    return DAL_FAIL(st, DAL_E_NOMEM, "out of memory creating the %s integrator", who);
  // the library's vector kernels (nvec.c); the integrator's work vectors are clones of y
  dal__nvec_fast(v->y);
  dal__nvec_fast(v->dky);
  memcpy(N_VGetArrayPointer(v->y), ig->y, (size_t)ig->ny * sizeof(double));
  return DAL_OK;
}

void dal__sun_vecs_free(dal_sun_vecs *v) {
  N_Vector vs[] = {v->y, v->ele, v->ewt, v->dky};
  for (size_t i = 0; i < sizeof vs / sizeof vs[0]; ++i)
    if (vs[i]) N_VDestroy(vs[i]);
  if (v->ctx) SUNContext_Free(&v->ctx);
}

int dal__sun_set_tols(void *mem, const dal_sun_setters *set, const dal_ode_integ *ig) {
  const dal_solve_opts *o = &ig->opts;
  int flag = set->tolerances(mem, ig->rtol, ig->atol);
  if (!flag && o->h0 > 0) flag = set->init_step(mem, o->h0);
  if (!flag && o->hmin > 0) flag = set->min_step(mem, o->hmin);
  if (!flag && o->hmax > 0) flag = set->max_step(mem, o->hmax);
  return flag;
}
