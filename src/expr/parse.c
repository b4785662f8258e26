// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The formula parser: recursive descent over + - * / ^ with unary signs, calls and names.
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "expr.h"

#define MAX_DEPTH 200

typedef struct parser {
  dal_xtree *tr;
  const char *s;
  size_t pos;
  int which, depth;
  const char *label;
  char *msg;
  size_t msglen;
  int failed;
} parser;

// the formula quoted for a message: at most 60 characters, with "..." when longer
static void quote(const parser *p, char *buf, size_t len) {
  size_t n = strlen(p->s);
  if (n > 60)
    snprintf(buf, len, "%.57s...", p->s);
  else
    snprintf(buf, len, "%s", p->s);
}

static int fail(parser *p, size_t col, const char *what) {
  if (!p->failed && p->msg && p->msglen) {
    char q[64];
    quote(p, q, sizeof q);
    if (p->label)
      snprintf(p->msg, p->msglen, "%s '%s', column %zu: %s", p->label, q, col + 1, what);
    else
      snprintf(p->msg, p->msglen, "formula %d '%s', column %zu: %s", p->which + 1, q, col + 1,
               what);
  }
  p->failed = 1;
  return -1;
}

static void skip(parser *p) {
  while (p->s[p->pos] == ' ' || p->s[p->pos] == '\t' || p->s[p->pos] == '\n' ||
         p->s[p->pos] == '\r')
    p->pos++;
}

static int mk(parser *p, int op, int a, int b, int idx, double c, size_t col) {
  if (a < -1 || b < -1) return -1;
  int n = dal__xnode(p->tr, op, a, b, idx, c);
  if (n < 0) {
    p->failed = 1;
    if (p->msg && p->msglen) snprintf(p->msg, p->msglen, "out of memory parsing a formula");
    return -2;
  }
  if (p->tr->node[n].src < 0) {
    p->tr->node[n].src = p->which;
    p->tr->node[n].col = (int)col + 1;
  }
  return n;
}

static int expr(parser *p);

static const char *const fn1[] = {"sin",  "cos",  "tan",  "asin", "acos", "atan",
                                  "sinh", "cosh", "tanh", "exp",  "log",  "sqrt"};

// a bad token, shown as the character found (or "end of formula")
static int unexpected(parser *p, const char *wanted) {
  char what[96];
  char c = p->s[p->pos];
  if (!c)
    snprintf(what, sizeof what, "%s expected, found the end of the formula", wanted);
  else if (isprint((unsigned char)c))
    snprintf(what, sizeof what, "%s expected, found '%c'", wanted, c);
  else
    snprintf(what, sizeof what, "%s expected, found byte 0x%02x", wanted, (unsigned char)c);
  return fail(p, p->pos, what);
}

// the arguments of a call: n expressions separated by commas, then ')'
static int args(parser *p, const char *fname, int n, int *out, size_t col) {
  for (int i = 0; i < n; ++i) {
    if (i) {
      skip(p);
      if (p->s[p->pos] != ',') {
        char w[96];
        snprintf(w, sizeof w, "',' (%s takes %d arguments)", fname, n);
        return unexpected(p, w);
      }
      p->pos++;
    }
    out[i] = expr(p);
    if (out[i] < 0) return -1;
  }
  skip(p);
  if (p->s[p->pos] != ')') {
    char w[96];
    snprintf(w, sizeof w, "')' closing %s( of column %zu", fname, col + 1);
    return unexpected(p, w);
  }
  p->pos++;
  return 0;
}

// a number, a name, a call or a parenthesized expression
// a number at s (column col): its extent scanned here (strtod would also take hex, inf and nan)
static int number(parser *p, const char *s, size_t col) {
  size_t n = 0;
  while (isdigit((unsigned char)s[n]))
    n++;
  if (s[n] == '.') {
    n++;
    while (isdigit((unsigned char)s[n]))
      n++;
  }
  if ((s[n] == 'e' || s[n] == 'E') &&
      (isdigit((unsigned char)s[n + 1]) ||
       ((s[n + 1] == '+' || s[n + 1] == '-') && isdigit((unsigned char)s[n + 2])))) {
    n += 2;
    while (isdigit((unsigned char)s[n]))
      n++;
  }
  char buf[64];
  if (n >= sizeof buf) return fail(p, col, "number too long");
  memcpy(buf, s, n);
  buf[n] = 0;
  double v = strtod(buf, NULL);
  if (!isfinite(v)) return fail(p, col, "number out of range");
  p->pos += n;
  return mk(p, X_NUM, -1, -1, 0, v, col);
}

// a call of function `name` (the '(' taken)
static int call(parser *p, const char *name, size_t col) {
  int x[2];
  for (int i = 0; i < (int)(sizeof fn1 / sizeof fn1[0]); ++i)
    if (!strcmp(name, fn1[i])) {
      if (args(p, name, 1, x, col)) return -1;
      return mk(p, X_SIN + i, x[0], -1, 0, 0.0, col);
    }
  int op = !strcmp(name, "atan2")   ? X_ATAN2
           : !strcmp(name, "hypot") ? X_HYPOT
           : !strcmp(name, "pow")   ? X_POW
                                    : -1;
  if (op < 0) {
    char w[160];
    snprintf(w, sizeof w,
             "unknown function '%s' (sin cos tan asin acos atan sinh cosh tanh exp log "
             "sqrt atan2 hypot pow)",
             name);
    return fail(p, col, w);
  }
  if (args(p, name, 2, x, col)) return -1;
  return mk(p, op, x[0], x[1], 0, 0.0, col);
}

// a name: an input, a parameter, t or pi
static int symbol(parser *p, const char *name, size_t col) {
  for (int i = 0; i < p->tr->nin + p->tr->nparam; ++i)
    if (!strcmp(name, p->tr->names[i]))
      return i < p->tr->nin ? mk(p, X_IN, -1, -1, i, 0.0, col)
                            : mk(p, X_PAR, -1, -1, i - p->tr->nin, 0.0, col);
  if (!strcmp(name, "t")) return mk(p, X_TIME, -1, -1, 0, 0.0, col);
  if (!strcmp(name, "pi")) return mk(p, X_NUM, -1, -1, 0, 3.14159265358979323846, col);
  char w[512];
  int k = snprintf(w, sizeof w, "unknown symbol '%s' (known:", name);
  for (int i = 0; i < p->tr->nin + p->tr->nparam && k < (int)sizeof w - 80; ++i)
    k += snprintf(w + k, sizeof w - (size_t)k, " %s", p->tr->names[i]);
  if (k < (int)sizeof w) snprintf(w + k, sizeof w - (size_t)k, " t pi)");
  return fail(p, col, w);
}

static int primary(parser *p) {
  skip(p);
  size_t col = p->pos;
  const char *s = p->s + p->pos;
  if (isdigit((unsigned char)*s) || (*s == '.' && isdigit((unsigned char)s[1])))
    return number(p, s, col);
  if (isalpha((unsigned char)*s) || *s == '_') {
    size_t n = 0;
    while (isalnum((unsigned char)s[n]) || s[n] == '_')
      n++;
    p->pos += n;
    skip(p);
    char name[64];
    if (n >= sizeof name) return fail(p, col, "name longer than 63 characters");
    memcpy(name, s, n);
    name[n] = 0;
    if (p->s[p->pos] != '(') return symbol(p, name, col);
    p->pos++;
    return call(p, name, col);
  }
  if (*s == '(') {
    p->pos++;
    int x = expr(p);
    if (x < 0) return -1;
    skip(p);
    if (p->s[p->pos] != ')') {
      char w[64];
      snprintf(w, sizeof w, "')' closing the '(' of column %zu", col + 1);
      return unexpected(p, w);
    }
    p->pos++;
    return x;
  }
  return unexpected(p, "a number, a name or '('");
}

static int unary(parser *p);

// primary ('^' unary)?: right-associative, the exponent may carry a sign
static int power(parser *p) {
  int a = primary(p);
  if (a < 0) return a;
  skip(p);
  size_t col = p->pos;
  int two = p->s[p->pos] == '*' && p->s[p->pos + 1] == '*';
  if (p->s[p->pos] == '^' || two) {
    p->pos += two ? 2 : 1;
    int b = unary(p);
    if (b < 0) return b;
    return mk(p, X_POW, a, b, 0, 0.0, col);
  }
  return a;
}

static int unary(parser *p) {
  skip(p);
  size_t col = p->pos;
  char c = p->s[p->pos];
  if (c == '-' || c == '+') {
    if (++p->depth > MAX_DEPTH) return fail(p, col, "formula nested more than 200 deep");
    p->pos++;
    int a = unary(p);
    p->depth--;
    if (a < 0 || c == '+') return a;
    return mk(p, X_NEG, a, -1, 0, 0.0, col);
  }
  if (++p->depth > MAX_DEPTH) return fail(p, col, "formula nested more than 200 deep");
  int r = power(p);
  p->depth--;
  return r;
}

// the operator at the parser's position joining two operands on level 1 (* and /; '**' and '/*' are
// not) or level 0 (+ and -); -1 for none
static int binary_op(const parser *p, int level) {
  char c = p->s[p->pos];
  if (!level) return c == '+' ? X_ADD : c == '-' ? X_SUB : -1;
  if ((c != '*' && c != '/') || p->s[p->pos + 1] == '*') return -1;
  return c == '*' ? X_MUL : X_DIV;
}

// a left-associative chain of operands: terms (level 1: unary operands joined by * and /) and
// the expression (level 0: terms joined by + and -)
static int chain(parser *p, int level) {
  int a = level ? unary(p) : chain(p, 1);
  while (a >= 0) {
    skip(p);
    size_t col = p->pos;
    int op = binary_op(p, level);
    if (op < 0) break;
    p->pos++;
    int b = level ? unary(p) : chain(p, 1);
    if (b < 0) return b;
    a = mk(p, op, a, b, 0, 0.0, col);
  }
  return a;
}

static int expr(parser *p) { return chain(p, 0); }

int dal__xparse(dal_xtree *tr, const char *text, int which, const char *label, int *root, char *msg,
                size_t msglen) {
  parser p = {tr, text, 0, which, 0, label, msg, msglen, 0};
  int r = expr(&p);
  if (r >= 0) {
    skip(&p);
    if (text[p.pos]) r = unexpected(&p, "an operator");
  }
  if (r < 0 || p.failed) {
    if (!p.failed) fail(&p, p.pos, "syntax error");
    return r == -2 ? DAL_E_NOMEM : DAL_E_ARG;
  }
  *root = r;
  return DAL_OK;
}
