// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Flagship demo: run the seed scenes (SICM oscillator, SICM driven pendulum, bead on a
// rotating ring) and the analysis scenes (the driven pendulum's Poincare sections and its
// Lyapunov exponents converging, the bead's bifurcation diagram) in full mode, leaving their
// CSVs and charts in one folder.
//
// Usage: demo [OUTDIR]   (default ./demo-output); demo --check runs each scene's own check.
// The scenes are the sibling programs sicm_oscillator, sicm_driven_pendulum, sicm_section,
// ring_scene, lyapunov and bead_bifurcation (built next to this one); each is self-contained and
// documented in its own file.
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dalembert/dalembert.h"

int main(int argc, char **argv) {
  int check = argc > 1 && strcmp(argv[1], "--check") == 0;
  const char *out = !check && argc > 1 ? argv[1] : "demo-output";
  // the scene programs live in this program's directory
  char dir[1024] = ".";
  const char *slash = strrchr(argv[0], '/');
  if (slash && (size_t)(slash - argv[0]) < sizeof dir) {
    memcpy(dir, argv[0], (size_t)(slash - argv[0]));
    dir[slash - argv[0]] = 0;
  }
  printf("dalembert %s: seed scenes%s\n", dal_version(), check ? " (checks)" : "");
  const char *scenes[6] = {"sicm_oscillator", "sicm_driven_pendulum", "sicm_section", "ring_scene",
                           "lyapunov",        "bead_bifurcation"};
  int bad = 0;
  for (int i = 0; i < 6; ++i) {
    char cmd[3200];
    if (check)
      snprintf(cmd, sizeof cmd, "'%s/%s' --check", dir, scenes[i]);
    else
      snprintf(cmd, sizeof cmd, "'%s/%s' --out '%s'", dir, scenes[i], out);
    printf("\n== %s\n", scenes[i]);
    fflush(stdout);
    int rc = system(cmd);
    if (rc != 0) {
      printf("%s failed (status %d)\n", scenes[i], rc);
      bad = 1;
    }
  }
  if (!check) printf("\nCSVs and charts are in %s/\n", out);
  if (check) printf("%s\n", bad ? "FAILED" : "ok");
  return bad;
}
