// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The viewer (output.h: dal_view_write): frames of a motion from the dense output, the scene's
// drawable geometry, and one self-contained HTML page (src/view/page.* embedded at build time).
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/base.h"
#include "dalembert/analysis.h"
#include "dalembert/output.h"
#include "view/view.h"

#define MAX_FRAMES 200000
#define MAX_PLOT 2000
#define QMAX 65534 // the largest quantized value of a page series (put_series)

// a point the page draws besides the particles (a pivot, an anchor, a circle's centre and the
// unit vectors of its plane, a line's direction), evaluated at every frame
enum { PT_PIVOT, PT_PIVOT_W, PT_ANCHOR, PT_CONST, PT_TURN_U, PT_LINK_ANCHOR };
typedef struct xpoint {
  int kind, owner, sub; // owner: placement, constraint or link; sub: coordinate or x0 offset
  int dir;              // a direction (a circle's plane, a line's direction), not a place
  double c[3];          // a constant point (PT_CONST)
} xpoint;

typedef struct viewer {
  const dal_system *sys;
  int d, N, n, m, K;
  xpoint *xp;
  int nxp;
  // geometry text (JSON arrays), built once
  char *links, *circles, *lines, *spheres, *planes;
  size_t links_len, links_cap, circles_len, circles_cap, lines_len, lines_cap, spheres_len,
      spheres_cap, planes_len, planes_cap;
  // frames
  const double *times;
  size_t nt, nframes, frame, fcount;
  int *is_frame; // times[i] is a frame (else a strobe time)
  double *pos, *xs;
  // plots
  size_t pstride, nplot;
  double *pq, *pqd, *pe, *pf;
  int nf; // force series: the multipliers (m) or |R| per particle (N)
  double E0, h0;
  int jacobi; // h differs from E (a moving constraint or placement) and is conserved (the
              // equations do not depend on t explicitly): its own plot
  // section points
  double *sec;
  size_t nsec, seccap;
  double strobe_next;
  dal_jet *jin, *jout;
  int rc;
} viewer;

// append printf text to a growing buffer
static int app(char **buf, size_t *len, size_t *cap, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;
static int app(char **buf, size_t *len, size_t *cap, const char *fmt, ...) {
  va_list ap;
  for (;;) {
    va_start(ap, fmt);
    int w = vsnprintf(*buf ? *buf + *len : NULL, *buf ? *cap - *len : 0, fmt, ap);
    va_end(ap);
    if (w < 0) return DAL_E_IO;
    if (*buf && *len + (size_t)w < *cap) {
      *len += (size_t)w;
      return DAL_OK;
    }
    size_t cap2 = (*cap ? *cap * 2 : 256) + (size_t)w;
    char *b = realloc(*buf, cap2);
    if (!b) return DAL_E_NOMEM;
    if (!*buf) b[0] = 0;
    *buf = b;
    *cap = cap2;
  }
}

static int add_point(viewer *v, int kind, int owner, int sub, const double *c) {
  xpoint *xp = realloc(v->xp, (size_t)(v->nxp + 1) * sizeof *xp);
  if (!xp) return -1;
  v->xp = xp;
  xpoint *p = &xp[v->nxp];
  memset(p, 0, sizeof *p);
  p->kind = kind;
  p->owner = owner;
  p->sub = sub;
  if (c) memcpy(p->c, c, 3 * sizeof *c);
  return v->nxp++;
}

// the centre of curvature of placement k's path along its coordinate j at the state (q_j
// shifted by dq), and the unit vectors u (centre -> particle) and w (the path's tangent) of its
// plane; 0 or -1 where the path is straight or the placement fails there
static int osc(viewer *v, const dal_state *st, int k, int j, double dq, double *C, double *u,
               double *w, double *rho) {
  const dal_system *sys = v->sys;
  const dal_place *pl = &sys->place[k];
  int d = v->d, ni = 0;
  if (pl->parent >= 0)
    for (int b = 0; b < d; ++b)
      v->jin[ni++] = dal_const(st->r[pl->parent * d + b]);
  for (int i = 0; i < pl->ncoord; ++i) {
    double q = st->q[sys->ipool[pl->coord_off + i]];
    v->jin[ni++] = i == j ? dal_var(q + dq, 1.0) : dal_const(q);
  }
  if (pl->prim->eval(v->jin, dal_const(st->t), st->prm.ppool + pl->param_off, v->jout, pl->ctx))
    return -1;
  double r[3] = {0}, c1[3] = {0}, c2[3] = {0}, s11 = 0, s12 = 0;
  for (int b = 0; b < d; ++b) {
    r[b] = v->jout[b].v, c1[b] = v->jout[b].d, c2[b] = v->jout[b].dd;
    s11 += c1[b] * c1[b], s12 += c1[b] * c2[b];
  }
  // curvature vector K = (c'' |c'|^2 - c' (c'.c'')) / |c'|^4; centre r + K / |K|^2
  double K[3], kk = 0;
  for (int b = 0; b < 3; ++b) {
    K[b] = s11 > 0 ? (c2[b] * s11 - c1[b] * s12) / (s11 * s11) : 0;
    kk += K[b] * K[b];
  }
  if (!(kk > 0) || !isfinite(kk)) return -1;
  *rho = 1 / sqrt(kk);
  for (int b = 0; b < 3; ++b) {
    C[b] = r[b] + K[b] / kk;
    u[b] = -K[b] * *rho;
    w[b] = c1[b] / sqrt(s11);
  }
  return 0;
}

// placement k's path along one of its coordinates is a circle (the same centre from three
// points of it): the coordinate's index, else -1
static int circle_coord(viewer *v, const dal_state *st, int k, double *rho) {
  const dal_place *pl = &v->sys->place[k];
  for (int j = 0; j < pl->ncoord; ++j) {
    double C[3][3], u[3], w[3], r0 = 0, r1, r2;
    if (osc(v, st, k, j, 0.0, C[0], u, w, &r0) || osc(v, st, k, j, 1.0, C[1], u, w, &r1) ||
        osc(v, st, k, j, -2.0, C[2], u, w, &r2))
      continue;
    double e = 0, s = r0;
    for (int b = 0; b < 3; ++b) {
      e = fmax(e, fmax(fabs(C[1][b] - C[0][b]), fabs(C[2][b] - C[0][b])));
      s = fmax(s, fabs(C[0][b]));
    }
    if (e <= 1e-9 * s && fabs(r1 - r0) <= 1e-9 * s && fabs(r2 - r0) <= 1e-9 * s) {
      *rho = r0;
      return j;
    }
  }
  return -1;
}

// a link's anchor x0 + x(t)
static void link_anchor(const dal_state *st, const dal_link *l, int d, double *x) {
  dal_jet jx[3];
  memcpy(x, l->x0, 3 * sizeof *x);
  if (l->fn && !l->fn(dal_const(st->t), jx, l->ctx))
    for (int b = 0; b < d; ++b)
      x[b] += jx[b].v;
}

// evaluate extra point i at the state into x (3)
static void eval_point(viewer *v, const dal_state *st, int i, double *x) {
  const dal_system *sys = v->sys;
  const xpoint *p = &v->xp[i];
  double C[3] = {0}, u[3] = {0}, w[3] = {0}, rho;
  x[0] = x[1] = x[2] = 0;
  switch (p->kind) {
  case PT_PIVOT:
  case PT_PIVOT_W:
    if (osc(v, st, p->owner, p->sub, 0.0, C, u, w, &rho)) {
      x[0] = x[1] = x[2] = NAN;
      return;
    }
    memcpy(x, p->kind == PT_PIVOT ? C : w, 3 * sizeof *x);
    return;
  case PT_ANCHOR: { // dal_con_anchor2/3: x0 + x(t) (the moving-point convention)
    const dal_con *c = &sys->con[p->owner];
    const double *par = st->prm.ppool + c->param_off;
    for (int b = 0; b < v->d; ++b)
      x[b] = par[1 + b];
    const dal_moving_point *mp = c->ctx;
    dal_jet jx[3];
    if (mp && mp->fn && !mp->fn(dal_const(st->t), jx, mp->ctx))
      for (int b = 0; b < v->d; ++b)
        x[b] += jx[b].v;
    return;
  }
  case PT_TURN_U: { // (cos a, sin a, 0), a = w t + phi0: a turning circle's plane, a turning line
    const double *par = st->prm.ppool + sys->con[p->owner].param_off + p->sub; // at w, phi0
    double a = par[0] * st->t + par[1];
    x[0] = cos(a), x[1] = sin(a);
    return;
  }
  case PT_LINK_ANCHOR: {
    const dal_link *l = p->sub ? &st->prm.dampers[p->owner] : &st->prm.springs[p->owner];
    link_anchor(st, l, v->d, x);
    return;
  }
  default:
    memcpy(x, p->c, 3 * sizeof *x);
    return;
  }
}

// a JSON row of indices and numbers to a geometry list: "[a,b,...],"
#define ROW(list, ...) app(&v->list, &v->list##_len, &v->list##_cap, __VA_ARGS__)

// the scene's drawable geometry (the page's lists, point indices: a particle, or N + an extra
// point): links [a, b, kind], circles [centre, u, w, R, pivot] (u a particle's index: the
// direction from the centre to it; u < 0: the page's own plane), lines [point, direction],
// spheres [centre, R], planes [point, normal]
static int geometry(viewer *v, const dal_state *st) {
  const dal_system *sys = v->sys;
  int N = v->N, d = v->d, rc = DAL_OK;
  v->jin = malloc((size_t)(sys->max_in + 3) * sizeof *v->jin);
  v->jout = malloc((size_t)(sys->max_out + 3) * sizeof *v->jout);
  if (!v->jin || !v->jout) return DAL_E_NOMEM;
  // placements: parent -> child; a sphere a spherical map moves on (its pivot, and the rod);
  // a pivot where the path is a circle about a fixed centre
  for (int k = 0; sys->place && k < N && !rc; ++k) {
    const dal_place *pl = &sys->place[k];
    if (!pl->prim) continue;
    // a child hangs from its parent: the link is enough (its circle would cost 6 numbers a frame)
    if (pl->parent >= 0) {
      rc = ROW(links, "[%d,%d,\"rod\"],", pl->parent, k);
      continue;
    }
    if (pl->prim == &dal_map_spherical || pl->prim == &dal_map_sphere) {
      const double *par = st->prm.ppool + pl->param_off; // (R or l, centre)
      int c = add_point(v, PT_CONST, k, 0, par + 1);
      if (c < 0) return DAL_E_NOMEM;
      rc = ROW(spheres, "[%d,%.17g],", N + c, fabs(par[0]));
      if (!rc && pl->prim == &dal_map_spherical) rc = ROW(links, "[%d,%d,\"rod\"],", N + c, k);
      continue;
    }
    double rho;
    int j = pl->ncoord ? circle_coord(v, st, k, &rho) : -1;
    if (j < 0) continue;
    // the circle's plane: the page's own in 2-D (no numbers stored); in 3-D it holds the centre,
    // the particle and the path's tangent w (stored, turning with it)
    int c = add_point(v, PT_PIVOT, k, j, NULL), u = -1 - N, w = -1 - N;
    if (d == 3) {
      u = k - N, w = add_point(v, PT_PIVOT_W, k, j, NULL);
      if (w < 0) return DAL_E_NOMEM;
      v->xp[w].dir = 1;
    }
    if (c < 0) return DAL_E_NOMEM;
    rc = ROW(links, "[%d,%d,\"rod\"],", N + c, k);
    if (!rc) rc = ROW(circles, "[%d,%d,%d,%.17g,1],", N + c, N + u, N + w, rho);
  }
  // built-in constraints: rods, anchors, circles, lines, spheres, planes
  for (int c = 0; c < sys->ncon && !rc; ++c) {
    const dal_con *con = &sys->con[c];
    const dal_primitive *pr = con->prim;
    const int *parts = sys->ipool + con->part_off;
    const double *par = st->prm.ppool + con->param_off;
    if (pr == &dal_con_distance2 || pr == &dal_con_distance3)
      rc = ROW(links, "[%d,%d,\"rod\"],", parts[0], parts[1]);
    else if (pr == &dal_con_anchor2 || pr == &dal_con_anchor3) {
      int a = add_point(v, PT_ANCHOR, c, 0, NULL);
      if (a < 0) return DAL_E_NOMEM;
      rc = ROW(links, "[%d,%d,\"rod\"],", N + a, parts[0]);
    } else if (pr == &dal_con_sphere) {
      int pc = add_point(v, PT_CONST, c, 0, par + DAL_SPHERE_CX);
      if (pc < 0) return DAL_E_NOMEM;
      rc = ROW(spheres, "[%d,%.17g],", N + pc, par[DAL_SPHERE_R]);
    } else if (pr == &dal_con_plane) {
      int pc = add_point(v, PT_CONST, c, 0, par + DAL_PLANE_CX);
      int pn = add_point(v, PT_CONST, c, 0, par + DAL_PLANE_NX);
      if (pc < 0 || pn < 0) return DAL_E_NOMEM;
      v->xp[pn].dir = 1;
      rc = ROW(planes, "[%d,%d],", N + pc, N + pn);
    } else if (pr == &dal_con_circle2 || pr == &dal_con_circle3 || pr == &dal_con_turning_circle) {
      int turning = pr == &dal_con_turning_circle, off = turning ? 3 : 1;
      double cc[3] = {par[off], par[off + 1], d == 3 ? par[off + 2] : 0}, uu[3] = {1, 0, 0},
             ww[3] = {0, 1, 0};
      if (pr == &dal_con_circle3) { // an orthonormal pair normal to n
        double nx = par[4], ny = par[5], nz = par[6], nn = sqrt(nx * nx + ny * ny + nz * nz);
        nx /= nn, ny /= nn, nz /= nn;
        double ax = fabs(nx) < 0.9 ? 1 : 0, ay = 1 - ax;
        double ux = ay * nz, uy = -ax * nz, uz = ax * ny - ay * nx;
        double un = sqrt(ux * ux + uy * uy + uz * uz);
        uu[0] = ux / un, uu[1] = uy / un, uu[2] = uz / un;
        ww[0] = ny * uu[2] - nz * uu[1], ww[1] = nz * uu[0] - nx * uu[2];
        ww[2] = nx * uu[1] - ny * uu[0];
      }
      if (turning) ww[1] = 0, ww[2] = 1;
      int pc = add_point(v, PT_CONST, c, 0, cc), pu = -1 - N, pw = -1 - N;
      if (d == 3) {
        pu = add_point(v, turning ? PT_TURN_U : PT_CONST, c, DAL_TURNING_CIRCLE_W, uu);
        pw = add_point(v, PT_CONST, c, 0, ww);
        if (pu < 0 || pw < 0) return DAL_E_NOMEM;
        v->xp[pu].dir = v->xp[pw].dir = 1;
      }
      if (pc < 0) return DAL_E_NOMEM;
      rc = ROW(circles, "[%d,%d,%d,%.17g,0],", N + pc, N + pu, N + pw, par[0]);
    } else if (pr == &dal_con_line2 || pr == &dal_con_line3 || pr == &dal_con_turning_line2) {
      int turning = pr == &dal_con_turning_line2;
      double cc[3] = {par[0], par[1], d == 3 ? par[2] : 0},
             aa[3] = {par[d], par[d + 1], d == 3 ? par[5] : 0};
      int pc = add_point(v, PT_CONST, c, 0, cc);
      int pa = add_point(v, turning ? PT_TURN_U : PT_CONST, c, DAL_TURNING_LINE2_W, aa);
      if (pc < 0 || pa < 0) return DAL_E_NOMEM;
      v->xp[pa].dir = 1;
      rc = ROW(lines, "[%d,%d],", N + pc, N + pa);
    }
  }
  // springs and dampers: between particles or to an anchor
  for (int i = 0; i < sys->nspring + sys->ndamper && !rc; ++i) {
    int damper = i >= sys->nspring, li = damper ? i - sys->nspring : i;
    const dal_link *l = damper ? &sys->dampers[li] : &sys->springs[li];
    int b = l->b;
    if (b < 0) {
      int a = add_point(v, PT_LINK_ANCHOR, li, damper, NULL);
      if (a < 0) return DAL_E_NOMEM;
      b = N + a;
    }
    rc = ROW(links, "[%d,%d,\"%s\"],", b, l->a, damper ? "damper" : "spring");
  }
  return rc;
}

// the monitor: one frame (positions, extra points, plot samples) or a strobe point
static int record(const dal_system *sys, const dal_state *st, void *ctx) {
  viewer *v = ctx;
  size_t i = v->frame++;
  const double *q = dal_state_q(st), *qd = dal_state_qdot(st);
  if (!v->is_frame[i]) { // a strobe time: a section point
    if (v->nsec == v->seccap) {
      size_t cap = v->seccap ? 2 * v->seccap : 64;
      double *s = realloc(v->sec, cap * 3 * sizeof *s);
      if (!s) return -1;
      v->sec = s, v->seccap = cap;
    }
    v->sec[3 * v->nsec] = st->t;
    v->sec[3 * v->nsec + 1] = q[0];
    v->sec[3 * v->nsec + 2] = qd[0];
    v->nsec++;
    return 0;
  }
  size_t f = v->fcount++;
  (void)sys;
  const double *r = dal_state_positions(st);
  if (!r) return -1;
  int d = v->d;
  for (int k = 0; k < v->N * d; ++k)
    v->pos[f * (size_t)(v->N * d) + (size_t)k] = r[k];
  for (int k = 0; k < v->nxp; ++k) {
    double x[3];
    eval_point(v, st, k, x);
    for (int b = 0; b < 3; ++b)
      v->xs[(f * (size_t)v->nxp + (size_t)k) * 3 + (size_t)b] = x[b];
  }
  if (f % v->pstride == 0 && f / v->pstride < v->nplot) {
    size_t s = f / v->pstride;
    dal_energies en;
    if (dal_state_energies(st, &en)) return -1;
    if (f == 0) v->E0 = en.E, v->h0 = en.h;
    if (en.T1 != 0 || en.T0 != 0) v->jacobi = 1;
    for (int j = 0; j < v->n; ++j) {
      v->pq[s * (size_t)v->n + (size_t)j] = q[j];
      v->pqd[s * (size_t)v->n + (size_t)j] = qd[j];
    }
    v->pe[2 * s] = en.E - v->E0;
    v->pe[2 * s + 1] = en.h - v->h0;
    const double *lam = v->m ? dal_state_lambda(st) : dal_state_reactions(st);
    if (!lam) return -1;
    for (int j = 0; j < v->nf; ++j) {
      double val = lam[j];
      if (!v->m) { // |R_k|
        val = 0;
        for (int b = 0; b < d; ++b)
          val += lam[j * d + b] * lam[j * d + b];
        val = sqrt(val);
      }
      v->pf[s * (size_t)v->nf + (size_t)j] = val;
    }
  }
  return 0;
}

// base64 of n bytes, quoted
static void put_b64(FILE *fp, const unsigned char *x, size_t n) {
  static const char tab[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  fputc('"', fp);
  for (size_t i = 0; i < n; i += 3) {
    size_t m = n - i < 3 ? n - i : 3;
    unsigned b0 = x[i], b1 = m > 1 ? x[i + 1] : 0, b2 = m > 2 ? x[i + 2] : 0;
    char out[4] = {tab[b0 >> 2], tab[((b0 & 3) << 4) | (b1 >> 4)],
                   m > 1 ? tab[((b1 & 15) << 2) | (b2 >> 6)] : '=', m > 2 ? tab[b2 & 63] : '='};
    fwrite(out, 1, 4, fp);
  }
  fputc('"', fp);
}

// A series of the page: `rows` rows of `w` numbers, written as {"w", "lo", "step", "b64"}.
// Each component c is quantized to an integer k in [0, QMAX] over its own range
// (x = lo_c + k step_c, step_c = (max - min) / QMAX, so the error is at most step_c / 2;
// k = QMAX + 1 marks a value that is not finite). Row r's k is predicted from the rows before
// (0; k[r-1]; 2 k[r-1] - k[r-2]) and the misses, zigzag-encoded base-128 varints row after row,
// are the bytes, in base64. A component whose range is within tiny[c] (nullable: 0) is
// constant (step 0, lo its middle value) and one never finite has lo null: neither has bytes.
static int put_series(FILE *fp, const double *x, size_t rows, int w, const double *tiny) {
  double *lo = malloc(2 * ((size_t)w + 1) * sizeof *lo), *step = lo + w + 1;
  long *prev = calloc(2 * (size_t)w + 1, sizeof *prev);
  size_t cap = rows * (size_t)w * 3 + 1, nb = 0;
  unsigned char *buf = lo && prev ? malloc(cap) : NULL;
  if (!buf) {
    free(lo), free(prev);
    return DAL_E_NOMEM;
  }
  fprintf(fp, "{\"w\":%d,\"lo\":[", w);
  for (int c = 0; c < w; ++c) {
    double a = INFINITY, b = -INFINITY;
    int gap = 0;
    for (size_t r = 0; r < rows; ++r) {
      double v = x[r * (size_t)w + (size_t)c];
      if (isfinite(v))
        a = fmin(a, v), b = fmax(b, v);
      else
        gap = 1;
    }
    int flat = a <= b && b - a <= (tiny ? tiny[c] : 0);
    lo[c] = flat ? (a + b) / 2 : a;
    step[c] = a > b || (flat && !gap) ? 0 : flat ? 1 : (b - a) / QMAX; // flat with gaps: k 0
    if (a <= b)
      fprintf(fp, "%s%.17g", c ? "," : "", lo[c]);
    else
      fprintf(fp, "%snull", c ? "," : "");
  }
  fputs("],\"step\":[", fp);
  for (int c = 0; c < w; ++c)
    fprintf(fp, "%s%.17g", c ? "," : "", step[c]);
  fputs("],\"b64\":", fp);
  for (size_t r = 0; r < rows; ++r)
    for (int c = 0; c < w; ++c) {
      if (!(step[c] > 0)) continue;
      double v = x[r * (size_t)w + (size_t)c];
      long k = isfinite(v) ? lround((v - lo[c]) / step[c]) : QMAX + 1;
      if (k > QMAX && isfinite(v)) k = QMAX;
      long *k1 = &prev[2 * c], *k2 = &prev[2 * c + 1]; // k of the rows r - 1 and r - 2
      long dk = k - (r >= 2 ? 2 * *k1 - *k2 : *k1);
      *k2 = *k1, *k1 = k;
      unsigned long z = dk < 0 ? 2 * (unsigned long)(-dk) - 1 : 2 * (unsigned long)dk;
      do {
        buf[nb++] = (unsigned char)((z & 127) | (z > 127 ? 128 : 0));
        z >>= 7;
      } while (z);
    }
  put_b64(fp, buf, nb);
  fputc('}', fp);
  free(buf);
  free(lo);
  free(prev);
  return ferror(fp) ? DAL_E_IO : DAL_OK;
}

// a JSON string (names: < and > escaped, so no text can close the script element)
static void put_str(FILE *fp, const char *s) {
  fputc('"', fp);
  for (; s && *s; ++s) {
    unsigned char ch = (unsigned char)*s;
    if (ch == '"' || ch == '\\')
      fprintf(fp, "\\%c", ch);
    else if (ch < 0x20 || ch == '<' || ch == '>' || ch == '&')
      fprintf(fp, "\\u%04x", ch);
    else
      fputc(ch, fp);
  }
  fputc('"', fp);
}

static int write_page(viewer *v, const dal_view_opts *o, dal_events *ev, FILE *fp) {
  const dal_system *sys = v->sys;
  fputs("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>", fp);
  for (const char *s = o->title ? o->title : "dalembert"; *s; ++s)
    if (*s == '<' || *s == '&')
      fprintf(fp, "&#%d;", *s);
    else
      fputc(*s, fp);
  fprintf(fp, "</title>\n<style>\n%s</style></head>\n<body>\n%s", dal__view_css, dal__view_html);
  fputs("<script id=\"dal-data\" type=\"application/json\">{", fp);
  fprintf(fp, "\"dim\":%d,\"N\":%d,\"n\":%d,\"K\":%d,\"frames\":%zu,\"t0\":%.17g,\"dt\":%.17g,",
          v->d, v->N, v->n, v->nxp, v->nframes, v->times[0], 1.0 / o->fps);
  fprintf(fp, "\"trail\":%.17g,\"title\":", o->trail);
  put_str(fp, o->title ? o->title : "dalembert");
  fputs(",\"particles\":[", fp);
  for (int k = 0; k < v->N; ++k) {
    fprintf(fp, "%s{\"name\":", k ? "," : "");
    put_str(fp, sys->part_names[k]);
    fprintf(fp, ",\"m\":%.9g}", sys->mass[k]);
  }
  fputs("],\"coords\":[", fp);
  for (int j = 0; j < v->n; ++j) {
    if (j) fputc(',', fp);
    put_str(fp, sys->coord_names[j]);
  }
  fputs("],\"forces\":[", fp);
  for (int j = 0; j < v->nf; ++j) {
    char name[96];
    if (v->m) {
      const dal_con *c = &sys->con[sys->row_con[j]];
      snprintf(name, sizeof name, "lambda:%s%s", c->name ? c->name : "?",
               c->prim->nout > 1 ? "." : "");
      if (c->prim->nout > 1)
        snprintf(name + strlen(name), sizeof name - strlen(name), "%d", j - c->row);
    } else
      snprintf(name, sizeof name, "|R:%s|", sys->part_names[j]);
    if (j) fputc(',', fp);
    put_str(fp, name);
  }
  fputs("]", fp);
  // the geometry lists (each row written with a trailing comma: the last one dropped)
  const char *lists[] = {"links", "circles", "lines", "spheres", "planes"};
  const char *text[] = {v->links, v->circles, v->lines, v->spheres, v->planes};
  const size_t len[] = {v->links_len, v->circles_len, v->lines_len, v->spheres_len, v->planes_len};
  for (int i = 0; i < 5; ++i)
    fprintf(fp, ",\"%s\":[%.*s]", lists[i], len[i] ? (int)len[i] - 1 : 0, text[i] ? text[i] : "");
  fputc(',', fp);
  // a place or direction that moves by less than 1e-9 of the scene (of a unit) is constant
  size_t np = (size_t)(v->N * v->d), nx = (size_t)v->nxp * 3;
  double ext = 0, *tiny = malloc((np + nx + 1) * sizeof *tiny);
  if (!tiny) return DAL_E_NOMEM;
  for (int b = 0; b < v->d; ++b) {
    double lo = INFINITY, hi = -INFINITY;
    for (size_t f = 0; f < v->nframes; ++f)
      for (int k = 0; k < v->N; ++k) {
        double x = v->pos[f * np + (size_t)(k * v->d + b)];
        lo = fmin(lo, x), hi = fmax(hi, x);
      }
    ext = fmax(ext, hi - lo);
  }
  for (size_t i = 0; i < np + nx; ++i)
    tiny[i] = i >= np && v->xp[(i - np) / 3].dir ? 1e-9 : 1e-9 * ext;
  fputs("\"pos\":", fp);
  int rc = put_series(fp, v->pos, v->nframes, (int)np, tiny);
  fputs(",\"xs\":", fp);
  if (!rc) rc = put_series(fp, v->xs, v->nframes, (int)nx, tiny + np);
  free(tiny);
  fprintf(fp, ",\"pstride\":%zu,\"nplot\":%zu,\"pq\":", v->pstride, v->nplot);
  if (!rc) rc = put_series(fp, v->pq, v->nplot, v->n, NULL);
  fputs(",\"pqd\":", fp);
  if (!rc) rc = put_series(fp, v->pqd, v->nplot, v->n, NULL);
  fputs(",\"pe\":", fp);
  if (!rc) rc = put_series(fp, v->pe, v->nplot, 2, NULL);
  fprintf(fp, ",\"jacobi\":%d", v->jacobi);
  fputs(",\"pf\":", fp);
  if (!rc) rc = put_series(fp, v->pf, v->nplot, v->nf, NULL);
  if (rc) return rc;
  // section points [t, q0, qdot0, kind]: the strobe's (kind 0), then the crossings of ev's
  // sections (kind 1)
  fputs(",\"sections\":[", fp);
  int any = 0;
  for (size_t i = 0; i < v->nsec; ++i)
    fprintf(fp, "%s[%.17g,%.9g,%.9g,0]", any++ ? "," : "", v->sec[3 * i], v->sec[3 * i + 1],
            v->sec[3 * i + 2]);
  double *q = ev ? malloc(2 * (size_t)v->n * sizeof *q) : NULL;
  for (long i = 0; q && i < dal_events_count(ev); ++i) {
    dal_event_record rec;
    if (dal_events_get(ev, i, &rec, q, q + v->n)) break;
    if (o->sections && !o->sections[rec.event]) continue;
    fprintf(fp, "%s[%.17g,%.9g,%.9g,1]", any++ ? "," : "", rec.t, q[0], q[v->n]);
  }
  free(q);
  fprintf(fp, "]}</script>\n<script>\n%s</script>\n</body></html>\n", dal__view_js);
  return ferror(fp) ? DAL_E_IO : DAL_OK;
}

// evaluate the geometry at the start, then run to the last time recording every frame (a
// terminal event or a stopping monitor ends the motion early: the frames up to it are kept)
static int frames_run(viewer *v, dal_state *st, const dal_solve_opts *solve, dal_events *ev,
                      const char *who) {
  const dal_system *sys = v->sys;
  size_t nf = v->nframes;
  int rc = dal_forward(sys, st);
  if (!rc) rc = geometry(v, st);
  if (!rc) {
    v->pos = malloc(nf * (size_t)(v->N * v->d) * sizeof *v->pos);
    v->xs = malloc((nf * (size_t)v->nxp * 3 + 1) * sizeof *v->xs);
    v->pq = malloc((v->nplot * (size_t)v->n + 1) * sizeof *v->pq);
    v->pqd = malloc((v->nplot * (size_t)v->n + 1) * sizeof *v->pqd);
    v->pe = malloc((2 * v->nplot + 2) * sizeof *v->pe);
    v->pf = malloc((v->nplot * (size_t)v->nf + 1) * sizeof *v->pf);
    if (!v->pos || !v->xs || !v->pq || !v->pqd || !v->pe || !v->pf) rc = DAL_E_NOMEM;
  }
  if (rc == DAL_E_NOMEM) return DAL_FAIL(st, rc, "%s: out of memory for %zu frames", who, nf);
  dal_solve_opts so = solve ? *solve : dal_default_solve_opts();
  if (!rc && ev) rc = dal_state_set_events(st, ev);
  if (!rc) {
    rc = dal_evolve_at(sys, st, &so, v->times, v->nt, record, v);
    if (ev) dal_state_set_events(st, NULL);
    if (rc == DAL_EVENT || rc == DAL_STOPPED) {
      v->nframes = v->fcount ? v->fcount : 1;
      v->nplot = (v->nframes + v->pstride - 1) / v->pstride;
      rc = DAL_OK;
    }
  }
  return rc;
}

dal_view_opts dal_default_view_opts(void) {
  dal_view_opts o;
  memset(&o, 0, sizeof o);
  o.t1 = 10.0;
  o.fps = 60.0;
  o.trail = 1.0;
  return o;
}

static void viewer_free(viewer *v) {
  free(v->xp);
  free(v->links);
  free(v->circles);
  free(v->lines);
  free(v->spheres);
  free(v->planes);
  free((void *)v->times);
  free(v->is_frame);
  free(v->pos);
  free(v->xs);
  free(v->pq);
  free(v->pqd);
  free(v->pe);
  free(v->pf);
  free(v->sec);
  free(v->jin);
  free(v->jout);
}

int dal_view_write(const dal_system *sys, dal_state *st, const dal_view_opts *opts, dal_events *ev,
                   FILE *fp) {
  if (!st) return DAL_E_ARG;
  int pair = dal__check_pair(sys, st, "view_write");
  if (pair) return pair;
  dal_view_opts o = opts ? *opts : dal_default_view_opts();
  double t0 = st->t;
  if (!isfinite(o.t1) || !isfinite(o.fps) || !isfinite(o.trail) || !isfinite(o.strobe))
    return DAL_FAIL(st, DAL_E_NONFINITE,
                    "view_write: t1 (%g), fps (%g), trail (%g) and strobe (%g) must be finite",
                    o.t1, o.fps, o.trail, o.strobe);
  if (!fp || !(o.fps > 0) || !isfinite(o.fps) || !(o.t1 > t0) || !isfinite(o.t1))
    return DAL_FAIL(st, DAL_E_ARG,
                    "view_write: needs a stream, fps > 0 (got %g) and t1 after the state's time "
                    "%.17g (got %g)",
                    o.fps, t0, o.t1);
  if (!sys->N)
    return DAL_FAIL(st, DAL_E_ARG,
                    "view_write: the system has no particles to draw (a Lagrangian only); "
                    "write its coordinates with dal_csv_monitor instead");
  double span = (o.t1 - t0) * o.fps;
  if (span > MAX_FRAMES)
    return DAL_FAIL(st, DAL_E_ARG,
                    "view_write: %.0f frames from t=%g to %g at %g fps exceed %d; lower fps or "
                    "shorten the run",
                    span, t0, o.t1, o.fps, MAX_FRAMES);
  viewer v;
  memset(&v, 0, sizeof v);
  v.sys = sys, v.d = sys->dim, v.N = sys->N, v.n = sys->n, v.m = sys->m;
  v.nf = v.m ? v.m : v.N;
  // frame times t0 + i / fps and strobe times merged, in order
  size_t nf = (size_t)floor(span + 1e-9) + 1;
  size_t ns = o.strobe > 0 ? (size_t)floor((o.t1 - t0) / o.strobe + 1e-9) + 1 : 0;
  double *times = malloc((nf + ns) * sizeof *times);
  v.is_frame = malloc((nf + ns) * sizeof *v.is_frame);
  int rc = times && v.is_frame ? DAL_OK : DAL_E_NOMEM;
  size_t a = 0, b = 0;
  while (!rc && (a < nf || b < ns)) {
    double ta = a < nf ? t0 + (double)a / o.fps : INFINITY;
    double tb = b < ns ? t0 + (double)b * o.strobe : INFINITY;
    int fr = ta <= tb;
    times[v.nt] = fr ? ta : tb;
    v.is_frame[v.nt++] = fr;
    if (fr)
      ++a;
    else
      ++b;
  }
  v.times = times;
  v.nframes = nf;
  v.pstride = (nf + MAX_PLOT - 1) / MAX_PLOT;
  v.nplot = (nf + v.pstride - 1) / v.pstride;
  // h is an invariant where the equations do not depend on t explicitly (a steadily turning
  // ring); a drive pumps E and h alike
  int steady = rc ? 0 : dal_time_dependence(sys, st, NULL, 0) == 0;
  if (!rc) rc = frames_run(&v, st, o.solve, ev, "view_write");
  v.jacobi = v.jacobi && steady;
  if (!rc) rc = write_page(&v, &o, ev, fp);
  if (rc == DAL_E_IO) DAL_FAIL(st, rc, "view_write: writing the page failed (disk full?)");
  viewer_free(&v);
  return rc;
}

// the picture's view: world -> px (the page's default view: from the side in 2-D; turned by
// yaw -0.6 and tilted by pitch 0.35 in 3-D), fitted to w x h
typedef struct proj {
  double A[2][4];
} proj;

static void fit(const viewer *v, const double *circR, double w, double h, proj *P) {
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (size_t f = 0; f < v->nframes; ++f) {
    for (int i = 0; i < v->N + v->nxp; ++i) {
      if (i >= v->N && v->xp[i - v->N].dir) continue;
      double x[3] = {0, 0, 0}, r = 0;
      if (i < v->N)
        for (int b = 0; b < v->d; ++b)
          x[b] = v->pos[(f * (size_t)v->N + (size_t)i) * (size_t)v->d + (size_t)b];
      else {
        for (int b = 0; b < 3; ++b)
          x[b] = v->xs[(f * (size_t)v->nxp + (size_t)(i - v->N)) * 3 + (size_t)b];
        r = circR[i - v->N];
      }
      if (!isfinite(x[0] + x[1] + x[2])) continue;
      for (int b = 0; b < 3; ++b)
        lo[b] = fmin(lo[b], x[b] - r), hi[b] = fmax(hi[b], x[b] + r);
    }
  }
  double c[3], R0[3] = {1, 0, 0}, R1[3] = {0, 1, 0}, s;
  for (int b = 0; b < 3; ++b)
    c[b] = (lo[b] + hi[b]) / 2;
  if (v->d == 2) {
    c[2] = 0;
    s = 0.9 * fmin(w / fmax(hi[0] - lo[0], 1e-9), h / fmax(hi[1] - lo[1], 1e-9));
  } else {
    double yaw = -0.6, pitch = 0.35, ext = fmax(fmax(hi[0] - lo[0], hi[1] - lo[1]), hi[2] - lo[2]);
    R0[0] = cos(yaw), R0[1] = -sin(yaw), R0[2] = 0;
    R1[0] = sin(pitch) * sin(yaw), R1[1] = sin(pitch) * cos(yaw), R1[2] = cos(pitch);
    s = 0.5 * fmin(w, h) / (0.5 * sqrt(3.0) * fmax(ext, 1e-9));
  }
  double c0 = R0[0] * c[0] + R0[1] * c[1] + R0[2] * c[2];
  double c1 = R1[0] * c[0] + R1[1] * c[1] + R1[2] * c[2];
  for (int b = 0; b < 3; ++b)
    P->A[0][b] = s * R0[b], P->A[1][b] = -s * R1[b];
  P->A[0][3] = w / 2 - s * c0;
  P->A[1][3] = h / 2 + s * c1;
}

// point i (a particle, or N + extra point) of frame f on the picture; dir: no translation
static void onscreen(const viewer *v, const proj *P, size_t f, int i, int dir, double *px) {
  double x[3] = {0, 0, 0};
  if (i < v->N)
    for (int b = 0; b < v->d; ++b)
      x[b] = v->pos[(f * (size_t)v->N + (size_t)i) * (size_t)v->d + (size_t)b];
  else
    for (int b = 0; b < 3; ++b)
      x[b] = v->xs[(f * (size_t)v->nxp + (size_t)(i - v->N)) * 3 + (size_t)b];
  for (int r = 0; r < 2; ++r)
    px[r] = P->A[r][0] * x[0] + P->A[r][1] * x[1] + P->A[r][2] * x[2] + (dir ? 0 : P->A[r][3]);
}

static int write_svg(viewer *v, FILE *fp) {
  const dal_system *sys = v->sys;
  const double W = 800, H = 600;
  double *circR = calloc((size_t)v->nxp + 1, sizeof *circR);
  if (!circR) return DAL_E_NOMEM;
  // circles: "[c,u,w,R,pivot]," rows of the geometry text
  int nc = 0, cs[64][3];
  double cr[64];
  for (const char *p = v->circles; p && *p && nc < 64;) {
    int a, b, c, piv;
    double R;
    if (sscanf(p, "[%d,%d,%d,%lf,%d]", &a, &b, &c, &R, &piv) != 5) break;
    cs[nc][0] = a, cs[nc][1] = b, cs[nc][2] = c, cr[nc++] = R;
    circR[a - v->N] = R;
    p = strchr(p, ']');
    p = p ? p + 2 : NULL;
  }
  for (const char *p = v->spheres; p && *p;) { // the spheres' radii (for the fit)
    int a;
    double R;
    if (sscanf(p, "[%d,%lf]", &a, &R) != 2) break;
    circR[a - v->N] = R;
    p = strchr(p, ']');
    p = p ? p + 2 : NULL;
  }
  proj P;
  fit(v, circR, W, H, &P);
  free(circR);
  fprintf(fp,
          "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%g\" height=\"%g\" viewBox=\"0 0 %g "
          "%g\">\n<rect width=\"100%%\" height=\"100%%\" fill=\"#fff\"/>\n",
          W, H, W, H);
  size_t last = v->nframes - 1;
  // the curves at the last time, faint
  for (int k = 0; k < nc; ++k) {
    fputs("<polyline fill=\"none\" stroke=\"#bbb\" points=\"", fp);
    double C[2], u[2], w[2];
    onscreen(v, &P, last, cs[k][0], 0, C);
    if (cs[k][1] < 0) // a 2-D circle: the plane's own axes
      u[0] = P.A[0][0], u[1] = P.A[1][0], w[0] = P.A[0][1], w[1] = P.A[1][1];
    else if (cs[k][1] < v->N) { // through a particle: u towards it (on screen, over R)
      onscreen(v, &P, last, cs[k][1], 0, u);
      onscreen(v, &P, last, cs[k][2], 1, w);
      double rr = 0;
      for (int b = 0; b < 3; ++b) { // the particle's distance from the centre
        size_t ip = (last * (size_t)v->N + (size_t)cs[k][1]) * (size_t)v->d + (size_t)b;
        double x = b < v->d ? v->pos[ip] : 0;
        x -= v->xs[(last * (size_t)v->nxp + (size_t)(cs[k][0] - v->N)) * 3 + (size_t)b];
        rr += x * x;
      }
      rr = sqrt(rr);
      for (int b = 0; b < 2; ++b)
        u[b] = (u[b] - C[b]) / (rr > 0 ? rr : 1);
    } else {
      onscreen(v, &P, last, cs[k][1], 1, u);
      onscreen(v, &P, last, cs[k][2], 1, w);
    }
    for (int j = 0; j <= 96; ++j) {
      double a = 2 * 3.14159265358979323846 * j / 96, ca = cos(a) * cr[k], sa = sin(a) * cr[k];
      fprintf(fp, "%.2f,%.2f ", C[0] + ca * u[0] + sa * w[0], C[1] + ca * u[1] + sa * w[1]);
    }
    fputs("\"/>\n", fp);
  }
  // the spheres' outlines at the last time
  for (const char *p = v->spheres; p && *p;) {
    int a;
    double R, C[2];
    if (sscanf(p, "[%d,%lf]", &a, &R) != 2) break;
    onscreen(v, &P, last, a, 0, C);
    fprintf(fp, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"%.2f\" fill=\"none\" stroke=\"#bbb\"/>\n",
            C[0], C[1], R * hypot(hypot(P.A[0][0], P.A[0][1]), P.A[0][2]));
    p = strchr(p, ']');
    p = p ? p + 2 : NULL;
  }
  // each time: links, then particles, more opaque as time goes on
  for (size_t f = 0; f < v->nframes; ++f) {
    double op = v->nframes > 1 ? 0.2 + 0.8 * (double)f / (double)last : 1;
    fprintf(fp, "<g opacity=\"%.3f\">\n", op);
    for (const char *p = v->links; p && *p;) {
      int a, b;
      char kind[16];
      if (sscanf(p, "[%d,%d,\"%15[a-z]\"]", &a, &b, kind) != 3) break;
      double pa[2], pb[2];
      onscreen(v, &P, f, a, 0, pa);
      onscreen(v, &P, f, b, 0, pb);
      fprintf(fp,
              "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" stroke=\"#444\" "
              "stroke-width=\"2\"%s/>\n",
              pa[0], pa[1], pb[0], pb[1],
              !strcmp(kind, "spring")   ? " stroke-dasharray=\"3 2\""
              : !strcmp(kind, "damper") ? " stroke-dasharray=\"8 3\""
                                        : "");
      if (a >= v->N)
        fprintf(fp, "<rect x=\"%.2f\" y=\"%.2f\" width=\"8\" height=\"8\" fill=\"#444\"/>\n",
                pa[0] - 4, pa[1] - 4);
      p = strchr(p, ']');
      p = p ? p + 2 : NULL;
    }
    double mmax = 0;
    for (int k = 0; k < v->N; ++k)
      mmax = fmax(mmax, sys->mass[k]);
    for (int k = 0; k < v->N; ++k) {
      double c[2];
      onscreen(v, &P, f, k, 0, c);
      fprintf(fp, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"%.2f\" fill=\"#1f77b4\"/>\n", c[0], c[1],
              fmax(3, 10 * cbrt(sys->mass[k] / mmax)));
    }
    fprintf(fp, "</g>\n");
  }
  fprintf(fp, "</svg>\n");
  return ferror(fp) ? DAL_E_IO : DAL_OK;
}

int dal_picture_write(const dal_system *sys, dal_state *st, const double *times, size_t n,
                      const dal_solve_opts *solve, FILE *fp) {
  if (!st) return DAL_E_ARG;
  int pair = dal__check_pair(sys, st, "picture_write");
  if (pair) return pair;
  if (!fp || !times || n < 1 || n > 1000)
    return DAL_FAIL(st, DAL_E_ARG, "picture_write: needs a stream and 1 to 1000 times (got %zu)",
                    n);
  if (!sys->N)
    return DAL_FAIL(st, DAL_E_ARG,
                    "picture_write: the system has no particles to draw (a Lagrangian only)");
  viewer v;
  memset(&v, 0, sizeof v);
  v.sys = sys, v.d = sys->dim, v.N = sys->N, v.n = sys->n, v.m = sys->m;
  v.nf = v.m ? v.m : v.N;
  double *t = malloc(n * sizeof *t);
  v.is_frame = malloc(n * sizeof *v.is_frame);
  int rc = t && v.is_frame ? DAL_OK : DAL_E_NOMEM;
  for (size_t i = 0; !rc && i < n; ++i)
    t[i] = times[i], v.is_frame[i] = 1;
  v.times = t;
  v.nt = v.nframes = n;
  v.pstride = n, v.nplot = 1;
  if (rc) DAL_FAIL(st, rc, "picture_write: out of memory");
  // dal_evolve_at checks the list (finite, not before the state's time, in order)
  if (!rc) rc = frames_run(&v, st, solve, NULL, "picture_write");
  if (!rc) rc = write_svg(&v, fp);
  if (rc == DAL_E_IO) DAL_FAIL(st, rc, "picture_write: writing the picture failed (disk full?)");
  viewer_free(&v);
  return rc;
}
