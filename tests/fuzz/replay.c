// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// Replays fuzz inputs through the libFuzzer entry point without libFuzzer (a ctest).
//
// usage: fuzz_replay [--slow SECONDS] [--dump DIR] [--random COUNT SEED] PATH...
// Each PATH is a file or a directory whose regular files are replayed in name order (so runs
// are reproducible). --random also feeds COUNT pseudo-random inputs from a fixed seed, which
// gives every build (including the sanitizer one) some fuzzing without clang; --dump writes
// them to DIR (to seed a corpus or keep a reproducer). --slow names every input that takes
// longer than SECONDS. A violated invariant aborts inside the target; a crash or a leak
// fails the test under the sanitizers.
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static double slow_limit = -1.0; // report inputs slower than this (seconds; < 0: never)

static double now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

// run one input, timing it
static void run_one(const uint8_t *data, size_t len, const char *what) {
  // with FZ_DIGEST set the target prints a digest line per input: name it
  if (getenv("FZ_DIGEST")) {
    const char *base = strrchr(what, '/');
    printf("%s ", base ? base + 1 : what);
  }
  double t0 = now();
  LLVMFuzzerTestOneInput(data, len);
  double dt = now() - t0;
  if (slow_limit >= 0 && dt > slow_limit)
    fprintf(stderr, "fuzz_replay: slow input %s: %.3f s\n", what, dt);
}

// read a whole file; returns 0 on success
static int replay_file(const char *path) {
  FILE *fp = fopen(path, "rb");
  if (!fp) {
    fprintf(stderr, "fuzz_replay: cannot open %s\n", path);
    return 1;
  }
  size_t cap = 4096, len = 0;
  uint8_t *buf = malloc(cap);
  while (buf) {
    size_t got = fread(buf + len, 1, cap - len, fp);
    len += got;
    if (len < cap) break;
    uint8_t *nb = realloc(buf, 2 * cap);
    if (!nb) {
      free(buf);
      buf = NULL;
      break;
    }
    buf = nb;
    cap *= 2;
  }
  fclose(fp);
  if (!buf) {
    fprintf(stderr, "fuzz_replay: out of memory reading %s\n", path);
    return 1;
  }
  run_one(buf, len, path);
  free(buf);
  return 0;
}

static int cmp_str(const void *a, const void *b) {
  return strcmp(*(char *const *)a, *(char *const *)b);
}

// replay every regular file of a directory in name order; *count receives the number replayed
static int replay_dir(const char *dir, int *count) {
  DIR *d = opendir(dir);
  if (!d) {
    fprintf(stderr, "fuzz_replay: cannot open directory %s\n", dir);
    return 1;
  }
  char **names = NULL;
  size_t n = 0, cap = 0;
  int bad = 0;
  for (struct dirent *e; (e = readdir(d)) != NULL;) {
    if (e->d_name[0] == '.') continue;
    size_t len = strlen(dir) + strlen(e->d_name) + 2;
    char *p = malloc(len);
    if (!p) {
      bad = 1;
      break;
    }
    snprintf(p, len, "%s/%s", dir, e->d_name);
    struct stat sb;
    if (stat(p, &sb) != 0 || !S_ISREG(sb.st_mode)) {
      free(p);
      continue;
    }
    if (n == cap) {
      cap = cap ? 2 * cap : 64;
      char **nn = realloc(names, cap * sizeof *nn);
      if (!nn) {
        free(p);
        bad = 1;
        break;
      }
      names = nn;
    }
    names[n++] = p;
  }
  closedir(d);
  if (n) qsort(names, n, sizeof *names, cmp_str);
  for (size_t i = 0; i < n; ++i) {
    bad |= replay_file(names[i]);
    free(names[i]);
  }
  free(names);
  *count += (int)n;
  return bad;
}

// xorshift64* bytes for the random inputs
static uint64_t next_rand(uint64_t *s) {
  *s ^= *s >> 12;
  *s ^= *s << 25;
  *s ^= *s >> 27;
  return *s * 2685821657736338717ULL;
}

int main(int argc, char **argv) {
  int bad = 0, count = 0;
  const char *dump = NULL;
  for (int a = 1; a < argc; ++a) {
    if (strcmp(argv[a], "--slow") == 0 && a + 1 < argc) {
      slow_limit = strtod(argv[++a], NULL);
      continue;
    }
    if (strcmp(argv[a], "--dump") == 0 && a + 1 < argc) {
      dump = argv[++a];
      continue;
    }
    if (strcmp(argv[a], "--random") == 0 && a + 2 < argc) {
      long nrand = strtol(argv[a + 1], NULL, 10);
      uint64_t seed = strtoull(argv[a + 2], NULL, 10) | 1u;
      a += 2;
      uint8_t buf[512];
      for (long k = 0; k < nrand; ++k) {
        size_t len = 16 + (size_t)(next_rand(&seed) % (sizeof buf - 16));
        for (size_t i = 0; i < len; ++i)
          buf[i] = (uint8_t)(next_rand(&seed) >> 56);
        char what[4096];
        snprintf(what, sizeof what, "%s/random-%ld", dump ? dump : "(random)", k);
        if (dump) {
          FILE *fp = fopen(what, "wb");
          if (!fp || fwrite(buf, 1, len, fp) != len) bad = 1;
          if (fp) fclose(fp);
        }
        run_one(buf, len, what);
        ++count;
      }
      continue;
    }
    struct stat sb;
    if (stat(argv[a], &sb) != 0) {
      fprintf(stderr, "fuzz_replay: %s does not exist\n", argv[a]);
      bad = 1;
    } else if (S_ISDIR(sb.st_mode)) {
      bad |= replay_dir(argv[a], &count);
    } else {
      bad |= replay_file(argv[a]);
      ++count;
    }
  }
  printf("fuzz_replay: %d inputs replayed%s\n", count, bad ? " (with errors)" : "");
  return bad || count == 0;
}
