// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The command line's shared parts: its options and the analysis commands.
//
//   dalembert run SCENE [-o FILE.csv] [--chart FILE.png] [--events FILE.csv] [--wrap]
//   dalembert show SCENE [--text | --latex | --scheme]
//   dalembert write SCENE
//   dalembert modes SCENE [--here]            normal modes at the equilibrium Newton finds
//                                             from the initial q (--here: at the initial q)
//   dalembert equilibria SCENE [--scan C=LO:HI:N]   equilibria from the initial q (and from N
//                                             starts of coordinate C), their stability
//   dalembert lyapunov SCENE [--t1 T] [--transient T] [--renorm T] [--nexp K] [--method M]
//                      [--h H]                Lyapunov exponents with 95% errors
//   dalembert section SCENE [-o FILE.csv] [--surface] [--wrap]   the scene's Poincare section
//   dalembert sweep SCENE --param NAME=LO:HI:N [--threads K] [--mpi] [-o FILE.csv]
//                                             final states over a grid of a scene parameter
//   dalembert floquet SCENE [--period T] [--format json]   Floquet multipliers of the initial
//                                             state over T (default: the scene's strobe period)
//   dalembert orbit SCENE [--period T] [--free] [--continue NAME=LO:HI:N] [--format json]
//                                             a periodic orbit from the initial state by
//                                             shooting, its multipliers (and its branch in a
//                                             parameter with folds and period doublings)
//   modes, equilibria: [--frozen] the linearization frozen at t0 of a time-dependent scene
//   every command: [--set NAME=VALUE]... [--progress | --no-progress]
#ifndef DAL_TOOLS_CLI_H
#define DAL_TOOLS_CLI_H

#include <stdio.h>

#include "dalembert/dalembert.h"
#include "dalembert/scene.h"

typedef struct cli {
  const char *path;                       // the scene file
  dal_scene *sc;                          // read from it
  const char *out, *png, *events;         // -o, --chart, --events
  const char *scan, *param, *method;      // --scan, --param, --method
  double t1, transient, renorm, h;        // lyapunov (-1: the default)
  double nexp, threads;                   // --nexp, --threads
  int here, surface, wrap, mpi, progress; // flags
  double period;                          // --period (-1: the scene's)
  const char *format;                     // --format (json)
  int json, frozen, free_period;          // --format json, --frozen, --free
  const char *cont;                       // orbit --continue NAME=LO:HI:N
  dal_expr_format fmt;                    // show
  int argc;
  char **argv;
  char msg[2048];
} cli;

int cli_usage(void);
int cli_status_exit(int rc);
// print msg when rc < 0; returns rc
int cli_fail(int rc, const char *msg);
// the progress line on stderr (when enabled): what, done of total, extra text
void cli_progress(const cli *c, const char *what, double done, double total, const char *extra);
// -o FILE or stdout (NULL and a message when it cannot be opened)
FILE *cli_out(const cli *c);
// close what cli_out opened; DAL_E_IO when that fails and rc was not already an error
int cli_close(const cli *c, FILE *fp, int rc);
// NAME=LO:HI:N into its parts (name points into the copy buf of len bytes)
int cli_grid(const char *spec, char *buf, size_t len, double *lo, double *hi, int *n);

// run the scene from its initial state to t1 with events ev (nullable) attached: a CSV row of
// dal_csv_monitor every dt to fp (nullable: none) and the progress line `what`
int cli_evolve(cli *c, FILE *fp, dal_events *ev, double dt, const char *what);

int cli_modes(cli *c);
int cli_equilibria(cli *c);
int cli_lyapunov(cli *c);
int cli_section(cli *c);
int cli_sweep(cli *c);
int cli_floquet(cli *c); // periodic.c
int cli_orbit(cli *c);

#endif
