/* Hooks for lamina's own tests only: not part of the installed API
 * (lamina.h), may change at any time. */
#ifndef LAM_TEST_HOOKS_H
#define LAM_TEST_HOOKS_H

#include <stddef.h>

#include "slice.h"

/* Flip the label of one contour (solid <-> hole) without touching its
 * points, depth or parent. Out of range does nothing (validate_layer.c). */
void lam_layer_flip_label_for_test(lam_layer *L, size_t contour);

#endif
