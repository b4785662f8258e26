// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The command line's services below its commands: options parsed by getopt_long from each
// command's table, help printed from the same rows, exit status, messages, the progress line,
// the output file and grid specifications (cli.h).
#define _GNU_SOURCE // getopt_long
#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli.h"

// the options every command takes (parsed here, not by the command)
enum { COMMON_SET, COMMON_NATIVE, COMMON_PROGRESS, COMMON_NO_PROGRESS, COMMON_HELP, NCOMMON };
static const cli_opt common[NCOMMON + 1] = {
    {"set", 0, CLI_TEXT, "NAME=VALUE", "a scene parameter's value (repeatable)", 0},
    {"native", 0, CLI_FLAG, NULL,
     "the scene's formulas and equations of motion as native code (dal_scene_native; a C "
     "compiler, results within rounding of the bytecode's)",
     0},
    {"progress", 0, CLI_FLAG, NULL, "a progress line on stderr (default: on a terminal, not in CI)",
     0},
    {"no-progress", 0, CLI_FLAG, NULL, "no progress line", 0},
    {"help", 'h', CLI_FLAG, NULL, "this help", 0},
    CLI_END,
};

// getopt_long's codes: a command's row k is ROW + k, a common row COMMON + k, an operand 1
enum { ROW = 1000, COMMON = 2000 };

static const char *const exit_help =
    "exit status:\n"
    "  0        success (a run stopped at a terminal event included)\n"
    "  1 ... 18 the library's failure status, negated: 1 invalid argument (a scene parameter,\n"
    "           a value the library refuses), 4 domain error, 8 no consistent start,\n"
    "           11 convergence failure, 15 unsupported combination, 16 a read or write failed\n"
    "           (standard output included), 18 a formula too large to show ... (the list\n"
    "           in dalembert/base.h)\n"
    "  64       a command line it does not understand (an unknown command or option, an option\n"
    "           of another command, a missing or malformed value)\n"
    "  130      interrupted (Ctrl-C): the output ends with whole rows\n";

static int nrows(const cli_opt *t) {
  int n = 0;
  while (t && t[n].name)
    ++n;
  return n;
}

// one option's help line: "  -o, --output FILE.csv   what"
static void help_row(FILE *fp, const cli_opt *o) {
  char head[64];
  snprintf(head, sizeof head, "%c%c%c --%s%s%s", o->short_name ? '-' : ' ',
           o->short_name ? o->short_name : ' ', o->short_name ? ',' : ' ', o->name,
           o->meta ? " " : "", o->meta ? o->meta : "");
  fprintf(fp, "  %-26s %s\n", head, o->help);
}

static void help_command(FILE *fp, const cli_cmd *cmd) {
  fprintf(fp, "usage: dalembert %s %s [options]\n%s\n", cmd->name, cmd->operand, cmd->help);
  if (nrows(cmd->opts)) fprintf(fp, "\noptions:\n");
  for (int k = 0; k < nrows(cmd->opts); ++k)
    help_row(fp, &cmd->opts[k]);
  fprintf(fp, "\noptions of every command:\n");
  for (int k = 0; k < NCOMMON; ++k)
    help_row(fp, &common[k]);
  fprintf(fp, "\n%s", exit_help);
}

static void help_global(FILE *fp, const cli_cmd *commands) {
  fprintf(fp, "usage: dalembert COMMAND SCENE [options]   (dalembert COMMAND --help: its options)\n"
              "       dalembert --help | --version\n\ncommands:\n");
  for (const cli_cmd *k = commands; k->name; ++k)
    fprintf(fp, "  %-11s %s\n", k->name, k->help);
  fprintf(fp, "\noptions of every command:\n");
  for (int k = 0; k < NCOMMON; ++k)
    help_row(fp, &common[k]);
  fprintf(fp, "\n%s", exit_help);
}

// the commands owning option `name` (the long name, or the letter when letter is set) as "a, b"
static void owners(const cli_cmd *commands, const char *name, int letter, char *buf, size_t len) {
  buf[0] = 0;
  for (const cli_cmd *k = commands; k->name; ++k)
    for (int r = 0; r < nrows(k->opts); ++r)
      if (letter ? k->opts[r].short_name == letter : !strcmp(k->opts[r].name, name)) {
        size_t u = strlen(buf);
        snprintf(buf + u, len - u, "%s%s", u ? ", " : "", k->name);
        break;
      }
}

// getopt_long refused argv word `word` (short option letter `letter` when it was one)
static int refuse(const cli *c, const cli_cmd *commands, const char *word, int letter) {
  char name[64], who[256];
  if (letter)
    snprintf(name, sizeof name, "%c", letter);
  else
    snprintf(name, sizeof name, "%.*s", (int)strcspn(word + 2, "="), word + 2);
  owners(commands, name, letter, who, sizeof who);
  int prefix = 0; // an abbreviation of two or more of its options
  for (int k = 0; !letter && k < nrows(c->cmd->opts) + NCOMMON; ++k) {
    const char *o =
        k < nrows(c->cmd->opts) ? c->cmd->opts[k].name : common[k - nrows(c->cmd->opts)].name;
    prefix += !strncmp(o, name, strlen(name));
  }
  if (prefix > 1)
    fprintf(
        stderr,
        "dalembert %s: '--%s' is short for more than one of its options (dalembert %s --help)\n",
        c->cmd->name, name, c->cmd->name);
  else if (who[0])
    fprintf(stderr, "dalembert %s: %s%s is an option of %s, not of %s (dalembert %s --help)\n",
            c->cmd->name, letter ? "-" : "--", name, who, c->cmd->name, c->cmd->name);
  else
    fprintf(stderr, "dalembert %s: unknown option '%s%s' (dalembert %s --help lists its options)\n",
            c->cmd->name, letter ? "-" : "", letter ? name : word, c->cmd->name);
  return CLI_USAGE;
}

// the value of row o as its kind requires
static int check_value(const cli *c, const cli_opt *o, const char *v, double *x) {
  if (o->kind == CLI_FLAG || o->kind == CLI_TEXT) return 0;
  if (o->kind == CLI_CHOICE) {
    size_t n = strlen(v);
    for (const char *w = o->meta; w && *w; w += strcspn(w, "|"), w += *w == '|')
      if (n && strcspn(w, "|") == n && !strncmp(w, v, n)) return 0;
    fprintf(stderr, "dalembert %s: --%s %s: one of %s\n", c->cmd->name, o->name, v, o->meta);
    return CLI_USAGE;
  }
  char *end;
  *x = strtod(v, &end);
  int ok = end != v && !*end && isfinite(*x);
  const char *need = "a finite number";
  if (o->kind == CLI_POSITIVE) ok = ok && *x > 0, need = "a number > 0";
  if (o->kind == CLI_NONNEG) ok = ok && *x >= 0, need = "a number >= 0";
  if (o->kind == CLI_COUNT) {
    ok = ok && *x >= 0 && *x <= o->max && *x == floor(*x);
    need = "an integer";
  }
  if (ok) return 0;
  if (o->kind == CLI_COUNT)
    fprintf(stderr, "dalembert %s: --%s %s: %s from 0 to %d\n", c->cmd->name, o->name, v, need,
            o->max);
  else
    fprintf(stderr, "dalembert %s: --%s %s: %s\n", c->cmd->name, o->name, v, need);
  return CLI_USAGE;
}

static const cli_cmd *find_command(const cli_cmd *commands, const char *name) {
  for (const cli_cmd *k = commands; k->name; ++k)
    if (!strcmp(k->name, name)) return k;
  return NULL;
}

static int unknown_command(const cli_cmd *commands, const char *word) {
  fprintf(stderr, "dalembert: unknown command '%s' (commands:", word);
  for (const cli_cmd *k = commands; k->name; ++k)
    fprintf(stderr, " %s", k->name);
  fprintf(stderr, "; dalembert --help)\n");
  return CLI_USAGE;
}

// the words before a command: --help, --version, help [COMMAND]
static int global(const cli_cmd *commands, int argc, char **argv, int *done) {
  *done = 1;
  if (argc < 2) {
    fprintf(stderr, "dalembert: no command (dalembert --help lists them)\n");
    return CLI_USAGE;
  }
  const char *w = argv[1];
  if (!strcmp(w, "--version") || !strcmp(w, "-V")) {
    printf("dalembert %d.%d.%d\n", DAL_VERSION_MAJOR, DAL_VERSION_MINOR, DAL_VERSION_PATCH);
    return 0;
  }
  if (!strcmp(w, "--help") || !strcmp(w, "-h") || (!strcmp(w, "help") && argc == 2)) {
    help_global(stdout, commands);
    return 0;
  }
  if (!strcmp(w, "help")) {
    const cli_cmd *k = find_command(commands, argv[2]);
    if (!k) return unknown_command(commands, argv[2]);
    help_command(stdout, k);
    return 0;
  }
  if (w[0] == '-') {
    fprintf(stderr, "dalembert: unknown option '%s' before the command (dalembert --help)\n", w);
    return CLI_USAGE;
  }
  if (!find_command(commands, w)) return unknown_command(commands, w);
  *done = 0;
  return 0;
}

// getopt_long's table and short-option string from the command's rows and the common ones
static void build(const cli_cmd *cmd, struct option *lo, char *so) {
  int n = 0, s = 0;
  so[s++] = '-'; // operands in place, as code 1
  so[s++] = ':'; // a missing value as ':'
  for (int pass = 0; pass < 2; ++pass) {
    const cli_opt *t = pass ? common : cmd->opts;
    for (int k = 0; k < nrows(t); ++k) {
      int arg = t[k].kind == CLI_FLAG ? no_argument : required_argument;
      int code = (pass ? COMMON : ROW) + k;
      lo[n++] = (struct option){t[k].name, arg, NULL, code};
      if (t[k].short_name) {
        so[s++] = t[k].short_name;
        if (arg == required_argument) so[s++] = ':';
      }
    }
  }
  lo[n] = (struct option){NULL, 0, NULL, 0};
  so[s] = 0;
}

// the getopt code of short option letter ch
static int short_code(const cli_cmd *cmd, int ch) {
  for (int k = 0; k < nrows(cmd->opts); ++k)
    if (cmd->opts[k].short_name == ch) return ROW + k;
  for (int k = 0; k < NCOMMON; ++k)
    if (common[k].short_name == ch) return COMMON + k;
  return -1;
}

// one option row given with value v (NULL for a flag)
static int take(cli *c, int code, const char *v, int *help) {
  if (code >= COMMON) {
    switch (code - COMMON) {
    case COMMON_SET:
      c->sets[c->nsets++] = v;
      break;
    case COMMON_NATIVE:
      c->native = 1;
      break;
    case COMMON_PROGRESS:
      c->progress = 1;
      break;
    case COMMON_NO_PROGRESS:
      c->progress = 0;
      break;
    default:
      *help = 1;
    }
    return 0;
  }
  int k = code - ROW;
  c->given[k]++;
  c->val[k] = v ? v : "";
  return v ? check_value(c, &c->cmd->opts[k], v, &c->num[k]) : 0;
}

int cli_parse(cli *c, const cli_cmd *commands, int argc, char **argv, int *done) {
  int rc = global(commands, argc, argv, done);
  if (*done) return rc;
  *done = 1;
  c->cmd = find_command(commands, argv[1]);
  if (nrows(c->cmd->opts) > CLI_MAXOPT) {
    fprintf(stderr, "dalembert %s: more than %d options in its table\n", c->cmd->name, CLI_MAXOPT);
    return CLI_USAGE;
  }
  c->sets = calloc((size_t)argc, sizeof *c->sets);
  if (!c->sets) return cli_exit(DAL_E_NOMEM);
  struct option lo[CLI_MAXOPT + NCOMMON + 1];
  char so[3 * (CLI_MAXOPT + NCOMMON) + 3];
  build(c->cmd, lo, so);
  int help = 0, nops = 0, ch;
  const char *extra = NULL;
  char **av = argv + 1; // the command as getopt's argv[0]
  int ac = argc - 1;
  opterr = 0;
  optind = 1;
  while (!rc && (ch = getopt_long(ac, av, so, lo, NULL)) != -1) {
    if (ch == 1) {
      if (nops++ == 0)
        c->path = optarg;
      else if (!extra)
        extra = optarg;
    } else if (ch == ':') {
      const char *w = av[optind - 1];
      int code = optopt >= ROW ? optopt : optopt ? short_code(c->cmd, optopt) : -1;
      const cli_opt *o = code >= COMMON ? &common[code - COMMON]
                         : code >= ROW  ? &c->cmd->opts[code - ROW]
                                        : NULL;
      fprintf(stderr, "dalembert %s: %s needs a value%s%s\n", c->cmd->name, w, o ? " " : "",
              o ? o->meta : "");
      rc = CLI_USAGE;
    } else if (ch == '?' && optopt >= ROW) {
      rc = cli_error(c, CLI_USAGE, "%.*s takes no value", (int)strcspn(av[optind - 1], "="),
                     av[optind - 1]);
    } else if (ch == '?') {
      rc = refuse(c, commands, optopt ? "" : av[optind - 1], optopt);
    } else {
      rc = take(c, ch < ROW ? short_code(c->cmd, ch) : ch, optarg, &help);
    }
  }
  for (int k = optind; k < ac && !rc; ++k) // after "--"
    if (nops++ == 0)
      c->path = av[k];
    else if (!extra)
      extra = av[k];
  if (rc) return rc;
  if (help) {
    help_command(stdout, c->cmd);
    return 0;
  }
  if (!c->path) {
    fprintf(stderr, "dalembert %s: needs %s (dalembert %s --help)\n", c->cmd->name, c->cmd->operand,
            c->cmd->name);
    return CLI_USAGE;
  }
  if (extra) {
    fprintf(stderr, "dalembert %s: unexpected word '%s' (one %s only; dalembert %s --help)\n",
            c->cmd->name, extra, c->cmd->operand, c->cmd->name);
    return CLI_USAGE;
  }
  *done = 0;
  return 0;
}

static int row_of(const cli *c, const char *name) {
  for (int k = 0; c->cmd && k < nrows(c->cmd->opts); ++k)
    if (!strcmp(c->cmd->opts[k].name, name)) return k;
  return -1;
}

int cli_given(const cli *c, const char *name) {
  int k = row_of(c, name);
  return k < 0 ? 0 : c->given[k];
}

const char *cli_text(const cli *c, const char *name) {
  int k = row_of(c, name);
  return k < 0 ? NULL : c->val[k];
}

double cli_num(const cli *c, const char *name, double dflt) {
  int k = row_of(c, name);
  return k < 0 || !c->given[k] ? dflt : c->num[k];
}

int cli_set_params(const cli *c, dal_scene *sc, char *msg, size_t len) {
  for (int k = 0; k < c->nsets; ++k) {
    const char *arg = c->sets[k], *eq = strchr(arg, '=');
    char name[256], *end;
    if (!eq || eq == arg || (size_t)(eq - arg) >= sizeof name)
      return cli_error(c, CLI_USAGE, "--set '%s' is not NAME=VALUE", arg);
    snprintf(name, sizeof name, "%.*s", (int)(eq - arg), arg);
    double v = strtod(eq + 1, &end);
    if (end == eq + 1 || *end)
      return cli_error(c, CLI_USAGE, "--set %s: '%s' is not a number", name, eq + 1);
    int rc = dal_scene_set_param(sc, name, v, msg, len);
    if (rc) return rc;
  }
  if (len) msg[0] = 0;
  if (!c->native) return DAL_OK;
  int rc = dal_scene_native(sc, NULL, msg, len);
  // honoured, or said why not: a note in msg for the caller to print once
  if (!rc && len && !msg[0] && !dal_codegen_eom_attached(dal_scene_system(sc)))
    snprintf(msg, len, "%s",
             dal_scene_nexprs(sc) ? "the formulas run native code; the equations of motion are "
                                    "not compiled"
                                  : "nothing to compile: the scene has no formulas (its built-in "
                                    "primitives are C already)");
  return rc;
}

int cli_json_asked(const cli *c) {
  const char *f = cli_text(c, "format");
  return f && !strcmp(f, "json");
}

int cli_exit(int rc) { return rc < 0 ? -rc : 0; }

int cli_error(const cli *c, int rc, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  fprintf(stderr, "dalembert%s%s: ", c->cmd ? " " : "", c->cmd ? c->cmd->name : "");
  vfprintf(stderr, fmt, ap);
  fputc('\n', stderr);
  va_end(ap);
  return rc;
}

int cli_fail(const cli *c, int rc, const char *msg) {
  if (rc < 0) cli_error(c, rc, "%s", msg);
  return rc;
}

void cli_progress(const cli *c, const char *what, double done, double total, const char *extra) {
  static double last = -1; // the fraction shown last: a line every 0.5% (calls are serialized)
  if (!c->progress) return;
  double f = total > 0 ? done / total : 1;
  if (f < 1 && last >= 0 && f - last < 0.005 && f >= last) return;
  last = f >= 1 ? -1 : f;
  fprintf(stderr, "\r%s: %.4g / %.4g%s%s   ", what, done, total, extra ? " " : "",
          extra ? extra : "");
  if (done >= total) fputc('\n', stderr);
  fflush(stderr);
}

int cli_open(const cli *c, const char *path, cli_file *f) {
  *f = (cli_file){path ? NULL : stdout, path, NULL, 0};
  if (!path) return DAL_OK;
  // a plain file (or a new one) is written under a temporary name beside it
  struct stat sb;
  if (stat(path, &sb) != 0 || S_ISREG(sb.st_mode)) {
    size_t len = strlen(path) + 16;
    f->tmp = malloc(len);
    if (!f->tmp) return cli_error(c, DAL_E_NOMEM, "out of memory for the name of %s", path);
    snprintf(f->tmp, len, "%s.partXXXXXX", path);
    int fd = mkstemp(f->tmp);
    if (fd < 0) { // a folder we cannot write beside the file: the file itself, in place
      free(f->tmp);
      f->tmp = NULL;
      f->fp = fopen(path, "w");
      f->in_place = 1;
      if (!f->fp) return cli_error(c, DAL_E_IO, "cannot write %s (%s)", path, strerror(errno));
      return DAL_OK;
    }
    mode_t mask = umask(0);
    umask(mask);
    if (fchmod(fd, 0666 & ~mask) != 0 || !(f->fp = fdopen(fd, "w"))) {
      int e = errno;
      close(fd);
      remove(f->tmp);
      free(f->tmp);
      f->tmp = NULL;
      return cli_error(c, DAL_E_IO, "cannot write %s (%s)", path, strerror(e));
    }
    return DAL_OK;
  }
  // a device or a pipe: written in place
  f->fp = fopen(path, "w");
  if (!f->fp) return cli_error(c, DAL_E_IO, "cannot write %s (%s)", path, strerror(errno));
  return DAL_OK;
}

int cli_commit(const cli *c, cli_file *f, int rc) {
  if (!f->fp) return rc;
  const char *name = f->path ? f->path : "standard output";
  errno = 0;
  int bad = fflush(f->fp) != 0 || ferror(f->fp);
  int e = errno;
  if (f->fp != stdout && fclose(f->fp) != 0 && !bad) bad = 1, e = errno;
  f->fp = NULL;
  if (bad)
    cli_error(c, DAL_E_IO, "writing %s failed (%s)%s", name, e ? strerror(e) : "write error",
              f->tmp ? "; nothing written there" : "");
  if (bad && !f->path) clearerr(stdout); // said once
  if (f->in_place && (bad || rc < 0)) {
    remove(f->path); // truncated and half-written: not left as if complete
    if (!bad) cli_error(c, rc, "%s not written (the command failed)", f->path);
  }
  if (f->tmp) {
    if (bad || rc < 0) {
      remove(f->tmp);
      if (!bad) cli_error(c, rc, "%s not written (the command failed)", f->path);
    } else if (rename(f->tmp, f->path) != 0) {
      e = errno;
      remove(f->tmp);
      bad = 1;
      cli_error(c, DAL_E_IO, "cannot write %s (%s)", f->path, strerror(e));
    }
    free(f->tmp);
    f->tmp = NULL;
  }
  return bad && rc >= 0 ? DAL_E_IO : rc;
}

FILE *cli_out(cli *c) { return cli_open(c, cli_text(c, "output"), &c->out) ? NULL : c->out.fp; }

int cli_close(cli *c, int rc) { return cli_commit(c, &c->out, rc); }

char *cli_read_text(const cli *c, const char *path) {
  FILE *fp = fopen(path, "rb");
  if (!fp) {
    cli_error(c, DAL_E_IO, "%s: cannot open (%s)", path, strerror(errno));
    return NULL;
  }
  size_t cap = 4096, n = 0;
  char *buf = malloc(cap);
  for (size_t k; buf && (k = fread(buf + n, 1, cap - n - 1, fp)) > 0;) {
    n += k;
    if (n + 1 < cap) continue;
    char *nb = cap < ((size_t)1 << 30) ? realloc(buf, 2 * cap) : NULL;
    if (!nb) free(buf);
    buf = nb;
    cap *= 2;
  }
  int bad = ferror(fp);
  fclose(fp);
  if (!buf || bad) {
    free(buf);
    cli_error(c, DAL_E_IO, "%s: cannot read (%s)", path, bad ? "read error" : "too large");
    return NULL;
  }
  buf[n] = 0;
  return buf;
}

// the flag SIGINT sets: the one mutable global of the command line, as a handler needs
static volatile sig_atomic_t interrupted;

static void on_sigint(int sig) {
  (void)sig;
  interrupted = 1;
}

void cli_catch_interrupt(void) {
  struct sigaction sa, old;
  // an interrupt ignored by the parent (nohup, a background job) stays ignored
  if (sigaction(SIGINT, NULL, &old) == 0 && old.sa_handler == SIG_IGN) return;
  memset(&sa, 0, sizeof sa);
  sa.sa_handler = on_sigint;
  sa.sa_flags = SA_RESETHAND; // a second Ctrl-C ends the process at once
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, NULL);
}

int cli_interrupted(void) { return interrupted != 0; }

int cli_cancel(void *ctx) {
  (void)ctx;
  return interrupted != 0;
}

void cli_note(const cli *c, const dal_state *st) {
  const char *m = st ? dal_state_errmsg(st) : "";
  if (m && *m) cli_error(c, 0, "%s%s", strncmp(m, "note", 4) ? "note: " : "", m);
}

int cli_grid(const cli *c, const char *opt, const char *spec, char *buf, size_t len, double *lo,
             double *hi, int *n) {
  snprintf(buf, len, "%s", spec ? spec : "");
  char *eq = strchr(buf, '='), *end;
  long count = 0;
  int ok =
      eq && eq != buf && sscanf(eq + 1, "%lf:%lf:", lo, hi) == 2 && isfinite(*lo) && isfinite(*hi);
  const char *last = ok ? strrchr(eq + 1, ':') : NULL;
  if (ok) {
    errno = 0;
    count = strtol(last + 1, &end, 10);
    ok = end != last + 1 && !*end && count >= 1;
  }
  if (!ok)
    return cli_error(c, CLI_USAGE, "--%s '%s' is not NAME=LO:HI:N (finite LO and HI, N >= 1)", opt,
                     spec ? spec : "");
  if (errno == ERANGE || count > CLI_GRID_MAX)
    return cli_error(c, CLI_USAGE, "--%s '%s': %s points are too many (at most %d)", opt, spec,
                     last + 1, CLI_GRID_MAX);
  *n = (int)count;
  *eq = 0;
  return DAL_OK;
}
