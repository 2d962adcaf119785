// A std::vector whose resize(n) leaves new elements of a trivial type uninitialised, for the large
// arrays the mesher sizes first and then fills in parallel chunks: zeroing them first cost the
// self-organizing default about 1 ms of its mesh (14 MB of bark written twice).
#pragma once

#include <memory>
#include <new>
#include <type_traits>
#include <vector>

namespace sylva {

template <class T>
struct default_init_allocator : std::allocator<T> {
  using std::allocator<T>::allocator;
  template <class U>
  struct rebind {
    using other = default_init_allocator<U>;
  };
  // resize(n) and vector(n) construct with no arguments: default-initialise (no zeroing of a
  // trivial type) instead of value-initialising. Construction with arguments (copies, fills) is
  // std::allocator_traits' own placement new.
  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
};

template <class T>
using uninit_vector = std::vector<T, default_init_allocator<T>>;

}  // namespace sylva
