// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Per-trajectory parameters: overrides against systems compiled with the same values.
//
// Reference: for every overridable kind (mass, placement and constraint parameters, gravity,
// spring stiffness and rest length, damper coefficient) a state of the original system with
// overrides must follow the trajectory of a system compiled with those values, bit for bit
// (same arithmetic in the same order), through the tree assembly (pendulum chain with a
// spring and a damper), a driven pendulum under DOPRI5 and BS, and a redundant DAE (GGL in
// IDA). Another state of the same system stays bit-identical to the original (the system is
// not written). Validation: the builder's messages, word for word; unknown names, bad
// indices and NaN are rejected with the state unchanged.
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "dalembert/dalembert.h"
#include "scenes.h"

// the chain: p0 on a driven pendulum, p1 and p2 hanging; spring p0-p2, damper p1-p2,
// anchor spring on p1
typedef struct chain_par {
  double m[3], l0, ax, w, l1, l2, g, k, L, c, ka;
} chain_par;

static dal_system *chain(const chain_par *P) {
  dal_builder *b = NULL;
  dal_system *s = NULL;
  int q[3], p[3], rc = dal_builder_create(2, &b);
  double h1 = P->l1, h2 = P->l2;
  double g[2] = {0, -P->g}, x0[2] = {0.5, -1.0};
  const char *names[3] = {"a", "b", "c"};
  for (int i = 0; i < 3 && !rc; ++i)
    rc = dal_builder_add_coord(b, NULL, &q[i]);
  for (int i = 0; i < 3 && !rc; ++i)
    rc = dal_builder_add_particle(b, names[i], P->m[i], &p[i]);
  scn_knobs k = scn_default(); // the drive of p0's pivot
  k.ax = P->ax;
  k.w = P->w;
  if (!rc) rc = scn_place_swing(b, &k, p[0], -1, P->l0, q[0]);
  if (!rc) rc = scn_place_swing(b, &k, p[1], p[0], h1, q[1]);
  if (!rc) rc = scn_place_swing(b, &k, p[2], p[1], h2, q[2]);
  if (!rc) rc = dal_builder_set_gravity(b, g);
  dal_spring_def sd = dal_default_spring_def();
  sd.a = p[0];
  sd.b = p[2];
  sd.k = P->k;
  sd.length = P->L;
  if (!rc) rc = dal_builder_add_spring_def(b, &sd);
  sd = dal_default_spring_def();
  sd.a = p[1];
  memcpy(sd.anchor, x0, sizeof x0);
  sd.k = P->ka;
  sd.length = 0.2;
  if (!rc) rc = dal_builder_add_spring_def(b, &sd);
  dal_damper_def dd = dal_default_damper_def();
  dd.a = p[1];
  dd.b = p[2];
  dd.c = P->c;
  if (!rc) rc = dal_builder_add_damper_def(b, &dd);
  if (!rc) rc = dal_builder_compile(b, &s);
  if (rc) fprintf(stderr, "chain: %s\n", dal_builder_errmsg(b));
  dal_builder_destroy(b);
  return s;
}

// a Cartesian particle on a rod of length L from (x0, 0), and a second one on a circle of
// radius R about the origin tied to the first by a rod "link" (a closed loop): 4 coordinates,
// 2 + 1 + 1 constraint rows
static dal_system *loop(double L, double x0, double R, double link, double m) {
  scn_knobs k = scn_default();
  k.l = L;
  k.x0 = x0;
  k.R = R;
  k.m = m;
  return scn_closed_loop(&k, link);
}

// advance st from (q0, v0) to t1; write the final (q, qdot) into out (2n); returns status
static int run(const dal_system *sys, dal_state *st, const double *q0, const double *v0,
               dal_method method, double t1, double *out) {
  dal_solve_opts o = dal_default_solve_opts();
  o.method = method;
  o.rtol = 1e-9;
  o.atol = 1e-11;
  int n = dal_system_ncoords(sys);
  int rc = dal_state_set(sys, st, 0.0, q0, v0);
  if (!rc) rc = dal_advance(sys, st, &o, t1);
  if (!rc) {
    memcpy(out, dal_state_q(st), (size_t)n * sizeof(double));
    memcpy(out + n, dal_state_qdot(st), (size_t)n * sizeof(double));
  }
  return rc;
}

static void test_chain(void) {
  chain_par P0 = {{1.0, 0.7, 1.3}, 1.0, 0.1, 3.0, 0.8, 0.6, 9.81, 20.0, 1.5, 0.3, 5.0};
  chain_par P1 = {{0.4, 2.1, 1.3}, 1.2, 0.25, 2.2, 0.8, 0.9, 3.71, 35.0, 1.1, 0.9, 5.0};
  dal_system *s0 = chain(&P0), *s1 = chain(&P1);
  CHECK(s0 && s1);
  if (!s0 || !s1) goto done;
  dal_state *a = NULL, *b = NULL, *ref = NULL, *ref0 = NULL;
  CHECK_OK(dal_state_create(s0, &a));
  CHECK_OK(dal_state_create(s0, &b));
  CHECK_OK(dal_state_create(s1, &ref));
  CHECK_OK(dal_state_create(s0, &ref0));
  // overrides, by reference and by name
  CHECK_OK(dal_state_set_mass(s0, a, 0, P1.m[0]));
  CHECK_OK(dal_state_set_param_named(s0, a, "mass:b", P1.m[1]));
  CHECK_OK(dal_state_set_param_named(s0, a, "place:a:0", P1.l0));
  CHECK_OK(dal_state_set_param_named(s0, a, "place:a:3", P1.ax));
  CHECK_OK(dal_state_set_param_named(s0, a, "place:0:5", P1.w));
  CHECK_OK(dal_state_set_param_named(s0, a, "place:c:0", P1.l2));
  double g[2] = {0, -P1.g};
  CHECK_OK(dal_state_set_gravity(s0, a, g));
  CHECK_OK(dal_state_set_param_named(s0, a, "spring:0:k", P1.k));
  CHECK_OK(dal_state_set_param_named(s0, a, "spring:0:L", P1.L));
  CHECK_OK(dal_state_set_param_named(s0, a, "damper:0:c", P1.c));
  {
    // a primitive's parameter by the name in its table addresses what its index does (the
    // names of dal_map_pendulum: l, x0, y0, ax, ay, w, ph); another primitive's name is
    // refused with the names this one has
    dal_param_ref rn, ri;
    char msg[256];
    CHECK_OK(dal_param_find(s0, "place:a:w", &rn, NULL, 0));
    CHECK_OK(dal_param_find(s0, "place:a:5", &ri, NULL, 0));
    CHECK(rn.kind == DAL_PARAM_PLACE && rn.target == ri.target && rn.index == DAL_PENDULUM_W &&
          ri.index == DAL_PENDULUM_W);
    CHECK_OK(dal_param_find(s0, "place:0:ax", &rn, NULL, 0));
    CHECK(rn.index == DAL_PENDULUM_AX && rn.target == 0);
    CHECK(dal_param_find(s0, "place:a:R", &rn, msg, sizeof msg) == DAL_E_ARG);
    CHECK_MSG(strstr(msg, "'R'") && strstr(msg, "(l, x0, y0, ax, ay, w, ph)"), "%s", msg);
  }
  dal_param_ref r;
  double v = 0;
  CHECK_OK(dal_param_find(s0, "place:a:5", &r, NULL, 0));
  CHECK_OK(dal_state_param(s0, a, &r, &v));
  CHECK(v == P1.w);
  CHECK_OK(dal_system_param(s0, &r, &v));
  CHECK(v == P0.w);
  char nm[64];
  CHECK_OK(dal_param_name(s0, &r, nm, sizeof nm));
  CHECK(strcmp(nm, "place:a:5") == 0);
  double q0[3] = {0.4, -0.3, 0.9}, v0[3] = {0.1, 0.5, -0.2};
  double xa[6], xb[6], xr[6], x0[6];
  const dal_method methods[] = {DAL_METHOD_DOPRI5, DAL_METHOD_BS, DAL_METHOD_ADAMS};
  for (int mi = 0; mi < 3; ++mi) {
    CHECK_OK(run(s0, a, q0, v0, methods[mi], 2.0, xa));
    CHECK_OK(run(s1, ref, q0, v0, methods[mi], 2.0, xr));
    CHECK_OK(run(s0, b, q0, v0, methods[mi], 2.0, xb));
    CHECK_OK(run(s0, ref0, q0, v0, methods[mi], 2.0, x0));
    CHECK_MSG(memcmp(xa, xr, sizeof xa) == 0, "%s: override %.17g vs compiled %.17g",
              dal_method_name(methods[mi]), xa[0], xr[0]);
    CHECK_MSG(memcmp(xb, x0, sizeof xb) == 0, "%s: untouched state changed",
              dal_method_name(methods[mi]));
    CHECK(memcmp(xa, xb, sizeof xa) != 0); // the overrides do change the motion
  }
  // energies come from the overridden masses and constants too
  dal_energies ea, er;
  CHECK_OK(dal_forward(s0, a));
  CHECK_OK(dal_forward(s1, ref));
  CHECK_OK(dal_state_energies(a, &ea));
  CHECK_OK(dal_state_energies(ref, &er));
  CHECK(memcmp(&ea, &er, sizeof ea) == 0);
  // copy to another state, then reset: back to the system's values
  CHECK_OK(dal_state_copy_params(s0, b, a));
  CHECK_OK(run(s0, b, q0, v0, DAL_METHOD_DOPRI5, 2.0, xb));
  CHECK_OK(run(s1, ref, q0, v0, DAL_METHOD_DOPRI5, 2.0, xr));
  CHECK(memcmp(xb, xr, sizeof xb) == 0);
  CHECK_OK(dal_state_reset_params(s0, b));
  CHECK_OK(run(s0, b, q0, v0, DAL_METHOD_DOPRI5, 2.0, xb));
  CHECK_OK(run(s0, ref0, q0, v0, DAL_METHOD_DOPRI5, 2.0, x0));
  CHECK(memcmp(xb, x0, sizeof xb) == 0);
  CHECK_OK(dal_state_param(s0, b, &r, &v));
  CHECK(v == P0.w);
  dal_state_destroy(a);
  dal_state_destroy(b);
  dal_state_destroy(ref);
  dal_state_destroy(ref0);
done:
  dal_system_destroy(s0);
  dal_system_destroy(s1);
}

static void test_dae(void) {
  // closed loop: a rod of 1.0 from (0.5, 0), a ring of radius 1 about the origin, a link 0.8
  dal_system *s0 = loop(1.0, 0.5, 1.0, 0.8, 1.0), *s1 = loop(1.1, 0.5, 1.0, 0.9, 2.5);
  CHECK(s0 && s1);
  if (!s0 || !s1) goto done;
  dal_state *a = NULL, *ref = NULL;
  CHECK_OK(dal_state_create(s0, &a));
  CHECK_OK(dal_state_create(s1, &ref));
  {
    dal_param_ref rn, ri; // dal_con_anchor2's parameters: L, x0, y0
    CHECK_OK(dal_param_find(s0, "con:rod:L", &rn, NULL, 0));
    CHECK_OK(dal_param_find(s0, "con:rod:0", &ri, NULL, 0));
    CHECK(rn.kind == DAL_PARAM_CONSTRAINT && rn.target == ri.target && rn.index == 0 &&
          ri.index == 0);
    CHECK_OK(dal_param_find(s0, "con:rod:y0", &rn, NULL, 0));
    CHECK(rn.index == DAL_ANCHOR_Y0);
  }
  CHECK_OK(dal_state_set_param_named(s0, a, "con:rod:L", 1.1));
  CHECK_OK(dal_state_set_param_named(s0, a, "con:link:0", 0.9));
  CHECK_OK(dal_state_set_param_named(s0, a, "mass:p", 2.5));
  // a rough guess: dal_advance makes it consistent first (for its own constraints)
  double q0[4] = {0.9, -0.9, 0.3, -0.9}, v0[4] = {0.2, 0.1, 0.0, 0.0}, xa[8], xr[8];
  CHECK_OK(run(s0, a, q0, v0, DAL_METHOD_AUTO, 1.0, xa));
  CHECK_OK(run(s1, ref, q0, v0, DAL_METHOD_AUTO, 1.0, xr));
  CHECK_MSG(memcmp(xa, xr, sizeof xa) == 0, "DAE override %.17g vs compiled %.17g", xa[0], xr[0]);
  // the constraint really is the overridden one: |r_p - (0.5, 0)| = 1.1
  CHECK_CLOSE(hypot(xa[0] - 0.5, xa[1]), 1.1, 1e-7);
  CHECK_CLOSE(hypot(xa[0] - xa[2], xa[1] - xa[3]), 0.9, 1e-7);
  // a rod that cannot close the loop: the distance from the anchor to the ring is at most 2.5
  CHECK_OK(dal_state_set_param_named(s0, a, "con:rod:0", 5.0));
  dal_solve_opts o = dal_default_solve_opts();
  CHECK_OK(dal_state_set(s0, a, 0.0, q0, v0));
  int rc = dal_advance(s0, a, &o, 1.0);
  CHECK_MSG(rc == DAL_E_INIT || rc == DAL_E_CONSTRAINT, "rod too long: %s (%s)",
            dal_status_name(rc), dal_state_errmsg(a));
  CHECK(strstr(dal_state_errmsg(a), "rod") || strstr(dal_state_errmsg(a), "link"));
  if (getenv("DAL_VERBOSE"))
    printf("rod too long: %s: %s\n", dal_status_name(rc), dal_state_errmsg(a));
  dal_state_destroy(a);
  dal_state_destroy(ref);
done:
  dal_system_destroy(s0);
  dal_system_destroy(s1);
}

// the builder's message for the same bad value, for comparison
static void builder_msg(double mass, char *buf, size_t len) {
  dal_builder *b = NULL;
  buf[0] = 0;
  if (dal_builder_create(2, &b)) return;
  dal_builder_add_particle(b, "a", mass, NULL);
  snprintf(buf, len, "%s", dal_builder_errmsg(b));
  dal_builder_destroy(b);
}

static void test_validation(void) {
  chain_par P0 = {{1.0, 0.7, 1.3}, 1.0, 0.1, 3.0, 0.8, 0.6, 9.81, 20.0, 1.5, 0.3, 5.0};
  dal_system *s = chain(&P0);
  CHECK(s != NULL);
  if (!s) return;
  dal_state *st = NULL;
  CHECK_OK(dal_state_create(s, &st));
  double q0[3] = {0.1, 0.2, 0.3}, v0[3] = {0, 0, 0};
  CHECK_OK(dal_state_set(s, st, 0.5, q0, v0));
  char want[512];
  // masses: the builder's words
  CHECK(dal_state_set_mass(s, st, 0, -1.0) == DAL_E_ARG);
  builder_msg(-1.0, want, sizeof want);
  CHECK_MSG(strcmp(dal_state_errmsg(st), want) == 0, "'%s' vs builder '%s'", dal_state_errmsg(st),
            want);
  CHECK(dal_state_set_mass(s, st, 0, NAN) == DAL_E_NONFINITE);
  builder_msg(NAN, want, sizeof want);
  CHECK_MSG(strcmp(dal_state_errmsg(st), want) == 0, "'%s' vs builder '%s'", dal_state_errmsg(st),
            want);
  CHECK(dal_state_set_mass(s, st, 0, 0.0) == DAL_E_ARG);
  CHECK(dal_state_set_mass(s, st, 3, 1.0) == DAL_E_ARG);
  CHECK(strstr(dal_state_errmsg(st), "particle index 3 out of range"));
  // primitive parameters, gravity, links
  CHECK(dal_state_set_param_named(s, st, "place:a:3", INFINITY) == DAL_E_NONFINITE);
  // the builder's message (the same checks, validate.c)
  CHECK(strstr(dal_state_errmsg(st), "placing particle 'a': parameter '") &&
        strstr(dal_state_errmsg(st), "of 'pendulum' (index 3) is inf"));
  CHECK(dal_state_set_param_named(s, st, "place:a:7", 1.0) == DAL_E_ARG);
  CHECK(strstr(dal_state_errmsg(st), "takes 7 parameters; index 7"));
  CHECK(dal_state_set_param_named(s, st, "gravity:1", NAN) == DAL_E_NONFINITE);
  CHECK(strstr(dal_state_errmsg(st), "gravity component 1"));
  CHECK(dal_state_set_param_named(s, st, "gravity:2", 1.0) == DAL_E_ARG);
  CHECK(dal_state_set_param_named(s, st, "spring:0:k", -3.0) == DAL_E_ARG);
  CHECK(strstr(dal_state_errmsg(st), "spring on particle 'a': coefficient -3"));
  CHECK(dal_state_set_param_named(s, st, "spring:1:L", -3.0) == DAL_E_ARG);
  CHECK(strstr(dal_state_errmsg(st), "anchor spring on particle 'b'"));
  CHECK(dal_state_set_param_named(s, st, "damper:0:c", NAN) == DAL_E_NONFINITE);
  CHECK(dal_state_set_param_named(s, st, "damper:1:c", 1.0) == DAL_E_ARG);
  // names
  CHECK(dal_state_set_param_named(s, st, "mass:nobody", 1.0) == DAL_E_ARG);
  CHECK(strstr(dal_state_errmsg(st), "no particle named 'nobody'"));
  CHECK(dal_state_set_param_named(s, st, "con:rod:0", 1.0) == DAL_E_ARG);
  CHECK(strstr(dal_state_errmsg(st), "no constraint named 'rod'"));
  CHECK(dal_state_set_param_named(s, st, "stiffness", 1.0) == DAL_E_ARG);
  CHECK(strstr(dal_state_errmsg(st), "unknown form"));
  CHECK(dal_state_set_param_named(s, st, "place:a:x", 1.0) == DAL_E_ARG);
  CHECK(dal_state_set_param_named(s, st, "place:a:1:2", 1.0) == DAL_E_ARG);
  // nothing changed: the system's values, the state's time and coordinates
  for (int k = 0; k < 3; ++k) {
    dal_param_ref r = {DAL_PARAM_MASS, k, 0};
    double v = 0;
    CHECK_OK(dal_state_param(s, st, &r, &v));
    CHECK(v == P0.m[k]);
  }
  dal_param_ref r = {DAL_PARAM_SPRING_K, 0, 0};
  double v = 0;
  CHECK_OK(dal_state_param(s, st, &r, &v));
  CHECK(v == P0.k);
  CHECK(dal_state_time(st) == 0.5 && dal_state_q(st)[2] == 0.3);
  // a state of another system
  dal_system *s2 = chain(&P0);
  CHECK(dal_state_set_mass(s2, st, 0, 1.0) == DAL_E_STATE);
  dal_system_destroy(s2);
  dal_state_destroy(st);
  dal_system_destroy(s);
}

int main(void) {
  test_chain();
  test_dae();
  test_validation();
  return check_summary("test_params");
}
