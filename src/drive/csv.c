// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// CSV monitor: one row t, q..., qdot..., E, h (or a selection of columns) per output time
// (header first), %.17g.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "base/base.h"
#include "model/model.h"
#include "dalembert/output.h"
#include "drive/drive.h"

// a row of the selection c->columns: evaluated whole before a byte is written
static int csv_columns(const dal_system *sys, const dal_state *st, dal_csv *c) {
  const dal_columns *cols = c->columns;
  int nc = dal_columns_count(cols);
  double buf[64], *row = nc <= 64 ? buf : malloc((size_t)nc * sizeof *row);
  if (!row) return DAL_FAIL_C(st, DAL_E_NOMEM, "csv_monitor: out of memory");
  int rc = dal_columns_eval(sys, st, cols, row);
  if (!rc && !c->header_done) {
    rc = dal_columns_write_header(cols, c->fp);
    c->header_done = 1;
  }
  for (int i = 0; i < nc && !rc; ++i) {
    double v = c->wrap_angles && dal__columns_is_q(cols, i) ? dal__wrap_pi(row[i]) : row[i];
    fprintf(c->fp, i ? ",%.17g" : "%.17g", v);
  }
  if (!rc) fputc('\n', c->fp);
  if (row != buf) free(row);
  if (!rc && ferror(c->fp)) rc = DAL_E_IO;
  if (rc == DAL_E_IO)
    return DAL_FAIL_C(st, DAL_E_IO,
                      "csv_monitor: writing the row at t=%.17g failed; check the "
                      "stream (disk full, closed file, permissions)",
                      st->t);
  return rc;
}

int dal_csv_monitor(const dal_system *sys, const dal_state *st, void *ctx) {
  dal_csv *c = ctx;
  int pair = dal__check_pair(sys, st, "csv_monitor");
  if (pair) return pair;
  if (!c || !c->fp)
    return DAL_FAIL_C(st, DAL_E_ARG, "csv_monitor: ctx must be a dal_csv with an open stream");
  if (c->columns) return csv_columns(sys, st, c);
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
