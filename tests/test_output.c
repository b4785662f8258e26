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

// the viewer's page: 10^4 frames of a 10-particle chain within 2 MB; bad options refused
static void view_size(void) {
  scn_knobs k = scn_default();
  k.N = 10;
  dal_system *sys = scn_chain(&k);
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(sys, &st));
  double q[10] = {0.5, 0.4, 0.3, 0.2, 0.1, 0, -0.1, -0.2, -0.3, -0.4}, qd[10] = {0};
  CHECK_OK(dal_state_set(sys, st, 0.0, q, qd));
  dal_view_opts o = dal_default_view_opts();
  dal_solve_opts so = scn_opts(DAL_FORM_AUTO, DAL_METHOD_DOPRI5, 1e-6);
  o.solve = &so;
  o.fps = 1000;
  o.t1 = 9.999; // frames 0 ... 9999
  FILE *fp = tmpfile();
  CHECK_OK(dal_view_write(sys, st, &o, NULL, fp));
  long size = ftell(fp);
  fclose(fp);
  printf("viewer: 10^4 frames of 10 particles (2-D chain): %ld bytes, %.1f bytes per frame and "
         "particle\n",
         size, (double)size / 1e5);
  CHECK(size < 2000000);
  // refused: no stream, t1 not after t, fps <= 0
  o.t1 = dal_state_time(st);
  CHECK(dal_view_write(sys, st, &o, NULL, stdout) == DAL_E_ARG);
  CHECK(strstr(dal_state_errmsg(st), "t1 after") != NULL);
  o.t1 = 100, o.fps = 0;
  CHECK(dal_view_write(sys, st, &o, NULL, stdout) == DAL_E_ARG);
  o.fps = 60;
  CHECK(dal_view_write(sys, st, &o, NULL, NULL) == DAL_E_ARG);
  dal_state_destroy(st);
  dal_system_destroy(sys);
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
