// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The public headers as text, for the tests that read them (test_api, test_api_sweep).
#ifndef DAL_TESTS_HEADERS_H
#define DAL_TESTS_HEADERS_H

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/// The whole file at path, NUL-terminated (the caller frees it); NULL when it cannot be read.
static inline char *read_text(const char *path) {
  FILE *fp = fopen(path, "rb");
  if (!fp) return NULL;
  fseek(fp, 0, SEEK_END);
  long len = ftell(fp);
  rewind(fp);
  char *s = len >= 0 ? malloc((size_t)len + 1) : NULL;
  if (s && fread(s, 1, (size_t)len, fp) != (size_t)len) {
    free(s);
    s = NULL;
  }
  if (s) s[len] = 0;
  fclose(fp);
  return s;
}

/// Call fn(text, name, ctx) with the text of every header (*.h) in dir (fn may change the text);
/// the number of headers read, or -1 when dir cannot be read.
static inline int for_each_header(const char *dir,
                                  void (*fn)(char *text, const char *name, void *ctx), void *ctx) {
  DIR *d = opendir(dir);
  if (!d) return -1;
  int files = 0;
  for (struct dirent *e; (e = readdir(d)) != NULL;) {
    size_t len = strlen(e->d_name);
    if (len < 3 || strcmp(e->d_name + len - 2, ".h") != 0) continue;
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
    char *text = read_text(path);
    if (!text) continue;
    fn(text, e->d_name, ctx);
    free(text);
    ++files;
  }
  closedir(d);
  return files;
}

#endif
