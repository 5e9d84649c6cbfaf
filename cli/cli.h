/* SPDX-License-Identifier: MIT */
/* The ttd program's commands and the helpers they share (option values, messages).
 *
 * Hook for `ttd bench` (the .c files of bench/ are compiled into this program by cli/CMakeLists.txt): define
 *     int ttd_bench_main(int argc, char **argv);
 * in bench/, with argv[0] == "bench" and the rest its arguments; return the exit status. It is
 * declared weak here, so the program links and says "not built" without it. The helpers below
 * (ttd_cli_parse_*, ttd_cli_print_isas) are there for it to use too. */
#ifndef TTD_CLI_CLI_H
#define TTD_CLI_CLI_H

#include <stdio.h>
#include "ttd/ttd.h"

/// Exit statuses of every command.
enum {
    TTD_EXIT_OK = 0,    ///< everything computed
    TTD_EXIT_INPUT = 1, ///< some input line was bad, or reading/writing failed
    TTD_EXIT_USAGE = 2  ///< bad command line (unknown option, value out of range, ISA unavailable)
};

/// `ttd dist [options] [FILE]`.
int ttd_cli_dist(int argc, char **argv);
/// `ttd dist` on given streams (for `ttd bench`, which times the command's input and output
/// paths in-process): argv holds "dist" and options only, no FILE; no progress line. Returns
/// the exit status.
int ttd_cli_dist_run(int argc, char **argv, FILE *in, FILE *out);
/// `ttd mesh distance | contacts | collide A B [options]` (cli/mesh.c); argv[0] is "mesh".
int ttd_cli_mesh(int argc, char **argv);
/// `ttd mesh mass A [options]` (cli/mesh_mass.c): a closed mesh's mass properties; argv[0] is "mass".
int ttd_cli_mesh_mass(int argc, char **argv);
/// `ttd scene collide | distance | contacts | manifold SCENE [options]` (cli/scene.c); argv[0] is "scene".
int ttd_cli_scene(int argc, char **argv);
/// `ttd points closest|signed|winding|grid` (points.c).
int ttd_cli_points(int argc, char **argv);
/// `ttd ccd FILE` (ccd.c): continuous collision of a CCD-benchmark CSV file.
int ttd_cli_ccd(int argc, char **argv);
/// Reads a CCD-benchmark CSV file (ccd.c): kind_hint 1 (vertex-face), 2 (edge-edge) or 0 (from
/// the path); *x0, *x1: 12 numbers a query (4 points), *truth 0/1 a query, *inexact the rows
/// whose rationals were rounded; malloc'd (the caller frees). 0, or -1 after a message.
int ttd_cli_ccd_read(const char *path, int kind_hint, int *kind, size_t *nq, double **x0, double **x1,
                     int **truth, size_t *inexact);
/// Runs n queries of that layout through ttd_ccd_vertex_face_d / ttd_ccd_edge_edge_d; the status.
int ttd_cli_ccd_run(const ttd_options *o, int kind, size_t n, const double *x0, const double *x1,
                    double delta, ttd_ccd_result *out);
/// `ttd mesh-ccd A_T0 A_T1 [B_T0 B_T1]` (mesh_ccd.c): continuous collision of deforming meshes.
int ttd_cli_mesh_ccd(int argc, char **argv);
/// `ttd mesh-ccd-rigid A B POSES` (mesh_ccd_rigid.c): continuous collision of rigid meshes between two poses.
int ttd_cli_mesh_ccd_rigid(int argc, char **argv);
/// `ttd bench ...`, defined in bench/ when it exists.
int ttd_bench_main(int argc, char **argv) __attribute__((weak));

/// Prints "ttd: " and the message to stderr.
void ttd_cli_error(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
/// A ttd_method_name, e.g. "penalty-ref"; 0 on success, -1 when unknown.
int ttd_cli_parse_method(const char *s, ttd_method *out);
/// A ttd_isa_name, e.g. "avx2" or "auto"; 0 on success, -1 when unknown.
int ttd_cli_parse_isa(const char *s, ttd_isa *out);
/// A whole decimal integer in [lo, hi]; 0 on success, -1 otherwise.
int ttd_cli_parse_int(const char *s, long lo, long hi, long *out);

/// Walks a command's arguments, one ttd_cli_next_arg at a time, so that every command reads
/// operands, --help, "--" and its options' names alike; what an option or operand means, and
/// which go together, stays with the command. Start it with ttd_cli_args_start.
typedef struct ttd_cli_args {
    const char *command;       ///< the command's name in messages, e.g. "mesh mass"
    const char *const *flags;  ///< options without a value, NULL-terminated (NULL: none)
    const char *const *valued; ///< options with a value, `--name value` or `--name=value`, NULL-terminated
    /// 0 (the default): an argument starting with '-' is an option ("-" alone is an operand) and
    /// "--" makes every later argument an operand. 1 (`ttd ccd`, `mesh-ccd`, `mesh-ccd-rigid`):
    /// only "--..." and "-h" are options, so "-x" is an operand and "--" an unknown option.
    int long_only;
    /// 1 (`ttd points`): "--" is an unknown option rather than the end of the options.
    int no_end_marker;
    int argc;
    char **argv;
    int i;                     ///< the next argument's index in argv
    int only_operands;         ///< "--" was read
    const char *arg;           ///< the argument last read (an operand's text)
    const char *opt, *val;     ///< the option last read: its entry in flags or valued, and its value
} ttd_cli_args;

/// What ttd_cli_next_arg read.
typedef enum ttd_cli_arg {
    TTD_ARG_END = 0, ///< no argument is left
    TTD_ARG_OPERAND, ///< an operand, in w->arg
    TTD_ARG_HELP,    ///< --help or -h
    TTD_ARG_FLAG,    ///< an option of flags, in w->opt
    TTD_ARG_VALUE,   ///< an option of valued, in w->opt, with its value in w->val
    /// An unknown option or a missing value, said on stderr ("COMMAND: unknown option 'ARG' (see
    /// ttd COMMAND --help)", "COMMAND: OPT needs a value"): exit status 2.
    TTD_ARG_BAD
} ttd_cli_arg;

/// A walker over argv[1..argc) (argv[0] is the command's own name) in the default style.
ttd_cli_args ttd_cli_args_start(const char *command, const char *const *flags, const char *const *valued, int argc,
                                char **argv);
/// The next argument: what it is, with w->arg, w->opt and w->val set to match.
ttd_cli_arg ttd_cli_next_arg(ttd_cli_args *w);
/// Where a walk of `ccd`, `mesh-ccd` or `mesh-ccd-rigid` stops early, its exit status: at --help
/// (k TTD_ARG_HELP) usage printed on stdout and TTD_EXIT_OK; at a bad argument (TTD_ARG_BAD,
/// already said on stderr) TTD_EXIT_USAGE; -1 for any other k, which the command reads on.
int ttd_cli_stop_status(ttd_cli_arg k, const char *usage);
/// "COMMAND: bad value for OPT: 'VAL' (WHY)" for the option w read last; WHY NULL says "see ttd
/// COMMAND --help".
void ttd_cli_bad_value(const ttd_cli_args *w, const char *why);
/// The options every computing command takes alike: --precision double|float, --isa NAME,
/// --threads N (0..2^20). 1 when opt is none of them; otherwise 0, or -1 when val is bad
/// (nothing printed: the caller names its command).
int ttd_cli_run_option(const char *opt, const char *val, ttd_options *o, int *use_float);
/// A finite number (strtod syntax, the whole string); 0 on success, -1 otherwise.
int ttd_cli_parse_real(const char *s, double *out);
/// Why the 12 numbers of a pose ([R | t] row by row) are not one the library takes (every entry
/// of R^T R - I within 1e-6, det R > 0, computed in double): -1 with the reason in err, or 0.
/// With ortho (--orthonormalize) R is first replaced by the nearest rotation when it is within
/// 1e-2 of orthonormal with det R > 0 (p is then changed). Shared by `ttd mesh` and `ttd scene`.
int ttd_cli_pose_problem(double p[12], int ortho, char *err, size_t errsize);
/// --weld TOL of the commands that read mesh files: a finite number >= 0 (0 on success, -1
/// otherwise; nothing printed).
int ttd_cli_parse_weld(const char *s, double *out);
struct ttd_meshfile;
/// Welds a mesh just read from name at tolerance tol (ttd_meshfile_weld): 0, with a note on
/// stderr when collapsed triangles were dropped, or -1 after the reader's message.
int ttd_cli_weld(struct ttd_meshfile *m, const char *name, double tol);
/// Lines "built: ...", "cpu:   ...", "auto:  ..." (the instruction sets).
void ttd_cli_print_isas(FILE *f);
/// Warns on stderr ("COMMAND: warning: ...") when the library is ignoring TTD_ISA.
void ttd_cli_warn_isa_env(const char *command);

#endif /* TTD_CLI_CLI_H */
