// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// docs/expressions.md's program: SICM's driven pendulum from formulas, run and shown.
#include <dalembert/dalembert.h>
#include <math.h>
#include <stdio.h>

int main(void) {
  const char *coords[] = {"theta"}, *masses[] = {"m"}, *gravity[] = {"0", "-g"};
  const char *r[] = {"l*sin(theta)", "a*cos(omega*t) - l*cos(theta)"};
  const char *names[] = {"m", "l", "a", "omega", "g"};
  double values[] = {1.0, 1.0, 0.1, 2 * sqrt(9.8), 9.8};
  char msg[512], text[512];

  /* the bob's position r(theta, t) as a primitive with named parameters */
  dal_expr_def d = dal_default_expr_def();
  d.name = "bob";
  d.formulas = r;
  d.nout = 2;
  d.inputs = coords;
  d.nin = 1;
  d.params = names;
  d.values = values;
  d.nparam = 5;
  dal_expr *place;
  if (dal_expr_create(&d, &place, msg, sizeof msg)) {
    puts(msg);
    return 1;
  }
  dal_builder *b;
  dal_system *sys;
  int th, bob;
  dal_builder_create(2, &b);
  dal_builder_add_coord(b, "theta", &th);
  dal_builder_add_particle(b, "bob", values[0], &bob);
  dal_place_def pd = dal_default_place_def();
  dal_expr_place_def(place, &pd); /* prim and ctx: the expression */
  pd.coords = &th;
  pd.ncoords = 1;
  dal_builder_place_def(b, bob, &pd);
  double g[2] = {0, -values[4]};
  dal_builder_set_gravity(b, g);
  if (dal_builder_compile(b, &sys)) {
    puts(dal_builder_errmsg(b));
    return 1;
  }

  /* the same formulas as equations: T, U, L, then Lagrange's equations */
  dal_expr_model_def md = dal_default_expr_model_def();
  md.dim = 2;
  md.coords = coords;
  md.ncoords = 1;
  md.masses = masses;
  md.nparticles = 1;
  md.positions = r;
  md.gravity = gravity;
  md.params = names;
  md.values = values;
  md.nparam = 5;
  dal_expr *L;
  dal_expr_equations eq;
  if (dal_expr_model_energies(&md, NULL, NULL, &L, msg, sizeof msg) ||
      dal_expr_lagrange(L, &eq, msg, sizeof msg)) {
    puts(msg);
    return 1;
  }
  dal_expr_print(eq.accel, 0, DAL_EXPR_TEXT, text, sizeof text);
  printf("thetaddot = %s\n", text);
  dal_expr_print(eq.accel, 0, DAL_EXPR_SCHEME, text, sizeof text);
  printf("SICM form: (up 1 thetadot %s)\n", text);

  /* run to t = 10; the derived equation gives the library's acceleration there */
  dal_state *st;
  dal_state_create(sys, &st);
  double q = 1.0, qdot = 0.0;
  dal_state_set(sys, st, 0.0, &q, &qdot);
  dal_solve_opts o = dal_default_solve_opts();
  o.method = DAL_METHOD_BS;
  o.rtol = 1e-12;
  int rc = dal_advance(sys, st, &o, 10.0) || dal_forward(sys, st);
  dal_jet in[2] = {dal_const(dal_state_q(st)[0]), dal_const(dal_state_qdot(st)[0])}, acc;
  dal_expr_eval(eq.accel, in, dal_const(10.0), NULL, &acc);
  double diff = fabs(acc.v - dal_state_qddot(st)[0]);
  printf("theta(10) = %.12f, thetaddot: derived %.15f, library %.15f\n", dal_state_q(st)[0], acc.v,
         dal_state_qddot(st)[0]);
  dal_state_destroy(st);
  dal_expr_equations_destroy(&eq);
  dal_expr_destroy(L);
  dal_system_destroy(sys);
  dal_builder_destroy(b);
  dal_expr_destroy(place);
  return rc || diff > 1e-12;
}
