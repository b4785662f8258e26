// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Compiling a builder into an immutable system: copies, dependency lists, storage offsets.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "codegen/codegen.h"
#include "model.h"

#define BFAIL(code, ...) dal__set_err(b->err, (code), __VA_ARGS__)

static char **dup_names(const dal_vec *v) {
  char **out = calloc((size_t)v->len + 1, sizeof(char *));
  if (!out) return NULL;
  for (int i = 0; i < v->len; ++i) {
    const char *s = ((char **)v->data)[i];
    size_t len = strlen(s);
    out[i] = malloc(len + 1);
    if (!out[i]) {
      for (int j = 0; j < i; ++j)
        free(out[j]);
      free(out);
      return NULL;
    }
    memcpy(out[i], s, len + 1);
  }
  return out;
}

static void *dup_mem(const void *p, size_t size) {
  void *q = malloc(size ? size : 1);
  if (q && size) memcpy(q, p, size);
  return q;
}

// sorted union of two sorted index lists into out; returns its length
static int merge_union(const int *a, int na, const int *b, int nb, int *out) {
  int i = 0, j = 0, k = 0;
  while (i < na || j < nb) {
    int x;
    if (j >= nb || (i < na && a[i] < b[j]))
      x = a[i++];
    else if (i >= na || b[j] < a[i])
      x = b[j++];
    else {
      x = a[i++];
      j++;
    }
    out[k++] = x;
  }
  return k;
}

// make room for `need` ints in a growable array *p of capacity *cap; 0 on success
static int reserve_ints(int **p, size_t *cap, size_t need) {
  if (need <= *cap) return 0;
  size_t nc = *cap ? *cap : 64;
  while (nc < need)
    nc *= 2;
  int *q = realloc(*p, nc * sizeof(int));
  if (!q) return -1;
  *p = q;
  *cap = nc;
  return 0;
}

static int cmp_int(const void *x, const void *y) {
  int a = *(const int *)x, b = *(const int *)y;
  return (a > b) - (a < b);
}

// sorted unique copy of list into out; returns its length
static int sorted_unique(const int *list, int n, int *out) {
  if (n <= 0) return 0; // list may be NULL (empty index pool)
  memcpy(out, list, (size_t)n * sizeof(int));
  qsort(out, (size_t)n, sizeof(int), cmp_int);
  int k = 0;
  for (int i = 0; i < n; ++i)
    if (k == 0 || out[k - 1] != out[i]) out[k++] = out[i];
  return k;
}

// Whether the articulated-body recursion (aba.c) applies: a tree of placements in which every
// coordinate is moved by exactly one placement and listed there once. A coordinate shared
// between placements couples branches the recursion treats as independent, and one that moves
// no particle leaves M singular (the KKT matrix may still be regular). Returns 1, or 0 with
// the reason in why, or -1 when out of memory.
static int recursion_applies(const dal_builder *b, const int *ip, char *why, size_t len) {
  int n = b->coords.len, N = b->parts.len;
  const dal_place *places = b->places.data;
  char **cn = b->coords.data, **pn = b->parts.data;
  if (b->lag || N == 0) {
    snprintf(why, len, "a Lagrangian system has no tree of particle placements");
    return 0;
  }
  if (b->map) {
    snprintf(why, len, "a whole-system map has no tree of particle placements");
    return 0;
  }
  int *owner = malloc(((size_t)n + 1) * sizeof(int));
  if (!owner) {
    snprintf(why, len, "out of memory");
    return -1;
  }
  for (int j = 0; j < n; ++j)
    owner[j] = -1;
  int ok = 1;
  for (int k = 0; k < N && ok; ++k)
    for (int i = 0; i < places[k].ncoord && ok; ++i) {
      int j = ip[places[k].coord_off + i];
      if (owner[j] >= 0) {
        snprintf(why, len, "coordinate '%s' moves both particle '%s' and particle '%s'", cn[j],
                 pn[owner[j]], pn[k]);
        ok = 0;
      }
      owner[j] = k;
    }
  for (int j = 0; j < n && ok; ++j)
    if (owner[j] < 0) {
      snprintf(why, len, "coordinate '%s' moves no particle (M is singular there)", cn[j]);
      ok = 0;
    }
  free(owner);
  return ok;
}

// the model as a whole: coordinates, particles placed, primitive tables still readable, no
// constraints on a Lagrangian system
static int validate_model(dal_builder *b) {
  int n = b->coords.len, N = b->parts.len;
  dal_place *places = b->places.data;
  dal_con *cons = b->cons.data;
  if (n == 0) return BFAIL(DAL_E_ARG, "the model has no generalized coordinates");
  if (!b->lag && N == 0) return BFAIL(DAL_E_ARG, "the model has no particles and no Lagrangian");
  if (!b->map)
    for (int k = 0; k < N; ++k)
      if (!places[k].prim)
        return BFAIL(DAL_E_ARG,
                     "particle '%s' has no position: place it with a primitive "
                     "(dal_builder_place_def) or set a whole-system map",
                     ((char **)b->parts.data)[k]);
  // a primitive table must still be one this library reads (it may have changed since)
  for (int k = 0; k < N && !b->map; ++k) {
    char what[96];
    snprintf(what, sizeof what, "particle '%s'", ((char **)b->parts.data)[k]);
    if (dal__prim_version_ok(places[k].prim, b->err, what)) return DAL_E_ARG;
  }
  for (int i = 0; i < b->cons.len; ++i) {
    char what[96];
    snprintf(what, sizeof what, "constraint '%s'", cons[i].name);
    if (dal__prim_version_ok(cons[i].prim, b->err, what)) return DAL_E_ARG;
  }
  if (b->lag && b->cons.len)
    return BFAIL(DAL_E_ARG,
                 "constraint '%s': constraints need particles or coordinates of a "
                 "particle system, not a Lagrangian system",
                 cons[0].name);
  return DAL_OK;
}

// scratch lists for the dependency unions: an instance's raw coordinate list (repeats
// allowed) or a union of sorted lists
typedef struct dep_scratch {
  int *tmp, *tmp2;
} dep_scratch;

// per-particle dependency coordinates, in placement order (parents come first); -1: no memory
static int particle_deps(const dal_builder *b, dal_system *s, const int *ip, dep_scratch *w) {
  int n = s->n, N = s->N, d = s->dim;
  const dal_place *places = b->places.data;
  int *tmp = w->tmp, *tmp2 = w->tmp2;
  size_t pcap = 0;
  if (reserve_ints(&s->pdep, &pcap, (size_t)N + 1)) return -1;
  s->max_in = 1;
  s->max_out = d;
  for (int k = 0; k < N; ++k) {
    int len;
    if (b->map) {
      for (int j = 0; j < n; ++j)
        tmp[j] = j;
      len = n;
    } else {
      const dal_place *pl = &places[k];
      int nc = sorted_unique(ip + pl->coord_off, pl->ncoord, tmp2);
      if (pl->parent >= 0) {
        int p = pl->parent;
        len = merge_union(s->pdep + s->pdep_off[p], s->pdep_off[p + 1] - s->pdep_off[p], tmp2, nc,
                          tmp);
      } else {
        memcpy(tmp, tmp2, (size_t)nc * sizeof(int));
        len = nc;
      }
      if (pl->prim->nin > s->max_in) s->max_in = pl->prim->nin;
    }
    if (reserve_ints(&s->pdep, &pcap, (size_t)s->pdep_off[k] + (size_t)len)) return -1;
    memcpy(s->pdep + s->pdep_off[k], tmp, (size_t)len * sizeof(int));
    s->pdep_off[k + 1] = s->pdep_off[k] + len;
    s->pj_off[k + 1] = s->pj_off[k] + d * len;
  }
  if (b->map) {
    if (n > s->max_in) s->max_in = n;
    if (N * d > s->max_out) s->max_out = N * d;
  }
  return 0;
}

// constraints: rows, dependency coordinates, compact G offsets; -1: no memory
static int constraint_rows(const dal_builder *b, dal_system *s, const int *ip, dep_scratch *w) {
  const dal_con *cons = b->cons.data;
  int *tmp = w->tmp, *tmp2 = w->tmp2;
  size_t ccap = 0;
  s->ncon = b->cons.len;
  s->con = calloc((size_t)s->ncon + 1, sizeof(dal_con));
  if (!s->con) return -1;
  int m = 0, cdep_total = 0;
  for (int i = 0; i < s->ncon; ++i)
    m += cons[i].prim->nout;
  s->m = m;
  s->row_con = malloc(((size_t)m + 1) * sizeof(int));
  s->con_loff = calloc((size_t)s->ncon + 1, sizeof(int));
  if (!s->row_con || !s->con_loff || reserve_ints(&s->cdep, &ccap, (size_t)s->ncon + 1)) return -1;
  s->g_total = 0;
  for (int i = 0; i < s->ncon; ++i) {
    dal_con *c = &s->con[i];
    *c = cons[i];
    c->name = NULL;
    size_t len = strlen(cons[i].name);
    c->name = malloc(len + 1);
    if (!c->name) return -1;
    memcpy(c->name, cons[i].name, len + 1);
    int nd = sorted_unique(ip + c->coord_off, c->ncoord, tmp);
    for (int a = 0; a < c->npart; ++a) {
      int p = ip[c->part_off + a];
      nd =
          merge_union(tmp, nd, s->pdep + s->pdep_off[p], s->pdep_off[p + 1] - s->pdep_off[p], tmp2);
      memcpy(tmp, tmp2, (size_t)nd * sizeof(int));
    }
    if (reserve_ints(&s->cdep, &ccap, (size_t)cdep_total + (size_t)nd)) return -1;
    c->dep_off = cdep_total;
    c->ndep = nd;
    memcpy(s->cdep + cdep_total, tmp, (size_t)nd * sizeof(int));
    cdep_total += nd;
    c->g_off = s->g_total;
    s->g_total += c->prim->nout * nd;
    s->con_loff[i + 1] = s->con_loff[i] + c->prim->nout * c->prim->nin;
    for (int r = 0; r < c->prim->nout; ++r)
      s->row_con[c->row + r] = i;
    if (c->prim->nin > s->max_in) s->max_in = c->prim->nin;
    if (c->prim->nout > s->max_out) s->max_out = c->prim->nout;
  }
  return 0;
}

// forces: gravity, springs, dampers, potentials and callbacks copied; -1: no memory
static int copy_forces(const dal_builder *b, dal_system *s) {
  s->has_gravity = b->has_gravity;
  memcpy(s->g, b->g, sizeof s->g);
  s->nspring = b->springs.len;
  s->ndamper = b->dampers.len;
  s->npotr = b->potr.len;
  s->npotq = b->potq.len;
  s->nforce = b->forces.len;
  s->ngenforce = b->genforces.len;
  s->springs = dup_mem(b->springs.data, (size_t)s->nspring * sizeof(dal_link));
  s->dampers = dup_mem(b->dampers.data, (size_t)s->ndamper * sizeof(dal_link));
  s->potr = dup_mem(b->potr.data, (size_t)s->npotr * sizeof(dal_cb));
  s->potq = dup_mem(b->potq.data, (size_t)s->npotq * sizeof(dal_cb));
  s->forces = dup_mem(b->forces.data, (size_t)s->nforce * sizeof(dal_cb));
  s->genforces = dup_mem(b->genforces.data, (size_t)s->ngenforce * sizeof(dal_cb));
  return !s->springs || !s->dampers || !s->potr || !s->potq || !s->forces || !s->genforces ? -1 : 0;
}

// the route and the storage it implies, and the tree assembly data; -1: no memory
static int route_and_tree(const dal_builder *b, dal_system *s, int recursive) {
  int n = s->n, N = s->N, d = s->dim, m = s->m;
  // the route (solve.h, "Dynamics routes"): the recursion where it applies, unless there are
  // so many constraint rows that the KKT matrix is cheaper than the m x m loop system
  // (base/bounds.h). (A placement moving more than d coordinates leaves M singular whatever the
  // route: its subtree moves only through its particle's position.)
  // (with a mass matrix that couples few coordinates the sparse KKT matrix wins from
  // DAL_LOOP_ROWS_LOCAL_MAX rows on: base/bounds.h)
  double coupling = 0.0;
  for (int p = 0; p < N; ++p) {
    double nd = s->pdep_off[p + 1] - s->pdep_off[p];
    coupling += nd * nd;
  }
  s->kkt_local = coupling <= DAL_KKT_LOCAL_COUPLING * n;
  int loop_rows_max = s->kkt_local ? DAL_LOOP_ROWS_LOCAL_MAX : DAL_LOOP_ROWS_MAX;
  s->aba = recursive && (b->dynamics == DAL_DYNAMICS_RECURSIVE ||
                         (b->dynamics == DAL_DYNAMICS_AUTO && m <= loop_rows_max));
  // dense mass matrix unless the system is large and needs none (a redundant system applies M
  // through J; the recursion needs no M); large recursive trees without constraints keep no
  // global Jacobians either (dal_state_jacobian forms them from the local blocks)
  s->dense_M = (m == 0 && !s->aba) || n <= DAL_DENSE_M_MAX;
  s->store_J = !(s->aba && m == 0 && n > DAL_DENSE_M_MAX);

  // tree assembly data: subtree masses (parents precede children) and local column offsets
  s->mu = dup_mem(s->mass, (size_t)N * sizeof(double));
  s->ploc_off = calloc((size_t)N + 1, sizeof(int));
  if (!s->mu || !s->ploc_off) return -1;
  for (int k = N - 1; k >= 0 && s->place; --k)
    if (s->place[k].parent >= 0) s->mu[s->place[k].parent] += s->mu[k];
  for (int k = 0; k < N; ++k)
    s->ploc_off[k + 1] = s->ploc_off[k] + (s->place ? d * s->place[k].ncoord : 0);
  return 0;
}

int dal_builder_compile(dal_builder *b, dal_system **out) {
  if (!b) return DAL_E_ARG;
  if (!out) return BFAIL(DAL_E_ARG, "compile: the output pointer is NULL");
  *out = NULL;
  int n = b->coords.len, N = b->parts.len, d = b->dim;
  dal_place *places = b->places.data;
  dal_con *cons = b->cons.data;
  static const int no_ints[1] = {0}; // an empty pool is NULL: ip + 0 must stay valid C
  const int *ip = b->ipool.data ? (const int *)b->ipool.data : no_ints;

  // validate the model as a whole, and the route asked for
  int rc = validate_model(b);
  if (rc) return rc;
  char why[DAL_ERRMSG_LEN / 2];
  int recursive = recursion_applies(b, ip, why, sizeof why);
  if (recursive < 0) return BFAIL(DAL_E_NOMEM, "out of memory compiling the system");
  if (b->dynamics == DAL_DYNAMICS_RECURSIVE && !recursive)
    return BFAIL(DAL_E_UNSUPPORTED,
                 "DAL_DYNAMICS_RECURSIVE does not apply: %s; use DAL_DYNAMICS_AUTO or _DENSE", why);

  // the system's copies of the builder's names, masses, callbacks, pools and placements
  dal_system *s = calloc(1, sizeof *s);
  if (!s) return BFAIL(DAL_E_NOMEM, "out of memory compiling the system");
  s->dim = d;
  s->n = n;
  s->N = N;
  s->coord_names = dup_names(&b->coords);
  s->part_names = dup_names(&b->parts);
  s->mass = dup_mem(b->masses.data, (size_t)N * sizeof(double));
  s->map = b->map;
  s->map_ctx = b->map_ctx;
  s->lag = b->lag;
  s->lag_ctx = b->lag_ctx;
  s->lag_parts = b->lag_parts;
  s->lag_parts_ctx = b->lag_parts_ctx;
  s->ipool = dup_mem(b->ipool.data, (size_t)b->ipool.len * sizeof(int));
  s->ppool = dup_mem(b->ppool.data, (size_t)b->ppool.len * sizeof(double));
  s->place = b->map ? NULL : dup_mem(places, (size_t)N * sizeof(dal_place));
  s->pdep_off = calloc((size_t)N + 1, sizeof(int));
  s->pj_off = calloc((size_t)N + 1, sizeof(int));
  // scratch lists long enough for any instance's coordinate list or a union
  size_t ntmp = (size_t)2 * n + 1;
  for (int k = 0; k < N && !b->map; ++k)
    if ((size_t)places[k].ncoord >= ntmp) ntmp = (size_t)places[k].ncoord + 1;
  for (int i = 0; i < b->cons.len; ++i)
    if ((size_t)cons[i].ncoord >= ntmp) ntmp = (size_t)cons[i].ncoord + 1;
  dep_scratch w = {malloc(ntmp * sizeof(int)), malloc(ntmp * sizeof(int))};
  int ok = s->coord_names && s->part_names && s->mass && s->ipool && s->ppool &&
           (b->map || s->place) && s->pdep_off && s->pj_off && w.tmp && w.tmp2;

  // dependencies of particles and constraints, forces, the route and the tree data
  ok = ok && !particle_deps(b, s, ip, &w) && !constraint_rows(b, s, ip, &w) && !copy_forces(b, s) &&
       !route_and_tree(b, s, recursive);
  free(w.tmp);
  free(w.tmp2);
  if (s->lag_parts && s->max_out < 2 * n) s->max_out = 2 * n; // the parts' outputs (st->jout)
  if (!ok) {
    dal_system_destroy(s);
    return BFAIL(DAL_E_NOMEM, "out of memory compiling the system (%d coordinates, %d particles)",
                 n, N);
  }
  b->err[0] = 0;
  *out = s;
  return DAL_OK;
}

void dal_system_destroy(dal_system *s) {
  if (!s) return;
  dal__eom_free(s->eom);
  if (s->coord_names)
    for (int i = 0; i < s->n; ++i)
      free(s->coord_names[i]);
  if (s->part_names)
    for (int i = 0; i < s->N; ++i)
      free(s->part_names[i]);
  if (s->con)
    for (int i = 0; i < s->ncon; ++i)
      free(s->con[i].name);
  DAL_FREE(s->coord_names, s->part_names, s->mass, s->place, s->ipool, s->ppool, s->pdep_off,
           s->pdep, s->pj_off, s->con_loff, s->mu, s->ploc_off, s->con, s->cdep, s->row_con,
           s->springs, s->dampers, s->potr, s->potq, s->forces, s->genforces, s);
}

int dal_system_dim(const dal_system *s) { return s ? s->dim : 0; }
dal_dynamics dal_system_dynamics(const dal_system *s) {
  return !s ? DAL_DYNAMICS_AUTO : s->aba ? DAL_DYNAMICS_RECURSIVE : DAL_DYNAMICS_DENSE;
}
int dal_system_ncoords(const dal_system *s) { return s ? s->n : 0; }
int dal_system_nparticles(const dal_system *s) { return s ? s->N : 0; }
int dal_system_nconstraints(const dal_system *s) { return s ? s->m : 0; }

const char *dal_system_coord_name(const dal_system *s, int i) {
  return (s && i >= 0 && i < s->n) ? s->coord_names[i] : NULL;
}

const char *dal_system_particle_name(const dal_system *s, int k) {
  return (s && k >= 0 && k < s->N) ? s->part_names[k] : NULL;
}

const char *dal_system_constraint_name(const dal_system *s, int i) {
  return (s && i >= 0 && i < s->m) ? s->con[s->row_con[i]].name : NULL;
}

double dal_system_mass(const dal_system *s, int k) {
  return (s && k >= 0 && k < s->N) ? s->mass[k] : NAN;
}
