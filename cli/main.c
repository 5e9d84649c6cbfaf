/* SPDX-License-Identifier: MIT */
/* The ttd program: `ttd dist`, `ttd mesh`, `ttd scene`, `ttd info`, `ttd bench` (when built), --help, --version. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"
#include "ttd/ttd_gpu.h"

#ifndef TTD_C_COMPILER
#define TTD_C_COMPILER "unknown"
#endif
#ifndef TTD_C_FLAGS
#define TTD_C_FLAGS ""
#endif

static const char ttd_usage[] =
    "usage: ttd COMMAND [options]\n"
    "Minimum distance between 3D triangles, many pairs at a time, on SIMD hardware.\n"
    "\n"
    "commands:\n"
    "  dist [options] [FILE]   distances of the triangle pairs in FILE or standard input\n"
    "                          (ttd dist --help for the format and options)\n"
    "  mesh distance A B       minimum distance between the meshes in files A and B (OBJ, STL,\n"
    "                          PLY, OFF, glTF, 3MF), closest points and triangles, poses of B\n"
    "  mesh contacts A B       every triangle pair within a margin (--margin M), or per triangle\n"
    "                          its closest partner (--per-triangle), or their number (--count)\n"
    "  mesh collide A B        whether the meshes touch, cross or come within --margin M\n"
    "  mesh self-contacts A    every pair of A's triangles within --margin M that share no\n"
    "                          vertex (a mesh against itself: cloth, folded sheets)\n"
    "  mesh self-collide A     whether A intersects itself (or comes within --margin M)\n"
    "  mesh mass A             mass, signed volume (its sign: the orientation), area, centre\n"
    "                          and inertia of the solid a closed mesh bounds (--density, --json)\n"
    "                          (ttd mesh --help for the formats and options)\n"
    "  points closest MESH P   the exact closest point of the mesh to each point of the file P\n"
    "  points signed MESH P    signed distances (negative inside), points winding MESH P: winding\n"
    "                          numbers, points grid MESH: signed distances on a grid into a .npy\n"
    "                          or raw file (ttd points --help for the formats and options)\n"
    "  scene collide SCENE     every pair of bodies of a scene file within --margin M (default\n"
    "                          0), with a witness pair of triangles each\n"
    "  scene distance SCENE    the closest pair of bodies, its triangles and closest points\n"
    "  scene contacts SCENE    every triangle pair of every body pair within --margin M\n"
    "  scene manifold SCENE    contact points, normals and depths per body pair, at most\n"
    "                          --max-points K each; each query once, or per step of\n"
    "                          --motion FILE (ttd scene --help for the formats and options)\n"
    "  ccd FILE                continuous collision of moving vertex-face or edge-edge queries in a\n"
    "                          CSV file of the CCD benchmark's format (ttd ccd --help)\n"
    "  mesh-ccd A0 A1 [B0 B1]  continuous collision of deforming meshes (files at t = 0 and t = 1):\n"
    "                          the earliest time of impact and the pairs at it (ttd mesh-ccd --help)\n"
    "  mesh-ccd-rigid A B POSES  continuous collision of rigid meshes between two poses each\n"
    "                          (ttd mesh-ccd-rigid --help)\n"
    "  info                    version, instruction sets built and supported, the one chosen\n"
    "                          (ttd info --help)\n"
    "  bench [options]         the benchmark (ttd bench --help), when built in\n"
    "  --help                  this text\n"
    "  --version               version and instruction sets\n"
    "\n"
    "The environment variable TTD_ISA (scalar, sse2, avx2, avx512, neon, portable) forces an instruction\n"
    "set wherever the options say auto.\n";

static void ttd_print_version(FILE *f)
{
    fprintf(f, "ttd %s\n", ttd_version_string());
    ttd_cli_print_isas(f);
}

static const char ttd_info_usage[] =
    "usage: ttd info\n"
    "Prints the version, the instruction sets built in, those this CPU and OS support, the one\n"
    "auto picks (and TTD_ISA when set), lanes per instruction set, the methods, the online cores,\n"
    "the compiler and flags, whether `ttd bench` is built in, and whether a GPU is usable (the\n"
    "GPU library, include/ttd/ttd_gpu.h). Takes no operands.\n";

static int ttd_info(int argc, char **argv)
{
    for (int i = 1; i < argc; ++i) {
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            fputs(ttd_info_usage, stdout);
            return TTD_EXIT_OK;
        }
    }
    if (argc > 1) {
        ttd_cli_error("info: unexpected argument '%s' (see ttd info --help)", argv[1]);
        return TTD_EXIT_USAGE;
    }
    ttd_print_version(stdout);
    printf("lanes (float/double):");
    for (int i = 1; i < TTD_ISA_COUNT; ++i)
        if (ttd_isa_available((ttd_isa)i))
            printf(" %s %d/%d", ttd_isa_name((ttd_isa)i), ttd_isa_lanes((ttd_isa)i, 4),
                   ttd_isa_lanes((ttd_isa)i, 8));
    printf("\nmethods:");
    for (int m = 0; m < TTD_METHOD_COUNT; ++m)
        printf(" %s", ttd_method_name((ttd_method)m));
    printf("\nthreads: %ld online cores\n", sysconf(_SC_NPROCESSORS_ONLN));
    printf("compiler: %s\nflags: %s\n", TTD_C_COMPILER, TTD_C_FLAGS);
    printf("bench: %s\n", ttd_bench_main ? "built" : "not built");
    ttd_gpu_info gi;
    const ttd_gpu_status gs = ttd_gpu_query(&gi);
    if (gs == TTD_GPU_OK)
        printf("gpu: usable: device %d of %d, %s (compute capability %d.%d), CUDA driver %d.%d, runtime %d.%d\n",
               gi.device, gi.device_count, gi.name, gi.cc_major, gi.cc_minor, gi.driver_version / 1000,
               gi.driver_version % 1000 / 10, gi.runtime_version / 1000, gi.runtime_version % 1000 / 10);
    else if (gs == TTD_GPU_ERR_NOT_BUILT)
        printf("gpu: not built (%s)\n", gi.message);
    else
        printf("gpu: built, not usable: %s\n", gi.message[0] ? gi.message : ttd_gpu_status_string(gs));
    return fflush(stdout) == 0 ? TTD_EXIT_OK : TTD_EXIT_INPUT;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fputs(ttd_usage, stderr);
        return TTD_EXIT_USAGE;
    }
    const char *cmd = argv[1];
    if (strcmp(cmd, "--help") == 0 || strcmp(cmd, "-h") == 0 || strcmp(cmd, "help") == 0) {
        fputs(ttd_usage, stdout);
        return TTD_EXIT_OK;
    }
    if (strcmp(cmd, "--version") == 0) {
        ttd_print_version(stdout);
        return TTD_EXIT_OK;
    }
    if (strcmp(cmd, "info") == 0)
        return ttd_info(argc - 1, argv + 1);
    if (strcmp(cmd, "dist") == 0)
        return ttd_cli_dist(argc - 1, argv + 1);
    if (strcmp(cmd, "mesh") == 0)
        return ttd_cli_mesh(argc - 1, argv + 1);
    if (strcmp(cmd, "points") == 0)
        return ttd_cli_points(argc - 1, argv + 1);
    if (strcmp(cmd, "scene") == 0)
        return ttd_cli_scene(argc - 1, argv + 1);
    if (strcmp(cmd, "ccd") == 0)
        return ttd_cli_ccd(argc - 1, argv + 1);
    if (strcmp(cmd, "mesh-ccd") == 0)
        return ttd_cli_mesh_ccd(argc - 1, argv + 1);
    if (strcmp(cmd, "mesh-ccd-rigid") == 0)
        return ttd_cli_mesh_ccd_rigid(argc - 1, argv + 1);
    if (strcmp(cmd, "bench") == 0) {
        if (ttd_bench_main == NULL) {
            ttd_cli_error("bench: not built into this program");
            return TTD_EXIT_USAGE;
        }
        return ttd_bench_main(argc - 1, argv + 1);
    }
    ttd_cli_error("unknown command '%s' (see ttd --help)", cmd);
    return TTD_EXIT_USAGE;
}
