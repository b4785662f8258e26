// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Scene files written back: the lines as read, parameters as numbers or formulas.
#define _POSIX_C_SOURCE 200809L
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene.h"

// the shortest decimal that reads back to v
static void shortest(double v, char *num, size_t len) {
  for (int prec = 15; prec <= 17; ++prec) {
    snprintf(num, len, "%.*g", prec, v);
    if (strtod(num, NULL) == v) break;
  }
}

int dal_scene_write(const dal_scene *sc, FILE *fp) {
  if (!sc || !fp) return DAL_E_ARG;
  fprintf(fp, "# %s, written by dalembert %s\n", sc->name, dal_version());
  int j = 0;
  for (int i = 0; i < sc->nlines; ++i) {
    const sline *l = &sc->lines[i];
    if (!strcmp(l->tok[0], "param") && j < sc->nparam) {
      // a value set by dal_scene_set_param or a plain number: the number; else the formula
      char num[40], *end = NULL;
      double v = strtod(l->f[0], &end);
      int plain = end != l->f[0] && !*end;
      if (sc->over[j] || plain) {
        shortest(sc->over[j] ? sc->overval[j] : v, num, sizeof num);
        fprintf(fp, "param %s = %s\n", l->tok[1], num);
      } else {
        fprintf(fp, "param %s = %s\n", l->tok[1], l->f[0]);
      }
      j++;
      continue;
    }
    for (int k = 0; k < l->ntok; ++k)
      fprintf(fp, "%s%s", k ? " " : "", l->tok[k]);
    for (int k = 0; k < l->nf; ++k)
      fprintf(fp, "%s%s", k ? "; " : " = ", l->f[k]);
    fputc('\n', fp);
  }
  return ferror(fp) ? DAL_E_IO : DAL_OK;
}

int dal_scene_write_c(const dal_scene *sc, const char *prefix, FILE *fp) {
  if (!sc) return DAL_E_ARG;
  return dal_codegen_write(sc->ex, sc->nex, prefix, fp);
}
