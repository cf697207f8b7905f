/* LAM_PREFETCH(p): ask the CPU to start loading the cache line at p.
 * Only a hint (never faults, changes no result); used where a loop knows
 * which scattered memory it will read a few iterations ahead. */
#ifndef LAM_PREFETCH_H
#define LAM_PREFETCH_H

#if defined(__GNUC__) || defined(__clang__)
#define LAM_PREFETCH(p) __builtin_prefetch(p)
#else
#define LAM_PREFETCH(p) ((void)(p))
#endif

#endif
