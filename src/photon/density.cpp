// Radiance and irradiance estimates, and the precomputed irradiance cache.
#include "photon/density.h"
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include "core/rng.h"

namespace caustica {

namespace {
// The precomputed irradiance's sites: a 1 / stride share of the global map's photons, chosen by
// a hash of their index (independently of where they lie).
bool is_site(uint32_t index, size_t stride) { return hash_seed(index, 0x73697465) % stride == 0; }  // "site"

struct SiteMoments {
  Vec3 offset_sum{0.0f};
  float flux = 0, r2_disc = 0;
};

// Shared by both estimates: gathers, filters and sums weight(photon) * power / area.
// With levels > 0, level_sums[l] also receives the estimate of the narrower bounce window
// min_bounces..max_bounces - l, for l < levels (level 0 is the returned estimate). `map`
// holds `share` of the photons (the precomputed irradiance's estimates leave out its sites),
// so the estimate is scaled by 1 / share. `moments` receives the luminance of the photons
// over the whole (unshrunk) disc and their luminance-weighted offsets from p.
template <class Weight>
Color gather(const PhotonMap& map, const Vec3& p, const Vec3& n_side, const EstimateSettings& s,
             std::vector<Neighbour>& scratch, EstimateInfo* info, Weight weight_of, Color* level_sums = nullptr,
             int levels = 0, float share = 1.0f, SiteMoments* moments = nullptr) {
  for (int l = 0; l < levels; ++l) level_sums[l] = Color(0.0f);
  const size_t found = s.fixed_radius ? map.radius_query(p, s.max_radius, scratch)
                                      : map.knn(p, s.k, s.max_radius, scratch);
  if (info) *info = EstimateInfo{0, 0.0f, found};
  if (found == 0) return Color(0.0f);
  // Fewer than k photons within max_radius: the disc is the whole search radius.
  const float r2_disc = s.fixed_radius || found < s.k ? s.max_radius * s.max_radius : scratch.back().dist2;
  // Progressive passes shrink the disc by a factor; the photons beyond it drop out.
  const bool shrunk = s.radius2_scale < 1.0f;
  const float r2 = shrunk ? r2_disc * s.radius2_scale : r2_disc;
  if (!(r2 > 0.0f)) return Color(0.0f);
  const float r = std::sqrt(r2);
  Color sum(0.0f);
  size_t used = 0;
  // A disc through the k-th nearest photon holds k - 1 photons inside it: counting the k-th as
  // well reads k / (k - 1) too high (11 % at k = 10, 2 % at k = 50). (k = 1 keeps its photon.)
  const size_t counted = !s.fixed_radius && found == s.k && s.k > 1 ? found - 1 : found;
  if (moments) *moments = SiteMoments{Vec3(0.0f), 0.0f, r2_disc};
  for (size_t i = 0; i < counted; ++i) {
    const Neighbour& nb = scratch[i];
    const bool outside = shrunk && nb.dist2 >= r2;
    if (outside && !moments) continue;
    const Photon& ph = map[nb.index];
    if (int(ph.bounces) < s.min_bounces || int(ph.bounces) > s.max_bounces) continue;
    const Vec3 wi = ph.incoming_dir();
    if (glm::dot(wi, n_side) <= 0.0f || !normals_agree(ph.surface_normal(), n_side)) continue;
    Color c = map.power(nb.index) * weight_of(wi);
    if (moments) {  // over the whole (unshrunk) disc
      moments->offset_sum += luminance(c) * (ph.position - p);
      moments->flux += luminance(c);
    }
    if (outside) continue;
    if (s.cone_filter) c *= 1.0f - std::sqrt(nb.dist2) / (s.cone_k * r);
    sum += c;
    ++used;
    for (int l = 1; l < std::min(levels, s.max_bounces - int(ph.bounces) + 1); ++l) level_sums[l] += c;
  }
  float area = kPi * r2;
  if (s.cone_filter) area *= 1.0f - 2.0f / (3.0f * s.cone_k);
  area *= share;
  if (info) *info = EstimateInfo{used, r, found};
  for (int l = 1; l < levels; ++l) level_sums[l] /= area;
  if (levels > 0) level_sums[0] = sum / area;
  return sum / area;
}
}  // namespace

Color radiance_estimate(const PhotonMap& map, const SurfaceHit& hit, const Vec3& wo, const EstimateSettings& s,
                        std::vector<Neighbour>& scratch, EstimateInfo* info) {
  const Vec3 n_side = glm::dot(wo, hit.n) >= 0 ? hit.n : -hit.n;
  const Vec3 wo_l = hit.frame.to_local(wo);
  const Bsdf& m = *hit.material;
  return gather(map, hit.p, n_side, s, scratch, info,
                [&](const Vec3& wi) { return m.eval(wo_l, hit.frame.to_local(wi), hit.sp); });
}

Color irradiance_estimate(const PhotonMap& map, const Vec3& p, const Vec3& n_side, const EstimateSettings& s,
                          std::vector<Neighbour>& scratch, EstimateInfo* info) {
  return gather(map, p, n_side, s, scratch, info, [](const Vec3&) { return Color(1.0f); });
}

double progressive_radius2_scale(int pass, double alpha) {
  double scale = 1.0;
  for (int j = 1; j <= pass; ++j) scale *= (double(j) + alpha) / double(j + 1);
  return scale;
}

void IrradianceCache::build(const PhotonMap& global, size_t stride, const EstimateSettings& s, int levels) {
  settings_ = s;
  levels_ = std::max(1, levels);
  // The sites, and the other photons, which estimate the irradiance at them: a site's own
  // photon would count at the centre of its disc however far progressive passes shrink it,
  // and a photon-placed site could not be told from the photons it is nearest to (a lookup's
  // nearest site lies where sites, and so photons, are sparse). Chosen by a hash of the index,
  // the sites are independent of the others: the cache reads a uniform density without bias
  // at any disc size (tests/photon/density_test.cpp).
  stride = std::max<size_t>(2, stride);
  std::vector<uint32_t> sites;
  std::vector<Photon> rest;
  rest.reserve(global.size() - global.size() / stride);
  for (uint32_t i = 0; i < uint32_t(global.size()); ++i) {
    if (is_site(i, stride)) sites.push_back(i);
    else rest.push_back(global[i]);
  }
  const size_t n = sites.size();
  const float share = float(rest.size()) / float(std::max<size_t>(global.size(), 1));
  PhotonMap others;
  others.build(std::move(rest), global.flux_scale());
  const size_t L = size_t(levels_);
  std::vector<Color> irradiance(n * L);
  std::vector<Vec3> gradient(n);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 256), [&](const tbb::blocked_range<size_t>& range) {
    std::vector<Neighbour> scratch;
    for (size_t i = range.begin(); i != range.end(); ++i) {
      const Photon& ph = global[sites[i]];
      const Vec3 normal = ph.surface_normal();
      SiteMoments m;
      gather(others, ph.position, normal, s, scratch, nullptr, [](const Vec3&) { return Color(1.0f); },
             &irradiance[i * L], levels_, share, &m);
      // The irradiance's gradient over itself, in the surface's plane, from the whole disc
      // (however far a progressive pass shrinks the estimate's): for a density rho + g.v over
      // a disc of radius r, the photons' offsets v sum to g pi r^4 / 4 (and rho pi r^2), so
      // g / rho is 4 / r^2 times their flux-weighted mean offset.
      if (m.flux > 0 && m.r2_disc > 0) {
        const Vec3 g = 4.0f * m.offset_sum / (m.flux * m.r2_disc);
        gradient[i] = g - glm::dot(g, normal) * normal;
      }
    }
  });
  double mean = 0;
  for (size_t i = 0; i < n; ++i) mean += max_component(irradiance[i * L]);
  mean = n > 0 ? mean / double(n) : 1.0;
  if (!(mean > 0)) mean = 1.0;
  std::vector<Photon> points(n);
  for (size_t i = 0; i < n; ++i) {
    const Photon& ph = global[sites[i]];
    const Vec3 normal = ph.surface_normal();
    points[i] = Photon::make(ph.position, irradiance[i * L] / float(mean), normal, normal, 0);
  }
  std::vector<uint32_t> order;
  points_.build(std::move(points), float(mean), kLeafSize, &order);
  std::vector<Vec3> positions(n), normals(n);
  for (size_t i = 0; i < n; ++i) {
    positions[i] = points_[uint32_t(i)].position;
    normals[i] = points_[uint32_t(i)].surface_normal();
  }
  grid_.build(positions, normals);
  gradient_.resize(n);
  for (size_t i = 0; i < n; ++i) gradient_[i] = gradient[size_t(order[i])];
  // The narrower windows' irradiance, in the map's (Morton) order.
  narrower_.assign(n * (L - 1), Color(0.0f));
  for (size_t i = 0; i < n; ++i) {
    for (size_t l = 1; l < L; ++l) narrower_[i * (L - 1) + l - 1] = irradiance[size_t(order[i]) * L + l];
  }
}

int IrradianceCache::level_for(const EstimateSettings& s) const {
  const int l = settings_.max_bounces - s.max_bounces;
  return s.min_bounces == settings_.min_bounces && l >= 0 && l < levels_ ? l : -1;
}

bool IrradianceCache::lookup(const Vec3& p, const Vec3& n_side, float max_radius, int level, Color& E,
                             std::vector<Neighbour>& scratch) const {
  // Approximate nearest (within twice the distance) is as good here and cheaper.
  const int64_t g = grid_.nearest(p, max_radius, [&](const Vec3& n) { return normals_agree(n, n_side); });
  if (g >= 0) {
    E = corrected(size_t(g), p, level);
    return true;
  }
  if (g == PointGrid::kNone) return false;
  // The nearest point nearly always lies on the same surface; look further only when not.
  for (size_t k : {size_t(1), size_t(8)}) {
    points_.knn(p, k, max_radius, scratch, 1.0f);
    for (const Neighbour& nb : scratch) {
      if (normals_agree(points_[nb.index].surface_normal(), n_side)) {
        E = corrected(nb.index, p, level);
        return true;
      }
    }
    if (scratch.size() < k) break;  // nothing more within max_radius
  }
  return false;
}

}  // namespace caustica
