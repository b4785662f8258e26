// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The analyses' --chart: an SVG of panels of points, lines and error bars, written by the command
// itself (no gnuplot), each panel declaring its data -> px map for the tests (cli.h: cli_chart).
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cli.h"

enum { PANEL_W = 640, PANEL_H = 360, LEFT = 78, RIGHT = 20, TOP = 34, BOTTOM = 46 };

static const char *const palette[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd",
                                      "#ff7f0e", "#8c564b", "#17becf"};

// text with <, >, & and " escaped
static void put_text(FILE *fp, const char *s) {
  for (; s && *s; ++s)
    if (*s == '<')
      fputs("&lt;", fp);
    else if (*s == '>')
      fputs("&gt;", fp);
    else if (*s == '&')
      fputs("&amp;", fp);
    else if (*s == '"')
      fputs("&quot;", fp);
    else
      fputc(*s, fp);
}

// a tick spacing of 1, 2 or 5 times a power of ten giving about 6 ticks over [lo, hi]
static double tick_step(double lo, double hi) {
  double raw = (hi - lo) / 6, p = pow(10, floor(log10(raw))), m = raw / p;
  return p * (m < 1.5 ? 1 : m < 3.5 ? 2 : m < 7.5 ? 5 : 10);
}

// the range of the finite values of a panel's x (axis 0) or y (axis 1, error bars included),
// widened by 5% (a single value: +-1 or +-5% of it)
static void range(const cli_panel *p, int axis, double *lo, double *hi) {
  *lo = INFINITY, *hi = -INFINITY;
  for (int s = 0; s < p->nseries; ++s) {
    const cli_series *se = &p->series[s];
    for (size_t i = 0; i < se->n; ++i) {
      double x = se->x[i * se->stride], y = se->y[i * se->stride];
      double e = axis && se->err ? fabs(se->err[i * se->stride]) : 0, v = axis ? y : x;
      if (!isfinite(x) || !isfinite(y) || !isfinite(e)) continue;
      *lo = fmin(*lo, v - e), *hi = fmax(*hi, v + e);
    }
  }
  if (!(*lo <= *hi)) *lo = 0, *hi = 1;
  double pad = *hi > *lo ? 0.05 * (*hi - *lo) : fmax(1e-300, 0.05 * fabs(*lo));
  if (!(*hi > *lo) && *lo == 0) pad = 1;
  *lo -= pad, *hi += pad;
}

static void panel(FILE *fp, const cli_panel *p, double y0) {
  double xlo, xhi, ylo, yhi;
  range(p, 0, &xlo, &xhi);
  range(p, 1, &ylo, &yhi);
  // px = ax + bx x, py = ay + by y (y up)
  double bx = (PANEL_W - LEFT - RIGHT) / (xhi - xlo), ax = LEFT - bx * xlo;
  double by = -(PANEL_H - TOP - BOTTOM) / (yhi - ylo), ay = y0 + PANEL_H - BOTTOM - by * ylo;
  fprintf(fp, "<g class=\"panel\" data-title=\"");
  put_text(fp, p->title);
  fprintf(fp, "\" data-transform=\"[%.17g,%.17g,%.17g,%.17g]\">\n", ax, bx, ay, by);
  fprintf(fp,
          "<rect x=\"%d\" y=\"%.1f\" width=\"%d\" height=\"%d\" fill=\"none\" stroke=\"#888\"/>\n",
          LEFT, y0 + TOP, PANEL_W - LEFT - RIGHT, PANEL_H - TOP - BOTTOM);
  // ticks and their labels
  for (int axis = 0; axis < 2; ++axis) {
    double lo = axis ? ylo : xlo, hi = axis ? yhi : xhi, st = tick_step(lo, hi);
    for (double v = ceil(lo / st) * st; v <= hi; v += st) {
      double at = axis ? ay + by * v : ax + bx * v, tv = fabs(v) < 1e-9 * st ? 0 : v;
      if (axis)
        fprintf(fp,
                "<line x1=\"%d\" y1=\"%.2f\" x2=\"%d\" y2=\"%.2f\" stroke=\"#888\"/><text x=\"%d\" "
                "y=\"%.2f\" text-anchor=\"end\" font-size=\"11\">%.4g</text>\n",
                LEFT - 4, at, LEFT, at, LEFT - 6, at + 4, tv);
      else
        fprintf(fp,
                "<line x1=\"%.2f\" y1=\"%.1f\" x2=\"%.2f\" y2=\"%.1f\" stroke=\"#888\"/><text "
                "x=\"%.2f\" y=\"%.1f\" text-anchor=\"middle\" font-size=\"11\">%.4g</text>\n",
                at, y0 + PANEL_H - BOTTOM, at, y0 + PANEL_H - BOTTOM + 4, at,
                y0 + PANEL_H - BOTTOM + 17, tv);
    }
  }
  fprintf(fp, "<text x=\"%d\" y=\"%.1f\" font-size=\"13\">", LEFT, y0 + TOP - 10);
  put_text(fp, p->title);
  fprintf(fp, "</text>\n<text x=\"%d\" y=\"%.1f\" text-anchor=\"middle\" font-size=\"12\">",
          (LEFT + PANEL_W - RIGHT) / 2, y0 + PANEL_H - 10);
  put_text(fp, p->xlabel);
  fprintf(fp,
          "</text>\n<text x=\"16\" y=\"%.1f\" text-anchor=\"middle\" font-size=\"12\" "
          "transform=\"rotate(-90 16 %.1f)\">",
          y0 + (TOP + PANEL_H - BOTTOM) / 2.0, y0 + (TOP + PANEL_H - BOTTOM) / 2.0);
  put_text(fp, p->ylabel);
  fputs("</text>\n", fp);
  // the series: points, a line, error bars; a legend line per named series
  for (int s = 0; s < p->nseries; ++s) {
    const cli_series *se = &p->series[s];
    const char *col = palette[s % 7];
    fprintf(fp, "<g class=\"series\" data-name=\"");
    put_text(fp, se->name);
    fprintf(fp, "\" fill=\"%s\" stroke=\"%s\">\n", col, col);
    if (se->line) fputs("<polyline fill=\"none\" points=\"", fp);
    for (size_t i = 0; i < se->n; ++i) {
      double x = se->x[i * se->stride], y = se->y[i * se->stride];
      double e = se->err ? se->err[i * se->stride] : 0;
      if (!isfinite(x) || !isfinite(y)) continue;
      double px = ax + bx * x, py = ay + by * y;
      if (se->line)
        fprintf(fp, "%.3f,%.3f ", px, py);
      else
        fprintf(fp, "<circle cx=\"%.3f\" cy=\"%.3f\" r=\"%g\" stroke=\"none\"/>\n", px, py,
                se->n > 2000 ? 0.8 : 2.0);
      if (!se->line && se->err && isfinite(e))
        fprintf(fp, "<line class=\"err\" x1=\"%.3f\" y1=\"%.3f\" x2=\"%.3f\" y2=\"%.3f\"/>\n", px,
                ay + by * (y - e), px, ay + by * (y + e));
    }
    if (se->line) fputs("\"/>\n", fp);
    if (se->name) {
      fprintf(fp, "<text x=\"%d\" y=\"%.1f\" text-anchor=\"end\" font-size=\"11\" stroke=\"none\">",
              PANEL_W - RIGHT - 4, y0 + TOP + 14 + 13.0 * s);
      put_text(fp, se->name);
      fputs("</text>\n", fp);
    }
    fputs("</g>\n", fp);
  }
  fputs("</g>\n", fp);
}

int cli_chart(const cli *c, cli_file *f, const cli_panel *p, int np) {
  FILE *fp = f->fp;
  fprintf(fp,
          "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\" viewBox=\"0 0 %d "
          "%d\" font-family=\"sans-serif\">\n<rect width=\"100%%\" height=\"100%%\" "
          "fill=\"#fff\"/>\n",
          PANEL_W, PANEL_H * np, PANEL_W, PANEL_H * np);
  for (int i = 0; i < np; ++i)
    panel(fp, &p[i], (double)PANEL_H * i);
  fputs("</svg>\n", fp);
  return ferror(fp) ? cli_error(c, DAL_E_IO, "%s: a write failed", f->path) : DAL_OK;
}
