// A wall made of triangles (an STL file's), moved as a whole or vertex by vertex by a
// prescribed motion (wall_motion.hpp), with a material, an optional conveyor velocity along its
// surface and a time window in which it exists. Triangles are two-sided: a grain is pushed away
// from whichever side it touches. Contacts follow wall_touch.hpp.
#pragma once

#include "core/vec3.hpp"
#include "scene/active_window.hpp"
#include "scene/triangle_mesh.hpp"
#include "scene/vertex_stars.hpp"
#include "scene/wall_controller.hpp"
#include "scene/wall_motion.hpp"
#include "scene/wall_touch.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <numbers>
#include <span>
#include <string>
#include <vector>

namespace yuxi {

struct MeshWall {
  std::string name;             // for messages and walls.csv
  std::string file;             // the mesh file it was read from ("" if built in code)
  std::uint32_t file_crc32 = 0; // of the file's bytes: a checkpoint refuses another file
  TriangleMesh mesh;            // at rest, in the scene's frame
  // How the file's triangles were placed in the scene (TriangleMesh::transform).
  double scale = 1.0;
  Vec3 rotate_axis{0, 0, 1};
  double rotate_degrees = 0.0;
  Vec3 translate;
  WallMotion motion = StaticMotion{};
  std::uint8_t material = 0;
  ActiveWindow active;
  // A conveyor: the surface moves with this velocity's component along each triangle, the
  // triangles stay [length/time].
  Vec3 surface_velocity;
  // Touches whose normals differ by less than this angle count as one (wall_touch.hpp rule 4).
  double merge_degrees = 15.0;
  // The point about which walls.csv gives the torque on the wall.
  Vec3 torque_point;
  // A servo-controlled wall: its controller sets its speed along servo_axis (unit) at every
  // step; servo_offset is how far it has moved along the axis, servo_speed its speed now. The
  // prescribed motion, if any, adds to it.
  std::shared_ptr<WallController> controller;
  Vec3 servo_axis{0, 0, -1};
  double servo_offset = 0.0; // [length]
  double servo_speed = 0.0;  // [length/time]

  // A rank may hold only a part of a mesh, the triangles near its grains: `mesh` is then that
  // part, `held` the index in the whole mesh of each of its triangles (ascending), and `whole`
  // the whole mesh at rest, from which the part is chosen again when the grains leave the box it
  // was chosen for or, for a moving mesh, at every list build (Simulation::list_wall_candidates),
  // and which the snapshots draw. With `held` empty, `mesh` is whole (or nothing is near).
  std::shared_ptr<const TriangleMesh> whole;
  std::vector<std::uint32_t> held;
  const TriangleMesh& whole_mesh() const { return whole ? *whole : mesh; }
  bool holds_whole() const { return !whole || mesh.n_triangles() == whole->n_triangles(); }
  // The whole mesh's index of triangle t of `mesh` (a contact's element).
  std::uint32_t element_of(std::uint32_t t) const { return held.empty() ? t : held[t]; }
  // Holds only the triangles whose box, placed as at the last place(), comes within `reach`
  // of the box [lo, hi], and places them; returns whether the held part changed.
  bool hold_near(const Vec3& lo, const Vec3& hi, double reach);
  // The whole mesh's vertices placed at the time of the last place().
  std::vector<Vec3> placed_whole() const;
  // Takes where the last place() put the mesh as where the last list build found it, from
  // which moved2_since_build() measures. The servo's offset then: a checkpoint keeps it, so
  // that a resumed run builds that list again with the mesh where it stood.
  void mark_built();
  double servo_offset_built = 0.0;
  // A bound on the square of how far any point of the whole mesh has moved, from where it
  // stood at the last list build to where the last place() put it [length^2]. It covers the
  // triangles a rank does not hold (docs/walls.md section 5):
  //  - under a rigid motion (and a servo's travel), a point's displacement is an affine map of
  //    the point, and its length, a convex function, is largest at a corner of the mesh's box
  //    at rest: the bound is the farthest corner's;
  //  - under the radial mode each point moves along its radius by cos(m alpha) times the
  //    change of dr sin(omega (t - t0)), at most that change; the servo adds its travel.
  double moved2_since_build() const;
  // Where each vertex is and how fast it moves, as of the last place().
  std::vector<Vec3> x, v;
  double placed_at = 0.0;
  // Each triangle as placed last: its corners and its unit normal, along (b - a) x (c - a),
  // side by side, so that the contact search reads one record per candidate. With them, what
  // the search's quick look needs (touches(), docs/walls.md section 1): the dual vectors e1,
  // e2 that give a point's barycentric weights of b and c, v = e1.(x - a) and w = e2.(x - a)
  // (dimensionless), and the squared altitudes from a, b and c [length^2]. A sliver (an angle
  // below about 0.06 degrees) gets zeros, and the search gives it no quick look.
  struct PlacedTriangle {
    Vec3 a, b, c, normal;
    Vec3 e1, e2;
    double altitude2[3];
  };
  std::vector<PlacedTriangle> placed;

  // Moves every vertex to time t (and takes the cosine of the merge angle).
  void place(double t) {
    placed_at = t;
    cos_merge_ = std::cos(merge_degrees * std::numbers::pi / 180.0);
    x.resize(mesh.vertices.size());
    v.resize(mesh.vertices.size());
    const WallMotionAtTime now = at_time(motion, t);
    const Vec3 shift = servo_offset * servo_axis, push = servo_speed * servo_axis;
    for (std::size_t k = 0; k < x.size(); ++k) {
      const PlacedState p = yuxi::place(now, mesh.vertices[k]);
      x[k] = p.position + shift;
      v[k] = p.velocity + push;
    }
    // The normals: those at rest, turned with a rigid motion (no square root per triangle);
    // a deforming mesh's from its placed corners.
    if (rest_normals_.size() != mesh.triangles.size()) {
      rest_normals_.resize(mesh.triangles.size());
      for (std::size_t k = 0; k < rest_normals_.size(); ++k) {
        const auto& tri = mesh.triangles[k];
        const Vec3& a = mesh.vertices[tri[0]];
        rest_normals_[k] = normalized(cross(mesh.vertices[tri[1]] - a, mesh.vertices[tri[2]] - a));
      }
    }
    if (!stars_.fits(mesh)) stars_ = VertexStars::of(mesh);
    const auto* rigid = std::get_if<RigidMotion::AtTime>(&now);
    const bool deforms = !rigid && !at_rest(now);
    const bool turns = rigid && !rigid->at_rest();
    placed.resize(mesh.triangles.size());
    for (std::size_t k = 0; k < placed.size(); ++k) {
      const auto& tri = mesh.triangles[k];
      PlacedTriangle& p = placed[k];
      p.a = x[tri[0]], p.b = x[tri[1]], p.c = x[tri[2]];
      const Vec3 n = cross(p.b - p.a, p.c - p.a);
      p.normal =
          deforms ? normalized(n) : (turns ? rigid->turn(rest_normals_[k]) : rest_normals_[k]);
      set_quick_look(p, n);
    }
  }
  bool moves() const { return controller || !std::holds_alternative<StaticMotion>(motion); }

  // The contacts of a sphere (centre c, radius r) with the listed triangles, as placed last.
  // `scratch` and `order` hold candidates between calls (no allocation once warm).
  void touches(const Vec3& c, double r, std::span<const std::uint32_t> triangles,
               std::vector<FeatureTouch>& scratch, std::vector<std::uint32_t>& order,
               WallTouches& out) const;

  // Whether triangle t, as placed last, comes closer than `reach` to the point c.
  bool within(const Vec3& c, double reach, std::uint32_t t) const;

private:
  // The dual vectors and squared altitudes of a placed triangle (PlacedTriangle above), given
  // n = ab x ac: e1 = (ac x n) / |n|^2 and e2 = (n x ab) / |n|^2, so that e1.ab = 1,
  // e1.ac = 0, e2.ab = 0, e2.ac = 1; the altitude from a is |n| / |bc|, and so on.
  static void set_quick_look(PlacedTriangle& p, const Vec3& n) {
    const Vec3 ab = p.b - p.a, ac = p.c - p.a;
    const double n2 = norm2(n), ab2 = norm2(ab), ac2 = norm2(ac), bc2 = norm2(p.c - p.b);
    if (!(n2 > 1e-6 * ab2 * ac2)) { // (sin^2 of the angle at a below 1e-6, or not finite)
      p.e1 = p.e2 = Vec3{};
      p.altitude2[0] = p.altitude2[1] = p.altitude2[2] = 0.0;
      return;
    }
    p.e1 = cross(ac, n) * (1.0 / n2);
    p.e2 = cross(n, ab) * (1.0 / n2);
    p.altitude2[0] = n2 / bc2, p.altitude2[1] = n2 / ac2, p.altitude2[2] = n2 / ab2;
  }

  // Whether a touch on an edge or a vertex lies where its feature is the closest point of
  // every triangle that holds it (wall_touch.hpp rule 3), as placed last.
  bool feature_closest(const FeatureTouch& f) const;

  // The corners of the whole mesh's box at rest, placed as at the last place().
  std::array<Vec3, 8> placed_box_corners() const;

  std::array<Vec3, 8> built_corners_{}; // placed_box_corners() at the last list build
  double built_radial_ = 0.0;           // the radial mode's dr sin(omega (t - t0)) then
  double cos_merge_ = 1.0;              // of merge_degrees, at the last place()
  std::vector<Vec3> rest_normals_;      // of the triangles at rest (taken at the first place())
  VertexStars stars_;                   // of `mesh` (taken at the first place())
  Vec3 rest_lo_, rest_hi_;              // the whole mesh's box at rest (taken with `whole`)
};

} // namespace yuxi
