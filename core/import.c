/* lam_model_load: read a file, pick the importer, build the model.
 *
 * The format is chosen by extension (.ug, .stl, .obj, any case); a file with
 * another extension is recognised by content: a binary STL by its size, an
 * ASCII STL by a leading "solid", an OBJ by `v`/`f` lines, Unigrafix by `;`
 * terminated statements. */
#include "import.h"
#include "model.h"

#include <errno.h>
#include <fcntl.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

int lam_read_file(const char *path, char **data, size_t *len, lam_error *err)
{
    *data = NULL;
    *len = 0;
    FILE *f = fopen(path, "rb");
    if (!f) return lam_error_set(err, LAM_EIO, path, 0, 0, "cannot open: %s", strerror(errno));
    struct stat st;
    if (fstat(fileno(f), &st) == 0 && S_ISDIR(st.st_mode)) {
        fclose(f);
        return lam_error_set(err, LAM_EIO, path, 0, 0, "is a directory");
    }
    size_t cap = st.st_size > 0 ? (size_t)st.st_size + 1 : 4096, n = 0;
    char *buf = malloc(cap);
    if (!buf) {
        fclose(f);
        return lam_error_set(err, LAM_ENOMEM, path, 0, 0, "out of memory reading the file");
    }
    for (;;) {
        if (n + 1 >= cap) {
            char *nb = realloc(buf, cap * 2);
            if (!nb) {
                free(buf);
                fclose(f);
                return lam_error_set(err, LAM_ENOMEM, path, 0, 0, "out of memory reading the file");
            }
            buf = nb;
            cap *= 2;
        }
        size_t got = fread(buf + n, 1, cap - 1 - n, f);
        n += got;
        if (got == 0) break;
    }
    int bad = ferror(f);
    fclose(f);
    if (bad) {
        free(buf);
        return lam_error_set(err, LAM_EIO, path, 0, 0, "read error");
    }
    buf[n] = '\0';
    *data = buf;
    *len = n;
    return LAM_OK;
}

int lam_map_file(const char *path, char **data, size_t *len, int *mapped, lam_error *err)
{
    *mapped = 0;
    struct stat st;
    long page = sysconf(_SC_PAGESIZE);
    /* Only a regular file whose size is not a whole number of pages: the
     * system zero-fills the rest of the last page, so the mapping ends in
     * the NUL the text readers rely on. Anything else is read. */
    if (page > 0 && stat(path, &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 0 &&
        st.st_size % page != 0 && (uintmax_t)st.st_size < SIZE_MAX / 2) {
        int fd = open(path, O_RDONLY);
        if (fd >= 0) {
            struct stat fst;
            void *p = MAP_FAILED;
            if (fstat(fd, &fst) == 0 && fst.st_size == st.st_size)
                p = mmap(NULL, (size_t)st.st_size, PROT_READ, MAP_PRIVATE, fd, 0);
            close(fd);
            if (p != MAP_FAILED) {
                *data = p;
                *len = (size_t)st.st_size;
                *mapped = 1;
                return LAM_OK;
            }
        }
    }
    return lam_read_file(path, data, len, err);
}

void lam_unmap_file(char *data, size_t len, int mapped)
{
    if (mapped) munmap(data, len);
    else free(data);
}

enum fmt { FMT_UNKNOWN, FMT_UG, FMT_STL, FMT_OBJ };

static enum fmt by_extension(const char *path)
{
    const char *slash = strrchr(path, '/');
    const char *dot = strrchr(slash ? slash : path, '.');
    if (!dot) return FMT_UNKNOWN;
    if (strcasecmp(dot, ".ug") == 0) return FMT_UG;
    if (strcasecmp(dot, ".stl") == 0) return FMT_STL;
    if (strcasecmp(dot, ".obj") == 0) return FMT_OBJ;
    return FMT_UNKNOWN;
}

static enum fmt by_content(const char *d, size_t n)
{
    if (n >= 84) {
        unsigned long long count = (unsigned char)d[80] | (unsigned)(unsigned char)d[81] << 8 |
                                   (unsigned long)(unsigned char)d[82] << 16 |
                                   (unsigned long)(unsigned char)d[83] << 24;
        if (84 + 50 * count == n) return FMT_STL;
    }
    size_t i = 0;
    while (i < n && (d[i] == ' ' || d[i] == '\t' || d[i] == '\r' || d[i] == '\n')) i++;
    if (n - i >= 5 && strncasecmp(d + i, "solid", 5) == 0) return FMT_STL;
    /* OBJ: a line starting "v " and no statement terminators in the first
     * kilobytes; Unigrafix has ';' after every statement. */
    size_t look = n < 65536 ? n : 65536;
    int semis = 0, vlines = 0;
    for (size_t k = 0; k < look; k++) {
        if (d[k] == ';') semis++;
        if ((k == 0 || d[k - 1] == '\n') && k + 1 < look && d[k] == 'v' && (d[k + 1] == ' ' || d[k + 1] == '\t'))
            vlines++;
        if (d[k] == '\0') return FMT_UNKNOWN;
    }
    if (semis) return FMT_UG;
    if (vlines) return FMT_OBJ;
    return FMT_UNKNOWN;
}

int lam_model_load(const char *path, lam_model **out, lam_error *err)
{
    *out = NULL;
    char *data;
    size_t len;
    int mapped;
    int rc = lam_map_file(path, &data, &len, &mapped, err);
    if (rc) return rc;
    if (len == 0) {
        lam_unmap_file(data, len, mapped);
        return lam_error_set(err, LAM_EFORMAT, path, 0, 0, "empty file");
    }
    enum fmt f = by_extension(path);
    if (f == FMT_UNKNOWN) f = by_content(data, len);
    lam_mesh mesh;
    lam_mesh_init(&mesh);
    const char *format = NULL;
    switch (f) {
    case FMT_UG:
        rc = lam_import_ug_buf(path, data, len, &mesh, err);
        format = "unigrafix";
        break;
    case FMT_STL: {
        int binary = 0;
        rc = lam_import_stl_buf(path, (const unsigned char *)data, len, &mesh, &binary, err);
        format = binary ? "stl-binary" : "stl-ascii";
        break;
    }
    case FMT_OBJ:
        rc = lam_import_obj_buf(path, data, len, &mesh, err);
        format = "obj";
        break;
    default:
        rc = lam_error_set(err, LAM_EFORMAT, path, 0, 0,
                           "unknown model format (lamina reads Unigrafix .ug, STL and OBJ)");
    }
    lam_unmap_file(data, len, mapped);
    if (rc) {
        lam_mesh_free(&mesh);
        return rc;
    }
    return lam_model_from_mesh(&mesh, path, format, out, err);
}
