/* SPDX-License-Identifier: MIT */
/* A small rigid-body simulator on ttd's scene manifolds: the judge of issue 23 (docs/simulator.md).
 *
 * Shapes are closed triangle meshes (boxes in three triangulations, icospheres, tori) with their
 * mass properties and a split into convex pieces; bodies are shapes at poses, dynamic or static.
 * Each step asks ttd for the contact manifolds within a margin (ttd_scene_manifold_d, at most
 * 4 points per body pair), solves the contacts by sequential impulses with friction, warm
 * started from the previous step's matching contacts, and moves the bodies by semi-implicit
 * Euler. Bodies rest on a thin gap inside the margin: a contact at distance d pushes only when
 * d falls below the rest gap, and lets the bodies close at most d - gap in one step (speculative
 * contact), so surfaces never need to cross and the manifold's distances stay meaningful.
 *
 * overlap.c measures interpenetration without the manifold: ttd's collide at 0 finds the pairs
 * whose surfaces touch or cross, and the separating-axis test on the shapes' convex pieces
 * gives their depth (exact for convex pieces: the smallest overlap over face normals and edge
 * cross products).
 *
 * Uses only ttd's public header (and gen/ for the icosphere and torus). Deterministic: one
 * thread in the solver, and ttd's answers do not depend on its thread count. */
#ifndef TTD_SIM_H
#define TTD_SIM_H

#include <ttd/ttd.h>

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/// The triangulations of a box's faces (docs/simulator.md).
typedef enum sim_box_tri {
    SIM_BOX_DIAG_A = 0, ///< python/README.md's cube: each face split along one diagonal
    SIM_BOX_DIAG_B = 1, ///< the same faces split along their other diagonals
    SIM_BOX_FAN = 2,    ///< docs/examples/cube.obj's quads, fanned from each quad's first corner
    SIM_BOX_CENTRE = 3, ///< a vertex at each face's centre, four triangles a face
    SIM_BOX_CUT = 4     ///< each face cut 4 x 4, its inner vertices moved in the face's plane (fixed generator)
} sim_box_tri;

/// A convex part of a shape, for the separating-axis test: its vertices, the outward normals of
/// its faces (a unit vector and a point's offset along it) and its edge directions, in the
/// shape's frame. Edges may repeat and include faces' diagonals (a superset of the hull's
/// edge directions does not change the test's answer).
typedef struct sim_piece {
    size_t nv, nn, ne;
    double centre[3], radius; ///< a sphere around its vertices
    double *v;       ///< 3 nv
    double *normal;  ///< 4 nn: unit normal, then its plane's offset (n . x <= offset inside)
    double *edge;    ///< 3 ne
} sim_piece;

/// A closed triangle mesh with its centroid at the origin, its mass properties at unit density
/// and its convex pieces.
typedef struct sim_shape {
    char name[32];
    double *v;        ///< 3 nv, centroid at the origin
    uint32_t *t;      ///< 3 nt, counter-clockwise from outside
    size_t nv, nt;
    ttd_mesh *mesh;   ///< ttd's mesh of v and t (double)
    double volume;
    double inertia[9]; ///< about the centroid, unit density
    double radius;    ///< the largest |v|
    double size;      ///< the largest extent of its bounding box: what drift is measured against
    size_t npieces;
    sim_piece *pieces;
} sim_shape;

/// A box of half extents h, triangulated as tri. 0, or -1 on failure (then *s is empty).
int sim_shape_box(sim_shape *s, const double h[3], sim_box_tri tri);
/// An icosphere of the given radius and subdivision level, turned so that a face lies flat
/// under it (its lowest face normal is -z).
int sim_shape_icosphere(sim_shape *s, double radius, int level);
/// A torus around z (ttd_gen_torus: tube centre radius R, tube radius r, nu x nv segments), cut
/// into nu convex pieces, one per segment.
int sim_shape_torus(sim_shape *s, double R, double r, size_t nu, size_t nv);
/// A bowl, static in the scenes: the shell between two concentric spheres (inner radius r, the
/// outer r + thickness) from the bottom up to the polar angle rim (rad) from the lowest point,
/// closed at the rim by a cone; nu segments around z, nseg along the arc. Each cell (a segment
/// by an arc step) is a convex piece. *bottom receives the inner surface's lowest point's
/// height in the shape's frame.
int sim_shape_bowl(sim_shape *s, double r, double thickness, double rim, size_t nu, size_t nseg, double *bottom);
/// Frees a shape (its ttd mesh too) and zeroes it.
void sim_shape_free(sim_shape *s);
/// The largest amount by which a vertex of a piece lies outside one of that piece's faces,
/// relative to the shape's radius: about 1e-16 when every piece is convex.
double sim_shape_convexity_defect(const sim_shape *s);

/// A body: a shape at a pose, moving or static.
typedef struct sim_body {
    const sim_shape *shape;
    int is_static;
    double inv_mass;
    double inv_inertia[9];        ///< in the body's frame
    double x[3], q[4], v[3], w[3]; ///< centroid, orientation (w, x, y, z), velocities (world)
    double R[9];                  ///< q as a matrix
    double inv_inertia_world[9];  ///< R inv_inertia R^T
} sim_body;

/// One contact point as the solver holds it.
typedef struct sim_contact {
    uint32_t a, b;          ///< bodies (a < b); the normal points from a to b
    double point[3], normal[3], distance;
    double ra[3], rb[3];    ///< point - x_a, point - x_b
    double local_a[3], local_b[3]; ///< the point in a's and b's frames (matching; the gap's change)
    double point_a0[3], point_b0[3]; ///< where those were at the manifold
    double t1[3], t2[3];    ///< tangents
    double mass_n, mass_t1, mass_t2;
    double impulse_n, impulse_t1, impulse_t2; ///< accumulated impulses along normal, t1, t2
    int claimed;            ///< (previous step's list) already handed to a new contact
} sim_contact;

/// The solver's settings (sim_world_default_settings gives the documented defaults).
typedef struct sim_settings {
    double dt;            ///< time step, s
    double gravity[3];
    double margin;        ///< M: the manifold's margin
    double rest_gap;      ///< the gap bodies rest on, inside the margin
    size_t max_points;    ///< K: manifold points per body pair
    int substeps;         ///< solver substeps per step (one manifold per step)
    int iterations;       ///< solve and relax sweeps per substep
    double friction;      ///< Coulomb coefficient
    double contact_hertz; ///< the stiffness of the spring that pushes a gap deficit out
    double damping_ratio; ///< and its damping ratio
    double max_push;      ///< the largest separating speed a deficit asks for, m/s
    double match_distance; ///< a contact keeps its impulses when the previous step had one this close
    int warm_start;       ///< 0: every step's impulses start at 0
    int solid;            ///< bodies are solids (ttd_scene_set_solid: depth through crossing); 0: surfaces
    int threads;          ///< ttd's thread count (results do not depend on it)
    int vertical_normals; ///< diagnostic: every normal replaced by +z (a stack's exact normal)
    double jig;           ///< the stacks' offsets and turns are this times their defaults (1)
    int ccd;              ///< continuous collision after the solver (ccd.c): 1 on, 0 off, -1 (default) the scenario's choice (off but fast-sphere)
} sim_settings;

sim_settings sim_default_settings(void);

/// A world: bodies, ttd's scene of them, the contacts of the last step.
typedef struct sim_world {
    sim_settings set;
    sim_body *body;
    size_t n, cap;
    ttd_scene *scene;
    ttd_options opt;
    ttd_scene_array manifold;
    sim_contact *contact, *previous;
    size_t ncontact, nprevious, contact_cap, previous_cap;
    double *poses;        ///< 12 per body, for ttd_scene_set_poses_d
    double time;
    double query_seconds, solve_seconds; ///< CPU time in the manifold query and in the rest
    size_t steps, points; ///< steps taken, manifold points summed over them
    double max_tilt;      ///< largest angle (rad) of a resting contact's normal from vertical, see sim_world_step
    /* continuous collision (ccd.c), when set.ccd > 0 */
    ttd_mesh **ccd_mesh;  ///< each body's world vertices at the step's start (static bodies: built once)
    double *ccd_x0;       ///< 7 per body: centroid and orientation at the step's start
    double *ccd_v, *ccd_box; ///< scratch: world vertices at both ends, each body's box around both
    size_t ccd_cap;
    double ccd_seconds;   ///< CPU time in the CCD pass
    double ccd_last_toi;  ///< the earliest toi of the last step's first round (INFINITY: none)
    double ccd_max_chord; ///< the largest chord error added to a pair's separation so far
    size_t ccd_queries, ccd_steps, ccd_rounds; ///< mesh CCD calls; steps and rounds it limited
    size_t ccd_skipped;   ///< pairs not asked: the chord error over the separation even in 64 pieces
    size_t ccd_max_pieces; ///< the most pieces a pair's step was cut into
} sim_world;

/// A world with settings set (NULL: the defaults). 0 or -1.
int sim_world_init(sim_world *w, const sim_settings *set);
void sim_world_free(sim_world *w);
/// Adds a body of shape at centroid x, orientation q (w, x, y, z; normalised here); static
/// bodies never move and are not tested against each other. Returns its index, or -1.
long sim_world_add(sim_world *w, const sim_shape *shape, const double x[3], const double q[4], int is_static);
/// One step: manifold, contacts, solver, integration. 0, or -1 with a message on stderr when
/// ttd refuses a call (which would be a bug here).
int sim_world_step(sim_world *w);
/// R and the world inverse inertia from b's q.
void sim_body_update(sim_body *b);
/// The CCD pass (ccd.c): sim_ccd_begin keeps the bodies' poses at a step's start; after the
/// solver, sim_ccd_limit asks ttd_mesh_ccd_d of every body pair whose boxes around both ends
/// come within the separation (half the margin for a pair not in the step's manifold, half the
/// manifold's distance for one in it, plus the chord error of turning bodies; pairs touching or
/// crossing at the start are the solver's) and moves each body hit back along its motion to its
/// earliest toi; it asks again (up to 4 rounds), then sends every moving body back to the step's
/// start. Velocities are kept: the next step's manifold holds the pair. 0, or -1 when ttd
/// refuses a call.
int sim_ccd_begin(sim_world *w);
int sim_ccd_limit(sim_world *w);
void sim_ccd_free(sim_world *w);
/// Kinetic energy of the moving bodies (unit density).
double sim_world_kinetic(const sim_world *w);
/// The pose [R | x] of body k (12 doubles).
void sim_body_pose(const sim_body *b, double pose[12]);

/// Interpenetration, measured without the manifold (overlap.c): the deepest overlap of any two
/// bodies' convex pieces (0 when none overlap), among the pairs whose surfaces ttd's collide at
/// 0 finds touching or crossing, and the pairs whose boxes overlap with one body's vertex inside
/// the other (nested). *pair_a, *pair_b name the deepest pair (UINT32_MAX when none);
/// *touching counts the pairs whose surfaces collide at 0 finds touching or crossing (not a solid held
/// inside another). -1 when ttd refuses a call.
int sim_world_overlap(sim_world *w, double *depth, uint32_t *pair_a, uint32_t *pair_b, size_t *touching);

/// The separating-axis overlap of two convex pieces placed by poses: the smallest overlap of
/// their projections over the candidate axes, <= 0 when some axis separates them.
double sim_piece_overlap(const sim_piece *p, const double pose_p[12], const sim_piece *q, const double pose_q[12]);

/// After the caller changed bodies' x and q (another engine's poses): their matrices, and ttd's
/// scene, follow. 0, or -1 when ttd refuses a pose.
int sim_world_sync(sim_world *w);

/// What a rest window measured (measure.c).
typedef struct sim_figures {
    double drift;        ///< largest horizontal displacement of a vertex from its place at the window's start / size
    double centre_drift; ///< the same for centroids
    size_t drift_body;   ///< the body of the largest drift
    double overlap;      ///< deepest interpenetration at a sample / margin
    uint32_t overlap_a, overlap_b;
    size_t touching;     ///< most body pairs with surfaces touching or crossing at a sample
    double kinetic;      ///< kinetic energy at the end
    double max_tilt_deg; ///< largest angle of a contact normal from vertical over the run (stacks: 0 is right)
} sim_figures;

/// Advances w by one step (ttd_sim: sim_world_step; another engine: its step, then sim_world_sync).
typedef int (*sim_step_fn)(void *ctx, sim_world *w);

/// Runs settle seconds, then a rest window of seconds: drift at every step, interpenetration
/// (sim_world_overlap) at the window's start, every 0.25 s and at its end. 0 or -1.
int sim_run_window(sim_world *w, double settle, double seconds, sim_step_fn step, void *ctx, sim_figures *f);

/// Writes the bodies' world triangles as an OBJ file, one group per body ("g static_3" or
/// "g body_7"). 0 or -1.
int sim_world_write_obj(const sim_world *w, const char *path);

typedef struct sim_run sim_run;
/// After every step of a scenario that judges itself (judged.c): records what its verdict
/// needs. 0, or -1 when ttd refuses a call.
typedef int (*sim_observe_fn)(sim_run *run);
/// Such a scenario's verdict on its run, in place of the rest figures' drift < 1e-3 and
/// interpenetration < 0.1: 1 met, 0 not, with what was measured written to note.
typedef int (*sim_verdict_fn)(const sim_run *run, const sim_figures *f, char *note, size_t size);

/// A scenario (scenarios.c: issue 23's and the towers; judged.c: issue 32's dominoes, crossing
/// rods, bowl and slope): its world and shapes, how long it settles before the rest window,
/// and for the scenes that judge themselves, their observer, verdict and records.
struct sim_run {
    char name[32];
    sim_world world;
    sim_shape shape[8];
    size_t nshape;
    double settle;  ///< seconds simulated before the rest window starts
    double seconds; ///< the rest window's own length (0: the command's, 10 s by default)
    sim_observe_fn observe; ///< NULL, or called after every step
    sim_verdict_fn verdict; ///< NULL: the rest figures decide
    double value[40];       ///< the observer's records (each scene's own layout)
    double *trace;          ///< and a series (pairs of numbers), grown by sim_run_trace
    size_t ntrace, trace_cap;
};

/// The scenarios' names, NULL-terminated: stack-a, stack-b, stack-fan, stack-mixed, pyramid,
/// bin, tower-a, tower-fan, tower-centre, tower-cut, dominoes, rods, bowl, slope-slide,
/// slope-hold, fast-sphere.
extern const char *const sim_scenarios[];
/// Builds scenario name with settings set. 0, or -1 (unknown name, or a failure).
int sim_run_build(sim_run *run, const char *name, const sim_settings *set);
/// A floor under run's world: the top of a static box 8.4 wide at z = 0 (its shape the run's
/// next). 0 or -1.
int sim_run_add_floor(sim_run *run);
/// judged.c's scenes (run's world already made): 0, -1 on a failure, 1 when name is not one.
int sim_run_build_judged(sim_run *run, const char *name);
/// Appends the pair (a, b) to run's trace. 0 or -1.
int sim_run_trace(sim_run *run, double a, double b);
/// One step of run's world, then its observer: a sim_step_fn with run as its context.
int sim_run_step(void *run, sim_world *w);
void sim_run_free(sim_run *run);

#ifdef __cplusplus
}
#endif
#endif
