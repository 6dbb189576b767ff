// libFuzzer target: capi/ablmg.h driven with arbitrary arrays and options. The input bytes
// are read as: counts n, m, k (small: the arrays come from the rest), index bases, option
// values, then doubles and ints for the arrays. Whatever they are, every call must return
// ABLMG_OK or one of the negative codes with a non-empty message, never crash or throw; a
// successful remesh must give a valid mesh (ablmg_quality.valid) whose getters agree with
// ablmg_get_sizes, and a transfer of arbitrary fields to it (any method byte) either fails
// with a code or gives finite values, a constant field staying constant.
#include "ablmg/capi/ablmg.h"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <vector>

namespace {

struct Reader {
  const std::uint8_t* p;
  std::size_t left;
  template <class T>
  T next() {
    T v{};
    if (left >= sizeof(T)) {
      std::memcpy(&v, p, sizeof(T));
      p += sizeof(T);
      left -= sizeof(T);
    }
    return v;
  }
};

void expectCode(ablmg_t* h, int rc) {
  if (rc == ABLMG_OK) return;
  if (rc > 0 || rc < ABLMG_ERR_MEMORY || !ablmg_last_error(h)[0]) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Reader r{data, size};
  const int n = r.next<std::uint8_t>() % 40, m = r.next<std::uint8_t>() % 60, k = r.next<std::uint8_t>() % 40;
  const int base = r.next<std::uint8_t>() % 3;  // 2: refused
  const std::uint8_t flags = r.next<std::uint8_t>();
  std::vector<double> xy(2 * std::size_t(n) + 1), metric(3 * std::size_t(n) + 1);
  std::vector<int> tri(3 * std::size_t(m) + 1), edges(2 * std::size_t(k) + 1), refs(std::size_t(k) + 1);
  // Coordinates on a small grid (so that meshes can be valid) or raw doubles (NaN, Inf, ...).
  for (auto& x : xy) x = (flags & 1) ? r.next<double>() : r.next<std::uint8_t>() % 8 * 0.25;
  for (auto& v : tri) v = (flags & 2) ? r.next<int>() : r.next<std::uint8_t>() % (n + 1);
  for (auto& v : edges) v = (flags & 2) ? r.next<int>() : r.next<std::uint8_t>() % (n + 1);
  for (auto& v : refs) v = r.next<std::uint8_t>();
  for (std::size_t i = 0; i < metric.size(); ++i)
    metric[i] = (flags & 4) ? r.next<double>() : (i % 3 == 1 ? 0.0 : 4.0 + r.next<std::uint8_t>() % 64);
  ablmg_t* h = ablmg_create();
  if (!h) return 0;
  expectCode(h, ablmg_set_vertices(h, xy.data(), nullptr, n));
  expectCode(h, ablmg_set_triangles(h, tri.data(), nullptr, m, base));
  expectCode(h, ablmg_set_edges(h, edges.data(), (flags & 8) ? refs.data() : nullptr, k, base));
  if (flags & 16)
    expectCode(h, ablmg_set_sizes(h, metric.data(), n));
  else
    expectCode(h, ablmg_set_metric(h, metric.data(), n));
  if (flags & 32) {
    expectCode(h, ablmg_set_double(h, ABLMG_HMIN, r.next<double>()));
    expectCode(h, ablmg_set_double(h, ABLMG_HMAX, r.next<double>()));
    expectCode(h, ablmg_set_double(h, ABLMG_HGRAD, r.next<double>()));
    expectCode(h, ablmg_set_int(h, ABLMG_SEED, r.next<std::int8_t>()));
    expectCode(h, ablmg_set_int(h, ABLMG_WARM_START, r.next<std::int8_t>() % 4));
    expectCode(h, ablmg_set_double(h, ablmg_option(r.next<std::int8_t>()), 1.0));
  }
  expectCode(h, ablmg_set_int(h, ABLMG_THREADS, 1));
  const int rc = ablmg_remesh(h);
  expectCode(h, rc);
  if (rc == ABLMG_OK) {
    int nv = 0, nt = 0, ne = 0;
    if (ablmg_get_sizes(h, &nv, &nt, &ne) != ABLMG_OK) std::abort();
    std::vector<double> oxy(2 * std::size_t(nv)), om(3 * std::size_t(nv));
    std::vector<int> otri(3 * std::size_t(nt)), oedges(2 * std::size_t(ne));
    ablmg_quality q;
    if (ablmg_get_vertices(h, oxy.data(), nullptr, nv) || ablmg_get_triangles(h, otri.data(), nullptr, nt, 1) ||
        ablmg_get_edges(h, oedges.data(), nullptr, ne, 0) || ablmg_get_metric(h, om.data(), nv) ||
        ablmg_get_quality(h, &q) || !q.valid || q.vertices != nv || q.triangles != nt)
      std::abort();
    if (ablmg_get_vertices(h, oxy.data(), nullptr, nv + 1) != ABLMG_ERR_CAPACITY) std::abort();
    // Two fields: arbitrary doubles (NaN, Inf, ...) or, with flags & 64, the constant 1.5.
    std::vector<double> fields(2 * std::size_t(n)), out(2 * std::size_t(nv));
    for (auto& u : fields) u = (flags & 64) ? 1.5 : r.next<double>();
    const int method = r.next<std::int8_t>() % 4;  // 3 and negatives: refused
    const int trc = ablmg_transfer(h, fields.data(), n, 2, method, out.data(), nv, nullptr);
    expectCode(h, trc);
    if (trc == ABLMG_OK)
      for (double u : out)
        if (!std::isfinite(u) || ((flags & 64) && std::abs(u - 1.5) > 1e-9)) std::abort();
  }
  ablmg_free(h);
  return 0;
}
