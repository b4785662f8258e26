// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The scene layer's private structures: element lines and the scene (reader, writer, shower).
#ifndef DAL_SCENE_SCENE_H
#define DAL_SCENE_SCENE_H

#include "dalembert/dalembert.h"
#include "dalembert/scene.h"

/// one element line, normalized: its words before a standalone '=' and its formulas after it
/// (a key=value word's value may hold spaces: "q=2 * a" is one word)
typedef struct sline {
  int line;
  int ntok, captok;
  char **tok;
  int nf;
  char *f[3]; // formulas (after '='), split at ';'
} sline;

/// a name table: string keys (borrowed) to ints, open addressing; linear in the names it holds
typedef struct dal_tab {
  const char **key;
  int *val;
  int cap, n;
} dal_tab;

/// the value of key (-1 when absent)
int dal__tab_get(const dal_tab *t, const char *key);
/// add key (borrowed; must outlive the table) with value v; DAL_OK or DAL_E_NOMEM
int dal__tab_put(dal_tab *t, const char *key, int v);
void dal__tab_free(dal_tab *t);

// text.c: text helpers, name tables, messages ("file:line: ..."), key=value words
char *dal__scene_dup(const char *s);
char *dal__scene_dupn(const char *s, size_t n);
/// the array v (n elements of size sz in use, room for *cap) with room for one more: v itself,
/// or v reallocated to twice its room (`first` elements at first, *cap updated); NULL when out
/// of memory (v is then untouched)
void *dal__scene_grow(void *v, int n, int *cap, size_t sz, int first);
/// a formatted string of any length (malloc'd; NULL when out of memory)
char *dal__scene_strf(const char *fmt, ...);
/// msg = "<scene>:<line>: " + fmt ...; returns rc
int dal__scene_err(const dal_scene *sc, int line, char *msg, size_t len, int rc, const char *fmt,
                   ...);
void dal__scene_free_line(sline *l);
/// the value of word `key`=value from word `from` on (NULL if absent)
const char *dal__scene_kv(const sline *l, int from, const char *key);

// grammar.c: the table of elements (handler, pass, form), a build of every line by it
/// line l's element by the grammar table, when the element is read in `pass` (0: parameters)
int dal__scene_line(dal_scene *sc, const sline *l, int pass, char *msg, size_t len);
/// the scene's lines built anew into a builder and a system (what an earlier build made is
/// undone first)
int dal__scene_build(dal_scene *sc, char *msg, size_t len);

// build.c: what a build made undone, and the element handlers
void dal__scene_unbuild(dal_scene *sc);
/// element handler: one line of its kind into the scene's builder
typedef int dal_scene_element_fn(dal_scene *sc, const sline *l, char *msg, size_t len);
dal_scene_element_fn dal__scene_param, dal__scene_dim, dal__scene_coord, dal__scene_particle,
    dal__scene_place, dal__scene_constraint, dal__scene_spring, dal__scene_force,
    dal__scene_gravity, dal__scene_potential, dal__scene_run, dal__scene_event;
/// index of particle `name` (-1 if absent)
int dal__scene_part(const dal_scene *sc, const char *name);

/// the scene's parameters the formulas f (nf) name, in the order of the file: names (borrowed
/// from the lines) and values, both malloc'd (the caller frees them)
int dal__scene_params(const dal_scene *sc, const char *const *f, int nf, const char ***names,
                      double **values, int *n);
/// an expression of formulas f (nf) over inputs `in` (nin, with velocities when vel) and the
/// scene's parameters the formulas name (a formula costs its own length, not the scene's
/// parameter count); *e is the caller's. msg as dal_expr_create.
int dal__scene_expr(const dal_scene *sc, const char *name, const char *const *f, int nf,
                    const char *const *in, int nin, int vel, dal_expr **e, char *msg, size_t len);

/// an `event` or a surface `section` line, compiled: g(t, q, qdot)
typedef struct scene_event {
  const char *name; // borrowed from the line
  dal_expr *e;      // kept in the scene's expression list
  int direction;    // dal_event_direction
  int terminal;
  int section;
} scene_event;

/// a `force` line: a generalized force Q_i(t, q, qdot) on coordinate i
typedef struct scene_force {
  dal_expr *e; // kept in the scene's expression list
  int coord;
} scene_force;

struct dal_scene {
  char *name;
  sline *lines;
  int nlines;
  // parameters: values set by dal_scene_set_param (over[j]) survive every rebuild
  int nparamlines;
  unsigned char *over;
  double *overval;
  // what the lines built: parameters (names borrowed from the lines), in the order of the file
  int nparam;
  const char **pname;
  double *pval;
  dal_tab ptab;   // parameter name -> index
  dal_tab syms;   // every name a formula may use (parameters, coordinates, rates, x_<p>) -> line
  dal_tab parts;  // particle name -> index
  dal_tab coords; // coordinate name -> index
  dal_tab elems;  // constraint, event and section names -> line
  char **symkeys; // the made names the tables borrow (rates, x_<p>, ...)
  int nsymkeys, capsymkeys;
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
  scene_force **gf; // the force lines (each allocated once: the builder keeps its address)
  int ngf;
  double strobe; // period of the stroboscopic section (0: none)
  int native;    // 1: the expressions run native code (dal_scene_native), again after a rebuild
  dal_codegen_opts native_opts;
};

/// the compiled equations of motion of the scene's system when its native options ask for them
/// (dal_codegen_attach_eom); out of their reach DAL_OK with a note in msg (grammar.c)
int dal__scene_native_eom(dal_scene *sc, char *msg, size_t msglen);

#endif
