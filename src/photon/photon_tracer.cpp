// Photon tracing in parallel over fixed chunks of photon indices, merged in index order.
#include "photon/photon_tracer.h"
#include <algorithm>
#include <chrono>
#include <unordered_map>
#include <tbb/parallel_for.h>
#include "core/error.h"
#include "core/memory.h"
#include "core/sampler.h"
#include "photon/gather.h"
#include "photon/volume_map.h"

namespace caustica {
namespace {

constexpr uint64_t kChunk = 4096;  // emitted photons per chunk
constexpr uint64_t kCausticShare = 10;  // caustic emission at most this times the global's
constexpr double kMinVolumeCausticShare = 0.1;  // (caustic_cap)

struct PendingPhoton {
  Vec3 position;
  Color flux;  // before division by the number emitted
  Vec3 incoming, normal;
  int bounces;
  uint16_t volume_tag = 0;  // a volume photon's medium and caustic-path mark (volume_photon_tag)
};

// A photon leaves an area light offset from its surface; a point light has no surface.
Ray emission_ray(const Vec3& origin, const Vec3& normal, const Vec3& dir) {
  return glm::dot(normal, normal) > 0 ? spawn_ray(origin, normal, dir) : Ray{origin, dir};
}

struct Aim {
  Vec3 centre;
  float radius;
};

class Emitter {
 public:
  Emitter(const Scene& scene, bool caustic, const PhotonPassSettings& s)
      : scene_(scene), caustic_(caustic), scene_radius_(0.5f * glm::length(scene.bounds().extent())) {
    for (const ObjectInfo& o : scene.objects) {
      const Bsdf& m = *scene.materials[o.material];
      // Not at surfaces that scatter nothing (Mitsuba's null): photons pass through them.
      if (m.flags() == 0) continue;
      const bool gather = is_gather_surface(m, s.glossy_threshold);
      // A gather surface is a target for its delta lobe (plastic's coat) only.
      if (gather ? m.has(kBsdfSpecular) : is_caustic_surface(m, s.caustic_threshold)) targets_.push_back({o.centre, o.radius});
    }
    // The medium each light's photons start in: a point light's where it is, an environment's
    // outside all, an area light's on the side it emits to where a grid of its points agree,
    // else (a light that crosses a medium's bounds) each photon's own (kPerPhoton).
    if (scene.has_media()) {
      for (const auto& light : scene.lights) {
        int32_t medium = scene.outside_medium();
        if (!light->is_infinite()) {
          constexpr int kGrid = 8;
          for (int i = 0; i < kGrid * kGrid && medium != kPerPhoton; ++i) {
            const LightPoint o = light->sample_origin(Vec2((float(i % kGrid) + 0.5f) / kGrid, (float(i / kGrid) + 0.5f) / kGrid));
            const bool surface = glm::dot(o.n, o.n) > 0.0f;
            const Vec3 dir = surface ? o.n : glm::normalize(Vec3(0.267f, 0.535f, 0.802f));
            const int32_t here = scene.medium_at(surface ? offset_origin(o.p, o.n, dir) : o.p, dir);
            medium = i == 0 || here == medium ? here : kPerPhoton;
            if (!surface) break;  // (a point)
          }
        }
        light_medium_.emplace(light.get(), medium);
      }
    }
  }
  bool has_targets() const { return !targets_.empty(); }

  // Returns false when the sampled photon carries no flux.
  bool emit(Rng& rng, Ray& ray, Color& flux, int32_t& medium) const {
    float pmf;
    const Light* light = scene_.sample_photon_light(rng.next_float(), pmf);
    if (!light || pmf <= 0) return false;
    if (!light_medium_.empty()) medium = light_medium_.at(light);
    const Vec2 u_pos(rng.next_float(), rng.next_float());
    const Vec2 u_dir(rng.next_float(), rng.next_float());
    if (!emit_from(light, pmf, u_pos, u_dir, rng, ray, flux)) return false;
    if (medium == kPerPhoton) medium = scene_.medium_at(ray.origin, ray.dir);
    return true;
  }

 private:
  static constexpr int32_t kPerPhoton = -2;  // a light_medium_ entry: the medium where each photon starts

  // A photon from `light` (chosen with probability pmf): its ray and flux.
  bool emit_from(const Light* light, float pmf, const Vec2& u_pos, const Vec2& u_dir, Rng& rng, Ray& ray,
                 Color& flux) const {
    if (!caustic_) {
      const EmittedPhoton e = light->sample_emission(u_pos, u_dir);
      if (is_black(e.flux)) return false;  // a black texel of a textured light
      flux = e.flux / pmf;
      ray = emission_ray(e.origin, e.normal, e.dir);
      return true;
    }
    const size_t j = std::min(targets_.size() - 1, size_t(rng.next_float() * targets_.size()));
    if (light->is_infinite()) {
      // A direction from the light, then a point on the disc that one target's bounding
      // sphere casts across it; the density is the mixture over all targets' discs.
      Vec3 dir;
      Color value;
      if (!light->sample_travel(u_dir, dir, value)) return false;
      const Vec3 p = point_on_disc(targets_[j].centre, dir, targets_[j].radius, u_pos);
      float pdf_pos = 0;
      for (const Aim& a : targets_) pdf_pos += disc_pdf(p, dir, a);
      pdf_pos /= float(targets_.size());
      if (pdf_pos <= 0 || is_black(value)) return false;
      flux = value / (pdf_pos * pmf);
      ray = Ray{p - dir * (2.0f * scene_radius_), dir};
      return true;
    }
    // Aim at one specular object's bounding sphere, chosen uniformly; the direction density
    // is the mixture over all objects whose cone contains the direction.
    const LightPoint origin = light->sample_origin(u_pos);
    const Vec3 dir = sample_towards(origin.p, targets_[j], u_dir);
    float pdf_dir = 0;
    for (const Aim& a : targets_) pdf_dir += cone_pdf(origin.p, a, dir);
    pdf_dir /= float(targets_.size());
    const Color intensity = light->emitted_towards(origin, dir);
    if (pdf_dir <= 0 || is_black(intensity)) return false;
    flux = intensity / (origin.pdf * pdf_dir * pmf);
    ray = emission_ray(origin.p, origin.n, dir);
    return true;
  }

  // The density of a point on the disc that sphere `a` casts across direction dir.
  static float disc_pdf(const Vec3& p, const Vec3& dir, const Aim& a) {
    const Vec3 d = p - a.centre;
    const float along = glm::dot(d, dir);
    const float off2 = glm::dot(d, d) - along * along;
    return off2 <= a.radius * a.radius ? 1.0f / (kPi * a.radius * a.radius) : 0.0f;
  }

  static bool inside(const Vec3& o, const Aim& a, float& d, float& cos_max) {
    d = glm::length(a.centre - o);
    if (d <= a.radius * 1.0001f) return true;
    cos_max = std::sqrt(std::max(0.0f, 1.0f - (a.radius * a.radius) / (d * d)));
    return false;
  }
  static Vec3 sample_towards(const Vec3& o, const Aim& a, const Vec2& u) {
    float d, cos_max;
    if (inside(o, a, d, cos_max)) return sample_uniform_sphere(u);
    return Frame((a.centre - o) / d).to_world(sample_uniform_cone(u, cos_max));
  }
  static float cone_pdf(const Vec3& o, const Aim& a, const Vec3& dir) {
    float d, cos_max;
    if (inside(o, a, d, cos_max)) return uniform_sphere_pdf();
    if (glm::dot(dir, (a.centre - o) / d) < cos_max) return 0.0f;
    return uniform_cone_pdf(cos_max);
  }

  const Scene& scene_;
  bool caustic_;
  float scene_radius_;
  std::vector<Aim> targets_;
  std::unordered_map<const Light*, int32_t> light_medium_;
};

// Follows one photon; appends what it stores to `out` (surfaces) and `volume` (scattering
// points in media) and counts its rays in `rays`. `medium`: the one the photon starts in.
// Caustic photons store L S+ D at surfaces and L S+ V in media (their first scattering point
// there, where they end); global photons store every scattering point, those of L S+ V paths
// marked (VolumePhoton::caustic_path) so that an estimate beside a volume caustic map skips them.
void trace_photon(const Scene& scene, Ray ray, Color flux, int32_t medium, bool caustic, const PhotonPassSettings& s,
                  Sampler& sampler, std::vector<PendingPhoton>& out, std::vector<PendingPhoton>& volume,
                  uint64_t& rays) {
  Rng& rng = sampler.rng;
  const int max_depth = s.max_depth;
  const bool media = scene.has_media();
  const int hero = media ? std::min(int(rng.next_float() * 3.0f), 2) : 0;
  Color beta = flux, r(1.0f);  // the throughput is hero_throughput(beta, r)
  int specular_bounces = 0;
  bool specular_path = true;  // every bounce so far on a caustic surface (no diffuse, no medium)
  // (Bounded: a photon crossing boundaries without end stops.)
  int crossings = 0;
  for (int depth = 0; depth < max_depth;) {
    SurfaceHit hit;
    ++rays;
    const bool found = scene.intersect(ray, hit);
    if (medium >= 0) {
      const Medium& med = *scene.media[size_t(medium)];
      const MediumEvent event = med.sample(ray, found ? hit.t : kInfinity, hero, sampler);
      if (!take_medium_event(event, hero, beta, r)) return;
      if (event.scattered) {
        const Vec3 p = ray.at(event.t), wo = -ray.dir;
        const bool caustic_path = specular_path && specular_bounces > 0;
        if (caustic) {
          if (caustic_path) volume.push_back({p, hero_throughput(beta, r), wo, Vec3(0.0f), depth, volume_photon_tag(medium, true)});
          return;
        }
        // (Not the photons straight from a light, unless asked: single scattering is the eye's
        // shadow rays'.)
        if (depth > 0 || s.volume_direct) volume.push_back({p, hero_throughput(beta, r), wo, Vec3(0.0f), depth, volume_photon_tag(medium, caustic_path)});
        specular_path = false;
        // Russian roulette by the scattering albedo (the weight's ratio to the hero density).
        const float survive = std::min(1.0f, max_component(event.weight) / event.pdf[hero]);
        if (!(survive > 0.0f) || rng.next_float() >= survive) return;
        beta /= survive;
        Vec3 wi;
        if (!(med.phase().sample(wo, Vec2(rng.next_float(), rng.next_float()), wi) > 0.0f)) return;
        ray = Ray{p, wi, kInfinity};
        ++depth;
        continue;
      }
    }
    if (!found) return;
    if (Scene::is_medium_boundary(hit)) {  // not a bounce: the photon goes on in the other medium
      if (++crossings > 256) return;
      Scene::cross(hit, ray, medium);
      continue;
    }
    const Vec3 wo = -ray.dir;
    const Vec3 wo_l = hit.frame.to_local(wo);
    const Bsdf& m = *hit.material;
    const bool gather = is_gather_surface(m, s.glossy_threshold);
    if (gather) {
      const Vec3 n_side = wo_l.z >= 0 ? hit.n : -hit.n;
      if (caustic) {
        if (specular_bounces > 0 && !s.caustic_volume_only) out.push_back({hit.p, hero_throughput(beta, r), wo, n_side, depth});
        // Past a gather surface the path is not L S+ V (as for global photons, which mark no
        // volume photon after one as a caustic path).
        specular_path = false;
        // The caustic map keeps only L S+ D: the photon goes on only along a delta lobe of this
        // surface (plastic's coat), which is not part of the estimate stored here.
        BsdfSample coat;
        if (!delta_continuation(m, wo_l, hit.sp, [&] { return rng.next_float(); }, coat)) return;
        const Vec3 wi = hit.frame.to_world(coat.wi);
        beta *= coat.weight;
        ++specular_bounces;
        if (hit.leaks(wi) || is_black(beta)) return;
        if (hit.media) medium = hit.media->entered(wi, hit.n);
        ray = spawn_ray(hit.p, hit.n, wi);
        ++depth;
        continue;
      }
      out.push_back({hit.p, hero_throughput(beta, r), wo, n_side, depth});
    }
    // A soft surface (rough glossy, not a gather surface) ends a caustic photon: the light it
    // passes on to a gather point is the final gather's.
    if (caustic && !gather && !is_caustic_surface(m, s.caustic_threshold)) return;
    BsdfSample bs;
    const Vec2 u(rng.next_float(), rng.next_float());
    if (!m.sample(wo_l, u, rng.next_float(), bs, hit.sp)) return;
    const Vec3 wi = hit.frame.to_world(bs.wi);
    if (hit.leaks(wi)) return;
    if (media && bs.null()) {
      // In media a null lobe (straight through a thindielectric) is no bounce, as for the eye
      // (EyePath::transparent_nulls): the light straight through it is the shadow rays'.
      beta *= bs.weight;
      if (++crossings > 256 || is_black(beta)) return;
      if (hit.media) medium = hit.media->entered(wi, hit.n);
      ray = spawn_ray(hit.p, hit.n, wi);
      continue;
    }
    if (gather) {
      // Russian roulette with the sampled reflectance as survival probability (for a diffuse
      // surface its albedo, as in Jensen 2001, sec. 5.3): the flux keeps its magnitude.
      const float survive = std::min(1.0f, max_component(bs.weight));
      if (survive <= 0 || rng.next_float() >= survive) return;
      beta *= bs.weight / survive;
      specular_path = false;
    } else {
      beta *= bs.weight;
      ++specular_bounces;
      if (!is_caustic_surface(m, s.caustic_threshold)) specular_path = false;
      if (is_black(beta)) return;
    }
    if (hit.media) medium = hit.media->entered(wi, hit.n);
    ray = spawn_ray(hit.p, hit.n, wi);
    ++depth;
  }
}

// A stop asked for (Ctrl-C): a flag polled between chunks and photons, nothing ordered by it.
bool stop_requested(const PhotonPassSettings& s) { return s.cancel && s.cancel->load(std::memory_order_relaxed); }

// The records of chunks' photons in order, and the scale their flux is stored at: records hold
// flux / flux_scale, near 1, where half floats are most precise. The mean sums per chunk in
// parallel, then the chunk sums in order: the same for any thread count.
std::vector<Photon> normalise(const std::vector<std::vector<PendingPhoton>>& chunks, uint64_t emitted,
                              float& flux_scale, bool volume = false) {
  std::vector<size_t> at(chunks.size() + 1, 0);
  for (size_t c = 0; c < chunks.size(); ++c) at[c + 1] = at[c] + chunks[c].size();
  const size_t stored = at.back();
  std::vector<double> chunk_sum(chunks.size(), 0.0);
  tbb::parallel_for(size_t(0), chunks.size(), [&](size_t c) {
    for (const PendingPhoton& p : chunks[c]) chunk_sum[c] += max_component(p.flux);
  });
  double mean = 0;
  for (double x : chunk_sum) mean += x;
  mean = stored == 0 ? 1.0 : mean / double(stored);
  flux_scale = float(mean / double(std::max<uint64_t>(emitted, 1)));
  const float inv = mean > 0 ? float(1.0 / mean) : 0.0f;
  std::vector<Photon> result(stored);
  tbb::parallel_for(size_t(0), chunks.size(), [&](size_t c) {
    for (size_t k = 0; k < chunks[c].size(); ++k) {
      const PendingPhoton& p = chunks[c][k];
      result[at[c] + k] = Photon::make(p.position, p.flux * inv, p.incoming, p.normal, p.bounces);
      if (volume) result[at[c] + k].normal = p.volume_tag;
    }
  });
  return result;
}

// Emits photons until `wanted` are stored; returns them normalised by the number emitted.
// `caustic_cap`: for the caustic map, the most photons it may emit (0: no bound beyond the
// global cap).
// `rays_out`: the rays traced, trimmed photons included.
// The photons scattered in media go to volume_out, at volume_scale.
std::vector<Photon> run_map(const Scene& scene, const PhotonPassSettings& s, bool caustic, uint64_t caustic_cap,
                            uint64_t& emitted_out, uint64_t& rays_out, float& flux_scale,
                            std::vector<Photon>& volume_out, float& volume_scale, std::vector<std::string>& warnings) {
  std::vector<Photon> result;
  emitted_out = 0;
  const size_t wanted = caustic ? s.caustic_photons : s.global_photons;
  if (wanted == 0 || scene.lights.empty()) return result;
  const Emitter emitter(scene, caustic, s);
  if (caustic && !emitter.has_targets()) return result;
  // Cap on emission, so a scene that stores (almost) nothing still ends. Caustic photons that
  // mostly escape (mirrors that face away from every diffuse surface) stop at kCausticShare
  // times the global map's emission: past it they would cost a pass many times its eye part
  // for a map too sparse to matter.
  uint64_t cap = uint64_t(wanted) * (caustic ? 200 : 50) + 1000000;
  if (caustic && caustic_cap > 0) cap = std::min(cap, caustic_cap);
  const uint64_t stream = caustic ? 1 : 0;

  // Each chunk's stored photons, in photon-index order, trimmed to what the wanted count keeps.
  std::vector<std::vector<PendingPhoton>> chunks, volume_chunks;
  const bool media = scene.has_media();
  // Past the global map's count, volume photons alone (PhotonPassSettings::volume_min_divisor).
  const size_t wanted_volume = media && !caustic && s.volume_min_divisor > 0 ? wanted / s.volume_min_divisor : 0;
  size_t stored = 0, stored_volume = 0;
  uint64_t emitted = 0, emitted_map = 0;  // all, and those that filled the map (surface_done)
  uint64_t volume_cap = cap;
  uint64_t chunks_in_round = 8;
  bool surface_done = false, done = false;
  while (!done && emitted < volume_cap) {
    if (stop_requested(s)) break;
    std::vector<std::vector<PendingPhoton>> chunk_out(chunks_in_round), chunk_volume(chunks_in_round);
    std::vector<std::vector<uint32_t>> chunk_counts(chunks_in_round);  // stored per emitted photon
    std::vector<std::vector<uint32_t>> chunk_volume_counts(chunks_in_round);  // and in media
    std::vector<uint64_t> chunk_rays(chunks_in_round, 0);
    const uint64_t first = emitted;
    tbb::parallel_for(uint64_t(0), chunks_in_round, [&](uint64_t c) {
      if (stop_requested(s)) return;
      auto& out = chunk_out[c];
      auto& counts = chunk_counts[c];
      auto& vol = chunk_volume[c];
      counts.reserve(kChunk);
      if (media) chunk_volume_counts[c].reserve(kChunk);
      for (uint64_t i = first + c * kChunk; i < first + (c + 1) * kChunk; ++i) {
        Sampler sampler(hash_seed(i, s.seed, stream));
        const size_t before = out.size(), volume_before = vol.size();
        Ray ray;
        Color flux;
        int32_t medium = -1;
        if (emitter.emit(sampler.rng, ray, flux, medium))
          trace_photon(scene, ray, flux, medium, caustic, s, sampler, out, vol, chunk_rays[c]);
        // In media the count that fills the map is the one it holds: a caustic pass keeping
        // volume photons alone counts those.
        const size_t kept = caustic && s.caustic_volume_only ? vol.size() - volume_before : out.size() - before;
        counts.push_back(uint32_t(kept));
        if (media) chunk_volume_counts[c].push_back(uint32_t(vol.size() - volume_before));
      }
    });
    for (uint64_t r : chunk_rays) rays_out += r;
    // Keep photons in photon-index order up to the one that completes the wanted count (a scan
    // of the counts; the chunks move, nothing is copied), then volume photons alone up to the
    // one that completes theirs.
    for (uint64_t c = 0; c < chunks_in_round && !done; ++c) {
      size_t keep = 0, keep_volume = 0, taken = 0;
      for (uint32_t n : chunk_counts[c]) {
        if (!surface_done) keep += n;
        if (media) keep_volume += chunk_volume_counts[c][taken];
        ++taken;
        ++emitted;
        // (In dense media a path stores many scattering points: their map stops at
        // PhotonPassSettings::kVolumeShare times the wanted count, so that memory stays bounded.)
        const bool volume_full = stored_volume + keep_volume >= PhotonPassSettings::kVolumeShare * wanted;
        if (!surface_done && (stored + keep >= wanted || emitted >= cap || volume_full)) {
          surface_done = true;
          emitted_map = emitted;
          volume_cap = std::min(cap, emitted * PhotonPassSettings::kVolumeEmission);
        }
        if (surface_done && (stored_volume + keep_volume >= wanted_volume || emitted >= volume_cap || volume_full)) {
          done = true;
          break;
        }
      }
      if (caustic && s.caustic_volume_only) keep = 0;  // (the count was the volume photons')
      chunk_out[c].resize(keep);
      chunk_volume[c].resize(keep_volume);
      stored += caustic && s.caustic_volume_only ? keep_volume : keep;
      chunks.push_back(std::move(chunk_out[c]));
      volume_chunks.push_back(std::move(chunk_volume[c]));
      stored_volume += keep_volume;
    }
    if (stop_requested(s)) break;
    // Size the next round from the storage rate seen so far (deterministic): the map's, then
    // the volume photons'.
    const double rate = emitted > 0 ? double(surface_done ? stored_volume : stored) / double(emitted) : 0.0;
    const size_t have = surface_done ? stored_volume : stored, goal = surface_done ? wanted_volume : wanted;
    const double need = rate > 0 ? double(goal - std::min(goal, have)) / rate : double(volume_cap);
    chunks_in_round = std::clamp<uint64_t>(uint64_t(need * 1.05 / kChunk) + 1, 1, 256);
  }
  if (!surface_done) emitted_map = emitted;
  // A stopped pass keeps nothing: no caller uses part of a map, and normalising and indexing
  // millions of photons would delay the stop by seconds.
  if (stop_requested(s)) return result;
  if (stored < wanted && emitted_map >= cap) {
    warnings.push_back(std::string(caustic ? "caustic" : "global") + " photon map: only " + std::to_string(stored) +
                       " of " + std::to_string(wanted) + " photons stored after " + std::to_string(emitted_map) +
                       " emitted (the cap); most photons escape or miss " +
                       (caustic ? "the specular objects" : "diffuse surfaces"));
  }
  emitted_out = emitted_map;
  volume_out = normalise(volume_chunks, emitted, volume_scale, true);
  return normalise(chunks, emitted_map, flux_scale);
}

// The caustic pass's emission bound: kCausticShare times the global pass's (at least 2^18). In
// media, where the caustic map holds volume photons alone, once the global map's volume photons
// of such paths (L S+ V) carry under kMinVolumeCausticShare of its volume photons' flux, it is
// bounded by the global pass's own emission: on scenes whose only specular objects are thin
// shells light passes straight through (Mitsuba's media test scenes: 1 to 5 %, against 21 % on
// volumetric-caustic and 58 % on Mitsuba's glass ball in fog), the caustic photons aimed at
// them found few and took nine tenths of a render. A caustic below the share keeps a map, from
// fewer photons.
uint64_t caustic_cap(const PhotonPassSettings& s, const PhotonPassResult& global) {
  if (global.global_emitted == 0) return 0;
  if (s.caustic_volume_only && !(global.volume_caustic_share >= kMinVolumeCausticShare)) return global.global_emitted;
  return std::max<uint64_t>(kCausticShare * global.global_emitted, uint64_t(1) << 18);
}

// The share of volume photons' flux on L S+ V paths (0 without any).
double caustic_path_share(const std::vector<Photon>& volume) {
  double all = 0, caustic = 0;
  for (const Photon& p : volume) {
    const double f = max_component(p.power());
    all += f;
    if (is_caustic_path(p)) caustic += f;
  }
  return all > 0 ? caustic / all : 0.0;
}

}  // namespace

// Refuses up front a photon count whose maps would not fit in this machine's memory.
void check_photon_memory(size_t photons) {
  // While tracing: a pending record (position, float flux, directions) and the final record;
  // then the kd-tree index and the precomputed-irradiance points (a quarter as many, each with
  // a record, an index entry and a grid entry, normal and cells: PointGrid).
  const double bytes_per_photon = 52.0 + sizeof(Photon) + 8.0 + 0.25 * (sizeof(Photon) + 8.0 + 60.0);
  check_memory(double(photons) * bytes_per_photon, "a photon pass of " + std::to_string(photons) + " photons", " (use fewer photons)");
}

PhotonPassResult trace_photons(const Scene& scene, const PhotonPassSettings& settings) {
  const auto t0 = std::chrono::steady_clock::now();
  PhotonPassResult r;
  r.global = run_map(scene, settings, false, 0, r.global_emitted, r.rays, r.global_scale, r.volume, r.volume_scale,
                     r.warnings);
  r.volume_caustic_share = caustic_path_share(r.volume);
  if (!stop_requested(settings))
    r.caustic = run_map(scene, settings, true, caustic_cap(settings, r), r.caustic_emitted, r.rays, r.caustic_scale,
                        r.volume_caustic, r.volume_caustic_scale, r.warnings);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace caustica
