// SPDX-License-Identifier: MIT
// SPDX-FileCopyrightText: 2026 dalembert engineers
// The viewer's page as strings: page.css, page.html and page.js, each a byte list the build
// writes from the file (cmake/embed.cmake), so the page stays a readable source in the tree.
#include "view/view.h"

const char dal__view_css[] = {
#include "view_page_css.inc"
};
const char dal__view_html[] = {
#include "view_page_html.inc"
};
const char dal__view_js[] = {
#include "view_page_js.inc"
};
