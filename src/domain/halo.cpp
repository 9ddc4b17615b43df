#include "domain/halo.hpp"

#include <cstring>
#include <stdexcept>
#include <type_traits>

namespace yuxi {
namespace {

template <class T> void put(std::string& out, const T& v) {
  out.append(reinterpret_cast<const char*>(&v), sizeof v);
}
template <class T> T take(const std::string& in, std::size_t& at) {
  T v;
  std::memcpy(&v, in.data() + at, sizeof v);
  at += sizeof v;
  return v;
}

// Every field of particle i, shifted.
void pack_particle(const ParticleStore& s, std::size_t i, const Vec3& shift, std::string& out) {
  s.for_each_field([&](const auto& field) {
    auto value = field[i];
    if constexpr (std::is_same_v<std::decay_t<decltype(value)>, Vec3>) {
      if (&field == &s.x || &field == &s.x_rest || &field == &s.x_build) value += shift;
    }
    put(out, value);
  });
}

void unpack_particle(ParticleStore& s, const std::string& in, std::size_t& at, std::size_t i) {
  s.for_each_field([&](auto& field) {
    using T = std::decay_t<decltype(field[0])>;
    field[i] = take<T>(in, at);
  });
}

int tag_of(int axis, int dir) {
  return 100 + 4 * axis + (dir > 0 ? 2 : 0);
}

} // namespace

void Halo::build(ParticleStore& s, const Decomposition& d, const Comm& comm, double cutoff,
                 const GhostPayload* payload) {
  s.clear_ghosts();
  swaps_.clear();
  const Vec3 lo = d.local_box().lo, hi = d.local_box().hi;
  const auto n_owned = static_cast<std::uint32_t>(s.n_owned());
  bool earlier_ghosts = false; // whether an earlier axis made ghosts (on every rank alike)
  for (int a = 0; a < 3; ++a) {
    const bool crossed = d.dims()[a] > 1 || d.box().periodic(a);
    if (crossed && d.min_width(a) < cutoff)
      throw std::invalid_argument("a sub-domain is narrower than the interaction cutoff: use "
                                  "fewer ranks along that axis");
    const auto n_now = static_cast<std::uint32_t>(s.size());
    for (int dir : {-1, +1}) {
      // Towards the upper neighbour go ghosts of earlier axes only: with none, nothing does.
      if (dir > 0 && !earlier_ghosts) continue;
      Swap w;
      w.send_to = d.neighbor(a, dir);
      w.receive_from = d.neighbor(a, -dir);
      if (w.send_to < 0 && w.receive_from < 0) continue;
      if (d.wraps(a, dir)) w.shift[a] = -dir * d.box().length(a);
      if (w.send_to >= 0)
        for (std::uint32_t k = dir < 0 ? 0 : n_owned; k < n_now; ++k)
          if (dir < 0 ? s.x[k][a] < lo[a] + cutoff : s.x[k][a] >= hi[a] - cutoff)
            w.sends.push_back(k);
      // [count][each field's block, in send order][payload bytes]
      std::string out;
      put(out, static_cast<std::uint64_t>(w.sends.size()));
      s.for_each_field([&](const auto& field) {
        using T = std::decay_t<decltype(field[0])>;
        const std::size_t at = out.size();
        out.resize(at + w.sends.size() * sizeof(T));
        char* block = out.data() + at;
        const bool position =
            std::is_same_v<T, Vec3> && (static_cast<const void*>(&field) == &s.x ||
                                        static_cast<const void*>(&field) == &s.x_rest ||
                                        static_cast<const void*>(&field) == &s.x_build);
        for (std::size_t m = 0; m < w.sends.size(); ++m) {
          T value = field[w.sends[m]];
          if constexpr (std::is_same_v<T, Vec3>) {
            if (position) value += w.shift;
          }
          std::memcpy(block + m * sizeof(T), &value, sizeof(T));
        }
      });
      if (payload) out += payload->pack(w.sends);
      const std::string in = comm.send_receive(w.send_to, out, w.receive_from, tag_of(a, dir));
      if (!in.empty()) {
        std::size_t at = 0;
        const auto count = take<std::uint64_t>(in, at);
        w.first = static_cast<std::uint32_t>(s.add_ghosts(count));
        w.count = static_cast<std::uint32_t>(count);
        s.for_each_field([&](auto& field) {
          const std::size_t bytes = count * sizeof(field[0]);
          if (bytes > 0) std::memcpy(&field[w.first], in.data() + at, bytes);
          at += bytes;
        });
        if (payload && at < in.size()) payload->unpack(w.first, in.substr(at));
      } else {
        w.first = static_cast<std::uint32_t>(s.size());
      }
      swaps_.push_back(std::move(w));
    }
    earlier_ghosts = earlier_ghosts || crossed;
  }
  n_ghosts_ = s.n_ghost();
  n_from_other_ranks_ = 0;
  last_message_ = swaps_.size();
  for (std::size_t k = swaps_.size(); k-- > 0;) {
    if (swaps_[k].local(comm)) continue;
    last_message_ = k;
    n_from_other_ranks_ += swaps_[k].count;
  }
}

void Halo::forward(ParticleStore& s, const Comm& comm) const {
  for (std::size_t k = 0; k < swaps_.size(); ++k) {
    const Swap& w = swaps_[k];
    if (w.local(comm)) {
      // A periodic image of our own particles: copy, no message.
      for (std::uint32_t n = 0; n < w.count; ++n) {
        const std::uint32_t i = w.sends[n], g = w.first + n;
        s.x[g] = s.x[i] + w.shift;
        s.v[g] = s.v[i];
        s.w[g] = s.w[i];
      }
      continue;
    }
    // One block per field ([x][v][w], each in send order), so that the receiver copies each
    // block into its ghosts whole.
    const std::size_t n_out = w.sends.size();
    out_.resize(n_out * forward_bytes_per_ghost);
    char* out = out_.data();
    for (std::size_t m = 0; m < n_out; ++m) {
      const std::uint32_t i = w.sends[m];
      const Vec3 shifted = s.x[i] + w.shift;
      std::memcpy(out + m * sizeof(Vec3), &shifted, sizeof(Vec3));
      std::memcpy(out + (n_out + m) * sizeof(Vec3), &s.v[i], sizeof(Vec3));
      std::memcpy(out + (2 * n_out + m) * sizeof(Vec3), &s.w[i], sizeof(Vec3));
    }
    comm.send_receive(w.send_to, out_, w.receive_from, in_, w.count * forward_bytes_per_ghost,
                      200 + 2 * static_cast<int>(k));
    const std::size_t block = w.count * sizeof(Vec3);
    if (block == 0) continue;
    std::memcpy(&s.x[w.first], in_.data(), block);
    std::memcpy(&s.v[w.first], in_.data() + block, block);
    std::memcpy(&s.w[w.first], in_.data() + 2 * block, block);
  }
}

template <class... Field> void Halo::pack_back(const Swap& w, std::string& out, Field&... fields) {
  // The ghosts of a swap are contiguous: one block per field, copied whole.
  out.clear();
  if (w.count > 0)
    (out.append(reinterpret_cast<const char*>(&fields[w.first]), w.count * sizeof(fields[0])), ...);
}

template <class... Field> void Halo::add_back(const Swap& w, Field&... fields) const {
  std::size_t at = 0;
  const auto add_block = [&](auto& field) {
    for (const std::uint32_t i : w.sends)
      field[i] += take<std::decay_t<decltype(field[i])>>(in_, at);
  };
  (add_block(fields), ...);
}

template <class... Field>
void Halo::reverse_add(const Comm& comm, std::size_t from, std::size_t down_to,
                       Field&... fields) const {
  for (std::size_t k = from; k-- > down_to;) {
    const Swap& w = swaps_[k];
    if (w.local(comm)) {
      for (std::uint32_t n = 0; n < w.count; ++n) {
        const std::uint32_t i = w.sends[n], g = w.first + n;
        ((fields[i] += fields[g]), ...);
      }
      continue;
    }
    pack_back(w, out_, fields...);
    // back the way the ghosts came: to the rank they were received from
    comm.send_receive(w.receive_from, out_, w.send_to, in_,
                      w.sends.size() * (sizeof(fields[0]) + ...), 400 + 2 * static_cast<int>(k));
    add_back(w, fields...);
  }
}

void Halo::reverse(ParticleStore& s, const Comm& comm) const {
  // (The last message goes as in reverse_start() on every rank: a rank with no pair to
  // compute before it may be sending to or receiving from one that has.)
  reverse_start(s, comm);
  reverse_finish(s, comm);
}

void Halo::reverse_start(ParticleStore& s, const Comm& comm) const {
  if (!sends_to_other_ranks()) return reverse_add(comm, swaps_.size(), 0, s.f, s.torque);
  const std::size_t k = last_message_;
  reverse_add(comm, swaps_.size(), k + 1, s.f, s.torque);
  const Swap& w = swaps_[k];
  settle(comm);
  pack_back(w, back_out_, s.f, s.torque);
  back_ = comm.start_send_receive(w.receive_from, back_out_, w.send_to, in_,
                                  w.sends.size() * reverse_bytes_per_ghost,
                                  400 + 2 * static_cast<int>(k));
}

void Halo::reverse_finish(ParticleStore& s, const Comm& comm) const {
  if (!sends_to_other_ranks()) return;
  comm.wait_receive(back_);
  add_back(swaps_[last_message_], s.f, s.torque);
  reverse_add(comm, last_message_, 0, s.f, s.torque);
}

void Halo::reverse_sum(std::vector<double>& per_particle, const Comm& comm) const {
  reverse_add(comm, swaps_.size(), 0, per_particle);
}

void Halo::migrate(
    ParticleStore& s, const Decomposition& d, const Comm& comm,
    const std::function<std::vector<std::string>(const std::vector<std::size_t>&)>& payloads,
    const std::function<void(std::size_t, const std::string&, const Vec3&)>& arrived,
    std::span<const Vec3> where) {
  s.clear_ghosts();
  const Vec3 lo = d.lo(), hi = d.hi();
  // The places that decide the owners, kept beside the particles as they leave and arrive.
  std::vector<Vec3> at(where.begin(), where.end());
  const bool anchored = !at.empty();
  const auto place = [&](std::size_t i) -> const Vec3& { return anchored ? at[i] : s.x[i]; };
  for (int a = 0; a < 3; ++a) {
    if (d.dims()[a] == 1) continue; // periodic wrap alone is done by the caller
    // Both directions at once: one pass to find who leaves, one call for their payloads, one
    // removal (particles that arrive and lie beyond the other face go in the caller's next
    // round).
    const int below = d.neighbor(a, -1), above = d.neighbor(a, +1);
    std::vector<std::size_t> leaving; // ascending
    for (std::size_t i = 0; i < s.n_owned(); ++i)
      if ((below >= 0 && place(i)[a] < lo[a]) || (above >= 0 && place(i)[a] >= hi[a]))
        leaving.push_back(i);
    const std::vector<std::string> carried = payloads(leaving);
    std::string out[2];
    for (std::size_t k = 0; k < leaving.size(); ++k) {
      const int dir = place(leaving[k])[a] < lo[a] ? -1 : +1;
      Vec3 shift;
      if (d.wraps(a, dir)) shift[a] = -dir * d.box().length(a);
      std::string& o = out[dir > 0 ? 1 : 0];
      pack_particle(s, leaving[k], shift, o);
      if (anchored) put(o, at[leaving[k]] + shift);
      put(o, static_cast<std::uint64_t>(carried[k].size()));
      o += carried[k];
    }
    // (the anchors follow the particles: the last owned ones fill the gaps, as in the store)
    if (anchored) {
      for (std::size_t k = leaving.size(); k-- > 0;) {
        at[leaving[k]] = at.back();
        at.pop_back();
      }
    }
    s.remove_owned_unordered(leaving); // (the caller sorts the particles next)
    for (int dir : {-1, +1}) {
      const int to = d.neighbor(a, dir), from = d.neighbor(a, -dir);
      const std::string in =
          comm.send_receive(to, out[dir > 0 ? 1 : 0], from, 600 + 4 * a + (dir > 0 ? 2 : 0));
      // What arrives from `from` was sent in direction dir: the sender's shift, -dir L where
      // that crossed the periodic boundary, the same for every particle of the message.
      Vec3 shift;
      if (d.wraps(a, -dir)) shift[a] = -dir * d.box().length(a);
      std::size_t pos = 0;
      while (pos < in.size()) {
        ParticleSpec dummy;
        const std::size_t i = s.add(dummy, 0);
        unpack_particle(s, in, pos, i);
        if (anchored) at.push_back(take<Vec3>(in, pos));
        const auto n = take<std::uint64_t>(in, pos);
        arrived(i, in.substr(pos, n), shift);
        pos += n;
      }
    }
  }
}

} // namespace yuxi
