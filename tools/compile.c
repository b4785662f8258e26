// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// dalembert compile SCENE [-o model.c]: the scene's formulas as a standalone C source
// (dal_scene_write_c); the functions' prefix is the output file's base name (else "model").
#include <ctype.h>
#include <stdio.h>
#include <string.h>

#include "cli.h"

// the prefix: the base name of path without its extension, made an identifier
static void prefix_of(const char *path, char *p, size_t len) {
  const char *b = path ? strrchr(path, '/') : NULL;
  b = b ? b + 1 : path;
  size_t k = 0;
  for (; b && b[k] && b[k] != '.' && k + 1 < len && k < 39; ++k)
    p[k] = isalnum((unsigned char)b[k]) ? b[k] : '_';
  p[k] = 0;
  if (!k || isdigit((unsigned char)p[0])) snprintf(p, len, "model");
}

int cli_compile(cli *c) {
  char prefix[48];
  prefix_of(c->out, prefix, sizeof prefix);
  FILE *fp = cli_out(c);
  if (!fp) return DAL_E_IO;
  int rc = dal_scene_write_c(c->sc, prefix, fp);
  if (rc) fprintf(stderr, "dalembert: compile %s: %s\n", c->path, dal_status_string(rc));
  return cli_close(c, fp, rc);
}
