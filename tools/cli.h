// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The command line's shared parts: the option and command tables, the parsed options, and the
// services every command uses (messages, progress, output files, grids).
//
// A command is one row of the command table in dalembert.c ({name, function, options, operands,
// one-line help}) and its own file: the function `int cli_<name>(cli *c)` and its options table
// `const cli_opt cli_<name>_opts[]` (ended by CLI_END), declared here with CLI_COMMAND(name).
// The parser (cli.c) builds getopt_long's table from it, refuses an option the command does not
// own (naming the commands that own it), checks every value against its row (a number, > 0,
// an integer in range) and prints the command's --help from the same rows. A command reads its
// options by their long name: cli_given, cli_text, cli_num.
//
// Exit status (cli_exit): 0 success (a run a terminal event stopped included); 1 ... 17 the
// library's failure status negated (1 invalid argument, 4 domain error, 11 convergence,
// 15 unsupported, 16 a write or read failed (standard output included), ...: dalembert/base.h);
// 64 a command line it does not understand; 130 interrupted (Ctrl-C).
#ifndef DAL_TOOLS_CLI_H
#define DAL_TOOLS_CLI_H

#include <stdio.h>

#include "dalembert/dalembert.h"
#include "dalembert/scene.h"

// exit statuses of the command line beside the library's (minus its status)
enum { CLI_USAGE = 64, CLI_INTERRUPTED = 130 };
// an options table holds at most this many rows
enum { CLI_MAXOPT = 32 };

// what an option takes, checked by the parser before the command runs
typedef enum cli_kind {
  CLI_FLAG,     // no value
  CLI_TEXT,     // any text
  CLI_REAL,     // a finite number
  CLI_POSITIVE, // a finite number > 0
  CLI_NONNEG,   // a finite number >= 0
  CLI_COUNT,    // an integer 0 ... max
  CLI_CHOICE,   // one of the words of meta, "csv|json"
} cli_kind;

// one option of a command: --name [value] (and -s when short is set)
typedef struct cli_opt {
  const char *name; // the long name without "--"; NULL ends a table (CLI_END)
  char short_name;  // one letter or 0
  cli_kind kind;
  const char *meta; // the value's placeholder in the help ("FILE.csv", "T")
  const char *help; // one line
  int max;          // CLI_COUNT: the largest value
} cli_opt;

#define CLI_END                                                                                    \
  { NULL, 0, CLI_FLAG, NULL, NULL, 0 }

typedef struct cli cli;
typedef int cli_fn(cli *c);

// one command: the row of the command table
typedef struct cli_cmd {
  const char *name;
  cli_fn *fn;
  const cli_opt *opts; // its options (CLI_END-terminated)
  const char *operand; // "SCENE": the one operand; a scene file is read (with --set) before fn
  const char *help;    // one line
} cli_cmd;

// an output: standard output, or a file written under a temporary name and renamed to its own
// when the command ends well (or is interrupted: its rows are whole), removed when it fails
typedef struct cli_file {
  FILE *fp;
  const char *path; // NULL: standard output
  char *tmp;        // the temporary file (NULL for stdout and for a path that is no plain file)
  int in_place;     // a plain file written in place (no temporary beside it): removed on failure
} cli_file;

// the parsed command line and the scene it names
struct cli {
  const cli_cmd *cmd;          // the command running
  const char *path;            // the scene file (its operand)
  char *text;                  // its text
  dal_scene *sc;               // read from it, --set applied
  int progress;                // the progress line on stderr
  int native;                  // --native: dal_scene_native after the --set values
  const char *val[CLI_MAXOPT]; // the value of each option row given (NULL: not given)
  double num[CLI_MAXOPT];      // ... as a number (numeric kinds)
  int given[CLI_MAXOPT];       // times given
  const char **sets;           // the --set NAME=VALUE texts, in order
  int nsets;
  cli_file out;   // -o FILE or stdout (cli_out)
  char msg[2048]; // the library's messages
};

// declares a command's function and its options table
#define CLI_COMMAND(x)                                                                             \
  int cli_##x(cli *c);                                                                             \
  extern const cli_opt cli_##x##_opts[]

CLI_COMMAND(run);
CLI_COMMAND(show);
CLI_COMMAND(write);
CLI_COMMAND(modes);
CLI_COMMAND(equilibria);
CLI_COMMAND(lyapunov);
CLI_COMMAND(section);
CLI_COMMAND(sweep);
CLI_COMMAND(floquet); // periodic.c
CLI_COMMAND(orbit);
CLI_COMMAND(view);
CLI_COMMAND(picture);
CLI_COMMAND(compile);

// the option rows shared by several commands
#define CLI_OPT_OUTPUT(what)                                                                       \
  { "output", 'o', CLI_TEXT, "FILE.csv", what " (default: stdout)", 0 }
#define CLI_OPT_WRAP                                                                               \
  { "wrap", 0, CLI_FLAG, NULL, "angles wrapped into [-pi, pi) (every coordinate taken as one)", 0 }
#define CLI_OPT_T1                                                                                 \
  { "t1", 0, CLI_POSITIVE, "T", "end time (default: the scene's t1)", 0 }
#define CLI_OPT_FROZEN                                                                             \
  { "frozen", 0, CLI_FLAG, NULL, "the linearization frozen at t0 of a time-dependent scene", 0 }
#define CLI_OPT_CHART(what)                                                                        \
  { "chart", 0, CLI_TEXT, "FILE.svg", what " (an SVG; docs/cli.md)", 0 }
#define CLI_OPT_FORMAT                                                                             \
  { "format", 0, CLI_CHOICE, "csv|json", "csv (default) or json (docs/cli.md: the schema)", 0 }

// --- parsing (cli.c) ---

// parse argv (argv[0] the program, argv[1] the command) into c; returns 0 to go on, or the
// exit status to leave with (0 after --help or --version, CLI_USAGE with a message naming the
// word it refused). `commands` ends with a row whose name is NULL.
int cli_parse(cli *c, const cli_cmd *commands, int argc, char **argv, int *done);

// the option `name` of the running command: times given (0 when not given or not its option)
int cli_given(const cli *c, const char *name);
// its text (NULL when not given)
const char *cli_text(const cli *c, const char *name);
// its number (dflt when not given)
double cli_num(const cli *c, const char *name, double dflt);
// apply the --set values to sc in their order: DAL_OK, CLI_USAGE (a malformed NAME=VALUE; said
// on stderr), or dal_scene_set_param's status (its message in msg)
int cli_set_params(const cli *c, dal_scene *sc, char *msg, size_t len);
// --format json given
int cli_json_asked(const cli *c);

// --- services (cli.c) ---

// the exit status of a library status rc (cli.h's table)
int cli_exit(int rc);
// print "dalembert <command>: msg" on stderr when rc < 0; returns rc
int cli_fail(const cli *c, int rc, const char *msg);
// print "dalembert <command>: ..." on stderr (printf-style); returns rc
int cli_error(const cli *c, int rc, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
// the progress line on stderr (when enabled): what, done of total, extra text
void cli_progress(const cli *c, const char *what, double done, double total, const char *extra);
// open an output (path NULL: standard output); DAL_E_IO with a message when it cannot be
int cli_open(const cli *c, const char *path, cli_file *f);
// end an output after the command's status rc: every write checked (fflush, ferror, fclose);
// a file renamed to its name when rc >= 0, removed when rc < 0 or a write failed. Returns rc,
// or DAL_E_IO (with a message) when a write failed and rc was not already an error.
int cli_commit(const cli *c, cli_file *f, int rc);
// -o FILE or stdout into c->out (NULL and a message when it cannot be opened)
FILE *cli_out(cli *c);
// cli_commit of c->out
int cli_close(cli *c, int rc);
// the scene file's text (NULL and a message naming it when it cannot be read)
char *cli_read_text(const cli *c, const char *path);

// Ctrl-C: the first SIGINT sets the flag (a second one ends the process); runs stop at their
// next step or output with whole rows, the command says where, and the exit status is 130
void cli_catch_interrupt(void);
int cli_interrupted(void);
// the cancel hook / monitor answer: nonzero once interrupted
int cli_cancel(void *ctx);

// a note the library left in the state's message after success, on stderr
void cli_note(const cli *c, const dal_state *st);
// NAME=LO:HI:N into its parts (name points into the copy buf of len bytes), 1 <= N <= CLI_GRID_MAX
enum { CLI_GRID_MAX = 10000000 };
int cli_grid(const cli *c, const char *opt, const char *spec, char *buf, size_t len, double *lo,
             double *hi, int *n);

// run the scene from its initial state to t1 (--t1 when the command owns it, else the scene's)
// with events ev (nullable) attached: a CSV row of dal_csv_monitor every dt to fp (nullable:
// none) and the progress line `what`
int cli_evolve(cli *c, FILE *fp, dal_events *ev, double dt, const char *what);

// --- charts (chart.c) ---

// a series of a chart's panel: the points (x[i stride], y[i stride]), i < n (a point not finite
// is left out), drawn as dots or as a line, with error bars +-err[i stride] (nullable)
typedef struct cli_series {
  const char *name; // the legend (nullable)
  const double *x, *y, *err;
  size_t n, stride;
  int line;
} cli_series;

// a panel: its title, axis labels and series
typedef struct cli_panel {
  const char *title, *xlabel, *ylabel;
  const cli_series *series;
  int nseries;
} cli_panel;

// the panels stacked into one SVG written to f (opened by cli_open; the caller commits it).
// Each panel states its map from data to px: <g class="panel" data-transform="[ax,bx,ay,by]">,
// px = ax + bx x, py = ay + by y; a dot is <circle cx cy>, a line <polyline points>, an error bar
// <line class="err">. Returns DAL_OK or DAL_E_IO (said).
int cli_chart(const cli *c, cli_file *f, const cli_panel *p, int np);

#endif
