// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Output columns (output.h) against independent references: the pendulum's tension
// m (g cos th + l thdot^2) as reaction and joint force, the Cartesian rod's multiplier (the
// same closed form through the DAE), a damper's work against the energy lost and its power
// against -c (v.e)^2; selections, their errors, and the default CSV unchanged.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "dalembert/dalembert.h"
#include "support/scenes.h"

// a monitor running a check on each output's row
typedef struct probe {
  const dal_columns *cols;
  double row[32];
  int rows;
  double worst;                         // largest error seen
  double (*err)(const struct probe *p); // the error of one row
  double m, l, g, c, E0;                // scene constants
} probe;

static int probe_monitor(const dal_system *sys, const dal_state *st, void *ctx) {
  probe *p = ctx;
  int rc = dal_columns_eval(sys, st, p->cols, p->row);
  if (rc) return -1;
  double e = p->err(p);
  if (!(e <= p->worst)) p->worst = isnan(e) ? INFINITY : e;
  p->rows++;
  return 0;
}

// pendulum about the origin: t, theta, theta_dot, x, y, Rx, Ry, Jx, Jy
static double tension_err(const probe *p) {
  const double *r = p->row;
  double th = r[1], w = r[2], T = p->m * (p->g * cos(th) + p->l * w * w);
  double ex = -r[3] / p->l, ey = -r[4] / p->l; // unit vector from the bob to the pivot
  double e = fabs(r[3] - p->l * sin(th)) + fabs(r[4] + p->l * cos(th));
  e += fabs(r[5] * ex + r[6] * ey - T) + fabs(r[5] * ey - r[6] * ex); // along, across the rod
  e += fabs(r[7] - r[5]) + fabs(r[8] - r[6]);                         // one joint: J = N
  return e / p->m / p->g;
}

// Cartesian pendulum: t, x:bob, y:bob, vx:bob, vy:bob, lambda:rod
static double rod_err(const probe *p) {
  const double *r = p->row;
  double l = sqrt(r[1] * r[1] + r[2] * r[2]);
  double cth = -r[2] / l, w2 = (r[3] * r[3] + r[4] * r[4]) / (l * l);
  double T = p->m * (p->g * cth + l * w2);
  return fabs(r[5] + T) / (p->m * p->g); // lambda = -T (primitives.h: a rod in tension)
}

// hanging spring with a damper to the origin: t, x, y, vx, vy, E, P, W
static double damper_err(const probe *p) {
  const double *r = p->row;
  double d = sqrt(r[1] * r[1] + r[2] * r[2]), ve = (r[1] * r[3] + r[2] * r[4]) / d;
  double P = -p->c * ve * ve; // a damper's power: -c (v . e)^2
  double e = fabs(r[6] - P) / (fabs(P) + 1.0);
  e += fabs((r[5] - p->E0) - r[7]) / fabs(p->E0); // E - E(0) = W
  return e;
}

static void pendulum_tension(void) {
  scn_knobs k = scn_default();
  k.m = 1.5;
  k.l = 0.8;
  dal_system *sys = scn_pendulum(&k);
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  double q = 2.0, qd = 0.5;
  CHECK_OK(dal_state_set(sys, st, 0.0, &q, &qd));
  char msg[512];
  dal_columns *cols = NULL;
  CHECK_OK(dal_columns_create(sys, "t,q:theta,qdot:*,x:bob,y:bob,Rx:bob,Ry:bob,Jx:*,Jy:b*", &cols,
                              msg, sizeof msg));
  CHECK(dal_columns_count(cols) == 9);
  CHECK(!strcmp(dal_columns_name(cols, 1), "theta"));
  CHECK(!strcmp(dal_columns_name(cols, 2), "theta_dot"));
  CHECK(!strcmp(dal_columns_name(cols, 5), "Rx:bob"));
  probe p = {.cols = cols, .err = tension_err, .m = k.m, .l = k.l, .g = k.g};
  dal_solve_opts o = scn_opts(DAL_FORM_AUTO, DAL_METHOD_DOPRI5, 1e-10);
  CHECK_OK(dal_evolve(sys, st, &o, 3.0, 0.01, probe_monitor, &p));
  printf("pendulum tension: %d rows, worst |N - m(g cos th + l thdot^2)| / mg = %.2e\n", p.rows,
         p.worst);
  CHECK(p.rows == 301);
  CHECK(p.worst < 1e-13);
  dal_columns_destroy(cols);
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

static void cartesian_rod(void) {
  scn_knobs k = scn_default();
  k.m = 0.7;
  k.l = 1.3;
  dal_system *sys = scn_cart_pendulum(&k);
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  double th = 1.2, q[2] = {k.l * sin(th), -k.l * cos(th)}, qd[2] = {0.0, 0.0};
  CHECK_OK(dal_state_set(sys, st, 0.0, q, qd));
  char msg[512];
  dal_columns *cols = NULL;
  CHECK_OK(dal_columns_create(sys, "t,x:bob,y:bob,vx:bob,vy:bob,lambda:*", &cols, msg, sizeof msg));
  CHECK(dal_columns_count(cols) == 6);
  CHECK(!strcmp(dal_columns_name(cols, 5), "lambda:rod"));
  probe p = {.cols = cols, .err = rod_err, .m = k.m, .l = k.l, .g = k.g};
  dal_solve_opts o = scn_opts(DAL_FORM_GGL, DAL_METHOD_BDF, 1e-9);
  CHECK_OK(dal_evolve(sys, st, &o, 2.0, 0.02, probe_monitor, &p));
  printf("Cartesian rod (GGL, IDA): %d rows, worst |lambda + m(g cos th + l thdot^2)| / mg = "
         "%.2e\n",
         p.rows, p.worst);
  CHECK(p.rows == 101);
  CHECK(p.worst < 1e-12);
  dal_columns_destroy(cols);
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

static void damper_work(void) {
  scn_knobs k = scn_default();
  k.k = 20.0;
  k.c = 0.4;
  dal_system *sys = scn_hanging_spring(&k);
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  double q[2] = {0.6, -1.5}, qd[2] = {1.0, 0.0};
  CHECK_OK(dal_state_set(sys, st, 0.0, q, qd));
  CHECK_OK(dal_forward(sys, st));
  dal_energies en;
  CHECK_OK(dal_state_energies(st, &en));
  char msg[512];
  dal_columns *cols = NULL;
  CHECK_OK(dal_columns_create(sys, "t,x:bob,y:bob,vx:bob,vy:bob,E,P,W", &cols, msg, sizeof msg));
  CHECK(dal_columns_need_work(cols));
  probe p = {.cols = cols, .err = damper_err, .m = k.m, .c = k.c, .E0 = en.E};
  dal_solve_opts o = scn_opts(DAL_FORM_AUTO, DAL_METHOD_DOPRI5, 1e-11);
  o.work = 1;
  CHECK_OK(dal_evolve(sys, st, &o, 5.0, 0.05, probe_monitor, &p));
  printf("damper: %d rows, E(0) = %.6f, W(5) = %.6f, worst error of P and of E - E(0) - W: "
         "%.2e\n",
         p.rows, en.E, p.row[7], p.worst);
  CHECK(p.row[7] < -0.5); // the damper took a good part of the energy
  CHECK(p.worst < 1e-9);
  dal_columns_destroy(cols);
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

// the default selection writes the bytes the default dal_csv always wrote; with wrap too
static void default_csv(void) {
  dal_system *sys = scn_pendulum(NULL);
  dal_columns *cols = NULL;
  char msg[512];
  CHECK_OK(dal_columns_create(sys, NULL, &cols, msg, sizeof msg));
  CHECK(dal_columns_count(cols) == 5);
  char *text[2] = {NULL, NULL};
  for (int pass = 0; pass < 2; ++pass) {
    dal_state *st = NULL;
    CHECK_OK(dal_state_create(sys, &st));
    double q = 3.0, qd = 2.0;
    CHECK_OK(dal_state_set(sys, st, 0.0, &q, &qd));
    FILE *fp = tmpfile();
    dal_csv c = {fp, 0, 1, pass ? cols : NULL};
    dal_solve_opts o = scn_opts(DAL_FORM_AUTO, DAL_METHOD_DOPRI5, 1e-8);
    CHECK_OK(dal_evolve(sys, st, &o, 1.0, 0.1, dal_csv_monitor, &c));
    long len = ftell(fp);
    text[pass] = calloc((size_t)len + 1, 1);
    rewind(fp);
    CHECK(text[pass] && fread(text[pass], 1, (size_t)len, fp) == (size_t)len);
    fclose(fp);
    dal_state_destroy(st);
  }
  CHECK(text[0] && text[1] && !strcmp(text[0], text[1]));
  CHECK(text[0] && !strncmp(text[0], "t,theta,theta_dot,E,h\n", 22));
  free(text[0]);
  free(text[1]);
  dal_columns_destroy(cols);
  dal_system_destroy(sys);
}

// every bad selection names its culprit and makes nothing
static void bad_selections(void) {
  dal_system *sys = scn_pendulum(NULL);
  static const struct {
    const char *spec, *says;
  } bad[] = {
      {"t,E,bogus", "'bogus'"},
      {"x:bobby", "particles: bob"},
      {"z:bob", "2-D"},
      {"lambda:*", "the system has none"},
      {"q:phi", "coordinates: theta"},
      {"t,,E", "empty"},
      {"Fx:bob", "unknown kind 'Fx:'"},
  };
  for (size_t i = 0; i < sizeof bad / sizeof *bad; ++i) {
    dal_columns *cols = (dal_columns *)&bad; // must be reset to NULL
    char msg[512] = "";
    int rc = dal_columns_create(sys, bad[i].spec, &cols, msg, sizeof msg);
    CHECK_MSG(rc == DAL_E_ARG && !cols && strstr(msg, bad[i].says), "'%s': rc %d, '%s'",
              bad[i].spec, rc, msg);
  }
  // an unevaluated state is refused, not read stale
  dal_state *st = NULL;
  dal_columns *cols = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  CHECK_OK(dal_columns_create(sys, "E", &cols, NULL, 0));
  double row[1];
  CHECK(dal_columns_eval(sys, st, cols, row) == DAL_E_STATE);
  CHECK(strstr(dal_state_errmsg(st), "not evaluated") != NULL);
  dal_columns_destroy(cols);
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

// the positions of a run at the frame times t0 + i / fps (a monitor keeps them)
typedef struct keep {
  double *r;
  size_t rows, width;
} keep;

static int keep_positions(const dal_system *sys, const dal_state *st, void *ctx) {
  keep *k = ctx;
  (void)sys;
  memcpy(k->r + k->rows++ * k->width, dal_state_positions(st), k->width * sizeof *k->r);
  return 0;
}

// the page's series `key` decoded as docs/guide.md states the format (view.c: put_series): the
// numbers of {"w", "lo", "step", "b64"}, base64, zigzag varints of the misses of the prediction
// (0; k[r-1]; 2 k[r-1] - k[r-2]), x = lo + k step; rows x w values into x
static int decode_series(const char *page, const char *key, size_t rows, double *x, double *step) {
  char pat[32];
  snprintf(pat, sizeof pat, "\"%s\":{\"w\":", key);
  const char *p = strstr(page, pat);
  if (!p) return -1;
  int w = atoi(p + strlen(pat));
  double *lo = calloc((size_t)w, sizeof *lo);
  const char *q = strstr(p, "\"lo\":[") + 6;
  for (int c = 0; c < w; ++c, ++q)
    lo[c] = strtod(q, (char **)&q);
  q = strstr(p, "\"step\":[") + 8;
  for (int c = 0; c < w; ++c, ++q)
    step[c] = strtod(q, (char **)&q);
  q = strstr(p, "\"b64\":\"") + 7;
  size_t n64 = strcspn(q, "\""), nb = 0;
  unsigned char *buf = malloc(n64);
  unsigned acc = 0;
  int bits = 0;
  for (size_t i = 0; i < n64 && q[i] != '='; ++i) {
    const char *tab = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    acc = (acc << 6) | (unsigned)(strchr(tab, q[i]) - tab);
    if ((bits += 6) >= 8) buf[nb++] = (unsigned char)(acc >> (bits -= 8)), acc &= (1u << bits) - 1;
  }
  long *k = calloc(2 * (size_t)w, sizeof *k);
  size_t at = 0;
  for (size_t r = 0; r < rows; ++r)
    for (int c = 0; c < w; ++c) {
      if (!(step[c] > 0)) {
        x[r * (size_t)w + (size_t)c] = lo[c];
        continue;
      }
      unsigned long z = 0;
      for (int sh = 0; at < nb; sh += 7) {
        z |= (unsigned long)(buf[at] & 127) << sh;
        if (!(buf[at++] & 128)) break;
      }
      long miss = z & 1 ? -(long)((z + 1) / 2) : (long)(z / 2);
      long kk = (r >= 2 ? 2 * k[2 * c] - k[2 * c + 1] : k[2 * c]) + miss;
      k[2 * c + 1] = k[2 * c], k[2 * c] = kk;
      x[r * (size_t)w + (size_t)c] = kk == 65535 ? NAN : lo[c] + (double)kk * step[c];
    }
  int ok = at == nb ? w : -1; // every byte read
  free(lo);
  free(buf);
  free(k);
  return ok;
}

// 10^4 frames at 60 per second of 10 particles within 2 MB, the positions decoded from the page
// within the stated precision (half a step, step = the coordinate's range / 65534) of the
// library's own run at the frame times
static void view_page(const char *what, dal_system *sys, dal_state *st, dal_solve_opts *so) {
  size_t nf = 10000, w = (size_t)(dal_system_nparticles(sys) * dal_system_dim(sys));
  double t0 = dal_state_time(st), *times = malloc(nf * sizeof *times);
  for (size_t i = 0; i < nf; ++i)
    times[i] = t0 + (double)i / 60;
  double *q0 = malloc(2 * (size_t)dal_system_ncoords(sys) * sizeof *q0);
  memcpy(q0, dal_state_q(st), (size_t)dal_system_ncoords(sys) * sizeof *q0);
  memcpy(q0 + dal_system_ncoords(sys), dal_state_qdot(st),
         (size_t)dal_system_ncoords(sys) * sizeof *q0);
  keep ref = {malloc(nf * w * sizeof(double)), 0, w};
  CHECK_OK(dal_evolve_at(sys, st, so, times, nf, keep_positions, &ref));
  CHECK(ref.rows == nf);
  CHECK_OK(dal_state_set(sys, st, t0, q0, q0 + dal_system_ncoords(sys)));
  dal_view_opts o = dal_default_view_opts();
  o.solve = so;
  o.t1 = times[nf - 1];
  FILE *fp = tmpfile();
  CHECK_OK(dal_view_write(sys, st, &o, NULL, fp));
  long size = ftell(fp);
  char *page = calloc((size_t)size + 1, 1);
  rewind(fp);
  CHECK(page && fread(page, 1, (size_t)size, fp) == (size_t)size);
  fclose(fp);
  CHECK(strstr(page, "\"frames\":10000,") != NULL);
  double *x = malloc(nf * w * sizeof *x), *step = malloc(w * sizeof *step), worst = 0;
  CHECK(decode_series(page, "pos", nf, x, step) == (int)w);
  for (size_t c = 0; c < w; ++c) { // the bound from the reference's own range
    double lo = INFINITY, hi = -INFINITY, e = 0;
    for (size_t r = 0; r < nf; ++r)
      lo = fmin(lo, ref.r[r * w + c]), hi = fmax(hi, ref.r[r * w + c]);
    for (size_t r = 0; r < nf; ++r)
      e = fmax(e, fabs(x[r * w + c] - ref.r[r * w + c]));
    CHECK_MSG(e <= (hi - lo) / 131068 * (1 + 1e-9) + 1e-15,
              "%s: coordinate %zu off by %.3g (range %.3g)", what, c, e, hi - lo);
    worst = fmax(worst, e / (hi - lo));
  }
  printf("viewer: 10^4 frames of 10 particles (%s): %ld bytes, %.1f bytes per frame and "
         "particle; positions within %.3g of each coordinate's range (bound 1/131068 = %.3g)\n",
         what, size, (double)size / 1e5, worst, 1.0 / 131068);
  CHECK(size < 2000000);
  free(page), free(x), free(step), free(times), free(q0), free(ref.r);
}

// the viewer's page: a 2-D chain and 3-D spherical pendulums (each on its turning circle);
// bad options refused
static void view_size(void) {
  scn_knobs k = scn_default();
  k.N = 10;
  dal_system *sys = scn_chain(&k);
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  double q[10] = {0.5, 0.4, 0.3, 0.2, 0.1, 0, -0.1, -0.2, -0.3, -0.4}, qd[10] = {0};
  CHECK_OK(dal_state_set(sys, st, 0.0, q, qd));
  dal_solve_opts so = scn_opts(DAL_FORM_AUTO, DAL_METHOD_DOPRI5, 1e-6);
  view_page("2-D chain", sys, st, &so);
  // refused: no stream, t1 not after t, fps <= 0
  dal_view_opts o = dal_default_view_opts();
  o.t1 = dal_state_time(st);
  CHECK(dal_view_write(sys, st, &o, NULL, stdout) == DAL_E_ARG);
  CHECK(strstr(dal_state_errmsg(st), "t1 after") != NULL);
  o.t1 = 100, o.fps = 0;
  CHECK(dal_view_write(sys, st, &o, NULL, stdout) == DAL_E_ARG);
  o.fps = 60;
  CHECK(dal_view_write(sys, st, &o, NULL, NULL) == DAL_E_ARG);
  dal_state_destroy(st);
  dal_system_destroy(sys);
  // ten spherical pendulums in formulas, each turning about the vertical (the heaviest page per
  // particle: every one moves on a circle whose plane turns)
  char text[4096];
  size_t len = (size_t)snprintf(text, sizeof text, "dim 3\n");
  for (int i = 0; i < 10; ++i)
    len += (size_t)snprintf(text + len, sizeof text - len,
                            "coord th%d q=1 v=0\ncoord ph%d q=0 v=%d\nparticle p%d mass=1\n"
                            "place p%d = %g + sin(th%d)*cos(ph%d); sin(th%d)*sin(ph%d); "
                            "-cos(th%d)\n",
                            i, i, 2 + i % 3, i, i, 1.5 * i, i, i, i, i, i);
  snprintf(text + len, sizeof text - len, "gravity 0 0 -9.81\n");
  dal_scene *sc = NULL;
  char msg[512];
  CHECK_OK(dal_scene_parse(text, "spherical10", &sc, msg, sizeof msg));
  CHECK_OK(dal_scene_state(sc, &st));
  so = scn_opts(DAL_FORM_AUTO, DAL_METHOD_DOPRI5, 1e-6);
  view_page("3-D spherical pendulums", (dal_system *)dal_scene_system(sc), st, &so);
  dal_state_destroy(st);
  dal_scene_destroy(sc);
}

// the picture: each exposure's bob where the library's own run puts it, seen from the pivot
static void picture(void) {
  dal_system *sys = scn_pendulum(NULL);
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  double q = 1.0, qd = 0.0, times[3] = {0.0, 0.4, 0.9}, th[3];
  dal_solve_opts o = scn_opts(DAL_FORM_AUTO, DAL_METHOD_DOPRI5, 1e-10);
  for (int i = 0; i < 3; ++i) { // the reference angles by separate runs
    CHECK_OK(dal_state_set(sys, st, 0.0, &q, &qd));
    if (times[i] > 0) CHECK_OK(dal_evolve_at(sys, st, &o, &times[i], 1, NULL, NULL));
    th[i] = dal_state_q(st)[0];
  }
  CHECK_OK(dal_state_set(sys, st, 0.0, &q, &qd));
  FILE *fp = tmpfile();
  CHECK_OK(dal_picture_write(sys, st, times, 3, &o, fp));
  long len = ftell(fp);
  char *svg = calloc((size_t)len + 1, 1);
  rewind(fp);
  CHECK(svg && fread(svg, 1, (size_t)len, fp) == (size_t)len);
  fclose(fp);
  // the pivot's square and the three bobs
  double px = NAN, py = NAN, cx[3], cy[3], worst = 0;
  const char *r = strstr(svg, "<rect x=");
  CHECK(r && sscanf(r, "<rect x=\"%lf\" y=\"%lf\"", &px, &py) == 2);
  px += 4, py += 4;
  const char *c = svg;
  int nb = 0;
  while (nb < 3 && (c = strstr(c, "<circle cx="))) {
    CHECK(sscanf(c, "<circle cx=\"%lf\" cy=\"%lf\"", &cx[nb], &cy[nb]) == 2);
    ++nb, ++c;
  }
  CHECK(nb == 3);
  for (int i = 0; i < nb; ++i) { // screen y grows downwards: theta = atan2(dx, dy)
    double a = atan2(cx[i] - px, cy[i] - py);
    worst = fmax(worst, fabs(a - th[i]));
    CHECK_CLOSE(hypot(cx[i] - px, cy[i] - py), hypot(cx[0] - px, cy[0] - py), 1e-3);
  }
  printf("picture: 3 exposures, bob angles from the pivot within %.1e rad of the library's\n",
         worst);
  CHECK(worst < 1e-4); // the picture's %.2f px over a rod of some 200 px
  CHECK(dal_picture_write(sys, st, times, 0, &o, stdout) == DAL_E_ARG);
  free(svg);
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

// names of any length reach the header whole (a fixed 80-byte name was cut silently before)
static void long_names(void) {
  char part[301], coord[301], spec[400];
  memset(part, 'p', 300);
  part[300] = 0;
  memset(coord, 'c', 300);
  coord[300] = 0;
  dal_builder *b = NULL;
  int c = -1, k = -1;
  CHECK_OK(dal_builder_create(2, &b));
  CHECK_OK(dal_builder_add_coord(b, coord, &c));
  CHECK_OK(dal_builder_add_particle(b, part, 1.0, &k));
  dal_place_def pd = dal_default_place_def();
  pd.prim = &dal_map_pendulum;
  pd.coords = &c;
  pd.ncoords = 1;
  pd.param[DAL_PENDULUM_L] = 1.0;
  CHECK_OK(dal_builder_place_def(b, k, &pd));
  dal_system *sys = NULL;
  CHECK_OK(dal_builder_compile(b, &sys));
  dal_builder_destroy(b);
  dal_columns *cols = NULL;
  char msg[200];
  snprintf(spec, sizeof spec, "x:p*,qdot:*");
  CHECK_OK(dal_columns_create(sys, spec, &cols, msg, sizeof msg));
  CHECK(dal_columns_count(cols) == 2);
  const char *n0 = dal_columns_name(cols, 0), *n1 = dal_columns_name(cols, 1);
  CHECK(n0 && strlen(n0) == 302 && !strncmp(n0, "x:", 2) && !strcmp(n0 + 2, part));
  CHECK(n1 && strlen(n1) == 304 && !strncmp(n1, coord, 300) && !strcmp(n1 + 300, "_dot"));
  dal_columns_destroy(cols);
  dal_system_destroy(sys);
}

int main(void) {
  long_names();
  pendulum_tension();
  cartesian_rod();
  damper_work();
  default_csv();
  bad_selections();
  view_size();
  picture();
  return check_summary("test_output");
}
