// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// dalembert compile SCENE [-o model.c] [--prefix NAME]: the scene's formulas as a standalone C
// source (dal_scene_write_c, interface in dalembert/codegen.h).
#include <ctype.h>
#include <stdio.h>
#include <string.h>

#include "cli.h"

const cli_opt cli_compile_opts[] = {
    {"output", 'o', CLI_TEXT, "FILE.c", "the C source (default: stdout)", 0},
    {"prefix", 0, CLI_TEXT, "NAME",
     "the functions' prefix (default: the output file's base name, else model)", 0},
    CLI_END,
};

// the prefix: --prefix, else the base name of -o without its extension made an identifier
static int prefix_of(const cli *c, char *p, size_t len) {
  const char *given = cli_text(c, "prefix");
  if (given) {
    size_t k = strlen(given);
    int ok = k > 0 && k < 40 && (isalpha((unsigned char)given[0]) || given[0] == '_');
    for (size_t i = 0; ok && i < k; ++i)
      ok = isalnum((unsigned char)given[i]) || given[i] == '_';
    if (!ok)
      return cli_error(c, CLI_USAGE, "--prefix '%s' is not a C name of at most 39 characters",
                       given);
    snprintf(p, len, "%s", given);
    return DAL_OK;
  }
  const char *path = cli_text(c, "output");
  const char *b = path ? strrchr(path, '/') : NULL;
  b = b ? b + 1 : path;
  size_t k = 0;
  for (; b && b[k] && b[k] != '.' && k + 1 < len && k < 39; ++k)
    p[k] = isalnum((unsigned char)b[k]) ? b[k] : '_';
  p[k] = 0;
  if (!k || isdigit((unsigned char)p[0])) snprintf(p, len, "model");
  return DAL_OK;
}

int cli_compile(cli *c) {
  char prefix[48];
  int rc = prefix_of(c, prefix, sizeof prefix);
  if (rc) return rc;
  FILE *fp = cli_out(c);
  if (!fp) return DAL_E_IO;
  rc = dal_scene_write_c(c->sc, prefix, fp);
  if (rc) cli_error(c, rc, "%s", dal_status_string(rc));
  return cli_close(c, rc);
}
