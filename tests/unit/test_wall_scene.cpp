// [[mesh]] and [[cylinder]] in scene files: the shipped wall scenes read and echo back, every
// mistake in a mesh file or its placement is one error naming the file and the place, and a
// checkpoint refuses a mesh file that changed since it was written.
#include "core/archive.hpp"
#include "io/scene_reader.hpp"
#include "io/scene_writer.hpp"
#include "run/scene_builder.hpp"
#include "temp_folder.hpp"

#include <fstream>
#include <gtest/gtest.h>

namespace yuxi {
namespace {

namespace fs = std::filesystem;

// A box of 10 with walls below and a flat square mesh at z = 1 under one grain.
std::string scene_with(const std::string& mesh_table) {
  return R"(materials = ["grain", "wall"]
[run]
dt = 1.0e-4
t_end = 0.01
[domain]
lo = [0.0, 0.0, 0.0]
hi = [10.0, 10.0, 10.0]
boundary = ["periodic", "periodic", "wall"]
gravity = [0.0, 0.0, -1.0]
wall_material = "wall"
[contact]
model = "linear"
[[contact.pair]]
materials = ["grain", "grain"]
k_n = 2.5e5
[[contact.pair]]
materials = ["grain", "wall"]
k_n = 1.0e6
[[particle]]
position = [5.0, 5.0, 3.0]
radius = 1.0
mass = 1.0
material = "grain"
)" + mesh_table;
}

const char* const square_stl = R"(solid square
facet normal 0 0 1
outer loop
vertex 2 2 1
vertex 8 2 1
vertex 8 8 1
endloop
endfacet
facet normal 0 0 1
outer loop
vertex 2 2 1
vertex 8 8 1
vertex 2 8 1
endloop
endfacet
endsolid square
)";

std::string replaced_text(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

struct Folder {
  fs::path dir = test::temp_dir("wall_scene");
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(dir / name, std::ios::binary) << text;
    return (dir / name).string();
  }
  Scene read(const std::string& text) const {
    return read_scene_text(text, (dir / "scene.toml").string());
  }
};

std::string error_of(const Folder& f, const std::string& text) {
  try {
    f.read(text);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(WallScene, ShippedWallScenesReadAndEchoBack) {
  for (const char* name : {"drum/drum-stl", "drum/drum-cylinder", "basin-mesh"}) {
    const Scene a = read_scene_file(std::string(YUXI_SCENES_DIR) + "/" + name + ".toml");
    ASSERT_EQ(a.walls.size(), 1u) << name;
    const std::string echo = resolved_scene_toml(a);
    const Scene b = read_scene_text(echo, "/elsewhere/resolved.toml"); // mesh paths absolute
    const auto body = [](const std::string& t) { return t.substr(t.find("\nmaterials")); };
    EXPECT_EQ(body(resolved_scene_toml(b)), body(echo)) << name;
  }
  const Scene drum = read_scene_file(std::string(YUXI_SCENES_DIR) + "/drum/drum-stl.toml");
  const auto& mesh = std::get<MeshWall>(drum.walls[0]);
  EXPECT_EQ(mesh.mesh.n_triangles(), 384u);
  EXPECT_EQ(std::get<RigidMotion>(mesh.motion).omega, 0.1);
}

TEST(WallScene, ACarriedCylinderAndAStopTimeReadAndEchoBack) {
  Folder f;
  f.write("square.stl", square_stl);
  const Scene a = f.read(scene_with(R"([[cylinder]]
name = "floor"
center = [5.0, 5.0, 0.5]
radius = 4.0
grains = "outside"
lo = -0.5
hi = 0.0
material = "wall"
velocity = [0.0, 0.0, -0.1]
t0 = 0.002
t1 = 0.004
[[mesh]]
file = "square.stl"
material = "wall"
velocity = [0.0, 0.0, 0.5]
t1 = 0.003
)"));
  const auto& floor = std::get<CylinderWall>(a.walls[1]); // (meshes first)
  EXPECT_TRUE(floor.moves());
  EXPECT_EQ(floor.carried.drift, (Vec3{0, 0, -0.1}));
  EXPECT_EQ(floor.carried.t1, 0.004);
  EXPECT_EQ(std::get<RigidMotion>(std::get<MeshWall>(a.walls[0]).motion).t1, 0.003);
  const std::string echo = resolved_scene_toml(a);
  const Scene b = f.read(echo);
  EXPECT_EQ(resolved_scene_toml(b), echo);
  EXPECT_EQ(std::get<CylinderWall>(b.walls[1]).carried.t0, 0.002);
  // a motion that stops before it starts
  EXPECT_NE(error_of(f, scene_with(R"([[cylinder]]
center = [5.0, 5.0, 0.5]
radius = 4.0
material = "wall"
velocity = [0.0, 0.0, -0.1]
t0 = 0.002
t1 = 0.001
)"))
                .find("t1"),
            std::string::npos);
}

TEST(WallScene, MeshMistakesNameTheFileAndThePlace) {
  const Folder f;
  f.write("square.stl", square_stl);
  const std::string ok = "[[mesh]]\nfile = \"square.stl\"\nmaterial = \"wall\"\n";
  const Scene s = f.read(scene_with(ok));
  ASSERT_EQ(s.walls.size(), 1u);
  EXPECT_TRUE(s.warnings.empty());
  // the file's own errors, at the scene's `file` key
  f.write("bad.stl", replaced_text(square_stl, "vertex 8 2 1", "vertex 8 2"));
  std::string e = error_of(f, scene_with("[[mesh]]\nfile = \"bad.stl\"\nmaterial = \"wall\"\n"));
  EXPECT_NE(e.find("scene.toml:"), std::string::npos) << e;
  EXPECT_NE(e.find("bad.stl: line 5"), std::string::npos) << e;
  e = error_of(f, scene_with("[[mesh]]\nfile = \"missing.stl\"\nmaterial = \"wall\"\n"));
  EXPECT_NE(e.find("missing.stl"), std::string::npos) << e;
  // outside the box, carried out of it, across a periodic face
  e = error_of(f, scene_with(ok + "translate = [0.0, 0.0, 50.0]\n"));
  EXPECT_NE(e.find("lies outside the box along z"), std::string::npos) << e;
  e = error_of(f, scene_with(ok + "velocity = [0.0, 0.0, 2000.0]\n"));
  EXPECT_NE(e.find("is carried out of the box along z"), std::string::npos) << e;
  e = error_of(f, scene_with(ok + "scale = 2.0\n"));
  EXPECT_NE(e.find("reaches across the periodic faces along x"), std::string::npos) << e;
  e = error_of(f, scene_with(ok + "omega = 1.0\nradial_mode = 2\nradial_amplitude = 0.1\n"));
  EXPECT_NE(e.find("not both"), std::string::npos) << e;
  e = error_of(f, scene_with(ok + "merge_degrees = 95.0\n"));
  EXPECT_NE(e.find("must be below 90"), std::string::npos) << e;
  // zero-area triangles are left out with a warning that counts them
  f.write("flat.stl",
          replaced_text(square_stl, "vertex 8 8 1\nvertex 2 8 1", "vertex 8 8 1\nvertex 8 8 1"));
  const Scene w = f.read(scene_with("[[mesh]]\nfile = \"flat.stl\"\nmaterial = \"wall\"\n"));
  ASSERT_EQ(w.warnings.size(), 1u);
  EXPECT_NE(w.warnings[0].find("1 triangles of zero area"), std::string::npos) << w.warnings[0];
}

TEST(WallScene, ACheckpointRefusesAChangedMeshFile) {
  const Folder f;
  f.write("square.stl", square_stl);
  const Scene s = f.read(scene_with("[[mesh]]\nfile = \"square.stl\"\nmaterial = \"wall\"\n"));
  auto sim = build_simulation(s, false);
  sim->run(50);
  ArchiveWriter saved;
  sim->save_state(saved);
  // the same file: loads
  auto same = build_simulation(s, false);
  same->load({{saved.data()}, 1});
  // another file under the same name: refused, naming it
  f.write("square.stl", replaced_text(square_stl, "vertex 2 8 1", "vertex 2 8.5 1"));
  const Scene changed =
      f.read(scene_with("[[mesh]]\nfile = \"square.stl\"\nmaterial = \"wall\"\n"));
  auto other = build_simulation(changed, false);
  try {
    other->load({{saved.data()}, 1});
    FAIL() << "a changed mesh file was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("square.stl has changed"), std::string::npos) << e.what();
  }
}

} // namespace
} // namespace yuxi
