// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// libFuzzer target for the text readers: scene files and formulas.
//
// An input starting with "L:" is a scene with long lists and names: every '@' becomes 300
// copies of "0+" (a formula of 600 characters) and every '%' a name of 300 letters, so that
// parts= and anchor= lists run far past any fixed buffer. The symbolic printer and show are
// held to a time bound (PRINT_SECONDS each, sanitizers included): a formula too large to show
// must say so (DAL_E_TOO_LARGE), not hang.
//
// An input starting with "F:" is a formula over inputs x, y (velocities xdot, ydot) and the
// parameter p: compiled, evaluated, checked, printed in the three formats, its text read back,
// differentiated (the symbolic part on formulas of at most 100 instructions). Any other input is a
// scene file: read, written back and read again (which must succeed), shown, and evaluated once at
// its initial state, its events created. Invariants (abort when violated): every refusal has a
// status and a message; what the library prints it reads back. No crash, no leak, no hang
// (scripts/fuzz.sh; the corpus is replayed by ctest).
#define _POSIX_C_SOURCE 200809L
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <time.h>

#include "dalembert/dalembert.h"

#define PRINT_SECONDS 30.0

static double now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void need(int cond, const char *what, const char *text) {
  if (!cond) {
    fprintf(stderr, "fuzz_scene: invariant violated: %s\n--- input:\n%s\n", what, text);
    abort();
  }
}

static void formula(const char *text) {
  const char *in[] = {"x", "y"}, *pn[] = {"p"};
  double pv[] = {0.7};
  dal_expr_def d = dal_default_expr_def();
  d.formulas = &text;
  d.nout = 1;
  d.inputs = in;
  d.nin = 2;
  d.velocities = 1;
  d.params = pn;
  d.values = pv;
  d.nparam = 1;
  dal_expr *e = NULL;
  char msg[512] = "";
  int rc = dal_expr_create(&d, &e, msg, sizeof msg);
  need(rc ? (rc < 0 && msg[0] && !e) : e != NULL, "a status and a message", text);
  if (rc) return;
  dal_jet x[4] = {dal_var(0.3, 1), dal_var(-1.1, 0.5), dal_const(2), dal_const(-0.4)}, out;
  dal_expr_check(e, x, dal_var(0.2, 1), NULL, &out, msg, sizeof msg);
  // the symbolic side on every formula: bounded in time, too large said so
  for (int f = 0; f < 3; ++f) {
    double t0 = now();
    int n = dal_expr_print(e, 0, (dal_expr_format)f, NULL, 0);
    need(now() - t0 < PRINT_SECONDS, "dal_expr_print within its time bound", text);
    need(n >= 0 || n == DAL_E_TOO_LARGE || n == DAL_E_NOMEM, "a length or too large", text);
    if (n < 0) continue;
    char *buf = malloc((size_t)n + 1);
    if (!buf) continue;
    dal_expr_print(e, 0, (dal_expr_format)f, buf, (size_t)n + 1);
    if (f == DAL_EXPR_TEXT) {
      // the printed text reads back
      const char *t = buf;
      dal_expr_def d2 = d;
      d2.formulas = &t;
      dal_expr *e2 = NULL;
      rc = dal_expr_create(&d2, &e2, msg, sizeof msg);
      need(rc == 0 || rc == DAL_E_NOMEM || strstr(msg, "too large") || strstr(msg, "nested") ||
               strstr(msg, "longer than"),
           "the printed text reads back", buf);
      dal_expr_destroy(e2);
    }
    free(buf);
  }
  dal_expr *de = NULL;
  if (!dal_expr_derivative(e, 0, 0, &de, msg, sizeof msg)) dal_expr_eval(de, x, x[0], NULL, &out);
  dal_expr_destroy(de);
  dal_expr_destroy(e);
}

static void scene(const char *text) {
  dal_scene *sc = NULL, *sc2 = NULL;
  char msg[1024] = "";
  int rc = dal_scene_parse(text, "fuzz", &sc, msg, sizeof msg);
  need(rc ? (rc < 0 && msg[0] && !sc) : sc != NULL, "a status and a message", text);
  if (rc) return;
  char *w = NULL;
  size_t wn = 0;
  FILE *fp = open_memstream(&w, &wn);
  if (fp) {
    dal_scene_write(sc, fp);
    fclose(fp);
    rc = dal_scene_parse(w, "written", &sc2, msg, sizeof msg);
    need(rc == 0 || rc == DAL_E_NOMEM, "the written scene reads back", w);
    dal_scene_destroy(sc2);
    free(w);
  }
  fp = fopen("/dev/null", "w");
  if (fp) {
    double t0 = now();
    rc = dal_scene_show(sc, fp, DAL_EXPR_TEXT, msg, sizeof msg);
    need(now() - t0 < 10 * PRINT_SECONDS, "dal_scene_show within its time bound", text);
    need(!rc || msg[0], "show: a status and a message", text);
    fclose(fp);
  }
  dal_state *st = NULL;
  if (!dal_scene_state(sc, &st)) dal_forward(dal_scene_system(sc), st);
  // the event and section lines: their set, each function once at the initial state
  dal_events *ev = NULL;
  if (st && !dal_scene_events(sc, &ev)) {
    for (int i = 0; i < dal_events_size(ev); ++i)
      need(dal_scene_event_is_section(sc, i) >= 0, "an event line or a section line", text);
    dal_state_set_events(st, ev);
    dal_state_set_events(st, NULL);
  }
  need(dal_scene_strobe(sc) >= 0, "a stroboscopic period >= 0", text);
  dal_events_destroy(ev);
  dal_state_destroy(st);
  dal_scene_destroy(sc);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  if (size > 4096) return 0;
  char *text = malloc(size + 1);
  if (!text) return 0;
  memcpy(text, data, size);
  text[size] = 0;
  if (strlen(text) == size) {
    if (size >= 2 && text[0] == 'F' && text[1] == ':') {
      formula(text + 2);
    } else if (size >= 2 && text[0] == 'L' && text[1] == ':') {
      // long lists: '@' -> "0+" x 300, '%' -> 300 letters
      size_t n = 0;
      for (size_t i = 2; i < size; ++i)
        n += text[i] == '@' ? 600 : text[i] == '%' ? 300 : 1;
      char *big = n < (1u << 20) ? malloc(n + 1) : NULL;
      if (big) {
        char *o = big;
        for (size_t i = 2; i < size; ++i) {
          if (text[i] == '@')
            for (int k = 0; k < 300; ++k)
              *o++ = '0', *o++ = '+';
          else if (text[i] == '%')
            for (int k = 0; k < 300; ++k)
              *o++ = 'n';
          else
            *o++ = text[i];
        }
        *o = 0;
        scene(big);
        free(big);
      }
    } else {
      scene(text);
    }
  }
  free(text);
  return 0;
}
