// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The command line's JSON writer (json.h).
#include <math.h>
#include <stdio.h>

#include "json.h"

static void put_string(FILE *fp, const char *s) {
  fputc('"', fp);
  for (const unsigned char *p = (const unsigned char *)s; *p; ++p) {
    if (*p == '"' || *p == '\\')
      fprintf(fp, "\\%c", *p);
    else if (*p == '\n')
      fputs("\\n", fp);
    else if (*p == '\t')
      fputs("\\t", fp);
    else if (*p < 0x20)
      fprintf(fp, "\\u%04x", *p);
    else
      fputc(*p, fp);
  }
  fputc('"', fp);
}

// the separator, indentation and key of the next member
static void member(cli_json *j, const char *key) {
  if (j->depth > 0) {
    int k = j->depth <= CLI_JSON_DEPTH ? j->depth - 1 : CLI_JSON_DEPTH - 1;
    fputs(j->count[k]++ ? ",\n" : "\n", j->fp);
    fprintf(j->fp, "%*s", 2 * j->depth, "");
  }
  if (key) {
    put_string(j->fp, key);
    fputs(": ", j->fp);
  }
}

static void begin(cli_json *j, const char *key, char o, char c) {
  member(j, key);
  fputc(o, j->fp);
  if (j->depth < CLI_JSON_DEPTH) {
    j->count[j->depth] = 0;
    j->close[j->depth] = c;
  }
  j->depth++;
}

cli_json cli_json_start(FILE *fp) {
  cli_json j = {fp, 0, {0}, {0}};
  begin(&j, NULL, '{', '}');
  return j;
}

void cli_json_object(cli_json *j, const char *key) { begin(j, key, '{', '}'); }
void cli_json_array(cli_json *j, const char *key) { begin(j, key, '[', ']'); }

void cli_json_end(cli_json *j) {
  if (j->depth <= 0) return;
  j->depth--;
  int k = j->depth < CLI_JSON_DEPTH ? j->depth : CLI_JSON_DEPTH - 1;
  if (j->count[k]) fprintf(j->fp, "\n%*s", 2 * j->depth, "");
  fputc(j->close[k], j->fp);
}

int cli_json_finish(cli_json *j) {
  while (j->depth > 0)
    cli_json_end(j);
  fputc('\n', j->fp);
  return ferror(j->fp) ? -1 : 0;
}

void cli_json_num(cli_json *j, const char *key, double v) {
  member(j, key);
  if (isfinite(v))
    fprintf(j->fp, "%.17g", v);
  else
    fputs("null", j->fp);
}

void cli_json_int(cli_json *j, const char *key, long v) {
  member(j, key);
  fprintf(j->fp, "%ld", v);
}

void cli_json_str(cli_json *j, const char *key, const char *s) {
  member(j, key);
  if (s)
    put_string(j->fp, s);
  else
    fputs("null", j->fp);
}

void cli_json_bool(cli_json *j, const char *key, int v) {
  member(j, key);
  fputs(v ? "true" : "false", j->fp);
}
