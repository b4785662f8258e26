// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// A small JSON writer for the command line's --format json (one document per command, the
// schemas in docs/cli.md): objects and arrays nested, numbers as %.17g (null where not
// finite: JSON has no inf or NaN), strings escaped.
//
//   cli_json j = cli_json_start(stdout);       // {
//   cli_json_str(&j, "command", "modes");       //   "command": "modes",
//   cli_json_array(&j, "modes");                //   "modes": [
//   cli_json_object(&j, NULL);                  //     {
//   cli_json_num(&j, "omega2", 9.8);            //       "omega2": 9.8
//   cli_json_end(&j);                           //     }
//   cli_json_end(&j);                           //   ]
//   cli_json_finish(&j);                        // }  (and a newline)
#ifndef DAL_TOOLS_JSON_H
#define DAL_TOOLS_JSON_H

#include <stdio.h>

enum { CLI_JSON_DEPTH = 16 };

typedef struct cli_json {
  FILE *fp;
  int depth;                  // open containers
  int count[CLI_JSON_DEPTH];  // members written in each
  char close[CLI_JSON_DEPTH]; // '}' or ']'
} cli_json;

// the top-level object opened on fp
cli_json cli_json_start(FILE *fp);
// close every open container and end the line; returns ferror(fp) ? -1 : 0
int cli_json_finish(cli_json *j);
// a member `key` (NULL inside an array) that is an object / an array, left open
void cli_json_object(cli_json *j, const char *key);
void cli_json_array(cli_json *j, const char *key);
// close the innermost container
void cli_json_end(cli_json *j);
// members: a number (null when not finite), an integer, a string (NULL: null), a boolean
void cli_json_num(cli_json *j, const char *key, double v);
void cli_json_int(cli_json *j, const char *key, long v);
void cli_json_str(cli_json *j, const char *key, const char *s);
void cli_json_bool(cli_json *j, const char *key, int v);

#endif
