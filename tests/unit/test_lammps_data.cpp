// The LAMMPS data reader: the chute file as LAMMPS reads it, and clear errors for broken files.
#include "core/units.hpp"
#include "io/lammps_data_reader.hpp"

#include <gtest/gtest.h>
#include <ostream>

namespace yuxi {
namespace {

const char* const small = R"(title line
3 atoms
2 atom types
0 10 xlo xhi
0 5 ylo yhi
-1 4 zlo zhi

Atoms # sphere

2 1 1.0 1.0 1 2 3 0 0 0
1 2 0.5 2.0 4 4 1
3 1 1.0 1.0 5 1 2 1 0 0

Velocities

1 0 0 0 0 0 0
2 0.5 0 0 0 0 1
3 0 0 -1 0 0 0
)";

TEST(LammpsData, ReadsSphereAtomsAndVelocities) {
  const LammpsData d = parse_lammps_data(small, "small.data");
  ASSERT_EQ(d.atoms.size(), 3u);
  EXPECT_EQ(d.n_types, 2);
  EXPECT_EQ(d.lo, (Vec3{0, 0, -1}));
  EXPECT_EQ(d.hi, (Vec3{10, 5, 4}));
  EXPECT_EQ(d.atoms[0].id, 1); // sorted by id
  EXPECT_EQ(d.atoms[0].type, 2);
  EXPECT_EQ(d.atoms[0].diameter, 0.5);
  EXPECT_EQ(d.atoms[1].v, (Vec3{0.5, 0, 0}));
  EXPECT_EQ(d.atoms[1].w, (Vec3{0, 0, 1}));
  EXPECT_EQ(d.atoms[2].x, (Vec3{5, 1, 2}));
}

struct Broken {
  const char* what;
  std::string from, to, expected;
};
// ctest lists a case by its name and this, not by a dump of the parameter's bytes.
void PrintTo(const Broken& c, std::ostream* os) {
  *os << c.what;
}

class BrokenData : public ::testing::TestWithParam<Broken> {};

TEST_P(BrokenData, IsRefusedWithFileAndLine) {
  std::string text = small;
  const auto at = text.find(GetParam().from);
  ASSERT_NE(at, std::string::npos);
  text.replace(at, GetParam().from.size(), GetParam().to);
  try {
    parse_lammps_data(text, "small.data");
    FAIL() << GetParam().what << ": accepted";
  } catch (const DataFileError& e) {
    EXPECT_NE(std::string(e.what()).find(GetParam().expected), std::string::npos)
        << GetParam().what << ": " << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(
    Table, BrokenData,
    ::testing::Values(
        Broken{"huge atom count (fuzzer finding)", "3 atoms", "320032000 atoms",
               "small.data:14: Atoms holds 3 lines; the header announces 320032000 atoms"},
        Broken{"negative atom count", "3 atoms", "-3 atoms",
               "the number of atoms must not be negative"},
        Broken{"bad number", "1 2 0.5 2.0 4 4 1", "1 2 0.5 2.0 4 x 1",
               "small.data:11: position \"x\" is not a finite number"},
        Broken{"missing column", "1 2 0.5 2.0 4 4 1", "1 2 0.5 2.0 4 4",
               "small.data:11: an Atoms line of atom_style sphere has 7 or 10"},
        Broken{"type out of range", "3 1 1.0 1.0 5", "3 7 1.0 1.0 5", "atom type 7 outside 1..2"},
        Broken{"duplicate id", "3 1 1.0 1.0 5", "2 1 1.0 1.0 5", "atom id 2 appears twice"},
        Broken{"truncated", "3 atoms", "4 atoms", "Atoms"},
        Broken{"unknown velocity atom", "3 0 0 -1", "9 0 0 -1", "velocity of an unknown atom 9"},
        Broken{"no box", "0 10 xlo xhi\n", "", "does not give xlo xhi"},
        Broken{"negative diameter", "2 1 1.0 1.0 1 2 3", "2 1 -1.0 1.0 1 2 3",
               "diameter and density must be > 0"}),
    [](const ::testing::TestParamInfo<Broken>& p) {
      std::string n = p.param.what;
      for (auto& ch : n)
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
      return n;
    });

TEST(LammpsData, ReadsTheChuteBenchmark) {
  const LammpsData d = read_lammps_data(YUXI_DATA_DIR "/lammps/data.chute");
  ASSERT_EQ(d.atoms.size(), 32000u);
  EXPECT_EQ(d.n_types, 2);
  EXPECT_EQ(d.hi, (Vec3{40, 20, 37.2886}));
  std::size_t base = 0;
  for (const auto& a : d.atoms) base += a.type == 2 ? 1 : 0;
  EXPECT_EQ(base, 912u);
}

} // namespace
} // namespace yuxi
