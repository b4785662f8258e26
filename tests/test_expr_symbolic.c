// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Equations shown: symbolic derivatives, simplification and Lagrange's equations, each checked
// against an independent numeric counterpart.
//
// 1. SICM's printed state derivative of the periodically driven pendulum (Sussman & Wisdom,
//    sec. 1.7), `(up 1 thetadot (/ (+ (* a (expt omega 2) (cos (* omega t)) (sin theta)) (* -1
//    g (sin theta))) l))`, read by a small S-expression reader in this file, and the
//    acceleration the library derives from the model's position formulas agree at 200 random
//    points (t, theta, thetadot, a, omega, g, l) to 1e-13; so does the library's numeric
//    acceleration (dal_forward on dal_map_pendulum with a moving pivot).
// 2. The bead on the turning ring (Likharev): the derived acceleration equals the closed form
//    omega^2 sin(theta) cos(theta) - (g/R) sin(theta); the double pendulum: the derived mass
//    matrix and forces equal dal_state_mass_matrix and M qddot from dal_forward.
// 3. dal_expr_derivative against the jets' first derivative (an independent route: forward
//    mode over the compiled program) for formulas using every function, along every input and
//    t, at random points.
// 4. Simplification identities written by hand (x + x = 2 x, sin^2 + cos^2 = 1, (a + b)^2 -
//    a^2 - b^2 = 2 a b, ...), and every printed text read back gives the same values.
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "dalembert/dalembert.h"
#include "scenes.h"

static unsigned long long seed = 0x9e3779b97f4a7c15ULL;
static double rnd(double lo, double hi) { return check_rand(&seed, lo, hi); }

// ---------------------------------------------------------------------------------------------
// a small reader of SICM's prefix notation into infix text: (op args...), names, numbers

static const char *sx_read(const char *s, char *out, size_t *k, size_t cap);

static void emit(char *out, size_t *k, size_t cap, const char *txt) {
  size_t n = strlen(txt);
  if (*k + n + 1 < cap) {
    memcpy(out + *k, txt, n + 1);
    *k += n;
  }
}

static const char *sx_read(const char *s, char *out, size_t *k, size_t cap) {
  while (isspace((unsigned char)*s))
    s++;
  if (*s != '(') {
    // an atom
    char atom[64];
    size_t n = 0;
    while (*s && !isspace((unsigned char)*s) && *s != '(' && *s != ')' && n < 63)
      atom[n++] = *s++;
    atom[n] = 0;
    emit(out, k, cap, "(");
    emit(out, k, cap, atom);
    emit(out, k, cap, ")");
    return s;
  }
  s++;
  while (isspace((unsigned char)*s))
    s++;
  char op[32];
  size_t n = 0;
  while (*s && !isspace((unsigned char)*s) && n < 31)
    op[n++] = *s++;
  op[n] = 0;
  const char *sep = !strcmp(op, "+")      ? "+"
                    : !strcmp(op, "*")    ? "*"
                    : !strcmp(op, "/")    ? "/"
                    : !strcmp(op, "-")    ? "-"
                    : !strcmp(op, "expt") ? "^"
                                          : ",";
  int call = !strcmp(sep, ",");
  if (call) {
    emit(out, k, cap, op);
  }
  emit(out, k, cap, "(");
  int first = 1;
  while (1) {
    while (isspace((unsigned char)*s))
      s++;
    if (*s == ')' || !*s) break;
    if (!first) emit(out, k, cap, sep);
    first = 0;
    s = sx_read(s, out, k, cap);
  }
  emit(out, k, cap, ")");
  return *s ? s + 1 : s;
}

static const char *sicm_driven =
    "(up 1 thetadot (/ (+ (* a (expt omega 2) (cos (* omega t)) (sin theta)) (* -1 g (sin "
    "theta))) l))";

static dal_expr *make(const char *name, const char *f, int nin, const char *const *in, int vel,
                      int np, const char *const *pn, const double *pv) {
  dal_expr_def d = dal_default_expr_def();
  d.name = name;
  d.formulas = &f;
  d.nout = 1;
  d.inputs = in;
  d.nin = nin;
  d.velocities = vel;
  d.params = pn;
  d.values = pv;
  d.nparam = np;
  dal_expr *e = NULL;
  char msg[512];
  int rc = dal_expr_create(&d, &e, msg, sizeof msg);
  CHECK_MSG(rc == 0, "%s: %s", f, msg);
  return e;
}

static void driven_pendulum(void) {
  const char *coords[] = {"theta"}, *masses[] = {"m"};
  const char *pos[] = {"l*sin(theta)", "a*cos(omega*t) - l*cos(theta)"};
  const char *grav[] = {"0", "-g"};
  const char *par[] = {"m", "l", "a", "omega", "g"};
  double val[] = {1, 1, 0.1, 2 * sqrt(9.8), 9.8};
  dal_expr_model_def d = dal_default_expr_model_def();
  d.name = "driven";
  d.dim = 2;
  d.coords = coords;
  d.ncoords = 1;
  d.masses = masses;
  d.nparticles = 1;
  d.positions = pos;
  d.gravity = grav;
  d.params = par;
  d.values = val;
  d.nparam = 5;
  dal_expr *L;
  char msg[512];
  CHECK_OK(dal_expr_model_energies(&d, NULL, NULL, &L, msg, sizeof msg));
  dal_expr_equations eq;
  CHECK_OK(dal_expr_lagrange(L, &eq, msg, sizeof msg));
  CHECK(eq.n == 1 && eq.accel && eq.mass && eq.force && eq.momentum);
  // SICM's state derivative (up 1 thetadot X): its third component read into infix
  const char *third = strstr(sicm_driven, "(/");
  char infix[1024];
  size_t k = 0;
  infix[0] = 0;
  sx_read(third, infix, &k, sizeof infix);
  dal_expr *sicm = make("sicm", infix, 1, coords, 1, 5, par, val);
  char text[1024], scheme[1024];
  dal_expr_print(eq.accel, 0, DAL_EXPR_TEXT, text, sizeof text);
  dal_expr_print(eq.accel, 0, DAL_EXPR_SCHEME, scheme, sizeof scheme);
  printf("SICM:     %s\n  read as %s\nlibrary:  %s\n          %s\n", sicm_driven, infix, text,
         scheme);
  // the numeric route: dal_map_pendulum with a vertically moving pivot
  double worst = 0, worst_num = 0;
  for (int s = 0; s < 200 && sicm; ++s) {
    double p[5] = {rnd(0.5, 2), rnd(0.5, 2), rnd(-0.5, 0.5), rnd(1, 8), rnd(1, 20)};
    double t = rnd(-10, 10), th = rnd(-3, 3), thd = rnd(-3, 3);
    dal_jet in[2] = {dal_const(th), dal_const(thd)}, A, B;
    CHECK_OK(dal_expr_eval(eq.accel, in, dal_const(t), p, &A));
    CHECK_OK(dal_expr_eval(sicm, in, dal_const(t), p, &B));
    double scale = 1 + p[2] * p[3] * p[3] / p[1] + p[4] / p[1];
    double r = fabs(A.v - B.v) / scale;
    if (r > worst) worst = r;
    if (s < 20) {
      scn_knobs kn = scn_default(); // the scene library's pendulum, its pivot driven along y
      kn.m = p[0];
      kn.l = p[1];
      kn.ay = p[2];
      kn.w = p[3];
      kn.g = p[4];
      dal_system *sys = scn_pendulum(&kn);
      CHECK(sys != NULL);
      dal_state *st;
      dal_state_create(sys, &st);
      dal_state_set(sys, st, t, &th, &thd);
      CHECK_OK(dal_forward(sys, st));
      double rn = fabs(dal_state_qddot(st)[0] - A.v) / scale;
      if (rn > worst_num) worst_num = rn;
      dal_state_destroy(st);
      dal_system_destroy(sys);
    }
  }
  printf("driven pendulum: |library - SICM| / scale <= %.3g over 200 points, |symbolic - "
         "dal_forward| <= %.3g over 20\n",
         worst, worst_num);
  CHECK(worst < 4e-14);
  CHECK(worst_num < 1e-13);
  // the mass: M = m l^2 exactly
  dal_jet in[2] = {dal_const(0.3), dal_const(0.1)}, M;
  dal_expr_eval(eq.mass, in, dal_const(0), val, &M);
  CHECK_CLOSE(M.v, val[0] * val[1] * val[1], 1e-15);
  dal_expr_destroy(sicm);
  dal_expr_equations_destroy(&eq);
  dal_expr_destroy(L);
}

static void ring_and_double_pendulum(void) {
  // the bead on the ring turning at omega about the vertical: closed form of the acceleration
  const char *coords[] = {"theta"}, *masses[] = {"m"};
  const char *pos[] = {"R*sin(theta)*cos(omega*t)", "R*sin(theta)*sin(omega*t)", "-R*cos(theta)"};
  const char *grav[] = {"0", "0", "-g"};
  const char *par[] = {"m", "R", "omega", "g"};
  double val[] = {0.3, 0.5, 5.0, 9.81};
  dal_expr_model_def d = dal_default_expr_model_def();
  d.name = "bead";
  d.dim = 3;
  d.coords = coords;
  d.ncoords = 1;
  d.masses = masses;
  d.nparticles = 1;
  d.positions = pos;
  d.gravity = grav;
  d.params = par;
  d.values = val;
  d.nparam = 4;
  dal_expr *L;
  char msg[512], text[1024];
  CHECK_OK(dal_expr_model_energies(&d, NULL, NULL, &L, msg, sizeof msg));
  dal_expr_equations eq;
  CHECK_OK(dal_expr_lagrange(L, &eq, msg, sizeof msg));
  dal_expr_print(eq.accel, 0, DAL_EXPR_TEXT, text, sizeof text);
  printf("bead on the ring: thetaddot = %s\n", text);
  for (int s = 0; s < 50; ++s) {
    double p[4] = {rnd(0.1, 2), rnd(0.2, 2), rnd(0, 10), rnd(1, 20)};
    double th = rnd(-3, 3), thd = rnd(-5, 5), t = rnd(0, 10);
    dal_jet in[2] = {dal_const(th), dal_const(thd)}, A;
    dal_expr_eval(eq.accel, in, dal_const(t), p, &A);
    double ref = p[2] * p[2] * sin(th) * cos(th) - p[3] / p[1] * sin(th);
    CHECK_CLOSE(A.v, ref, 1e-13 * (1 + p[2] * p[2] + p[3] / p[1]));
  }
  dal_expr_equations_destroy(&eq);
  dal_expr_destroy(L);

  // the double pendulum: M and F against the numeric route
  const char *c2[] = {"th1", "th2"}, *m2[] = {"m1", "m2"};
  const char *p2[] = {"l1*sin(th1)", "-l1*cos(th1)", "l1*sin(th1) + l2*sin(th2)",
                      "-l1*cos(th1) - l2*cos(th2)"};
  const char *g2[] = {"0", "-g"};
  const char *n2[] = {"m1", "m2", "l1", "l2", "g"};
  double v2[] = {1.3, 0.7, 1.1, 0.8, 9.81};
  d = dal_default_expr_model_def();
  d.name = "double";
  d.dim = 2;
  d.coords = c2;
  d.ncoords = 2;
  d.masses = m2;
  d.nparticles = 2;
  d.positions = p2;
  d.gravity = g2;
  d.params = n2;
  d.values = v2;
  d.nparam = 5;
  CHECK_OK(dal_expr_model_energies(&d, NULL, NULL, &L, msg, sizeof msg));
  CHECK_OK(dal_expr_lagrange(L, &eq, msg, sizeof msg));
  CHECK(eq.accel == NULL && eq.n == 2);
  for (int i = 0; i < 4; ++i) {
    dal_expr_print(eq.mass, i, DAL_EXPR_TEXT, text, sizeof text);
    printf("double pendulum M%d%d = %s\n", i / 2 + 1, i % 2 + 1, text);
  }
  for (int i = 0; i < 2; ++i) {
    dal_expr_print(eq.force, i, DAL_EXPR_TEXT, text, sizeof text);
    printf("double pendulum F%d = %s\n", i + 1, text);
  }
  dal_builder *b;
  dal_system *sys;
  int q[2], k1, k2;
  dal_builder_create(2, &b);
  dal_builder_add_coord(b, "th1", &q[0]);
  dal_builder_add_coord(b, "th2", &q[1]);
  dal_builder_add_particle(b, "a", v2[0], &k1);
  dal_builder_add_particle(b, "b", v2[1], &k2);
  dal_place_def pd = dal_default_place_def();
  pd.prim = &dal_map_pendulum;
  pd.coords = &q[0];
  pd.ncoords = 1;
  pd.param[DAL_PENDULUM_L] = v2[2];
  dal_builder_place_def(b, k1, &pd);
  pd = dal_default_place_def();
  pd.prim = &dal_map_hanging;
  pd.parent = k1;
  pd.coords = &q[1];
  pd.ncoords = 1;
  pd.param[DAL_HANGING_L] = v2[3];
  dal_builder_place_def(b, k2, &pd);
  double gv[2] = {0, -v2[4]};
  dal_builder_set_gravity(b, gv);
  CHECK_OK(dal_builder_set_dynamics(b, DAL_DYNAMICS_DENSE));
  CHECK_OK(dal_builder_compile(b, &sys));
  dal_builder_destroy(b);
  dal_state *st;
  dal_state_create(sys, &st);
  for (int s = 0; s < 20; ++s) {
    double qv[2] = {rnd(-3, 3), rnd(-3, 3)}, qd[2] = {rnd(-3, 3), rnd(-3, 3)};
    dal_state_set(sys, st, 0, qv, qd);
    CHECK_OK(dal_forward(sys, st));
    const double *Mn = dal_state_mass_matrix(st), *acc = dal_state_qddot(st);
    dal_jet in[4] = {dal_const(qv[0]), dal_const(qv[1]), dal_const(qd[0]), dal_const(qd[1])};
    dal_jet M[4], F[2];
    dal_expr_eval(eq.mass, in, dal_const(0), NULL, M);
    dal_expr_eval(eq.force, in, dal_const(0), NULL, F);
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j)
        CHECK_CLOSE(M[i * 2 + j].v, Mn[j * 2 + i], 1e-14);
    for (int i = 0; i < 2; ++i)
      CHECK_CLOSE(M[i * 2].v * acc[0] + M[i * 2 + 1].v * acc[1], F[i].v, 1e-12);
  }
  dal_state_destroy(st);
  dal_system_destroy(sys);
  dal_expr_equations_destroy(&eq);
  dal_expr_destroy(L);
}

// ---------------------------------------------------------------------------------------------
// derivatives against jets, identities, and printed text read back

static void derivatives(void) {
  static const char *const f[] = {
      "x*sin(y) + cos(x*y)^2 - tan(y/3)",
      "exp(-x^2/2)*log(1 + y^2) + sqrt(x^2 + y^2 + 1)",
      "asin(x/3) + acos(y/4) + atan(x*y)",
      "sinh(x) - cosh(y)*tanh(x - y) + x^y",
      "atan2(y, x + 3) + hypot(x, y)*t + a*x^3/(1 + y^2)",
      "(x + y*t)^(5/2) / (2 + x)^-2",
  };
  const char *in[] = {"x", "y"}, *pn[] = {"a"};
  double pv[] = {1.7};
  for (size_t i = 0; i < sizeof f / sizeof f[0]; ++i) {
    dal_expr *e = make("f", f[i], 2, in, 0, 1, pn, pv);
    if (!e) continue;
    for (int j = -1; j < 2; ++j) {
      dal_expr *de;
      char msg[256];
      CHECK_OK(dal_expr_derivative(e, 0, j, &de, msg, sizeof msg));
      if (!de) continue;
      for (int s = 0; s < 30; ++s) {
        double x = rnd(0.2, 1.2), y = rnd(0.2, 1.2), t = rnd(0.1, 1);
        dal_jet jin[2] = {dal_var(x, j == 0), dal_var(y, j == 1)}, out, dout;
        dal_expr_eval(e, jin, dal_var(t, j == -1), NULL, &out);
        dal_jet cin[2] = {dal_const(x), dal_const(y)};
        dal_expr_eval(de, cin, dal_const(t), NULL, &dout);
        CHECK_MSG(fabs(dout.v - out.d) <= 1e-12 * (1 + fabs(out.d)),
                  "d(%s)/d%s at (%g, %g, %g): symbolic %.17g, jet %.17g", f[i], j < 0 ? "t" : in[j],
                  x, y, t, dout.v, out.d);
      }
      dal_expr_destroy(de);
    }
    // the printed text, read back, has the same values
    char text[2048];
    int n = dal_expr_print(e, 0, DAL_EXPR_TEXT, text, sizeof text);
    CHECK(n > 0 && n < (int)sizeof text);
    dal_expr *back = make("back", text, 2, in, 0, 1, pn, pv);
    for (int s = 0; s < 10 && back; ++s) {
      dal_jet jin[2] = {dal_const(rnd(0.2, 1.2)), dal_const(rnd(0.2, 1.2))}, o1, o2;
      dal_expr_eval(e, jin, dal_const(0.5), NULL, &o1);
      dal_expr_eval(back, jin, dal_const(0.5), NULL, &o2);
      CHECK_MSG(fabs(o1.v - o2.v) <= 1e-13 * (1 + fabs(o1.v)), "'%s' printed as '%s'", f[i], text);
    }
    dal_expr_destroy(back);
    dal_expr_destroy(e);
  }
}

static void identity(const char *f, const char *want) {
  const char *in[] = {"x", "y", "a", "b", "u"};
  dal_expr *e = make("id", f, 5, in, 0, 0, NULL, NULL);
  char text[512] = "";
  if (e) dal_expr_print(e, 0, DAL_EXPR_TEXT, text, sizeof text);
  CHECK_MSG(!strcmp(text, want), "'%s' printed as '%s', expected '%s'", f, text, want);
  dal_expr_destroy(e);
}

static void identities(void) {
  identity("x + x", "2*x");
  identity("x*x*x/x", "x^2");
  identity("0*x + 1*y - 0", "y");
  identity("sin(u)^2 + cos(u)^2", "1");
  identity("a*x*sin(u)^2 + x*a*cos(u)^2", "a*x");
  identity("(a + b)^2 - a^2 - b^2", "2*a*b");
  identity("(x - y)*(x + y)", "x^2 - y^2");
  identity("2*3 + x^0 + 4/8", "15/2");
  identity("a*x + a*y", "a*(x + y)");
  identity("-a*x - a*y", "-a*(x + y)");
  identity("x/2 + 3*y/4", "1/4*(2*x + 3*y)");
  identity("sqrt(x)^2", "x");
  identity("sin(-x) + cos(-x)", "cos(x) - sin(x)");
  identity("exp(0) + log(1) + sin(0)", "1");
  identity("x/(a*b)", "x/(a*b)");
  identity("1/sqrt(x)", "1/sqrt(x)");
  // LaTeX and SICM forms of one formula
  const char *in[] = {"theta"}, *pn[] = {"m", "l"};
  double pv[] = {1, 1};
  dal_expr *e = make("T", "1/2*m*(thetadot*l)^2", 1, in, 1, 2, pn, pv);
  char text[256];
  dal_expr_print(e, 0, DAL_EXPR_LATEX, text, sizeof text);
  CHECK_MSG(!strcmp(text, "\\frac{1}{2} l^{2} m \\dot{\\theta}^{2}"), "%s", text);
  dal_expr_print(e, 0, DAL_EXPR_SCHEME, text, sizeof text);
  CHECK_MSG(!strcmp(text, "(* 1/2 (expt l 2) m (expt thetadot 2))"), "%s", text);
  // truncation: the full length is returned
  int n = dal_expr_print(e, 0, DAL_EXPR_TEXT, text, 5);
  CHECK(n == (int)strlen("1/2*l^2*m*thetadot^2") && strlen(text) == 4);
  CHECK(dal_expr_print(e, 1, DAL_EXPR_TEXT, text, sizeof text) == DAL_E_ARG);
  dal_expr_destroy(e);
}

int main(void) {
  driven_pendulum();
  ring_and_double_pendulum();
  derivatives();
  identities();
  return check_summary("test_expr_symbolic");
}
