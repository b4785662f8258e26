// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Named output columns of a state (output.h): a selection by name or glob, a row, a header.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/base.h"
#include "dalembert/output.h"
#include "drive/drive.h"

// what a column reads
enum {
  COL_T,
  COL_Q,
  COL_QDOT,
  COL_X, // position component (axis in sub)
  COL_V,
  COL_R, // reaction
  COL_J, // joint force
  COL_LAMBDA,
  COL_TE, // kinetic energy T
  COL_U,
  COL_E,
  COL_H,
  COL_P,
  COL_W,
};

typedef struct col {
  int kind, index, sub;
  char *name; // owned: names of any length (particles, coordinates, constraints)
} col;

struct dal_columns {
  const dal_system *sys;
  int n, cap;
  col *c;
  unsigned need; // DAL_P_* products a row reads
  int joint;     // a row reads joint forces
  int work;      // a row reads W
};

// glob match: '*' any run, '?' one character
static int glob(const char *p, const char *s) {
  for (; *p; ++p, ++s) {
    if (*p == '*') {
      while (p[1] == '*')
        ++p;
      if (!p[1]) return 1;
      for (; *s; ++s)
        if (glob(p + 1, s)) return 1;
      return glob(p + 1, s);
    }
    if (!*s || (*p != '?' && *p != *s)) return 0;
  }
  return !*s;
}

// a column named a b c (concatenated; b and c may be empty)
static int push(dal_columns *cs, int kind, int index, int sub, const char *a, const char *b,
                const char *c3) {
  size_t la = strlen(a), lb = strlen(b), lc = strlen(c3);
  char *name = malloc(la + lb + lc + 1);
  if (!name) return DAL_E_NOMEM;
  memcpy(name, a, la);
  memcpy(name + la, b, lb);
  memcpy(name + la + lb, c3, lc + 1);
  if (cs->n == cs->cap) {
    int cap = cs->cap ? 2 * cs->cap : 16;
    col *c = realloc(cs->c, (size_t)cap * sizeof *c);
    if (!c) {
      free(name);
      return DAL_E_NOMEM;
    }
    cs->c = c;
    cs->cap = cap;
  }
  col *c = &cs->c[cs->n++];
  c->kind = kind;
  c->index = index;
  c->sub = sub;
  c->name = name;
  return DAL_OK;
}

static const char *const axes = "xyz";

// one item of the selection: the columns it names, or DAL_E_ARG with msg
static int item(dal_columns *cs, const char *it, char *msg, size_t msglen) {
  const dal_system *sys = cs->sys;
  static const struct {
    const char *name;
    int kind;
    unsigned need;
  } scalars[] = {{"t", COL_T, 0},
                 {"T", COL_TE, DAL_P_DYN},
                 {"U", COL_U, DAL_P_DYN},
                 {"E", COL_E, DAL_P_DYN},
                 {"h", COL_H, DAL_P_DYN | DAL_P_OUT},
                 {"P", COL_P, DAL_P_POW},
                 {"W", COL_W, 0}};
  for (size_t k = 0; k < sizeof scalars / sizeof *scalars; ++k)
    if (!strcmp(it, scalars[k].name)) {
      cs->need |= scalars[k].need;
      if (scalars[k].kind == COL_W) cs->work = 1;
      return push(cs, scalars[k].kind, 0, 0, it, "", "");
    }
  const char *colon = strchr(it, ':');
  if (!colon) {
    if (msg)
      snprintf(msg, msglen,
               "columns: unknown column '%s'; columns are t, T, U, E, h, P, W and q:, qdot:, x:, "
               "y:, z:, vx:, vy:, vz:, Rx:, Ry:, Rz:, Jx:, Jy:, Jz:, lambda: followed by a name "
               "or a glob (output.h)",
               it);
    return DAL_E_ARG;
  }
  char kind[16];
  size_t kl = (size_t)(colon - it);
  if (kl >= sizeof kind) kl = sizeof kind - 1;
  memcpy(kind, it, kl);
  kind[kl] = 0;
  const char *pat = colon + 1;
  int before = cs->n, d = sys->dim, rc = DAL_OK;
  if (!strcmp(kind, "q") || !strcmp(kind, "qdot")) {
    int dot = kind[1] != 0;
    for (int i = 0; i < sys->n && !rc; ++i)
      if (glob(pat, sys->coord_names[i])) {
        rc = push(cs, dot ? COL_QDOT : COL_Q, i, 0, sys->coord_names[i], dot ? "_dot" : "", "");
      }
    if (before == cs->n && !rc) goto none_coord;
    return rc;
  }
  if (!strcmp(kind, "lambda")) {
    for (int c = 0; c < sys->ncon && !rc; ++c) {
      const dal_con *con = &sys->con[c];
      if (!con->name || !glob(pat, con->name)) continue;
      int rows = con->prim->nout;
      for (int i = 0; i < rows && !rc; ++i) {
        char row[16] = "";
        if (rows > 1) snprintf(row, sizeof row, ".%d", i);
        rc = push(cs, COL_LAMBDA, con->row + i, 0, "lambda:", con->name, row);
      }
    }
    cs->need |= DAL_P_ACC;
    if (before == cs->n && !rc) {
      if (msg) {
        int w = snprintf(msg, msglen, "columns: '%s': no named constraint matches '%s' (", it, pat);
        int any = 0;
        for (int c = 0; c < sys->ncon && w >= 0 && (size_t)w < msglen; ++c)
          if (sys->con[c].name)
            w += snprintf(msg + w, msglen - (size_t)w, "%s%s",
                          any++ ? ", " : "constraints: ", sys->con[c].name);
        if (w >= 0 && (size_t)w < msglen)
          snprintf(msg + w, msglen - (size_t)w, "%s)", any ? "" : "the system has none");
      }
      return DAL_E_ARG;
    }
    return rc;
  }
  // particle columns: x y z, vx vy vz, Rx Ry Rz, Jx Jy Jz
  int ck = -1, axis = -1;
  if (strlen(kind) == 1 && strchr(axes, kind[0]))
    ck = COL_X, axis = (int)(strchr(axes, kind[0]) - axes);
  else if (strlen(kind) == 2 && strchr(axes, kind[1])) {
    axis = (int)(strchr(axes, kind[1]) - axes);
    ck = kind[0] == 'v' ? COL_V : kind[0] == 'R' ? COL_R : kind[0] == 'J' ? COL_J : -1;
  }
  if (ck < 0) {
    if (msg)
      snprintf(msg, msglen,
               "columns: '%s': unknown kind '%s:'; kinds are q:, qdot:, x:, y:, z:, vx:, vy:, "
               "vz:, Rx:, Ry:, Rz:, Jx:, Jy:, Jz:, lambda: (output.h)",
               it, kind);
    return DAL_E_ARG;
  }
  if (axis >= d) {
    if (msg)
      snprintf(msg, msglen, "columns: '%s': the system is %d-D (no %c axis)", it, d, axes[axis]);
    return DAL_E_ARG;
  }
  if (ck == COL_J && !sys->place) {
    if (msg)
      snprintf(msg, msglen,
               "columns: '%s': joint forces need particles placed one by one (the system has "
               "one map for all, or a Lagrangian); use Rx:, Ry:, Rz: (the reactions)",
               it);
    return DAL_E_ARG;
  }
  cs->need |= ck == COL_X || ck == COL_V ? DAL_P_KIN : DAL_P_OUT;
  if (ck == COL_J) cs->joint = 1;
  for (int k = 0; k < sys->N && !rc; ++k)
    if (glob(pat, sys->part_names[k])) {
      char pre[20];
      snprintf(pre, sizeof pre, "%s:", kind);
      rc = push(cs, ck, k, axis, pre, sys->part_names[k], "");
    }
  if (before == cs->n && !rc) {
    if (msg) {
      int w =
          snprintf(msg, msglen, "columns: '%s': no particle matches '%s' (particles: ", it, pat);
      for (int k = 0; k < sys->N && w >= 0 && (size_t)w < msglen; ++k)
        w += snprintf(msg + w, msglen - (size_t)w, "%s%s", k ? ", " : "", sys->part_names[k]);
      if (w >= 0 && (size_t)w < msglen)
        snprintf(msg + w, msglen - (size_t)w, "%s)", sys->N ? "" : "none");
    }
    return DAL_E_ARG;
  }
  return rc;
none_coord:
  if (msg) {
    int w =
        snprintf(msg, msglen, "columns: '%s': no coordinate matches '%s' (coordinates: ", it, pat);
    for (int i = 0; i < sys->n && w >= 0 && (size_t)w < msglen; ++i)
      w += snprintf(msg + w, msglen - (size_t)w, "%s%s", i ? ", " : "", sys->coord_names[i]);
    if (w >= 0 && (size_t)w < msglen) snprintf(msg + w, msglen - (size_t)w, ")");
  }
  return DAL_E_ARG;
}

int dal_columns_create(const dal_system *sys, const char *spec, dal_columns **out, char *msg,
                       size_t msglen) {
  if (msg && msglen) msg[0] = 0;
  if (out) *out = NULL;
  if (!sys || !out) {
    if (msg) snprintf(msg, msglen, "columns: sys and out must not be NULL");
    return DAL_E_ARG;
  }
  if (!spec || !*spec) spec = "t,q:*,qdot:*,E,h";
  dal_columns *cs = calloc(1, sizeof *cs);
  if (!cs) return DAL_E_NOMEM;
  cs->sys = sys;
  int rc = DAL_OK;
  // split at commas (spaces around an item are dropped)
  for (const char *p = spec; !rc;) {
    while (*p == ' ')
      ++p;
    const char *e = strchr(p, ',');
    size_t len = e ? (size_t)(e - p) : strlen(p);
    while (len && p[len - 1] == ' ')
      --len;
    char it[128];
    if (!len || len >= sizeof it) {
      if (msg)
        snprintf(msg, msglen, "columns: %s item in '%.200s'", len ? "an overlong" : "an empty",
                 spec);
      rc = DAL_E_ARG;
      break;
    }
    memcpy(it, p, len);
    it[len] = 0;
    rc = item(cs, it, msg, msglen);
    if (!e) break;
    p = e + 1;
  }
  if (rc) {
    if (rc == DAL_E_NOMEM && msg) snprintf(msg, msglen, "columns: out of memory");
    dal_columns_destroy(cs);
    return rc;
  }
  *out = cs;
  return DAL_OK;
}

void dal_columns_destroy(dal_columns *cols) {
  if (!cols) return;
  for (int i = 0; i < cols->n; ++i)
    free(cols->c[i].name);
  free(cols->c);
  free(cols);
}

int dal_columns_count(const dal_columns *cols) { return cols ? cols->n : 0; }

const char *dal_columns_name(const dal_columns *cols, int i) {
  return cols && i >= 0 && i < cols->n ? cols->c[i].name : NULL;
}

int dal_columns_need_work(const dal_columns *cols) { return cols ? cols->work : 0; }

int dal_columns_write_header(const dal_columns *cols, FILE *fp) {
  if (!cols || !fp) return DAL_E_ARG;
  for (int i = 0; i < cols->n; ++i)
    fprintf(fp, "%s%s", i ? "," : "", cols->c[i].name);
  fputc('\n', fp);
  return ferror(fp) ? DAL_E_IO : DAL_OK;
}

int dal_columns_eval(const dal_system *sys, const dal_state *st, const dal_columns *cols,
                     double *row) {
  if (!st) return DAL_E_ARG;
  int pair = dal__check_pair(sys, st, "columns_eval");
  if (pair) return pair;
  if (!cols || !row || cols->sys != sys)
    return DAL_FAIL_C(st, DAL_E_ARG,
                      "columns_eval: cols and row must not be NULL and cols must be made for "
                      "this system (dal_columns_create)");
  // evaluate what the row reads (a monitor's state on demand)
  unsigned need = cols->need | (cols->joint ? DAL_P_OUT : 0u);
  if ((cols->need & DAL_P_DYN) && sys->m) need |= DAL_P_OUT;
  dal__lazy_eval_for(st, need);
  if ((st->have & need) != need) {
    if (st->lazy_rc) return st->lazy_rc;
    return DAL_FAIL_C(st, DAL_E_STATE,
                      "columns_eval: the state is not evaluated at t=%.17g; call dal_forward "
                      "first (dal_evolve calls monitors with evaluated states)",
                      st->t);
  }
  // joint forces (a selection is shared read-only: its scratch is the row's own)
  int d = sys->dim;
  double *jf = NULL;
  if (cols->joint) {
    jf = malloc((size_t)(sys->N * d) * sizeof *jf);
    if (!jf) return DAL_FAIL_C(st, DAL_E_NOMEM, "columns_eval: out of memory");
    int rc = dal_joint_forces(sys, st, jf);
    if (rc) {
      free(jf);
      return rc;
    }
  }
  for (int i = 0; i < cols->n; ++i) {
    const col *c = &cols->c[i];
    double v = NAN;
    switch (c->kind) {
    case COL_T:
      v = st->t;
      break;
    case COL_Q:
      v = st->q[c->index];
      break;
    case COL_QDOT:
      v = st->qdot[c->index];
      break;
    case COL_X:
      v = st->r[c->index * d + c->sub];
      break;
    case COL_V:
      v = st->v[c->index * d + c->sub];
      break;
    case COL_R:
      v = st->N[c->index * d + c->sub];
      break;
    case COL_J:
      v = jf[c->index * d + c->sub];
      break;
    case COL_LAMBDA:
      v = st->lambda[c->index];
      break;
    case COL_TE:
      v = st->en.T;
      break;
    case COL_U:
      v = st->en.U;
      break;
    case COL_E:
      v = st->en.E;
      break;
    case COL_H:
      v = st->en.h;
      break;
    case COL_P:
      v = st->power;
      break;
    case COL_W:
      v = st->W;
      break;
    default:
      DAL_ASSERT(0);
    }
    row[i] = v;
  }
  free(jf);
  return DAL_OK;
}

int dal__columns_is_q(const dal_columns *cols, int i) {
  return cols && i >= 0 && i < cols->n && cols->c[i].kind == COL_Q;
}
