// The member-sphere files of clumps (io/sphere_list_reader.hpp): CSV with a header, and the
// plain sphere lists of LIGGGHTS; every malformed file refused with its line.
#include "io/sphere_list_reader.hpp"

#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <gtest/gtest.h>
#include <string>

namespace yuxi {
namespace {

TEST(SphereListReader, ReadsCsvColumnsInAnyOrder) {
  const auto m = parse_sphere_list("# a rod\nradius,z,x,y,id\n0.5,-0.5,0,0,1\n0.5, 0.5, 0, 0, 2\n",
                                   "rod.csv", SphereListFormat::csv);
  ASSERT_EQ(m.size(), 2u);
  EXPECT_EQ(m[1].centre.z, 0.5);
  EXPECT_EQ(m[1].radius, 0.5);
  const auto r = parse_sphere_list("x,y,z,r\n1,2,3,0.25\n", "a.csv", SphereListFormat::csv);
  EXPECT_EQ(r[0].centre.y, 2.0);
  EXPECT_EQ(r[0].radius, 0.25);
}

TEST(SphereListReader, ReadsTheNamedCsvCellsAndNoOthers) {
  // Cells split at commas only, empty ones kept: a text cell with a space, an empty first cell.
  const auto m = parse_sphere_list("id,x,y,z,r,label\n,1,2,3,0.5,glass bead\n", "a.csv",
                                   SphereListFormat::csv);
  ASSERT_EQ(m.size(), 1u);
  EXPECT_EQ(m[0].centre.x, 1.0);
  EXPECT_EQ(m[0].centre.z, 3.0);
  EXPECT_EQ(m[0].radius, 0.5);
  // A byte-order mark, quoted and upper-case names, quoted numbers and a plus sign.
  const auto q =
      parse_sphere_list("\xEF\xBB\xBF\"X\", \"Y\", \"Z\", \"Radius\"\r\n+1, \"2\", 3, 0.25\r\n",
                        "q.csv", SphereListFormat::csv);
  ASSERT_EQ(q.size(), 1u);
  EXPECT_EQ(q[0].centre.x, 1.0);
  EXPECT_EQ(q[0].centre.y, 2.0);
  EXPECT_EQ(q[0].radius, 0.25);
}

TEST(SphereListReader, ReadsAPlainListWithComments) {
  const auto m = parse_sphere_list("# x y z r\n\n0 0 -0.3 0.5   # first\n0\t0\t0.3\t0.4\r\n",
                                   "rice.txt", SphereListFormat::plain);
  ASSERT_EQ(m.size(), 2u);
  EXPECT_EQ(m[1].centre.z, 0.3);
  EXPECT_EQ(m[1].radius, 0.4);
}

// The message of the error that parsing `text` raises.
std::string error_of(const std::string& text, SphereListFormat format) {
  try {
    parse_sphere_list(text, "f", format);
  } catch (const ShapeFileError& e) {
    return e.what();
  }
  return "no error";
}

TEST(SphereListReader, NamesTheLineOfEveryFault) {
  using enum SphereListFormat;
  EXPECT_EQ(error_of("x,y,z\n1,2,3\n", csv),
            "f:1: the header has no column 'radius' (it needs x, y, z and radius)");
  EXPECT_EQ(error_of("x,y,z,r\n1,2,3\n", csv), "f:2: 3 cells where the header has 4");
  EXPECT_EQ(error_of("x,y,x,z,r\n1,2,3,4,0.5\n", csv), "f:1: the header names 'x' twice");
  EXPECT_EQ(error_of("x,y,z,radius,R\n1,2,3,0.5,0.5\n", csv),
            "f:1: the header names 'radius' twice");
  EXPECT_EQ(error_of("x,y,z,r\n1,2,3,0.5,\n", csv), "f:2: 5 cells where the header has 4");
  EXPECT_EQ(error_of("x,y,z,r\n1,,3,0.5\n", csv), "f:2: '' is not a finite number");
  EXPECT_EQ(error_of("0 0 0 1\n0 0 1\n", plain), "f:2: 3 fields where a member needs 4 (x y z r)");
  EXPECT_EQ(error_of("0 0 0 1\n0 0 1 abc\n", plain), "f:2: 'abc' is not a finite number");
  EXPECT_EQ(error_of("0 0 0 1\n0 0 inf 1\n", plain), "f:2: 'inf' is not a finite number");
  EXPECT_EQ(error_of("0 0 0 -1\n", plain), "f:1: the radius -1 is not positive");
  EXPECT_EQ(error_of("# nothing\n", plain), "f: no member sphere");
  EXPECT_EQ(error_of("", csv), "f: empty: no header and no member");
  EXPECT_EQ(error_of("x,y,z,r\n", csv), "f: no member sphere");
}

TEST(SphereListReader, RefusesMoreMembersThanAClumpHolds) {
  std::string text;
  for (std::size_t k = 0; k <= max_clump_members; ++k) text += "0 0 0 1\n";
  EXPECT_EQ(error_of(text, SphereListFormat::plain),
            fmt::format("f:{}: more than {} members in one clump", max_clump_members + 1,
                        max_clump_members));
}

TEST(SphereListReader, ReadsAFileByItsName) {
  const auto dir = std::filesystem::temp_directory_path() / "yuxi_sphere_list";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "a.csv") << "x,y,z,radius\n0,0,0,1\n";
  std::ofstream(dir / "a.txt") << "0 0 0 1\n1 0 0 1\n";
  EXPECT_EQ(read_sphere_list((dir / "a.csv").string()).size(), 1u);
  EXPECT_EQ(read_sphere_list((dir / "a.txt").string()).size(), 2u);
  EXPECT_THROW(read_sphere_list((dir / "missing.txt").string()), ShapeFileError);
  std::filesystem::remove_all(dir);
}

} // namespace
} // namespace yuxi
