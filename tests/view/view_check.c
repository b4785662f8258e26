// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The viewer in a browser: writes a scene's page (dal_view_write), opens it in headless Chromium
// at two times (#t=...) and checks from the rendered DOM: no console error, every particle's
// drawn centre within 2 px of the library's own position at the shown time (a separate run,
// dal_evolve_at to that time) through the page's declared transform, a 3-D drag changes the
// picture, and the file names no URL outside itself. Chromium missing is a failure, not a skip.
//   view_check SCENE OUTDIR [SCREENSHOT.png]
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../check.h"
#include "dalembert/dalembert.h"

#define PI 3.14159265358979323846

static char chromium[256];
static char profile[1100]; // the browser's own profile folder (no HOME needed; one per scene)

// the value of attribute `name` in the DOM text (HTML-unescaped into out)
static int attr(const char *dom, const char *name, char *out, size_t len) {
  char key[64];
  snprintf(key, sizeof key, "%s=\"", name);
  const char *p = strstr(dom, key);
  if (!p) return -1;
  p += strlen(key);
  size_t k = 0;
  while (*p && *p != '"' && k + 1 < len) {
    if (!strncmp(p, "&quot;", 6))
      out[k++] = '"', p += 6;
    else if (!strncmp(p, "&amp;", 5))
      out[k++] = '&', p += 5;
    else
      out[k++] = *p++;
  }
  out[k] = 0;
  return 0;
}

// the numbers of a JSON text in order
static int numbers(const char *s, double *x, int max) {
  int n = 0;
  while (*s && n < max) {
    if (strchr("-0123456789.", *s)) {
      char *end;
      x[n++] = strtod(s, &end);
      s = end;
    } else
      ++s;
  }
  return n;
}

// the page's DOM at fragment `frag` (malloc'd text)
static char *dom_at(const char *html, const char *frag) {
  char cmd[2048];
  snprintf(cmd, sizeof cmd,
           "'%s' --headless --no-sandbox --disable-gpu --no-first-run --disable-extensions "
           "--user-data-dir='%s' --virtual-time-budget=3000 --dump-dom 'file://%s#%s' 2>/dev/null",
           chromium, profile, html, frag);
  FILE *p = popen(cmd, "r");
  if (!p) return NULL;
  size_t cap = 1 << 16, len = 0;
  char *buf = malloc(cap);
  size_t got;
  while (buf && (got = fread(buf + len, 1, cap - len - 1, p)) > 0) {
    len += got;
    if (cap - len < 4096) {
      char *b = realloc(buf, cap *= 2);
      if (!b) {
        free(buf);
        buf = NULL;
      }
      buf = b;
    }
  }
  pclose(p);
  if (buf) buf[len] = 0;
  return buf;
}

typedef struct seen {
  double A[8], drawn[64], t;
  int ndrawn, errors;
  double shape[16][32]; // the declared shapes: kind letter (c, s, p, l), then its numbers
  int nshape, len[16];
  int sections; // the section points the phase plot shows
  int jacobi;   // the plot of h - h(0) is shown
} seen;

// the declared shapes [["circle", n...], ...] into s (the kind's first letter, its numbers)
static void shapes(const char *v, seen *s) {
  s->nshape = 0;
  for (const char *p = strstr(v, "[\""); p && s->nshape < 16; p = strstr(p + 1, "[\"")) {
    int k = s->nshape++;
    s->shape[k][0] = p[2];
    const char *end = strchr(p, ']');
    char buf[2048];
    snprintf(buf, sizeof buf, "%.*s", (int)(end - p), p + 2 + strcspn(p + 2, "\"") + 1);
    s->len[k] = 1 + numbers(buf, s->shape[k] + 1, 31);
  }
}

static int look(const char *html, const char *frag, seen *s) {
  char *dom = dom_at(html, frag);
  static char v[1 << 16];
  // the page's declarations, each read into its field
  static const char *const names[] = {"data-errors", "data-transform",      "data-drawn",
                                      "data-t",      "data-sections-shown", "data-shapes"};
  int ok = dom != NULL;
  for (int i = 0; ok && i < 6; ++i) {
    ok = !attr(dom, names[i], v, sizeof v);
    if (!ok) break;
    if (i == 0) s->errors = atoi(v);
    if (i == 1) ok = numbers(v, s->A, 8) == 8;
    if (i == 2) s->ndrawn = numbers(v, s->drawn, 64);
    if (i == 3) s->t = atof(v);
    if (i == 4) s->sections = atoi(v);
    if (i == 5) shapes(v, s);
  }
  // the Jacobi plot's canvas: shown unless its tag has the attribute hidden
  const char *jp = dom ? strstr(dom, "id=\"plot-jacobi\"") : NULL;
  const char *je = jp ? strchr(jp, '>') : NULL, *jh = jp ? strstr(jp, "hidden") : NULL;
  s->jacobi = je && !(jh && jh < je);
  if (!ok) {
    fprintf(stderr, "view_check: no rendered page at #%s (chromium's DOM: %.300s)\n", frag,
            dom ? dom : "(none)");
    if (dom && strstr(dom, "id=\"errors\"")) {
      const char *e = strstr(dom, "id=\"errors\"");
      fprintf(stderr, "  errors: %.500s\n", e);
    }
  }
  free(dom);
  return ok ? 0 : -1;
}

// the library's positions at time t by its own run from the scene's start
static int expected(dal_scene *sc, double t, double *r) {
  const dal_system *sys = dal_scene_system(sc);
  const dal_solve_opts *so = dal_scene_opts(sc, NULL, NULL, NULL);
  dal_state *st = NULL;
  int rc = dal_scene_state(sc, &st);
  if (!rc && t > dal_state_time(st)) rc = dal_evolve_at(sys, st, so, &t, 1, NULL, NULL);
  if (!rc) rc = dal_forward(sys, st);
  const double *p = rc ? NULL : dal_state_positions(st);
  int n = dal_system_nparticles(sys) * dal_system_dim(sys);
  if (p) memcpy(r, p, (size_t)n * sizeof *r);
  dal_state_destroy(st);
  return p ? 0 : -1;
}

static double check_positions(dal_scene *sc, const seen *s, const char *what) {
  const dal_system *sys = dal_scene_system(sc);
  int N = dal_system_nparticles(sys), d = dal_system_dim(sys);
  double r[96], worst = 0;
  CHECK_MSG(s->errors == 0, "%s: %d console errors", what, s->errors);
  CHECK_MSG(s->ndrawn == 2 * N, "%s: %d drawn numbers for %d particles", what, s->ndrawn, N);
  CHECK_OK(expected(sc, s->t, r));
  for (int k = 0; k < N && s->ndrawn == 2 * N; ++k) {
    double x = r[k * d], y = r[k * d + 1], z = d == 3 ? r[k * d + 2] : 0;
    double px = s->A[0] * x + s->A[1] * y + s->A[2] * z + s->A[3];
    double py = s->A[4] * x + s->A[5] * y + s->A[6] * z + s->A[7];
    double e = hypot(px - s->drawn[2 * k], py - s->drawn[2 * k + 1]);
    worst = fmax(worst, e);
    CHECK_MSG(e <= 2.0, "%s: particle %d drawn at (%.2f, %.2f), the library's (%.2f, %.2f)", what,
              k, s->drawn[2 * k], s->drawn[2 * k + 1], px, py);
  }
  return worst;
}

// --- the curves and surfaces of tests/view/shapes2.scene and shapes3.scene, as the scene files
// state them (the particles of the library's run are checked to lie on them, so a table that
// drifted from its scene fails): c circle (centre, an orthonormal pair of its plane at time t,
// R), s sphere (centre, R), p plane (point, unit normal), l line (point, unit direction)
typedef struct shape {
  char kind;
  double c[3], u[3], w[3], R;
  int part; // the particle on it
} shape;

static void unit3(double *a) {
  double n = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  for (int b = 0; b < 3; ++b)
    a[b] /= n;
}

// the shapes of the scene named `base` at time t, in the page's order (circles, spheres, planes,
// lines; each in the order of the scene's placements, then its constraints); 0: not a shapes scene
static int expect(const char *base, double t, shape *e) {
  const double r2 = 1 / sqrt(2.0), r6 = 1 / sqrt(6.0);
  if (!strncmp(base, "shapes2.", 8)) {
    double a = 1.5 * t; // the rod turning about (3, 0) at 1.5 rad/s from the x axis
    e[0] = (shape){'c', {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 1, 0};
    e[1] = (shape){'l', {0, -2, 0}, {1 / hypot(1, 0.3), 0.3 / hypot(1, 0.3), 0}, {0}, 0, 1};
    e[2] = (shape){'l', {3, 0, 0}, {cos(a), sin(a), 0}, {0}, 0, 2};
    return 3;
  }
  if (!strncmp(base, "shapes3.", 8)) {
    double a = 2 * t + 0.3; // the ring's plane turning about the vertical through (-2, 0, 0)
    e[0] = (shape){'c', {-2, 0, 0}, {cos(a), sin(a), 0}, {0, 0, 1}, 0.6, 2};
    e[1] = (shape){'c', {0, 3, 1}, {r2, -r2, 0}, {r6, r6, -2 * r6}, 0.5, 3}; // normal (1, 1, 1)
    e[2] = (shape){'s', {0, -2, 0}, {0}, {0}, 0.7, 4};
    e[3] = (shape){'s', {2, 0, 0}, {0}, {0}, 0.8, 0};
    e[4] = (shape){'p', {0, 0, -1.5}, {0.2, 0, 1}, {0}, 0, 1};
    unit3(e[4].u);
    return 5;
  }
  return 0;
}

// world -> screen through the declared transform (dir: no translation)
static void to_px(const double *A, const double *x, int dir, double *p) {
  for (int r = 0; r < 2; ++r)
    p[r] = A[4 * r] * x[0] + A[4 * r + 1] * x[1] + A[4 * r + 2] * x[2] + (dir ? 0 : A[4 * r + 3]);
}

// the largest distance from a point of ellipse a to ellipse b and back (sampled), px
static double ellipses(const double *ca, const double *ua, const double *wa, const double *cb,
                       const double *ub, const double *wb) {
  double worst = 0;
  for (int pass = 0; pass < 2; ++pass) {
    const double *c1 = pass ? cb : ca, *u1 = pass ? ub : ua, *w1 = pass ? wb : wa;
    const double *c2 = pass ? ca : cb, *u2 = pass ? ua : ub, *w2 = pass ? wa : wb;
    for (int i = 0; i < 64; ++i) {
      double s = 2 * PI * i / 64, x = c1[0] + cos(s) * u1[0] + sin(s) * w1[0];
      double y = c1[1] + cos(s) * u1[1] + sin(s) * w1[1], best = INFINITY;
      for (int j = 0; j < 2048; ++j) {
        double r = 2 * PI * j / 2048;
        best = fmin(best, hypot(c2[0] + cos(r) * u2[0] + sin(r) * w2[0] - x,
                                c2[1] + cos(r) * u2[1] + sin(r) * w2[1] - y));
      }
      worst = fmax(worst, best);
    }
  }
  return worst;
}

// every drawn curve and surface where the scene puts it at the shown time, through the declared
// transform; the particles of the library's run on them
static double check_shapes(dal_scene *sc, const char *base, const seen *s, const char *what) {
  shape e[8];
  int ne = expect(base, s->t, e), d = dal_system_dim(dal_scene_system(sc));
  double r[96], worst = 0;
  if (!ne) return 0;
  CHECK_OK(expected(sc, s->t, r));
  CHECK_MSG(s->nshape == ne, "%s: %d shapes drawn, the scene has %d", what, s->nshape, ne);
  for (int k = 0; k < ne && k < s->nshape; ++k) {
    const double *g = s->shape[k];
    const shape *x = &e[k];
    double p[3] = {r[x->part * d], r[x->part * d + 1], d == 3 ? r[x->part * d + 2] : 0}, q[3];
    for (int b = 0; b < 3; ++b)
      q[b] = p[b] - x->c[b];
    double along = q[0] * x->u[0] + q[1] * x->u[1] + q[2] * x->u[2], off = 0;
    CHECK_MSG(g[0] == x->kind, "%s: shape %d is '%c', the scene's '%c'", what, k, (char)g[0],
              x->kind);
    if (x->kind == 'c' || x->kind == 's') { // the particle at distance R (in the circle's plane)
      double in = 0, nn = 0;
      for (int b = 0; b < 3; ++b) {
        double pl = along * x->u[b] + (q[0] * x->w[0] + q[1] * x->w[1] + q[2] * x->w[2]) * x->w[b];
        in += pl * pl, nn += q[b] * q[b];
      }
      off = x->kind == 'c' ? fabs(sqrt(in) - x->R) + sqrt(fmax(nn - in, 0)) : fabs(sqrt(nn) - x->R);
    } else if (x->kind == 'p') // on the plane
      off = fabs(along);
    else // on the line
      off = hypot(q[0] - along * x->u[0], q[1] - along * x->u[1]);
    CHECK_MSG(off < 1e-6, "%s: particle %d is %.3g off the scene's shape %d", what, x->part, off,
              k);
    double C[2], U[2], Wd[2], err = INFINITY;
    to_px(s->A, x->c, 0, C);
    if (x->kind == 'c' && s->len[k] == 7) { // the ellipse drawn against the scene's circle
      double ru[3], rw[3];
      for (int b = 0; b < 3; ++b)
        ru[b] = x->R * x->u[b], rw[b] = x->R * x->w[b];
      to_px(s->A, ru, 1, U);
      to_px(s->A, rw, 1, Wd);
      double gu[2] = {g[3] - g[1], g[4] - g[2]}, gw[2] = {g[5] - g[1], g[6] - g[2]};
      err = ellipses(C, U, Wd, g + 1, gu, gw);
    } else if (x->kind == 's' && s->len[k] == 4) { // the outline: centre and radius
      double k0 = sqrt(s->A[0] * s->A[0] + s->A[1] * s->A[1] + s->A[2] * s->A[2]);
      err = hypot(g[1] - C[0], g[2] - C[1]) + fabs(g[3] - k0 * x->R);
    } else if (x->kind == 'p' && s->len[k] == 21) { // the corners: on the plane, drawn there
      err = 0;
      for (int i = 0; i < 4; ++i) {
        const double *w = g + 1 + 3 * i;
        double px[2], h = 0;
        for (int b = 0; b < 3; ++b)
          h += (w[b] - x->c[b]) * x->u[b];
        to_px(s->A, w, 0, px);
        CHECK_MSG(fabs(h) < 1e-9, "%s: the plane's corner %d is %.3g off the plane", what, i, h);
        err = fmax(err, hypot(px[0] - g[13 + 2 * i], px[1] - g[14 + 2 * i]));
      }
    } else if (x->kind == 'l' && s->len[k] == 5) { // both points on the scene's line, apart
      to_px(s->A, x->u, 1, U);
      double n = hypot(U[0], U[1]);
      err = 0;
      for (int i = 0; i < 2; ++i)
        err = fmax(err, fabs((g[1 + 2 * i] - C[0]) * U[1] - (g[2 + 2 * i] - C[1]) * U[0]) / n);
      CHECK_MSG(hypot(g[3] - g[1], g[4] - g[2]) > 1, "%s: line %d drawn from one point", what, k);
    }
    CHECK_MSG(err <= 2.0, "%s: shape %d ('%c') drawn %.3g px from the scene's", what, k, x->kind,
              err);
    worst = fmax(worst, err);
  }
  return worst;
}

int main(int argc, char **argv) {
  if (argc < 3) {
    fprintf(stderr, "usage: view_check SCENE OUTDIR [SCREENSHOT.png]\n");
    return 2;
  }
  // the browser: $CHROMIUM, else chromium on the PATH (scripts/deps.sh installs it)
  const char *env = getenv("CHROMIUM");
  FILE *w = popen(env && *env ? "true" : "command -v chromium || command -v chromium-browser", "r");
  if (env && *env) snprintf(chromium, sizeof chromium, "%s", env);
  if (w && !(env && *env) && fgets(chromium, sizeof chromium, w))
    chromium[strcspn(chromium, "\n")] = 0;
  if (w) pclose(w);
  if (!chromium[0]) {
    fprintf(stderr, "view_check: chromium not found: install it (scripts/deps.sh installs "
                    "Debian's chromium) or set CHROMIUM\n");
    return 1;
  }
  char msg[1024];
  dal_scene *sc = NULL;
  if (dal_scene_read(argv[1], &sc, msg, sizeof msg)) {
    fprintf(stderr, "view_check: %s\n", msg);
    return 1;
  }
  const char *base = strrchr(argv[1], '/');
  base = base ? base + 1 : argv[1];
  char html[1024];
  snprintf(html, sizeof html, "%s/%.*s.html", argv[2], (int)strcspn(base, "."), base);
  snprintf(profile, sizeof profile, "%s/chromium-%.*s", argv[2], (int)strcspn(base, "."), base);
  // the page of the first 3 seconds at 60 frames per second, with the scene's sections (as
  // dalembert view writes it)
  const dal_system *sys = dal_scene_system(sc);
  double t0;
  dal_view_opts o = dal_default_view_opts();
  o.solve = dal_scene_opts(sc, &t0, NULL, NULL);
  o.t1 = t0 + 3.0;
  o.title = base;
  o.strobe = dal_scene_strobe(sc);
  dal_state *st = NULL;
  dal_events *ev = NULL;
  CHECK_OK(dal_scene_state(sc, &st));
  CHECK_OK(dal_scene_events(sc, &ev));
  int flags[64] = {0};
  for (int i = 0; ev && i < dal_events_size(ev) && i < 64; ++i)
    flags[i] = dal_scene_event_is_section(sc, i) == 1;
  o.sections = flags;
  FILE *fp = fopen(html, "w");
  CHECK(fp != NULL);
  if (!fp) return check_summary("view_check");
  CHECK_OK(dal_view_write(sys, st, &o, ev, fp));
  fclose(fp);
  dal_state_destroy(st);
  // the file names no URL outside itself
  fp = fopen(html, "r");
  static char text[1 << 22];
  size_t len = fp ? fread(text, 1, sizeof text - 1, fp) : 0;
  if (fp) fclose(fp);
  text[len] = 0;
  static const char *const urls[] = {
      "http:", "https:", "url(", " src=", "href=", "@import", "//cdn", "ftp:"};
  for (size_t i = 0; i < sizeof urls / sizeof *urls; ++i)
    CHECK_MSG(!strstr(text, urls[i]), "%s names '%s'", html, urls[i]);
  // two times: drawn centres where the library's positions put them
  seen a, b, c;
  CHECK_OK(look(html, "t=0.5", &a));
  CHECK_OK(look(html, "t=0.85", &b));
  CHECK_CLOSE(a.t, 0.5 + t0, 1e-9);
  CHECK_CLOSE(b.t, 0.85 + t0, 1e-9);
  double e1 = check_positions(sc, &a, "t=0.5"), e2 = check_positions(sc, &b, "t=0.85");
  printf("%s: %zu bytes, drawn centres within %.3f px (t=0.5) and %.3f px (t=0.85)\n", base, len,
         e1, e2);
  // the Jacobi integral's plot where h is an invariant and differs from E: the steadily turning
  // ring in its own coordinate (Likharev's bead); not for a drive or a still scene
  int turning = !strncmp(base, "bead_ring_", 10);
  CHECK_MSG(a.jacobi == turning, "the plot of h - h(0) is %s", a.jacobi ? "shown" : "hidden");
  // the section points fill in: those up to the time shown (the strobe's at t0 + k T, the
  // crossings of the scene's section lines the run recorded)
  for (int i = 0; i < 3; ++i) {
    seen at;
    const double tt[3] = {0.5, 0.85, 2.5};
    char frag[32];
    snprintf(frag, sizeof frag, "t=%g", tt[i]);
    if (i == 2) CHECK_OK(look(html, frag, &at));
    int want = o.strobe > 0 ? (int)floor(tt[i] / o.strobe + 1e-9) + 1 : 0;
    for (long k = 0; ev && k < dal_events_count(ev); ++k) {
      dal_event_record rec;
      CHECK_OK(dal_events_get(ev, k, &rec, NULL, NULL));
      want += flags[rec.event] && rec.t <= t0 + tt[i] + 1e-9;
    }
    int got = i == 0 ? a.sections : i == 1 ? b.sections : at.sections;
    CHECK_MSG(got == want, "t=%g: %d section points shown, %d up to then", tt[i], got, want);
    if (i == 2 && want)
      printf("%s: section points shown at t = 0.5, 0.85, 2.5: %d, %d, %d\n", base, a.sections,
             b.sections, got);
  }
  dal_events_destroy(ev);
  shape none[8];
  if (expect(base, 0, none)) {
    e1 = check_shapes(sc, base, &a, "t=0.5"), e2 = check_shapes(sc, base, &b, "t=0.85");
    printf("%s: %d curves and surfaces drawn within %.3f px (t=0.5) and %.3f px (t=0.85) of the "
           "scene's\n",
           base, a.nshape, e1, e2);
  }
  // 3-D: a drag turns the picture (and the declared transform still holds)
  if (dal_system_dim(sys) == 3) {
    CHECK_OK(look(html, "t=0.5&drag=60,25", &c));
    double moved = 0;
    for (int k = 0; k < c.ndrawn && k < a.ndrawn; ++k)
      moved = fmax(moved, fabs(c.drawn[k] - a.drawn[k]));
    CHECK_MSG(moved > 5, "a drag moved the drawing by %.2f px only", moved);
    double e3 = check_positions(sc, &c, "t=0.5 after a drag");
    if (expect(base, 0, none)) e3 = fmax(e3, check_shapes(sc, base, &c, "t=0.5 after a drag"));
    printf("%s: a drag moved the drawing by %.1f px; after it within %.3f px\n", base, moved, e3);
    // a wheel turn zooms by exp(0.001 * 300) (the page's rate), centres still in place
    seen z;
    CHECK_OK(look(html, "t=0.5&wheel=-300", &z));
    double s0 = sqrt(a.A[0] * a.A[0] + a.A[1] * a.A[1] + a.A[2] * a.A[2]);
    double s1 = sqrt(z.A[0] * z.A[0] + z.A[1] * z.A[1] + z.A[2] * z.A[2]);
    CHECK_CLOSE(s1 / s0, exp(0.3), 1e-9);
    double e4 = check_positions(sc, &z, "t=0.5 after a wheel turn");
    printf("%s: a wheel turn zoomed by %.4f; after it within %.3f px\n", base, s1 / s0, e4);
  }
  if (argc > 3) { // the guide's screenshot
    char cmd[3000];
    snprintf(cmd, sizeof cmd,
             "'%s' --headless --no-sandbox --disable-gpu --no-first-run --hide-scrollbars "
             "--user-data-dir='%s' --virtual-time-budget=3000 --window-size=1060,540 "
             "--screenshot='%s' 'file://%s#t=0.5' >/dev/null 2>&1",
             chromium, profile, argv[3], html);
    CHECK(system(cmd) == 0);
  }
  dal_scene_destroy(sc);
  return check_summary("view_check");
}
