#include "dem/wall_loads.h"

#include <algorithm>

namespace chutelab::dem {

void WallLoads::prepare(const std::vector<Wall>& walls, std::size_t blocks, std::size_t threads) {
  walls_ = walls.size();
  blocks_ = blocks;
  force_.resize(blocks * walls_);
  torque_.resize(blocks * walls_);
  elements_.resize(blocks);
  element_base_.resize(walls_);
  meshes_ = false;
  std::size_t slots = 0;
  for (std::size_t k = 0; k < walls_; slots += walls[k].element_force.size(), ++k) {
    element_base_[k] = walls[k].element_force.size() > 1 ? static_cast<std::int32_t>(slots) : -1;
    meshes_ = meshes_ || element_base_[k] >= 0;
  }
  slot_.resize(threads);
  for (auto& s : slot_)  // every slot a block uses is reset to -1 after it
    if (s.size() != slots) s.assign(slots, -1);
}

void WallLoads::finish_block(std::size_t ob, std::size_t thread, std::size_t lo, std::size_t hi,
                             const WallContactList& list, const double* mass, const Vec3& gravity, Vec3* f, Vec3* t) {
  const std::size_t nw = walls_;
  const Vec3 g = gravity;
  const std::int32_t* wb = list.begin.data();
  const std::uint8_t* touch = list.touch.data();
  const Vec3* force = list.force.data();
  const Vec3* torque = list.torque.data();
  const std::int32_t* __restrict wall_of = list.wall.data();
  const std::int32_t* __restrict element_of = list.element.data();
  const Vec3* __restrict wall_torque = list.wall_torque.data();
  // The shares are summed in the thread's own scratch and stored once at the end: the shares of two
  // threads' blocks may share a cache line, and a store per contact would pass it back and forth.
  thread_local std::vector<Vec3> acc;  // allocated by this thread, away from the others' data
  acc.assign(2 * nw, Vec3::Zero());
  Vec3* __restrict sf = acc.data();
  Vec3* __restrict st = acc.data() + nw;
  std::vector<ElementShare> parts = std::move(elements_[ob]);
  parts.clear();
  for (std::size_t i = lo; i < hi; ++i) {
    Vec3 fi = f[i], ti = t[i];
    for (auto q = static_cast<std::size_t>(wb[i]); q < static_cast<std::size_t>(wb[i + 1]); ++q) {
      if (!touch[q]) continue;
      fi += force[q];
      ti += torque[q];
      const auto k = static_cast<std::size_t>(wall_of[q]);
      const Vec3 fw = -force[q];
      sf[k] += fw;
      st[k] += wall_torque[q];
    }
    f[i] = fi + mass[i] * g;
    t[i] = ti;
  }
  std::copy(sf, sf + nw, force_.data() + ob * nw);
  std::copy(st, st + nw, torque_.data() + ob * nw);
  if (!meshes_) {
    elements_[ob] = std::move(parts);
    return;
  }
  // Apart from the loop above: inside it, its rare call (push_back) would keep fi and ti on the stack
  // (bench bed, one thread: 3 % slower).
  const std::int32_t* __restrict base = element_base_.data();
  std::int32_t* __restrict slot_of = slot_[thread].data();
  for (auto q = static_cast<std::size_t>(wb[lo]); q < static_cast<std::size_t>(wb[hi]); ++q) {
    if (!touch[q]) continue;
    const std::int32_t b = base[wall_of[q]];
    if (b < 0) continue;
    std::int32_t& at = slot_of[b + element_of[q]];
    if (at < 0) {
      at = static_cast<std::int32_t>(parts.size());
      parts.push_back({wall_of[q], element_of[q], Vec3::Zero()});
    }
    parts[static_cast<std::size_t>(at)].f -= force[q];
  }
  for (const ElementShare& es : parts) slot_of[base[es.wall] + es.element] = -1;
  elements_[ob] = std::move(parts);
}

void WallLoads::sum_into(std::vector<Wall>& walls) const {
  const std::size_t nw = walls_;
  for (std::size_t k = 0; k < nw; ++k) {
    Vec3 sf = Vec3::Zero(), st = Vec3::Zero();
    for (std::size_t ob = 0; ob < blocks_; ++ob) {
      sf += force_[ob * nw + k];
      st += torque_[ob * nw + k];
    }
    walls[k].force = sf;
    walls[k].torque = st;
    std::fill(walls[k].element_force.begin(), walls[k].element_force.end(), element_base_[k] < 0 ? sf : Vec3::Zero());
  }
  for (std::size_t ob = 0; ob < blocks_; ++ob)
    for (const ElementShare& es : elements_[ob])
      walls[static_cast<std::size_t>(es.wall)].element_force[static_cast<std::size_t>(es.element)] += es.f;
}

}  // namespace chutelab::dem
