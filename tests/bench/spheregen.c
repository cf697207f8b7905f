/* spheregen TRIANGLES OUT.stl: a closed UV sphere of radius 20 with about
 * TRIANGLES triangles as binary STL (the bench's scaling meshes; writing
 * 5 million triangles takes a second, where a Python loop takes a minute).
 * nlat rings of nlon vertices between the poles; fans at the poles,
 * quads split in two between rings, facing outward. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static FILE *out;
static uint32_t count;

static void put(const double *a, const double *b, const double *c)
{
    unsigned char rec[50] = { 0 };
    float v[9] = { (float)a[0], (float)a[1], (float)a[2], (float)b[0], (float)b[1], (float)b[2],
                   (float)c[0], (float)c[1], (float)c[2] };
    memcpy(rec + 12, v, sizeof v); /* the normal left 0: readers compute it */
    fwrite(rec, 1, 50, out);
    count++;
}

static void vertex(long i, long j, long nlat, long nlon, double *p)
{
    double th = M_PI * (double)i / (double)nlat, ph = 2 * M_PI * (double)j / (double)nlon;
    p[0] = 20 * sin(th) * cos(ph);
    p[1] = 20 * sin(th) * sin(ph);
    p[2] = 20 * cos(th);
}

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: spheregen TRIANGLES OUT.stl\n");
        return 2;
    }
    double t = atof(argv[1]);
    /* 2 nlon (nlat - 1) triangles with nlon = 2 nlat */
    long nlat = (long)ceil(sqrt(t / 4)) + 1, nlon = 2 * nlat;
    if (nlat < 3) nlat = 3, nlon = 6;
    if (!(out = fopen(argv[2], "wb"))) return perror(argv[2]), 1;
    static char buf[1 << 20];
    setvbuf(out, buf, _IOFBF, sizeof buf);
    unsigned char head[84] = "binary STL: spheregen";
    fwrite(head, 1, 84, out);
    double np[3] = { 0, 0, 20 }, sp[3] = { 0, 0, -20 };
    for (long i = 1; i < nlat; i++)
        for (long j = 0; j < nlon; j++) {
            double a[3], b[3], c[3], d[3];
            vertex(i, j, nlat, nlon, a);
            vertex(i, (j + 1) % nlon, nlat, nlon, b);
            if (i == 1) put(np, a, b);
            if (i + 1 < nlat) {
                vertex(i + 1, j, nlat, nlon, c);
                vertex(i + 1, (j + 1) % nlon, nlat, nlon, d);
                put(a, c, d);
                put(a, d, b);
            } else {
                put(a, sp, b);
            }
        }
    fseek(out, 80, SEEK_SET);
    unsigned char n[4] = { (unsigned char)count, (unsigned char)(count >> 8), (unsigned char)(count >> 16),
                           (unsigned char)(count >> 24) };
    fwrite(n, 1, 4, out);
    return fclose(out) != 0;
}
