// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Per-trajectory parameters: copy-on-write overrides of a shared system's parameters.
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dalembert/params.h"
#include "model.h"

void dal__params_init(dal_state *st) {
  const dal_system *sys = st->sys;
  memset(&st->prm, 0, sizeof st->prm);
  st->prm.mass = sys->mass;
  st->prm.mu = sys->mu;
  st->prm.ppool = sys->ppool;
  st->prm.g = sys->g;
  st->prm.springs = sys->springs;
  st->prm.dampers = sys->dampers;
  st->prm.has_gravity = sys->has_gravity;
}

void dal__params_free(dal_state *st) {
  free(st->prm.own_mass);
  free(st->prm.own_mu);
  free(st->prm.own_ppool);
  free(st->prm.own_springs);
  free(st->prm.own_dampers);
  memset(&st->prm, 0, sizeof st->prm);
}

// length of the system's parameter pool (the system does not store it)
static size_t ppool_len(const dal_system *sys) {
  size_t len = 0;
  for (int k = 0; k < sys->N && sys->place; ++k) {
    size_t end = (size_t)sys->place[k].param_off + (size_t)sys->place[k].prim->nparam;
    if (end > len) len = end;
  }
  for (int i = 0; i < sys->ncon; ++i) {
    size_t end = (size_t)sys->con[i].param_off + (size_t)sys->con[i].prim->nparam;
    if (end > len) len = end;
  }
  return len;
}

// subtree masses from the state's masses, summed in the order system.c uses (bit-identical)
static void subtree_masses(const dal_system *sys, const double *mass, double *mu) {
  memcpy(mu, mass, (size_t)sys->N * sizeof(double));
  for (int k = sys->N - 1; k >= 0 && sys->place; --k)
    if (sys->place[k].parent >= 0) mu[sys->place[k].parent] += mu[k];
}

// a malloc'd copy of n elements of size sz (room for one at least); NULL when out of memory
static void *copy_of(const void *src, size_t n, size_t sz) {
  void *p = malloc((n ? n : 1) * sz);
  if (p && n) memcpy(p, src, n * sz);
  return p;
}

// make the state own a copy of the array `ref` points into; 0 or DAL_E_NOMEM
static int own(const dal_system *sys, dal_state *st, dal_param_kind kind) {
  dal_params *p = &st->prm;
  size_t N = (size_t)sys->N;
  switch (kind) {
  case DAL_PARAM_MASS:
    if (p->own_mass) return DAL_OK;
    p->own_mass = copy_of(sys->mass, N, sizeof(double));
    p->own_mu = copy_of(sys->mu, N, sizeof(double));
    if (!p->own_mass || !p->own_mu) {
      free(p->own_mass);
      free(p->own_mu);
      p->own_mass = p->own_mu = NULL;
      return DAL_E_NOMEM;
    }
    p->mass = p->own_mass;
    p->mu = p->own_mu;
    return DAL_OK;
  case DAL_PARAM_PLACE:
  case DAL_PARAM_CONSTRAINT: {
    if (!p->own_ppool && !(p->own_ppool = copy_of(sys->ppool, ppool_len(sys), sizeof(double))))
      return DAL_E_NOMEM;
    p->ppool = p->own_ppool;
    return DAL_OK;
  }
  case DAL_PARAM_GRAVITY:
    if (p->g != p->own_g) {
      memcpy(p->own_g, sys->g, sizeof p->own_g);
      p->g = p->own_g;
    }
    return DAL_OK;
  case DAL_PARAM_SPRING_K:
  case DAL_PARAM_SPRING_L:
    if (!p->own_springs &&
        !(p->own_springs = copy_of(sys->springs, (size_t)sys->nspring, sizeof(dal_link))))
      return DAL_E_NOMEM;
    p->springs = p->own_springs;
    return DAL_OK;
  case DAL_PARAM_DAMPER_C:
    if (!p->own_dampers &&
        !(p->own_dampers = copy_of(sys->dampers, (size_t)sys->ndamper, sizeof(dal_link))))
      return DAL_E_NOMEM;
    p->dampers = p->own_dampers;
    return DAL_OK;
  case DAL_PARAM_NONE:
    break;
  }
  return DAL_E_ARG;
}

// DAL_E_ARG with "parameter: <what> index i out of range [0, n)" unless 0 <= i < n
static int index_in(int i, int n, const char *what, char *msg, size_t len) {
  if (i >= 0 && i < n) return DAL_OK;
  if (msg && len) snprintf(msg, len, "parameter: %s index %d out of range [0, %d)", what, i, n);
  return DAL_E_ARG;
}

int dal_param_check(const dal_system *sys, const dal_param_ref *ref, char *msg, size_t len) {
  if (msg && len) msg[0] = 0;
  if (!sys || !ref) {
    if (msg && len) snprintf(msg, len, "parameter: system or parameter reference is NULL");
    return DAL_E_ARG;
  }
  int t = ref->target, i = ref->index;
  switch (ref->kind) {
  case DAL_PARAM_MASS:
  case DAL_PARAM_PLACE:
    if (index_in(t, sys->N, "particle", msg, len)) return DAL_E_ARG;
    if (ref->kind == DAL_PARAM_MASS) return DAL_OK;
    if (!sys->place) {
      if (msg && len)
        snprintf(msg, len,
                 "parameter of particle '%s': the particles are placed by a "
                 "whole-system map, which has no parameters",
                 sys->part_names[t]);
      return DAL_E_ARG;
    }
    if (i < 0 || i >= sys->place[t].prim->nparam) {
      if (msg && len)
        snprintf(msg, len,
                 "placing particle '%s': primitive '%s' takes %d parameters; index %d "
                 "is out of range (see the primitive's parameter list in primitives.h)",
                 sys->part_names[t], sys->place[t].prim->name, sys->place[t].prim->nparam, i);
      return DAL_E_ARG;
    }
    return DAL_OK;
  case DAL_PARAM_CONSTRAINT:
    if (index_in(t, sys->ncon, "constraint", msg, len)) return DAL_E_ARG;
    if (i < 0 || i >= sys->con[t].prim->nparam) {
      if (msg && len)
        snprintf(msg, len,
                 "constraint '%s': primitive '%s' takes %d parameters; index %d is "
                 "out of range (see the primitive's parameter list in primitives.h)",
                 sys->con[t].name, sys->con[t].prim->name, sys->con[t].prim->nparam, i);
      return DAL_E_ARG;
    }
    return DAL_OK;
  case DAL_PARAM_GRAVITY:
    if (i < 0 || i >= sys->dim) {
      if (msg && len) snprintf(msg, len, "gravity component %d out of range [0, %d)", i, sys->dim);
      return DAL_E_ARG;
    }
    return DAL_OK;
  case DAL_PARAM_SPRING_K:
  case DAL_PARAM_SPRING_L:
    return index_in(t, sys->nspring, "spring", msg, len);
  case DAL_PARAM_DAMPER_C:
    return index_in(t, sys->ndamper, "damper", msg, len);
  case DAL_PARAM_NONE:
    break;
  }
  if (msg && len) snprintf(msg, len, "parameter: unknown kind %d", (int)ref->kind);
  return DAL_E_ARG;
}

// the value a parameter has in the arrays of p (system's or state's)
static double read_param(const dal_system *sys, const dal_params *p, const dal_param_ref *r) {
  switch (r->kind) {
  case DAL_PARAM_MASS:
    return p->mass[r->target];
  case DAL_PARAM_PLACE:
    return p->ppool[sys->place[r->target].param_off + r->index];
  case DAL_PARAM_CONSTRAINT:
    return p->ppool[sys->con[r->target].param_off + r->index];
  case DAL_PARAM_GRAVITY:
    return p->has_gravity ? p->g[r->index] : 0.0;
  case DAL_PARAM_SPRING_K:
    return p->springs[r->target].k;
  case DAL_PARAM_SPRING_L:
    return p->springs[r->target].L;
  case DAL_PARAM_DAMPER_C:
    return p->dampers[r->target].k;
  case DAL_PARAM_NONE:
    break;
  }
  return NAN;
}

int dal_system_param(const dal_system *sys, const dal_param_ref *ref, double *value) {
  if (!value || dal_param_check(sys, ref, NULL, 0)) return DAL_E_ARG;
  dal_params p = {.mass = sys->mass,
                  .ppool = sys->ppool,
                  .g = sys->g,
                  .springs = sys->springs,
                  .dampers = sys->dampers,
                  .has_gravity = sys->has_gravity};
  *value = read_param(sys, &p, ref);
  return DAL_OK;
}

int dal_state_param(const dal_system *sys, const dal_state *st, const dal_param_ref *ref,
                    double *value) {
  if (!st || !value) return DAL_E_ARG;
  if (!sys || st->sys != sys) return DAL_E_STATE;
  if (dal_param_check(sys, ref, NULL, 0)) return DAL_E_ARG;
  *value = read_param(sys, &st->prm, ref);
  return DAL_OK;
}

int dal_param_name(const dal_system *sys, const dal_param_ref *ref, char *buf, size_t len) {
  if (!buf || !len || dal_param_check(sys, ref, NULL, 0)) return DAL_E_ARG;
  int t = ref->target, i = ref->index;
  switch (ref->kind) {
  case DAL_PARAM_MASS:
    snprintf(buf, len, "mass:%s", sys->part_names[t]);
    break;
  case DAL_PARAM_PLACE:
    snprintf(buf, len, "place:%s:%d", sys->part_names[t], i);
    break;
  case DAL_PARAM_CONSTRAINT:
    snprintf(buf, len, "con:%s:%d", sys->con[t].name, i);
    break;
  case DAL_PARAM_GRAVITY:
    snprintf(buf, len, "gravity:%d", i);
    break;
  case DAL_PARAM_SPRING_K:
    snprintf(buf, len, "spring:%d:k", t);
    break;
  case DAL_PARAM_SPRING_L:
    snprintf(buf, len, "spring:%d:L", t);
    break;
  case DAL_PARAM_DAMPER_C:
    snprintf(buf, len, "damper:%d:c", t);
    break;
  case DAL_PARAM_NONE:
    return DAL_E_ARG;
  }
  return DAL_OK;
}

// a non-negative decimal integer filling the whole string s[0..n); -1 if not one
static int parse_index(const char *s, size_t n) {
  if (n == 0 || n > 9) return -1;
  int v = 0;
  for (size_t i = 0; i < n; ++i) {
    if (!isdigit((unsigned char)s[i])) return -1;
    v = 10 * v + (s[i] - '0');
  }
  return v;
}

// index of a name among names[0..count) (or a decimal index); -1 if none
static int find_name(char *const *names, int count, const char *s, size_t n) {
  for (int i = 0; i < count; ++i)
    if (strlen(names[i]) == n && memcmp(names[i], s, n) == 0) return i;
  int v = parse_index(s, n);
  return v < count ? v : -1;
}

// a primitive's parameter by its decimal index or its name (tables of version 2); -1 if neither
static int prim_param_index(const dal_primitive *prim, const char *s, size_t n) {
  int v = parse_index(s, n);
  if (v >= 0 || !prim || prim->version < 2 || !prim->param_names) return v;
  for (int i = 0; i < prim->nparam && i < DAL_MAX_PARAM; ++i) {
    const char *nm = prim->param_names[i];
    if (nm && strlen(nm) == n && memcmp(nm, s, n) == 0) return i;
  }
  return -1;
}

// the primitive whose parameters r addresses (place or con with a valid target), or NULL
static const dal_primitive *ref_prim(const dal_system *sys, const dal_param_ref *r) {
  if (r->kind == DAL_PARAM_PLACE && r->target >= 0 && sys->place) return sys->place[r->target].prim;
  if (r->kind == DAL_PARAM_CONSTRAINT && r->target >= 0) return sys->con[r->target].prim;
  return NULL;
}

// "l, x0, y0" (the names of a primitive's parameters) into buf
static void list_param_names(const dal_primitive *prim, char *buf, size_t len) {
  size_t used = 0;
  buf[0] = 0;
  for (int i = 0; prim && i < prim->nparam && i < DAL_MAX_PARAM && used + 1 < len; ++i) {
    char nb[16];
    int w = snprintf(buf + used, len - used, "%s%s", i ? ", " : "",
                     dal__param_name(prim, i, nb, sizeof nb));
    if (w < 0) break;
    used += (size_t)w;
  }
}

static int set_def_param(const dal_primitive *prim, double *param, const char *name, double value) {
  if (!prim || !name || !param) return DAL_E_ARG;
  int i = prim_param_index(prim, name, strlen(name));
  if (i < 0 || i >= prim->nparam || i >= DAL_MAX_PARAM) return DAL_E_ARG;
  param[i] = value;
  return DAL_OK;
}

int dal_place_def_set(dal_place_def *def, const char *name, double value) {
  return def ? set_def_param(def->prim, def->param, name, value) : DAL_E_ARG;
}

int dal_constraint_def_set(dal_constraint_def *def, const char *name, double value) {
  return def ? set_def_param(def->prim, def->param, name, value) : DAL_E_ARG;
}

// split name "kind:target[:index]" at ':' into its fields f (lengths fl); returns their
// number (4: more than three)
static int split_fields(const char *name, const char *f[3], size_t fl[3]) {
  int nf = 1;
  for (const char *c = name;; ++c) {
    if (*c == ':' || *c == 0) {
      fl[nf - 1] = (size_t)(c - f[nf - 1]);
      if (*c == 0) break;
      if (nf == 3) return 4;
      f[nf++] = c + 1;
    }
  }
  return nf;
}

// the kind and target of a parameter from its nf fields (target -1: no such element); -1 for
// an unknown form
static int parse_kind(const dal_system *sys, const char *f[3], const size_t fl[3], int nf,
                      dal_param_ref *r) {
#define KIND_IS(s) (fl[0] == strlen(s) && memcmp(f[0], s, fl[0]) == 0)
  if (KIND_IS("mass") && nf == 2) {
    r->kind = DAL_PARAM_MASS;
    r->target = find_name(sys->part_names, sys->N, f[1], fl[1]);
  } else if (KIND_IS("place") && nf == 3) {
    r->kind = DAL_PARAM_PLACE;
    r->target = find_name(sys->part_names, sys->N, f[1], fl[1]);
  } else if (KIND_IS("con") && nf == 3) {
    r->kind = DAL_PARAM_CONSTRAINT;
    r->target = -1;
    for (int i = 0; i < sys->ncon && r->target < 0; ++i)
      if (strlen(sys->con[i].name) == fl[1] && memcmp(sys->con[i].name, f[1], fl[1]) == 0)
        r->target = i;
    if (r->target < 0) {
      int v = parse_index(f[1], fl[1]);
      r->target = v < sys->ncon ? v : -1;
    }
  } else if (KIND_IS("gravity") && nf == 2) {
    r->kind = DAL_PARAM_GRAVITY;
    r->index = parse_index(f[1], fl[1]);
  } else if (KIND_IS("spring") && nf == 3 && fl[2] == 1 && (f[2][0] == 'k' || f[2][0] == 'L')) {
    r->kind = f[2][0] == 'k' ? DAL_PARAM_SPRING_K : DAL_PARAM_SPRING_L;
    r->target = parse_index(f[1], fl[1]);
  } else if (KIND_IS("damper") && nf == 3 && fl[2] == 1 && f[2][0] == 'c') {
    r->kind = DAL_PARAM_DAMPER_C;
    r->target = parse_index(f[1], fl[1]);
  } else {
    return -1;
  }
#undef KIND_IS
  return 0;
}

int dal_param_find(const dal_system *sys, const char *name, dal_param_ref *out, char *msg,
                   size_t len) {
  if (msg && len) msg[0] = 0;
  if (!sys || !name || !out) {
    if (msg && len) snprintf(msg, len, "parameter lookup: system, name or output is NULL");
    return DAL_E_ARG;
  }
  // split "kind:target[:index]" (names may not contain ':')
  const char *f[3] = {name, NULL, NULL};
  size_t fl[3] = {0, 0, 0};
  int nf = split_fields(name, f, fl);
  dal_param_ref r = {DAL_PARAM_NONE, 0, 0};
  if (parse_kind(sys, f, fl, nf, &r) != 0) {
    if (msg && len)
      snprintf(msg, len, "parameter '%s': unknown form; use one of %s", name,
               "mass:<particle>, place:<particle>:<i or name>, con:<constraint>:<i or name>, "
               "gravity:<i>, spring:<j>:k, spring:<j>:L, damper:<j>:c");
    return DAL_E_ARG;
  }
  if (r.target < 0) {
    const char *what = r.kind == DAL_PARAM_CONSTRAINT                            ? "constraint"
                       : (r.kind == DAL_PARAM_MASS || r.kind == DAL_PARAM_PLACE) ? "particle"
                       : r.kind == DAL_PARAM_DAMPER_C                            ? "damper"
                                                                                 : "spring";
    if (msg && len)
      snprintf(msg, len,
               "parameter '%s': no %s named '%.*s' in the system (give a name used in "
               "the builder or a 0-based index)",
               name, what, (int)fl[1], f[1]);
    return DAL_E_ARG;
  }
  if (r.kind == DAL_PARAM_PLACE || r.kind == DAL_PARAM_CONSTRAINT)
    r.index = prim_param_index(ref_prim(sys, &r), f[2], fl[2]);
  if (r.index < 0) {
    const dal_primitive *prim = ref_prim(sys, &r);
    char names[256];
    list_param_names(prim, names, sizeof names);
    if (msg && len) {
      if (prim && names[0])
        snprintf(msg, len,
                 "parameter '%s': '%.*s' is neither a parameter of '%s' (%s) nor a 0-based "
                 "index",
                 name, (int)fl[nf - 1], f[nf - 1], prim->name ? prim->name : "(unnamed)", names);
      else
        snprintf(msg, len, "parameter '%s': the index must be a non-negative integer", name);
    }
    return DAL_E_ARG;
  }
  char m2[DAL_ERRMSG_LEN];
  if (dal_param_check(sys, &r, m2, sizeof m2)) {
    if (msg && len) snprintf(msg, len, "parameter '%s': %s", name, m2);
    return DAL_E_ARG;
  }
  *out = r;
  return DAL_OK;
}

// validate a value with the builder's checks and messages (validate.c)
static int validate(const dal_system *sys, dal_state *st, const dal_param_ref *r, double v) {
  int t = r->target, i = r->index, rc;
  char what[96];
  switch (r->kind) {
  case DAL_PARAM_MASS:
    return dal__check_mass(st->err, sys->part_names[t], v);
  case DAL_PARAM_PLACE:
  case DAL_PARAM_CONSTRAINT: {
    int place = r->kind == DAL_PARAM_PLACE;
    const dal_primitive *prim = place ? sys->place[t].prim : sys->con[t].prim;
    const double *cur = st->prm.ppool + (place ? sys->place[t].param_off : sys->con[t].param_off);
    snprintf(what, sizeof what, place ? "placing particle '%s'" : "constraint '%s'",
             place ? sys->part_names[t] : sys->con[t].name);
    if ((rc = dal__check_prim_value(st->err, what, prim, i, v)) != 0) return rc;
    // the instance's whole vector with the new value in its domain (a rod of length 0)
    double p[DAL_MAX_PARAM];
    int np = prim->nparam < DAL_MAX_PARAM ? prim->nparam : DAL_MAX_PARAM;
    for (int j = 0; j < np; ++j)
      p[j] = j == i ? v : cur[j];
    return np == prim->nparam ? dal__check_prim_domain(st->err, what, prim, p) : DAL_OK;
  }
  case DAL_PARAM_GRAVITY:
    return dal__check_gravity(st->err, i, v);
  case DAL_PARAM_SPRING_K:
  case DAL_PARAM_SPRING_L:
  case DAL_PARAM_DAMPER_C: {
    int damper = r->kind == DAL_PARAM_DAMPER_C;
    const dal_link *l = damper ? &st->prm.dampers[t] : &st->prm.springs[t];
    const char *kind =
        damper ? (l->b < 0 ? "anchor damper" : "damper") : (l->b < 0 ? "anchor spring" : "spring");
    double k = r->kind == DAL_PARAM_SPRING_L ? l->k : v;
    double L = r->kind == DAL_PARAM_SPRING_L ? v : l->L;
    return dal__check_link(st->err, kind, sys->part_names[l->a], k, L);
  }
  case DAL_PARAM_NONE:
    break;
  }
  return DAL_E_ARG;
}

// the start of every call that changes a state's parameters: the pair, then an idle state
static int parameter_call(const dal_system *sys, dal_state *st, const char *what) {
  int rc = dal__check_pair(sys, st, what);
  if (rc) return rc;
  return dal__check_idle(st, what) ? DAL_E_STATE : DAL_OK;
}

int dal_state_set_param(const dal_system *sys, dal_state *st, const dal_param_ref *ref,
                        double value) {
  int rc = parameter_call(sys, st, "set_param");
  if (rc) return rc;
  char msg[DAL_ERRMSG_LEN];
  if (dal_param_check(sys, ref, msg, sizeof msg)) return DAL_FAIL(st, DAL_E_ARG, "%s", msg);
  rc = validate(sys, st, ref, value);
  if (rc) return rc;
  if (own(sys, st, ref->kind))
    return DAL_FAIL(st, DAL_E_NOMEM, "set_param: out of memory copying the system's parameters");
  dal_params *p = &st->prm;
  switch (ref->kind) {
  case DAL_PARAM_MASS:
    p->own_mass[ref->target] = value;
    subtree_masses(sys, p->own_mass, p->own_mu);
    break;
  case DAL_PARAM_PLACE:
    p->own_ppool[sys->place[ref->target].param_off + ref->index] = value;
    break;
  case DAL_PARAM_CONSTRAINT:
    p->own_ppool[sys->con[ref->target].param_off + ref->index] = value;
    break;
  case DAL_PARAM_GRAVITY:
    p->own_g[ref->index] = value;
    p->has_gravity = 1;
    break;
  case DAL_PARAM_SPRING_K:
    p->own_springs[ref->target].k = value;
    break;
  case DAL_PARAM_SPRING_L:
    p->own_springs[ref->target].L = value;
    break;
  case DAL_PARAM_DAMPER_C:
    p->own_dampers[ref->target].k = value;
    break;
  case DAL_PARAM_NONE:
    break;
  }
  dal__integ_reset(st);
  dal__state_moved(st);
  st->err[0] = 0;
  return DAL_OK;
}

int dal_state_set_param_named(const dal_system *sys, dal_state *st, const char *name,
                              double value) {
  int rc = parameter_call(sys, st, "set_param");
  if (rc) return rc;
  dal_param_ref r;
  char msg[DAL_ERRMSG_LEN];
  if (dal_param_find(sys, name, &r, msg, sizeof msg)) return DAL_FAIL(st, DAL_E_ARG, "%s", msg);
  return dal_state_set_param(sys, st, &r, value);
}

int dal_state_set_mass(const dal_system *sys, dal_state *st, int k, double mass) {
  dal_param_ref r = {DAL_PARAM_MASS, k, 0};
  return dal_state_set_param(sys, st, &r, mass);
}

int dal_state_set_gravity(const dal_system *sys, dal_state *st, const double *g) {
  int rc = parameter_call(sys, st, "set_gravity");
  if (rc) return rc;
  if (!g) return DAL_FAIL(st, DAL_E_ARG, "set_gravity: g is NULL");
  for (int i = 0; i < sys->dim; ++i)
    if (!isfinite(g[i]))
      return DAL_FAIL(st, DAL_E_NONFINITE, "gravity component %d is %g", i, g[i]);
  for (int i = 0; i < sys->dim; ++i) {
    dal_param_ref r = {DAL_PARAM_GRAVITY, 0, i};
    rc = dal_state_set_param(sys, st, &r, g[i]);
    if (rc) return rc;
  }
  return DAL_OK;
}

void dal__params_rewind(dal_state *st) {
  const dal_system *sys = st->sys;
  dal_params *p = &st->prm;
  size_t N = (size_t)sys->N;
  if (p->own_mass) {
    memcpy(p->own_mass, sys->mass, N * sizeof(double));
    memcpy(p->own_mu, sys->mu, N * sizeof(double));
  }
  size_t len = p->own_ppool ? ppool_len(sys) : 0;
  if (len) memcpy(p->own_ppool, sys->ppool, len * sizeof(double));
  if (p->own_springs && sys->nspring)
    memcpy(p->own_springs, sys->springs, (size_t)sys->nspring * sizeof(dal_link));
  if (p->own_dampers && sys->ndamper)
    memcpy(p->own_dampers, sys->dampers, (size_t)sys->ndamper * sizeof(dal_link));
  p->g = sys->g;
  p->has_gravity = sys->has_gravity;
}

int dal_state_reset_params(const dal_system *sys, dal_state *st) {
  int rc = parameter_call(sys, st, "reset_params");
  if (rc) return rc;
  dal__params_free(st);
  dal__params_init(st);
  dal__integ_reset(st);
  dal__state_moved(st);
  return DAL_OK;
}

int dal_state_copy_params(const dal_system *sys, dal_state *dst, const dal_state *src) {
  if (!dst || !src) return DAL_E_ARG;
  if (!sys || dst->sys != sys || src->sys != sys)
    return DAL_FAIL(dst, DAL_E_STATE, "copy_params: the states belong to different systems");
  if (dal__check_idle(dst, "copy_params")) return DAL_E_STATE;
  if (dst == src) return DAL_OK;
  const dal_params *s = &src->prm;
  // reserve every copy first so that a failure leaves dst unchanged
  static const dal_param_kind kinds[] = {DAL_PARAM_MASS, DAL_PARAM_PLACE, DAL_PARAM_SPRING_K,
                                         DAL_PARAM_DAMPER_C};
  const void *owned[] = {s->own_mass, s->own_ppool, s->own_springs, s->own_dampers};
  dal_params keep = dst->prm;
  for (int i = 0; i < 4; ++i)
    if (owned[i] && own(sys, dst, kinds[i])) {
      // undo the copies made here
      if (!keep.own_mass) {
        free(dst->prm.own_mass);
        free(dst->prm.own_mu);
      }
      if (!keep.own_ppool) free(dst->prm.own_ppool);
      if (!keep.own_springs) free(dst->prm.own_springs);
      if (!keep.own_dampers) free(dst->prm.own_dampers);
      dst->prm = keep;
      return DAL_FAIL(dst, DAL_E_NOMEM, "copy_params: out of memory");
    }
  dal_params *d = &dst->prm;
  size_t N = (size_t)sys->N;
  if (s->own_mass) {
    memcpy(d->own_mass, s->own_mass, N * sizeof(double));
    memcpy(d->own_mu, s->own_mu, N * sizeof(double));
  } else if (d->own_mass) {
    memcpy(d->own_mass, sys->mass, N * sizeof(double));
    memcpy(d->own_mu, sys->mu, N * sizeof(double));
  }
  if (d->own_ppool) {
    size_t len = ppool_len(sys);
    if (len) memcpy(d->own_ppool, s->own_ppool ? s->own_ppool : sys->ppool, len * sizeof(double));
  }
  if (d->own_springs && sys->nspring)
    memcpy(d->own_springs, s->own_springs ? s->own_springs : sys->springs,
           (size_t)sys->nspring * sizeof(dal_link));
  if (d->own_dampers && sys->ndamper)
    memcpy(d->own_dampers, s->own_dampers ? s->own_dampers : sys->dampers,
           (size_t)sys->ndamper * sizeof(dal_link));
  memcpy(d->own_g, s->g, sizeof d->own_g);
  d->g = d->own_g;
  d->has_gravity = s->has_gravity;
  dal__integ_reset(dst);
  dal__state_moved(dst);
  return DAL_OK;
}

// the integrator memory kept in a state: dropping it, with the factorization history it holds
void dal__integ_reset(dal_state *st) {
  if (st->integ && st->integ_free) st->integ_free(st->integ);
  st->integ = NULL;
  st->integ_free = NULL;
  dal__kkt_reset(st->kkt);
}
