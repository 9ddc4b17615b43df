// A plain view of the particles: one pointer per field of the store's field list
// (core/particle_fields.hpp) and the counts, trivially copyable, so that a loop (or a device
// kernel) takes it by value and indexes it as it would the store: view.x[i], view.radius[j].
// It stays valid until the store is resized or reordered (a list build). `Const`: read-only.
#pragma once

#include "core/host_device.hpp"
#include "core/particle_fields.hpp"

#include <cstddef>
#include <type_traits>

namespace yuxi {

template <bool Const> struct BasicParticleView {
  template <class T> using Ptr = std::conditional_t<Const, const T*, T*>;
#define YUXI_VIEW_POINTER(type, name) Ptr<type> name = nullptr;
  YUXI_PARTICLE_FIELDS(YUXI_VIEW_POINTER)
#undef YUXI_VIEW_POINTER
  std::size_t owned = 0; // owned particles [0, owned), then ghosts
  std::size_t total = 0;

  YUXI_HD std::size_t n_owned() const {
    return owned;
  }
  YUXI_HD std::size_t size() const {
    return total;
  }
  YUXI_HD bool is_grain(std::size_t i) const {
    return kind[i] == Kind::grain;
  }

  BasicParticleView() = default;
  // A read-only view of a writable view's particles.
  template <bool Other>
  requires(Const && !Other) YUXI_HD BasicParticleView(const BasicParticleView<Other>& o)
      : owned(o.owned), total(o.total) {
#define YUXI_VIEW_COPY(type, name) name = o.name;
    YUXI_PARTICLE_FIELDS(YUXI_VIEW_COPY)
#undef YUXI_VIEW_COPY
  }
};

using ParticleView = BasicParticleView<false>;
using ConstParticleView = BasicParticleView<true>;

static_assert(std::is_trivially_copyable_v<ParticleView>);
static_assert(std::is_trivially_copyable_v<ConstParticleView>);

} // namespace yuxi
