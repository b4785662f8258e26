// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The driven pendulum's stability chart by Floquet multipliers (dal_floquet).
//
// Problem: a pendulum (l = 1, g = 9.81) whose pivot moves vertically, y = a cos(w t), in its
// angle theta (dal_map_pendulum). Its bottom and its top are solutions at every time; over one
// drive period 2 pi / w their monodromy decides stability. The chart sweeps the amplitude a and
// the frequency w over a grid, on two threads (each its own systems and states), and marks
// where the bottom and where the inverted top are stable.
//
// Checks (--check: a 12 x 12 grid): against the Mathieu chart (y'' + (A - 2Q cos 2s) y = 0,
// s = w t / 2): the bottom has A = 4 g / (l w^2), Q = 2 a / l and is unstable inside the first
// tongue 1 - Q - Q^2/8 < A < 1 + Q - Q^2/8 and stable outside it by a margin of 0.05 (away
// from the second tongue at A = 4) (the tongue's boundaries to second order, Abramowitz &
// Stegun 20.2.25); the top (A = -4 g / (l w^2)) is stable only where A > -Q^2 / 2 (Kapitza: a^2 w^2
// > 2 g l) and is stable where A > -Q^2 / 2 + 7 Q^4 / 128 + 0.02 Q^2 with A < 0.5 (first tongue
// far). Every point's det must be 1 (Liouville) to 1e-8.
//
// Full mode (no argument): a 60 x 48 grid into floquet_chart.csv and, when gnuplot is
// installed, floquet_chart.png (docs/img/floquet_chart.png is this output).
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <dalembert/dalembert.h>

#include "example_util.h"

#define G 9.81
#define PI 3.14159265358979323846

typedef struct cell {
  double a, w;
  dal_stability bottom, top;
  double det_err; // max |det - 1| of the two
  int rc;
} cell;

typedef struct job {
  cell *cells;
  int count, stride, first;
} job;

static dal_system *pendulum(double a, double w) { return ex_pendulum(1.0, 1.0, G, 0.0, a, w); }

// the verdicts of the bottom and the top of one cell
static void analyse(cell *c) {
  dal_system *sys = pendulum(c->a, c->w);
  dal_state *st = NULL;
  c->rc = sys ? dal_state_create(sys, &st) : DAL_E_NOMEM;
  c->det_err = 0.0;
  for (int top = 0; top < 2 && !c->rc; ++top) {
    double q = top ? PI : 0.0, v = 0.0;
    dal_floquet_report r;
    c->rc = dal_state_set(sys, st, 0.0, &q, &v);
    if (!c->rc) c->rc = dal_floquet(sys, st, NULL, 2 * PI / c->w, NULL, NULL, NULL, &r);
    if (c->rc) {
      fprintf(stderr, "a %g w %g: %s\n", c->a, c->w, dal_state_errmsg(st));
      break;
    }
    *(top ? &c->top : &c->bottom) = r.verdict;
    c->det_err = fmax(c->det_err, fabs(r.det - 1.0));
  }
  dal_state_destroy(st);
  dal_system_destroy(sys);
}

static void *worker(void *arg) {
  job *j = arg;
  for (int i = j->first; i < j->count; i += j->stride)
    analyse(&j->cells[i]);
  return NULL;
}

static int stable(dal_stability s) { return s == DAL_NEUTRAL || s == DAL_ASYMPTOTIC; }

// the Mathieu chart's statements at one cell (see the file comment); 0 when they hold
static int check_cell(const cell *c) {
  double Q = 2 * c->a, Ab = 4 * G / (c->w * c->w), At = -Ab, bad = 0;
  double lo = 1 - Q - Q * Q / 8, hi = 1 + Q - Q * Q / 8;
  if (Ab > lo + 0.05 && Ab < hi - 0.05 && stable(c->bottom)) bad = 1;
  int tongue2 = fabs(Ab - 4) < 0.1 + Q * Q; // the second tongue at A = 4 (width ~ Q^2 / 2)
  if ((Ab < lo - 0.05 || Ab > hi + 0.05) && Ab > 0.3 && !tongue2 && !stable(c->bottom)) bad = 1;
  if (At < -Q * Q / 2 && stable(c->top)) bad = 1;
  if (At > -Q * Q / 2 + 7 * pow(Q, 4) / 128 + 0.02 * Q * Q && At < 0.5 && !stable(c->top)) bad = 1;
  if (c->det_err > 1e-8) bad = 1;
  if (bad)
    fprintf(stderr, "CHECK FAILED at a %g w %g (A %g, Q %g): bottom %s, top %s, det err %.3g\n",
            c->a, c->w, Ab, Q, dal_floquet_verdict_name(c->bottom),
            dal_floquet_verdict_name(c->top), c->det_err);
  return (int)bad;
}

int main(int argc, char **argv) {
  int check = argc > 1 && strcmp(argv[1], "--check") == 0;
  int na = check ? 12 : 48, nw = check ? 12 : 60;
  double a0 = 0.005, a1 = 0.3, w0 = 3.0, w1 = 60.0;
  cell *cells = calloc((size_t)(na * nw), sizeof *cells);
  if (!cells) return 1;
  for (int i = 0; i < na; ++i)
    for (int j = 0; j < nw; ++j) {
      cell *c = &cells[i * nw + j];
      c->a = a0 + (a1 - a0) * i / (na - 1);
      c->w = w0 * pow(w1 / w0, (double)j / (nw - 1)); // log-spaced frequencies
    }
  // two threads, interleaved cells
  pthread_t th[2];
  job jobs[2];
  for (int k = 0; k < 2; ++k) {
    jobs[k] = (job){cells, na * nw, 2, k};
    if (pthread_create(&th[k], NULL, worker, &jobs[k])) return 1;
  }
  for (int k = 0; k < 2; ++k)
    pthread_join(th[k], NULL);
  int fails = 0, nb = 0, nt = 0;
  for (int i = 0; i < na * nw; ++i) {
    if (cells[i].rc) ++fails;
    nb += stable(cells[i].bottom);
    nt += stable(cells[i].top);
    if (check) fails += check_cell(&cells[i]);
  }
  printf("%d x %d drives: bottom stable at %d, top stable at %d\n", na, nw, nb, nt);
  if (!check) {
    FILE *fp = fopen("floquet_chart.csv", "w");
    if (!fp) return 1;
    fprintf(fp, "a,w,bottom,top,code\n");
    for (int i = 0; i < na * nw; ++i) {
      const cell *c = &cells[i];
      fprintf(fp, "%.6g,%.6g,%s,%s,%d\n", c->a, c->w, dal_floquet_verdict_name(c->bottom),
              dal_floquet_verdict_name(c->top), stable(c->bottom) + 2 * stable(c->top));
    }
    fclose(fp);
    FILE *gp = popen("gnuplot 2>/dev/null", "w");
    if (gp) {
      fprintf(gp, "set terminal pngcairo size 900,600\nset output 'floquet_chart.png'\n"
                  "set xrange [3:60]\nset yrange [0:0.31]\nset palette maxcolors 4\n"
                  "set datafile separator ','\nset logscale x\nset xlabel 'drive frequency w "
                  "(rad/s)'\nset ylabel 'drive amplitude a (m), l = 1'\n"
                  "set title 'driven pendulum: Floquet stability (dal\\_floquet)'\n"
                  "set palette defined (0 'white', 1 '#4477aa', 2 '#ee6677', 3 '#228833')\n"
                  "set cbrange [-0.5:3.5]\nset cbtics ('none' 0, 'bottom' 1, 'top' 2, 'both' 3)\n"
                  "plot 'floquet_chart.csv' every ::1 using 2:1:5 with points pt 5 ps 1.2 "
                  "palette notitle, sqrt(2*9.81)/x lc 'black' dt 2 title 'a w = sqrt(2 g l)'\n");
      if (pclose(gp)) fprintf(stderr, "gnuplot failed; no chart\n");
    }
  }
  free(cells);
  if (fails) fprintf(stderr, "CHECK FAILED: %d cells\n", fails);
  return fails ? 1 : 0;
}
