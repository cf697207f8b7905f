/* The viewer's page, core/out/viewer.html, as a C string: generated at build
 * time by the Makefile (od), so the program needs no file at run time. */
#ifndef LAM_VIEWER_HTML_H
#define LAM_VIEWER_HTML_H

#include <stddef.h>

/* Where the page takes its head (before the viewer's script) and its data
 * (after it): each on a line of its own in the template (docs/viewer.md). */
#define LAM_VIEWER_HEAD "@LAMINA_HEAD@"
#define LAM_VIEWER_DATA "@LAMINA_DATA@"

extern const char lam_viewer_html[];      /* NUL-terminated */
extern const size_t lam_viewer_html_len;

#endif
