/* SPDX-License-Identifier: MIT */
/* `ttd scene collide | distance | contacts | manifold SCENE [options]`: the library's scene
 * queries (include/ttd/ttd.h, "Scenes") on bodies read from a scene file, at its poses or at
 * every step of a motion file. The usage text below is the reference for the formats;
 * docs/scenes-cli.md has them with examples.
 *
 * As `ttd mesh` does, everything that can be checked is checked before anything is computed,
 * so that a run either prints its whole answer or nothing but messages: options (exit 2), then
 * the scene file, line by line (every bad line named FILE:LINE, its meshes read with the mesh
 * reader and built, its bodies added, their filters and excluded pairs set), then the whole
 * motion file (every bad line named, each pose checked against its body's mesh, the steps
 * counted off by the bodies or by `step` lines), all exit 1. Only then does a query run, once,
 * or once per step of the motion (the poses of step s set with ttd_scene_set_poses_*), and each
 * step's lines are written before the next step is computed.
 *
 * Lines come out sorted by (i, j), then by the triangles (ia, ib): the library's order, sorted
 * again here so that the output is a documented function of the input (a manifold's points are
 * kept in the library, deepest first and then spread, and printed in triangle order, then by
 * point: a triangle pair may give several). */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <math.h>
#include <time.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include <ttd/meshfile.h>
#include "parse.h"

/// Bad lines of a scene or motion file reported before the rest are only counted.
#define TTD_SCENE_MAX_MESSAGES 20

typedef enum ttd_scene_cmd { TTD_SCENE_COLLIDE, TTD_SCENE_DISTANCE, TTD_SCENE_CONTACTS, TTD_SCENE_MANIFOLD } ttd_scene_cmd;

static const char *const ttd_scene_cmd_names[] = {"collide", "distance", "contacts", "manifold"};
static const char *const ttd_scene_full_names[] = {"scene collide", "scene distance", "scene contacts",
                                                   "scene manifold"};

static const char ttd_scene_usage_text[] =
    "usage: ttd scene collide SCENE [--margin M] [--count] [options]\n"
    "       ttd scene distance SCENE [--margin M] [options]\n"
    "       ttd scene contacts SCENE [--margin M] [--count] [options]\n"
    "       ttd scene manifold SCENE [--margin M] [--max-points K] [--count] [options]\n"
    "Queries over every pair of bodies of a scene: bodies are triangle meshes (OBJ, STL, PLY, OFF, glTF or 3MF files)\n"
    "placed in the world by rigid poses. Every query is exact: the answer of the exact method over all\n"
    "triangle pairs of all body pairs, in the world frame (docs/scenes-cli.md).\n"
    "\n"
    "The scene file SCENE ('-' for standard input), one statement a line:\n"
    "    mesh NAME FILE\n"
    "        the mesh in FILE (OBJ, STL, PLY, OFF, glTF or 3MF, recognised by content), a path relative to the scene\n"
    "        file's folder (or absolute), known as NAME from then on\n"
    "    body MESH r00 r01 r02 t0 r10 r11 r12 t1 r20 r21 r22 t2 [name BODY]\n"
    "        a body of mesh MESH at the world pose [R | t] (x_world = R x_mesh + t), row by row; or\n"
    "        16 numbers, the 4x4 matrix row by row, whose bottom row must be 0 0 0 1; 'name BODY'\n"
    "        names it (a name is used once and does not start with a digit)\n"
    "    filter BODY GROUP MASK\n"
    "        the body's collision group and mask, 32 bits each (decimal or 0x hex): bodies i and j\n"
    "        are a pair only when (group_i & mask_j) and (group_j & mask_i) are both non-zero\n"
    "        (default: group 1, mask 0xffffffff)\n"
    "    exclude BODY BODY\n"
    "        the two bodies are not a pair\n"
    "    solid BODY\n"
    "        the body is a solid (its mesh must be closed): a pair of solids collides when one lies\n"
    "        inside the other (distance 0), and its manifold has points of each inside the other\n"
    "        at negative d, depth M - d past M (docs/scenes.md, section 5b)\n"
    "    '#' starts a comment (a whole line, or after a statement); blank lines are ignored.\n"
    "  Bodies are numbered 0, 1, 2, ... in file order; BODY is a body's name or number, from a body\n"
    "  line above. A mesh may serve any number of bodies. Names and FILE are one word each (no\n"
    "  blanks, no '#'). R must be a rotation: every entry of R^T R - I within 1e-6 and det R > 0\n"
    "  (see --orthonormalize).\n";

static const char ttd_scene_usage_outputs[] =
    "\n"
    "Outputs, one line per item, sorted by body pair (i, j), i < j, then by triangles (ia of body\n"
    "i, ib of body j; 0-based in file order, polygons fan-triangulated); points in the world:\n"
    "  collide    i j ia ib                      each body pair within M, with one witness pair of\n"
    "                                            triangles within M (the first found, not the closest)\n"
    "  distance   d i j ia ib px py pz qx qy qz  the closest body pair, one line: p on triangle ia of\n"
    "                                            body i, q on ib of body j; ties to the smallest (i, j),\n"
    "                                            then (ia, ib); d = 0 and p = q when they touch or cross;\n"
    "                                            'inf -1 -1 -1 -1 nan nan nan nan nan nan' when no pair\n"
    "                                            is within M (or the scene has fewer than two bodies)\n"
    "  contacts   i j ia ib d px py pz qx qy qz  every triangle pair within M\n"
    "  manifold   i j px py pz nx ny nz d depth ix iy iz jx jy jz key\n"
    "                                            per body pair within M, at most K contact points:\n"
    "                                            the midpoint of a point of each body (a triangle pair's\n"
    "                                            closest points, or a corner where faces lie on faces:\n"
    "                                            a vertex within M of the other face, a crossing of\n"
    "                                            edges), the\n"
    "                                            unit normal from body i towards body j, the two\n"
    "                                            points' distance d and depth M - d; no two within 1e-3\n"
    "                                            of the smaller body's radius; the K kept are the\n"
    "                                            deepest, then spread by area; normals from the\n"
    "                                            bodies' faces and real edges (docs/scenes-cli.md;\n"
    "                                            printed in triangle order, then by point); then the\n"
    "                                            point of body i, that of body j, and the contact's key\n"
    "                                            (16 hex digits: the features of both bodies it lies on,\n"
    "                                            the same while the contact persists)\n"
    "  i and j are body numbers; with --names, a named body's name.\n";

static const char ttd_scene_usage_options[] =
    "\n"
    "options:\n"
    "  --margin M        M >= 0, finite. collide, contacts, manifold: the margin (default 0: touching\n"
    "                    or crossing); distance: an upper bound (default none)\n"
    "  --count           collide, contacts, manifold: print only the number of lines instead\n"
    "  --max-points K    manifold: at most K points per body pair, 0 for all (default 4)\n"
    "  --nearest         distance: after the closest pair's line, one line per body (in body order)\n"
    "                    with its nearest body: 'd i j ia ib p q' with i the body, j its nearest (the\n"
    "                    smallest number at that distance), p on body i ('inf i -1 -1 -1 nan...'\n"
    "                    when none is within M)\n"
    "  --motion FILE     run the query once per step of the motion in FILE ('-': standard input):\n"
    "                    T steps back to back, each N lines of 12 (or 16) numbers, the new world\n"
    "                    poses of bodies 0..N-1 in order (N the bodies of the scene); blank lines and\n"
    "                    '#' comments are skipped. A line 'step' (or 'step S', S the step's index\n"
    "                    from 0) may open every step, and then each step must hold N poses exactly.\n"
    "                    The scene file's poses are where the bodies start;\n"
    "                    the queries run at the T steps only. Every output line then starts with the\n"
    "                    step's index (0-based), and --count prints 'step count', one line per step.\n"
    "                    The whole file is read and checked first (96 bytes a pose are kept).\n"
    "  --orthonormalize  replace each pose's R (scene and motion) by the nearest rotation before the\n"
    "                    check, for poses printed with few digits: R must be within 1e-2 of\n"
    "                    orthonormal (every entry of R^T R - I) with det R > 0\n"
    "  --names           print a named body's name for i and j (unnamed bodies: their number)\n"
    "  --stats           after each query, print on standard error what the library's last query did\n"
    "                    (ttd_scene_get_stats: candidate body pairs, node tests, triangle pairs given\n"
    "                    to the exact method, results) and its time (wall and process CPU, ms)\n"
    "  --repeat N        run each query N times (the answer printed once), for profiling one query;\n"
    "                    with --stats the times are the fastest and the median of the N\n"
    "  --solid           every body a solid, as a 'solid BODY' line for each would make it\n"
    "  --strict          refuse an OBJ line that is not an OBJ statement (skipped and reported once\n"
    "                    per file by default)\n"
    "  --weld TOL        merge each mesh's vertices within distance TOL of each other (chained),\n"
    "                    dropping collapsed triangles, before the bodies are made\n"
    "                    (docs/mesh-files.md, Welding)\n"
    "  --precision P     double (default; printed with %%.17g) or float: meshes read with float\n"
    "                    coordinates rounded once from the file's text, poses and margin parsed with\n"
    "                    strtof, the queries run in float, printed with %%.9g\n"
    "  --isa I           %s (default auto; TTD_ISA may force one)\n"
    "  --threads N       worker threads, 0 = every core (default); body pairs are spread over them,\n"
    "                    and the results do not depend on N\n"
    "  --help            this text\n"
    "\n"
    "Numbers: every mesh coordinate, and every body's under its poses, must stay within 2^60 (float)\n"
    "or 2^508 (double) in magnitude; a mesh or a pose beyond that is refused (exit 1).\n"
    "Exit status: 0 done; 1 a scene, mesh or motion file that cannot be read or is malformed (the\n"
    "message names the file and line; nothing is printed on standard output), a library error, or\n"
    "an output error; 2 bad command line (unknown option or command, a missing or extra operand, a\n"
    "bad value).\n";

static void ttd_scene_print_usage(FILE *f)
{
    char isas[256] = "";
    for (int i = 0; i < TTD_ISA_COUNT; ++i)
        snprintf(isas + strlen(isas), sizeof isas - strlen(isas), "%s%s", i ? "|" : "", ttd_isa_name((ttd_isa)i));
    fputs(ttd_scene_usage_text, f);
    fputs(ttd_scene_usage_outputs, f);
    fprintf(f, ttd_scene_usage_options, isas);
}

/* ---- options ------------------------------------------------------------------------------ */

typedef struct ttd_scene_args {
    ttd_scene_cmd cmd;
    const char *name; /* "scene collide" etc., for messages */
    ttd_options opt;
    int use_float;
    const char *path, *motion_path;
    const char *margin_s;
    double margin; /* float-rounded with --precision float; distance: +inf without --margin */
    size_t max_points;
    int count, orthonormalize, strict, names, stats, solid, nearest;
    long repeat;   /* --repeat: runs of each query (the last one printed) */
    const char *weld_s; /* --weld TOL: every mesh's vertices within TOL merged after reading */
    double weld;
} ttd_scene_args;

/* Options of `ttd scene CMD`; --name value and --name=value both work. Returns 0, 1 after
 * --help, -1 on a bad command line (message printed). */
static int ttd_scene_parse_args(int argc, char **argv, ttd_scene_args *a)
{
    const char *name = a->name;
    a->opt = ttd_default_options();
    a->max_points = 4;
    a->repeat = 1;
    static const char *const flags[] = {"--nearest", "--count", "--orthonormalize", "--strict",
                                        "--names",   "--stats", "--solid",          NULL};
    static const char *const valued[] = {"--margin", "--max-points", "--motion", "--precision",
                                         "--isa",    "--threads",    "--repeat", "--weld", NULL};
    ttd_cli_args w = ttd_cli_args_start(name, flags, valued, argc, argv);
    for (ttd_cli_arg k; (k = ttd_cli_next_arg(&w)) != TTD_ARG_END;) {
        const char *opt = w.opt, *val = w.val;
        if (k == TTD_ARG_BAD)
            return -1;
        if (k == TTD_ARG_HELP) {
            ttd_scene_print_usage(stdout);
            return 1;
        }
        if (k == TTD_ARG_OPERAND) {
            if (a->path != NULL) {
                ttd_cli_error("%s: unexpected argument '%s' (one scene file is taken)", name, w.arg);
                return -1;
            }
            a->path = w.arg;
            continue;
        }
        if (k == TTD_ARG_FLAG) {
            if (strcmp(opt, "--nearest") == 0 && a->cmd != TTD_SCENE_DISTANCE) {
                ttd_cli_error("%s: --nearest is an option of scene distance only", name);
                return -1;
            }
            if (strcmp(opt, "--count") == 0 && a->cmd == TTD_SCENE_DISTANCE) {
                ttd_cli_error("%s: --count is an option of scene collide, contacts and manifold", name);
                return -1;
            }
            *(strcmp(opt, "--nearest") == 0         ? &a->nearest
              : strcmp(opt, "--count") == 0         ? &a->count
              : strcmp(opt, "--orthonormalize") == 0 ? &a->orthonormalize
              : strcmp(opt, "--strict") == 0        ? &a->strict
              : strcmp(opt, "--names") == 0         ? &a->names
              : strcmp(opt, "--stats") == 0         ? &a->stats
                                                    : &a->solid) = 1;
            continue;
        }
        long iv;
        int bad = 0;
        if (strcmp(opt, "--margin") == 0)
            a->margin_s = val;
        else if (strcmp(opt, "--motion") == 0)
            a->motion_path = val;
        else if (strcmp(opt, "--repeat") == 0)
            bad = ttd_cli_parse_int(val, 1, 1L << 20, &a->repeat);
        else if (strcmp(opt, "--weld") == 0) {
            a->weld_s = val;
            bad = ttd_cli_parse_weld(val, &a->weld);
        }
        else if (strcmp(opt, "--max-points") == 0) {
            if (a->cmd != TTD_SCENE_MANIFOLD) {
                ttd_cli_error("%s: --max-points is an option of scene manifold only", name);
                return -1;
            }
            bad = ttd_cli_parse_int(val, 0, 1L << 30, &iv);
            a->max_points = bad ? 0 : (size_t)iv;
        } else {
            bad = ttd_cli_run_option(opt, val, &a->opt, &a->use_float) < 0;
        }
        if (bad) {
            ttd_cli_bad_value(&w, NULL);
            return -1;
        }
    }
    if (a->path == NULL) {
        ttd_cli_error("%s: the scene file is missing (see ttd %s --help)", name, name);
        return -1;
    }
    if (a->motion_path && strcmp(a->motion_path, "-") == 0 && strcmp(a->path, "-") == 0) {
        ttd_cli_error("%s: standard input cannot hold both the scene and the motion", name);
        return -1;
    }
    /* The margin is parsed once the precision is known, whatever the order of the options. */
    a->margin = a->cmd == TTD_SCENE_DISTANCE ? (double)INFINITY : 0.0;
    if (a->margin_s != NULL) {
        char *end;
        errno = 0;
        double v = a->use_float ? (double)strtof(a->margin_s, &end) : strtod(a->margin_s, &end);
        if (end == a->margin_s || *end != '\0' || !isfinite(v) || !(v >= 0)) {
            ttd_cli_error("%s: bad value for --margin: '%s' (a finite number >= 0%s)", name, a->margin_s,
                          a->use_float ? " in float range" : "");
            return -1;
        }
        a->margin = v;
    }
    return 0;
}

/* ---- the scene file ----------------------------------------------------------------------- */

typedef struct ttd_scene_mesh {
    char *name;
    ttd_mesh *mesh;                /* NULL when its file could not be read (already reported) */
} ttd_scene_mesh;

/* A body line of the scene file, good or bad: what later lines refer to it by. */
typedef struct ttd_scene_body_rec {
    char *name;                    /* NULL when unnamed */
    uint32_t id;                   /* the library's id, UINT32_MAX when the body was not added */
} ttd_scene_body_rec;

/* What a run holds: the meshes by name, the bodies (their mesh and starting pose), the scene. */
typedef struct ttd_scene_state {
    const ttd_scene_args *a;
    const char *fname;             /* the scene file's name in messages */
    ttd_scene_mesh *meshes;
    size_t nmeshes, mesh_cap;
    const ttd_mesh **body_mesh;    /* per body added */
    size_t nbodies, body_cap;
    ttd_scene_body_rec *lines;     /* per body line, in file order: the body numbers */
    size_t nlines, line_cap;
    char **id_name;                /* per body added (library id): its name or NULL, for --names */
    ttd_scene *scene;
    unsigned long long bad;        /* bad lines of the file being read */
} ttd_scene_state;

/* Reports a bad line (the first TTD_SCENE_MAX_MESSAGES; then once that more were cut). */
static void ttd_scene_bad_line(ttd_scene_state *st, const char *fname, unsigned long long line, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));

static void ttd_scene_bad_line(ttd_scene_state *st, const char *fname, unsigned long long line, const char *fmt, ...)
{
    if (st->bad < TTD_SCENE_MAX_MESSAGES) {
        char msg[2048];
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(msg, sizeof msg, fmt, ap);
        va_end(ap);
        ttd_cli_error("%s:%llu: %s", fname, line, msg);
    } else if (st->bad == TTD_SCENE_MAX_MESSAGES) {
        ttd_cli_error("%s: more bad lines; only the first %d are shown", fname, TTD_SCENE_MAX_MESSAGES);
    }
    ++st->bad;
}

static int ttd_scene_is_blank(char c)
{
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

/* The next word of [*p, end) (blank-separated, ending at '#'), or NULL at the end; its length in *len. */
static const char *ttd_scene_word(const char **p, const char *end, size_t *len)
{
    const char *s = *p;
    while (s < end && ttd_scene_is_blank(*s))
        ++s;
    if (s == end || *s == '#') {
        *p = s;
        return NULL;
    }
    const char *e = s;
    while (e < end && !ttd_scene_is_blank(*e) && *e != '#')
        ++e;
    *p = e;
    *len = (size_t)(e - s);
    return s;
}

/* The mesh called name[0..len), or NULL. */
static ttd_scene_mesh *ttd_scene_find_mesh(ttd_scene_state *st, const char *name, size_t len)
{
    for (size_t k = 0; k < st->nmeshes; ++k)
        if (strlen(st->meshes[k].name) == len && memcmp(st->meshes[k].name, name, len) == 0)
            return &st->meshes[k];
    return NULL;
}

/* The path of a mesh file named in the scene file: relative to the scene file's folder. */
static char *ttd_scene_mesh_path(const char *scene_path, const char *file, size_t len)
{
    const char *slash = strcmp(scene_path, "-") == 0 ? NULL : strrchr(scene_path, '/');
    const size_t dir = file[0] == '/' || slash == NULL ? 0 : (size_t)(slash - scene_path) + 1;
    /* a bare '-' would be standard input to the reader: name it as a file */
    const int dot = dir == 0 && len == 1 && file[0] == '-';
    char *path = malloc(dir + len + 3);
    if (path == NULL)
        return NULL;
    memcpy(path, dot ? "./" : scene_path, dot ? 2 : dir);
    memcpy(path + (dot ? 2 : dir), file, len);
    path[(dot ? 2 : dir) + len] = '\0';
    return path;
}

/* `mesh NAME FILE` at line `line`: read and build it. 0, or -1 when out of memory. */
static int ttd_scene_mesh_line(ttd_scene_state *st, unsigned long long line, const char *p, const char *end)
{
    const ttd_scene_args *a = st->a;
    size_t nlen = 0, flen = 0, xlen = 0;
    const char *name = ttd_scene_word(&p, end, &nlen);
    const char *file = name ? ttd_scene_word(&p, end, &flen) : NULL;
    const char *extra = file ? ttd_scene_word(&p, end, &xlen) : NULL;
    if (file == NULL || extra != NULL) {
        ttd_scene_bad_line(st, st->fname, line, "expected 'mesh NAME FILE', found %s",
                           file == NULL ? (name == NULL ? "no NAME" : "no FILE") : "more words");
        return 0;
    }
    if (ttd_scene_find_mesh(st, name, nlen) != NULL) {
        ttd_scene_bad_line(st, st->fname, line, "mesh '%.*s' is already defined", (int)nlen, name);
        return 0;
    }
    if (st->nmeshes == st->mesh_cap) {
        const size_t cap = st->mesh_cap ? 2 * st->mesh_cap : 8;
        ttd_scene_mesh *m = realloc(st->meshes, cap * sizeof *m);
        if (m == NULL)
            return -1;
        st->meshes = m;
        st->mesh_cap = cap;
    }
    ttd_scene_mesh *m = &st->meshes[st->nmeshes];
    m->mesh = NULL;
    m->name = malloc(nlen + 1);
    char *path = ttd_scene_mesh_path(a->path, file, flen);
    if (m->name == NULL || path == NULL) {
        free(m->name);
        free(path);
        return -1;
    }
    memcpy(m->name, name, nlen);
    m->name[nlen] = '\0';
    st->nmeshes++;

    char err[1024];
    ttd_meshfile mf = {0};
    const int flags = (a->use_float ? TTD_MESHFILE_FLOAT : 0) | (a->strict ? TTD_MESHFILE_STRICT : 0);
    if (ttd_meshfile_read(path, flags, &mf, err, sizeof err) != 0) {
        ttd_scene_bad_line(st, st->fname, line, "mesh '%s': %s", m->name, err);
    } else {
        if (mf.skipped_lines > 0) {
            const int one = mf.skipped_lines == 1;
            ttd_cli_error("%s: skipped %zu %s, first at %s:%zu (--strict refuses them)", path, mf.skipped_lines,
                          one ? "line that is not an OBJ statement" : "lines that are not OBJ statements", path,
                          mf.first_skipped_line);
        }
        char werr[512];
        size_t dropped = 0;
        if (a->weld_s && ttd_meshfile_weld(&mf, a->weld, &dropped, werr, sizeof werr) != 0) {
            ttd_scene_bad_line(st, st->fname, line, "mesh '%s': %s: %s", m->name, path, werr);
            ttd_meshfile_free(&mf);
            free(path);
            return 0;
        }
        ttd_status s = a->use_float ? ttd_mesh_create_f(&a->opt, mf.verts_f, mf.nv, mf.tris, mf.nt, &m->mesh)
                                    : ttd_mesh_create_d(&a->opt, mf.verts, mf.nv, mf.tris, mf.nt, &m->mesh);
        if (s != TTD_OK) {
            m->mesh = NULL;
            ttd_scene_bad_line(st, st->fname, line, "mesh '%s': %s: cannot build the mesh: %s", m->name, path,
                               ttd_status_string(s));
        }
    }
    ttd_meshfile_free(&mf);
    free(path);
    return 0;
}

/* A pose's numbers from [p, end): 12 or 16 (cli/parse.h), a rotation (ttd_cli_pose_problem);
 * 0 with the 12 numbers in v, or -1 with the reason in err. */
static int ttd_scene_parse_pose(const ttd_scene_args *a, const char *p, const char *end, double v[12], char *err,
                                size_t errsize)
{
    ttd_line_kind kind = ttd_parse_pose_line(p, (size_t)(end - p), a->use_float, v, err, errsize);
    if (kind == TTD_LINE_SKIP) {
        snprintf(err, errsize, "expected 12 numbers ([R | t], 3x4) or 16 (a 4x4 matrix), found 0");
        return -1;
    }
    if (kind != TTD_LINE_PAIR)
        return -1;
    return ttd_cli_pose_problem(v, a->orthonormalize, err, errsize);
}

/* Whether word[0..len) is `kw`. */
static int ttd_scene_is(const char *word, size_t len, const char *kw)
{
    return word != NULL && len == strlen(kw) && memcmp(word, kw, len) == 0;
}

/* `body MESH numbers [name BODY]` at line `line`, the file's body number `no` (its place among
 * the body lines, good or bad, as st->lines has it): add the body. 0, or -1 when out of memory. */
static int ttd_scene_body_line(ttd_scene_state *st, unsigned long long line, const char *p, const char *end)
{
    const ttd_scene_args *a = st->a;
    if (st->nlines == st->line_cap) {
        const size_t cap = st->line_cap ? 2 * st->line_cap : 16;
        ttd_scene_body_rec *b = realloc(st->lines, cap * sizeof *b);
        if (b == NULL)
            return -1;
        st->lines = b;
        st->line_cap = cap;
    }
    const size_t no = st->nlines++;
    ttd_scene_body_rec *bl = &st->lines[no];
    bl->name = NULL;
    bl->id = UINT32_MAX;
    size_t nlen = 0;
    const char *name = ttd_scene_word(&p, end, &nlen);
    if (name == NULL) {
        ttd_scene_bad_line(st, st->fname, line, "expected 'body MESH' and 12 numbers ([R | t]) or 16 (4x4), found no MESH");
        return 0;
    }
    /* the pose ends where a 'name BODY' clause starts (a number is never the word 'name') */
    const char *pose_end = end, *q = p;
    size_t wlen = 0;
    for (const char *w; (w = ttd_scene_word(&q, end, &wlen)) != NULL;)
        if (ttd_scene_is(w, wlen, "name")) {
            pose_end = w;
            break;
        }
    if (pose_end != end) {
        size_t blen = 0, xlen = 0;
        const char *body = ttd_scene_word(&q, end, &blen);
        const char *extra = body ? ttd_scene_word(&q, end, &xlen) : NULL;
        if (body == NULL || extra != NULL) {
            ttd_scene_bad_line(st, st->fname, line, "body %zu: expected 'name BODY' at the end of the line, found %s",
                               no, body == NULL ? "no BODY" : "more words");
            return 0;
        }
        if (*body >= '0' && *body <= '9') {
            ttd_scene_bad_line(st, st->fname, line,
                               "body %zu: the name '%.*s' starts with a digit (numbers refer to bodies by number)", no,
                               (int)blen, body);
            return 0;
        }
        for (size_t k = 0; k < no; ++k)
            if (st->lines[k].name && strlen(st->lines[k].name) == blen && memcmp(st->lines[k].name, body, blen) == 0) {
                ttd_scene_bad_line(st, st->fname, line, "body %zu: the name '%.*s' is body %zu's already", no,
                                   (int)blen, body, k);
                return 0;
            }
        if ((bl->name = malloc(blen + 1)) == NULL)
            return -1;
        memcpy(bl->name, body, blen);
        bl->name[blen] = '\0';
    }
    const ttd_scene_mesh *m = ttd_scene_find_mesh(st, name, nlen);
    double v[12];
    char err[512];
    if (m == NULL) {
        ttd_scene_bad_line(st, st->fname, line, "body %zu: unknown mesh '%.*s' (a 'mesh NAME FILE' line must come first)",
                           no, (int)nlen, name);
        return 0;
    }
    /* the rest of the line is the pose's: its own comment and blanks are the parser's business */
    if (ttd_scene_parse_pose(a, p, pose_end, v, err, sizeof err) != 0) {
        ttd_scene_bad_line(st, st->fname, line, "body %zu: %s", no, err);
        return 0;
    }
    if (m->mesh == NULL) /* its mesh line failed, and said so: count the body, add nothing */
        return 0;
    if (st->bad > 0) /* the file is refused anyway: only its lines are checked from now on */
        return 0;
    if (st->nbodies == st->body_cap) {
        const size_t cap = st->body_cap ? 2 * st->body_cap : 16;
        const ttd_mesh **b = realloc(st->body_mesh, cap * sizeof *b);
        char **n = b == NULL ? NULL : realloc(st->id_name, cap * sizeof *n);
        if (b != NULL)
            st->body_mesh = b;
        if (n == NULL)
            return -1;
        st->id_name = n;
        st->body_cap = cap;
    }
    uint32_t got;
    ttd_status s;
    if (a->use_float) {
        float f[12];
        for (int k = 0; k < 12; ++k)
            f[k] = (float)v[k];
        s = ttd_scene_add_f(st->scene, m->mesh, f, &got);
    } else {
        s = ttd_scene_add_d(st->scene, m->mesh, v, &got);
    }
    if (s == TTD_ERR_OUT_OF_MEMORY)
        return -1;
    if (s != TTD_OK) {
        ttd_scene_bad_line(st, st->fname, line, "body %zu: %s", no, ttd_status_string(s));
        return 0;
    }
    bl->id = got;
    st->id_name[st->nbodies] = bl->name;
    st->body_mesh[st->nbodies++] = m->mesh;
    return 0;
}

/* The body line that word[0..len) refers to: a body's name, or its number (decimal digits);
 * -1 after a message naming what (the statement) when there is none above this line. */
static long ttd_scene_body_ref(ttd_scene_state *st, unsigned long long line, const char *what, const char *word,
                               size_t len)
{
    const int shown = len > 40 ? 40 : (int)len;
    if (*word >= '0' && *word <= '9') {
        size_t no = 0, k = 0;
        for (; k < len && word[k] >= '0' && word[k] <= '9'; ++k)
            no = no > st->nlines ? no : 10 * no + (size_t)(word[k] - '0');
        if (k < len)
            ttd_scene_bad_line(st, st->fname, line, "%s: '%.*s' is neither a body number nor a name", what, shown,
                               word);
        else if (no >= st->nlines && st->nlines == 0)
            ttd_scene_bad_line(st, st->fname, line, "%s: no body %.*s (no body line comes before this one)", what,
                               shown, word);
        else if (no >= st->nlines)
            ttd_scene_bad_line(st, st->fname, line, "%s: no body %.*s (the body lines above this one are 0 to %zu)",
                               what, shown, word, st->nlines - 1);
        else
            return (long)no;
        return -1;
    }
    for (size_t k = 0; k < st->nlines; ++k)
        if (st->lines[k].name && strlen(st->lines[k].name) == len && memcmp(st->lines[k].name, word, len) == 0)
            return (long)k;
    ttd_scene_bad_line(st, st->fname, line, "%s: unknown body '%.*s' (a body line naming it must come first)", what,
                       shown, word);
    return -1;
}

/* A 32-bit group or mask: decimal digits, or 0x and hex digits. 0, or -1. */
static int ttd_scene_u32(const char *word, size_t len, uint32_t *out)
{
    const int hex = len > 2 && word[0] == '0' && (word[1] == 'x' || word[1] == 'X');
    unsigned long long v = 0;
    for (size_t k = hex ? 2 : 0; k < len; ++k) {
        const char c = word[k];
        int d;
        if (c >= '0' && c <= '9')
            d = c - '0';
        else if (hex && c >= 'a' && c <= 'f')
            d = c - 'a' + 10;
        else if (hex && c >= 'A' && c <= 'F')
            d = c - 'A' + 10;
        else
            return -1;
        v = v * (hex ? 16u : 10u) + (unsigned)d;
        if (v > UINT32_MAX)
            return -1;
    }
    *out = (uint32_t)v;
    return 0;
}

/* `filter BODY GROUP MASK` (rule 0), `exclude BODY BODY` (1) or `solid BODY` (2) at line
 * `line`: the library's ttd_scene_set_filter, ttd_scene_exclude_pair or ttd_scene_set_solid on
 * the bodies named. 0, or -1 when out of memory. */
static int ttd_scene_pair_rule_line(ttd_scene_state *st, unsigned long long line, int rule, const char *p,
                                    const char *end)
{
    static const char *const whats[3] = {"filter", "exclude", "solid"};
    static const char *const forms[3] = {"filter BODY GROUP MASK", "exclude BODY BODY", "solid BODY"};
    static const int wants[3] = {3, 2, 1};
    const char *what = whats[rule];
    const int exclude = rule == 1;
    const char *w[4];
    size_t len[4] = {0};
    int n = 0;
    while (n < 4 && (w[n] = ttd_scene_word(&p, end, &len[n])) != NULL)
        ++n;
    const int want = wants[rule];
    if (n != want) {
        static const char *const missing[3][3] = {{"no BODY", "no GROUP", "no MASK"}, {"no BODY", "one BODY", ""}, {"no BODY", "", ""}};
        ttd_scene_bad_line(st, st->fname, line, "expected '%s', found %s", forms[rule],
                           n > want ? "more words" : missing[rule][n]);
        return 0;
    }
    const long b0 = ttd_scene_body_ref(st, line, what, w[0], len[0]);
    if (b0 < 0)
        return 0;
    ttd_status s = TTD_OK;
    if (exclude) {
        const long b1 = ttd_scene_body_ref(st, line, what, w[1], len[1]);
        if (b1 < 0)
            return 0;
        if (b1 == b0) {
            ttd_scene_bad_line(st, st->fname, line, "exclude: body %ld twice (a pair is two bodies)", b0);
            return 0;
        }
        const uint32_t i = st->lines[b0].id, j = st->lines[b1].id;
        if (st->bad == 0 && i != UINT32_MAX && j != UINT32_MAX)
            s = ttd_scene_exclude_pair(st->scene, i, j, 1);
    } else if (rule == 2) {
        const uint32_t i = st->lines[b0].id;
        if (st->bad == 0 && i != UINT32_MAX)
            s = ttd_scene_set_solid(st->scene, i, 1);
    } else {
        uint32_t group, mask;
        for (int k = 1; k < 3; ++k)
            if (ttd_scene_u32(w[k], len[k], k == 1 ? &group : &mask) != 0) {
                ttd_scene_bad_line(st, st->fname, line,
                                   "filter: %s '%.*s' is not a 32-bit number (0 to 4294967295, or 0x0 to 0xffffffff)",
                                   k == 1 ? "GROUP" : "MASK", (int)(len[k] > 40 ? 40 : len[k]), w[k]);
                return 0;
            }
        const uint32_t i = st->lines[b0].id;
        if (st->bad == 0 && i != UINT32_MAX)
            s = ttd_scene_set_filter(st->scene, i, group, mask);
    }
    if (s == TTD_ERR_OUT_OF_MEMORY)
        return -1;
    if (s != TTD_OK)
        ttd_scene_bad_line(st, st->fname, line, "%s: %s", what, ttd_status_string(s));
    return 0;
}

/* Reads the scene file, builds its meshes and adds its bodies; 0 or the exit status. */
static int ttd_scene_read(ttd_scene_state *st)
{
    const ttd_scene_args *a = st->a;
    const int from_stdin = strcmp(a->path, "-") == 0;
    st->fname = from_stdin ? "<stdin>" : a->path;
    FILE *in = from_stdin ? stdin : fopen(a->path, "rb");
    if (in == NULL) {
        ttd_cli_error("%s: cannot open: %s", st->fname, strerror(errno));
        return TTD_EXIT_INPUT;
    }
    ttd_line_reader *r = malloc(sizeof *r);
    int rc = 0;
    if (r == NULL) {
        ttd_cli_error("out of memory");
        rc = TTD_EXIT_INPUT;
    }
    if (r != NULL) {
        size_t len;
        int overlong;
        ttd_reader_init(r, in);
        while (rc == 0 && ttd_reader_next(r, &len, &overlong)) {
            const char *p = r->line, *end = r->line + len;
            size_t klen = 0;
            const char *key = ttd_scene_word(&p, end, &klen);
            if (key == NULL)
                continue; /* blank or a comment */
            if (overlong) {
                ttd_scene_bad_line(st, st->fname, r->line_no, "line longer than %d bytes", TTD_CLI_MAX_LINE);
                continue;
            }
            if (memchr(r->line, '\0', len) != NULL) {
                ttd_scene_bad_line(st, st->fname, r->line_no, "a NUL byte in the line");
                continue;
            }
            int mem = 0;
            if (ttd_scene_is(key, klen, "mesh"))
                mem = ttd_scene_mesh_line(st, r->line_no, p, end);
            else if (ttd_scene_is(key, klen, "body"))
                mem = ttd_scene_body_line(st, r->line_no, p, end);
            else if (ttd_scene_is(key, klen, "filter") || ttd_scene_is(key, klen, "exclude") ||
                     ttd_scene_is(key, klen, "solid"))
                mem = ttd_scene_pair_rule_line(st, r->line_no, key[0] == 'f' ? 0 : key[0] == 'e' ? 1 : 2, p, end);
            else {
                char word[64];
                snprintf(word, sizeof word, "%.*s%s", klen > 40 ? 40 : (int)klen, key, klen > 40 ? "..." : "");
                ttd_scene_bad_line(st, st->fname, r->line_no,
                                   "unknown statement '%s' (mesh, body, filter, exclude or solid)", word);
            }
            if (mem != 0) {
                ttd_cli_error("%s:%llu: out of memory", st->fname, r->line_no);
                rc = TTD_EXIT_INPUT;
            }
        }
        if (rc == 0 && r->error) {
            ttd_cli_error("%s: read error: %s", st->fname, strerror(r->error));
            rc = TTD_EXIT_INPUT;
        }
    }
    if (rc == 0 && st->bad > 0) {
        ttd_cli_error("%s: %llu bad line%s; nothing computed", st->fname, st->bad, st->bad == 1 ? "" : "s");
        rc = TTD_EXIT_INPUT;
    }
    free(r);
    if (!from_stdin)
        fclose(in);
    return rc;
}

/* ---- the motion file ---------------------------------------------------------------------- */

/* The poses of every step: 12 per body per step, doubles (exact floats in float). */
typedef struct ttd_scene_motion {
    double *d;
    size_t poses, cap;             /* poses read (steps * bodies when complete) */
} ttd_scene_motion;

/* A motion file's `step` line ("step", or "step S"), checked: 1 when line[0..len) is one (S, when
 * given, in *index, else SIZE_MAX; a malformed one sets err), 0 when it is not. */
static int ttd_scene_step_line(const char *line, size_t len, size_t *index, char *err, size_t errsize)
{
    const char *p = line, *end = line + len;
    size_t klen = 0, ilen = 0, xlen = 0;
    const char *key = ttd_scene_word(&p, end, &klen);
    if (!ttd_scene_is(key, klen, "step"))
        return 0;
    const char *idx = ttd_scene_word(&p, end, &ilen);
    const char *extra = idx ? ttd_scene_word(&p, end, &xlen) : NULL;
    *index = SIZE_MAX;
    err[0] = '\0';
    size_t v = 0, k = 0;
    for (; idx != NULL && k < ilen && idx[k] >= '0' && idx[k] <= '9' && v < SIZE_MAX / 10 - 1; ++k)
        v = 10 * v + (size_t)(idx[k] - '0');
    if (extra != NULL || (idx != NULL && k < ilen))
        snprintf(err, errsize, "expected 'step' or 'step S' (S the step's index, from 0), found %s",
                 extra ? "more words" : "an index that is not a whole number");
    else if (idx != NULL)
        *index = v;
    return 1;
}

/* A step opened by a `step` line at `line` that holds `got` poses of the scene's n. */
static void ttd_scene_short_step(ttd_scene_state *st, const char *fname, unsigned long long line, size_t step,
                                 size_t got, size_t n)
{
    ttd_scene_bad_line(st, fname, line,
                       "step %zu has %zu pose%s where the scene has %zu bod%s "
                       "(one pose per body after each 'step' line)",
                       step, got, got == 1 ? "" : "s", n, n == 1 ? "y" : "ies");
}

/* Reads and checks the whole motion file; 0 or the exit status. Steps are counted off N poses at
 * a time (N the bodies), or, where the file opens every step with a `step` line, by those lines,
 * and then each step must hold N poses. */
static int ttd_scene_read_motion(ttd_scene_state *st, ttd_scene_motion *mo)
{
    const ttd_scene_args *a = st->a;
    const int from_stdin = strcmp(a->motion_path, "-") == 0;
    const char *fname = from_stdin ? "<stdin>" : a->motion_path;
    FILE *in = from_stdin ? stdin : fopen(a->motion_path, "rb");
    if (in == NULL) {
        ttd_cli_error("%s: cannot open: %s", fname, strerror(errno));
        return TTD_EXIT_INPUT;
    }
    ttd_line_reader *r = malloc(sizeof *r);
    int rc = 0;
    size_t index = 0;                   /* of the next pose line, good or bad */
    unsigned long long step_line = 0;   /* the line of the current step's first pose (its `step` line) */
    int marked = -1;                    /* 1: its steps open with `step` lines; 0: they do not; -1: not known yet */
    size_t steps = 0, in_step = 0;      /* with `step` lines: steps opened, poses in the last one */
    const size_t n = st->nbodies;
    st->bad = 0;
    if (r == NULL) {
        ttd_cli_error("out of memory");
        rc = TTD_EXIT_INPUT;
    }
    if (r != NULL) {
        size_t len;
        int overlong;
        ttd_reader_init(r, in);
        while (rc == 0 && ttd_reader_next(r, &len, &overlong)) {
            double v[12];
            char err[512];
            size_t at;
            if (!overlong && ttd_scene_step_line(r->line, len, &at, err, sizeof err)) {
                if (err[0] != '\0')
                    ttd_scene_bad_line(st, fname, r->line_no, "%s", err);
                else if (marked == 0)
                    ttd_scene_bad_line(st, fname, r->line_no, "a 'step' line, but the poses above it had none: a "
                                       "motion file opens every step with a 'step' line, or none");
                else if (at != SIZE_MAX && at != steps)
                    ttd_scene_bad_line(st, fname, r->line_no, "'step %zu' where step %zu comes (steps are numbered 0, "
                                       "1, 2, ... in order)", at, steps);
                if (marked == 1 && in_step < n) /* too many poses were named at the first extra one */
                    ttd_scene_short_step(st, fname, step_line, steps - 1, in_step, n);
                if (marked != 0) {
                    marked = 1;
                    step_line = r->line_no;
                    ++steps;
                    in_step = 0;
                }
                continue;
            }
            ttd_line_kind kind = ttd_read_pose_line(r, len, overlong, a->use_float, v, err, sizeof err);
            if (kind == TTD_LINE_SKIP)
                continue;
            if (n == 0) {
                ttd_scene_bad_line(st, fname, r->line_no, "a pose, but the scene has no bodies");
                ++index;
                continue;
            }
            if (marked < 0)
                marked = 0;
            if (marked == 1 && in_step++ >= n) {
                if (in_step == n + 1) /* once per step */
                    ttd_scene_bad_line(st, fname, r->line_no, "step %zu: more poses than the scene's %zu bod%s (one "
                                       "pose per body after each 'step' line)", steps - 1, n, n == 1 ? "y" : "ies");
                continue;
            }
            const size_t step = marked == 1 ? steps - 1 : index / n, body = marked == 1 ? in_step - 1 : index % n;
            if (marked == 0 && body == 0)
                step_line = r->line_no;
            ++index;
            if (kind == TTD_LINE_PAIR && ttd_cli_pose_problem(v, a->orthonormalize, err, sizeof err) != 0)
                kind = TTD_LINE_ERROR;
            if (kind == TTD_LINE_PAIR) {
                /* the coordinate range, as ttd_scene_set_poses will check it, named here */
                size_t badk;
                ttd_status s;
                if (a->use_float) {
                    float f[12];
                    for (int k = 0; k < 12; ++k)
                        f[k] = (float)v[k];
                    s = ttd_mesh_check_poses_f(st->body_mesh[body], st->body_mesh[body], 1, f, &badk);
                } else {
                    s = ttd_mesh_check_poses_d(st->body_mesh[body], st->body_mesh[body], 1, v, &badk);
                }
                if (s != TTD_OK) {
                    kind = TTD_LINE_ERROR;
                    snprintf(err, sizeof err, "%s", ttd_status_string(s));
                }
            }
            if (kind == TTD_LINE_ERROR) {
                ttd_scene_bad_line(st, fname, r->line_no, "step %zu, body %zu: %s", step, body, err);
                continue;
            }
            if (st->bad > 0)
                continue;
            if (mo->poses == mo->cap) {
                const size_t cap = mo->cap ? 2 * mo->cap : 64;
                double *d = cap > SIZE_MAX / (12 * sizeof *d) ? NULL : realloc(mo->d, cap * 12 * sizeof *d);
                if (d == NULL) {
                    ttd_cli_error("%s:%llu: out of memory for the motion", fname, r->line_no);
                    rc = TTD_EXIT_INPUT;
                    break;
                }
                mo->d = d;
                mo->cap = cap;
            }
            memcpy(mo->d + 12 * mo->poses++, v, sizeof v);
        }
        if (rc == 0 && r->error) {
            ttd_cli_error("%s: read error: %s", fname, strerror(r->error));
            rc = TTD_EXIT_INPUT;
        }
    }
    if (rc == 0 && marked == 1 && in_step < n)
        ttd_scene_short_step(st, fname, step_line, steps - 1, in_step, n);
    else if (rc == 0 && marked == 0 && n > 0 && index % n != 0)
        ttd_scene_bad_line(st, fname, step_line, "step %zu is incomplete: %zu of %zu poses (one per body), to the end of the file",
                           index / n, index % n, n);
    if (rc == 0 && st->bad > 0) {
        ttd_cli_error("%s: %llu bad line%s; nothing computed", fname, st->bad, st->bad == 1 ? "" : "s");
        rc = TTD_EXIT_INPUT;
    }
    free(r);
    if (!from_stdin)
        fclose(in);
    return rc;
}

/* ---- queries and output ------------------------------------------------------------------- */

static void ttd_scene_put_reals(FILE *out, int use_float, const double *v, int n)
{
    for (int k = 0; k < n; ++k)
        fprintf(out, use_float ? " %.9g" : " %.17g", v[k]);
}

/* Body id as i or j is printed, after sep: its name with --names where it has one (names, NULL
 * without --names, holds them by id), else its number. */
static void ttd_scene_put_body(FILE *out, char *const *names, uint32_t id, const char *sep)
{
    if (names != NULL && names[id] != NULL)
        fprintf(out, "%s%s", sep, names[id]);
    else
        fprintf(out, "%s%lu", sep, (unsigned long)id);
}

/* Triangles ia and ib after a space each: -1 for UINT32_MAX (no triangle: the outer body of two
 * nested solids). */
static void ttd_scene_put_tris(FILE *out, uint32_t ia, uint32_t ib)
{
    fprintf(out, ia == UINT32_MAX ? " -1" : " %lu", (unsigned long)ia);
    fprintf(out, ib == UINT32_MAX ? " -1" : " %lu", (unsigned long)ib);
}

/* Items of one query, widened to double, for sorting and printing. */
typedef struct ttd_scene_item {
    uint32_t i, j, ti, tj;
    double d, depth, p[3], q[3]; /* manifold: p the point, q the normal */
    double pi[3], pj[3];         /* manifold: each body's point */
    uint64_t key;                /* manifold: the contact's key */
} ttd_scene_item;

static int ttd_scene_item_cmp(const void *x, const void *y)
{
    const ttd_scene_item *u = x, *v = y;
    if (u->i != v->i)
        return u->i < v->i ? -1 : 1;
    if (u->j != v->j)
        return u->j < v->j ? -1 : 1;
    if (u->ti != v->ti)
        return u->ti < v->ti ? -1 : 1;
    if (u->tj != v->tj)
        return u->tj < v->tj ? -1 : 1;
    for (int r = 0; r < 3; ++r) /* a manifold's corners: several points of one triangle pair */
        if (u->p[r] != v->p[r])
            return u->p[r] < v->p[r] ? -1 : 1;
    return (u->d > v->d) - (u->d < v->d);
}

/* What the query loop reuses from step to step. */
typedef struct ttd_scene_buffers {
    ttd_scene_array arr;
    ttd_scene_item *items;
    size_t cap;
    ttd_scene_contact_d *near_d; /* --nearest: one per body id */
    ttd_scene_contact_f *near_f;
    size_t counted;              /* contacts --count: the number, no contact held */
} ttd_scene_buffers;

static double ttd_scene_clock(clockid_t id)
{
    struct timespec t;
    clock_gettime(id, &t);
    return (double)t.tv_sec * 1e3 + (double)t.tv_nsec * 1e-6;
}

static int ttd_scene_cmp_double(const void *x, const void *y)
{
    const double a = *(const double *)x, b = *(const double *)y;
    return (a > b) - (a < b);
}

/* Runs the query a->repeat times (the last answer stays in cd/cf or b->arr); with --stats, prints
 * the library's stats of the last run and the runs' times on standard error. */
static ttd_status ttd_scene_run(const ttd_scene_args *a, ttd_scene *scene, long long step, ttd_scene_buffers *b,
                                ttd_scene_contact_d *cd, ttd_scene_contact_f *cf)
{
    const int f = a->use_float;
    ttd_status s = TTD_OK;
    double wall[64], cpu[64];
    const long nt = a->repeat < 64 ? a->repeat : 64; /* times kept: the first 64 runs */
    for (long r = 0; r < a->repeat && s == TTD_OK; ++r) {
        const double w0 = ttd_scene_clock(CLOCK_MONOTONIC), c0 = ttd_scene_clock(CLOCK_PROCESS_CPUTIME_ID);
        switch (a->cmd) {
        case TTD_SCENE_DISTANCE:
            s = f ? ttd_scene_distance_f(&a->opt, scene, (float)a->margin, cf, b->near_f)
                  : ttd_scene_distance_d(&a->opt, scene, a->margin, cd, b->near_d);
            break;
        case TTD_SCENE_COLLIDE:
            s = f ? ttd_scene_collide_f(&a->opt, scene, (float)a->margin, &b->arr)
                  : ttd_scene_collide_d(&a->opt, scene, a->margin, &b->arr);
            break;
        case TTD_SCENE_CONTACTS:
            if (a->count) /* counted by the library: the contacts are never held */
                s = f ? ttd_scene_contacts_count_f(&a->opt, scene, (float)a->margin, &b->counted)
                      : ttd_scene_contacts_count_d(&a->opt, scene, a->margin, &b->counted);
            else
                s = f ? ttd_scene_contacts_f(&a->opt, scene, (float)a->margin, &b->arr)
                      : ttd_scene_contacts_d(&a->opt, scene, a->margin, &b->arr);
            break;
        default:
            s = f ? ttd_scene_manifold_f(&a->opt, scene, (float)a->margin, a->max_points, &b->arr)
                  : ttd_scene_manifold_d(&a->opt, scene, a->margin, a->max_points, &b->arr);
            break;
        }
        if (r < nt) {
            wall[r] = ttd_scene_clock(CLOCK_MONOTONIC) - w0;
            cpu[r] = ttd_scene_clock(CLOCK_PROCESS_CPUTIME_ID) - c0;
        }
    }
    if (s != TTD_OK || !a->stats)
        return s;
    ttd_scene_stats t;
    ttd_scene_get_stats(scene, &t);
    qsort(wall, (size_t)nt, sizeof *wall, ttd_scene_cmp_double);
    qsort(cpu, (size_t)nt, sizeof *cpu, ttd_scene_cmp_double);
    char at[32] = "";
    if (step >= 0)
        snprintf(at, sizeof at, " step %lld:", step);
    fprintf(stderr,
            "ttd %s:%s %llu candidate body pairs, %llu node tests, %llu triangle pairs tested, %llu results; "
            "%.4g ms wall, %.4g ms CPU (fastest of %ld; median %.4g / %.4g)\n",
            a->name, at, (unsigned long long)t.body_pairs, (unsigned long long)t.node_tests,
            (unsigned long long)t.pair_tests, (unsigned long long)t.results, wall[0], cpu[0], nt, wall[nt / 2],
            cpu[nt / 2]);
    return s;
}

/* One line of `scene distance`: the closest pair (self -1), or body self's nearest (--nearest),
 * 'inf' with -1s and NaNs where there is none within the margin. */
static void ttd_scene_put_distance(FILE *out, char *const *names, int f, const ttd_scene_contact_d *cd,
                                   const ttd_scene_contact_f *cf, double margin, long long step, long self)
{
    if (step >= 0)
        fprintf(out, "%lld ", step);
    const uint32_t j = f ? cf->j : cd->j;
    const double d = f ? (double)cf->distance : cd->distance;
    if (j == UINT32_MAX || !(d <= margin)) {
        fputs("inf", out);
        if (self >= 0)
            ttd_scene_put_body(out, names, (uint32_t)self, " ");
        else
            fputs(" -1", out);
        fputs(" -1 -1 -1 nan nan nan nan nan nan\n", out);
        return;
    }
    double pq[7] = {d};
    for (int r = 0; r < 3; ++r) {
        pq[1 + r] = f ? (double)cf->p[r] : cd->p[r];
        pq[4 + r] = f ? (double)cf->q[r] : cd->q[r];
    }
    fprintf(out, f ? "%.9g" : "%.17g", d);
    ttd_scene_put_body(out, names, f ? cf->i : cd->i, " ");
    ttd_scene_put_body(out, names, j, " ");
    ttd_scene_put_tris(out, f ? cf->tri_i : cd->tri_i, f ? cf->tri_j : cd->tri_j);
    ttd_scene_put_reals(out, f, pq + 1, 6);
    fputc('\n', out);
}

/* One query on the scene as it is; its lines (prefixed by "step " when step >= 0) on out, bodies
 * as ttd_scene_put_body prints them. 0 or the exit status. */
static int ttd_scene_query(const ttd_scene_args *a, ttd_scene *scene, char *const *names, long long step,
                           ttd_scene_buffers *b, FILE *out)
{
    const int f = a->use_float;
    ttd_status s;
    if (a->cmd == TTD_SCENE_DISTANCE) {
        ttd_scene_contact_d cd;
        ttd_scene_contact_f cf;
        s = ttd_scene_run(a, scene, step, b, &cd, &cf);
        if (s != TTD_OK)
            goto failed;
        ttd_scene_put_distance(out, names, f, &cd, &cf, a->margin, step, -1);
        if (a->nearest)
            for (size_t id = 0; id < ttd_scene_id_limit(scene); ++id)
                ttd_scene_put_distance(out, names, f, b->near_d + id, b->near_f + id, a->margin, step, (long)id);
        return 0;
    }
    s = ttd_scene_run(a, scene, step, b, NULL, NULL);
    if (s != TTD_OK)
        goto failed;
    const size_t n = a->cmd == TTD_SCENE_CONTACTS && a->count ? b->counted : b->arr.count;
    if (a->count) {
        if (step >= 0)
            fprintf(out, "%lld ", step);
        fprintf(out, "%zu\n", n);
        return 0;
    }
    if (n > b->cap) {
        ttd_scene_item *v = realloc(b->items, n * sizeof *v);
        if (v == NULL) {
            ttd_cli_error("out of memory for %zu lines", n);
            return TTD_EXIT_INPUT;
        }
        b->items = v;
        b->cap = n;
    }
    for (size_t k = 0; k < n; ++k) {
        ttd_scene_item *it = &b->items[k];
        memset(it, 0, sizeof *it);
        if (a->cmd == TTD_SCENE_COLLIDE) {
            const ttd_scene_hit *h = (const ttd_scene_hit *)b->arr.data + k;
            *it = (ttd_scene_item){.i = h->i, .j = h->j, .ti = h->tri_i, .tj = h->tri_j};
        } else if (a->cmd == TTD_SCENE_CONTACTS && f) {
            const ttd_scene_contact_f *c = (const ttd_scene_contact_f *)b->arr.data + k;
            *it = (ttd_scene_item){.i = c->i, .j = c->j, .ti = c->tri_i, .tj = c->tri_j, .d = (double)c->distance};
            for (int r = 0; r < 3; ++r) {
                it->p[r] = (double)c->p[r];
                it->q[r] = (double)c->q[r];
            }
        } else if (a->cmd == TTD_SCENE_CONTACTS) {
            const ttd_scene_contact_d *c = (const ttd_scene_contact_d *)b->arr.data + k;
            *it = (ttd_scene_item){.i = c->i, .j = c->j, .ti = c->tri_i, .tj = c->tri_j, .d = c->distance};
            memcpy(it->p, c->p, sizeof it->p);
            memcpy(it->q, c->q, sizeof it->q);
        } else if (f) {
            const ttd_scene_point_f *c = (const ttd_scene_point_f *)b->arr.data + k;
            *it = (ttd_scene_item){.i = c->i, .j = c->j, .ti = c->tri_i, .tj = c->tri_j, .d = (double)c->distance,
                                   .depth = (double)c->depth};
            for (int r = 0; r < 3; ++r) {
                it->p[r] = (double)c->point[r];
                it->q[r] = (double)c->normal[r];
                it->pi[r] = (double)c->point_i[r];
                it->pj[r] = (double)c->point_j[r];
            }
            it->key = c->key;
        } else {
            const ttd_scene_point_d *c = (const ttd_scene_point_d *)b->arr.data + k;
            *it = (ttd_scene_item){.i = c->i, .j = c->j, .ti = c->tri_i, .tj = c->tri_j, .d = c->distance,
                                   .depth = c->depth};
            memcpy(it->p, c->point, sizeof it->p);
            memcpy(it->q, c->normal, sizeof it->q);
            memcpy(it->pi, c->point_i, sizeof it->pi);
            memcpy(it->pj, c->point_j, sizeof it->pj);
            it->key = c->key;
        }
    }
    if (n > 1)
        qsort(b->items, n, sizeof *b->items, ttd_scene_item_cmp);
    for (size_t k = 0; k < n; ++k) {
        const ttd_scene_item *it = &b->items[k];
        if (step >= 0)
            fprintf(out, "%lld ", step);
        ttd_scene_put_body(out, names, it->i, "");
        ttd_scene_put_body(out, names, it->j, " ");
        if (a->cmd == TTD_SCENE_MANIFOLD) {
            ttd_scene_put_reals(out, f, it->p, 3);
            ttd_scene_put_reals(out, f, it->q, 3);
            ttd_scene_put_reals(out, f, &it->d, 1);
            ttd_scene_put_reals(out, f, &it->depth, 1);
            ttd_scene_put_reals(out, f, it->pi, 3);
            ttd_scene_put_reals(out, f, it->pj, 3);
            fprintf(out, " %016llx", (unsigned long long)it->key);
        } else {
            ttd_scene_put_tris(out, it->ti, it->tj);
            if (a->cmd == TTD_SCENE_CONTACTS) {
                ttd_scene_put_reals(out, f, &it->d, 1);
                ttd_scene_put_reals(out, f, it->p, 3);
                ttd_scene_put_reals(out, f, it->q, 3);
            }
        }
        fputc('\n', out);
    }
    return 0;
failed:
    if (step >= 0)
        ttd_cli_error("%s: step %lld: %s", a->name, step, ttd_status_string(s));
    else
        ttd_cli_error("%s: %s", a->name, ttd_status_string(s));
    return TTD_EXIT_INPUT;
}

/* ---- the command -------------------------------------------------------------------------- */

int ttd_cli_scene(int argc, char **argv)
{
    if (argc < 2) {
        ttd_scene_print_usage(stderr);
        return TTD_EXIT_USAGE;
    }
    const char *sub = argv[1];
    if (strcmp(sub, "--help") == 0 || strcmp(sub, "-h") == 0 || strcmp(sub, "help") == 0) {
        ttd_scene_print_usage(stdout);
        return TTD_EXIT_OK;
    }
    int cmd = -1;
    for (int c = 0; c < 4; ++c)
        if (strcmp(sub, ttd_scene_cmd_names[c]) == 0)
            cmd = c;
    if (cmd < 0) {
        ttd_cli_error("scene: unknown command '%s' (collide, distance, contacts or manifold; see ttd scene --help)",
                      sub);
        return TTD_EXIT_USAGE;
    }
    ttd_scene_args a;
    memset(&a, 0, sizeof a);
    a.cmd = (ttd_scene_cmd)cmd;
    a.name = ttd_scene_full_names[cmd];
    int rc = ttd_scene_parse_args(argc - 1, argv + 1, &a);
    if (rc != 0)
        return rc > 0 ? TTD_EXIT_OK : TTD_EXIT_USAGE;
    if (ttd_isa_selected(&a.opt) == TTD_ISA_AUTO) {
        ttd_cli_error("%s: --isa %s is not available here; this machine has:", a.name, ttd_isa_name(a.opt.isa));
        ttd_cli_print_isas(stderr);
        return TTD_EXIT_USAGE;
    }
    ttd_cli_warn_isa_env(a.name);

    ttd_scene_state st;
    memset(&st, 0, sizeof st);
    st.a = &a;
    ttd_scene_motion mo = {0};
    ttd_scene_buffers buf = {{0}, NULL, 0, NULL, NULL, 0};
    float *posef = NULL;
    ttd_status s = a.use_float ? ttd_scene_create_f(&st.scene) : ttd_scene_create_d(&st.scene);
    if (s != TTD_OK) {
        ttd_cli_error("%s: %s", a.name, ttd_status_string(s));
        return TTD_EXIT_INPUT;
    }
    rc = ttd_scene_read(&st);
    for (size_t k = 0; rc == 0 && a.solid && k < st.nlines; ++k) { /* --solid: every body a solid */
        s = ttd_scene_set_solid(st.scene, st.lines[k].id, 1);
        if (s != TTD_OK) {
            ttd_cli_error("%s: --solid: body %zu%s%s: %s", st.fname, k, st.lines[k].name ? " " : "",
                          st.lines[k].name ? st.lines[k].name : "", ttd_status_string(s));
            rc = TTD_EXIT_INPUT;
        }
    }
    if (rc == 0 && a.motion_path != NULL)
        rc = ttd_scene_read_motion(&st, &mo);
    char *const *names = a.names ? st.id_name : NULL;
    if (rc == 0 && a.nearest) { /* one record per body id, the scene's bodies fixed from here */
        const size_t ids = ttd_scene_id_limit(st.scene) ? ttd_scene_id_limit(st.scene) : 1;
        buf.near_d = malloc(ids * sizeof *buf.near_d);
        buf.near_f = malloc(ids * sizeof *buf.near_f);
        if (buf.near_d == NULL || buf.near_f == NULL) {
            ttd_cli_error("out of memory");
            rc = TTD_EXIT_INPUT;
        }
    }
    if (rc == 0) {
        static char outbuf[1 << 16];
        setvbuf(stdout, outbuf, _IOFBF, sizeof outbuf);
        if (a.motion_path == NULL) {
            rc = ttd_scene_query(&a, st.scene, names, -1, &buf, stdout);
        } else if (st.nbodies > 0) {
            const size_t n = st.nbodies, steps = mo.poses / n;
            if (a.use_float && (posef = malloc(12 * n * sizeof *posef)) == NULL) {
                ttd_cli_error("out of memory");
                rc = TTD_EXIT_INPUT;
            }
            for (size_t t = 0; rc == 0 && t < steps && !ferror(stdout); ++t) {
                const double *pd = mo.d + 12 * n * t;
                if (a.use_float) {
                    for (size_t k = 0; k < 12 * n; ++k)
                        posef[k] = (float)pd[k];
                    s = ttd_scene_set_poses_f(st.scene, n, posef);
                } else {
                    s = ttd_scene_set_poses_d(st.scene, n, pd);
                }
                if (s != TTD_OK) {
                    ttd_cli_error("%s: step %zu: %s", a.name, t, ttd_status_string(s));
                    rc = TTD_EXIT_INPUT;
                    break;
                }
                rc = ttd_scene_query(&a, st.scene, names, (long long)t, &buf, stdout);
            }
        }
    }
    if (fflush(stdout) != 0 || ferror(stdout)) {
        ttd_cli_error("error writing the output");
        rc = TTD_EXIT_INPUT;
    }
    ttd_scene_destroy(st.scene);
    for (size_t k = 0; k < st.nmeshes; ++k) {
        ttd_mesh_destroy(st.meshes[k].mesh);
        free(st.meshes[k].name);
    }
    free(st.meshes);
    free(st.body_mesh);
    for (size_t k = 0; k < st.nlines; ++k)
        free(st.lines[k].name);
    free(st.lines);
    free(st.id_name);
    free(mo.d);
    free(posef);
    free(buf.items);
    free(buf.near_d);
    free(buf.near_f);
    ttd_scene_array_free(&buf.arr);
    return rc;
}
