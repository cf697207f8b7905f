/* What makes two vertices one when welding: bitwise-equal coordinates,
 * -0.0 counting as 0.0, and the hash every welder uses (the serial one in
 * mesh.c and the binary STL reader's threaded one in stl_weld.c), so both
 * agree on which corners are the same vertex. Internal to lamina. */
#ifndef LAM_WELD_HASH_H
#define LAM_WELD_HASH_H

#include <stdint.h>
#include <string.h>

static inline uint64_t lam_weld_bits(double d)
{
    uint64_t u;
    d += 0.0; /* -0.0 + 0.0 == +0.0: both zeros weld */
    memcpy(&u, &d, sizeof u);
    return u;
}

static inline uint64_t lam_weld_hash(const double *p)
{
    /* floats widened to double end in 29 zero bits: mix thoroughly
     * (murmur3's finaliser) before the low bits pick a slot */
    uint64_t h = lam_weld_bits(p[0]) * 0x9e3779b97f4a7c15ull;
    h = (h ^ lam_weld_bits(p[1])) * 0xc2b2ae3d27d4eb4full;
    h = (h ^ lam_weld_bits(p[2])) * 0x165667b19e3779f9ull;
    h ^= h >> 33;
    h *= 0xff51afd7ed558ccdull;
    h ^= h >> 33;
    h *= 0xc4ceb9fe1a85ec53ull;
    h ^= h >> 33;
    return h;
}

static inline int lam_weld_same(const double *a, const double *b)
{
    return lam_weld_bits(a[0]) == lam_weld_bits(b[0]) && lam_weld_bits(a[1]) == lam_weld_bits(b[1]) &&
           lam_weld_bits(a[2]) == lam_weld_bits(b[2]);
}

#endif
