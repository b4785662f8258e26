// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The mutable model builder: validates every addition and names the culprit on error.
#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model.h"

// grow a vector to hold one more element of size sz; returns the new slot or NULL
static void *vec_push(dal_vec *v, size_t sz) {
  if (v->len == v->cap) {
    int cap = v->cap ? 2 * v->cap : 8;
    void *p = realloc(v->data, (size_t)cap * sz);
    if (!p) return NULL;
    v->data = p;
    v->cap = cap;
  }
  char *slot = (char *)v->data + (size_t)v->len * sz;
  memset(slot, 0, sz);
  v->len++;
  return slot;
}

static char *dup_name(const char *name, char prefix, int i) {
  char tmp[32];
  if (!name) {
    snprintf(tmp, sizeof tmp, "%c%d", prefix, i);
    name = tmp;
  }
  size_t len = strlen(name);
  char *s = malloc(len + 1);
  if (s) memcpy(s, name, len + 1);
  return s;
}

int dal_builder_create(int dim, dal_builder **out) {
  if (!out) return DAL_E_ARG;
  *out = NULL;
  if (dim != 0 && dim != 2 && dim != 3) return DAL_E_ARG;
  dal_builder *b = calloc(1, sizeof *b);
  if (!b) return DAL_E_NOMEM;
  b->dim = dim;
  *out = b;
  return DAL_OK;
}

void dal_builder_destroy(dal_builder *b) {
  if (!b) return;
  for (int i = 0; i < b->coords.len; ++i)
    free(((char **)b->coords.data)[i]);
  for (int i = 0; i < b->parts.len; ++i)
    free(((char **)b->parts.data)[i]);
  for (int i = 0; i < b->cons.len; ++i)
    free(((dal_con *)b->cons.data)[i].name);
  dal_vec *vs[] = {&b->coords, &b->parts,  &b->masses,   &b->places,  &b->cons,
                   &b->ipool,  &b->ppool,  &b->springs,  &b->dampers, &b->potr,
                   &b->potq,   &b->forces, &b->genforces};
  for (size_t i = 0; i < sizeof vs / sizeof vs[0]; ++i)
    free(vs[i]->data);
  free(b);
}

const char *dal_builder_errmsg(const dal_builder *b) { return b ? b->err : ""; }

#define BFAIL(code, ...) dal__set_err(b->err, (code), __VA_ARGS__)

// every builder call starts so: a NULL builder is refused, and the message is always that of
// the last call
#define BUILDER_CALL(b)                                                                            \
  do {                                                                                             \
    if (!(b)) return DAL_E_ARG;                                                                    \
    (b)->err[0] = 0;                                                                               \
  } while (0)

// a nonzero subnormal (|x| < DBL_MIN) carries fewer than 53 significant bits (validate.c)
static int subnormal(double x) { return x != 0.0 && fabs(x) < DBL_MIN; }

int dal_builder_add_coord(dal_builder *b, const char *name, int *index) {
  BUILDER_CALL(b);
  char **slot = vec_push(&b->coords, sizeof(char *));
  if (!slot) return BFAIL(DAL_E_NOMEM, "out of memory adding a coordinate");
  *slot = dup_name(name, 'q', b->coords.len - 1);
  if (!*slot) {
    b->coords.len--;
    return BFAIL(DAL_E_NOMEM, "out of memory adding a coordinate");
  }
  if (index) *index = b->coords.len - 1;
  return DAL_OK;
}

int dal_builder_add_particle(dal_builder *b, const char *name, double mass, int *index) {
  BUILDER_CALL(b);
  const char *nm = name ? name : "(unnamed)";
  int mrc = dal__check_mass(b->err, nm, mass);
  if (mrc) return mrc;
  if (b->lag)
    return BFAIL(DAL_E_ARG,
                 "particle '%s': the system is given by a Lagrangian; it has no "
                 "particles",
                 nm);
  if (b->dim == 0)
    return BFAIL(DAL_E_ARG,
                 "particle '%s': the builder was created with dim 0 (a Lagrangian system); "
                 "create it with dim 2 or 3 for particles",
                 nm);
  if (b->masses.cap == b->masses.len || b->places.cap == b->places.len ||
      b->parts.cap == b->parts.len) {
    // reserve all three before writing any, so a failure changes nothing
    double *m = vec_push(&b->masses, sizeof(double));
    if (!m) return BFAIL(DAL_E_NOMEM, "out of memory adding particle '%s'", nm);
    b->masses.len--;
    dal_place *p = vec_push(&b->places, sizeof(dal_place));
    if (!p) return BFAIL(DAL_E_NOMEM, "out of memory adding particle '%s'", nm);
    b->places.len--;
    char **s = vec_push(&b->parts, sizeof(char *));
    if (!s) return BFAIL(DAL_E_NOMEM, "out of memory adding particle '%s'", nm);
    b->parts.len--;
  }
  char *copy = dup_name(name, 'p', b->parts.len);
  if (!copy) return BFAIL(DAL_E_NOMEM, "out of memory adding particle '%s'", nm);
  *(double *)vec_push(&b->masses, sizeof(double)) = mass;
  dal_place *p = vec_push(&b->places, sizeof(dal_place));
  p->parent = -1;
  *(char **)vec_push(&b->parts, sizeof(char *)) = copy;
  if (index) *index = b->parts.len - 1;
  return DAL_OK;
}

// append n elements of size sz to a pool; returns their offset or -1 on memory failure
static int pool_append(dal_vec *v, size_t sz, int n, const void *x) {
  int off = v->len;
  for (int i = 0; i < n; ++i) {
    void *s = vec_push(v, sz);
    if (!s) {
      v->len = off;
      return -1;
    }
    memcpy(s, (const char *)x + (size_t)i * sz, sz);
  }
  return off;
}
static int pool_ints(dal_builder *b, int n, const int *x) {
  return pool_append(&b->ipool, sizeof(int), n, x);
}
static int pool_doubles(dal_builder *b, int n, const double *x) {
  return pool_append(&b->ppool, sizeof(double), n, x);
}

// the "unset" marker of def parameters: a quiet NaN with a payload no arithmetic produces
static const uint64_t unset_bits = 0x7ff8da1dda1d0000u;

static double unset_param(void) {
  double x;
  memcpy(&x, &unset_bits, sizeof x);
  return x;
}

static int is_unset(double x) {
  uint64_t u;
  memcpy(&u, &x, sizeof u);
  return u == unset_bits;
}

int dal__prim_version_ok(const dal_primitive *prim, char *err, const char *what) {
  if (prim->version < 1)
    return dal__set_err(err, DAL_E_ARG,
                        "%s: primitive '%s' has table version %d; set .version = "
                        "DAL_PRIMITIVE_VERSION (%d) in its definition",
                        what, prim->name ? prim->name : "(unnamed)", prim->version,
                        DAL_PRIMITIVE_VERSION);
  if (prim->version > DAL_PRIMITIVE_VERSION)
    return dal__set_err(err, DAL_E_ARG,
                        "%s: primitive '%s' was written for table version %d, newer than this "
                        "library's %d (dalembert %s); link a newer dalembert or set .version to "
                        "%d",
                        what, prim->name ? prim->name : "(unnamed)", prim->version,
                        DAL_PRIMITIVE_VERSION, dal_version(), DAL_PRIMITIVE_VERSION);
  return DAL_OK;
}

// resolve an instance's parameters into out (prim->nparam values): the first ngiven from
// given (unset markers allowed), the rest unset; unset ones take the primitive's defaults
static int resolve_params(dal_builder *b, const char *what, const dal_primitive *prim, int ngiven,
                          const double *given, double *out) {
  char nb[16];
  for (int i = 0; i < prim->nparam; ++i) {
    double x = i < ngiven ? given[i] : unset_param();
    if (is_unset(x)) {
      double dflt = (prim->version >= 2 && prim->param_defaults) ? prim->param_defaults[i] : NAN;
      if (isnan(dflt))
        return BFAIL(DAL_E_ARG,
                     "%s: parameter '%s' of '%s' (index %d) is required and was not set; "
                     "give it a value (see the primitive's documentation)",
                     what, dal__param_name(prim, i, nb, sizeof nb), prim->name, i);
      x = dflt;
    }
    int rc = dal__check_prim_value(b->err, what, prim, i, x);
    if (rc) return rc;
    out[i] = x;
  }
  // a built-in's parameters must lie in their domain (a rod of length 0, a zero normal)
  return dal__check_prim_domain(b->err, what, prim, out);
}

// shared validation of a primitive instance: version, counts, coordinate indices
static int check_instance(dal_builder *b, const char *what, const dal_primitive *prim, int nfixed,
                          int ncoords, const int *coords, int nparam, const double *param) {
  if (!prim || !prim->eval)
    return BFAIL(DAL_E_ARG, "%s: primitive is NULL or has no eval function", what);
  // the primitive's own definition (a user primitive may be malformed)
  if (!prim->name || prim->nin < 0 || prim->nout < 1 || prim->nparam < 0)
    return BFAIL(DAL_E_ARG,
                 "%s: primitive '%s' is malformed (nin = %d, nout = %d, nparam = %d): it needs a "
                 "name, nin >= 0, nout >= 1 and nparam >= 0",
                 what, prim->name ? prim->name : "(no name)", prim->nin, prim->nout, prim->nparam);
  int rc = dal__prim_version_ok(prim, b->err, what);
  if (rc) return rc;
  if (ncoords < 0 || (ncoords > 0 && !coords))
    return BFAIL(DAL_E_ARG, "%s: %d coordinates given with a %s list", what, ncoords,
                 coords ? "non-NULL" : "NULL");
  if (prim->nin != nfixed + ncoords)
    return BFAIL(DAL_E_ARG,
                 "%s: primitive '%s' takes %d inputs but %d were given (%d from particles + %d "
                 "coordinates); see its documentation in primitives.h",
                 what, prim->name, prim->nin, nfixed + ncoords, nfixed, ncoords);
  if (nparam < 0 || nparam > prim->nparam || (nparam > 0 && !param))
    return BFAIL(DAL_E_ARG, "%s: primitive '%s' takes %d parameters but %d were given", what,
                 prim->name, prim->nparam, nparam);
  for (int i = 0; i < ncoords; ++i)
    if (coords[i] < 0 || coords[i] >= b->coords.len)
      return BFAIL(DAL_E_ARG, "%s: coordinate index %d (input %d) out of range [0, %d)", what,
                   coords[i], i, b->coords.len);
  return DAL_OK;
}

// placement with a parameter list of ngiven values (unset markers allowed)
static int place(dal_builder *b, int particle, const dal_primitive *prim, int parent, int ncoords,
                 const int *coords, int nparam, const double *param, void *ctx) {
  if (particle < 0 || particle >= b->parts.len)
    return BFAIL(DAL_E_ARG, "place: particle index %d out of range [0, %d)", particle,
                 b->parts.len);
  const char *pn = ((char **)b->parts.data)[particle];
  char what[96];
  snprintf(what, sizeof what, "placing particle '%s'", pn);
  if (b->map) return BFAIL(DAL_E_ARG, "%s: a whole-system map is set; use one or the other", what);
  dal_place *pl = &((dal_place *)b->places.data)[particle];
  if (pl->prim) return BFAIL(DAL_E_ARG, "%s: the particle is already placed", what);
  if (parent >= 0) {
    if (parent >= b->parts.len || parent == particle)
      return BFAIL(DAL_E_ARG, "%s: parent index %d invalid", what, parent);
    if (!((dal_place *)b->places.data)[parent].prim)
      return BFAIL(DAL_E_ARG, "%s: parent '%s' must be placed first", what,
                   ((char **)b->parts.data)[parent]);
    // kinematics runs in particle order, so a parent must precede its children
    if (parent > particle)
      return BFAIL(DAL_E_ARG,
                   "%s: parent '%s' (particle %d) must be added before the particle it carries "
                   "(particle %d); add particles from the root outwards",
                   what, ((char **)b->parts.data)[parent], parent, particle);
  }
  int rc = check_instance(b, what, prim, parent >= 0 ? b->dim : 0, ncoords, coords, nparam, param);
  if (rc) return rc;
  if (prim->nout != b->dim)
    return BFAIL(DAL_E_ARG, "%s: primitive '%s' gives %d outputs but the scene is %dD", what,
                 prim->name, prim->nout, b->dim);
  double *full = prim->nparam ? malloc((size_t)prim->nparam * sizeof(double)) : NULL;
  if (prim->nparam && !full) return BFAIL(DAL_E_NOMEM, "%s: out of memory", what);
  rc = resolve_params(b, what, prim, nparam, param, full);
  if (rc) {
    free(full);
    return rc;
  }
  int coff = pool_ints(b, ncoords, coords);
  int poff = pool_doubles(b, prim->nparam, full);
  free(full);
  if (coff < 0 || poff < 0) return BFAIL(DAL_E_NOMEM, "%s: out of memory", what);
  pl = &((dal_place *)b->places.data)[particle];
  pl->prim = prim;
  pl->ctx = ctx;
  pl->parent = parent;
  pl->ncoord = ncoords;
  pl->coord_off = coff;
  pl->param_off = poff;
  return DAL_OK;
}

int dal_builder_set_map(dal_builder *b, dal_map_fn *fn, void *ctx) {
  BUILDER_CALL(b);
  if (!fn) return BFAIL(DAL_E_ARG, "set_map: map function is NULL");
  for (int k = 0; k < b->places.len; ++k)
    if (((dal_place *)b->places.data)[k].prim)
      return BFAIL(DAL_E_ARG, "set_map: particle '%s' is already placed by a primitive",
                   ((char **)b->parts.data)[k]);
  b->map = fn;
  b->map_ctx = ctx;
  return DAL_OK;
}

int dal_builder_set_lagrangian(dal_builder *b, dal_lagrangian_fn *fn, void *ctx) {
  BUILDER_CALL(b);
  if (!fn) return BFAIL(DAL_E_ARG, "set_lagrangian: Lagrangian function is NULL");
  if (b->parts.len)
    return BFAIL(DAL_E_ARG,
                 "set_lagrangian: the system already has %d particles; a "
                 "Lagrangian system has none",
                 b->parts.len);
  b->lag = fn;
  b->lag_ctx = ctx;
  return DAL_OK;
}

int dal__builder_set_lagrangian_parts(dal_builder *b, dal__lagrangian_parts_fn *fn, void *ctx) {
  BUILDER_CALL(b);
  if (!b->lag) return BFAIL(DAL_E_ARG, "set_lagrangian_parts: set the Lagrangian first");
  b->lag_parts = fn;
  b->lag_parts_ctx = ctx;
  return DAL_OK;
}

static int add_constraint(dal_builder *b, const char *name, const dal_primitive *prim, int nparts,
                          const int *parts, int ncoords, const int *coords, int nparam,
                          const double *param, void *ctx, int *index) {
  char what[96];
  snprintf(what, sizeof what, "constraint '%s'", name ? name : "(unnamed)");
  if (nparts < 0 || (nparts > 0 && !parts))
    return BFAIL(DAL_E_ARG, "%s: %d particles given with a %s list", what, nparts,
                 parts ? "non-NULL" : "NULL");
  for (int i = 0; i < nparts; ++i)
    if (parts[i] < 0 || parts[i] >= b->parts.len)
      return BFAIL(DAL_E_ARG, "%s: particle index %d (input %d) out of range [0, %d)", what,
                   parts[i], i, b->parts.len);
  int rc = check_instance(b, what, prim, nparts * b->dim, ncoords, coords, nparam, param);
  if (rc) return rc;
  if (prim->nout < 1)
    return BFAIL(DAL_E_ARG, "%s: primitive '%s' has no outputs", what, prim->name);
  double *full = prim->nparam ? malloc((size_t)prim->nparam * sizeof(double)) : NULL;
  if (prim->nparam && !full) return BFAIL(DAL_E_NOMEM, "%s: out of memory", what);
  rc = resolve_params(b, what, prim, nparam, param, full);
  if (rc) {
    free(full);
    return rc;
  }
  int row = 0;
  for (int i = 0; i < b->cons.len; ++i)
    row += ((dal_con *)b->cons.data)[i].prim->nout;
  int poff = pool_ints(b, nparts, parts);
  int coff = pool_ints(b, ncoords, coords);
  int pm = pool_doubles(b, prim->nparam, full);
  free(full);
  dal_con *c = (poff < 0 || coff < 0 || pm < 0) ? NULL : vec_push(&b->cons, sizeof(dal_con));
  char *nm = c ? dup_name(name, 'c', b->cons.len - 1) : NULL;
  if (!nm) {
    if (c) b->cons.len--;
    return BFAIL(DAL_E_NOMEM, "%s: out of memory", what);
  }
  c->name = nm;
  c->prim = prim;
  c->ctx = ctx;
  c->npart = nparts;
  c->part_off = poff;
  c->ncoord = ncoords;
  c->coord_off = coff;
  c->param_off = pm;
  c->row = row;
  if (index) *index = row;
  return DAL_OK;
}

// ---------------------------------------------------------------------------------------
// element definitions

#define DEF_COOKIE 0x0da1def5

dal_place_def dal_default_place_def(void) {
  dal_place_def d;
  memset(&d, 0, sizeof d);
  d.parent = -1;
  for (int i = 0; i < DAL_MAX_PARAM; ++i)
    d.param[i] = unset_param();
  d.cookie = DEF_COOKIE;
  return d;
}

dal_constraint_def dal_default_constraint_def(void) {
  dal_constraint_def d;
  memset(&d, 0, sizeof d);
  for (int i = 0; i < DAL_MAX_PARAM; ++i)
    d.param[i] = unset_param();
  d.cookie = DEF_COOKIE;
  return d;
}

dal_spring_def dal_default_spring_def(void) {
  dal_spring_def d;
  memset(&d, 0, sizeof d);
  d.a = -1;
  d.b = -1;
  d.cookie = DEF_COOKIE;
  return d;
}

dal_damper_def dal_default_damper_def(void) {
  dal_damper_def d;
  memset(&d, 0, sizeof d);
  d.a = -1;
  d.b = -1;
  d.cookie = DEF_COOKIE;
  return d;
}

// a def's parameters: param[] entries beyond the primitive's count left unset, or all of them
// unset when the def gives a param_list; *np and *par receive the list the instance reads
static int def_params(dal_builder *b, const char *what, const dal_primitive *prim,
                      const double *param, const double *list, int nlist, int *np,
                      const double **par) {
  *np = prim && prim->nparam > 0 ? prim->nparam : 0;
  *par = param;
  // a malformed count (nparam < 0) is reported by check_instance; never index param[-1]
  if (!prim || prim->nparam < 0) return DAL_OK;
  if (list || nlist) {
    for (int i = 0; i < DAL_MAX_PARAM; ++i)
      if (!is_unset(param[i]))
        return BFAIL(DAL_E_ARG,
                     "%s: both param[%d] and a param_list are given; give the parameters in "
                     "one of them",
                     what, i);
    if (nlist < 0 || nlist > prim->nparam || (nlist > 0 && !list))
      return BFAIL(
          DAL_E_ARG, "%s: param_list holds %d values%s but primitive '%s' takes %d parameters",
          what, nlist, list ? "" : " at NULL", prim->name ? prim->name : "(unnamed)", prim->nparam);
    *np = nlist;
    *par = list;
    return DAL_OK;
  }
  int np_in = prim->nparam < DAL_MAX_PARAM ? prim->nparam : DAL_MAX_PARAM;
  for (int i = np_in; i < DAL_MAX_PARAM; ++i)
    if (!is_unset(param[i]))
      return BFAIL(DAL_E_ARG,
                   "%s: param[%d] is set but primitive '%s' takes only %d parameters; check the "
                   "index enum used",
                   what, i, prim->name ? prim->name : "(unnamed)", prim->nparam);
  if (prim->nparam > DAL_MAX_PARAM)
    return BFAIL(DAL_E_ARG,
                 "%s: primitive '%s' takes %d parameters, more than param[] holds (%d); give "
                 "them in the def's param_list",
                 what, prim->name ? prim->name : "(unnamed)", prim->nparam, DAL_MAX_PARAM);
  return DAL_OK;
}

#define DEF_CHECK(def, kind)                                                                       \
  do {                                                                                             \
    if (!(def)) return BFAIL(DAL_E_ARG, "%s: def is NULL", kind);                                  \
    if ((def)->cookie != DEF_COOKIE)                                                               \
      return BFAIL(DAL_E_ARG,                                                                      \
                   "%s: the def was not initialized; start from dal_default_%s() and then "        \
                   "set fields",                                                                   \
                   kind, kind);                                                                    \
  } while (0)

int dal_builder_place_def(dal_builder *b, int particle, const dal_place_def *def) {
  BUILDER_CALL(b);
  DEF_CHECK(def, "place_def");
  char what[96];
  snprintf(what, sizeof what, "placing particle %d", particle);
  if (particle >= 0 && particle < b->parts.len)
    snprintf(what, sizeof what, "placing particle '%s'", ((char **)b->parts.data)[particle]);
  int np;
  const double *par;
  int rc = def_params(b, what, def->prim, def->param, def->param_list, def->nparam_list, &np, &par);
  if (rc) return rc;
  return place(b, particle, def->prim, def->parent, def->ncoords, def->coords, np, par, def->ctx);
}

int dal_builder_add_constraint_def(dal_builder *b, const dal_constraint_def *def, int *index) {
  BUILDER_CALL(b);
  DEF_CHECK(def, "constraint_def");
  char what[96];
  snprintf(what, sizeof what, "constraint '%s'", def->name ? def->name : "(unnamed)");
  int np;
  const double *par;
  int rc = def_params(b, what, def->prim, def->param, def->param_list, def->nparam_list, &np, &par);
  if (rc) return rc;
  return add_constraint(b, def->name, def->prim, def->nparts, def->parts, def->ncoords, def->coords,
                        np, par, def->ctx, index);
}

int dal_builder_set_gravity(dal_builder *b, const double *g) {
  BUILDER_CALL(b);
  if (!g) return BFAIL(DAL_E_ARG, "set_gravity: g is NULL");
  if (b->dim == 0)
    return BFAIL(DAL_E_ARG, "set_gravity: the builder has dim 0 (a Lagrangian system has no "
                            "space); put gravity into the Lagrangian");
  for (int i = 0; i < b->dim; ++i) {
    int rc = dal__check_gravity(b->err, i, g[i]);
    if (rc) return rc;
  }
  memcpy(b->g, g, (size_t)b->dim * sizeof(double));
  b->has_gravity = 1;
  return DAL_OK;
}

int dal_builder_set_dynamics(dal_builder *b, dal_dynamics how) {
  if (!b) return DAL_E_ARG;
  if (how != DAL_DYNAMICS_AUTO && how != DAL_DYNAMICS_DENSE && how != DAL_DYNAMICS_RECURSIVE)
    return BFAIL(DAL_E_ARG,
                 "set_dynamics: unknown route %d (DAL_DYNAMICS_AUTO, _DENSE or "
                 "_RECURSIVE)",
                 (int)how);
  b->dynamics = how;
  return DAL_OK;
}

static int add_link(dal_builder *b, dal_vec *v, const char *kind, int pa, int pb, const double *x0,
                    dal_path_fn *fn, void *ctx, double k, double L) {
  if (pa < 0 || pa >= b->parts.len)
    return BFAIL(DAL_E_ARG, "%s: particle index %d out of range [0, %d)", kind, pa, b->parts.len);
  if (pb >= b->parts.len || pb == pa || (pb < -1))
    return BFAIL(DAL_E_ARG, "%s: second particle index %d invalid", kind, pb);
  int rc = dal__check_link(b->err, kind, ((char **)b->parts.data)[pa], k, L);
  if (rc) return rc;
  if (pb < 0 && x0)
    for (int i = 0; i < b->dim; ++i)
      if (!isfinite(x0[i]) || subnormal(x0[i]))
        return BFAIL(isfinite(x0[i]) ? DAL_E_ARG : DAL_E_NONFINITE,
                     "%s on particle '%s': anchor component %d is %g%s", kind,
                     ((char **)b->parts.data)[pa], i, x0[i],
                     isfinite(x0[i]) ? ", subnormal; " DAL__SUBNORMAL_REMEDY : "");
  dal_link *l = vec_push(v, sizeof(dal_link));
  if (!l) return BFAIL(DAL_E_NOMEM, "%s: out of memory", kind);
  l->a = pa;
  l->b = pb;
  l->k = k;
  l->L = L;
  if (pb < 0 && x0) memcpy(l->x0, x0, (size_t)b->dim * sizeof(double));
  l->fn = pb < 0 ? fn : NULL;
  l->ctx = ctx;
  return DAL_OK;
}

int dal_builder_add_spring_def(dal_builder *b, const dal_spring_def *def) {
  BUILDER_CALL(b);
  DEF_CHECK(def, "spring_def");
  int anchored = def->b < 0;
  if (def->b < -1) return BFAIL(DAL_E_ARG, "spring: second particle index %d invalid", def->b);
  return add_link(b, &b->springs, anchored ? "anchor spring" : "spring", def->a, def->b,
                  anchored ? def->anchor : NULL, def->path, def->ctx, def->k, def->length);
}

int dal_builder_add_damper_def(dal_builder *b, const dal_damper_def *def) {
  BUILDER_CALL(b);
  DEF_CHECK(def, "damper_def");
  int anchored = def->b < 0;
  if (def->b < -1) return BFAIL(DAL_E_ARG, "damper: second particle index %d invalid", def->b);
  return add_link(b, &b->dampers, anchored ? "anchor damper" : "damper", def->a, def->b,
                  anchored ? def->anchor : NULL, def->path, def->ctx, def->c, 0.0);
}

static int add_cb(dal_builder *b, dal_vec *v, const char *kind, int isnull, dal_cb cb) {
  if (isnull) return BFAIL(DAL_E_ARG, "%s: function is NULL", kind);
  dal_cb *c = vec_push(v, sizeof(dal_cb));
  if (!c) return BFAIL(DAL_E_NOMEM, "%s: out of memory", kind);
  *c = cb;
  return DAL_OK;
}

int dal_builder_add_potential_r(dal_builder *b, dal_potential_r_fn *fn, void *ctx) {
  BUILDER_CALL(b);
  dal_cb cb = {.fn.potr = fn, .ctx = ctx};
  return add_cb(b, &b->potr, "potential U(r,t)", fn == NULL, cb);
}

int dal_builder_add_potential_q(dal_builder *b, dal_potential_q_fn *fn, void *ctx) {
  BUILDER_CALL(b);
  dal_cb cb = {.fn.potq = fn, .ctx = ctx};
  return add_cb(b, &b->potq, "potential U(q,t)", fn == NULL, cb);
}

int dal_builder_add_force(dal_builder *b, dal_force_fn *fn, void *ctx) {
  BUILDER_CALL(b);
  dal_cb cb = {.fn.force = fn, .ctx = ctx};
  return add_cb(b, &b->forces, "force callback", fn == NULL, cb);
}

int dal_builder_add_genforce(dal_builder *b, dal_genforce_fn *fn, void *ctx) {
  BUILDER_CALL(b);
  dal_cb cb = {.fn.gen = fn, .ctx = ctx};
  return add_cb(b, &b->genforces, "generalized force callback", fn == NULL, cb);
}
