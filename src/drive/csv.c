// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// CSV monitor: one row t, q..., qdot..., E, h per output time (header first), %.17g.
#include <math.h>
#include <stdio.h>

#include "model/model.h"

int dal_csv_monitor(const dal_system *sys, const dal_state *st, void *ctx) {
  dal_csv *c = ctx;
  int pair = dal__check_pair(sys, st, "csv_monitor");
  if (pair) return pair;
  if (!c || !c->fp)
    return DAL_FAIL_C(st, DAL_E_ARG, "csv_monitor: ctx must be a dal_csv with an open stream");
  // a row holds the state's energies: they must be current at its (t, q, qdot)
  dal__lazy_eval_for(st, DAL_P_DYN | (sys->m ? DAL_P_OUT : 0u));
  if (!(st->have & DAL_P_DYN))
    return DAL_FAIL_C(st, DAL_E_STATE,
                      "csv_monitor: the state is not evaluated at t=%.17g; call dal_forward "
                      "first (dal_evolve calls monitors with evaluated states)",
                      st->t);
  int n = sys->n;
  if (!c->header_done) {
    fputs("t", c->fp);
    for (int i = 0; i < n; ++i)
      fprintf(c->fp, ",%s", sys->coord_names[i]);
    for (int i = 0; i < n; ++i)
      fprintf(c->fp, ",%s_dot", sys->coord_names[i]);
    fputs(",E,h\n", c->fp);
    c->header_done = 1;
  }
  fprintf(c->fp, "%.17g", st->t);
  for (int i = 0; i < n; ++i)
    fprintf(c->fp, ",%.17g", c->wrap_angles ? dal__wrap_pi(st->q[i]) : st->q[i]);
  for (int i = 0; i < n; ++i)
    fprintf(c->fp, ",%.17g", st->qdot[i]);
  fprintf(c->fp, ",%.17g,%.17g\n", st->en.E, st->en.h);
  if (ferror(c->fp))
    return DAL_FAIL_C(st, DAL_E_IO,
                      "csv_monitor: writing the row at t=%.17g failed; check the "
                      "stream (disk full, closed file, permissions)",
                      st->t);
  return DAL_OK;
}
