/* SPDX-License-Identifier: MIT */
/* `ttd mesh mass A [options]`: the mass properties of the solid a closed mesh file bounds
 * (ttd_mesh_mass_properties_d/f, docs/mass-properties.md), as text or one JSON object. Reached
 * through `ttd mesh` (cli/mesh.c hands "mass" over); kept apart because it takes one mesh, no
 * pose and none of the query options. The usage text below is the reference for the output. */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <string.h>

#include "cli.h"
#include <ttd/meshfile.h>

static const char ttd_mass_usage[] =
    "usage: ttd mesh mass A [--density RHO] [--json] [--precision P] [--weld TOL] [--strict]\n"
    "The mass properties of the solid of uniform density that the closed triangle mesh in the file A\n"
    "bounds ('-' for standard input; OBJ, STL, PLY, OFF, glTF 2.0 or 3MF, recognised by content:\n"
    "docs/mesh-files.md), by the divergence theorem with compensated sums (docs/mass-properties.md).\n"
    "Closed: every edge, between vertices' places (equal coordinates are one place), runs once\n"
    "each way; a mesh wound inward is closed.\n"
    "\n"
    "output, one quantity a line, numbers printed with %.17g:\n"
    "    mass M                  density times the absolute volume\n"
    "    volume V ORIENTATION    the signed volume: V > 0 'outward' (counter-clockwise seen from\n"
    "                            outside), V < 0 'inward' (every face wound the other way), V = 0\n"
    "                            'flat' (the mesh encloses nothing: centre and inertia are nan)\n"
    "    area S                  the surface's area\n"
    "    center X Y Z            the centre of mass, in the file's coordinates\n"
    "    inertia I00 I01 I02     the inertia tensor about the centre of mass, one row a line\n"
    "    inertia I10 I11 I12     (density times the integrals of y^2 + z^2, -xy, ...)\n"
    "    inertia I20 I21 I22\n"
    "An inward mesh gives the mass, centre and inertia of the same solid; only V's sign differs.\n"
    "\n"
    "options:\n"
    "  --density RHO     the density, a finite number > 0 (default 1)\n"
    "  --json            one JSON object instead: {\"density\": RHO, \"mass\": M, \"volume\": V,\n"
    "                    \"orientation\": \"outward\", \"area\": S, \"center\": [X, Y, Z], \"inertia\":\n"
    "                    [[I00, I01, I02], [I10, I11, I12], [I20, I21, I22]]} (a number that is not\n"
    "                    finite is null)\n"
    "  --precision P     double (default) or float: the coordinates rounded once to float from the\n"
    "                    file's text, as `ttd mesh --precision float` reads them (the sums are in\n"
    "                    double either way: double holds a float exactly)\n"
    "  --weld TOL        merge the vertices within distance TOL of each other first (chained),\n"
    "                    dropping triangles that collapse (docs/mesh-files.md, Welding)\n"
    "  --strict          refuse an OBJ line that is not an OBJ statement (skipped and reported by\n"
    "                    default)\n"
    "  --help            this text\n"
    "\n"
    "Exit status: 0 done; 1 the file cannot be read or is malformed (the message names the file and\n"
    "line or byte offset), the mesh is not closed, or an output error; 2 bad command line (unknown\n"
    "option, a missing or extra operand, a density that is not a finite number > 0). Nothing is\n"
    "printed on standard output unless the status is 0.\n";

typedef struct ttd_mass_args {
    const char *path;
    double density;
    int use_float, json, strict;
    const char *weld_s;
    double weld;
} ttd_mass_args;

/* Options; --name value and --name=value both work. 0, 1 after --help, -1 after a message. */
static int ttd_mass_parse_args(int argc, char **argv, ttd_mass_args *a)
{
    static const char name[] = "mesh mass";
    static const char *const flags[] = {"--json", "--strict", NULL};
    static const char *const valued[] = {"--density", "--precision", "--weld", NULL};
    a->density = 1.0;
    ttd_cli_args w = ttd_cli_args_start(name, flags, valued, argc, argv);
    for (ttd_cli_arg k; (k = ttd_cli_next_arg(&w)) != TTD_ARG_END;) {
        const char *val = w.val;
        if (k == TTD_ARG_BAD)
            return -1;
        if (k == TTD_ARG_HELP) {
            fputs(ttd_mass_usage, stdout);
            return 1;
        }
        if (k == TTD_ARG_OPERAND) {
            if (a->path != NULL) {
                ttd_cli_error("%s: unexpected argument '%s' (one mesh file A is taken)", name, w.arg);
                return -1;
            }
            a->path = w.arg;
        } else if (k == TTD_ARG_FLAG) {
            *(w.opt[2] == 'j' ? &a->json : &a->strict) = 1;
        } else if (strcmp(w.opt, "--density") == 0) {
            /* the library refuses the same (TTD_ERR_BAD_OPTIONS); checked here to say why */
            if (ttd_cli_parse_real(val, &a->density) != 0 || !(a->density > 0)) {
                ttd_cli_bad_value(&w, "a finite number > 0");
                return -1;
            }
        } else if (strcmp(w.opt, "--weld") == 0) {
            a->weld_s = val;
            if (ttd_cli_parse_weld(val, &a->weld) != 0) {
                ttd_cli_bad_value(&w, "a finite number >= 0");
                return -1;
            }
        } else if (strcmp(val, "double") == 0 || strcmp(val, "float") == 0) {
            a->use_float = val[0] == 'f';
        } else {
            ttd_cli_bad_value(&w, "double or float");
            return -1;
        }
    }
    if (a->path == NULL) {
        ttd_cli_error("%s: the mesh file A is missing (see ttd %s --help)", name, name);
        return -1;
    }
    return 0;
}

/* Reads, welds and builds the mesh, then computes; 0 or the exit status after the message. */
static int ttd_mass_compute(const ttd_mass_args *a, ttd_mass_properties *mp)
{
    const char *fname = strcmp(a->path, "-") == 0 ? "<stdin>" : a->path;
    const ttd_options opt = ttd_default_options();
    ttd_meshfile file;
    char err[1024];
    const int flags = (a->use_float ? TTD_MESHFILE_FLOAT : 0) | (a->strict ? TTD_MESHFILE_STRICT : 0);
    if (ttd_meshfile_read(a->path, flags, &file, err, sizeof err) != 0) {
        ttd_cli_error("%s", err);
        return TTD_EXIT_INPUT;
    }
    if (file.skipped_lines > 0)
        ttd_cli_error("%s: skipped %zu %s, first at %s:%zu (--strict refuses them)", fname, file.skipped_lines,
                      file.skipped_lines == 1 ? "line that is not an OBJ statement" : "lines that are not OBJ statements",
                      fname, file.first_skipped_line);
    if (a->weld_s && ttd_cli_weld(&file, fname, a->weld) != 0) {
        ttd_meshfile_free(&file);
        return TTD_EXIT_INPUT;
    }
    ttd_mesh *mesh = NULL;
    ttd_status st = a->use_float ? ttd_mesh_create_f(&opt, file.verts_f, file.nv, file.tris, file.nt, &mesh)
                                 : ttd_mesh_create_d(&opt, file.verts, file.nv, file.tris, file.nt, &mesh);
    ttd_meshfile_free(&file);
    if (st != TTD_OK) {
        ttd_cli_error("%s: cannot build the mesh: %s", fname, ttd_status_string(st));
        return TTD_EXIT_INPUT;
    }
    st = a->use_float ? ttd_mesh_mass_properties_f(mesh, a->density, mp)
                      : ttd_mesh_mass_properties_d(mesh, a->density, mp);
    if (st == TTD_ERR_MESH_NOT_CLOSED) {
        /* name what is wrong where the orientation check sees it (it compares vertex indices,
         * the mass's check places, so an unwelded soup is "open" to it: say nothing then) */
        ttd_orientation o = TTD_ORIENTATION_OUTWARD;
        (void)ttd_mesh_orientation(mesh, &o);
        ttd_cli_error("%s: mesh mass: the mesh is not closed%s: an edge that does not run once each way (a hole, "
                      "or faces wound both ways), so it bounds no solid",
                      fname, o == TTD_ORIENTATION_INCONSISTENT ? " (inconsistently oriented)" : "");
    } else if (st != TTD_OK) {
        ttd_cli_error("%s: mesh mass: %s", fname, ttd_status_string(st));
    }
    ttd_mesh_destroy(mesh);
    return st == TTD_OK ? 0 : TTD_EXIT_INPUT;
}

/* The orientation the signed volume reports. */
static const char *ttd_mass_orientation(double volume)
{
    return volume > 0 ? "outward" : volume < 0 ? "inward" : volume == 0 ? "flat" : "unknown";
}

/* A JSON number: %.17g, or null where JSON has none (NaN, inf). */
static void ttd_mass_json_number(FILE *f, double x)
{
    if (isfinite(x))
        fprintf(f, "%.17g", x);
    else
        fputs("null", f);
}

static void ttd_mass_print(FILE *f, const ttd_mass_args *a, const ttd_mass_properties *in)
{
    ttd_mass_properties p = *in, *mp = &p;
    /* x + 0 turns a zero's sign (a product of inertia summed to -0) into +0: "-0" would only puzzle */
    mp->mass += 0.0;
    mp->volume += 0.0;
    mp->area += 0.0;
    for (int k = 0; k < 3; ++k)
        mp->center[k] += 0.0;
    for (int k = 0; k < 9; ++k)
        mp->inertia[k] += 0.0;
    if (!a->json) {
        fprintf(f, "mass %.17g\nvolume %.17g %s\narea %.17g\n", mp->mass, mp->volume, ttd_mass_orientation(mp->volume),
                mp->area);
        fprintf(f, "center %.17g %.17g %.17g\n", mp->center[0], mp->center[1], mp->center[2]);
        for (int r = 0; r < 3; ++r)
            fprintf(f, "inertia %.17g %.17g %.17g\n", mp->inertia[3 * r], mp->inertia[3 * r + 1], mp->inertia[3 * r + 2]);
        return;
    }
    const struct {
        const char *key;
        double v;
    } scalars[] = {{"density", a->density}, {"mass", mp->mass}, {"volume", mp->volume}};
    fputc('{', f);
    for (size_t k = 0; k < sizeof scalars / sizeof scalars[0]; ++k) {
        fprintf(f, "%s\"%s\": ", k ? ", " : "", scalars[k].key);
        ttd_mass_json_number(f, scalars[k].v);
    }
    fprintf(f, ", \"orientation\": \"%s\", \"area\": ", ttd_mass_orientation(mp->volume));
    ttd_mass_json_number(f, mp->area);
    fputs(", \"center\": [", f);
    for (int c = 0; c < 3; ++c) {
        fputs(c ? ", " : "", f);
        ttd_mass_json_number(f, mp->center[c]);
    }
    fputs("], \"inertia\": [", f);
    for (int r = 0; r < 3; ++r) {
        fputs(r ? ", [" : "[", f);
        for (int c = 0; c < 3; ++c) {
            fputs(c ? ", " : "", f);
            ttd_mass_json_number(f, mp->inertia[3 * r + c]);
        }
        fputc(']', f);
    }
    fputs("]}\n", f);
}

int ttd_cli_mesh_mass(int argc, char **argv)
{
    ttd_mass_args a;
    memset(&a, 0, sizeof a);
    int rc = ttd_mass_parse_args(argc, argv, &a);
    if (rc != 0)
        return rc > 0 ? TTD_EXIT_OK : TTD_EXIT_USAGE;
    ttd_mass_properties mp;
    if ((rc = ttd_mass_compute(&a, &mp)) != 0)
        return rc;
    ttd_mass_print(stdout, &a, &mp);
    if (fflush(stdout) != 0 || ferror(stdout)) {
        ttd_cli_error("mesh mass: error writing the output");
        return TTD_EXIT_INPUT;
    }
    return TTD_EXIT_OK;
}
