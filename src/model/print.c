// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Human-readable model and state printouts (after MuJoCo's mj_printModel / mj_printData).
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "model.h"

// "name=value" for each parameter of one primitive instance
static void print_params(FILE *fp, const dal_primitive *prim, const double *param) {
  char nb[16];
  for (int i = 0; i < prim->nparam; ++i)
    fprintf(fp, "%s%s=%.17g", i ? ", " : "", dal__param_name(prim, i, nb, sizeof nb), param[i]);
}

static void print_ints(FILE *fp, const dal_system *sys, const int *x, int n, int particles) {
  for (int i = 0; i < n; ++i)
    fprintf(fp, "%s'%s'", i ? ", " : "",
            particles ? sys->part_names[x[i]] : sys->coord_names[x[i]]);
}

// the end of a primitive instance's line: " <word> (its coordinates)", " with <parameters>"
static void print_instance(FILE *fp, const dal_system *sys, const char *word, const int *coords,
                           int ncoord, const dal_primitive *prim, const double *param) {
  if (ncoord) {
    fprintf(fp, " %s (", word);
    print_ints(fp, sys, coords, ncoord, 0);
    fputc(')', fp);
  }
  if (prim->nparam) {
    fprintf(fp, " with ");
    print_params(fp, prim, param);
  }
  fputc('\n', fp);
}

static void print_link(FILE *fp, const dal_system *sys, const dal_link *l, const char *kind,
                       const char *coef) {
  fprintf(fp, "  %s '%s' - ", kind, sys->part_names[l->a]);
  if (l->b >= 0) {
    fprintf(fp, "'%s'", sys->part_names[l->b]);
  } else {
    fprintf(fp, "anchor (");
    for (int i = 0; i < sys->dim; ++i)
      fprintf(fp, "%s%.17g", i ? ", " : "", l->x0[i]);
    fprintf(fp, ")%s", l->fn ? " + x(t)" : "");
  }
  fprintf(fp, ": %s=%.17g", coef, l->k);
  if (coef[0] == 'k') fprintf(fp, ", length=%.17g", l->L);
  fputc('\n', fp);
}

int dal_system_print(const dal_system *sys, FILE *fp) {
  if (!sys || !fp) return DAL_E_ARG;
  int d = sys->dim;
  fprintf(fp, "system: dim %d, %d coordinates, %d particles, %d constraint rows\n", d, sys->n,
          sys->N, sys->m);
  fprintf(fp, "coordinates:\n");
  for (int i = 0; i < sys->n; ++i)
    fprintf(fp, "  [%d] '%s'\n", i, sys->coord_names[i]);
  if (sys->lag) fprintf(fp, "given by a Lagrangian L(t, q, qdot)\n");
  if (sys->N) fprintf(fp, "particles:\n");
  for (int k = 0; k < sys->N; ++k) {
    fprintf(fp, "  [%d] '%s' mass=%.17g", k, sys->part_names[k], sys->mass[k]);
    if (sys->map) {
      fprintf(fp, " placed by the whole-system map r(q, t)\n");
      continue;
    }
    const dal_place *pl = &sys->place[k];
    fprintf(fp, " placed by '%s'", pl->prim->name);
    if (pl->parent >= 0) fprintf(fp, " on parent '%s'", sys->part_names[pl->parent]);
    print_instance(fp, sys, "of", sys->ipool + pl->coord_off, pl->ncoord, pl->prim,
                   sys->ppool + pl->param_off);
  }
  if (sys->ncon) fprintf(fp, "constraints:\n");
  for (int i = 0; i < sys->ncon; ++i) {
    const dal_con *c = &sys->con[i];
    fprintf(fp, "  [row %d", c->row);
    if (c->prim->nout > 1) fprintf(fp, "-%d", c->row + c->prim->nout - 1);
    fprintf(fp, "] '%s' by '%s'", c->name, c->prim->name);
    if (c->npart) {
      fprintf(fp, " on particles (");
      print_ints(fp, sys, sys->ipool + c->part_off, c->npart, 1);
      fputc(')', fp);
    }
    print_instance(fp, sys, "on coordinates", sys->ipool + c->coord_off, c->ncoord, c->prim,
                   sys->ppool + c->param_off);
  }
  fprintf(fp, "forces:\n");
  if (sys->has_gravity) {
    fprintf(fp, "  gravity (");
    for (int i = 0; i < d; ++i)
      fprintf(fp, "%s%.17g", i ? ", " : "", sys->g[i]);
    fprintf(fp, ")\n");
  }
  for (int i = 0; i < sys->nspring; ++i)
    print_link(fp, sys, &sys->springs[i], "spring", "k");
  for (int i = 0; i < sys->ndamper; ++i)
    print_link(fp, sys, &sys->dampers[i], "damper", "c");
  if (sys->npotr) fprintf(fp, "  %d potential(s) U(r, t)\n", sys->npotr);
  if (sys->npotq) fprintf(fp, "  %d potential(s) U(q, t)\n", sys->npotq);
  if (sys->nforce) fprintf(fp, "  %d force callback(s) F(t, r, v)\n", sys->nforce);
  if (sys->ngenforce)
    fprintf(fp, "  %d generalized force callback(s) Q(t, q, qdot)\n", sys->ngenforce);
  if (!sys->has_gravity && !sys->nspring && !sys->ndamper && !sys->npotr && !sys->npotq &&
      !sys->nforce && !sys->ngenforce)
    fprintf(fp, "  none\n");
  return ferror(fp) ? DAL_E_IO : DAL_OK;
}

static void print_vec(FILE *fp, const char *label, const double *x, int n) {
  fprintf(fp, "%s", label);
  for (int i = 0; i < n; ++i)
    fprintf(fp, " %.17g", x[i]);
  fputc('\n', fp);
}

int dal_state_print(const dal_system *sys, const dal_state *st, FILE *fp) {
  int pair = dal__check_pair(sys, st, "state_print");
  if (pair) return pair;
  if (!fp) return DAL_FAIL_C(st, DAL_E_ARG, "state_print: fp is NULL");
  dal__lazy_eval(st);
  int n = sys->n, m = sys->m;
  fprintf(fp, "state at t=%.17g\n", st->t);
  if (sys->lag) {
    // a Lagrangian system has no separate Q and c: the forces and velocity terms are inside L.
    // Shown: A qddot (A = d2L/dqdot2), the whole generalized force the motion balances, and
    // Q_ext, the part from outside L (force callbacks, U(q, t))
    int acc = (st->have & DAL_P_ACC) && (st->have & DAL_P_M);
    fprintf(fp, "  (Lagrangian system: d/dt dL/dqdot - dL/dq = Q_ext; Aqddot, with "
                "A = d2L/dqdot2, is the generalized force the motion balances, Q_ext the part from "
                "outside L: force callbacks, U(q, t); the velocity terms are inside L)\n");
    for (int i = 0; i < n; ++i) {
      double aq = NAN;
      if (acc) {
        aq = 0.0;
        for (int j = 0; j < n; ++j)
          aq += st->M[(size_t)j * n + i] * st->qddot[j];
      }
      fprintf(fp, "  '%s': q=%.17g qdot=%.17g qddot=%.17g Aqddot=%.17g Q_ext=%.17g\n",
              sys->coord_names[i], st->q[i], st->qdot[i], acc ? st->qddot[i] : NAN, aq,
              (st->have & DAL_P_DYN) ? st->Q[i] : NAN);
    }
  } else {
    for (int i = 0; i < n; ++i)
      fprintf(fp, "  '%s': q=%.17g qdot=%.17g qddot=%.17g Q=%.17g c=%.17g\n", sys->coord_names[i],
              st->q[i], st->qdot[i], (st->have & DAL_P_ACC) ? st->qddot[i] : NAN,
              (st->have & DAL_P_DYN) ? st->Q[i] : NAN, (st->have & DAL_P_DYN) ? st->c[i] : NAN);
  }
  if (!(st->have & DAL_P_ACC)) {
    fprintf(fp, "  (not evaluated: call dal_forward for M, Q, c, lambda and energies)\n");
    return ferror(fp) ? DAL_E_IO : DAL_OK;
  }
  if (st->M) {
    fprintf(fp, "M (column-major rows shown as rows; symmetric):\n");
    for (int i = 0; i < n; ++i) {
      fprintf(fp, " ");
      for (int j = 0; j < n; ++j)
        fprintf(fp, " %.17g", st->M[(size_t)j * n + i]);
      fputc('\n', fp);
    }
  }
  for (int r = 0; r < m; ++r)
    fprintf(fp, "  row %d ('%s'): lambda=%.17g phi=%.17g phidot=%.17g\n", r,
            sys->con[sys->row_con[r]].name, st->lambda[r], st->phi[r], st->phidot[r]);
  for (int k = 0; k < sys->N; ++k) {
    fprintf(fp, "  particle '%s':", sys->part_names[k]);
    print_vec(fp, " r", st->r + (size_t)k * sys->dim, sys->dim);
  }
  const dal_energies *e = &st->en;
  fprintf(fp, "energies: T=%.17g U=%.17g E=%.17g h=%.17g (T2=%.17g T1=%.17g T0=%.17g)\n", e->T,
          e->U, e->E, e->h, e->T2, e->T1, e->T0);
  if (st->init_rep_valid)
    fprintf(fp, "last consistent start: max |phi| %.3g -> %.3g, max |delta q| %.3g (%s)\n",
            st->init_rep.phi_before, st->init_rep.phi_after, st->init_rep.dq_max,
            st->init_rep.dq_coord >= 0 ? sys->coord_names[st->init_rep.dq_coord] : "-");
  return ferror(fp) ? DAL_E_IO : DAL_OK;
}
