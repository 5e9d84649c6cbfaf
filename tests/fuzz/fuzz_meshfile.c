/* SPDX-License-Identifier: MIT */
/* libFuzzer target: the mesh-file reader (ttd/meshfile.h) on arbitrary bytes, read once with
 * double coordinates only and once with floats too. Checked: no crash, hang or out-of-bounds
 * access (AddressSanitizer; libFuzzer hands over a buffer of exactly size bytes); on success at
 * least one vertex and triangle, every index below nv, every coordinate finite, each float
 * within one float step of its double (both are roundings of the same number); the two reads
 * agree (a float read may fail only where a value overflows float, and then says so); on
 * failure a non-empty message that starts with the file's name and an empty mesh. A mesh read is
 * then welded (ttd_meshfile_weld) at tolerance 0 and at a tolerance taken from the input: no more
 * vertices than before, every index below the new count, no triangle with a repeated vertex, the
 * triangles kept plus those dropped equal to those read. Build and run: scripts/fuzz.sh. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <ttd/meshfile.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void check(int rc, const ttd_meshfile *m, const char *err, int want_float)
{
    if (rc != 0) {
        if (rc != -1 || strncmp(err, "fuzz:", 5) != 0)
            abort();
        if (m->verts || m->verts_f || m->tris || m->nv || m->nt)
            abort();
        return;
    }
    if (m->nv == 0 || m->nt == 0 || !m->verts || !m->tris || (want_float != 0) != (m->verts_f != NULL))
        abort();
    for (size_t k = 0; k < 3 * m->nt; ++k)
        if (m->tris[k] >= m->nv)
            abort();
    for (size_t k = 0; k < 3 * m->nv; ++k) {
        if (!isfinite(m->verts[k]))
            abort();
        if (want_float) {
            float f = m->verts_f[k], g = (float)m->verts[k];
            if (!isfinite(f) || (f != g && nextafterf(g, INFINITY) != f && nextafterf(g, -INFINITY) != f))
                abort();
        }
    }
}

static void check_weld(ttd_meshfile *m, double tol)
{
    size_t nv = m->nv, nt = m->nt, dropped = 0;
    char err[256];
    if (ttd_meshfile_weld(m, tol, &dropped, err, sizeof err) != 0) {
        if (m->nv != nv || m->nt != nt || !strstr(err, "collapses"))
            abort(); /* only a mesh whose every triangle collapses is refused, and left as it was */
        return;
    }
    if (m->nv == 0 || m->nv > nv || m->nt == 0 || m->nt + dropped != nt)
        abort();
    for (size_t t = 0; t < m->nt; ++t) {
        const uint32_t *x = m->tris + 3 * t;
        if (x[0] >= m->nv || x[1] >= m->nv || x[2] >= m->nv || x[0] == x[1] || x[1] == x[2] || x[0] == x[2])
            abort();
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char err0[256], err1[256];
    ttd_meshfile m0, m1;
    int r0 = ttd_meshfile_parse("fuzz", data, size, 0, &m0, err0, sizeof err0);
    check(r0, &m0, err0, 0);
    int r1 = ttd_meshfile_parse("fuzz", data, size, 1, &m1, err1, sizeof err1);
    check(r1, &m1, err1, 1);
    if (r1 == 0 && (r0 != 0 || m0.nv != m1.nv || m0.nt != m1.nt || m0.format != m1.format ||
                    memcmp(m0.verts, m1.verts, 3 * m0.nv * sizeof(double)) != 0 ||
                    memcmp(m0.tris, m1.tris, 3 * m0.nt * sizeof(uint32_t)) != 0))
        abort();
    if (r0 == 0 && r1 != 0 && !strstr(err1, "float"))
        abort();
    if (r0 != 0 && r1 != 0 && strcmp(err0, err1) != 0 && !strstr(err1, "float"))
        abort(); /* the same error, unless the float read stopped earlier at an overflow */
    if (r0 == 0)
        check_weld(&m0, 0.0);
    if (r1 == 0)
        check_weld(&m1, size > 0 ? ldexp(1.0, (int)(data[size - 1] % 64) - 40) : 1e-9);
    ttd_meshfile_free(&m0);
    ttd_meshfile_free(&m1);
    return 0;
}
