// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The scene layer's private structures: element lines and the scene (reader, writer, shower).
#ifndef DAL_SCENE_SCENE_H
#define DAL_SCENE_SCENE_H

#include "dalembert/dalembert.h"
#include "dalembert/scene.h"

#define MAXTOK 64

/// one element line, normalized: its words before a standalone '=' and its formulas after it
typedef struct sline {
  int line;
  int ntok;
  char *tok[MAXTOK];
  int nf;
  char *f[3]; // formulas (after '='), split at ';'
} sline;

/// index of s in names (n of them), -1 if absent
int dal__scene_find(char *const *names, int n, const char *s);
/// the value of word `key`=value from word `from` on (NULL if absent)
const char *dal__scene_kv(const sline *l, int from, const char *key);

/// an `event` or a surface `section` line, compiled: g(t, q, qdot)
typedef struct scene_event {
  const char *name; // borrowed from the line
  dal_expr *e;      // kept in the scene's expression list
  int direction;    // dal_event_direction
  int terminal;
  int section;
} scene_event;

struct dal_scene {
  char *name;
  sline *lines;
  int nlines;
  // parameters (the values set_param changes)
  int nparam;
  char **pname;
  double *pval;
  // what the lines built
  int dim;
  int ncoord;
  char **cname;
  double *q0, *v0;
  int npart;
  char **partname;
  dal_expr **ex;
  int nex, capex;
  dal_builder *b;
  dal_system *sys;
  dal_solve_opts opts;
  double t0, t1, dt;
  int has_run;
  scene_event *ev; // the event and surface-section lines, in order
  int nev;
  double strobe; // period of the stroboscopic section (0: none)
  int native;    // 1: the expressions run native code (dal_scene_native), again after a rebuild
  dal_codegen_opts native_opts;
};

#endif
