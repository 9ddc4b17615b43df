#include "sim/particle_diagnosis.hpp"

#include <fmt/format.h>
#include <map>
#include <utility>

namespace yuxi {

std::string describe_particle(const ParticleStore& s, std::size_t i) {
  const std::string clump =
      s.body[i] >= 0 ? fmt::format("member {} of clump {}, ", s.gid[i] - s.body[i], s.body[i])
                     : std::string();
  return fmt::format("{} {} ({}radius {:.4g}) at ({:.6g}, {:.6g}, {:.6g}) with velocity ({:.6g}, "
                     "{:.6g}, {:.6g}), angular velocity ({:.6g}, {:.6g}, {:.6g})",
                     s.is_grain(i) ? "grain" : "wall particle", s.gid[i], clump, s.radius[i],
                     s.x[i].x, s.x[i].y, s.x[i].z, s.v[i].x, s.v[i].y, s.v[i].z, s.w[i].x, s.w[i].y,
                     s.w[i].z);
}

std::string describe_contacts(const ParticleStore& s, const Box& box,
                              const std::vector<PlaneWall>& planes, double t, std::size_t i) {
  // A diagnosis, not a hot path: every particle is looked at.
  std::map<GlobalId, std::pair<bool, double>> touching; // gid -> grain?, overlap
  for (std::size_t j = 0; j < s.size(); ++j) {
    if (s.gid[j] == s.gid[i]) continue;
    if (s.body[i] >= 0 && s.body[j] == s.body[i]) continue; // (its own clump: never a contact)
    const Vec3 d = j < s.n_owned() ? box.minimum_image(s.x[i], s.x[j]) : s.x[i] - s.x[j];
    const double overlap = s.radius[i] + s.radius[j] - norm(d);
    if (overlap > 0) touching.emplace(s.gid[j], std::pair{s.is_grain(j), overlap});
  }
  std::string out;
  for (const auto& [gid, contact] : touching)
    out += fmt::format("{}{} {} (overlap {:.4g})", out.empty() ? "" : ", ",
                       contact.first ? "grain" : "wall particle", gid, contact.second);
  for (const auto& p : planes) {
    const double overlap = s.radius[i] - p.distance(s.x[i], t);
    if (overlap > 0)
      out += fmt::format("{}flat wall (overlap {:.4g})", out.empty() ? "" : ", ", overlap);
  }
  return out.empty() ? "none" : out;
}

} // namespace yuxi
