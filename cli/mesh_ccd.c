/* SPDX-License-Identifier: MIT */
/* `ttd mesh-ccd`: continuous collision of deforming meshes (docs/ccd.md, section 10): mesh
 * files at t = 0 and at t = 1 (the same triangles), one mesh against itself or two meshes. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cli.h"
#include "ttd/meshfile.h"

static const char mesh_ccd_usage[] =
    "usage: ttd mesh-ccd [options] A_T0 A_T1            (A against itself)\n"
    "       ttd mesh-ccd [options] A_T0 A_T1 B_T0 B_T1  (A against B)\n"
    "Continuous collision of deforming meshes: each vertex moves on a straight line from its\n"
    "position in the t = 0 file to its position in the t = 1 file (any format ttd mesh reads;\n"
    "the two files of a mesh must hold the same triangles). Prints the earliest time of impact\n"
    "(conservative: never after the true first time) and every vertex-face and edge-edge pair\n"
    "whose own time is within 2^-52 of it. A against itself: the pairs of triangles that share\n"
    "no vertex (--shared-vertex: also those sharing one, less the sub-queries at that vertex).\n"
    "options:\n"
    "  --min-separation D   report pairs that come within D (default 0)\n"
    "  --shared-vertex      self: also the triangle pairs that share one vertex\n"
    "  --float              read and compute the meshes in float (widened to double exactly)\n"
    "  --threads N          worker threads (default 0: all cores); the answer does not depend on it\n"
    "  --summary            only the first line\n"
    "output: 'toi T pairs N triangle-pairs P queries Q searched R time S s', with a note where a pair\n"
    "used up its budget (a conservative hit) (T inf when nothing comes\n"
    "within D; Q primitive pairs whose boxes came within D, R of them searched in time),\n"
    "then a line per pair 'KIND A0 A1 B0 B1 TOI GAP': KIND vf (vertex A0 of A, triangle B0 of B),\n"
    "fv (triangle A0 of A, vertex B0 of B) or ee (edge A0-A1 of A, edge B0-B1 of B); unused ids\n"
    "are -1; A against itself names both as A. Exit 1 for an unreadable or mismatched file.\n";

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Reads the two files of a mesh and builds it from the first; *x1 the second's vertices (in
 * file m1, which the caller frees). 0, or -1 after a message. */
static int load_pair(const char *p0, const char *p1, int use_float, const ttd_options *o, ttd_meshfile *m0,
                     ttd_meshfile *m1, ttd_mesh **mesh)
{
    char err[1024];
    const int flags = use_float ? TTD_MESHFILE_FLOAT : 0;
    if (ttd_meshfile_read(p0, flags, m0, err, sizeof err) != 0 || ttd_meshfile_read(p1, flags, m1, err, sizeof err) != 0) {
        ttd_cli_error("mesh-ccd: %s", err);
        return -1;
    }
    if (m0->nv != m1->nv || m0->nt != m1->nt || memcmp(m0->tris, m1->tris, 3 * m0->nt * sizeof *m0->tris) != 0) {
        ttd_cli_error("mesh-ccd: %s and %s do not hold the same triangles (%zu vertices, %zu triangles against %zu, %zu)",
                      p0, p1, m0->nv, m0->nt, m1->nv, m1->nt);
        return -1;
    }
    const ttd_status st = use_float ? ttd_mesh_create_f(o, m0->verts_f, m0->nv, m0->tris, m0->nt, mesh)
                                    : ttd_mesh_create_d(o, m0->verts, m0->nv, m0->tris, m0->nt, mesh);
    if (st != TTD_OK) {
        ttd_cli_error("mesh-ccd: %s: cannot build the mesh: %s", p0, ttd_status_string(st));
        return -1;
    }
    return 0;
}

static long long id_or_none(uint32_t x)
{
    return x == UINT32_MAX ? -1 : (long long)x;
}

int ttd_cli_mesh_ccd(int argc, char **argv)
{
    static const char *const switches[] = {"--summary", "--float", "--shared-vertex", NULL};
    static const char *const valued[] = {"--min-separation", "--threads", NULL};
    ttd_options o = ttd_default_options();
    const char *paths[4];
    int np = 0, summary = 0, use_float = 0;
    unsigned flags = 0;
    double delta = 0;
    ttd_cli_args w = ttd_cli_args_start("mesh-ccd", switches, valued, argc, argv);
    w.long_only = 1;
    for (ttd_cli_arg k; (k = ttd_cli_next_arg(&w)) != TTD_ARG_END;) {
        if (k == TTD_ARG_BAD || k == TTD_ARG_HELP)
            return ttd_cli_stop_status(k, mesh_ccd_usage);
        const char *opt = w.opt, *val = w.val;
        if (k == TTD_ARG_FLAG) {
            summary |= strcmp(opt, "--summary") == 0;
            use_float |= strcmp(opt, "--float") == 0;
            flags |= strcmp(opt, "--shared-vertex") == 0 ? (unsigned)TTD_SELF_SHARED_VERTEX : 0u;
        } else if (k == TTD_ARG_VALUE) {
            long v;
            if (strcmp(opt, "--min-separation") == 0 && ttd_cli_parse_real(val, &delta) == 0 && delta >= 0 &&
                isfinite(delta))
                ;
            else if (strcmp(opt, "--threads") == 0 && ttd_cli_parse_int(val, 0, 1 << 20, &v) == 0)
                o.threads = (int)v;
            else {
                ttd_cli_error("mesh-ccd: bad value '%s' for %s", val, opt);
                return TTD_EXIT_USAGE;
            }
        } else if (np == 4) {
            ttd_cli_error("mesh-ccd: two or four files (see ttd mesh-ccd --help)");
            return TTD_EXIT_USAGE;
        } else {
            paths[np++] = w.arg;
        }
    }
    if (np != 2 && np != 4) {
        ttd_cli_error("mesh-ccd: two or four files (see ttd mesh-ccd --help)");
        fputs(mesh_ccd_usage, stderr);
        return TTD_EXIT_USAGE;
    }
    if (np == 4 && flags) {
        ttd_cli_error("mesh-ccd: --shared-vertex is for one mesh against itself");
        return TTD_EXIT_USAGE;
    }
    ttd_meshfile f[4];
    memset(f, 0, sizeof f);
    ttd_mesh *ma = NULL, *mb = NULL;
    int rc = TTD_EXIT_OK;
    if (load_pair(paths[0], paths[1], use_float, &o, &f[0], &f[1], &ma) != 0 ||
        (np == 4 && load_pair(paths[2], paths[3], use_float, &o, &f[2], &f[3], &mb) != 0)) {
        rc = TTD_EXIT_INPUT;
        goto done;
    }
    ttd_mesh_ccd_result r;
    const double t0 = now_s();
    ttd_status st;
    if (np == 2)
        st = use_float ? ttd_mesh_self_ccd_f(&o, ma, f[1].verts_f, delta, flags, &r)
                       : ttd_mesh_self_ccd_d(&o, ma, f[1].verts, delta, flags, &r);
    else
        st = use_float ? ttd_mesh_ccd_f(&o, ma, f[1].verts_f, mb, f[3].verts_f, delta, &r)
                       : ttd_mesh_ccd_d(&o, ma, f[1].verts, mb, f[3].verts, delta, &r);
    const double secs = now_s() - t0;
    if (st != TTD_OK) {
        ttd_cli_error("mesh-ccd: %s", ttd_status_string(st));
        rc = st == TTD_ERR_BAD_OPTIONS ? TTD_EXIT_USAGE : TTD_EXIT_INPUT;
        goto done;
    }
    printf("toi %.17g pairs %zu triangle-pairs %llu queries %llu searched %llu time %.6f s%s\n", r.toi, r.count,
           (unsigned long long)r.triangle_pairs, (unsigned long long)r.queries, (unsigned long long)r.searches, secs,
           (r.flags & TTD_CCD_BUDGET) ? " (some pair used up its budget: a conservative hit)" : "");
    static const char *const kinds[3] = {"vf", "fv", "ee"};
    if (!summary)
        for (size_t i = 0; i < r.count; ++i) {
            const ttd_mesh_ccd_pair *p = &r.pairs[i];
            printf("%s %lld %lld %lld %lld %.17g %.3g\n", kinds[p->kind], id_or_none(p->a[0]), id_or_none(p->a[1]),
                   id_or_none(p->b[0]), id_or_none(p->b[1]), p->toi, p->gap);
        }
    ttd_mesh_ccd_free(&r);
    if (fflush(stdout) != 0 || ferror(stdout)) {
        ttd_cli_error("mesh-ccd: cannot write the output");
        rc = TTD_EXIT_INPUT;
    }
done:
    ttd_mesh_destroy(ma);
    ttd_mesh_destroy(mb);
    for (int i = 0; i < 4; ++i)
        ttd_meshfile_free(&f[i]);
    return rc;
}
