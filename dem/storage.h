#pragma once
// Storage of the engine's per-slot and per-particle arrays.
#include <cstddef>
#include <vector>

namespace chutelab::dem {

// Sizes an array whose old contents are not needed (all of it is written next). Storage is kept from
// one rebuild to the next, so its pages are not faulted in anew; to grow, the old block is released
// before the new one is taken, so the two are never held together (the rebuild's memory peak).
template <class T>
void resize_for_overwrite(std::vector<T>& v, std::size_t n) {
  if (n > v.capacity()) {
    v = std::vector<T>();
    v.reserve(n + n / 16);
  }
  v.resize(n);
}

}  // namespace chutelab::dem
