// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// White box: the assembled Newton matrix dF/dy + cj dF/dy' of every DAE form, dense and
// sparse, against central finite differences of the residual (the oracle only).
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "form/form.h"
#include "scenes.h"

static int wobble(dal_jet t, dal_jet *x, void *ctx) {
  (void)ctx;
  x[0] = dal_scale(dal_sin(dal_scale(t, 3.0)), 0.3);
  x[1] = dal_scale(dal_cos(dal_scale(t, 2.0)), 0.2);
  return 0;
}
static dal_moving_point mover = {wobble, NULL};

// Cartesian double pendulum whose pivot moves (rheonomic) when moving is set
static dal_system *scene(int moving) {
  scn_knobs k = scn_default();
  k.m = 1.3;
  k.m2 = 0.8;
  k.l2 = 0.7;
  k.x0 = 0.1;
  k.pivot = moving ? &mover : NULL;
  return scn_cart_double_pendulum(&k);
}

static double urand(unsigned *s) {
  *s = *s * 1103515245u + 12345u;
  return ((*s >> 8) & 0xffff) / 65535.0 - 0.5;
}

// compare the assembled matrix with finite differences at a random point
static void check_form(dal_system *sys, dal_formulation form, int sparse, unsigned seed) {
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  dal_dae f;
  CHECK(dal__dae_init(&f, sys, st, form, 0.7, 1.9, 0) == 0);
  CHECK(dal__dae_pattern(&f) == 0);
  int neq = f.neq, n = f.n;
  double *y = calloc((size_t)neq, sizeof(double)), *yp = calloc((size_t)neq, sizeof(double));
  double *F1 = calloc((size_t)neq, sizeof(double)), *F2 = calloc((size_t)neq, sizeof(double));
  double *A = calloc((size_t)neq * neq, sizeof(double));
  double *D = calloc((size_t)neq * neq, sizeof(double)), *val = calloc((size_t)f.pat.nnz + 1, 8);
  unsigned s = seed;
  for (int i = 0; i < neq; ++i) {
    y[i] = (i < n ? 1.0 : 3.0) * urand(&s) + (i == 1 ? -1.0 : 0.0);
    yp[i] = 4.0 * urand(&s);
  }
  double t = 0.37, cj = 17.0;
  dal_dae_sink sink = {sparse ? DAL_SINK_SPARSE : DAL_SINK_DENSE, 0, NULL, sparse ? val : A};
  CHECK(dal__dae_newton(&f, t, cj, y, &sink) == 0);
  if (sparse)
    for (int j = 0; j < neq; ++j)
      for (int p = f.pat.colptr[j]; p < f.pat.colptr[j + 1]; ++p)
        A[(size_t)j * neq + f.pat.rowind[p]] = val[p];
  // central differences in y and y' (step h: error ~ h^2 f''' + eps / h)
  double h = 1e-5, worst = 0.0;
  for (int j = 0; j < neq; ++j) {
    for (int pass = 0; pass < 2; ++pass) {
      double *x = pass ? yp : y, keep = x[j], w = pass ? cj : 1.0;
      x[j] = keep + h;
      CHECK(dal__dae_residual(&f, t, y, yp, F1) == 0);
      x[j] = keep - h;
      CHECK(dal__dae_residual(&f, t, y, yp, F2) == 0);
      x[j] = keep;
      for (int i = 0; i < neq; ++i)
        D[(size_t)j * neq + i] += w * (F1[i] - F2[i]) / (2 * h);
    }
  }
  int rows_l0 = f.off_l, rows_l1 = f.off_l + f.m;
  for (int j = 0; j < neq; ++j)
    for (int i = 0; i < neq; ++i) {
      // index-1 leaves d(G v' + gamma_phi)/dq out of its constraint rows (documented)
      if (form == DAL_FORM_INDEX1 && i >= rows_l0 && i < rows_l1 && j < n) continue;
      double a = A[(size_t)j * neq + i], d = D[(size_t)j * neq + i];
      double e = fabs(a - d) / (1.0 + fabs(d));
      if (e > worst) worst = e;
      CHECK_MSG(e < 1e-6, "form %s %s entry (%d, %d): assembled %.10g, differences %.10g",
                dal_formulation_name(form), sparse ? "sparse" : "dense", i, j, a, d);
    }
  printf("  %-6s %-6s %s: worst relative difference %.1e over %d x %d\n",
         dal_formulation_name(form), sparse ? "sparse" : "dense",
         sys->con[0].ctx ? "moving pivot" : "fixed pivot", worst, neq, neq);
  free(y);
  free(yp);
  free(F1);
  free(F2);
  free(A);
  free(D);
  free(val);
  dal__dae_free(&f);
  dal_state_destroy(st);
}

int main(void) {
  dal_formulation forms[3] = {DAL_FORM_GGL, DAL_FORM_INDEX3, DAL_FORM_INDEX1};
  for (int moving = 0; moving < 2; ++moving) {
    dal_system *sys = scene(moving);
    CHECK(sys != NULL);
    CHECK(dal__dae_newton_exact(sys));
    for (int fi = 0; fi < 3; ++fi)
      for (int sparse = 0; sparse < 2; ++sparse)
        check_form(sys, forms[fi], sparse, 7u + fi);
    dal_system_destroy(sys);
  }
  return check_summary("test_newton");
}
