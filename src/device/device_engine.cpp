// The device engine's step, written once as Thrust algorithms and the functors of
// step_phases.hpp. g++ compiles this file with Thrust's CPP system (the host build, which CI
// tests); with -DYUXI_CUDA=ON nvcc compiles the same file as CUDA. Keep fmt, spdlog and the
// scene headers out of it: nvcc does not compile fmt 9 under C++20.
#include "device/device_engine.hpp"

#include "contact/hertz_mindlin.hpp"
#include "contact/hooke.hpp"
#include "contact/linear_spring_dashpot.hpp"
#include "contact/luding.hpp"
#include "contact/thermodynamic.hpp"
#include "device/clump_phases.hpp"
#include "device/kept_state.hpp"
#include "device/step_phases.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <cmath>
#include <map>
#include <numeric>
#include <stdexcept>
#include <string>
#include <thrust/binary_search.h>
#include <thrust/copy.h>
#include <thrust/count.h>
#include <thrust/device_free.h>
#include <thrust/device_malloc.h>
#include <thrust/device_vector.h>
#include <thrust/execution_policy.h>
#include <thrust/for_each.h>
#include <thrust/functional.h>
#include <thrust/gather.h>
#include <thrust/iterator/counting_iterator.h>
#include <thrust/iterator/transform_iterator.h>
#include <thrust/reduce.h>
#include <thrust/scan.h>
#include <thrust/sequence.h>
#include <thrust/sort.h>
#include <type_traits>
#include <utility>
#include <vector>

#if defined(__CUDACC__)
#include <cuda_runtime.h>
#endif

namespace yuxi::device {
namespace {

// The bytes that this thread's engines hold on the device, now and at most since an engine
// started (DeviceMemory::peak): every device array and, on the GPU, the kept temporary storage
// of Thrust's algorithms (Scratch). An engine runs on the thread that calls it.
struct HeldBytes {
  std::size_t now = 0, most = 0;
  void add(std::size_t n) {
    now += n;
    most = std::max(most, now);
  }
  void remove(std::size_t n) { now -= n; }
};
HeldBytes& held() {
  thread_local HeldBytes bytes;
  return bytes;
}

// Thrust's device allocator, counting what it holds into held().
template <class T> struct CountedAllocator : thrust::device_allocator<T> {
  using base = thrust::device_allocator<T>;
  template <class U> struct rebind { using other = CountedAllocator<U>; };
  CountedAllocator() = default;
  template <class U> CountedAllocator(const CountedAllocator<U>&) {}
  typename base::pointer allocate(typename base::size_type n) {
    typename base::pointer at = base::allocate(n);
    held().add(n * sizeof(T));
    return at;
  }
  void deallocate(typename base::pointer at, typename base::size_type n) {
    base::deallocate(at, n);
    held().remove(n * sizeof(T));
  }
};

template <class T> using DeviceVector = thrust::device_vector<T, CountedAllocator<T>>;

template <class T> T* raw(DeviceVector<T>& v) {
  return thrust::raw_pointer_cast(v.data());
}
template <class T> const T* raw(const DeviceVector<T>& v) {
  return thrust::raw_pointer_cast(v.data());
}
template <class T> std::size_t bytes(const DeviceVector<T>& v) {
  return v.capacity() * sizeof(T);
}
template <class... Vectors> std::size_t bytes_of(const Vectors&... vectors) {
  return (bytes(vectors) + ...);
}

// v holds n elements afterwards, of unspecified values: every caller writes them all. Within
// what v holds (down to half of it), nothing is allocated. Otherwise v is allocated afresh for
// n and a sixteenth: Thrust's own resize doubles what a vector holds when it grows, so the
// per-pair arrays would hold up to twice the pairs listed once a list build listed one more than
// the last. (An empty vector is always replaced: Thrust 1.17's CPP system grows one by copying
// its no elements from a null pointer with memmove, which UBSan rejects.)
template <class T> void resize(DeviceVector<T>& v, std::size_t n) {
  const std::size_t held = v.capacity();
  if (!v.empty() && n <= held && n >= held / 2) {
    v.resize(n);
    return;
  }
  DeviceVector<T> fresh;
  if (n > 0) {
    DeviceVector<T>(n + n / 16).swap(fresh);
    fresh.resize(n);
  }
  fresh.swap(v);
}

// The end of a vector as a raw pointer: the algorithms that take thrust::device are given
// [raw(v), last(v)), the same memory on either backend and no element references (Thrust
// 1.17's bind a null execution policy, which UBSan stops, in its CPU radix sort among others).
template <class T> T* last(DeviceVector<T>& v) {
  return raw(v) + v.size();
}
template <class T> const T* last(const DeviceVector<T>& v) {
  return raw(v) + v.size();
}

// v holds at least n elements afterwards, of unspecified values: n and a sixteenth where it had
// to grow, or where n is below a quarter of it. For arrays of a count that changes every step,
// kept apart from the size: they are not resized each step (a resize that grows, even within
// what is held, fills the new elements).
template <class T> void make_room(DeviceVector<T>& v, std::size_t n) {
  if (n <= v.size() && n >= v.size() / 4) return;
  resize(v, n + n / 16);
}

// Each of `vectors` resized to n (resize()).
template <class... Vectors> void resize_all(std::size_t n, Vectors&... vectors) {
  (resize(vectors, n), ...);
}
// Room for n in each of `vectors` (make_room()).
template <class... Vectors> void make_room_all(std::size_t n, Vectors&... vectors) {
  (make_room(vectors, n), ...);
}

// A copy of v on the host.
template <class T> std::vector<T> to_host(const DeviceVector<T>& v) {
  std::vector<T> out(v.size());
  if (!v.empty()) thrust::copy(v.begin(), v.end(), out.begin());
  return out;
}

// The temporary storage of Thrust's algorithms (select, reduce, scan, sort), kept between calls:
// each algorithm would otherwise allocate and free its own, every step, and on the GPU freeing
// waits for the device. A request that no kept block fits frees the kept blocks first, so what is
// kept stays about the largest recent request; `trim` frees them all (after a list build, whose
// sorts ask for the most). One per thread: an engine runs on the thread that calls it. Used on
// the GPU only (on_device).
class Scratch {
public:
  using value_type = char;
  Scratch() { held(); } // (made first, so gone last: the destructor counts into it)
  Scratch(const Scratch&) = delete;
  Scratch& operator=(const Scratch&) = delete;
  ~Scratch() {
    trim();
    for (const auto& [at, size] : used_) {
      thrust::device_free(thrust::device_pointer_cast(at));
      held().remove(static_cast<std::size_t>(size));
    }
  }

  char* allocate(std::ptrdiff_t n) {
    auto fit = kept_.lower_bound(n);
    if (fit == kept_.end()) {
      trim();
      fit = kept_.emplace(
          n, thrust::raw_pointer_cast(thrust::device_malloc<char>(static_cast<std::size_t>(n))));
      held().add(static_cast<std::size_t>(n));
    }
    char* at = fit->second;
    used_.emplace(at, fit->first);
    kept_.erase(fit);
    return at;
  }
  void deallocate(char* at, std::size_t) {
    const auto block = used_.find(at);
    kept_.emplace(block->second, at);
    used_.erase(block);
  }
  void trim() {
    for (const auto& [size, at] : kept_) {
      thrust::device_free(thrust::device_pointer_cast(at));
      held().remove(static_cast<std::size_t>(size));
    }
    kept_.clear();
  }
  std::size_t bytes() const {
    std::size_t total = 0;
    for (const auto& [size, at] : kept_) total += static_cast<std::size_t>(size);
    return total;
  }

private:
  std::multimap<std::ptrdiff_t, char*> kept_;
  std::map<char*, std::ptrdiff_t> used_;
};

Scratch& scratch() {
  thread_local Scratch kept;
  return kept;
}

// The execution policy of every algorithm. On the GPU, with the kept temporary storage, and
// without Thrust's wait after each algorithm: the kernels of one stream run in order anyway, and
// every result the host reads comes back through a copy, which waits. On the CPU, Thrust's device
// system as it is (allocating there costs little, and Thrust 1.17's CPU radix sort with an
// allocator binds element references to a null policy, which UBSan stops).
#if THRUST_DEVICE_SYSTEM == THRUST_DEVICE_SYSTEM_CUDA
auto on_device() {
  return thrust::cuda::par_nosync(scratch());
}
#else
const auto& on_device() {
  return thrust::device;
} // (Thrust's own object: a copy trips UBSan)
#endif

// Sorts [first, last) ascending and carries `values` along, stably. On the GPU, Thrust's radix
// sort; on the CPU, std::stable_sort through pairs, since Thrust 1.17's CPU sorts (radix and
// merge) bind element references to a null execution policy, which UBSan stops. Both are stable,
// so both give the same order.
template <class K, class V> void sort_by_key(K* first, K* last, V* values) {
#if THRUST_DEVICE_SYSTEM == THRUST_DEVICE_SYSTEM_CUDA
  thrust::stable_sort_by_key(on_device(), first, last, values);
#else
  std::vector<std::pair<K, V>> zipped(static_cast<std::size_t>(last - first));
  for (std::size_t k = 0; k < zipped.size(); ++k) zipped[k] = {first[k], values[k]};
  std::stable_sort(zipped.begin(), zipped.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  for (std::size_t k = 0; k < zipped.size(); ++k) {
    first[k] = zipped[k].first;
    values[k] = zipped[k].second;
  }
#endif
}

// Waits for the device's work (the phase clocks): nothing to wait for on the CPU.
void wait_for_device() {
#if defined(__CUDACC__)
  cudaDeviceSynchronize();
#endif
}

// Applies f to every index in [0, n): one thread per index on the GPU, a loop on the CPU.
template <class F> void for_each_index(std::uint32_t n, const F& f) {
  if (n == 0) return;
  thrust::for_each_n(on_device(), thrust::counting_iterator<std::uint32_t>(0), n, f);
}

// One element to or from the device. Through copies, not v[k]: Thrust 1.17's element reference
// binds a null execution policy, which UBSan stops.
template <class T> T read_one(const DeviceVector<T>& v, std::size_t k) {
  std::array<T, 1> one{};
  thrust::copy_n(v.begin() + static_cast<std::ptrdiff_t>(k), 1, one.begin());
  return one[0];
}
template <class T> void write_one(DeviceVector<T>& v, std::size_t k, const T& value) {
  const std::array<T, 1> one{value};
  thrust::copy_n(one.begin(), 1, v.begin() + static_cast<std::ptrdiff_t>(k));
}

// A contact that touches (a pair's or a grain-plane candidate's flag).
struct IsOpen {
  YUXI_HD bool operator()(std::uint8_t b) const { return (b & touches_now) != 0; }
};

// 1 for a grain outside the box along an open axis (NaN too), and its mechanical energy
// (core/particle_energy.hpp; a clump's member's is its clump's: ClumpEscaped); 0 for the others.
struct Escaped {
  Particles p;
  DeviceBox box;
  Vec3 g_potential;
  std::uint32_t* gone;
  double* energy;
  YUXI_HD void operator()(std::uint32_t i) const {
    bool out = false;
    if (p.kind[i] == Kind::grain)
      for (int a = 0; a < 3; ++a)
        if (!box.periodic[a] && !(p.x[i][a] >= box.lo[a] && p.x[i][a] <= box.hi[a])) out = true;
    gone[i] = out ? 1 : 0;
    energy[i] = out && !p.is_member(i) ? mechanical_energy(p.mass(i), p.x[i], p.v[i], p.w[i],
                                                           p.inv_inertia(i), g_potential)
                                       : 0.0;
  }
};

// Sums of device arrays in a fixed order, many with one copy to the host. Each array of n
// values is added in two levels of StridedSum (step_phases.hpp): min(n, 65,536) threads, then
// min(that, 256); the host adds the last partial sums in order. The order depends on n alone, so
// the GPU and the host build give the same bits; every thread of the first level reads values
// that its neighbours' reads sit beside, so the sum runs at the memory's speed. The first
// level's partial sums are read by the second as soon as they are written: `first`, their room,
// can serve several OrderedSums.
class OrderedSums {
public:
  static constexpr std::uint32_t first_width = 65536, second_width = 256;

  // (the first level's room grows to the widest sum asked for: a small scene keeps little)
  explicit OrderedSums(DeviceVector<double>& first) : first_(first), second_(16 * second_width) {}

  // Queues the sum of v's first n values (all of them by default); collect() returns it, in the
  // order of the calls to add.
  void add(const DeviceVector<double>& v) { add(v, v.size()); }
  void add(const DeviceVector<double>& v, std::size_t count) { add_values(raw(v), count); }
  // Queues the sum of values[0, count), values an array or values computed as they are read
  // (step_phases.hpp, GravityWork).
  template <class Values> void add_values(const Values& values, std::size_t count) {
    const std::uint32_t n = static_cast<std::uint32_t>(count);
    const std::uint32_t wide = std::min(n, first_width), narrow = std::min(wide, second_width);
    if (used_ + narrow > second_.size()) second_.resize(2 * (used_ + narrow)); // keeps the sums
    if (first_.size() < wide) resize(first_, wide);
    for_each_index(wide, StridedSum<Values>{values, n, wide, raw(first_)});
    for_each_index(narrow,
                   StridedSum<const double*>{raw(first_), wide, narrow, raw(second_) + used_});
    widths_.push_back(narrow);
    used_ += narrow;
  }
  // The queued sums, in order; the queue is empty afterwards.
  std::vector<double> collect() {
    std::vector<double> partial(used_), sums;
    if (used_ > 0) thrust::copy_n(second_.begin(), used_, partial.begin());
    std::size_t at = 0;
    for (const std::uint32_t w : widths_) {
      double s = 0.0;
      for (std::uint32_t k = 0; k < w; ++k) s += partial[at + k];
      sums.push_back(s);
      at += w;
    }
    widths_.clear();
    used_ = 0;
    return sums;
  }
  // The sum of v's first n values (all by default) alone.
  double operator()(const DeviceVector<double>& v) { return (*this)(v, v.size()); }
  double operator()(const DeviceVector<double>& v, std::size_t n) {
    add(v, n);
    return collect()[0];
  }
  // (the second level's: the first's room is its owner's)
  std::size_t device_bytes() const { return bytes(second_); }

private:
  DeviceVector<double>& first_;
  DeviceVector<double> second_;
  std::vector<std::uint32_t> widths_;
  std::size_t used_ = 0;
};

// Wall time since the last add_to(), added to a phase's total.
class PhaseClock {
public:
  void add_to(double& total) {
    wait_for_device();
    const auto now = std::chrono::steady_clock::now();
    total += std::chrono::duration<double>(now - last_).count();
    last_ = now;
  }

private:
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

struct IsZero {
  YUXI_HD bool operator()(std::uint32_t b) const { return b == 0; }
};

// The engine of law Model, keeping its contacts' states as Kept says (kept_state.hpp).
template <class Model, class Kept> class Engine final : public LawEngine<Model> {
public:
  using State = typename Kept::State; // as kept on the device
  using Whole = typename Model::State;
  using Coeffs = typename Model::Coeffs;

  Engine(const DeviceScene& scene, const std::vector<Coeffs>& coeffs,
         const std::vector<KeyedState<Whole>>& contacts) {
    const HostParticles& hp = scene.particles;
    if (hp.size() >= (std::size_t{1} << 31))
      throw std::invalid_argument("device engine: more than 2^31 particles");
    for (const GlobalId id : hp.gid)
      if (id < 0 || id >= (GlobalId{1} << 32))
        throw std::invalid_argument("device engine: a particle id beyond 32 bits (" +
                                    std::to_string(id) + ")");
    if (coeffs.size() != scene.n_materials * scene.n_materials)
      throw std::invalid_argument("device engine: coefficients for " +
                                  std::to_string(coeffs.size()) + " material pairs, expected " +
                                  std::to_string(scene.n_materials * scene.n_materials));
    n_ = static_cast<std::uint32_t>(hp.size());
    x_ = hp.x;
    v_ = hp.v;
    w_ = hp.w;
    if (scene.forces_given) { // (kept until the first step's forces)
      if (hp.f.size() != hp.size() || hp.torque.size() != hp.size())
        throw std::invalid_argument("device engine: " + std::to_string(hp.f.size()) +
                                    " forces and " + std::to_string(hp.torque.size()) +
                                    " torques given for " + std::to_string(hp.size()) +
                                    " particles");
      given_force_ = hp.f;
      given_torque_ = hp.torque;
    }
    x_build_ = hp.x;
    take_species(hp);
    gid_ = std::vector<std::uint32_t>(hp.gid.begin(), hp.gid.end()); // (checked above)
    kind_ = hp.kind;
    material_ = hp.material;
    take_clumps(scene);
    if (hp.motion.size() == hp.size())
      motion_ = hp.motion;
    else
      motion_.assign(n_, std::uint16_t{0});
    motions_ = scene.motions.empty() ? std::vector<DeviceMotion>(1) : scene.motions;
    if (motions_.size() > static_cast<std::size_t>(max_wall_motions))
      throw std::invalid_argument("device engine: " + std::to_string(motions_.size()) +
                                  " wall motions; it runs at most " +
                                  std::to_string(max_wall_motions));
    for (const std::uint16_t m : hp.motion)
      if (m >= motions_.size())
        throw std::invalid_argument("device engine: a wall particle of motion " +
                                    std::to_string(m) + ", beyond the scene's " +
                                    std::to_string(motions_.size()));
    // Rest positions and the walls' work on the grains only where a wall particle moves: a
    // standing one stays where it stands (x is its rest position) and does no work.
    for (const DeviceMotion& m : motions_) moving_walls_ = moving_walls_ || m.radial_cosine;
    if (moving_walls_) x_rest_ = hp.x_rest.size() == hp.size() ? hp.x_rest : hp.x;
    // (a wall particle's velocity is its motion's; one given a velocity and no motion would
    // book work as the CPU engine does)
    walls_work_ = moving_walls_;
    for (std::size_t i = 0; i < hp.size(); ++i)
      if (hp.kind[i] == Kind::wall && !(hp.v[i] == Vec3{})) walls_work_ = true;
    coeffs_ = coeffs;
    n_materials_ = static_cast<std::uint32_t>(scene.n_materials);

    box_.lo = scene.lo;
    box_.hi = scene.hi;
    for (int a = 0; a < 3; ++a) box_.periodic[a] = scene.periodic[a];
    gravity_ = scene.gravity;
    for (int a = 0; a < 3; ++a) g_periodic_[a] = scene.periodic[a] ? scene.gravity[a] : 0.0;
    g_potential_ = scene.gravity - g_periodic_;
    remove_escaped_ = scene.remove_escaped;
    dt_ = scene.dt;
    skin_ = scene.skin;
    time_ = scene.time;
    double largest = 0.0;
    for (const double r : hp.radius) largest = std::max(largest, r);
    const double edge = std::max(scene.cell_size, 2 * largest + scene.skin);
    cells_.lo = scene.lo;
    for (int a = 0; a < 3; ++a) {
      const double length = scene.hi[a] - scene.lo[a];
      cells_.n[a] = std::max(1, static_cast<int>(std::floor(length / edge)));
      cells_.edge[a] = length / cells_.n[a];
      if (scene.periodic[a] && cells_.n[a] < 3)
        throw std::invalid_argument("device engine: the periodic box is less than 3 cells of " +
                                    std::to_string(edge) + " along axis " + std::to_string(a));
    }
    if (static_cast<double>(cells_.n[0]) * cells_.n[1] * cells_.n[2] >= 2147483648.0)
      throw std::invalid_argument("device engine: the box holds 2^31 cells or more of " +
                                  std::to_string(edge) + "; it indexes cells with 31 bits");
    resize(tally_, n_ + 1);
    if (scene.planes.size() > 255)
      throw std::invalid_argument("device engine: " + std::to_string(scene.planes.size()) +
                                  " planes; it runs at most 255");
    n_planes_ = static_cast<std::uint32_t>(scene.planes.size());
    if (n_planes_ > 0) {
      std::vector<Vec3> point, normal;
      std::vector<std::uint8_t> material;
      std::vector<double> excursion;
      for (const DevicePlane& plane : scene.planes) {
        excursion.push_back(std::abs(plane.amplitude));
        if (plane.amplitude != 0.0) any_oscillating_ = true;
        if (plane.material >= scene.n_materials)
          throw std::invalid_argument("device engine: a plane of material " +
                                      std::to_string(plane.material) + ", beyond the scene's " +
                                      std::to_string(scene.n_materials));
        point.push_back(plane.point);
        normal.push_back(plane.normal);
        material.push_back(plane.material);
      }
      plane_point_ = point;
      plane_normal_ = normal;
      plane_material_ = material;
      plane_excursion_ = excursion;
      planes_ = scene.planes;
      plane_work_total_.assign(n_planes_, 0.0);
      resize(plane_offset_, n_planes_);
      resize(plane_velocity_, n_planes_);
    }
    // The open contacts at the start, sorted by key: the first list build takes them back.
    std::vector<std::pair<std::uint64_t, State>> pairs, planes;
    for (const KeyedState<Whole>& c : contacts) {
      if (c.second >= 0) {
        pairs.push_back({contact_key(c.first, c.second), Kept::kept(c.state)});
        continue;
      }
      const GlobalId plane = -c.second - 1;
      if (plane >= static_cast<GlobalId>(n_planes_))
        throw std::invalid_argument("device engine: a contact with plane " + std::to_string(plane) +
                                    ", beyond the scene's " + std::to_string(n_planes_));
      planes.push_back(
          {plane_key(c.first, static_cast<std::uint32_t>(plane)), Kept::kept(c.state)});
    }
    PairStash start_pairs = stash_start(std::move(pairs));
    Stash start_planes = stash_of(std::move(planes));
    // A run continued mid-way makes its last list build again, where the particles stood then
    // (Simulation::build_lists_after_load does the same): the same cells, order and pairs.
    const bool rebuild = hp.x_build.size() == hp.size() && n_ > 0;
    if (rebuild) {
      x_now_ = hp.x;
      x_ = hp.x_build;
    }
    build_list(start_pairs, start_planes, false);
    if (rebuild) {
      x_.swap(x_now_);
      DeviceVector<Vec3>().swap(x_now_);
    }
    // The forces of the start, without advancing the history, unless they came with the state:
    // a run continued mid-way keeps the forces its last step computed, at the half-step
    // velocities, as a resumed checkpoint does.
    place_planes();
    if (!scene.forces_given) {
      compute_forces(0.0);
      gather_clump_loads();
    }
  }

  void run(std::int64_t steps) override {
    for (std::int64_t s = 0; s < steps; ++s) step_once(s + 1 == steps);
  }

  HostParticles particles() const override {
    HostParticles h;
    const auto get = [](const auto& from, auto& to) { to = to_host(from); };
    HostParticles sorted;
    get(x_, sorted.x);
    get(v_, sorted.v);
    get(w_, sorted.w);
    if (given_force_.empty()) {
      sorted.f = loads(false);
      sorted.torque = loads(true);
    } else {
      get(given_force_, sorted.f);
      get(given_torque_, sorted.torque);
    }
    {
      const std::vector<Species> species = to_host(species_);
      const std::vector<std::uint16_t> species_of = to_host(species_of_);
      for (std::uint32_t i = 0; i < n_; ++i) {
        const Species& s = species[species_of.empty() ? i : species_of[i]];
        sorted.radius.push_back(s.radius);
        sorted.mass.push_back(s.mass);
        sorted.inv_mass.push_back(s.inv_mass);
        sorted.inv_inertia.push_back(s.inv_inertia);
      }
    }
    const std::vector<std::uint32_t> ids = to_host(gid_);
    sorted.gid.assign(ids.begin(), ids.end());
    get(kind_, sorted.kind);
    get(material_, sorted.material);
    if (moving_walls_)
      get(x_rest_, sorted.x_rest);
    else
      sorted.x_rest = sorted.x;
    get(x_build_, sorted.x_build);
    get(motion_, sorted.motion);
    if (n_clumps_ > 0) {
      const std::vector<std::uint32_t> body_of = to_host(body_of_);
      const std::vector<RigidBody> bodies = to_host(clump_body_);
      for (const std::uint32_t b : body_of)
        sorted.body.push_back(b == no_body ? GlobalId{-1} : GlobalId{bodies[b].gid});
    }
    std::vector<std::uint32_t> order(n_);
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(),
              [&](std::uint32_t a, std::uint32_t b) { return sorted.gid[a] < sorted.gid[b]; });
    const auto pick = [&](const auto& from, auto& to) {
      to.resize(n_);
      for (std::uint32_t k = 0; k < n_; ++k) to[k] = from[order[k]];
    };
    pick(sorted.x, h.x);
    pick(sorted.v, h.v);
    pick(sorted.w, h.w);
    pick(sorted.f, h.f);
    pick(sorted.torque, h.torque);
    pick(sorted.radius, h.radius);
    pick(sorted.mass, h.mass);
    pick(sorted.inv_mass, h.inv_mass);
    pick(sorted.inv_inertia, h.inv_inertia);
    pick(sorted.gid, h.gid);
    pick(sorted.kind, h.kind);
    pick(sorted.material, h.material);
    pick(sorted.x_rest, h.x_rest);
    pick(sorted.x_build, h.x_build);
    pick(sorted.motion, h.motion);
    if (n_clumps_ > 0) pick(sorted.body, h.body);
    return h;
  }

  std::vector<DeviceClump> clumps() const override {
    std::vector<DeviceClump> out;
    if (n_clumps_ == 0) return out;
    const std::vector<RigidBody> bodies = to_host(clump_body_);
    const std::vector<Vec3> frame = to_host(clump_frame_);
    const std::vector<Vec3> force = to_host(clump_force_), torque = to_host(clump_torque_);
    for (std::uint32_t c = 0; c < n_clumps_; ++c) {
      const RigidBody& b = bodies[c];
      DeviceClump& d = out.emplace_back();
      d.id = b.gid;
      d.mass = b.mass;
      d.inertia = b.inertia;
      d.x = b.x;
      d.v = b.v;
      d.q = b.q;
      d.p = b.p;
      d.force = force[c];
      d.torque = torque[c];
      d.members.assign(frame.begin() + b.first, frame.begin() + b.first + b.count);
    }
    return out;
  }

  DeviceEnergies energies() const override {
    DeviceEnergies e;
    DeviceVector<double> rotation;
    resize(rotation, n_);
    for_each_index(n_, RotationalEnergy{view(), raw(rotation)});
    sums_.add_values(TranslationalEnergy{view()}, n_);
    sums_.add(rotation);
    sums_.add_values(GravitationalEnergy{view(), g_potential_}, n_);
    DeviceVector<double> clump_rotation;
    if (n_clumps_ > 0) { // (the clumps' energies, in place of their members')
      resize(clump_rotation, n_clumps_);
      for_each_index(n_clumps_, ClumpRotationalEnergy{raw(clump_body_), raw(clump_rotation)});
      sums_.add_values(ClumpTranslationalEnergy{raw(clump_body_)}, n_clumps_);
      sums_.add(clump_rotation);
      sums_.add_values(ClumpGravitationalEnergy{raw(clump_body_), g_potential_}, n_clumps_);
    }
    const std::vector<double> kinetic = sums_.collect();
    e.translational = kinetic[0];
    e.rotational = kinetic[1];
    e.gravitational = kinetic[2];
    if (n_clumps_ > 0) {
      e.translational += kinetic[3];
      e.rotational += kinetic[4];
      e.gravitational += kinetic[5];
    }
    // (a clump counts once, its members not)
    e.grains = (n_ == 0 ? 0 : thrust::count(on_device(), raw(kind_), last(kind_), Kind::grain)) -
               static_cast<std::int64_t>(clump_member_.size()) + n_clumps_;
    const auto touching = [](const DeviceVector<std::uint8_t>& open) -> std::int64_t {
      return open.empty() ? 0 : thrust::count_if(on_device(), raw(open), last(open), IsOpen{});
    };
    e.contacts = touching(open_) + touching(plane_open_);
    e.elastic = sums_(elastic_, flagged_) + sums_(plane_elastic_);
    e.relaxation =
        (holds_relaxation ? sums_(relaxation_, flagged_) : 0.0) + sums_(plane_relaxation_);
    e.dissipated = dissipated_total_;
    e.gravity_work = gravity_work_total_;
    e.wall_work = wall_work_total_;
    e.removed = removed_total_;
    e.escaped = escaped_;
    return e;
  }

  std::vector<KeyedState<Whole>> open_contacts() const override {
    std::vector<KeyedState<Whole>> out;
    PairStash stash;
    stash_open_contacts(stash);
    DeviceVector<std::uint64_t> keys;
    DeviceVector<State> states;
    resize(states, stash.keys.size());
    for_each_index(static_cast<std::uint32_t>(stash.keys.size()),
                   StashedState<Kept>{raw(carried_), raw(stash.held), raw(states)});
    std::vector<std::uint64_t> k = to_host(stash.keys);
    std::vector<State> st = to_host(states);
    for (std::size_t c = 0; c < k.size(); ++c)
      out.push_back({static_cast<GlobalId>(k[c] >> 32), static_cast<GlobalId>(k[c] & 0xffffffffu),
                     Kept::whole(st[c])});
    // The grain-plane contacts, keyed as the CPU engine keys them: (grain, -(plane + 1)).
    stash_open_planes(keys, states);
    k = to_host(keys);
    st = to_host(states);
    for (std::size_t c = 0; c < k.size(); ++c)
      out.push_back({static_cast<GlobalId>(k[c] >> 8), -static_cast<GlobalId>(k[c] & 0xffu) - 1,
                     Kept::whole(st[c])});
    return out;
  }

  std::vector<PlaneLoad> plane_loads() const override {
    std::vector<PlaneLoad> loads(n_planes_);
    for (std::uint32_t k = 0; k < n_planes_; ++k) loads[k].work = plane_work_total_[k];
    const std::vector<Vec3> force = to_host(plane_force_);
    const std::vector<std::uint8_t> plane = to_host(plane_of_), open = to_host(plane_open_);
    for (std::size_t c = 0; c < force.size(); ++c) {
      if (!open[c]) continue;
      loads[plane[c]].force -= force[c];
      ++loads[plane[c]].contacts;
    }
    return loads;
  }

  std::int64_t step() const override { return step_; }
  double time() const override { return time_; }
  std::int64_t list_builds() const override { return builds_; }
  DevicePhaseSeconds phase_seconds() const override { return phases_; }

  std::vector<PairEnergy> pair_energies() const override {
    const std::vector<double> elastic = to_host(elastic_);
    const std::vector<std::uint32_t> row = to_host(touch_row_), partner = to_host(partner_),
                                     pair = to_host(touch_pair_);
    const std::vector<std::uint32_t> gid = to_host(gid_);
    std::vector<PairEnergy> out;
    for (std::size_t c = 0; c < flagged_; ++c)
      if (elastic[c] != 0.0) out.push_back({gid[row[c]], gid[partner[pair[c]]], elastic[c]});
    const std::vector<double> plane_elastic = to_host(plane_elastic_);
    const std::vector<std::uint32_t> plane_row = to_host(plane_row_);
    const std::vector<std::uint8_t> plane = to_host(plane_of_);
    for (std::size_t c = 0; c < plane_elastic.size(); ++c)
      if (plane_elastic[c] != 0.0)
        out.push_back({gid[plane_row[c]], -static_cast<GlobalId>(plane[c]) - 1, plane_elastic[c]});
    return out;
  }
  std::size_t listed_pairs() const override { return partner_.size(); }

  DeviceMemory device_memory() const override {
    DeviceMemory m;
    m.particles = bytes_of(x_, v_, w_, x_build_, x_rest_, species_, species_of_, gid_, kind_,
                           material_, motion_, tally_, given_force_, given_torque_);
    m.cells = bytes_of(cell_start_);
    m.pairs = bytes_of(row_start_, partner_, image_, reverse_start_, reverse_pair_, open_, slot_);
    m.contacts = bytes_of(carried_, states_, touch_pair_, touch_row_, force_, torque_i_, torque_j_,
                          elastic_, relaxation_, dissipated_, wall_work_);
    m.planes = bytes_of(plane_point_, plane_normal_, plane_material_, plane_excursion_,
                        plane_offset_, plane_velocity_, plane_start_, plane_row_, plane_of_,
                        plane_state_, plane_open_, plane_force_, plane_torque_, plane_elastic_,
                        plane_relaxation_, plane_dissipated_, plane_work_);
    m.clumps =
        bytes_of(clump_body_, clump_frame_, clump_member_, body_of_, clump_force_, clump_torque_);
    m.work = bytes(sums_first_) + sums_.device_bytes() + step_sums_.device_bytes() +
             scratch().bytes() + bytes_of(coeffs_, too_wide_);
    m.peak = held().most - held_before_;
    return m;
  }

  std::string device_name() const override {
#if defined(__CUDACC__)
    int device = 0;
    cudaDeviceProp prop{};
    if (cudaGetDevice(&device) == cudaSuccess &&
        cudaGetDeviceProperties(&prop, device) == cudaSuccess)
      return std::string("cuda: ") + prop.name;
    return "cuda";
#else
    return "host (Thrust CPP)";
#endif
  }

private:
  Particles view() const {
    // The functors write through these pointers; the engine owns the arrays.
    auto& self = const_cast<Engine&>(*this);
    return Particles{raw(self.x_),
                     raw(self.v_),
                     raw(self.w_),
                     raw(self.x_build_),
                     raw(species_),
                     species_of_.empty() ? nullptr : raw(species_of_),
                     raw(gid_),
                     raw(kind_),
                     raw(material_),
                     body_of_.empty() ? nullptr : raw(body_of_),
                     n_};
  }
  ClumpSet clump_set() const {
    auto& self = const_cast<Engine&>(*this);
    return ClumpSet{raw(self.clump_body_), raw(clump_frame_), raw(self.clump_member_), n_clumps_};
  }
  // Each particle's force (or torque) summed from the contacts on the device, brought to the
  // host a sixteenth at a time: an output step holds 1.5 bytes a particle more, not 24.
  std::vector<Vec3> loads(bool torque) const {
    std::vector<Vec3> out(n_);
    const std::uint32_t part = std::max<std::uint32_t>(65536, n_ / 16 + 1);
    DeviceVector<Vec3> load(std::min(part, n_));
    for (std::uint32_t first = 0; first < n_; first += part) {
      const std::uint32_t m = std::min(part, n_ - first);
      for_each_index(m, WriteLoads{view(), grain_loads(), first, torque, raw(load)});
      thrust::copy_n(load.begin(), m, out.begin() + first);
    }
    return out;
  }
  // The sums of the forces on the grains from what the last evaluation's contacts gave.
  GrainLoads grain_loads() const {
    auto& self = const_cast<Engine&>(*this);
    return GrainLoads{pair_list(),       self.pair_output(),  raw(open_), raw(slot_),
                      raw(plane_start_), self.plane_output(), gravity_};
  }
  PairList pair_list() const {
    return PairList{raw(row_start_),     raw(partner_),      raw(image_),
                    raw(reverse_start_), raw(reverse_pair_), n_};
  }
  PlaneSet plane_set() const {
    return PlaneSet{raw(plane_point_),
                    raw(plane_normal_),
                    raw(plane_material_),
                    raw(plane_excursion_),
                    raw(plane_offset_),
                    raw(plane_velocity_),
                    n_planes_};
  }
  PlaneOutput plane_output() {
    return PlaneOutput{raw(plane_force_),      raw(plane_torque_),     raw(plane_elastic_),
                       raw(plane_relaxation_), raw(plane_dissipated_), raw(plane_work_)};
  }
  // (relaxation and wall_work null where the law holds none or no wall particle moves)
  PairOutput pair_output() {
    return PairOutput{raw(force_),
                      raw(torque_i_),
                      raw(torque_j_),
                      raw(elastic_),
                      holds_relaxation ? raw(relaxation_) : nullptr,
                      raw(dissipated_),
                      walls_work_ ? raw(wall_work_) : nullptr};
  }

  // v holds exactly n elements afterwards, of unspecified values (particles only ever grow
  // fewer: room to grow would be wasted).
  template <class T> static void exact_size(DeviceVector<T>& v, std::size_t n) {
    if (v.capacity() == n)
      v.resize(n);
    else
      DeviceVector<T>(n).swap(v);
  }

  // The particles' radii, masses and inertias, as a table of species shared by index where at
  // most 65,536 distinct ones are at most half the particles; otherwise one per particle.
  void take_species(const HostParticles& hp) {
    std::vector<Species> table;
    std::vector<std::uint16_t> index;
    std::map<std::array<std::uint64_t, 4>, std::uint16_t> seen; // by their bits
    const std::size_t most = std::min<std::size_t>(65536, hp.size() / 2);
    const auto species_at = [&](std::size_t i) {
      return Species{hp.radius[i], hp.mass[i], hp.inv_mass[i], hp.inv_inertia[i]};
    };
    for (std::size_t i = 0; i < hp.size(); ++i) {
      const Species s = species_at(i);
      const std::array<std::uint64_t, 4> bits{
          std::bit_cast<std::uint64_t>(s.radius), std::bit_cast<std::uint64_t>(s.mass),
          std::bit_cast<std::uint64_t>(s.inv_mass), std::bit_cast<std::uint64_t>(s.inv_inertia)};
      const auto [at, added] = seen.emplace(bits, static_cast<std::uint16_t>(table.size()));
      if (added) {
        if (table.size() == most) break;
        table.push_back(s);
      }
      index.push_back(at->second);
    }
    if (index.size() == hp.size() && !index.empty()) {
      species_ = table;
      species_of_ = index;
      return;
    }
    table.clear();
    for (std::size_t i = 0; i < hp.size(); ++i) table.push_back(species_at(i));
    species_of_.clear();
    if (!table.empty()) species_ = table; // (assigned only when not empty: see resize())
  }

  // The scene's clumps: their bodies, their members' frames, and each particle's clump, checked
  // against one another (every member a grain of its clump, each member once).
  void take_clumps(const DeviceScene& scene) {
    const HostParticles& hp = scene.particles;
    const auto refuse = [](const std::string& what) {
      throw std::invalid_argument("device engine: " + what);
    };
    if (scene.clumps.empty()) {
      for (const GlobalId b : hp.body)
        if (b >= 0) refuse("a particle names clump " + std::to_string(b) + ", which is not here");
      return;
    }
    if (hp.body.size() != hp.size())
      refuse(std::to_string(hp.body.size()) + " clump ids for " + std::to_string(hp.size()) +
             " particles");
    if (scene.clumps.size() >= (std::size_t{1} << 31)) refuse("2^31 clumps or more");
    std::vector<RigidBody> bodies;
    std::vector<Vec3> frame, force, torque;
    for (const DeviceClump& c : scene.clumps) {
      if (!bodies.empty() && !(GlobalId{bodies.back().gid} < c.id))
        refuse("clump ids must ascend and differ (clump " + std::to_string(c.id) + ")");
      if (c.id < 0 || c.id + static_cast<GlobalId>(c.members.size()) > (GlobalId{1} << 32))
        refuse("a clump's ids beyond 32 bits (clump " + std::to_string(c.id) + ")");
      if (c.members.empty() || !(c.mass > 0) || !(c.inertia.x > 0) || !(c.inertia.y > 0) ||
          !(c.inertia.z > 0))
        refuse("clump " + std::to_string(c.id) +
               " has no members, or no positive mass and moments");
      RigidBody& b = bodies.emplace_back();
      b.x = c.x;
      b.v = c.v;
      b.q = c.q;
      b.p = c.p;
      b.omega = lab_angular_velocity(c.q, c.p, c.inertia);
      b.inertia = c.inertia;
      b.mass = c.mass;
      b.first = static_cast<std::uint32_t>(frame.size());
      b.count = static_cast<std::uint32_t>(c.members.size());
      b.gid = static_cast<std::uint32_t>(c.id);
      frame.insert(frame.end(), c.members.begin(), c.members.end());
      force.push_back(c.force);
      torque.push_back(c.torque);
    }
    constexpr auto missing = no_body;
    std::vector<std::uint32_t> body_of(hp.size(), no_body), member(frame.size(), missing);
    for (std::size_t i = 0; i < hp.size(); ++i) {
      if (hp.body[i] < 0) continue;
      const auto at = std::lower_bound(scene.clumps.begin(), scene.clumps.end(), hp.body[i],
                                       [](const DeviceClump& c, GlobalId id) { return c.id < id; });
      if (at == scene.clumps.end() || at->id != hp.body[i])
        refuse("particle " + std::to_string(hp.gid[i]) + " names clump " +
               std::to_string(hp.body[i]) + ", which is not here");
      const auto c = static_cast<std::uint32_t>(at - scene.clumps.begin());
      const GlobalId k = hp.gid[i] - at->id;
      if (hp.kind[i] != Kind::grain || k < 0 || k >= static_cast<GlobalId>(at->members.size()) ||
          member[bodies[c].first + k] != missing)
        refuse("particle " + std::to_string(hp.gid[i]) + " is no member of clump " +
               std::to_string(at->id) + " (" + std::to_string(at->members.size()) +
               " members, ids " + std::to_string(at->id) + " on)");
      body_of[i] = c;
      member[bodies[c].first + static_cast<std::uint32_t>(k)] = static_cast<std::uint32_t>(i);
    }
    for (const RigidBody& b : bodies)
      for (std::uint32_t k = 0; k < b.count; ++k)
        if (member[b.first + k] == missing)
          refuse("member " + std::to_string(k) + " (particle " + std::to_string(b.gid + k) +
                 ") of clump " + std::to_string(b.gid) + " is missing");
    n_clumps_ = static_cast<std::uint32_t>(bodies.size());
    clump_body_ = bodies;
    clump_frame_ = frame;
    clump_member_ = member;
    body_of_ = body_of;
    clump_force_ = force; // (made the start's own by gather_clump_loads() where not given)
    clump_torque_ = torque;
  }

  // Each clump's load from what its members' contacts gave at the last evaluation.
  void gather_clump_loads() {
    for_each_index(n_clumps_, GatherClumpLoads{clump_set(), grain_loads(), raw(clump_force_),
                                               raw(clump_torque_)});
  }

  // The clumps' kicks (one or two half kicks, then the drift if `drift`) under their kept
  // loads, and their members placed (positions too where moved_far is given).
  void move_clumps(int kicks, bool drift, double limit2, std::uint32_t* moved_far) {
    if (n_clumps_ == 0) return;
    for_each_index(n_clumps_, KickClumps{clump_set(), raw(clump_force_), raw(clump_torque_), dt_,
                                         kicks, drift});
    if (drift) { // NO_SQUISH's free rotation, a pass a turn (TurnClumps)
      const double half_dt = 0.5 * dt_;
      for_each_index(n_clumps_, TurnClumps{clump_set(), 3, half_dt, false});
      for_each_index(n_clumps_, TurnClumps{clump_set(), 2, half_dt, false});
      for_each_index(n_clumps_, TurnClumps{clump_set(), 1, dt_, false});
      for_each_index(n_clumps_, TurnClumps{clump_set(), 2, half_dt, false});
      for_each_index(n_clumps_, TurnClumps{clump_set(), 3, half_dt, true});
    }
    for_each_index(n_, PlaceMembers{view(), clump_set(), limit2, moved_far});
  }

  // field[k] = field[order[k]], through scratch; field holds exactly what it needs afterwards
  // (the particles only ever grow fewer: room to grow would be wasted).
  template <class T>
  static void permute_by(const DeviceVector<std::uint32_t>& order, DeviceVector<T>& field,
                         DeviceVector<T>& scratch) {
    exact_size(scratch, order.size());
    thrust::gather(on_device(), raw(order), last(order), raw(field), raw(scratch));
    field.swap(scratch);
  }
  // The same through a scratch array of its own, freed on return.
  template <class T>
  static void permute_by(const DeviceVector<std::uint32_t>& order, DeviceVector<T>& field) {
    DeviceVector<T> scratch;
    permute_by(order, field, scratch);
  }
  // Drops the grains outside the box along an open axis (or stops the run, as the scene says).
  // A clump leaves whole, with the first of its members out.
  void remove_escaped() {
    DeviceVector<std::uint32_t> gone(n_);
    DeviceVector<double> energy(n_);
    for_each_index(n_, Escaped{view(), box_, g_potential_, raw(gone), raw(energy)});
    DeviceVector<std::uint32_t> clump_gone;
    DeviceVector<double> clump_energy;
    if (n_clumps_ > 0) {
      resize_all(n_clumps_, clump_gone, clump_energy);
      for_each_index(n_clumps_, ClumpEscaped{clump_set(), raw(gone), g_potential_, raw(clump_gone),
                                             raw(clump_energy)});
      for_each_index(n_, MembersLeave{view(), raw(clump_gone), raw(gone)});
    }
    const std::uint32_t n_gone =
        thrust::reduce(on_device(), raw(gone), last(gone), std::uint32_t{0});
    if (n_gone == 0) return;
    if (!remove_escaped_) {
      const auto count = [](std::uint32_t k, const std::string& thing) {
        return std::to_string(k) + " " + thing + (k == 1 ? "" : "s");
      };
      std::string what = count(n_gone, "grain");
      if (n_clumps_ > 0) { // (a clump counts once, its members not)
        const std::vector<std::uint32_t> flag = to_host(clump_gone);
        const std::vector<RigidBody> bodies = to_host(clump_body_);
        std::uint32_t clumps = 0, members = 0;
        for (std::uint32_t c = 0; c < n_clumps_; ++c)
          if (flag[c]) ++clumps, members += bodies[c].count;
        what = count(n_gone - members, "grain") + " and " + count(clumps, "clump");
      }
      throw std::runtime_error("device engine: " + what +
                               " left the box through an open face at step " +
                               std::to_string(step_) + " (on_escape = \"stop\")");
    }
    removed_total_ += sums_(energy);
    escaped_ += n_gone;
    if (n_clumps_ > 0) {
      removed_total_ += sums_(clump_energy);
      escaped_ -= remove_clumps(clump_gone); // (a clump counts once, its members not)
    }
    DeviceVector<std::uint32_t> keep(n_ - n_gone);
    thrust::copy_if(on_device(), thrust::counting_iterator<std::uint32_t>(0),
                    thrust::counting_iterator<std::uint32_t>(n_), raw(gone), raw(keep), IsZero{});
    permute_particles(keep);
    n_ -= n_gone;
    resize(tally_, n_ + 1);
  }

  // The clumps flagged in `gone` taken out (a rare event, done on the host), the others
  // renumbered in order with their loads, their members still among the particles (they leave
  // next); returns how many members left, less how many clumps.
  std::int64_t remove_clumps(const DeviceVector<std::uint32_t>& gone) {
    const std::vector<std::uint32_t> flag = to_host(gone);
    const std::vector<RigidBody> bodies = to_host(clump_body_);
    const std::vector<Vec3> frame = to_host(clump_frame_);
    std::vector<RigidBody> kept;
    std::vector<Vec3> kept_frame;
    std::vector<std::uint32_t> renumber(n_clumps_, no_body);
    std::vector<Vec3> force, torque;
    const std::vector<Vec3> last_force = to_host(clump_force_),
                            last_torque = to_host(clump_torque_);
    std::int64_t members = 0, clumps = 0;
    for (std::uint32_t c = 0; c < n_clumps_; ++c) {
      if (flag[c]) {
        members += bodies[c].count;
        ++clumps;
        continue;
      }
      renumber[c] = static_cast<std::uint32_t>(kept.size());
      RigidBody b = bodies[c];
      b.first = static_cast<std::uint32_t>(kept_frame.size());
      kept_frame.insert(kept_frame.end(), frame.begin() + bodies[c].first,
                        frame.begin() + bodies[c].first + bodies[c].count);
      kept.push_back(b);
      force.push_back(last_force[c]);
      torque.push_back(last_torque[c]);
    }
    const DeviceVector<std::uint32_t> device_renumber = renumber;
    for_each_index(n_, RenumberClumps{raw(device_renumber), raw(body_of_)});
    n_clumps_ = static_cast<std::uint32_t>(kept.size());
    const auto assign = [](auto& to, const auto& from) {
      using V = std::remove_reference_t<decltype(to)>;
      V fresh;
      if (!from.empty()) V(from.begin(), from.end()).swap(fresh); // (see resize())
      fresh.swap(to);
    };
    assign(clump_body_, kept);
    assign(clump_frame_, kept_frame);
    assign(clump_force_, force);
    assign(clump_torque_, torque);
    exact_size(clump_member_, kept_frame.size()); // (remapped with the particles' new order)
    return members - clumps;
  }

  // Every per-particle array reordered (and cut to order's length): array[k] = array[order[k]].
  // The clumps' members are found again in the new order.
  void permute_particles(const DeviceVector<std::uint32_t>& order) {
    // The vectors through x_build_ as their scratch (no array more): the list's reference
    // positions are where the particles stand at a build, x_ copied in afterwards.
    for (DeviceVector<Vec3>* field : {&x_, &v_, &w_}) permute_by(order, *field, x_build_);
    if (!given_force_.empty()) {
      permute_by(order, given_force_, x_build_);
      permute_by(order, given_torque_, x_build_);
    }
    if (moving_walls_) permute_by(order, x_rest_, x_build_);
    if (!x_now_.empty()) permute_by(order, x_now_, x_build_);
    exact_size(x_build_, order.size());
    if (!x_.empty()) // (none left: every grain gone; a copy of nothing from null trips UBSan)
      thrust::copy(on_device(), raw(x_), last(x_), raw(x_build_));
    if (species_of_.empty())
      permute_by(order, species_);
    else
      permute_by(order, species_of_);
    permute_by(order, gid_);
    permute_by(order, kind_);
    permute_by(order, material_);
    permute_by(order, motion_);
    if (!body_of_.empty()) {
      permute_by(order, body_of_);
      Particles p = view();
      p.n = static_cast<std::uint32_t>(order.size());
      for_each_index(p.n, RemapMembers{p, clump_set()});
    }
  }

  // Open contacts' keys in ascending order, and their states: carried across a list build.
  struct Stash {
    DeviceVector<std::uint64_t> keys;
    DeviceVector<State> states;
  };
  static Stash stash_of(std::vector<std::pair<std::uint64_t, State>> open) {
    std::sort(open.begin(), open.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<std::uint64_t> keys(open.size());
    std::vector<State> states(open.size());
    for (std::size_t k = 0; k < open.size(); ++k) {
      keys[k] = open[k].first;
      states[k] = open[k].second;
    }
    Stash stash;
    if (!keys.empty()) { // (assigned only when not empty: see resize())
      stash.keys = keys;
      stash.states = states;
    }
    return stash;
  }

  // The open contacts between particles, keys ascending, each with where its state is
  // (StashContact): the states stay in their slots of the last evaluation through a list build.
  struct PairStash {
    DeviceVector<std::uint64_t> keys;
    DeviceVector<std::uint32_t> held;
  };
  // The contacts a run starts with (keys, and states seen from the smaller id): their states
  // made the carried ones, in key order.
  PairStash stash_start(std::vector<std::pair<std::uint64_t, State>> open) {
    Stash sorted = stash_of(std::move(open));
    PairStash stash;
    if (sorted.keys.empty()) return stash;
    stash.keys.swap(sorted.keys);
    carried_.swap(sorted.states);
    resize(stash.held, stash.keys.size());
    thrust::sequence(on_device(), raw(stash.held), last(stash.held));
    return stash;
  }

  // A list build in a step: the open contacts stashed, then the list built afresh.
  void build_list() {
    PairStash pairs;
    Stash planes;
    stash_open_contacts(pairs);
    stash_open_planes(planes.keys, planes.states);
    build_list(pairs, planes, true);
  }

  // The indices of the open contacts' flags in `open` (IsOpen), in order.
  static DeviceVector<std::uint32_t> set_indices(const DeviceVector<std::uint8_t>& open) {
    const std::uint32_t n = static_cast<std::uint32_t>(open.size());
    DeviceVector<std::uint32_t> at(n);
    const std::uint32_t n_set = static_cast<std::uint32_t>(
        thrust::copy_if(on_device(), thrust::counting_iterator<std::uint32_t>(0),
                        thrust::counting_iterator<std::uint32_t>(n), raw(open), raw(at), IsOpen{}) -
        raw(at));
    // (a copy of the first n_set: resize() keeps no values)
    DeviceVector<std::uint32_t> set;
    if (n_set > 0) DeviceVector<std::uint32_t>(at.begin(), at.begin() + n_set).swap(set);
    return set;
  }

  // Sorts `keys` and carries `states` along (through an index: a state can be too large to ride
  // in the sort itself, radix sort keeping its values in shared memory).
  static void sort_stash(DeviceVector<std::uint64_t>& keys, DeviceVector<State>& states) {
    DeviceVector<std::uint32_t> by_key(keys.size());
    thrust::sequence(on_device(), raw(by_key), last(by_key));
    sort_by_key(raw(keys), last(keys), raw(by_key));
    DeviceVector<State> scratch;
    permute_by(by_key, states, scratch);
  }

  // The open grain-plane contacts' keys in ascending order, and their states.
  void stash_open_planes(DeviceVector<std::uint64_t>& keys, DeviceVector<State>& stashed) const {
    const DeviceVector<std::uint32_t> open = set_indices(plane_open_);
    const std::uint32_t n_open = static_cast<std::uint32_t>(open.size());
    resize(keys, n_open);
    resize(stashed, n_open);
    for_each_index(n_open, StashPlane<Kept>{view(), raw(plane_row_), raw(plane_of_),
                                            raw(plane_state_), raw(open), raw(keys), raw(stashed)});
    sort_stash(keys, stashed);
  }

  // The open contacts' keys (the particles' global ids) in ascending order, and where their
  // states are.
  void stash_open_contacts(PairStash& stash) const {
    const DeviceVector<std::uint32_t> open_pairs = set_indices(open_);
    const std::uint32_t n_open = static_cast<std::uint32_t>(open_pairs.size());
    resize(stash.keys, n_open);
    resize(stash.held, n_open);
    for_each_index(n_open, StashContact{view(), pair_list(), raw(slot_), raw(open_pairs),
                                        raw(stash.keys), raw(stash.held)});
    sort_by_key(raw(stash.keys), last(stash.keys), raw(stash.held));
  }

  // The counts in v[0, n) become their offsets in place: v[i] = count[0] + ... + count[i - 1]
  // for i in [0, n]; returns the total, v[n]. v holds n + 1.
  static std::uint32_t counts_to_offsets(DeviceVector<std::uint32_t>& v, std::uint32_t n) {
    write_one(v, n, std::uint32_t{0});
    thrust::exclusive_scan(on_device(), raw(v), raw(v) + n + 1, raw(v));
    return read_one(v, n);
  }

  // Escapes, the cell sort, the list and the grain-plane candidates, with the open contacts
  // (`pairs`, `planes`) taken back by their new pairs and candidates. In a step (not at the
  // start, as Simulation::build_lists), the clumps' centres wrap into the periodic box.
  void build_list(const PairStash& pairs, const Stash& planes, bool in_step) {
    const std::uint32_t n_stashed = static_cast<std::uint32_t>(pairs.keys.size());
    // 1. Grains that left through an open face stop the run, or leave it with their mechanical
    // energy booked as removed (Simulation::handle_escapes_here).
    remove_escaped();
    if (in_step && n_clumps_ > 0) for_each_index(n_clumps_, WrapClumps{view(), clump_set(), box_});

    // 2. Wrap, sort by (cell, global id), and find each cell's start.
    DeviceVector<std::uint64_t> key(n_);
    for_each_index(n_, CellOfParticle{view(), box_, cells_, raw(key)});
    // (the key and order live for the build only: the steps between builds need none)
    {
      DeviceVector<std::uint32_t> order(n_);
      thrust::sequence(on_device(), raw(order), last(order));
      sort_by_key(raw(key), last(key), raw(order));
      resize(cell_start_, cells_.count() + 1);
      const auto first_keys = thrust::make_transform_iterator(
          thrust::counting_iterator<std::uint32_t>(0), FirstKeyOfCell{});
      thrust::lower_bound(on_device(), raw(key), last(key), first_keys,
                          first_keys + (cells_.count() + 1), raw(cell_start_));
      DeviceVector<std::uint64_t>().swap(key);
      permute_particles(order); // (the sort's key freed before: the permutation needs room)
    }

    // 3. The half list: count (into the rows' starts), offsets, fill.
    resize(row_start_, n_ + 1);
    // (the cells hold clumps' members at their wrapped places: an array for the build alone)
    DeviceVector<Vec3> in_cells;
    if (n_clumps_ > 0) {
      resize(in_cells, n_);
      for_each_index(n_, PlaceInCells{view(), box_, raw(in_cells)});
    }
    FindPartners find{view(),
                      n_clumps_ > 0 ? raw(in_cells) : raw(x_),
                      box_,
                      cells_,
                      raw(cell_start_),
                      skin_,
                      raw(row_start_),
                      nullptr,
                      nullptr,
                      nullptr};
    for_each_index(n_, find);
    const std::uint32_t total = counts_to_offsets(row_start_, n_);
    resize_all(total, partner_, image_);
    find.count = nullptr;
    find.out_start = raw(row_start_);
    find.partner = raw(partner_);
    find.image = raw(image_);
    for_each_index(n_, find);
    if (n_clumps_ > 0) {
      DeviceVector<Vec3>().swap(in_cells);
      for_each_index(n_, MemberImages{view(), pair_list(), box_, raw(image_), raw(too_wide_)});
      if (read_one(too_wide_, 0) != 0)
        throw std::runtime_error(
            "device engine: a clump's member and a particle near it stand more than one periodic "
            "box length apart across the box: a clump spans about the periodic box's length, or "
            "a member's place is not finite");
    }

    // 4. Each particle's pairs as the partner, in pair order.
    DeviceVector<std::uint32_t> partner_sorted = partner_;
    resize(reverse_pair_, total);
    thrust::sequence(on_device(), raw(reverse_pair_), last(reverse_pair_));
    sort_by_key(raw(partner_sorted), last(partner_sorted), raw(reverse_pair_));
    resize(reverse_start_, n_ + 1);
    thrust::lower_bound(on_device(), raw(partner_sorted), last(partner_sorted),
                        thrust::counting_iterator<std::uint32_t>(0),
                        thrust::counting_iterator<std::uint32_t>(n_ + 1), raw(reverse_start_));

    // 5. Per-pair room, and the open contacts back in their new pairs: each pair takes its
    // state's slot, where the next evaluation carries it from (GatherTouches).
    resize_all(total, open_, slot_);
    for_each_index(n_, RestoreContact<Kept>{view(), pair_list(), raw(pairs.keys), raw(pairs.held),
                                            n_stashed, raw(carried_), raw(slot_), raw(open_)});

    // 6. The grain-plane candidates (count, offsets, fill), with their open contacts' states.
    resize(plane_start_, n_ + 1);
    FindPlanes find_planes{view(),  plane_set(), skin_,  raw(plane_start_),
                           nullptr, nullptr,     nullptr};
    for_each_index(n_, find_planes);
    const std::uint32_t candidates = counts_to_offsets(plane_start_, n_);
    resize_all(candidates, plane_row_, plane_of_);
    find_planes.count = nullptr;
    find_planes.start = raw(plane_start_);
    find_planes.row = raw(plane_row_);
    find_planes.plane = raw(plane_of_);
    for_each_index(n_, find_planes);
    resize_all(candidates, plane_state_, plane_open_, plane_force_, plane_torque_, plane_elastic_,
               plane_relaxation_, plane_dissipated_, plane_work_);
    for_each_index(candidates, RestorePlane<Kept>{view(), raw(plane_row_), raw(plane_of_),
                                                  raw(planes.keys), raw(planes.states),
                                                  static_cast<std::uint32_t>(planes.keys.size()),
                                                  raw(plane_state_), raw(plane_open_)});
    ++builds_;
    scratch().trim(); // the sorts' temporary storage: the steps until the next build need little
  }

  void compute_forces(double dt) {
    // The pairs that touch or have just come apart, flagged and counted by row (FindTouches),
    // gathered into this step's slots with their states (GatherTouches), then their laws.
    for_each_index(n_, FindTouches{view(), pair_list(), box_, raw(open_), raw(tally_)});
    flagged_ = counts_to_offsets(tally_, n_); // (each row's count becomes its first slot)
    make_room_all(flagged_, touch_pair_, touch_row_, states_, force_, torque_i_, torque_j_,
                  elastic_, dissipated_);
    if (holds_relaxation) make_room(relaxation_, flagged_);
    if (walls_work_) make_room(wall_work_, flagged_);
    for_each_index(n_, GatherTouches<Kept>{pair_list(), raw(open_), raw(tally_), raw(carried_),
                                           raw(states_), raw(slot_), raw(touch_pair_),
                                           raw(touch_row_)});
    for_each_index(flagged_, PairForces<Kept>{view(), pair_list(), box_, raw(coeffs_), n_materials_,
                                              dt, raw(states_), raw(open_), raw(touch_pair_),
                                              raw(touch_row_), pair_output()});
    carried_.swap(states_); // this evaluation's states, for the next
    for_each_index(static_cast<std::uint32_t>(plane_row_.size()),
                   PlaneForces<Kept>{view(), plane_set(), raw(plane_row_), raw(plane_of_),
                                     raw(coeffs_), n_materials_, dt, raw(plane_state_),
                                     raw(plane_open_), plane_output()});
  }

  // One step. The last of a run ends with the final kick alone; the others end with the next
  // step's first kick and drift too (FinalKick), which sum the forces once for both.
  void step_once(bool last) {
    PhaseClock clock;
    const double limit2 = 0.25 * skin_ * skin_;
    if (!drifted_) {
      const bool given = !given_force_.empty();
      for_each_index(n_, KickDrift{view(), grain_loads(), given ? raw(given_force_) : nullptr,
                                   given ? raw(given_torque_) : nullptr, dt_, limit2, raw(tally_)});
      move_clumps(1, true, limit2, raw(tally_)); // (under the loads of the last evaluation)
    }
    drifted_ = false;
    time_ += dt_;
    ++step_;
    place_walls();
    if (any_oscillating_) place_planes(); // (still planes stay where the start put them)
    const bool build = thrust::reduce(on_device(), raw(tally_), raw(tally_) + n_, std::uint32_t{0},
                                      thrust::maximum<std::uint32_t>()) != 0;
    clock.add_to(phases_.integration);
    // (queued: collected with the contacts' books below; read now, before the final kick)
    step_sums_.add_values(GravityWork{view(), g_periodic_, dt_}, n_);
    // (queued now, collected below: a list build between may take the last clumps away)
    const bool clumps_worked = n_clumps_ > 0;
    if (clumps_worked)
      step_sums_.add_values(ClumpGravityWork{raw(clump_body_), g_periodic_, dt_}, n_clumps_);
    clock.add_to(phases_.books);
    if (build) build_list();
    clock.add_to(phases_.list_build);
    compute_forces(dt_);
    // (the forces a run continued with, until the contacts hold their own: kept for particles()
    // should this first step stop before)
    DeviceVector<Vec3>().swap(given_force_);
    DeviceVector<Vec3>().swap(given_torque_);
    clock.add_to(phases_.forces);
    for_each_index(n_, FinalKick{view(), grain_loads(), dt_, limit2, last ? nullptr : raw(tally_)});
    if (n_clumps_ > 0) {
      gather_clump_loads();
      move_clumps(last ? 1 : 2, !last, limit2, last ? nullptr : raw(tally_));
    }
    drifted_ = !last;
    clock.add_to(phases_.integration);
    step_sums_.add(dissipated_, flagged_);
    step_sums_.add(plane_dissipated_);
    if (walls_work_) step_sums_.add(wall_work_, flagged_);
    const std::vector<double> booked = step_sums_.collect();
    std::size_t next = 0;
    gravity_work_total_ += booked[next++];
    if (clumps_worked) gravity_work_total_ += booked[next++];
    dissipated_total_ += booked[next++];
    dissipated_total_ += booked[next++];
    if (walls_work_) wall_work_total_ += booked[next++];
    if (any_oscillating_) book_plane_work();
    clock.add_to(phases_.books);
  }

  // Each plane's offset and velocity at time_ (on the host: DevicePlane::offset, velocity).
  void place_planes() {
    if (n_planes_ == 0) return;
    std::vector<double> offset(n_planes_);
    std::vector<Vec3> velocity(n_planes_);
    for (std::uint32_t k = 0; k < n_planes_; ++k) {
      offset[k] = planes_[k].offset(time_);
      velocity[k] = planes_[k].velocity(time_);
    }
    thrust::copy(offset.begin(), offset.end(), plane_offset_.begin());
    thrust::copy(velocity.begin(), velocity.end(), plane_velocity_.begin());
  }

  // The oscillating planes' work this step: in all (the books) and per plane (walls.csv).
  void book_plane_work() {
    wall_work_total_ += sums_(plane_work_);
    const std::uint32_t candidates = static_cast<std::uint32_t>(plane_work_.size());
    DeviceVector<double> share(candidates);
    for (std::uint32_t k = 0; k < n_planes_; ++k) {
      if (planes_[k].amplitude == 0.0) continue;
      for_each_index(candidates, OfPlane{raw(plane_work_), raw(plane_of_), k, raw(share)});
      plane_work_total_[k] += sums_(share);
    }
  }

  // The wall particles of each started motion at time_ (RadialCosineMotion::at_time, on the
  // host: the same sine and cosine for every backend).
  void place_walls() {
    PlaceWalls place{view(), raw(x_rest_), raw(motion_), {}, 0.25 * skin_ * skin_, raw(tally_)};
    bool any = false;
    for (std::size_t k = 0; k < motions_.size(); ++k) {
      const DeviceMotion& m = motions_[k];
      if (!m.radial_cosine || time_ < m.t0) continue;
      const double phase = m.omega * (time_ - m.t0);
      place.now[k] = MotionNow{true, m.center, std::abs(m.mode), m.amplitude * std::sin(phase),
                               m.omega * m.amplitude * std::cos(phase)};
      any = true;
    }
    if (any) for_each_index(n_, place);
  }

  // What this thread's engines held on the device when this one started; the most held since
  // counts from here (first of the members: before any array is made).
  std::size_t held_before_ = [] {
    held().most = held().now;
    return held().now;
  }();
  std::uint32_t n_ = 0, n_materials_ = 1;
  DeviceVector<Vec3> x_, v_, w_, x_build_;
  // The forces and torques a run continued mid-way came with, until its first step's forces.
  DeviceVector<Vec3> given_force_, given_torque_;
  // The step's first kick and drift are done (by the last step's FinalKick): tally_ holds the
  // moved-far flags.
  bool drifted_ = false;
  DeviceVector<Vec3> x_now_; // while the start's list is made again: where the particles stand
  // The clumps (clump_phases.hpp): their bodies; per member slot, the member's centre in the
  // principal frame and its particle's index; per particle, its clump or no_body (empty: no
  // clumps); per clump, its load at the last evaluation (given with a run continued mid-way).
  std::uint32_t n_clumps_ = 0;
  DeviceVector<RigidBody> clump_body_;
  DeviceVector<Vec3> clump_frame_;
  DeviceVector<std::uint32_t> clump_member_, body_of_;
  DeviceVector<Vec3> clump_force_, clump_torque_;
  // Set by a list build that found a pair farther apart than one periodic image (MemberImages).
  DeviceVector<std::uint32_t> too_wide_ = DeviceVector<std::uint32_t>(1, 0u);
  // The still planes, and the grain-plane candidates of the last list build (per candidate: its
  // grain, its plane, the contact's state, whether it is open, and what it gave this step).
  std::uint32_t n_planes_ = 0;
  DeviceVector<Vec3> plane_point_, plane_normal_;
  DeviceVector<std::uint8_t> plane_material_;
  DeviceVector<std::uint32_t> plane_start_, plane_row_;
  DeviceVector<std::uint8_t> plane_of_, plane_open_;
  DeviceVector<State> plane_state_;
  DeviceVector<Vec3> plane_force_, plane_torque_;
  DeviceVector<double> plane_elastic_, plane_relaxation_, plane_dissipated_, plane_work_;
  // Each plane's largest excursion, its offset and velocity now, and (host) its description and
  // cumulative work.
  DeviceVector<double> plane_excursion_, plane_offset_;
  DeviceVector<Vec3> plane_velocity_;
  std::vector<DevicePlane> planes_;
  std::vector<double> plane_work_total_;
  bool any_oscillating_ = false;
  bool moving_walls_ = false; // a wall particle moves: x_rest_ is kept
  bool walls_work_ = false;   // a wall particle moves or has a velocity: wall_work_ is kept
  // The law's contacts hold energy in a relaxation buffer: relaxation_ is kept.
  static constexpr bool holds_relaxation = requires {
    requires Model::holds_relaxation;
  };
  // The particles' species (Particles): a table and each particle's index in it, or (where they
  // are too many to share) one species per particle and no index.
  DeviceVector<Species> species_;
  DeviceVector<std::uint16_t> species_of_;
  DeviceVector<std::uint32_t> gid_; // (ids beyond 32 bits are refused)
  DeviceVector<Kind> kind_;
  DeviceVector<std::uint8_t> material_;
  DeviceVector<std::uint32_t> cell_start_;
  DeviceVector<std::uint32_t> row_start_, partner_, reverse_start_, reverse_pair_;
  DeviceVector<std::uint8_t> image_;
  DeviceVector<State> carried_, states_;   // per slot: the last evaluation's, this one's
  DeviceVector<std::uint8_t> open_;        // per pair: FindTouches's flag
  DeviceVector<std::uint32_t> slot_;       // per pair: its slot among the flagged
  DeviceVector<std::uint32_t> touch_pair_; // per slot: the flagged pairs, in pair order
  DeviceVector<std::uint32_t> touch_row_;  // per slot: the flagged pair's row
  std::uint32_t flagged_ = 0;              // how many pairs are flagged: the per-slot arrays' count
  DeviceVector<Vec3> force_, torque_i_, torque_j_;
  DeviceVector<double> elastic_, relaxation_, dissipated_;
  // Per particle and one more, a step's scratch: whether the particle moved more than half the
  // skin (KickDrift, PlaceWalls: the list-build test), then how many of its row's pairs are
  // flagged and, summed, the row's first slot (compute_forces).
  DeviceVector<std::uint32_t> tally_;
  DeviceVector<double> sums_first_;       // the first level's partial sums of both (OrderedSums)
  mutable OrderedSums sums_{sums_first_}; // one sum at a time
  OrderedSums step_sums_{sums_first_};    // the books of a step, queued
  DeviceVector<Coeffs> coeffs_;
  DeviceBox box_;
  DeviceCells cells_;
  Vec3 gravity_, g_periodic_;
  double dt_ = 0, skin_ = 0, time_ = 0;
  double dissipated_total_ = 0, gravity_work_total_ = 0, wall_work_total_ = 0;
  double removed_total_ = 0;
  std::int64_t escaped_ = 0;
  bool remove_escaped_ = false;
  Vec3 g_potential_;
  DeviceVector<Vec3> x_rest_;
  DeviceVector<std::uint16_t> motion_;
  DeviceVector<double> wall_work_;
  std::vector<DeviceMotion> motions_;
  std::int64_t step_ = 0, builds_ = 0;
  DevicePhaseSeconds phases_;
};

} // namespace

// The one factory this compilation defines: make_cuda_engine where nvcc compiles the file,
// make_host_engine where g++ does. Both libraries can then be linked into one program.
#if defined(__CUDACC__)
#define YUXI_ENGINE_FACTORY make_cuda_engine
#else
#define YUXI_ENGINE_FACTORY make_host_engine
#endif

template <class Model>
std::unique_ptr<LawEngine<Model>>
YUXI_ENGINE_FACTORY(const DeviceScene& scene, const std::vector<typename Model::Coeffs>& coeffs,
                    const std::vector<KeyedState<typename Model::State>>& contacts) {
#if defined(__CUDACC__)
  int devices = 0;
  if (cudaGetDeviceCount(&devices) != cudaSuccess || devices == 0)
    throw std::runtime_error("device engine: this build runs on a GPU, and no CUDA GPU was found");
#endif
  // The tangential spring alone where the law's state holds a rolling one that no pair uses.
  if constexpr (std::is_same_v<typename Model::State, TangentialRollingState>)
    if (TangentialOnly<Model>::fits(coeffs, contacts))
      return std::make_unique<Engine<Model, TangentialOnly<Model>>>(scene, coeffs, contacts);
  return std::make_unique<Engine<Model, WholeState<Model>>>(scene, coeffs, contacts);
}

#define YUXI_INSTANTIATE_ENGINE(Model)                                                             \
  template std::unique_ptr<LawEngine<Model>> YUXI_ENGINE_FACTORY<Model>(                           \
      const DeviceScene&, const std::vector<Model::Coeffs>&,                                       \
      const std::vector<KeyedState<Model::State>>&);
YUXI_INSTANTIATE_ENGINE(LinearSpringDashpot)
YUXI_INSTANTIATE_ENGINE(HertzMindlin)
YUXI_INSTANTIATE_ENGINE(Luding)
YUXI_INSTANTIATE_ENGINE(Thermodynamic)
YUXI_INSTANTIATE_ENGINE(Hooke)

} // namespace yuxi::device
