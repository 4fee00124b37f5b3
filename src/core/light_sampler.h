// Choosing a light for a shadow ray at a shading point. Two ways, as pbrt-v4 offers them:
// "power", in proportion to each light's power (times its sampling weight) wherever the point
// is; and "tree" (the default), a binary tree over the finite lights' bounds (core/
// light_bounds.h) descended by each subtree's importance at the point, so that a dim light near
// the point is not starved by a bright one far away or behind it (pbrt-v4's BVHLightSampler,
// after Conty Estevez and Kulla 2018). Lights at infinity are chosen, by power among them, with
// probability n / (n + 1) for n of them beside the tree. Photon emission keeps choosing by power
// (Scene::sample_photon_light): each photon then carries the same flux.
#pragma once
#include <memory>
#include <string>
#include <vector>
#include "core/lights/light.h"
#include "core/sampling.h"

namespace caustica {

enum class LightSamplerKind : uint8_t { Tree, Power };
bool parse_light_sampler(const std::string& name, LightSamplerKind& kind);
const char* light_sampler_name(LightSamplerKind kind);

class LightSampler {
 public:
  LightSampler() = default;
  LightSampler(const std::vector<std::unique_ptr<Light>>& lights, LightSamplerKind kind);
  // The light for a shadow ray from p (shading normal n, or zero) chosen by u, and its
  // probability; -1 where no light can reach p (or the scene has none).
  int sample(const Vec3& p, const Vec3& n, float u, float& pmf) const;
  // The probability that sample() at (p, n) chooses light i.
  float pmf(const Vec3& p, const Vec3& n, size_t i) const;
  // In proportion to power times sampling weight, wherever (photon emission; "power").
  size_t sample_by_power(float u, float& pmf) const { return by_power_.sample(u, &pmf); }
  float pmf_by_power(size_t i) const { return by_power_.pmf(i); }
  size_t nodes() const { return nodes_.size(); }

 private:
  struct Node {
    CompactLightBounds bounds;
    int32_t child = -1;   // an inner node's first child (the second follows it); -1 for a leaf
    int32_t light = -1;   // a leaf's light
    int32_t parent = -1;
  };
  // Makes node the root of a subtree over items[begin, end).
  void build(std::vector<std::pair<LightBounds, int32_t>>& items, size_t begin, size_t end, int32_t node);
  // The chance that the descent at a node takes its first child c rather than c + 1 (their
  // importances' share at p, n); negative where neither can light p.
  float first_child_share(int32_t c, const Vec3& p, const Vec3& n) const;
  LightSamplerKind kind_ = LightSamplerKind::Tree;
  Distribution1D by_power_;           // every light ("power"; photon emission)
  std::vector<size_t> infinite_;      // "tree": the lights at infinity,
  Distribution1D infinite_by_power_;  // chosen among them by power,
  float p_infinite_ = 0.0f;           // with this probability in all
  std::vector<Node> nodes_;           // "tree": the finite lights (root first)
  std::vector<int32_t> leaf_of_;      // by light: its leaf, or -1
  std::vector<int32_t> infinite_index_;  // by light: its place in infinite_, or -1
};

}  // namespace caustica
