// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Scene files run: parameters set, the system, the initial state, the events, the run.
#define _POSIX_C_SOURCE 200809L
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene.h"

int dal_scene_set_param(dal_scene *sc, const char *name, double value, char *msg, size_t msglen) {
  if (msg && msglen) msg[0] = 0;
  if (!sc || !name) return DAL_E_ARG;
  int j = dal__tab_get(&sc->ptab, name);
  if (j < 0) {
    if (msg && msglen) snprintf(msg, msglen, "%s: no parameter '%s'", sc->name, name);
    return DAL_E_ARG;
  }
  if (!isfinite(value)) {
    if (msg && msglen) snprintf(msg, msglen, "%s: parameter '%s' is not finite", sc->name, name);
    return DAL_E_NONFINITE;
  }
  // a value the model refuses leaves the scene as it was
  unsigned char old = sc->over[j];
  double oldv = sc->overval[j];
  sc->over[j] = 1;
  sc->overval[j] = value;
  int rc = dal__scene_build(sc, msg, msglen);
  if (rc) {
    sc->over[j] = old;
    sc->overval[j] = oldv;
    dal__scene_build(sc, NULL, 0);
  }
  return rc;
}

const dal_system *dal_scene_system(const dal_scene *sc) { return sc ? sc->sys : NULL; }

const dal_solve_opts *dal_scene_opts(const dal_scene *sc, double *t0, double *t1, double *dt) {
  if (!sc) return NULL;
  if (t0) *t0 = sc->t0;
  if (t1) *t1 = sc->t1;
  if (dt) *dt = sc->dt;
  return &sc->opts;
}

int dal_scene_state(const dal_scene *sc, dal_state **out) {
  if (!sc || !out) return DAL_E_ARG;
  int rc = dal_state_create(sc->sys, out);
  if (rc) return rc;
  rc = dal_state_set(sc->sys, *out, sc->t0, sc->q0, sc->v0);
  if (rc) {
    dal_state_destroy(*out);
    *out = NULL;
  }
  return rc;
}

int dal_scene_events(const dal_scene *sc, dal_events **out) {
  if (out) *out = NULL;
  if (!sc || !out) return DAL_E_ARG;
  int rc = dal_events_create(sc->sys, out);
  for (int i = 0; i < sc->nev && !rc; ++i) {
    dal_event_def d = dal_default_event_def();
    d.name = sc->ev[i].name;
    d.g = dal_expr_event;
    d.ctx = sc->ev[i].e;
    d.direction = (dal_event_direction)sc->ev[i].direction;
    d.terminal = sc->ev[i].terminal;
    int k = dal_events_add(*out, &d);
    if (k < 0) rc = k;
  }
  if (rc) {
    dal_events_destroy(*out);
    *out = NULL;
  }
  return rc;
}

int dal_scene_event_is_section(const dal_scene *sc, int i) {
  return sc && i >= 0 && i < sc->nev ? sc->ev[i].section : -1;
}

double dal_scene_strobe(const dal_scene *sc) { return sc ? sc->strobe : 0.0; }

int dal_scene_run_events(const dal_scene *sc, FILE *csv, dal_events *ev, dal_state **stp, char *msg,
                         size_t msglen) {
  if (msg && msglen) msg[0] = 0;
  if (stp) *stp = NULL;
  if (!sc) return DAL_E_ARG;
  dal_events *own = NULL;
  dal_state *st;
  int rc = ev || !sc->nev ? DAL_OK : dal_scene_events(sc, &own);
  if (!rc) rc = dal_scene_state(sc, &st);
  if (rc) {
    if (msg && msglen)
      snprintf(msg, msglen, "%s: the initial state: %s", sc->name, dal_status_string(rc));
    dal_events_destroy(own);
    return rc;
  }
  dal_events *use = ev ? ev : own;
  if (use) rc = dal_state_set_events(st, use);
  dal_csv c = {csv, 0, 0, NULL};
  if (!rc)
    rc = dal_evolve(sc->sys, st, &sc->opts, sc->t1, sc->dt, csv ? dal_csv_monitor : NULL,
                    csv ? &c : NULL);
  if (rc && msg && msglen) snprintf(msg, msglen, "%s: %s", sc->name, dal_state_errmsg(st));
  dal_state_set_events(st, NULL);
  dal_events_destroy(own);
  if (stp)
    *stp = st;
  else
    dal_state_destroy(st);
  return rc;
}

int dal_scene_run(const dal_scene *sc, FILE *csv, dal_state **stp, char *msg, size_t msglen) {
  return dal_scene_run_events(sc, csv, NULL, stp, msg, msglen);
}

int dal_scene_native(dal_scene *sc, const dal_codegen_opts *o, char *msg, size_t msglen) {
  if (msg && msglen) msg[0] = 0;
  if (!sc) return DAL_E_ARG;
  if (!sc->nex) return DAL_OK;
  int rc = dal_codegen_attach(sc->ex, sc->nex, o, msg, msglen);
  if (rc) return rc;
  sc->native = 1;
  sc->native_opts = o ? *o : dal_codegen_default_opts();
  return dal__scene_native_eom(sc, msg, msglen);
}

int dal_scene_nexprs(const dal_scene *sc) { return sc ? sc->nex : 0; }

const dal_expr *dal_scene_expr(const dal_scene *sc, int i) {
  return sc && i >= 0 && i < sc->nex ? sc->ex[i] : NULL;
}
