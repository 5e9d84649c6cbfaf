/* SPDX-License-Identifier: MIT */
/* `ttd mesh distance | contacts | collide A B [options]`: the library's mesh queries on two
 * meshes read from files (ttd/meshfile.h), under one pose (--pose), many (--poses FILE) or the
 * identity; `ttd mesh self-contacts | self-collide A`: one mesh against itself (its pairs that
 * share no vertex), which run as a contacts or collide query of one pose. `ttd mesh mass A` is
 * handed to cli/mesh_mass.c. The usage text below is the reference for the output formats; docs/mesh-files.md
 * has a summary.
 *
 * Everything that can be checked is checked before anything is computed, so that a run either
 * prints its whole answer or nothing but messages: options and a --pose argument (exit 2), the
 * whole poses file (every bad line named, exit 1), both meshes (the reader's message, exit 1),
 * every pose against the meshes (exit 1). A pose that is not a rotation is caught here with the
 * library's own test (include/ttd/ttd.h), so the message can say which pose and why; one that
 * would move B beyond the meshes' coordinate range by ttd_mesh_check_poses, so that the message
 * names the pose.
 *
 * Poses go to the library in chunks, so that memory stays bounded however many poses there are
 * (contacts: chunks sized from the pairs per pose seen so far), and each chunk's lines are
 * written before the next is computed. Contacts of a pose are sorted by (ia, ib): the output is
 * then a documented function of the input, whatever order the library collects them in. */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include <ttd/meshfile.h>
#include "parse.h"

/// Poses per library call for distance and collide.
#define TTD_MESH_POSE_CHUNK 4096
/// Contact pairs (or per-triangle records) a chunk of poses aims at; one pose may exceed it.
#define TTD_MESH_PAIR_TARGET ((size_t)1 << 20)
/// Bad pose lines reported before the rest are only counted.
#define TTD_MESH_MAX_MESSAGES 20
/// The library's tolerance on R^T R - I (include/ttd/ttd.h, "Mesh queries").
#define TTD_MESH_POSE_TOLERANCE 1e-6
/// The largest defect (an entry of R^T R - I) that --orthonormalize repairs: poses printed with
/// 3 or more significant digits; beyond it R is more than rounded and is refused.
#define TTD_MESH_ORTHONORMALIZE_TOLERANCE 1e-2

typedef enum ttd_mesh_cmd {
    TTD_MESH_DISTANCE,
    TTD_MESH_CONTACTS,
    TTD_MESH_COLLIDE,
    TTD_MESH_SELF_CONTACTS,
    TTD_MESH_SELF_COLLIDE,
    TTD_MESH_NCMD
} ttd_mesh_cmd;

static const char *const ttd_mesh_cmd_names[] = {"distance", "contacts", "collide", "self-contacts", "self-collide"};

static const char *const ttd_mesh_synopsis[] = {
    "ttd mesh distance A B [--pose P | --poses FILE] [--upper-bound X] [--rel-tol X] [options]\n",
    "ttd mesh contacts A B --margin M [--pose P | --poses FILE] [--per-triangle] [--count] [options]\n",
    "ttd mesh collide A B [--margin M] [--pose P | --poses FILE] [options]\n",
    "ttd mesh self-contacts A --margin M [--shared-vertex] [--count] [options]\n",
    "ttd mesh self-collide A [--margin M] [--shared-vertex] [options]\n"};

/* Whether a command takes one mesh (against itself). */
static int ttd_mesh_is_self(ttd_mesh_cmd cmd)
{
    return cmd == TTD_MESH_SELF_CONTACTS || cmd == TTD_MESH_SELF_COLLIDE;
}

static const char ttd_mesh_usage_head[] =
    "Queries between two triangle meshes read from the files A and B ('-' for standard input, once\n"
    "for both when A and B are the same path): OBJ, STL (ASCII or binary), PLY (ASCII or binary),\n"
    "OFF, glTF 2.0 (GLB, .gltf) or 3MF, recognised by content (docs/mesh-files.md). Triangle indices ia (of A) and ib\n"
    "(of B) are 0-based in file order, polygons fan-triangulated. Every query is exact: the answer of\n"
    "the exact method over all triangle pairs.\n";

static const char ttd_mesh_usage_distance[] =
    "\n"
    "distance: the minimum distance, one line per pose:\n"
    "    d px py pz qx qy qz ia ib\n"
    "  p on triangle ia of A, q on triangle ib of B, both in A's frame; when the meshes touch or\n"
    "  cross, d is 0 and p = q, a point common to both. With --solid, where one mesh lies inside\n"
    "  the other, d is 0, p = q is a vertex of the inner mesh, and the outer mesh's triangle is -1.\n"
    "  --upper-bound X   X >= 0: a pose whose distance exceeds X may stop early and prints\n"
    "                    'inf nan nan nan nan nan nan -1 -1' (default: no bound)\n"
    "  --rel-tol X       X >= 0: the pair printed may be up to a factor 1 + X farther than the\n"
    "                    minimum, for fewer pair tests (default 0, exact)\n";

static const char ttd_mesh_usage_contacts[] =
    "\n"
    "contacts: every triangle pair at distance <= M, one line per pair, sorted by ia then ib:\n"
    "    ia ib d px py pz qx qy qz\n"
    "  p on triangle ia of A, q on triangle ib of B, in A's frame.\n"
    "  --margin M        M >= 0, finite (required)\n"
    "  --count           print only the number of pairs, one line per pose (counted, not held)\n"
    "  --per-triangle    instead of pairs, for each triangle its closest partner within M (ties: the\n"
    "                    smaller index); first the triangles of A that have one, by ia, then those\n"
    "                    of B, by ib:\n"
    "                        a ia ib d px py pz qx qy qz    p on ia (of A), q on ib (of B)\n"
    "                        b ib ia d px py pz qx qy qz    p on ib (of B), q on ia (of A)\n"
    "                    with --count: 'na nb', the triangles of A and of B that have one\n"
    "  With --poses, each pair or per-triangle line starts with the pose's index (0-based, the\n"
    "  order of the poses in FILE), and the lines of pose i come before those of pose i + 1.\n";

static const char ttd_mesh_usage_collide[] =
    "\n"
    "collide: whether the meshes come within M of each other (0: touch or cross), one line per\n"
    "pose: '1 ia ib' with the first pair found within M (a witness, not the closest pair), or '0'.\n"
    "With --solid, where one mesh lies inside the other: '1 ia -1' or '1 -1 ib' (the inner mesh's\n"
    "triangle 0).\n"
    "  --margin M        M >= 0, finite (default 0)\n";

static const char ttd_mesh_usage_self[] =
    "\n"
    "self-contacts: every pair of triangles i < j of A at distance <= M that share no vertex (by\n"
    "index: neighbours in the mesh touch by construction), one line per pair, sorted by i then j:\n"
    "    i j d px py pz qx qy qz\n"
    "  p on triangle i, q on triangle j.\n"
    "  --margin M        M >= 0, finite (required)\n"
    "  --count           print only the number of pairs (counted, not held)\n"
    "self-collide: whether A comes within M of itself (0: intersects itself), by those pairs: '1 i j'\n"
    "with the first pair found (i < j), or '0'.\n"
    "  --margin M        M >= 0, finite (default 0)\n"
    "both:\n"
    "  --shared-vertex   also pairs that share exactly one vertex v, by how near they come away from\n"
    "                    it: the nearer of each triangle's edge opposite v against the other\n"
    "                    triangle (what a cloth solver needs where a sheet folds at a vertex;\n"
    "                    include/ttd/ttd.h, ttd_mesh_self_contacts_d)\n"
    "  --pose, --poses, --solid and --per-triangle do not apply.\n";

static const char ttd_mesh_usage_common[] =
    "\n"
    "options:\n"
    "  --pose P          one argument of 12 numbers separated by blanks, the 3x4 matrix [R | t] row\n"
    "                    by row (r00 r01 r02 t0 r10 r11 r12 t1 r20 r21 r22 t2), mapping B's\n"
    "                    coordinates into A's frame: x_A = R x_B + t; or 16, the 4x4 matrix row\n"
    "                    by row, whose bottom row must be 0 0 0 1. R must be a rotation: every\n"
    "                    entry of R^T R - I within 1e-6 and det R > 0. Example:\n"
    "                    --pose \"1 0 0 0  0 1 0 0  0 0 1 5\" (B moved by 5 along z)\n"
    "  --orthonormalize  replace each pose's R by the nearest rotation (its polar factor) before\n"
    "                    the check, for poses printed with few digits: R must be within 1e-2 of\n"
    "                    orthonormal (every entry of R^T R - I) with det R > 0\n"
    "  --poses FILE      one such pose per line ('-': standard input); blank lines and '#'\n"
    "                    comments are skipped. The whole file is read and checked first (its poses\n"
    "                    are kept in memory, 96 bytes each). Output line i (distance, collide,\n"
    "                    --count) belongs to pose i; a file without poses gives no output.\n"
    "                    Without --pose or --poses, B is used as given (the identity pose).\n"
    "  --solid           distance and collide only: treat A and B as solids, so that one inside\n"
    "                    the other collides at distance 0 (both must be closed meshes). Without\n"
    "                    it the queries compare surfaces, as FCL's do: a mesh inside another is\n"
    "                    at the distance between their surfaces\n"
    "  --strict          refuse an OBJ line that is not an OBJ statement (such as FCL's header\n"
    "                    line of two counts); by default such lines are skipped, counted, and\n"
    "                    reported once on standard error\n"
    "  --weld TOL        merge the vertices of each mesh within distance TOL of each other (chained),\n"
    "                    dropping triangles that collapse, for STL-like files whose facets repeat\n"
    "                    their corners with last-bit differences (docs/mesh-files.md, Welding)\n"
    "  --precision P     double (default; printed with %%.17g) or float: meshes read with float\n"
    "                    coordinates rounded once from the file's text, poses, margin and bounds\n"
    "                    parsed with strtof, the queries run in float, printed with %%.9g\n"
    "  --isa I           %s (default auto; TTD_ISA may force one)\n"
    "  --threads N       worker threads, 0 = every core (default); poses are spread over them,\n"
    "                    and the results do not depend on N\n"
    "  --help            this text\n"
    "\n"
    "\n"
    "Numbers: the meshes' coordinates, and B's under every pose, must stay within 2^60 (float)\n"
    "or 2^508 (double) in magnitude; a mesh or a pose beyond that is refused (exit 1).\n"
    "Exit status: 0 done; 1 a mesh file or poses file that cannot be read or is malformed (the\n"
    "message names the file and line or byte offset; nothing is printed on standard output), a\n"
    "pose moving B out of range, a library error, or an output error; 2 bad command line (unknown\n"
    "option or command, a missing or extra operand, a bad value, a --pose that is not 12 or 16\n"
    "finite numbers or not a rotation).\n";

/* The usage of one command, or of all (cmd < 0). */
static void ttd_mesh_print_usage(FILE *f, int cmd)
{
    char isas[256] = "";
    for (int i = 0; i < TTD_ISA_COUNT; ++i)
        snprintf(isas + strlen(isas), sizeof isas - strlen(isas), "%s%s", i ? "|" : "", ttd_isa_name((ttd_isa)i));
    for (int c = 0; c < TTD_MESH_NCMD; ++c)
        if (cmd < 0 || cmd == c)
            fprintf(f, "%s%s", c == (cmd < 0 ? 0 : cmd) ? "usage: " : "       ", ttd_mesh_synopsis[c]);
    if (cmd < 0)
        fputs("       ttd mesh mass A [--density RHO] [--json] [options]   (ttd mesh mass --help)\n", f);
    fputs(ttd_mesh_usage_head, f);
    if (cmd < 0 || cmd == TTD_MESH_DISTANCE)
        fputs(ttd_mesh_usage_distance, f);
    if (cmd < 0 || cmd == TTD_MESH_CONTACTS)
        fputs(ttd_mesh_usage_contacts, f);
    if (cmd < 0 || cmd == TTD_MESH_COLLIDE)
        fputs(ttd_mesh_usage_collide, f);
    if (cmd < 0 || ttd_mesh_is_self((ttd_mesh_cmd)cmd))
        fputs(ttd_mesh_usage_self, f);
    fprintf(f, ttd_mesh_usage_common, isas);
}

/* ---- options ------------------------------------------------------------------------------ */

typedef struct ttd_mesh_args {
    ttd_mesh_cmd cmd;
    const char *name;                 /* "mesh distance" etc., for messages */
    ttd_options opt;
    int use_float;
    const char *path_a, *path_b;
    const char *pose, *poses_path;    /* at most one of them */
    const char *margin_s, *upper_s, *rel_s;
    double margin, upper, rel;        /* float-rounded values with --precision float */
    int per_triangle, count;
    int orthonormalize;               /* --orthonormalize: R replaced by the nearest rotation */
    int strict;                       /* --strict: OBJ lines that are not statements refused */
    const char *weld_s;               /* --weld TOL: vertices within TOL merged after reading */
    double weld;
    unsigned self_flags;              /* --shared-vertex: TTD_SELF_SHARED_VERTEX */
} ttd_mesh_args;

/* A finite number >= 0 in the precision's type (strtof in float: rounded once); 0 or -1. */
static int ttd_mesh_parse_nonneg(const char *s, int use_float, double *out)
{
    char *end;
    errno = 0;
    double v = use_float ? (double)strtof(s, &end) : strtod(s, &end);
    if (end == s || *end != '\0' || !isfinite(v) || !(v >= 0))
        return -1;
    *out = v;
    return 0;
}

/* Options of `ttd mesh CMD`; --name value and --name=value both work. Returns 0, 1 after
 * --help, -1 on a bad command line (message printed). */
static int ttd_mesh_parse_args(int argc, char **argv, ttd_mesh_args *a)
{
    const char *name = a->name;
    a->opt = ttd_default_options();
    a->upper = (double)INFINITY;
    static const char *const flags[] = {"--per-triangle", "--count", "--shared-vertex", "--orthonormalize",
                                        "--strict",       "--solid", NULL};
    static const char *const valued[] = {"--pose",   "--poses",     "--margin", "--upper-bound",
                                         "--rel-tol", "--precision", "--isa",    "--threads", "--weld", NULL};
    ttd_cli_args w = ttd_cli_args_start(name, flags, valued, argc, argv);
    for (ttd_cli_arg k; (k = ttd_cli_next_arg(&w)) != TTD_ARG_END;) {
        const char *arg = w.arg, *opt = w.opt, *val = w.val;
        if (k == TTD_ARG_BAD)
            return -1;
        if (k == TTD_ARG_HELP) {
            ttd_mesh_print_usage(stdout, (int)a->cmd);
            return 1;
        }
        if (k == TTD_ARG_OPERAND) {
            if (a->path_a == NULL)
                a->path_a = arg;
            else if (a->path_b == NULL && !ttd_mesh_is_self(a->cmd))
                a->path_b = arg;
            else {
                ttd_cli_error("%s: unexpected argument '%s' (%s taken)", name, arg,
                              ttd_mesh_is_self(a->cmd) ? "one mesh file A is" : "two mesh files A and B are");
                return -1;
            }
            continue;
        }
        if (k == TTD_ARG_FLAG) {
            if (strcmp(opt, "--per-triangle") == 0 || strcmp(opt, "--count") == 0) {
                const int ok = a->cmd == TTD_MESH_CONTACTS || (opt[2] == 'c' && a->cmd == TTD_MESH_SELF_CONTACTS);
                if (!ok) {
                    ttd_cli_error("%s: %s is an option of mesh contacts%s only", name, opt,
                                  opt[2] == 'c' ? " and mesh self-contacts" : "");
                    return -1;
                }
                *(opt[2] == 'p' ? &a->per_triangle : &a->count) = 1;
            } else if (strcmp(opt, "--shared-vertex") == 0) {
                if (!ttd_mesh_is_self(a->cmd)) {
                    ttd_cli_error("%s: --shared-vertex is an option of mesh self-contacts and self-collide", name);
                    return -1;
                }
                a->self_flags = TTD_SELF_SHARED_VERTEX;
            } else if (strcmp(opt, "--solid") == 0) {
                if (a->cmd == TTD_MESH_CONTACTS || ttd_mesh_is_self(a->cmd)) {
                    ttd_cli_error("%s: --solid is an option of mesh distance and collide (contacts are between "
                                  "surfaces)", name);
                    return -1;
                }
                a->opt.solid = 1;
            } else {
                *(opt[2] == 'o' ? &a->orthonormalize : &a->strict) = 1;
            }
            continue;
        }
        int bad = 0;
        if ((strcmp(opt, "--pose") == 0 || strcmp(opt, "--poses") == 0) && ttd_mesh_is_self(a->cmd)) {
            ttd_cli_error("%s: %s does not apply (one mesh against itself)", name, opt);
            return -1;
        } else if (strcmp(opt, "--pose") == 0)
            a->pose = val;
        else if (strcmp(opt, "--poses") == 0)
            a->poses_path = val;
        else if (strcmp(opt, "--weld") == 0) {
            a->weld_s = val;
            bad = ttd_cli_parse_weld(val, &a->weld) != 0;
        } else if (strcmp(opt, "--margin") == 0) {
            if (a->cmd == TTD_MESH_DISTANCE) {
                ttd_cli_error("%s: --margin is an option of mesh contacts and mesh collide", name);
                return -1;
            }
            a->margin_s = val;
        } else if (strcmp(opt, "--upper-bound") == 0 || strcmp(opt, "--rel-tol") == 0) {
            if (a->cmd != TTD_MESH_DISTANCE) {
                ttd_cli_error("%s: %s is an option of mesh distance only", name, opt);
                return -1;
            }
            *(opt[2] == 'u' ? &a->upper_s : &a->rel_s) = val;
        } else {
            bad = ttd_cli_run_option(opt, val, &a->opt, &a->use_float) < 0;
        }
        if (bad) {
            ttd_cli_bad_value(&w, NULL);
            return -1;
        }
    }
    if (ttd_mesh_is_self(a->cmd) && a->path_a == NULL) {
        ttd_cli_error("%s: the mesh file A is missing (see ttd %s --help)", name, name);
        return -1;
    }
    if (ttd_mesh_is_self(a->cmd))
        a->path_b = a->path_a; /* the mesh against itself */
    if (a->path_b == NULL) {
        ttd_cli_error("%s: %s (see ttd %s --help)", name,
                      a->path_a == NULL ? "the mesh files A and B are missing" : "the mesh file B is missing", name);
        return -1;
    }
    if (a->pose && a->poses_path) {
        ttd_cli_error("%s: --pose and --poses do not go together", name);
        return -1;
    }
    if (a->poses_path && strcmp(a->poses_path, "-") == 0 &&
        (strcmp(a->path_a, "-") == 0 || strcmp(a->path_b, "-") == 0)) {
        ttd_cli_error("%s: standard input cannot hold both a mesh and the poses", name);
        return -1;
    }
    if ((a->cmd == TTD_MESH_CONTACTS || a->cmd == TTD_MESH_SELF_CONTACTS) && a->margin_s == NULL) {
        ttd_cli_error("%s: --margin M is required", name);
        return -1;
    }
    /* Numbers are parsed once the precision is known, whatever the order of the options. */
    const struct {
        const char *s, *opt;
        double *v;
    } reals[] = {{a->margin_s, "--margin", &a->margin}, {a->upper_s, "--upper-bound", &a->upper},
                 {a->rel_s, "--rel-tol", &a->rel}};
    for (size_t k = 0; k < sizeof reals / sizeof reals[0]; ++k) {
        if (reals[k].s && ttd_mesh_parse_nonneg(reals[k].s, a->use_float, reals[k].v) != 0) {
            ttd_cli_error("%s: bad value for %s: '%s' (a finite number >= 0%s)", name, reals[k].opt, reals[k].s,
                          a->use_float ? " in float range" : "");
            return -1;
        }
    }
    return 0;
}

/* ---- poses -------------------------------------------------------------------------------- */

/* The defect of R (the largest |entry| of R^T R - I) and det R, of a pose's 12 numbers. */
static double ttd_mesh_pose_defect(const double p[12], double *det_out)
{
    const double r[9] = {p[0], p[1], p[2], p[4], p[5], p[6], p[8], p[9], p[10]};
    *det_out = r[0] * (r[4] * r[8] - r[5] * r[7]) - r[1] * (r[3] * r[8] - r[5] * r[6]) +
               r[2] * (r[3] * r[7] - r[4] * r[6]);
    double defect = 0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            const double g = r[i] * r[j] + r[3 + i] * r[3 + j] + r[6 + i] * r[6 + j];
            defect = fmax(defect, fabs(g - (i == j ? 1.0 : 0.0)));
        }
    return defect;
}

/* Why 12 finite numbers are not a pose the library takes (its test, include/ttd/ttd.h: every
 * entry of R^T R - I within 1e-6, det R > 0, computed in double), or 0 when they are one. With
 * ortho (--orthonormalize), R is first replaced by the nearest rotation when det R > 0 and its
 * defect is at most TTD_MESH_ORTHONORMALIZE_TOLERANCE: the polar factor of R, by Newton's
 * iteration R <- (R + R^-T) / 2, which converges quadratically from near a rotation (a handful
 * of steps from a defect of 1e-2 to rounding). */
int ttd_cli_pose_problem(double p[12], int ortho, char *err, size_t errsize)
{
    double det;
    double defect = ttd_mesh_pose_defect(p, &det);
    if (ortho && det > 0 && defect > 0 && defect <= TTD_MESH_ORTHONORMALIZE_TOLERANCE) {
        double r[9] = {p[0], p[1], p[2], p[4], p[5], p[6], p[8], p[9], p[10]};
        for (int it = 0; it < 30; ++it) {
            const double c[9] = {r[4] * r[8] - r[5] * r[7], r[5] * r[6] - r[3] * r[8], r[3] * r[7] - r[4] * r[6],
                                 r[2] * r[7] - r[1] * r[8], r[0] * r[8] - r[2] * r[6], r[1] * r[6] - r[0] * r[7],
                                 r[1] * r[5] - r[2] * r[4], r[2] * r[3] - r[0] * r[5], r[0] * r[4] - r[1] * r[3]};
            const double d = r[0] * c[0] + r[1] * c[1] + r[2] * c[2]; /* R^-T = cofactors / det */
            double change = 0;
            for (int i = 0; i < 9; ++i) {
                const double next = 0.5 * (r[i] + c[i] / d);
                change = fmax(change, fabs(next - r[i]));
                r[i] = next;
            }
            if (change <= 1e-15)
                break;
        }
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                p[4 * i + j] = r[3 * i + j];
        defect = ttd_mesh_pose_defect(p, &det);
    }
    if (!(det > 0)) {
        snprintf(err, errsize, "not a rotation: det R = %.17g <= 0%s", det,
                 defect <= TTD_MESH_POSE_TOLERANCE ? " (a reflection)" : "");
        return -1;
    }
    if (!(defect <= TTD_MESH_POSE_TOLERANCE)) {
        if (ortho)
            snprintf(err, errsize,
                     "not a rotation: R is not orthonormal (an entry of R^T R - I is %.3g; --orthonormalize "
                     "repairs at most %g)",
                     defect, TTD_MESH_ORTHONORMALIZE_TOLERANCE);
        else
            snprintf(err, errsize,
                     "not a rotation: R is not orthonormal (an entry of R^T R - I is %.3g, at most 1e-6 allowed; "
                     "--orthonormalize replaces R by the nearest rotation)",
                     defect);
        return -1;
    }
    return 0;
}

/* The poses of a run: 12 doubles each (exact floats with --precision float), and their float
 * copy when the queries run in float. */
typedef struct ttd_mesh_poses {
    double *d;
    float *f;
    size_t k, cap;
} ttd_mesh_poses;

static int ttd_mesh_poses_add(ttd_mesh_poses *ps, const double v[12])
{
    if (ps->k == ps->cap) {
        size_t cap = ps->cap ? 2 * ps->cap : 64;
        double *d = cap > SIZE_MAX / (12 * sizeof *d) ? NULL : realloc(ps->d, cap * 12 * sizeof *d);
        if (d == NULL)
            return -1;
        ps->d = d;
        ps->cap = cap;
    }
    memcpy(ps->d + 12 * ps->k++, v, 12 * sizeof *v);
    return 0;
}

/* Reads every pose of the file; 0, or the exit status after the messages. */
static int ttd_mesh_read_poses(const ttd_mesh_args *a, ttd_mesh_poses *ps)
{
    const int from_stdin = strcmp(a->poses_path, "-") == 0;
    const char *fname = from_stdin ? "<stdin>" : a->poses_path;
    FILE *in = from_stdin ? stdin : fopen(a->poses_path, "rb");
    if (in == NULL) {
        ttd_cli_error("%s: cannot open: %s", fname, strerror(errno));
        return TTD_EXIT_INPUT;
    }
    ttd_line_reader *r = malloc(sizeof *r);
    int rc = 0;
    unsigned long long bad = 0;
    size_t index = 0; /* of the next pose line, good or bad */
    if (r == NULL) {
        ttd_cli_error("out of memory");
        rc = TTD_EXIT_INPUT;
    } else {
        size_t len;
        int overlong;
        ttd_reader_init(r, in);
        while (rc == 0 && ttd_reader_next(r, &len, &overlong)) {
            double v[12];
            char err[256];
            ttd_line_kind kind = ttd_read_pose_line(r, len, overlong, a->use_float, v, err, sizeof err);
            if (kind == TTD_LINE_SKIP)
                continue;
            if (kind == TTD_LINE_PAIR && ttd_cli_pose_problem(v, a->orthonormalize, err, sizeof err) != 0)
                kind = TTD_LINE_ERROR;
            ++index;
            if (kind == TTD_LINE_ERROR) {
                if (bad < TTD_MESH_MAX_MESSAGES)
                    ttd_cli_error("%s:%llu: pose %zu: %s", fname, r->line_no, index - 1, err);
                else if (bad == TTD_MESH_MAX_MESSAGES)
                    ttd_cli_error("%s: more bad lines; only the first %d are shown", fname, TTD_MESH_MAX_MESSAGES);
                ++bad;
                continue;
            }
            if (bad == 0 && ttd_mesh_poses_add(ps, v) != 0) {
                ttd_cli_error("%s:%llu: out of memory for the poses", fname, r->line_no);
                rc = TTD_EXIT_INPUT;
            }
        }
        if (rc == 0 && r->error) {
            ttd_cli_error("%s: read error: %s", fname, strerror(r->error));
            rc = TTD_EXIT_INPUT;
        }
    }
    if (rc == 0 && bad > 0) {
        ttd_cli_error("%s: %llu bad pose line%s; nothing computed", fname, bad, bad == 1 ? "" : "s");
        rc = TTD_EXIT_INPUT;
    }
    free(r);
    if (!from_stdin)
        fclose(in);
    return rc;
}

/* The poses of a run: --pose (exit 2 when bad), --poses FILE (exit 1), or the identity. */
static int ttd_mesh_get_poses(const ttd_mesh_args *a, ttd_mesh_poses *ps)
{
    int rc = 0;
    if (a->poses_path) {
        rc = ttd_mesh_read_poses(a, ps);
    } else {
        double v[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
        if (a->pose) {
            char err[256];
            ttd_line_kind kind = ttd_parse_pose_line(a->pose, strlen(a->pose), a->use_float, v, err, sizeof err);
            if (kind != TTD_LINE_PAIR) {
                if (kind == TTD_LINE_SKIP) /* blank, or only a comment */
                    snprintf(err, sizeof err, "expected 12 numbers ([R | t], 3x4) or 16 (a 4x4 matrix), found 0");
                ttd_cli_error("%s: --pose '%s': %s", a->name, a->pose, err);
                return TTD_EXIT_USAGE;
            }
            if (ttd_cli_pose_problem(v, a->orthonormalize, err, sizeof err) != 0) {
                ttd_cli_error("%s: --pose '%s': %s", a->name, a->pose, err);
                return TTD_EXIT_USAGE;
            }
        }
        if (ttd_mesh_poses_add(ps, v) != 0) {
            ttd_cli_error("out of memory");
            return TTD_EXIT_INPUT;
        }
    }
    if (rc == 0 && a->use_float && ps->k > 0) {
        ps->f = malloc(12 * ps->k * sizeof *ps->f);
        if (ps->f == NULL) {
            ttd_cli_error("out of memory for the poses");
            return TTD_EXIT_INPUT;
        }
        for (size_t i = 0; i < 12 * ps->k; ++i)
            ps->f[i] = (float)ps->d[i];
    }
    return rc;
}

/* ---- meshes ------------------------------------------------------------------------------- */

/* Reads and builds one mesh; 0 or the exit status after the message. The file's arrays stay in
 * *file (the caller frees them): B's vertices are needed to check the poses. */
static int ttd_mesh_load(const ttd_mesh_args *a, const char *path, ttd_meshfile *file, ttd_mesh **out)
{
    char err[1024];
    const int flags = (a->use_float ? TTD_MESHFILE_FLOAT : 0) | (a->strict ? TTD_MESHFILE_STRICT : 0);
    if (ttd_meshfile_read(path, flags, file, err, sizeof err) != 0) {
        ttd_cli_error("%s", err);
        return TTD_EXIT_INPUT;
    }
    if (file->skipped_lines > 0) {
        const char *name = strcmp(path, "-") == 0 ? "<stdin>" : path;
        const int one = file->skipped_lines == 1;
        ttd_cli_error("%s: skipped %zu %s, first at %s:%zu (--strict refuses them)", name, file->skipped_lines,
                      one ? "line that is not an OBJ statement" : "lines that are not OBJ statements", name,
                      file->first_skipped_line);
    }
    if (a->weld_s && ttd_cli_weld(file, strcmp(path, "-") == 0 ? "<stdin>" : path, a->weld) != 0)
        return TTD_EXIT_INPUT;
    ttd_status st = a->use_float ? ttd_mesh_create_f(&a->opt, file->verts_f, file->nv, file->tris, file->nt, out)
                                 : ttd_mesh_create_d(&a->opt, file->verts, file->nv, file->tris, file->nt, out);
    if (st != TTD_OK) {
        ttd_cli_error("%s: cannot build the mesh: %s", strcmp(path, "-") == 0 ? "<stdin>" : path,
                      ttd_status_string(st));
        return TTD_EXIT_INPUT;
    }
    return 0;
}

/* Every pose checked against the meshes as the library's queries will check it (the coordinate
 * range: include/ttd/ttd.h), so that a refused pose is named; 0, or the exit status after the
 * message. */
static int ttd_mesh_check_range(const ttd_mesh_args *a, const ttd_mesh *ma, const ttd_mesh *mb,
                                const ttd_mesh_poses *ps)
{
    if (ps->k == 0)
        return 0;
    size_t bad;
    const ttd_status st = a->use_float ? ttd_mesh_check_poses_f(ma, mb, ps->k, ps->f, &bad)
                                       : ttd_mesh_check_poses_d(ma, mb, ps->k, ps->d, &bad);
    if (st == TTD_OK)
        return 0;
    if (bad == ps->k)
        ttd_cli_error("%s: %s", a->name, ttd_status_string(st));
    else if (a->poses_path)
        ttd_cli_error("%s: pose %zu: %s", a->name, bad, ttd_status_string(st));
    else
        ttd_cli_error("%s: --pose: %s", a->name, ttd_status_string(st));
    return TTD_EXIT_INPUT;
}

/* ---- output ------------------------------------------------------------------------------- */

/* The distance and the two points of a line, in the precision's format. */
static void ttd_mesh_put_dpq(FILE *out, int use_float, double d, const double p[3], const double q[3])
{
    fprintf(out, use_float ? "%.9g %.9g %.9g %.9g %.9g %.9g %.9g" : "%.17g %.17g %.17g %.17g %.17g %.17g %.17g", d,
            p[0], p[1], p[2], q[0], q[1], q[2]);
}

/* What one run holds while it computes and writes chunk after chunk. */
typedef struct ttd_mesh_run {
    const ttd_mesh_args *a;
    const ttd_mesh *ma, *mb;
    const ttd_mesh_poses *ps;
    FILE *out;
} ttd_mesh_run;

/* A library error: its message, with the poses of the call; returns the exit status. */
static int ttd_mesh_failed(const ttd_mesh_run *r, ttd_status st, size_t first, size_t k)
{
    if (st == TTD_ERR_MESH_NOT_CLOSED) { /* --solid: name the mesh, and what it is */
        ttd_orientation oa = TTD_ORIENTATION_OUTWARD, ob = TTD_ORIENTATION_OUTWARD;
        (void)ttd_mesh_orientation(r->ma, &oa);
        (void)ttd_mesh_orientation(r->mb, &ob);
        const int bad_a = oa == TTD_ORIENTATION_OPEN || oa == TTD_ORIENTATION_INCONSISTENT;
        ttd_cli_error("%s: --solid: mesh %s (%s) is %s: %s", r->a->name, bad_a ? "A" : "B",
                      bad_a ? r->a->path_a : r->a->path_b,
                      (bad_a ? oa : ob) == TTD_ORIENTATION_INCONSISTENT ? "inconsistently oriented" : "open",
                      ttd_status_string(st));
        return TTD_EXIT_INPUT;
    }
    if (r->ps->k > 1)
        ttd_cli_error("%s: poses %zu..%zu: %s", r->a->name, first, first + k - 1, ttd_status_string(st));
    else
        ttd_cli_error("%s: %s", r->a->name, ttd_status_string(st));
    return TTD_EXIT_INPUT;
}

static int ttd_mesh_run_distance(const ttd_mesh_run *r)
{
    const ttd_mesh_args *a = r->a;
    const size_t chunk = r->ps->k < TTD_MESH_POSE_CHUNK ? r->ps->k : TTD_MESH_POSE_CHUNK;
    ttd_mesh_result_d *rd = a->use_float ? NULL : malloc(chunk * sizeof *rd);
    ttd_mesh_result_f *rf = a->use_float ? malloc(chunk * sizeof *rf) : NULL;
    int rc = 0;
    if (rd == NULL && rf == NULL) {
        ttd_cli_error("out of memory");
        return TTD_EXIT_INPUT;
    }
    for (size_t first = 0; first < r->ps->k && rc == 0 && !ferror(r->out); first += chunk) {
        const size_t k = r->ps->k - first < chunk ? r->ps->k - first : chunk;
        ttd_status st = a->use_float ? ttd_mesh_distance_f(&a->opt, r->ma, r->mb, k, r->ps->f + 12 * first,
                                                           (float)a->upper, (float)a->rel, rf)
                                     : ttd_mesh_distance_d(&a->opt, r->ma, r->mb, k, r->ps->d + 12 * first, a->upper,
                                                           a->rel, rd);
        if (st != TTD_OK) {
            rc = ttd_mesh_failed(r, st, first, k);
            break;
        }
        for (size_t i = 0; i < k; ++i) {
            double d, p[3], q[3];
            uint32_t ta, tb;
            unsigned flags;
            if (a->use_float) {
                d = (double)rf[i].distance;
                for (int c = 0; c < 3; ++c) {
                    p[c] = (double)rf[i].p[c];
                    q[c] = (double)rf[i].q[c];
                }
                ta = rf[i].tri_a;
                tb = rf[i].tri_b;
                flags = rf[i].flags;
            } else {
                d = rd[i].distance;
                memcpy(p, rd[i].p, sizeof p);
                memcpy(q, rd[i].q, sizeof q);
                ta = rd[i].tri_a;
                tb = rd[i].tri_b;
                flags = rd[i].flags;
            }
            if (flags & TTD_MESH_ABOVE_BOUND) {
                fputs("inf nan nan nan nan nan nan -1 -1\n", r->out);
                continue;
            }
            ttd_mesh_put_dpq(r->out, a->use_float, d, p, q);
            /* --solid, one mesh inside the other: the outer mesh has no triangle to name */
            fprintf(r->out, " %ld %ld\n", ta == UINT32_MAX ? -1L : (long)ta, tb == UINT32_MAX ? -1L : (long)tb);
        }
    }
    free(rd);
    free(rf);
    return rc;
}

static int ttd_mesh_run_collide(const ttd_mesh_run *r)
{
    const ttd_mesh_args *a = r->a;
    const size_t chunk = r->ps->k < TTD_MESH_POSE_CHUNK ? r->ps->k : TTD_MESH_POSE_CHUNK;
    ttd_collision *res = malloc(chunk * sizeof *res);
    int rc = 0;
    if (res == NULL) {
        ttd_cli_error("out of memory");
        return TTD_EXIT_INPUT;
    }
    for (size_t first = 0; first < r->ps->k && !ferror(r->out); first += chunk) {
        const size_t k = r->ps->k - first < chunk ? r->ps->k - first : chunk;
        ttd_status st;
        if (ttd_mesh_is_self(a->cmd)) /* one pose, the identity */
            st = a->use_float ? ttd_mesh_self_collide_f(&a->opt, r->ma, (float)a->margin, a->self_flags, res)
                              : ttd_mesh_self_collide_d(&a->opt, r->ma, a->margin, a->self_flags, res);
        else
            st = a->use_float ? ttd_mesh_collide_f(&a->opt, r->ma, r->mb, k, r->ps->f + 12 * first, (float)a->margin, res)
                              : ttd_mesh_collide_d(&a->opt, r->ma, r->mb, k, r->ps->d + 12 * first, a->margin, res);
        if (st != TTD_OK) {
            rc = ttd_mesh_failed(r, st, first, k);
            break;
        }
        for (size_t i = 0; i < k; ++i) {
            if (res[i].hit)
                fprintf(r->out, "1 %ld %ld\n", res[i].tri_a == UINT32_MAX ? -1L : (long)res[i].tri_a,
                        res[i].tri_b == UINT32_MAX ? -1L : (long)res[i].tri_b);
            else
                fputs("0\n", r->out);
        }
    }
    free(res);
    return rc;
}

static int ttd_contact_cmp_d(const void *x, const void *y)
{
    const ttd_contact_d *u = x, *v = y;
    if (u->tri_a != v->tri_a)
        return u->tri_a < v->tri_a ? -1 : 1;
    return (u->tri_b > v->tri_b) - (u->tri_b < v->tri_b);
}

static int ttd_contact_cmp_f(const void *x, const void *y)
{
    const ttd_contact_f *u = x, *v = y;
    if (u->tri_a != v->tri_a)
        return u->tri_a < v->tri_a ? -1 : 1;
    return (u->tri_b > v->tri_b) - (u->tri_b < v->tri_b);
}

/* Poses of the next contact chunk: about TTD_MESH_PAIR_TARGET pairs at the rate seen so far. */
static size_t ttd_mesh_next_chunk(size_t pairs_seen, size_t poses_seen, size_t left)
{
    size_t chunk = TTD_MESH_POSE_CHUNK;
    if (poses_seen > 0 && pairs_seen > 0) {
        const double per_pose = (double)pairs_seen / (double)poses_seen;
        const double fit = (double)TTD_MESH_PAIR_TARGET / per_pose;
        chunk = fit < 1 ? 1 : fit < (double)TTD_MESH_POSE_CHUNK ? (size_t)fit : TTD_MESH_POSE_CHUNK;
    } else if (poses_seen == 0) {
        chunk = 16; /* a first look before the rate is known */
    }
    return chunk < left ? chunk : left;
}

/* --count: the library counts each pose's pairs without holding them (ttd_mesh_contacts_count_*),
 * so a count of millions of pairs takes no memory for them. */
static int ttd_mesh_run_contacts_count(const ttd_mesh_run *r)
{
    const ttd_mesh_args *a = r->a;
    size_t counts[TTD_MESH_POSE_CHUNK];
    int rc = 0;
    for (size_t first = 0, k; first < r->ps->k && !ferror(r->out); first += k) {
        k = ttd_mesh_is_self(a->cmd) ? 1 : r->ps->k - first < TTD_MESH_POSE_CHUNK ? r->ps->k - first : TTD_MESH_POSE_CHUNK;
        ttd_status st;
        if (ttd_mesh_is_self(a->cmd)) /* one pose, the identity */
            st = a->use_float ? ttd_mesh_self_contacts_count_f(&a->opt, r->ma, (float)a->margin, a->self_flags, counts)
                              : ttd_mesh_self_contacts_count_d(&a->opt, r->ma, a->margin, a->self_flags, counts);
        else
            st = a->use_float
                     ? ttd_mesh_contacts_count_f(&a->opt, r->ma, r->mb, k, r->ps->f + 12 * first, (float)a->margin, counts)
                     : ttd_mesh_contacts_count_d(&a->opt, r->ma, r->mb, k, r->ps->d + 12 * first, a->margin, counts);
        if (st != TTD_OK) {
            rc = ttd_mesh_failed(r, st, first, k);
            break;
        }
        for (size_t i = 0; i < k; ++i)
            fprintf(r->out, "%zu\n", counts[i]);
    }
    return rc;
}

static int ttd_mesh_run_contacts(const ttd_mesh_run *r)
{
    const ttd_mesh_args *a = r->a;
    if (a->count)
        return ttd_mesh_run_contacts_count(r);
    const int indexed = a->poses_path != NULL;
    ttd_contacts_d sd = {0};
    ttd_contacts_f sf = {0};
    size_t pairs_seen = 0;
    int rc = 0;
    for (size_t first = 0, k; first < r->ps->k && !ferror(r->out); first += k) {
        k = ttd_mesh_next_chunk(pairs_seen, first, r->ps->k - first);
        ttd_status st;
        if (ttd_mesh_is_self(a->cmd)) /* one pose, the identity */
            st = a->use_float ? ttd_mesh_self_contacts_f(&a->opt, r->ma, (float)a->margin, a->self_flags, &sf)
                              : ttd_mesh_self_contacts_d(&a->opt, r->ma, a->margin, a->self_flags, &sd);
        else
            st = a->use_float ? ttd_mesh_contacts_f(&a->opt, r->ma, r->mb, k, r->ps->f + 12 * first, (float)a->margin, &sf)
                              : ttd_mesh_contacts_d(&a->opt, r->ma, r->mb, k, r->ps->d + 12 * first, a->margin, &sd);
        if (st != TTD_OK) {
            rc = ttd_mesh_failed(r, st, first, k);
            break;
        }
        const size_t *start = a->use_float ? sf.pose_start : sd.pose_start;
        pairs_seen += a->use_float ? sf.count : sd.count;
        for (size_t i = 0; i < k; ++i) {
            const size_t lo = start[i], hi = start[i + 1];
            if (a->count) {
                fprintf(r->out, "%zu\n", hi - lo);
                continue;
            }
            if (hi == lo) /* pairs may be NULL then */
                continue;
            if (a->use_float)
                qsort(sf.pairs + lo, hi - lo, sizeof *sf.pairs, ttd_contact_cmp_f);
            else
                qsort(sd.pairs + lo, hi - lo, sizeof *sd.pairs, ttd_contact_cmp_d);
            for (size_t j = lo; j < hi; ++j) {
                double d, p[3], q[3];
                uint32_t ta, tb;
                if (a->use_float) {
                    const ttd_contact_f *c = &sf.pairs[j];
                    d = (double)c->distance;
                    for (int m = 0; m < 3; ++m) {
                        p[m] = (double)c->p[m];
                        q[m] = (double)c->q[m];
                    }
                    ta = c->tri_a;
                    tb = c->tri_b;
                } else {
                    const ttd_contact_d *c = &sd.pairs[j];
                    d = c->distance;
                    memcpy(p, c->p, sizeof p);
                    memcpy(q, c->q, sizeof q);
                    ta = c->tri_a;
                    tb = c->tri_b;
                }
                if (indexed)
                    fprintf(r->out, "%zu ", first + i);
                fprintf(r->out, "%lu %lu ", (unsigned long)ta, (unsigned long)tb);
                ttd_mesh_put_dpq(r->out, a->use_float, d, p, q);
                fputc('\n', r->out);
            }
        }
    }
    ttd_contacts_free_d(&sd);
    ttd_contacts_free_f(&sf);
    return rc;
}

/* One per-triangle record widened to double; 0 when the triangle has no partner. */
static int ttd_mesh_closest_get(const ttd_mesh_args *a, const void *base, size_t i, uint32_t *partner, double *d,
                                double p[3], double q[3])
{
    if (a->use_float) {
        const ttd_closest_f *c = (const ttd_closest_f *)base + i;
        if (c->partner == UINT32_MAX)
            return 0;
        *partner = c->partner;
        *d = (double)c->distance;
        for (int m = 0; m < 3; ++m) {
            p[m] = (double)c->p[m];
            q[m] = (double)c->q[m];
        }
    } else {
        const ttd_closest_d *c = (const ttd_closest_d *)base + i;
        if (c->partner == UINT32_MAX)
            return 0;
        *partner = c->partner;
        *d = c->distance;
        memcpy(p, c->p, 3 * sizeof *p);
        memcpy(q, c->q, 3 * sizeof *q);
    }
    return 1;
}

static int ttd_mesh_run_closest(const ttd_mesh_run *r)
{
    const ttd_mesh_args *a = r->a;
    const int indexed = a->poses_path != NULL;
    const size_t nta = ttd_mesh_triangle_count(r->ma), ntb = ttd_mesh_triangle_count(r->mb);
    const size_t per_pose = nta + ntb; /* both at least 1, and each below 2^32 */
    size_t chunk = TTD_MESH_PAIR_TARGET / per_pose;
    chunk = chunk < 1 ? 1 : chunk > TTD_MESH_POSE_CHUNK ? TTD_MESH_POSE_CHUNK : chunk;
    chunk = chunk < r->ps->k ? chunk : r->ps->k;
    const size_t rec = a->use_float ? sizeof(ttd_closest_f) : sizeof(ttd_closest_d);
    void *fa = chunk * nta > SIZE_MAX / rec ? NULL : malloc(chunk * nta * rec);
    void *fb = chunk * ntb > SIZE_MAX / rec ? NULL : malloc(chunk * ntb * rec);
    int rc = 0;
    if (fa == NULL || fb == NULL) {
        ttd_cli_error("out of memory for %zu per-triangle records", chunk * per_pose);
        free(fa);
        free(fb);
        return TTD_EXIT_INPUT;
    }
    for (size_t first = 0; first < r->ps->k && !ferror(r->out); first += chunk) {
        const size_t k = r->ps->k - first < chunk ? r->ps->k - first : chunk;
        ttd_status st = a->use_float ? ttd_mesh_closest_f(&a->opt, r->ma, r->mb, k, r->ps->f + 12 * first,
                                                          (float)a->margin, fa, fb)
                                     : ttd_mesh_closest_d(&a->opt, r->ma, r->mb, k, r->ps->d + 12 * first, a->margin,
                                                          fa, fb);
        if (st != TTD_OK) {
            rc = ttd_mesh_failed(r, st, first, k);
            break;
        }
        for (size_t i = 0; i < k; ++i) {
            size_t na = 0, nb = 0;
            for (int side = 0; side < 2; ++side) {
                const size_t nt = side ? ntb : nta;
                const void *base = side ? fb : fa;
                for (size_t t = 0; t < nt; ++t) {
                    uint32_t partner;
                    double d, p[3], q[3];
                    if (!ttd_mesh_closest_get(a, base, i * nt + t, &partner, &d, p, q))
                        continue;
                    ++*(side ? &nb : &na);
                    if (a->count)
                        continue;
                    if (indexed)
                        fprintf(r->out, "%zu ", first + i);
                    fprintf(r->out, "%c %zu %lu ", side ? 'b' : 'a', t, (unsigned long)partner);
                    ttd_mesh_put_dpq(r->out, a->use_float, d, p, q);
                    fputc('\n', r->out);
                }
            }
            if (a->count)
                fprintf(r->out, "%zu %zu\n", na, nb);
        }
    }
    free(fa);
    free(fb);
    return rc;
}

/* ---- the command -------------------------------------------------------------------------- */

/* The instruction set is checked before any file is read (as `ttd dist` does); 0 or 2. */
static int ttd_mesh_check_isa(const ttd_mesh_args *a)
{
    if (ttd_isa_selected(&a->opt) == TTD_ISA_AUTO) {
        ttd_cli_error("%s: --isa %s is not available here; this machine has:", a->name, ttd_isa_name(a->opt.isa));
        ttd_cli_print_isas(stderr);
        return TTD_EXIT_USAGE;
    }
    ttd_cli_warn_isa_env(a->name);
    return 0;
}

int ttd_cli_mesh(int argc, char **argv)
{
    if (argc < 2) {
        ttd_mesh_print_usage(stderr, -1);
        return TTD_EXIT_USAGE;
    }
    const char *sub = argv[1];
    if (strcmp(sub, "--help") == 0 || strcmp(sub, "-h") == 0 || strcmp(sub, "help") == 0) {
        ttd_mesh_print_usage(stdout, -1);
        return TTD_EXIT_OK;
    }
    if (strcmp(sub, "mass") == 0) /* one mesh, no pose, no query options: cli/mesh_mass.c */
        return ttd_cli_mesh_mass(argc - 1, argv + 1);
    ttd_mesh_args a;
    memset(&a, 0, sizeof a);
    static const char *const full_names[] = {"mesh distance", "mesh contacts", "mesh collide", "mesh self-contacts",
                                             "mesh self-collide"};
    int cmd = -1;
    for (int c = 0; c < TTD_MESH_NCMD; ++c)
        if (strcmp(sub, ttd_mesh_cmd_names[c]) == 0)
            cmd = c;
    if (cmd < 0) {
        ttd_cli_error("mesh: unknown command '%s' (distance, contacts, collide, self-contacts, self-collide or "
                      "mass; see ttd mesh --help)",
                      sub);
        return TTD_EXIT_USAGE;
    }
    a.cmd = (ttd_mesh_cmd)cmd;
    a.name = full_names[cmd];
    int rc = ttd_mesh_parse_args(argc - 1, argv + 1, &a);
    if (rc != 0)
        return rc > 0 ? TTD_EXIT_OK : TTD_EXIT_USAGE;
    if ((rc = ttd_mesh_check_isa(&a)) != 0)
        return rc;

    ttd_mesh_poses ps = {0};
    ttd_meshfile fa = {0}, fb = {0};
    ttd_mesh *ma = NULL, *mb = NULL;
    const int same = strcmp(a.path_a, a.path_b) == 0; /* read once, also from standard input */
    rc = ttd_mesh_get_poses(&a, &ps);
    if (rc == 0)
        rc = ttd_mesh_load(&a, a.path_a, &fa, &ma);
    if (rc == 0 && !same)
        rc = ttd_mesh_load(&a, a.path_b, &fb, &mb);
    if (rc == 0)
        rc = ttd_mesh_check_range(&a, ma, mb ? mb : ma, &ps);
    if (rc == 0 && ps.k > 0) {
        static char outbuf[1 << 16];
        setvbuf(stdout, outbuf, _IOFBF, sizeof outbuf);
        const ttd_mesh_run r = {.a = &a, .ma = ma, .mb = mb ? mb : ma, .ps = &ps, .out = stdout};
        rc = a.cmd == TTD_MESH_DISTANCE                                 ? ttd_mesh_run_distance(&r)
             : a.cmd == TTD_MESH_COLLIDE || a.cmd == TTD_MESH_SELF_COLLIDE ? ttd_mesh_run_collide(&r)
             : a.per_triangle                                           ? ttd_mesh_run_closest(&r)
                                                                        : ttd_mesh_run_contacts(&r);
    }
    if (fflush(stdout) != 0 || ferror(stdout)) {
        ttd_cli_error("error writing the output");
        rc = TTD_EXIT_INPUT;
    }
    ttd_mesh_destroy(ma);
    ttd_mesh_destroy(mb);
    ttd_meshfile_free(&fa);
    ttd_meshfile_free(&fb);
    free(ps.d);
    free(ps.f);
    return rc;
}
