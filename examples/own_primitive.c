// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// A primitive of your own: a bead on an ellipse, placed by a def with named parameters.
//
// Problem: a bead (0.1 kg) on a vertical elliptical wire x = a sin s, y = -b cos s (semi-axes
// a = 0.6 m, b = 0.3 m), under gravity; s is the wire's parameter. The primitive is written once
// over jets with names and defaults for its parameters (table version DAL_PRIMITIVE_VERSION).
// Checks (--check): dal_verify_primitive passes it; a forgotten required parameter is an error
// that names it; small oscillations about the bottom have the closed-form period
// 2 pi / sqrt(g b / a^2) (linearized: kinetic m a^2 s'^2 / 2, potential m g b s^2 / 2).
#include <dalembert/dalembert.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

enum { ELLIPSE_A, ELLIPSE_B, ELLIPSE_NPARAM };

static int ellipse(const dal_jet *in, dal_jet t, const double *p, dal_jet *out, void *ctx) {
  (void)t;
  (void)ctx;
  dal_jet s, c;
  dal_sincos(in[0], &s, &c);
  out[0] = dal_scale(s, p[ELLIPSE_A]);
  out[1] = dal_scale(c, -p[ELLIPSE_B]);
  return 0;
}

static const char *const ellipse_names[] = {"a", "b"};
static const double ellipse_defaults[] = {NAN, NAN}; // both required
static const dal_primitive map_ellipse = {
    .name = "ellipse",
    .version = DAL_PRIMITIVE_VERSION,
    .nin = 1,
    .nout = 2,
    .nparam = ELLIPSE_NPARAM,
    .eval = ellipse,
    .doc = "in (s); param (a, b); out (a sin s, -b cos s)",
    .param_names = ellipse_names,
    .param_defaults = ellipse_defaults,
};

// zero crossings of s(t) going up, by linear interpolation on the monitor grid
typedef struct period {
  double last_s, last_t, first, latest;
  int n;
} period;

static int monitor(const dal_system *sys, const dal_state *st, void *ctx) {
  (void)sys;
  period *p = ctx;
  double s = dal_state_q(st)[0], t = dal_state_time(st);
  if (p->last_s < 0 && s >= 0) {
    double tc = p->last_t + (t - p->last_t) * (-p->last_s) / (s - p->last_s);
    if (p->n++ == 0) p->first = tc;
    p->latest = tc;
  }
  p->last_s = s;
  p->last_t = t;
  return 0;
}

int main(int argc, char **argv) {
  int check = argc > 1 && strcmp(argv[1], "--check") == 0, bad = 0;
  const double a = 0.6, b = 0.3, par[2] = {a, b};
  dal_verify_report vr;
  if (dal_verify_primitive(&map_ellipse, par, NULL, NULL, &vr)) bad = 1;
  printf("%s\n", vr.msg);
  dal_builder *bld = NULL;
  int s, bead;
  dal_builder_create(2, &bld);
  dal_builder_add_coord(bld, "s", &s);
  dal_builder_add_particle(bld, "bead", 0.1, &bead);
  dal_place_def d = dal_default_place_def();
  d.prim = &map_ellipse;
  d.coords = &s;
  d.ncoords = 1;
  d.param[ELLIPSE_A] = a; // b forgotten:
  if (dal_builder_place_def(bld, bead, &d) != DAL_E_ARG) bad = 1;
  printf("forgotten parameter: %s\n", dal_builder_errmsg(bld));
  if (!strstr(dal_builder_errmsg(bld), "parameter 'b' of 'ellipse'")) bad = 1;
  d.param[ELLIPSE_B] = b;
  dal_builder_place_def(bld, bead, &d);
  double g[2] = {0, -9.81};
  dal_builder_set_gravity(bld, g);
  dal_system *sys = NULL;
  if (dal_builder_compile(bld, &sys)) return 1;
  dal_state *st = NULL;
  dal_state_create(sys, &st);
  double s0 = 1e-3, v0 = 0.0;
  dal_state_set(sys, st, 0, &s0, &v0);
  dal_solve_opts o = dal_default_solve_opts();
  o.rtol = 1e-10;
  period p = {s0, 0.0, 0.0, 0.0, 0};
  if (dal_evolve(sys, st, &o, 20.0, 1e-3, monitor, &p)) return 1;
  double T = (p.latest - p.first) / (p.n - 1),
         T0 = 2 * 3.14159265358979323846 / sqrt(9.81 * b / (a * a));
  printf("small oscillations: period %.8f s, closed form %.8f s (relative difference %.2g)\n", T,
         T0, fabs(T - T0) / T0);
  // amplitude 1e-3 rad: the nonlinear correction is O(s0^2) ~ 1e-6
  if (p.n < 3 || fabs(T - T0) / T0 > 1e-5) bad = 1;
  dal_state_destroy(st);
  dal_system_destroy(sys);
  dal_builder_destroy(bld);
  if (check) printf("own_primitive: %s\n", bad ? "FAILED" : "ok");
  return bad;
}
