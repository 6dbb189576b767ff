/*
 * ablmg.h: the C interface of ablmg's remesher, for C, Fortran (iso_c_binding) and any language
 * with a C FFI. It is the call `ablmg remesh` makes between reading and writing files
 * (ablmg::adapt::remesh, <ablmg/adapt/remesh.hpp>): same input, options and seed give the same
 * mesh, bit for bit, as `ablmg remesh -in IN.mesh -sol IN.sol` on files holding those arrays.
 *
 * What it does: the input triangle mesh gives the domain (its boundary edges, with their refs,
 * become the boundary loops; corners are kept) and, with one metric per vertex, the background
 * metric (log-Euclidean interpolation). The metric's sizes are clamped to [hmin, hmax], graded
 * (hgrad), and a new mesh whose edges have unit length in the metric is built (bubble placement
 * + connection, paper eqs. 3-12). The new mesh is valid: counter-clockwise triangles covering
 * the domain once, every boundary edge present with its ref.
 *
 * Arrays (n vertices, m triangles, k boundary edges):
 *   vertices   double[2n]  x0 y0 x1 y1 ...            (any length unit)
 *   triangles  int[3m]     a0 b0 c0 a1 b1 c1 ...      (vertex indices, 0- or 1-based: `base`)
 *   edges      int[2k]     a0 b0 a1 b1 ...            (the boundary edges: every edge that lies in
 *                                                      one triangle, each once)
 *   refs       int[n], int[m], int[k]                 (optional: NULL means all 0, or 1 for edges)
 *   metric     double[3n]  m11 m12 m22 per vertex     (symmetric positive definite, in 1/length²;
 *                                                      the unit ellipse {x : xᵀMx = 1} is the
 *                                                      wanted edge), or sizes double[n] (h > 0:
 *                                                      M = I/h²)
 * Triangles and boundary edges may be given in either orientation: they are turned
 * counter-clockwise and the boundary edges to have the domain on their left (as medit files
 * are read). The arrays are copied; the caller keeps them.
 *
 * Errors: every function returns ABLMG_OK (0) or a negative ablmg_status; the handle then holds
 * a one-line message, ablmg_last_error(handle), naming the array, the index and the value (for
 * a failed run the message ablmg remesh would print, e.g. "input: invalid mesh: triangle 3 is
 * inverted"). Nothing is printed, no file is written, no C++ exception leaves this interface,
 * and there is no global state: handles are independent, one handle per thread at a time.
 *
 * Usage (tests/consumer/remesh_c.c runs this; link ablmg::capi with CMake, or
 * `pkg-config --cflags --libs ablmg`):
 *
 *   #include <ablmg/capi/ablmg.h>
 *   #include <stdio.h>
 *   #include <stdlib.h>
 *
 *   int main(void) {
 *     // The unit square as two triangles, four boundary edges with refs 1..4.
 *     const double xy[] = {0, 0, 1, 0, 1, 1, 0, 1};
 *     const int tri[] = {1, 2, 3, 1, 3, 4};            // 1-based, as in a medit file
 *     const int edges[] = {1, 2, 2, 3, 3, 4, 4, 1}, edge_refs[] = {1, 2, 3, 4};
 *     double metric[4 * 3];
 *     for (int i = 0; i < 4; ++i) {                    // h = 0.05 along x, 0.2 along y
 *       metric[3 * i] = 1 / (0.05 * 0.05); metric[3 * i + 1] = 0; metric[3 * i + 2] = 1 / (0.2 * 0.2);
 *     }
 *     ablmg_t* h = ablmg_create();
 *     if (!h) return 1;
 *     int rc = ablmg_set_vertices(h, xy, NULL, 4);
 *     if (rc == ABLMG_OK) rc = ablmg_set_triangles(h, tri, NULL, 2, 1);
 *     if (rc == ABLMG_OK) rc = ablmg_set_edges(h, edges, edge_refs, 4, 1);
 *     if (rc == ABLMG_OK) rc = ablmg_set_metric(h, metric, 4);
 *     if (rc == ABLMG_OK) rc = ablmg_set_double(h, ABLMG_HGRAD, 1.3);
 *     if (rc == ABLMG_OK) rc = ablmg_remesh(h);
 *     if (rc != ABLMG_OK) {
 *       fprintf(stderr, "ablmg: %s\n", ablmg_last_error(h));
 *       ablmg_free(h);
 *       return 1;
 *     }
 *     int nv, nt, ne;
 *     ablmg_get_sizes(h, &nv, &nt, &ne);
 *     double* out_xy = malloc(sizeof(double) * 2 * nv);
 *     int* out_tri = malloc(sizeof(int) * 3 * nt);
 *     ablmg_get_vertices(h, out_xy, NULL, nv);
 *     ablmg_get_triangles(h, out_tri, NULL, nt, 0);  // 0-based this time
 *     ablmg_quality q;
 *     ablmg_get_quality(h, &q);
 *     printf("%d vertices, %d triangles, q mean %.3f, %.1f %% of edges in [1/sqrt2, sqrt2]\n",
 *            nv, nt, q.quality_mean, 100 * q.edge_in_sqrt2);
 *     free(out_xy);
 *     free(out_tri);
 *     ablmg_free(h);
 *     return 0;
 *   }
 *
 * A solver loop sets the new arrays (and the metric of its next solution) on the same handle
 * and calls ablmg_remesh again; every setter replaces what it sets and keeps the options.
 * Between the two, ablmg_transfer carries the solver's fields (P1, one value per vertex) from
 * the mesh the last ablmg_remesh read to its result:
 *
 *   double* u_new = malloc(sizeof(double) * nv);
 *   ablmg_transfer_stats s;
 *   rc = ablmg_transfer(h, u_old, 4, 1, ABLMG_TRANSFER_PROJECTION, u_new, nv, &s);
 *   // s.relative_mass_defect ~ 1e-15: the integral of u is kept
 */
#ifndef ABLMG_CAPI_ABLMG_H
#define ABLMG_CAPI_ABLMG_H

#ifdef __cplusplus
extern "C" {
#endif

#define ABLMG_VERSION_MAJOR 0
#define ABLMG_VERSION_MINOR 2
#define ABLMG_VERSION_PATCH 0

/** Return codes: ABLMG_OK or one of the negative errors. */
typedef enum ablmg_status {
  ABLMG_OK = 0,
  ABLMG_ERR_NULL = -1,         /**< a required pointer (handle, array, output) is NULL */
  ABLMG_ERR_ARGUMENT = -2,     /**< a count, base, option id or option value is out of range */
  ABLMG_ERR_INPUT = -3,        /**< a value is bad: NaN/Inf coordinate, index out of range,
                                    non-SPD or non-finite metric, size <= 0, a metric asking
                                    for more than 50 000 000 nodes */
  ABLMG_ERR_INVALID_MESH = -4, /**< the input is not a valid mesh (inverted or overlapping
                                    triangles, open or pinched boundary, unused vertex, ...):
                                    messages start "ablmg_remesh: input: " */
  ABLMG_ERR_STATE = -5,        /**< called out of order: remesh before vertices, triangles,
                                    edges and metric are set (with matching counts), or a
                                    getter before a successful remesh */
  ABLMG_ERR_CAPACITY = -6,     /**< a getter's count is not the result's (ablmg_get_sizes) */
  ABLMG_ERR_MESHER = -7,       /**< the mesher failed on a valid input; the message says why */
  ABLMG_ERR_MEMORY = -8        /**< out of memory */
} ablmg_status;

/** Options set with ablmg_set_double / ablmg_set_int. */
typedef enum ablmg_option {
  ABLMG_HMIN = 1,   /**< double >= 0, default 0: smallest size h1, h2 of the clamped metric */
  ABLMG_HMAX = 2,   /**< double > hmin, default +infinity (HUGE_VAL): largest size */
  ABLMG_HGRAD = 3,  /**< double, default 1.3 (MMG's): size gradation beta > 1 after the clamp
                         (metric-space, adapt/gradation.hpp); <= 0 (MMG's -1) disables it;
                         (0, 1] is refused */
  ABLMG_SEED = 4,   /**< int >= 0, default 0: the placement's seed
                         (mesher::PlacementOptions::seed), the `--seed` of `ablmg remesh`:
                         0 places the nodes as the lattice and warm start put them; s > 0
                         first moves each interior node by a draw of (s, node) within 0.1
                         metric units, giving another mesh of the same statistics. The same
                         seed gives the same mesh */
  ABLMG_THREADS = 5, /**< int >= 0, default 0 (OpenMP's default): threads of the remesh; the
                         result does not depend on it. The caller's OpenMP setting is
                         restored when ablmg_remesh returns. */
  ABLMG_WARM_START = 6, /**< int, default 2 (auto): 1 seeds the placement with the input's
                         interior vertices, 0 starts from the lattice, 2 does the first when the
                         input already fits its metric (half its edges within 10 %), as
                         `ablmg remesh --warm-start auto|on|off` */
  ABLMG_METRIC_QUANTUM = 7 /**< double >= 0, default 0 (off): snap the metric to a grid of this
                         step first (log2 of its eigenvalues, its angle; adapt/metric_snap.hpp),
                         so that metrics differing by round-off, e.g. from 1 and 2 MPI ranks,
                         give the same mesh; 2^-8 changes sizes by < 0.07 %. `ablmg remesh
                         --metric-quantum Q` */
} ablmg_option;

/** Solution transfer methods (ablmg_transfer; adapt/transfer.hpp). */
typedef enum ablmg_transfer_method {
  ABLMG_TRANSFER_INTERPOLATION = 0, /**< the old field at each new vertex (located in the old
                                         mesh; outside it, at the closest boundary point):
                                         exact for linear fields, not conservative */
  ABLMG_TRANSFER_PROJECTION = 1,    /**< conservative L2 projection on the supermesh of the two
                                         meshes: keeps the integral to round-off, exact for
                                         linear fields; may overshoot the old field's range */
  ABLMG_TRANSFER_PROJECTION_BOUNDED = 2 /**< the projection clipped to the old field's
                                         [min, max], the clipped mass given back where there
                                         is room: in range and conservative */
} ablmg_transfer_method;

/** What a transfer did (ablmg_transfer). */
typedef struct ablmg_transfer_stats {
  long supermesh_pieces;        /**< non-empty old/new triangle intersections (projections) */
  double supermesh_area;        /**< their total area (= the domain's when both cover it) */
  long outside_vertices;        /**< new vertices outside the old mesh (interpolation) */
  int solver_iterations;        /**< conjugate-gradient iterations, largest over the fields */
  double relative_mass_defect;  /**< max over fields of |int u_new - int u_old| / int |u_old| */
  double seconds;               /**< wall time */
} ablmg_transfer_stats;

/** The opaque handle: input arrays, options, the last result and the last error message. */
typedef struct ablmg_handle ablmg_t;

/** Quality of the result in its metric (mesher/quality.hpp, paper §4.2): edge lengths l in the
 * metric (target 1; eq. 3 with the averaged tensor) and triangle quality
 * q = 4 sqrt(3) A_M / (l1² + l2² + l3²) in (0, 1] (1: equilateral in the metric). */
typedef struct ablmg_quality {
  int vertices, triangles, edges; /**< edges: unique edges of the mesh */
  int valid;                      /**< 1: Mesh2::validate() passed (always, for a result) */
  double edge_min, edge_mean, edge_max;
  double edge_in_sqrt2;    /**< fraction of edges with l in [1/sqrt2, sqrt2] */
  double edge_within_10;   /**< fraction with |l - 1| <= 0.1 */
  double edge_deviation[6];/**< fractions with eps = |l-1| <= 5 %, 5-10 %, ..., 20-25 %, > 25 % */
  double quality_min, quality_mean, quality_max;
  double quality_bins[5];  /**< fractions with q in [0, .2), [.2, .4), [.4, .6), [.6, .8), [.8, 1] */
  int clamped_metrics;     /**< input metrics changed by the [hmin, hmax] clamp */
  int graded_metrics;      /**< input metrics changed by the gradation */
  int repaired_triangles;  /**< triangles the connection repaired (few on smooth metrics) */
} ablmg_quality;

/** "0.2.0" (a static string). */
const char* ablmg_version(void);

/** A new handle with no mesh and the default options; NULL only when out of memory. */
ablmg_t* ablmg_create(void);
/** Frees the handle and everything it holds; NULL is allowed (no-op). */
void ablmg_free(ablmg_t* handle);
/** The message of the last failed call on this handle ("" after a success); owned by the
 * handle, valid until its next call. For a NULL handle, a static "null ablmg handle". */
const char* ablmg_last_error(const ablmg_t* handle);

/** n vertices: xy[2n] coordinates (finite), refs[n] or NULL (all 0). n >= 3. */
int ablmg_set_vertices(ablmg_t* handle, const double* xy, const int* refs, int n);
/** m triangles: tri[3m] vertex indices in [base, base + n), refs[m] or NULL. base is 0 or 1.
 * Needs the vertices set first (indices are checked against their count). m >= 1. */
int ablmg_set_triangles(ablmg_t* handle, const int* tri, const int* refs, int m, int base);
/** k boundary edges: edges[2k] vertex indices in [base, base + n), refs[k] or NULL (all 1). */
int ablmg_set_edges(ablmg_t* handle, const int* edges, const int* refs, int k, int base);
/** The metric at each of the n vertices: m[3n] = m11 m12 m22, symmetric positive definite. */
int ablmg_set_metric(ablmg_t* handle, const double* m, int n);
/** The metric as a size per vertex: h[n] > 0, M = I / h² (a medit .sol of type 1). */
int ablmg_set_sizes(ablmg_t* handle, const double* h, int n);
/** Sets a double option (ABLMG_HMIN, ABLMG_HMAX, ABLMG_HGRAD, ABLMG_METRIC_QUANTUM); checked
 * here and at remesh. */
int ablmg_set_double(ablmg_t* handle, ablmg_option option, double value);
/** Sets an integer option (ABLMG_SEED, ABLMG_THREADS). */
int ablmg_set_int(ablmg_t* handle, ablmg_option option, long long value);

/** Validates the input (the mesh as Mesh2::validate, the metric SPD and finite, hmin < hmax)
 * and remeshes. On success the result replaces the previous one; on failure the previous
 * result is dropped and the getters return ABLMG_ERR_STATE. The input stays set. */
int ablmg_remesh(ablmg_t* handle);

/** Sizes of the result: vertices, triangles, boundary edges (each pointer may be NULL). */
int ablmg_get_sizes(ablmg_t* handle, int* nvertices, int* ntriangles, int* nedges);
/** Copies the result's n vertices into xy[2n] (and their refs into refs[n] unless NULL);
 * n must be the result's vertex count. */
int ablmg_get_vertices(ablmg_t* handle, double* xy, int* refs, int n);
/** Its m counter-clockwise triangles, indices from `base` (0 or 1); refs[m] may be NULL. */
int ablmg_get_triangles(ablmg_t* handle, int* tri, int* refs, int m, int base);
/** Its k boundary edges (domain on the left), indices from `base`, with the input's refs. */
int ablmg_get_edges(ablmg_t* handle, int* edges, int* refs, int k, int base);
/** The metric at its n vertices (clamped, graded and interpolated): m[3n] = m11 m12 m22. */
int ablmg_get_metric(ablmg_t* handle, double* m, int n);
/** Its quality in that metric (and what the remesh changed); see ablmg_quality. */
int ablmg_get_quality(ablmg_t* handle, ablmg_quality* quality);

/** Transfers nfields P1 fields from the mesh the last successful ablmg_remesh read (its
 * n_old vertices, as set then: later setters do not change it) to that remesh's result (its
 * n_new vertices, ablmg_get_sizes). Field-major arrays, as a Fortran u(n, nfields):
 *   old_fields double[nfields * n_old]   field f at input vertex i: old_fields[f * n_old + i]
 *   new_fields double[nfields * n_new]   (written) field f at result vertex i: new_fields[f * n_new + i]
 * method: an ablmg_transfer_method (passed as an int). stats may be NULL. Errors:
 * ABLMG_ERR_STATE before a successful remesh; ABLMG_ERR_ARGUMENT for n_old not the input's
 * vertex count, nfields < 1 or a method out of range; ABLMG_ERR_CAPACITY for n_new not the
 * result's; ABLMG_ERR_INPUT for a value that is not finite (naming field and vertex). On an
 * error new_fields is left as it was. Deterministic for any thread count. */
int ablmg_transfer(ablmg_t* handle, const double* old_fields, int n_old, int nfields, int method,
                   double* new_fields, int n_new, ablmg_transfer_stats* stats);

#ifdef __cplusplus
}
#endif

#endif /* ABLMG_CAPI_ABLMG_H */
