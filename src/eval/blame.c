// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Diagnosis of non-finite applied forces: which built-in force overflowed, when the dynamics
// stage reports only the sum (the message then must not send the user to callbacks that
// the scene does not have); the one message of a degenerate mass matrix.
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "eval.h"

// the force magnitude of link l on particle k (the other end fixed or a particle); NAN when
// the other end is a path anchor (only its callback knows where it is)
static double link_force(const dal_system *sys, const dal_state *st, const dal_link *l, int spring,
                         double *len_out) {
  int d = sys->dim;
  const double *ra = st->r + l->a * d, *va = st->v + l->a * d, *rb = l->x0, *vb = NULL;
  if (l->b >= 0) {
    rb = st->r + l->b * d;
    vb = st->v + l->b * d;
  } else if (l->fn) {
    return NAN;
  }
  double e[3], s = 0.0;
  for (int i = 0; i < d; ++i) {
    e[i] = ra[i] - rb[i];
    s += e[i] * e[i];
  }
  double len = sqrt(s);
  *len_out = len;
  if (spring) return l->k * (len - l->L);
  double rel = 0.0;
  for (int i = 0; i < d; ++i)
    rel += (va[i] - (vb ? vb[i] : 0.0)) * (e[i] / len);
  return l->k * rel;
}

int dal__blame_forces(const dal_system *sys, dal_state *st) {
  int d = sys->dim, Nd = sys->N * d, j = 0;
  while (j < Nd && isfinite(st->F[j]))
    ++j;
  char culprit[256] = "";
  if (j == Nd) {
    // the particle forces are finite: the generalized force J' F (or a callback) overflowed
    int i = 0;
    while (i < sys->n && isfinite(st->Q[i]))
      ++i;
    if (i == sys->n || sys->ngenforce > 0) return DAL_E_NONFINITE;
    return DAL_FAIL(st, DAL_E_NONFINITE,
                    "generalized force on coordinate '%s' is %g at t=%.17g: the finite particle "
                    "forces projected on it (J' F) exceed double range; check the scale of the "
                    "coordinates and forces",
                    sys->coord_names[i], st->Q[i], st->t);
  }
  int k = j / d, a = j % d;
  if (sys->has_gravity && !isfinite(sys->mass[k] * sys->g[a]))
    snprintf(culprit, sizeof culprit, "gravity (mass %g times g = %g)", sys->mass[k], sys->g[a]);
  for (int i = 0; i < sys->nspring + sys->ndamper && !culprit[0]; ++i) {
    int spring = i < sys->nspring;
    const dal_link *l = spring ? &sys->springs[i] : &sys->dampers[i - sys->nspring];
    if (l->a != k && l->b != k) continue;
    double len = NAN, f = link_force(sys, st, l, spring, &len);
    if (isfinite(f) || isnan(len)) continue;
    if (l->b >= 0)
      snprintf(culprit, sizeof culprit, "the %s between '%s' and '%s' (%s %g, length %g)",
               spring ? "spring" : "damper", sys->part_names[l->a], sys->part_names[l->b],
               spring ? "stiffness" : "coefficient", l->k, len);
    else
      snprintf(culprit, sizeof culprit, "the %s from '%s' to its anchor (%s %g, length %g)",
               spring ? "spring" : "damper", sys->part_names[l->a],
               spring ? "stiffness" : "coefficient", l->k, len);
  }
  if (!culprit[0] && sys->nforce > 0) return DAL_E_NONFINITE; // a force callback, as it says
  if (!culprit[0])
    snprintf(culprit, sizeof culprit,
             "the sum of its gravity, spring, damper and potential forces (each finite)");
  return DAL_FAIL(st, DAL_E_NONFINITE,
                  "applied force on particle '%s' (component %d) is %g at t=%.17g: %s overflows; "
                  "the particles are too far apart or too fast for double precision there, or a "
                  "coefficient is too large: check the state and the coefficients",
                  sys->part_names[k], a, st->F[j], st->t, culprit);
}

int dal__fail_degenerate(const dal_system *sys, dal_state *st, int bad, const char *what) {
  return DAL_FAIL(st, DAL_E_SINGULAR,
                  "%s%smass matrix singular or not positive definite at t=%.17g, %s: coordinate "
                  "'%s' is degenerate (it moves no mass there, e.g. a chart singularity such "
                  "as a spherical pendulum's pole); use redundant coordinates with "
                  "constraints, or another chart",
                  what ? what : "", what ? ": " : "", st->t, dal__qtext(sys, st->q).s,
                  sys->coord_names[bad]);
}
