// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// What the generated-code tests share: a private cache for the run, its options, and text.
#ifndef DAL_TESTS_TEST_CODEGEN_H
#define DAL_TESTS_TEST_CODEGEN_H

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

#include "check.h"
#include "dalembert/dalembert.h"

static char cache[256];

// options with the run's cache
static dal_codegen_opts opts(void) {
  dal_codegen_opts o = dal_codegen_default_opts();
  o.cache_dir = cache;
  return o;
}

// make the run's private cache (mkdtemp: 0700)
static void cache_make(void) {
  snprintf(cache, sizeof cache, "/tmp/dal_codegen_test.XXXXXX");
  CHECK(mkdtemp(cache) != NULL);
}

// remove it
static void cache_remove(void) {
  char cmd[400];
  snprintf(cmd, sizeof cmd, "rm -rf %s", cache);
  CHECK(system(cmd) == 0);
}

// snprintf through a va_list
static void put(char *s, size_t len, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(s, len, fmt, ap);
  va_end(ap);
}

#endif
