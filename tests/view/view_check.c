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
} seen;

static int look(const char *html, const char *frag, seen *s) {
  char *dom = dom_at(html, frag);
  static char v[1 << 16];
  int ok = dom != NULL;
  if (ok && !attr(dom, "data-errors", v, sizeof v))
    s->errors = atoi(v);
  else
    ok = 0;
  if (ok && !attr(dom, "data-transform", v, sizeof v))
    ok = numbers(v, s->A, 8) == 8;
  else
    ok = 0;
  if (ok && !attr(dom, "data-drawn", v, sizeof v))
    s->ndrawn = numbers(v, s->drawn, 64);
  else
    ok = 0;
  if (ok && !attr(dom, "data-t", v, sizeof v))
    s->t = atof(v);
  else
    ok = 0;
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

int main(int argc, char **argv) {
  if (argc < 3) {
    fprintf(stderr, "usage: view_check SCENE OUTDIR [SCREENSHOT.png]\n");
    return 2;
  }
  // the browser: $CHROMIUM, else chromium on the PATH (scripts/deps.sh installs it)
  const char *env = getenv("CHROMIUM");
  FILE *w = popen(env && *env ? "true" : "command -v chromium || command -v chromium-browser",
                  "r");
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
  // the page of the first second at 60 frames per second
  const dal_system *sys = dal_scene_system(sc);
  double t0;
  dal_view_opts o = dal_default_view_opts();
  o.solve = dal_scene_opts(sc, &t0, NULL, NULL);
  o.t1 = t0 + 1.0;
  o.title = base;
  dal_state *st = NULL;
  CHECK_OK(dal_scene_state(sc, &st));
  FILE *fp = fopen(html, "w");
  CHECK(fp != NULL);
  if (!fp) return check_summary("view_check");
  CHECK_OK(dal_view_write(sys, st, &o, NULL, fp));
  fclose(fp);
  dal_state_destroy(st);
  // the file names no URL outside itself
  fp = fopen(html, "r");
  static char text[1 << 22];
  size_t len = fp ? fread(text, 1, sizeof text - 1, fp) : 0;
  if (fp) fclose(fp);
  text[len] = 0;
  static const char *const urls[] = {"http:", "https:", "url(", " src=", "href=", "@import",
                                     "//cdn", "ftp:"};
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
  // 3-D: a drag turns the picture (and the declared transform still holds)
  if (dal_system_dim(sys) == 3) {
    CHECK_OK(look(html, "t=0.5&drag=60,25", &c));
    double moved = 0;
    for (int k = 0; k < c.ndrawn && k < a.ndrawn; ++k)
      moved = fmax(moved, fabs(c.drawn[k] - a.drawn[k]));
    CHECK_MSG(moved > 5, "a drag moved the drawing by %.2f px only", moved);
    double e3 = check_positions(sc, &c, "t=0.5 after a drag");
    printf("%s: a drag moved the drawing by %.1f px; after it within %.3f px\n", base, moved, e3);
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
