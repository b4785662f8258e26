// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The viewer's face: the page's CSS, HTML body and JavaScript, embedded at build time from
// src/view/page.css, page.html and page.js (cmake/embed.cmake writes them as C strings).
#ifndef DAL_VIEW_VIEW_H
#define DAL_VIEW_VIEW_H

/// the page's style sheet (page.css)
extern const char dal__view_css[];
/// the page's body markup (page.html)
extern const char dal__view_html[];
/// the page's script (page.js)
extern const char dal__view_js[];

#endif
