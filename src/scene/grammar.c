// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The scene grammar: one table of the elements by their first word, with the handler that
// builds each (build.c), the pass that reads it and its form, which the help prints; a build of
// every line in the table's passes.
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene.h"

// the grammar: the elements of a scene file by their first word, the pass that reads them
// (parameters first, so every formula may use every parameter) and their forms
static const struct {
  const char *key;
  dal_scene_element_fn *fn;
  int pass;
  const char *form;
} elements[] = {
    {"param", dal__scene_param, 0, "param NAME = FORMULA        (of the parameters above)"},
    {"dim", dal__scene_dim, 1, "dim 2|3|0                   (0: a Lagrangian only; first)"},
    {"coord", dal__scene_coord, 1, "coord NAME [q=F] [v=F]      (initial value and rate)"},
    {"particle", dal__scene_particle, 1, "particle NAME mass=F"},
    {"place", dal__scene_place, 1,
     "place P [parent=Q] = F1; F2[; F3]  |  place P PRIMITIVE COORDS... [NAME=F]..."},
    {"constraint", dal__scene_constraint, 1,
     "constraint NAME [parts=A,B,...] = F1[; F2; F3]  |  constraint NAME PRIMITIVE "
     "[parts=..] [COORDS...] [NAME=F]..."},
    {"spring", dal__scene_spring, 1, "spring A B|anchor=F,F[,F] k=F [L=F]"},
    {"damper", dal__scene_spring, 1, "damper A B|anchor=F,F[,F] c=F"},
    {"force", dal__scene_force, 1, "force COORD = F(t, q, qdot)  (a generalized force on COORD)"},
    {"gravity", dal__scene_gravity, 1, "gravity F F [F]"},
    {"potential", dal__scene_potential, 1, "potential = U(q, t)"},
    {"lagrangian", dal__scene_potential, 1, "lagrangian = L(t, q, qdot)"},
    {"run", dal__scene_run, 1, "run [method=M] [rtol=F] [atol=F] [step=F] [t0=F] [t1=F] [dt=F]"},
    {"event", dal__scene_event, 1, "event NAME [rising|falling|both] [terminal] = g(t, q, qdot)"},
    {"section", dal__scene_event, 1,
     "section NAME [rising|falling|both] = g(t, q, qdot)  |  section NAME period=F"},
};

enum { NELEMENTS = sizeof elements / sizeof *elements };

int dal_scene_help(FILE *fp) {
  if (!fp) return DAL_E_ARG;
  fprintf(fp, "scene file: one element per line, '#' starts a comment, F a formula (a value after "
              "key= may hold spaces):\n");
  for (int i = 0; i < NELEMENTS; ++i)
    fprintf(fp, "  %s\n", elements[i].form);
  return ferror(fp) ? DAL_E_IO : DAL_OK;
}

int dal__scene_line(dal_scene *sc, const sline *l, int pass, char *msg, size_t len) {
  for (int i = 0; i < NELEMENTS; ++i)
    if (!strcmp(l->tok[0], elements[i].key))
      return elements[i].pass == pass ? elements[i].fn(sc, l, msg, len) : DAL_OK;
  if (pass) return DAL_OK;
  char known[256] = "";
  for (int i = 0; i < NELEMENTS; ++i)
    snprintf(known + strlen(known), sizeof known - strlen(known), "%s%s", i ? " " : "",
             elements[i].key);
  return dal__scene_err(sc, l->line, msg, len, DAL_E_ARG, "unknown element '%s' (%s)", l->tok[0],
                        known);
}

int dal__scene_native_eom(dal_scene *sc, char *msg, size_t msglen) {
  if (!sc->native_opts.eom) return DAL_OK;
  int rc = dal_codegen_attach_eom(sc->sys, &sc->native_opts, msg, msglen);
  // out of the compiled equations' reach: the general path runs, and the note says so
  if (rc == DAL_E_UNSUPPORTED || rc == DAL_E_TOO_LARGE) rc = DAL_OK;
  return rc;
}

int dal__scene_build(dal_scene *sc, char *msg, size_t len) {
  dal__scene_unbuild(sc);
  sc->dim = 2;
  sc->opts = dal_default_solve_opts();
  sc->t0 = 0;
  sc->t1 = 10;
  sc->dt = 0.01;
  sc->has_run = 0;
  sc->pname = calloc((size_t)sc->nparamlines + 1, sizeof *sc->pname);
  sc->pval = calloc((size_t)sc->nparamlines + 1, sizeof *sc->pval);
  int rc = sc->pname && sc->pval ? DAL_OK : DAL_E_NOMEM;
  for (int pass = 0; pass < 2; ++pass)
    for (int i = 0; i < sc->nlines && !rc; ++i)
      rc = dal__scene_line(sc, &sc->lines[i], pass, msg, len);
  if (!rc && !sc->b)
    rc = dal__scene_err(sc, sc->nlines ? sc->lines[sc->nlines - 1].line : 0, msg, len, DAL_E_ARG,
                        "no coordinates or particles");
  if (!rc) {
    rc = dal_builder_compile(sc->b, &sc->sys);
    if (rc && msg && len) snprintf(msg, len, "%s: %s", sc->name, dal_builder_errmsg(sc->b));
  }
  // native code again for the new expressions (the cache has it)
  if (!rc && sc->native && sc->nex)
    rc = dal_codegen_attach(sc->ex, sc->nex, &sc->native_opts, msg, len);
  if (!rc && sc->native) rc = dal__scene_native_eom(sc, msg, len);
  return rc;
}
