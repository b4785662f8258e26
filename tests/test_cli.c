// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The command line's analyses against independent references: the C route of the seed scenes
// (the models of examples/sicm_driven_pendulum.c, sicm_section.c, lyapunov.c, bead_ring.c,
// built from the library's primitives without any expression) and closed forms.
//
// 1. modes: the pendulum (driven_pendulum.scene with a = 0) at theta = 0: omega^2 = g/l; the
//    bead below the critical rate: Omega^2 = g/R - w^2 (closed forms).
// 2. equilibria: the bead above the critical rate has cos theta* = g/(R w^2), neutral, with
//    Omega^2 = w^2 sin^2 theta*, and the bottom unstable with omega^2 = g/R - w^2 < 0.
// 3. lyapunov: the driven pendulum over 40 s, RK4 at h = 2^-8 (lyapunov.c's check options),
//    equal to dal_lyapunov on the C route to 1e-6, and lambda_1 + lambda_2 = 0 to 1e-9.
// 4. section: the stroboscopic points (once per drive period) equal to dal_evolve with
//    dt = T on the C route to 1e-8 (sicm_section.c's section), and the surface section
//    (sin theta = 0 rising) equal to the C route's event log.
// 5. the two orbits of sicm_driven_pendulum (thetadot0 = 0 and 1e-10, --set): the time
//    they first differ by 0.1 rad equals the C route's to one output step.
// 6. sweep: the final states over omega equal the C route (dal_map_ring at each omega) to
//    1e-9, and 1 and 2 threads write the same bytes.
// 7. exit codes: the library's status (a bad --param: 1; no section line: 1), and the progress
//    line only on stderr.
// 8. manners: --help and --version exit 0, an option of another command is refused naming its
//    owners, unknown words and malformed values are named (exit 64).
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

#include "check.h"
#include "dalembert/dalembert.h"

#define PI 3.14159265358979323846
#define MAXROW 4096

static const double g = 9.8;

// the CLI's output: the numeric rows of its CSV (comment and header lines skipped; words that
// are not numbers read as NaN), and its exit status
typedef struct table {
  int nrow, ncol, status;
  double v[MAXROW][8];
} table;

static table tab;

static int cli(const char *args) {
  char cmd[2048];
  snprintf(cmd, sizeof cmd, "%s %s --no-progress", CLI, args);
  FILE *p = popen(cmd, "r");
  tab.nrow = tab.ncol = 0;
  if (!p) return -1;
  char line[4096];
  while (fgets(line, sizeof line, p)) {
    if (line[0] == '#' || !strchr("-0123456789", line[0]) || tab.nrow == MAXROW) continue;
    int c = 0;
    for (char *sv = NULL, *s = strtok_r(line, ",\n", &sv); s && c < 8;
         s = strtok_r(NULL, ",\n", &sv)) {
      char *end;
      double x = strtod(s, &end);
      tab.v[tab.nrow][c++] = end == s ? NAN : x;
    }
    tab.ncol = c;
    tab.nrow++;
  }
  int st = pclose(p);
  tab.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return tab.status;
}

// the C route: one particle on one coordinate placed by a built-in map (its parameters as a
// list), under gravity g
static dal_system *one_coordinate(const dal_primitive *prim, int dim, const double *param, int np,
                                  const double *grav) {
  dal_builder *b;
  dal_system *sys = NULL;
  int th, bob;
  dal_builder_create(dim, &b);
  dal_builder_add_coord(b, "theta", &th);
  dal_builder_add_particle(b, "bob", 1.0, &bob);
  dal_place_def d = dal_default_place_def();
  d.prim = prim;
  d.coords = &th;
  d.ncoords = 1;
  d.param_list = param;
  d.nparam_list = np;
  dal_builder_place_def(b, bob, &d);
  dal_builder_set_gravity(b, grav);
  CHECK_OK(dal_builder_compile(b, &sys));
  dal_builder_destroy(b);
  return sys;
}

// the driven pendulum: dal_map_pendulum (l, x0, y0, ax, ay, w, ph) with a moving pivot
static dal_system *pendulum(double a) {
  double param[7] = {1.0, 0, 0, 0, a, 2.0 * sqrt(g), 0}, grav[2] = {0, -g};
  return one_coordinate(&dal_map_pendulum, 2, param, 7, grav);
}

static void modes(void) {
  CHECK(cli("modes " SCENES "/driven_pendulum.scene --set a=0") == 0 && tab.nrow == 1);
  CHECK_CLOSE(tab.v[0][1], g / 1.0, 1e-13);
  CHECK_CLOSE(tab.v[0][2], sqrt(g), 1e-13);
  printf("modes of the pendulum: omega = %.15f, sqrt(g/l) = %.15f\n", tab.v[0][2], sqrt(g));
  CHECK(cli("modes " SCENES "/bead_ring_below.scene") == 0 && tab.nrow == 1);
  CHECK_CLOSE(tab.v[0][1], 9.81 - 4.0, 1e-13);
}

static void equilibria(void) {
  const double w = 5, ts = acos(9.81 / (w * w));
  CHECK(cli("equilibria " SCENES "/bead_ring_above.scene --scan theta=-1.5:1.5:7") == 0);
  int got = 0, bottom = 0;
  for (int i = 0; i < tab.nrow; ++i) {
    if (fabs(tab.v[i][0] - ts) < 1e-12) {
      got = 1;
      CHECK_CLOSE(tab.v[i][2], w * w * sin(ts) * sin(ts), 1e-12);
    }
    if (fabs(tab.v[i][0]) < 1e-12) {
      bottom = 1;
      CHECK_CLOSE(tab.v[i][2], 9.81 - w * w, 1e-12);
    }
  }
  CHECK_MSG(got && bottom, "theta* = %.15f or the bottom not among %d equilibria", ts, tab.nrow);
  printf("equilibria of the bead above: theta* = acos(g/(R w^2)) = %.15f found: %d\n", ts, got);
  // the pendulum from 15 starts over [-3.5, 3.5]: the bottom and the top, the top once although
  // Newton reaches it at theta = -pi and at +pi (the same point of the bob)
  CHECK(cli("equilibria " SCENES "/driven_pendulum.scene --set a=0 --scan theta=-3.5:3.5:15") == 0);
  int top = 0, low = 0;
  for (int i = 0; i < tab.nrow; ++i) {
    top += fabs(fabs(tab.v[i][0]) - acos(-1.0)) < 1e-12;
    low += fabs(tab.v[i][0]) < 1e-12;
  }
  CHECK_MSG(tab.nrow == 2 && top == 1 && low == 1,
            "the pendulum: %d equilibria (top %d, bottom %d), expected the bottom and the top once",
            tab.nrow, top, low);
}

static void lyapunov(void) {
  CHECK(cli("lyapunov " SCENES "/driven_pendulum.scene --t1 40 --method rk4 --h 0.00390625") == 0 &&
        tab.nrow == 2);
  dal_system *sys = pendulum(0.1);
  dal_state *st;
  double q = 1, v = 0, ex[2], er[2];
  dal_state_create(sys, &st);
  dal_state_set(sys, st, 0, &q, &v);
  dal_lyapunov_opts o = dal_default_lyapunov_opts();
  o.t_end = 40;
  o.method = DAL_METHOD_RK4;
  o.h = ldexp(1.0, -8);
  CHECK_OK(dal_lyapunov(sys, st, &o, ex, er, NULL, NULL));
  printf("lyapunov over 40 s: CLI %.12f %.12f, C route %.12f %.12f (+- %.3f)\n", tab.v[0][1],
         tab.v[1][1], ex[0], ex[1], er[0]);
  CHECK(fabs(tab.v[0][1] - ex[0]) <= 1e-6 * fabs(ex[0]));
  CHECK(fabs(tab.v[1][1] - ex[1]) <= 1e-6 * fabs(ex[1]));
  CHECK(fabs(tab.v[0][1] + tab.v[1][1]) <= 1e-9);
  CHECK(fabs(tab.v[0][2] - er[0]) <= 1e-3 * er[0]);
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

// the C route's stroboscopic points (t, theta, thetadot) into rows of `ref`
typedef struct strobe {
  int n;
  double ref[64][3];
} strobe;

static int record(const dal_system *sys, const dal_state *st, void *ctx) {
  (void)sys;
  strobe *s = ctx;
  if (s->n < 64) {
    s->ref[s->n][0] = dal_state_time(st);
    s->ref[s->n][1] = dal_state_q(st)[0];
    s->ref[s->n][2] = dal_state_qdot(st)[0];
    s->n++;
  }
  return 0;
}

static void sections(void) {
  const double T = 2 * PI / (2 * sqrt(g));
  CHECK(cli("section " SCENES "/driven_pendulum.scene") == 0);
  CHECK(tab.nrow > 90 && tab.ncol == 5);
  dal_system *sys = pendulum(0.1);
  dal_state *st;
  double q = 1, v = 0, worst = 0;
  dal_state_create(sys, &st);
  dal_state_set(sys, st, 0, &q, &v);
  dal_solve_opts so = dal_default_solve_opts();
  so.method = DAL_METHOD_BS;
  so.rtol = 1e-12;
  strobe s = {0};
  CHECK_OK(dal_evolve(sys, st, &so, 30 * T, T, record, &s));
  for (int i = 0; i < s.n && i < tab.nrow; ++i) {
    CHECK_CLOSE(tab.v[i][0], s.ref[i][0], 1e-13);
    for (int k = 1; k < 3; ++k)
      worst = fmax(worst, fabs(tab.v[i][k] - s.ref[i][k]) / (1 + fabs(s.ref[i][k])));
  }
  printf("stroboscopic section: %d points against the C route, largest difference %.2e\n", s.n,
         worst);
  CHECK(s.n == 31 && worst < 1e-8);
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

// g = sin(theta) for the C route's surface section
static double sin_theta(double t, const double *q, const double *qdot, void *ctx) {
  (void)t, (void)qdot, (void)ctx;
  return sin(q[0]);
}

static void surface(void) {
  CHECK(cli("section " SCENES "/driven_pendulum.scene --surface") == 0 && tab.nrow > 5);
  dal_system *sys = pendulum(0.1);
  dal_state *st;
  dal_events *ev;
  double q = 1, v = 0, worst = 0;
  dal_state_create(sys, &st);
  dal_state_set(sys, st, 0, &q, &v);
  dal_events_create(sys, &ev);
  dal_event_def d = dal_default_event_def();
  d.g = sin_theta;
  d.direction = DAL_EVENT_RISING;
  dal_events_add(ev, &d);
  dal_state_set_events(st, ev);
  dal_solve_opts so = dal_default_solve_opts();
  so.method = DAL_METHOD_BS;
  so.rtol = 1e-12;
  CHECK_OK(dal_advance(sys, st, &so, 20.0));
  long n = dal_events_count(ev);
  for (long i = 0; i < n && i < tab.nrow; ++i) {
    dal_event_record r;
    double qe, ve;
    dal_events_get(ev, i, &r, &qe, &ve);
    worst = fmax(worst, fabs(tab.v[i][0] - r.t) + fabs(tab.v[i][3] - ve));
  }
  printf("surface section: %ld crossings to t = 20 against the C route, largest difference "
         "%.2e\n",
         n, worst);
  CHECK(n > 3 && worst < 1e-8);
  dal_state_set_events(st, NULL);
  dal_events_destroy(ev);
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

// the first output time at which the CLI's two runs differ by more than 0.1 rad
static double separation_cli(void) {
  static double a[12000];
  int na = 0;
  FILE *f;
  char line[512];
  cli("run " SCENES "/driven_pendulum.scene -o cli_orbit0.csv");
  cli("run " SCENES "/driven_pendulum.scene -o cli_orbit1.csv --set thetadot0=1e-10");
  if ((f = fopen("cli_orbit0.csv", "r"))) {
    while (fgets(line, sizeof line, f) && na < 12000)
      if (line[0] != 't') sscanf(line, "%*f,%lf", &a[na++]);
    fclose(f);
  }
  if (!(f = fopen("cli_orbit1.csv", "r"))) return NAN;
  double t = NAN, th;
  int k = 0;
  while (fgets(line, sizeof line, f) && k < na) {
    double tt;
    if (line[0] == 't' || sscanf(line, "%lf,%lf", &tt, &th) != 2) continue;
    if (fabs(th - a[k++]) > 0.1) {
      t = tt;
      break;
    }
  }
  fclose(f);
  return t;
}

typedef struct orbit {
  double th[12000];
  int n;
} orbit;

static int keep(const dal_system *sys, const dal_state *st, void *ctx) {
  (void)sys;
  orbit *o = ctx;
  if (o->n < 12000) o->th[o->n++] = dal_state_q(st)[0];
  return 0;
}

static void two_orbits(void) {
  dal_system *sys = pendulum(0.1);
  dal_state *st;
  static orbit o[2];
  dal_solve_opts so = dal_default_solve_opts();
  so.method = DAL_METHOD_BS;
  so.rtol = 1e-12;
  dal_state_create(sys, &st);
  for (int k = 0; k < 2; ++k) {
    double q = 1, v = k ? 1e-10 : 0;
    dal_state_set(sys, st, 0, &q, &v);
    CHECK_OK(dal_evolve(sys, st, &so, 100.0, 0.01, keep, &o[k]));
  }
  double tc = NAN;
  for (int i = 0; i < o[0].n && i < o[1].n; ++i)
    if (fabs(o[0].th[i] - o[1].th[i]) > 0.1) {
      tc = 0.01 * i;
      break;
    }
  double t = separation_cli();
  printf("two orbits 1e-10 apart separate by 0.1 rad at t = %.2f (CLI), %.2f (C route)\n", t, tc);
  CHECK(fabs(t - tc) <= 0.0100001);
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

static void sweep(void) {
  CHECK(cli("sweep " SCENES "/bead_ring_below.scene --param omega=1:3:3 --threads 2 -o "
            "cli_sweep2.csv") == 0);
  CHECK(cli("sweep " SCENES "/bead_ring_below.scene --param omega=1:3:3 --threads 1") == 0 &&
        tab.nrow == 3);
  for (int i = 0; i < 3; ++i) {
    double w = 1 + i, param[3] = {1, w, 0}, gv[3] = {0, 0, -9.81}, q = 0.5, v = 0;
    dal_system *sys = one_coordinate(&dal_map_ring, 3, param, 3, gv);
    dal_state *st;
    dal_state_create(sys, &st);
    dal_state_set(sys, st, 0, &q, &v);
    dal_solve_opts so = dal_default_solve_opts();
    so.method = DAL_METHOD_BS;
    so.rtol = 1e-11;
    CHECK_OK(dal_advance(sys, st, &so, 20.0));
    CHECK_CLOSE(tab.v[i][1], w, 0);
    CHECK_CLOSE(tab.v[i][3], dal_state_q(st)[0], 1e-9);
    CHECK_CLOSE(tab.v[i][4], dal_state_qdot(st)[0], 1e-9);
    dal_state_destroy(st);
    dal_system_destroy(sys);
  }
  // threads change nothing: the same bytes
  char cmd[1024];
  snprintf(cmd, sizeof cmd,
           "%s sweep %s/bead_ring_below.scene --param omega=1:3:3 --no-progress | cmp -s - "
           "cli_sweep2.csv",
           CLI, SCENES);
  CHECK(system(cmd) == 0);
}

// the progress line: on stderr with --progress (its last state the end time), never on stdout,
// and none when CI is set
static void progress(void) {
  char cmd[1024];
  snprintf(cmd, sizeof cmd,
           "%s run %s/bead_ring_below.scene --progress 2>&1 >/dev/null | tr '\\r' '\\n' | "
           "grep -q 'run: t: 20 / 20'",
           CLI, SCENES);
  CHECK(system(cmd) == 0);
  snprintf(cmd, sizeof cmd,
           "CI=1 %s run %s/bead_ring_below.scene 2>&1 >/dev/null | grep -q t:", CLI, SCENES);
  CHECK(system(cmd) != 0);
  snprintf(cmd, sizeof cmd,
           "%s run %s/bead_ring_below.scene --progress 2>/dev/null | grep -q 'run: t'", CLI,
           SCENES);
  CHECK(system(cmd) != 0);
}

// the CLI's stdout and stderr together in out (its exit status returned)
static char said[8192];
static int cli_said(const char *args) {
  char cmd[2048];
  snprintf(cmd, sizeof cmd, "%s %s 2>&1", CLI, args);
  FILE *p = popen(cmd, "r");
  if (!p) return -1;
  size_t n = fread(said, 1, sizeof said - 1, p);
  said[n] = 0;
  int st = pclose(p);
  return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

// status and the words the message must hold
static void says(const char *args, int status, const char *w1, const char *w2) {
  int st = cli_said(args);
  CHECK_MSG(st == status && strstr(said, w1) && (!w2 || strstr(said, w2)),
            "dalembert %s: exit %d (want %d), said: %s", args, st, status, said);
}

// the command line's manners: options parsed per command from its table (getopt_long), an
// option of another command refused naming its owners, unknown words named, --help exit 0
static void manners(void) {
  const char *dp = SCENES "/driven_pendulum.scene";
  char a[1024];
  says("--version", 0, "dalembert 0.", NULL);
  char v[64];
  snprintf(v, sizeof v, "dalembert %d.%d.%d\n", DAL_VERSION_MAJOR, DAL_VERSION_MINOR,
           DAL_VERSION_PATCH);
  CHECK(!strcmp(said, v));
  says("--help", 0, "commands:", "exit status:");
  CHECK(strstr(said, "  lyapunov ") && strstr(said, "  130 "));
  says("-h", 0, "commands:", NULL);
  says("", 64, "no command", NULL);
  says("frob x.scene", 64, "unknown command 'frob'", NULL);
  snprintf(a, sizeof a, "run %s --help", dp);
  says(a, 0, "usage: dalembert run SCENE", "--t1 T");
  says("lyapunov -h", 0, "--transient T", "--renorm T");
  snprintf(a, sizeof a, "run %s --bogus", dp);
  says(a, 64, "dalembert run: unknown option '--bogus'", NULL);
  snprintf(a, sizeof a, "modes %s --t1 5", dp);
  says(a, 64, "--t1 is an option of run, lyapunov, section, not of modes", NULL);
  snprintf(a, sizeof a, "modes %s -o x.csv", dp);
  says(a, 64, "-o is an option of run, section, sweep, not of modes", NULL);
  snprintf(a, sizeof a, "lyapunov %s --t1 -5", dp);
  says(a, 64, "--t1 -5: a number > 0", NULL);
  snprintf(a, sizeof a, "lyapunov %s --t1", dp);
  says(a, 64, "--t1 needs a value T", NULL);
  snprintf(a, sizeof a, "lyapunov %s --t 5", dp);
  says(a, 64, "'--t' is short for more than one", NULL);
  snprintf(a, sizeof a, "run %s stray", dp);
  says(a, 64, "unexpected word 'stray'", NULL);
  snprintf(a, sizeof a, "run %s --wrap=1", dp);
  says(a, 64, "--wrap takes no value", NULL);
  says("run", 64, "dalembert run: needs SCENE", NULL);
  snprintf(a, sizeof a, "sweep %s --param a=0:1:2 --threads 2.5", dp);
  says(a, 64, "--threads 2.5: an integer from 0 to 1024", NULL);
  snprintf(a, sizeof a, "show %s --latex --scheme", dp);
  says(a, 64, "one of --text, --latex, --scheme", NULL);
  snprintf(a, sizeof a, "run %s --set a", dp);
  says(a, 64, "--set 'a' is not NAME=VALUE", NULL);
  snprintf(a, sizeof a, "run %s --set nope=1", dp);
  says(a, 1, "no parameter 'nope'", NULL);
}

static void exit_codes(void) {
  CHECK(cli("sweep " SCENES "/bead_ring_below.scene --param nope=0:1:2 2>/dev/null") == 1);
  CHECK(cli("section " SCENES "/bead_ring_below.scene 2>/dev/null") == 1);
  CHECK(cli("lyapunov " SCENES "/driven_pendulum.scene --method rattle 2>/dev/null") == 15);
  CHECK(cli("modes " SCENES "/driven_pendulum.scene --bogus 2>/dev/null") == 64);
}

int main(void) {
  modes();
  equilibria();
  lyapunov();
  sections();
  surface();
  two_orbits();
  sweep();
  progress();
  exit_codes();
  manners();
  return check_summary("test_cli");
}
