/* SPDX-License-Identifier: MIT */
/* `ttd mesh-ccd-rigid`: continuous collision of two rigid meshes between two poses each
 * (docs/ccd.md, section 13): mesh files and a text file of the four poses. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "ttd/meshfile.h"

static const char rigid_usage[] =
    "usage: ttd mesh-ccd-rigid [options] A B POSES\n"
    "Continuous collision of two rigid meshes: each moves from its pose at t = 0 to its pose at\n"
    "t = 1, its origin on a straight line and its rotation about one fixed axis at a constant rate\n"
    "(R(t) = Rot(u, t theta) R0 with R1 R0^T = Rot(u, theta), theta in [0, pi]). POSES is a text\n"
    "file ('-': standard input) of 48 numbers: A's pose at t = 0, A's at t = 1, B's at t = 0, B's at\n"
    "t = 1, each the 12 numbers [R | t] row by row (x_world = R x + t). Prints whether and when the\n"
    "meshes first come within the separation: no contact is missed, toi is never after the true\n"
    "first time and the distance at it is at most D + tolerance.\n"
    "options:\n"
    "  --min-separation D   the separation (default 0)\n"
    "  --float              read and compute the meshes and poses in float\n"
    "output: one line 'hit H toi T distance X tolerance E steps N tri_a I tri_b J' (T and X inf\n"
    "and I, J -1 without a hit), with ' (step bound: a conservative hit)' where the step bound was\n"
    "reached. Exit 1 for an unreadable file or refused poses, 2 for the command line.\n";

static int read_poses(const char *path, double p[48])
{
    FILE *f = strcmp(path, "-") == 0 ? stdin : fopen(path, "r");
    if (f == NULL) {
        ttd_cli_error("mesh-ccd-rigid: cannot open %s", path);
        return -1;
    }
    int n = 0;
    char word[128];
    while (n < 48 && fscanf(f, "%127s", word) == 1) {
        if (ttd_cli_parse_real(word, &p[n]) != 0) {
            ttd_cli_error("mesh-ccd-rigid: %s: '%s' is not a number", path, word);
            n = -1;
            break;
        }
        ++n;
    }
    const int extra = n == 48 && fscanf(f, "%127s", word) == 1;
    if (f != stdin)
        fclose(f);
    if (n >= 0 && (n != 48 || extra)) {
        ttd_cli_error("mesh-ccd-rigid: %s holds %s numbers: four poses are 48", path, extra ? "more than 48" : "fewer than 48");
        return -1;
    }
    return n == 48 ? 0 : -1;
}

int ttd_cli_mesh_ccd_rigid(int argc, char **argv)
{
    static const char *const switches[] = {"--float", NULL};
    static const char *const valued[] = {"--min-separation", NULL};
    const char *paths[3];
    int np = 0, use_float = 0;
    double delta = 0;
    ttd_cli_args w = ttd_cli_args_start("mesh-ccd-rigid", switches, valued, argc, argv);
    w.long_only = 1;
    for (ttd_cli_arg k; (k = ttd_cli_next_arg(&w)) != TTD_ARG_END;) {
        if (k == TTD_ARG_BAD || k == TTD_ARG_HELP)
            return ttd_cli_stop_status(k, rigid_usage);
        if (k == TTD_ARG_FLAG) {
            use_float = 1;
        } else if (k == TTD_ARG_VALUE) {
            if (!(ttd_cli_parse_real(w.val, &delta) == 0 && delta >= 0 && isfinite(delta))) {
                ttd_cli_error("mesh-ccd-rigid: bad value '%s' for %s", w.val, w.opt);
                return TTD_EXIT_USAGE;
            }
        } else if (np == 3) {
            ttd_cli_error("mesh-ccd-rigid: two mesh files and a poses file (see ttd mesh-ccd-rigid --help)");
            return TTD_EXIT_USAGE;
        } else {
            paths[np++] = w.arg;
        }
    }
    if (np != 3) {
        ttd_cli_error("mesh-ccd-rigid: two mesh files and a poses file (see ttd mesh-ccd-rigid --help)");
        fputs(rigid_usage, stderr);
        return TTD_EXIT_USAGE;
    }
    double poses[48];
    if (read_poses(paths[2], poses) != 0)
        return TTD_EXIT_INPUT;
    for (int k = 0; k < 4; ++k) {
        char err[256];
        if (ttd_cli_pose_problem(poses + 12 * k, 0, err, sizeof err) != 0) {
            ttd_cli_error("mesh-ccd-rigid: %s: pose %d (%s at t = %d): %s", paths[2], k + 1, k < 2 ? "A" : "B", k % 2,
                          err);
            return TTD_EXIT_INPUT;
        }
    }
    ttd_meshfile f[2];
    memset(f, 0, sizeof f);
    ttd_mesh *m[2] = {NULL, NULL};
    int rc = TTD_EXIT_OK;
    for (int k = 0; k < 2 && rc == TTD_EXIT_OK; ++k) {
        char err[1024];
        if (ttd_meshfile_read(paths[k], use_float ? TTD_MESHFILE_FLOAT : 0, &f[k], err, sizeof err) != 0) {
            ttd_cli_error("mesh-ccd-rigid: %s", err);
            rc = TTD_EXIT_INPUT;
            break;
        }
        const ttd_status st = use_float ? ttd_mesh_create_f(NULL, f[k].verts_f, f[k].nv, f[k].tris, f[k].nt, &m[k])
                                        : ttd_mesh_create_d(NULL, f[k].verts, f[k].nv, f[k].tris, f[k].nt, &m[k]);
        if (st != TTD_OK) {
            ttd_cli_error("mesh-ccd-rigid: %s: cannot build the mesh: %s", paths[k], ttd_status_string(st));
            rc = TTD_EXIT_INPUT;
        }
    }
    if (rc == TTD_EXIT_OK) {
        ttd_mesh_ccd_rigid_result r;
        ttd_status st;
        if (use_float) {
            float pf[48];
            for (int i = 0; i < 48; ++i)
                pf[i] = (float)poses[i];
            st = ttd_mesh_ccd_rigid_f(NULL, m[0], pf, m[1], pf + 24, delta, &r);
        } else {
            st = ttd_mesh_ccd_rigid_d(NULL, m[0], poses, m[1], poses + 24, delta, &r);
        }
        if (st != TTD_OK) {
            ttd_cli_error("mesh-ccd-rigid: %s", ttd_status_string(st));
            rc = TTD_EXIT_INPUT;
        } else {
            printf("hit %u toi %.17g distance %.17g tolerance %.3g steps %u tri_a %lld tri_b %lld%s\n", r.hit, r.toi,
                   r.distance, r.tolerance, r.steps, r.tri_a == UINT32_MAX ? -1LL : (long long)r.tri_a,
                   r.tri_b == UINT32_MAX ? -1LL : (long long)r.tri_b,
                   (r.flags & TTD_CCD_BUDGET) ? " (step bound: a conservative hit)" : "");
            if (fflush(stdout) != 0 || ferror(stdout)) {
                ttd_cli_error("mesh-ccd-rigid: cannot write the output");
                rc = TTD_EXIT_INPUT;
            }
        }
    }
    for (int k = 0; k < 2; ++k) {
        ttd_mesh_destroy(m[k]);
        ttd_meshfile_free(&f[k]);
    }
    return rc;
}
