/* A solver's loop on ablmg's C interface (ablmg.h), from an installed package: start from the
 * square [0,1]² as two triangles, remesh to a metric given by a function (a layer along the
 * diagonal, sharper each cycle) sampled at the current vertices, three times, feeding each
 * result back. Each result must be valid with the four boundary refs, meet the quality
 * figures and grow, and the linear field u = 1 + x + 2y, carried over by the conservative
 * transfer (ablmg_transfer), must be reproduced with its integral kept; a hostile input (a NaN coordinate) must give ABLMG_ERR_INPUT and leave the
 * handle usable. Exit 0 and one line per cycle, or 1 and the failed check. */
#include <ablmg/capi/ablmg.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

/* The metric at (x, y): size h1 across the diagonal x = y (from `width` on it to 0.1), 0.1 along. */
static void layer_metric(double x, double y, double width, double* m) {
  const double d = fabs(x - y) / sqrt(2.0), h1 = fmin(0.1, width + 0.5 * d), h2 = 0.1;
  const double c = sqrt(0.5), l1 = 1 / (h1 * h1), l2 = 1 / (h2 * h2);
  /* M = l1 n nᵀ + l2 t tᵀ, n = (c, -c) across the diagonal, t = (c, c) along it. */
  m[0] = l1 * c * c + l2 * c * c;
  m[1] = -l1 * c * c + l2 * c * c;
  m[2] = l1 * c * c + l2 * c * c;
}

static int fail(ablmg_t* h, const char* what) {
  fprintf(stderr, "remesh_c: %s: %s\n", what, h ? ablmg_last_error(h) : "");
  ablmg_free(h);
  return 1;
}

int main(void) {
  int nv = 4, nt = 2, ne = 4, previous = 4;
  double* xy = malloc(sizeof(double) * 8);
  int* tri = malloc(sizeof(int) * 6);
  int* edges = malloc(sizeof(int) * 8);
  int* refs = malloc(sizeof(int) * 4);
  const double square[8] = {0, 0, 1, 0, 1, 1, 0, 1};
  const int square_tri[6] = {0, 1, 2, 0, 2, 3}, square_edges[8] = {0, 1, 1, 2, 2, 3, 3, 0};
  for (int i = 0; i < 8; ++i) xy[i] = square[i], edges[i] = square_edges[i];
  for (int i = 0; i < 6; ++i) tri[i] = square_tri[i];
  for (int i = 0; i < 4; ++i) refs[i] = i + 1;
  ablmg_t* h = ablmg_create();
  if (!h) return fail(NULL, "ablmg_create");
  for (int cycle = 1; cycle <= 3; ++cycle) {
    const double width = 0.04 / pow(2.0, cycle);
    double* metric = malloc(sizeof(double) * 3 * (size_t)nv);
    for (int i = 0; i < nv; ++i) layer_metric(xy[2 * i], xy[2 * i + 1], width, metric + 3 * i);
    int rc = ablmg_set_vertices(h, xy, NULL, nv);
    if (rc == ABLMG_OK) rc = ablmg_set_triangles(h, tri, NULL, nt, 0);
    if (rc == ABLMG_OK) rc = ablmg_set_edges(h, edges, refs, ne, 0);
    if (rc == ABLMG_OK) rc = ablmg_set_metric(h, metric, nv);
    if (rc == ABLMG_OK) rc = ablmg_set_double(h, ABLMG_HMIN, 1e-3);
    if (rc == ABLMG_OK) rc = ablmg_remesh(h);
    free(metric);
    if (rc != ABLMG_OK) return fail(h, "remesh");
    const int nv_old = nv;
    double* u_old = malloc(sizeof(double) * (size_t)nv_old);
    for (int i = 0; i < nv_old; ++i) u_old[i] = 1 + xy[2 * i] + 2 * xy[2 * i + 1];
    if (ablmg_get_sizes(h, &nv, &nt, &ne) != ABLMG_OK) return fail(h, "ablmg_get_sizes");
    xy = realloc(xy, sizeof(double) * 2 * (size_t)nv);
    tri = realloc(tri, sizeof(int) * 3 * (size_t)nt);
    edges = realloc(edges, sizeof(int) * 2 * (size_t)ne);
    refs = realloc(refs, sizeof(int) * (size_t)ne);
    if (ablmg_get_vertices(h, xy, NULL, nv) != ABLMG_OK || ablmg_get_triangles(h, tri, NULL, nt, 0) != ABLMG_OK ||
        ablmg_get_edges(h, edges, refs, ne, 0) != ABLMG_OK)
      return fail(h, "getters");
    double* u_new = malloc(sizeof(double) * (size_t)nv);
    ablmg_transfer_stats ts;
    rc = ablmg_transfer(h, u_old, nv_old, 1, ABLMG_TRANSFER_PROJECTION, u_new, nv, &ts);
    double worst = 0;
    for (int i = 0; rc == ABLMG_OK && i < nv; ++i)
      worst = fmax(worst, fabs(u_new[i] - (1 + xy[2 * i] + 2 * xy[2 * i + 1])));
    free(u_old);
    free(u_new);
    if (rc != ABLMG_OK) return fail(h, "ablmg_transfer");
    if (!(worst < 1e-10 && ts.relative_mass_defect < 1e-12 && fabs(ts.supermesh_area - 1) < 1e-12))
      return fail(h, "the transfer did not reproduce u = 1 + x + 2y with its integral");
    ablmg_quality q;
    if (ablmg_get_quality(h, &q) != ABLMG_OK) return fail(h, "ablmg_get_quality");
    int seen[5] = {0, 0, 0, 0, 0};
    for (int e = 0; e < ne; ++e)
      if (refs[e] >= 1 && refs[e] <= 4) seen[refs[e]] = 1;
    printf("cycle %d: %d vertices, %d triangles, q min %.3f mean %.3f, %.1f %% of edges in [1/sqrt2, sqrt2]\n", cycle,
           nv, nt, q.quality_min, q.quality_mean, 100 * q.edge_in_sqrt2);
    if (!q.valid) return fail(h, "invalid mesh");
    if (!(seen[1] && seen[2] && seen[3] && seen[4])) return fail(h, "boundary refs lost");
    if (!(q.quality_min > 0.3 && q.quality_mean > 0.9)) return fail(h, "quality below q min 0.3, mean 0.9");
    if (!(q.edge_in_sqrt2 > 0.95)) return fail(h, "fewer than 95 % of edges in [1/sqrt2, sqrt2]");
    /* From the second cycle on (the first samples the metric at the four corners only). */
    if (cycle >= 3 && !(nv > previous)) return fail(h, "the vertex count did not grow as the layer thinned");
    previous = nv;
  }
  /* A NaN coordinate: a clean error code and message, and the handle still works. */
  xy[3] = NAN;
  if (ablmg_set_vertices(h, xy, NULL, nv) != ABLMG_ERR_INPUT) return fail(h, "NaN coordinate accepted");
  printf("NaN coordinate refused: %s\n", ablmg_last_error(h));
  ablmg_free(h);
  free(xy);
  free(tri);
  free(edges);
  free(refs);
  return 0;
}
