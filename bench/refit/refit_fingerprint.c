/* SPDX-License-Identifier: MIT */
/* FNV-1a of every node's boxes (centres, axes, extents, children, count: not the padding) after
 * each of four refits of `ttd bench`'s twisted torus (refit_steps.c's), at 900, 10k, 100k and 1M
 * triangles, on the scalar, AVX2 and AVX-512 rows, and the tree's measure after the last two:
 * built against two versions of the library, equal lines mean the same boxes bit for bit. Reads
 * the mesh's internals (src/mesh/mesh.h).
 *   gcc -O2 -Iinclude -I. -Isrc bench/refit/refit_fingerprint.c build/gen/libttd_gen.a \
 *       build/src/libttd.a -lm -lpthread -o refit_fingerprint */
#include "gen/meshes.h"
#include "mesh/mesh.h"
#include "ttd/ttd.h"
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>

static uint64_t fnv(uint64_t h, const void *p, size_t n)
{
    const unsigned char *c = p;
    for (size_t i = 0; i < n; ++i) {
        h ^= c[i];
        h *= 0x100000001b3ULL;
    }
    return h;
}

int main(void)
{
    static const size_t nus[4] = {30, 100, 316, 1000};
    static const char *const isas[3] = {"scalar", "avx2", "avx512"};
    for (int s = 0; s < 4; ++s)
        for (int ii = 0; ii < 3; ++ii) {
            const ttd_isa isa = ttd_isa_from_name(isas[ii]);
            if (!ttd_isa_available(isa))
                continue;
            ttd_gen_mesh g;
            if (ttd_gen_torus(1.0, 0.3, nus[s], nus[s] / 2, &g) != 0)
                return 1;
            double *mv = malloc(3 * g.nv * sizeof *mv), lo[3], hi[3], q[4];
            if (mv == NULL)
                return 1;
            ttd_gen_mesh_bounds(&g, lo, hi);
            for (size_t i = 0; i < g.nv; ++i) {
                const double *x = g.verts + 3 * i, a = 0.3 * (x[0] - lo[0]) / (hi[0] - lo[0]);
                mv[3 * i] = 1.02 * x[0];
                mv[3 * i + 1] = x[1] * cos(a) - x[2] * sin(a);
                mv[3 * i + 2] = x[1] * sin(a) + x[2] * cos(a);
            }
            ttd_options o = ttd_default_options();
            o.threads = 1;
            o.isa = isa;
            ttd_mesh *m;
            if (ttd_mesh_create_d(&o, g.verts, g.nv, g.tris, g.nt, &m) != TTD_OK)
                return 1;
            uint64_t h = 0xcbf29ce484222325ULL;
            for (int k = 0; k < 4; ++k) {
                if (ttd_mesh_set_vertices_d(&o, m, k % 2 ? g.verts : mv) != TTD_OK)
                    return 1;
                for (size_t n = 0; n < m->nnodes; ++n)
                    h = fnv(h, (const ttd_node_d *)m->nodes + n, offsetof(ttd_node_d, count) + sizeof(int32_t));
                q[k] = m->quality;
            }
            printf("%zu %s %016llx measure %.17g %.17g\n", g.nt, isas[ii], (unsigned long long)h, q[2], q[3]);
            ttd_mesh_destroy(m);
            free(mv);
            ttd_gen_mesh_free(&g);
        }
    return 0;
}
