// The light samplers: by power, and a tree of light bounds.
#include "core/light_sampler.h"
#include <algorithm>
#include <cmath>

namespace caustica {
namespace {
using Item = std::pair<LightBounds, int32_t>;  // a light's bounds and index

// Sorts items[begin, end) by their boxes' centres along axis (the light's index breaks ties:
// the tree is the same on every run), or by index alone for axis -1.
void sort_items(std::vector<Item>& items, size_t begin, size_t end, int axis) {
  std::sort(items.begin() + std::ptrdiff_t(begin), items.begin() + std::ptrdiff_t(end), [axis](const Item& a, const Item& b) {
    const float ca = axis < 0 ? 0.0f : a.first.bounds.centre()[axis], cb = axis < 0 ? 0.0f : b.first.bounds.centre()[axis];
    return ca < cb || (ca == cb && a.second < b.second);
  });
}

// A number in [0, 1): rescaled sample numbers must not reach 1.
float below_one(float u) { return std::min(u, 0x1.fffffep-1f); }

// The tree's split cost of a node (pbrt-v4's surface area orientation heuristic): its power
// times the solid angle its cone of emission (normals widened by theta_e) covers, weighted by
// cosine, times its size (the squared diagonal: point lights have boxes of zero area).
double node_cost(const LightBounds& b) {
  const double theta_o = std::acos(std::clamp(double(b.normals.cos_theta), -1.0, 1.0));
  const double theta_e = std::acos(std::clamp(double(b.cos_theta_e), -1.0, 1.0));
  const double theta_w = std::min(theta_o + theta_e, double(kPi));
  const double s = std::sin(theta_o), c = std::cos(theta_o);
  const double m_omega = 2.0 * kPi * (1.0 - c) +
                         0.5 * kPi * (2.0 * theta_w * s - std::cos(theta_o - 2.0 * theta_w) - 2.0 * theta_o * s + c);
  const Vec3 d = b.bounds.extent();
  return double(b.phi) * m_omega * double(glm::dot(d, d));
}
}  // namespace

bool parse_light_sampler(const std::string& name, LightSamplerKind& kind) {
  if (name == "tree") kind = LightSamplerKind::Tree;
  else if (name == "power") kind = LightSamplerKind::Power;
  else return false;
  return true;
}

const char* light_sampler_name(LightSamplerKind kind) { return kind == LightSamplerKind::Tree ? "tree" : "power"; }

LightSampler::LightSampler(const std::vector<std::unique_ptr<Light>>& lights, LightSamplerKind kind) : kind_(kind) {
  std::vector<float> powers, infinite_powers;
  for (const auto& light : lights) powers.push_back(light->sampling_power());
  by_power_ = Distribution1D(powers.data(), powers.size());
  if (kind_ != LightSamplerKind::Tree) return;
  leaf_of_.assign(lights.size(), -1);
  infinite_index_.assign(lights.size(), -1);
  std::vector<Item> items;
  for (size_t i = 0; i < lights.size(); ++i) {
    if (lights[i]->is_infinite()) {
      infinite_index_[i] = int32_t(infinite_.size());
      infinite_.push_back(i);
      infinite_powers.push_back(powers[i]);
      continue;
    }
    const LightBounds b = lights[i]->light_bounds();
    if (b.phi > 0.0f && !b.bounds.empty()) items.emplace_back(b, int32_t(i));
  }
  infinite_by_power_ = Distribution1D(infinite_powers.data(), infinite_powers.size());
  if (!items.empty()) {
    nodes_.reserve(2 * items.size() - 1);
    nodes_.emplace_back();
    build(items, 0, items.size(), 0);
  }
  p_infinite_ = infinite_.empty() ? 0.0f : nodes_.empty() ? 1.0f : float(infinite_.size()) / float(infinite_.size() + 1);
}

void LightSampler::build(std::vector<Item>& items, size_t begin, size_t end, int32_t node) {
  if (end - begin == 1) {
    nodes_[size_t(node)].bounds = CompactLightBounds(items[begin].first);
    nodes_[size_t(node)].light = items[begin].second;
    leaf_of_[size_t(items[begin].second)] = node;
    return;
  }
  // The split of least cost over the three axes, the items sorted by their boxes' centres.
  Bounds centres;
  for (size_t i = begin; i < end; ++i) centres.extend(items[i].first.bounds.centre());
  size_t best_mid = begin + (end - begin) / 2;
  int best_axis = -1;
  double best_cost = INFINITY;
  std::vector<double> left_cost(end - begin);
  for (int axis = 0; axis < 3; ++axis) {
    if (!(centres.hi[axis] > centres.lo[axis])) continue;
    sort_items(items, begin, end, axis);
    LightBounds acc;
    for (size_t i = begin; i + 1 < end; ++i) {
      acc = LightBounds::unite(acc, items[i].first);
      left_cost[i - begin] = node_cost(acc);
    }
    acc = LightBounds{};
    for (size_t i = end - 1; i > begin; --i) {
      acc = LightBounds::unite(acc, items[i].first);
      const double cost = left_cost[i - 1 - begin] + node_cost(acc);
      if (cost < best_cost) best_cost = cost, best_mid = i, best_axis = axis;
    }
  }
  sort_items(items, begin, end, best_axis);  // (every centre the same: halves in index order)
  const int32_t child = int32_t(nodes_.size());
  nodes_.emplace_back();
  nodes_.emplace_back();
  nodes_[size_t(child)].parent = nodes_[size_t(child) + 1].parent = node;
  nodes_[size_t(node)].child = child;
  LightBounds all;
  for (size_t i = begin; i < end; ++i) all = LightBounds::unite(all, items[i].first);
  nodes_[size_t(node)].bounds = CompactLightBounds(all);
  build(items, begin, best_mid, child);
  build(items, best_mid, end, child + 1);
}

float LightSampler::first_child_share(int32_t c, const Vec3& p, const Vec3& n) const {
  const float i0 = nodes_[size_t(c)].bounds.importance(p, n), i1 = nodes_[size_t(c) + 1].bounds.importance(p, n);
  return i0 + i1 > 0.0f ? i0 / (i0 + i1) : -1.0f;
}

int LightSampler::sample(const Vec3& p, const Vec3& n, float u, float& pmf) const {
  pmf = 0.0f;
  if (kind_ == LightSamplerKind::Power) {
    if (by_power_.size() == 0) return -1;
    return int(by_power_.sample(u, &pmf));
  }
  if (!infinite_.empty() && u < p_infinite_) {
    float q = 0.0f;
    const size_t k = infinite_by_power_.sample(below_one(u / p_infinite_), &q);
    pmf = p_infinite_ * q;
    return int(infinite_[k]);
  }
  if (nodes_.empty()) return -1;
  float prob = 1.0f - p_infinite_;
  if (p_infinite_ > 0.0f) u = below_one((u - p_infinite_) / (1.0f - p_infinite_));
  // (One finite light is always chosen: its importance would only rule out points that its
  // own sampling gives nothing, at a cost on every shadow ray.)
  int32_t node = 0;
  while (nodes_[size_t(node)].child >= 0) {
    const int32_t c = nodes_[size_t(node)].child;
    const float p0 = first_child_share(c, p, n);
    if (p0 < 0.0f) return -1;
    if (u < p0) {
      node = c;
      u = below_one(u / p0);
      prob *= p0;
    } else {
      node = c + 1;
      u = below_one((u - p0) / (1.0f - p0));
      prob *= 1.0f - p0;
    }
  }
  pmf = prob;
  return nodes_[size_t(node)].light;
}

float LightSampler::pmf(const Vec3& p, const Vec3& n, size_t i) const {
  if (kind_ == LightSamplerKind::Power) return i < by_power_.size() ? by_power_.pmf(i) : 0.0f;
  if (i >= leaf_of_.size()) return 0.0f;
  if (infinite_index_[i] >= 0) return p_infinite_ * infinite_by_power_.pmf(size_t(infinite_index_[i]));
  int32_t node = leaf_of_[i];
  if (node < 0) return 0.0f;
  float prob = 1.0f - p_infinite_;
  while (nodes_[size_t(node)].parent >= 0) {
    const int32_t parent = nodes_[size_t(node)].parent, c = nodes_[size_t(parent)].child;
    const float p0 = first_child_share(c, p, n);
    if (p0 < 0.0f) return 0.0f;
    prob *= node == c ? p0 : 1.0f - p0;
    node = parent;
  }
  return prob;
}

}  // namespace caustica
