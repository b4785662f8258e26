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
// 9. regressions of the last audit: a moved start said on stderr, run --t1, writes to a full
//    device (exit 16), no file left by a failed run, sweep blaming the file's line, a grid too
//    large, lyapunov's atol (against the C route with atol = rtol), Ctrl-C (exit 130, whole
//    rows ending where stderr says).
#define _DEFAULT_SOURCE // glob, nanosleep
#include <glob.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

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

static void write_file(const char *path, const char *text) {
  FILE *f = fopen(path, "w");
  CHECK(f && fputs(text, f) >= 0 && fclose(f) == 0);
}

// the CLI's stdout and stderr together in out (its exit status returned)
static char said[8192];
static int cli_said(const char *args) {
  char cmd[2048];
  snprintf(cmd, sizeof cmd, "{ %s %s; } 2>&1", CLI, args);
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
  says(a, 64, "--t1 is an option of run, lyapunov, section, view, picture, not of modes", NULL);
  snprintf(a, sizeof a, "modes %s -o x.csv", dp);
  says(a, 64, "-o is an option of run, section, sweep, view, picture, compile, not of modes", NULL);
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
  // the culprit named: the scene file and its line, the option and its word
  write_file("cli_bad2.scene", "dim 2\ncoord th\nparticle b mass=1\nplace b = l*sin(th); 0\n");
  says("run cli_bad2.scene", 1, "cli_bad2.scene:4: place b:", "unknown symbol 'l'");
  says("run cli_missing.scene", 16, "cli_missing.scene: cannot open (No such file or directory)",
       NULL);
  snprintf(a, sizeof a, "run %s --chart x.png", dp);
  says(a, 64, "--chart needs -o FILE.csv", NULL);
  snprintf(a, sizeof a, "lyapunov %s --method nope", dp);
  says(a, 64, "--method: unknown method 'nope'", NULL);
  says("equilibria " SCENES "/bead_ring_above.scene --scan phi=0:1:2", 1,
       "bead_ring_above.scene has no coordinate 'phi'", NULL);
  says("equilibria " SCENES "/bead_ring_above.scene --scan theta=0:x:2", 64,
       "--scan 'theta=0:x:2' is not NAME=LO:HI:N", NULL);
  says("section " SCENES "/bead_ring_below.scene", 1, "bead_ring_below.scene has no section line",
       NULL);
  says("sweep " SCENES "/bead_ring_below.scene --param nope=0:1:2", 1,
       "bead_ring_below.scene has no parameter 'nope'", NULL);
  says("modes " SCENES "/bead_ring_below.scene --format xml", 64, "--format xml: one of csv|json",
       NULL);
  says("help frob", 64, "unknown command 'frob'", NULL);
  says("--frob", 64, "unknown option '--frob' before the command", NULL);
}

// the line of `file` that starts with `start` (0: none)
static int line_of(const char *file, const char *start) {
  FILE *f = fopen(file, "r");
  char line[1024];
  int k = 0, found = 0;
  while (f && !found && fgets(line, sizeof line, f))
    ++k, found = !strncmp(line, start, strlen(start));
  if (f) fclose(f);
  return found ? k : 0;
}

// defects of the command line found by the last audit, each with its reproducer
static void regressions(void) {
  char a[1024], w[512];
  // a start off its constraint is moved onto it: said on stderr, with the move (1.3 - 1) and
  // the residual (1.3^2 - 1), and the CSV starts on the circle
  write_file("cli_rod.scene", "dim 2\ncoord x q=0 v=0\ncoord y q=-1.3 v=0\nparticle b mass=1\n"
                              "place b = x; y\nconstraint rod parts=b = x_b^2 + y_b^2 - 1\n"
                              "gravity 0 -9.8\nrun t1=1 dt=0.1\n");
  says("run cli_rod.scene -o cli_rod.csv", 0, "moved coordinate 'y' by 0.3 ",
       "residual 0.69 on 'rod'");
  CHECK(cli("run cli_rod.scene --no-progress 2>/dev/null") == 0 && tab.nrow == 11);
  CHECK_CLOSE(tab.v[0][2], -1.0, 1e-12);
  // ... and in a sweep, in the trajectory's message (the start y0 = -1 needs no move)
  write_file("cli_rod2.scene", "dim 2\nparam y0 = -1.3\ncoord x q=0 v=0\ncoord y q=y0 v=0\n"
                               "particle b mass=1\nplace b = x; y\n"
                               "constraint rod parts=b = x_b^2 + y_b^2 - 1\n"
                               "gravity 0 -9.8\nrun t1=1 dt=0.1\n");
  says("sweep cli_rod2.scene --param y0=-1.3:-1:2", 0, "\n0,-1.3,DAL_OK,",
       "1 of 2 trajectories left a note");
  const char *note = strstr(said, "\"cli_rod2.scene: note: the consistent start at t=0 moved "
                                  "coordinate 'y' by 0.3 ");
  const char *first = strstr(said, "note: the consistent");
  CHECK(note && first && !strstr(first + 1, "note: the consistent") && strstr(said, ",\"\"\n"));
  // --t1 of run is honoured (the scene's t1 is 100)
  CHECK(cli("run " SCENES "/driven_pendulum.scene --t1 5") == 0 && tab.nrow == 501);
  CHECK_CLOSE(tab.v[tab.nrow - 1][0], 5.0, 0);
  // results that cannot be written: exit 16 and the reason, for stdout and for -o
  const char *full[] = {"modes " SCENES "/bead_ring_below.scene",
                        "run " SCENES "/bead_ring_below.scene",
                        "section " SCENES "/driven_pendulum.scene --format json", "--help"};
  for (int k = 0; k < 4; ++k) {
    snprintf(a, sizeof a, "%s >/dev/full", full[k]);
    says(a, 16, "writing standard output failed (No space left on device)", NULL);
  }
  says("run " SCENES "/bead_ring_below.scene -o /dev/full", 16,
       "writing /dev/full failed (No space left on device)", NULL);
  // a run that fails leaves no file under the name asked for (nothing half-written)
  write_file("cli_fail.scene",
             "dim 2\ncoord x q=0 v=0\nparticle b mass=1\nplace b = x; sqrt(1 - t)\nrun t1=2 "
             "dt=0.1\n");
  remove("cli_fail.csv");
  says("run cli_fail.scene -o cli_fail.csv", 4, "cli_fail.scene: coordinate map 'place b'",
       "cli_fail.csv not written");
  CHECK(access("cli_fail.csv", F_OK) != 0);
  // sweep names the scene file's line of the culprit, not a line of a rewritten text
  int line = line_of(SCENES "/bead_ring_below.scene", "particle bead");
  snprintf(w, sizeof w, "bead_ring_below.scene:%d: particle 'bead': mass -1 is not positive", line);
  says("sweep " SCENES "/bead_ring_below.scene --param m=-1:1:3", 0, w, NULL);
  // a grid too large for memory is refused with its count
  says("sweep " SCENES "/bead_ring_below.scene --param omega=1:2:2147483647", 64,
       "--param 'omega=1:2:2147483647': 2147483647 points are too many", NULL);
  says("equilibria " SCENES "/bead_ring_below.scene --scan theta=1:2:99999999999", 64,
       "99999999999 points are too many", NULL);
}

// the scene's atol rule: lyapunov on a scene stating no atol runs with atol = rtol, as a run of
// the scene does (solve.h), not with dal_lyapunov's default 1e-10
static void lyapunov_atol(void) {
  write_file("cli_lyap.scene", "dim 2\nparam omega = 6.2609903369994111\ncoord theta q=1 v=0\n"
                               "particle bob mass=1\n"
                               "place bob = sin(theta); 0.1*cos(omega*t) - cos(theta)\n"
                               "gravity 0 -9.8\nrun method=dopri5 rtol=1e-5 t1=20 dt=0.01\n");
  CHECK(cli("lyapunov cli_lyap.scene") == 0 && tab.nrow == 2);
  dal_system *sys = pendulum(0.1);
  dal_state *st;
  double q = 1, v = 0, ex[2][2], er[2];
  dal_state_create(sys, &st);
  const double atol[2] = {1e-5, 1e-10};
  for (int k = 0; k < 2; ++k) {
    dal_state_set(sys, st, 0, &q, &v);
    dal_lyapunov_opts o = dal_default_lyapunov_opts();
    o.t_end = 20;
    o.method = DAL_METHOD_DOPRI5;
    o.rtol = 1e-5;
    o.atol = atol[k];
    CHECK_OK(dal_lyapunov(sys, st, &o, ex[k], er, NULL, NULL));
  }
  printf("lyapunov at rtol 1e-5: CLI %.12f, C route with atol = rtol %.12f, with 1e-10 %.12f\n",
         tab.v[0][1], ex[0][0], ex[1][0]);
  CHECK(fabs(tab.v[0][1] - ex[0][0]) <= 1e-9 && fabs(ex[1][0] - ex[0][0]) > 1e-7);
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

// Ctrl-C: the run stops at a whole row, says where, exits 130, and its -o file holds whole
// rows ending at the time it states
static void interrupt(void) {
  remove("cli_int.csv");
  pid_t pid = fork();
  if (pid == 0) {
    signal(SIGINT, SIG_DFL); // a test started in the background inherits it ignored
    if (!freopen("cli_int.err", "w", stderr)) _exit(127);
    execl(CLI, CLI, "run", SCENES "/driven_pendulum.scene", "--t1", "1e6", "-o", "cli_int.csv",
          "--no-progress", (char *)NULL);
    _exit(127);
  }
  // wait for rows in the temporary file, then interrupt
  glob_t gl = {0};
  for (int k = 0; k < 2000; ++k) {
    int found = glob("cli_int.csv.part*", 0, NULL, &gl) == 0;
    FILE *f = found ? fopen(gl.gl_pathv[0], "r") : NULL;
    long size = 0;
    if (f) fseek(f, 0, SEEK_END), size = ftell(f), fclose(f);
    globfree(&gl);
    if (size > 8192) break;
    nanosleep(&(struct timespec){0, 10000000}, NULL);
  }
  kill(pid, SIGINT);
  int st = 0, k = 0;
  while (waitpid(pid, &st, WNOHANG) == 0 && k++ < 3000) // 30 s at most
    nanosleep(&(struct timespec){0, 10000000}, NULL);
  if (k > 3000) kill(pid, SIGKILL), waitpid(pid, &st, 0);
  CHECK_MSG(WIFEXITED(st) && WEXITSTATUS(st) == 130, "interrupted run: status %d", st);
  FILE *f = fopen("cli_int.csv", "r");
  char line[512];
  int rows = 0, whole = 1;
  double last = NAN;
  while (f && fgets(line, sizeof line, f)) {
    int commas = 0;
    for (char *p = line; *p; ++p)
      commas += *p == ',';
    whole = whole && commas == 4 && line[strlen(line) - 1] == '\n';
    if (rows++) last = strtod(line, NULL);
  }
  if (f) fclose(f);
  char err[1024] = "";
  f = fopen("cli_int.err", "r");
  if (f) err[fread(err, 1, sizeof err - 1, f)] = 0, fclose(f);
  const char *at = strstr(err, "the rows written end at t = ");
  double stated = at ? strtod(at + strlen("the rows written end at t = "), NULL) : NAN;
  printf("Ctrl-C: %d whole rows, the last at t = %.17g; stderr: %s", rows, last, err);
  CHECK(rows > 100 && whole && strstr(err, "dalembert run: interrupted at t = "));
  CHECK(stated == last);
}

// --native (every command): the scene's formulas and equations of motion compiled
// (dal_scene_native). The run agrees with the bytecode's within rounding carried over the run
// (the compiled equations are within 2^-45 of the general path: test_codegen_eom); a scene out
// of the compiled equations' reach still runs and says why on stderr, as does a scene with no
// formulas to compile
static table plain;
static void native_flag(void) {
  CHECK(cli("run " SCENES "/driven_pendulum.scene --t1 2 2>/dev/null") == 0 && tab.nrow == 201);
  plain = tab;
  CHECK(cli("run " SCENES "/driven_pendulum.scene --t1 2 --native 2>/dev/null") == 0);
  double d = tab.nrow == plain.nrow && tab.ncol == plain.ncol ? 0.0 : INFINITY;
  for (int i = 0; i < plain.nrow && d < INFINITY; ++i)
    for (int j = 0; j < plain.ncol; ++j)
      d = fmax(d, fabs(tab.v[i][j] - plain.v[i][j]));
  CHECK_MSG(d <= 1e-10, "run --native differs from the bytecode's run by %g", d);
  write_file("cli_native_rod.scene", "dim 2\ncoord x q=0 v=0\ncoord y q=-1 v=0\nparticle b mass=1\n"
                                     "place b = x; y\nconstraint rod parts=b = x_b^2 + y_b^2 - 1\n"
                                     "gravity 0 -9.8\nrun t1=0.2 dt=0.1\n");
  says("run cli_native_rod.scene --native", 0, "note: equations of motion not compiled",
       "constraints");
  write_file("cli_native_c.scene", "dim 2\ncoord th q=0.3 v=0\nparticle b mass=1\n"
                                   "place b pendulum th l=1\ngravity 0 -9.8\nrun t1=0.2 dt=0.1\n");
  says("run cli_native_c.scene --native", 0, "note: nothing to compile", "C already");
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
  regressions();
  lyapunov_atol();
  interrupt();
  native_flag();
  return check_summary("test_cli");
}
