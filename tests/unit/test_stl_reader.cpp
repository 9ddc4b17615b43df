// The STL reader: ASCII and binary files of the same mesh give the same triangles, binary files
// whose header starts with "solid" are binary, degenerate triangles are dropped and counted, and
// every malformed file is refused with its name and the line or triangle at fault.
#include "io/stl_reader.hpp"
#include "temp_folder.hpp"

#include <bit>
#include <cstdint>
#include <fmt/format.h>
#include <fstream>
#include <gtest/gtest.h>
#include <limits>
#include <ostream>
#include <string>
#include <vector>
#include <zlib.h>

namespace yuxi {
namespace {

using Triangle = std::array<Vec3, 3>;

// A unit-ish cube (coordinates exact in float32): 12 triangles.
std::vector<Triangle> cube() {
  const double lo[3] = {-0.5, 0.25, -1.5}, hi[3] = {2.0, 1.75, 0.125};
  const auto corner = [&](int i) {
    return Vec3{(i & 1) ? hi[0] : lo[0], (i & 2) ? hi[1] : lo[1], (i & 4) ? hi[2] : lo[2]};
  };
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  std::vector<Triangle> out;
  for (const auto& f : faces) {
    out.push_back({corner(f[0]), corner(f[1]), corner(f[2])});
    out.push_back({corner(f[0]), corner(f[2]), corner(f[3])});
  }
  return out;
}

std::string ascii_stl(const std::vector<Triangle>& tris, const std::string& name = "cube") {
  std::string s = "solid " + name + "\n";
  for (const auto& t : tris) {
    s += "  facet normal 0 0 0\n    outer loop\n";
    for (const Vec3& v : t) s += fmt::format("      vertex {} {} {}\n", v.x, v.y, v.z);
    s += "    endloop\n  endfacet\n";
  }
  return s + "endsolid " + name + "\n";
}

void put_u32(std::string& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out += static_cast<char>((v >> (8 * i)) & 0xffu);
}
void put_float(std::string& out, float f) {
  put_u32(out, std::bit_cast<std::uint32_t>(f));
}

std::string binary_stl(const std::vector<Triangle>& tris, const std::string& header = "binary") {
  std::string s = header;
  s.resize(80, '\0');
  put_u32(s, static_cast<std::uint32_t>(tris.size()));
  for (const auto& t : tris) {
    for (int k = 0; k < 3; ++k) put_float(s, 0.0f); // normal: ignored
    for (const Vec3& v : t)
      for (int k = 0; k < 3; ++k) put_float(s, static_cast<float>(v[k]));
    s += std::string(2, '\0'); // attribute
  }
  return s;
}

// The message of the MeshFileError that parsing `bytes` throws ("" if it is accepted).
std::string refusal(const std::string& bytes, const std::string& name) {
  try {
    parse_stl(bytes, name);
  } catch (const MeshFileError& e) {
    return e.what();
  }
  return "";
}

std::uint32_t zlib_crc(const std::string& bytes) {
  return static_cast<std::uint32_t>(crc32(crc32(0L, Z_NULL, 0),
                                          reinterpret_cast<const Bytef*>(bytes.data()),
                                          static_cast<uInt>(bytes.size())));
}

void write_file(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  ASSERT_TRUE(out.good()) << path;
}

TEST(StlReader, AsciiAndBinaryGiveTheSameTriangles) {
  const auto tris = cube();
  const TriangleSoup a = parse_stl(ascii_stl(tris), "cube.stl");
  const TriangleSoup b = parse_stl(binary_stl(tris), "cube-binary.stl");
  ASSERT_EQ(a.triangles.size(), 12u);
  ASSERT_EQ(b.triangles.size(), 12u);
  for (std::size_t i = 0; i < tris.size(); ++i)
    for (int v = 0; v < 3; ++v) {
      EXPECT_EQ(a.triangles[i][v], tris[i][v]) << "ascii triangle " << i << " vertex " << v;
      EXPECT_EQ(b.triangles[i][v], tris[i][v]) << "binary triangle " << i << " vertex " << v;
    }
  EXPECT_EQ(a.dropped_degenerate, 0u);
  EXPECT_EQ(b.dropped_degenerate, 0u);
  EXPECT_EQ(b.bytes, 84u + 50u * 12u);
}

TEST(StlReader, BinaryWithASolidHeaderIsBinary) {
  const auto tris = cube();
  const std::string bytes = binary_stl(tris, "solid cube, exported as binary");
  const TriangleSoup s = parse_stl(bytes, "solid-binary.stl");
  ASSERT_EQ(s.triangles.size(), tris.size());
  EXPECT_EQ(s.triangles.front()[1], tris.front()[1]);
  EXPECT_EQ(s.triangles.back()[2], tris.back()[2]);

  // With a wrong count it cannot be told from a broken ASCII file; the message says both.
  std::string wrong = bytes;
  wrong[80] = 11;
  const std::string m = refusal(wrong, "solid-binary.stl");
  EXPECT_EQ(m.rfind("solid-binary.stl: line 1: ", 0), 0u) << m;
  EXPECT_NE(m.find("its header announces 11 triangles (634 bytes) but the file holds 684 bytes"),
            std::string::npos)
      << m;
}

TEST(StlReader, AsciiVariantsAreAccepted) {
  // Upper-case keywords, CRLF, blank lines, '+' signs, exponents, two solids in one file.
  const std::string text = "  SOLID part one\r\n\r\n"
                           "facet normal nan nan nan\r\n outer loop\r\n"
                           "  vertex +1 0 0\r\n  vertex 0 1e0 0\r\n  vertex 0 0 -1.5E+00\r\n"
                           " ENDLOOP\r\nendfacet\r\nendsolid part one\r\n"
                           "solid two\nFacet Normal 0 0 1\nouter loop\nvertex 0 0 0\n"
                           "vertex 2 0 0\nvertex 0 2 0\nendloop\nendfacet\nendsolid";
  const TriangleSoup s = parse_stl(text, "variants.stl");
  ASSERT_EQ(s.triangles.size(), 2u);
  EXPECT_EQ(s.triangles[0][0], (Vec3{1, 0, 0}));
  EXPECT_EQ(s.triangles[0][2], (Vec3{0, 0, -1.5}));
  EXPECT_EQ(s.triangles[1][1], (Vec3{2, 0, 0}));
}

TEST(StlReader, DegenerateTrianglesAreDroppedAndCounted) {
  std::vector<Triangle> tris = cube();
  const Vec3 o{0, 0, 0}, a{1, 1, 1};
  tris.insert(tris.begin() + 3, Triangle{o, a, a});                      // two equal vertices
  tris.insert(tris.begin() + 7, Triangle{o, a, Vec3{3, 3, 3}});          // exactly collinear
  tris.push_back(Triangle{o, a, Vec3{3, 3, 3 + 1e-13}});                 // collinear to round-off
  tris.push_back(Triangle{Vec3{5, 5, 5}, Vec3{5, 5, 5}, Vec3{5, 5, 5}}); // a point
  const Triangle thin{o, a, Vec3{3, 3, 3 + 1e-6}};                       // thin, but a triangle
  tris.push_back(thin);
  const TriangleSoup s = parse_stl(ascii_stl(tris), "degenerate.stl");
  EXPECT_EQ(s.dropped_degenerate, 4u);
  ASSERT_EQ(s.triangles.size(), 13u);
  const auto ref = cube();
  for (std::size_t i = 0; i < ref.size(); ++i) EXPECT_EQ(s.triangles[i], ref[i]) << i;
  EXPECT_EQ(s.triangles.back(), thin);

  // Huge and tiny coordinates neither overflow nor underflow the area test.
  const double big = 1e300, tiny = 1e-300;
  const TriangleSoup far =
      parse_stl(ascii_stl({Triangle{Vec3{-big, 0, 0}, Vec3{big, 0, 0}, Vec3{0, big, 0}},
                           Triangle{Vec3{-big, 0, 0}, Vec3{big, 0, 0}, Vec3{0, 0, 0}},
                           Triangle{Vec3{0, 0, 0}, Vec3{tiny, 0, 0}, Vec3{0, tiny, 0}}}),
                "extreme.stl");
  EXPECT_EQ(far.triangles.size(), 2u);
  EXPECT_EQ(far.dropped_degenerate, 1u);

  // A mesh of degenerate triangles only is empty.
  const std::string m = refusal(binary_stl({Triangle{o, a, a}, Triangle{a, a, a}}), "flat.stl");
  EXPECT_NE(m.find("flat.stl: the mesh is empty: all 2 of its triangles have zero area"),
            std::string::npos)
      << m;
}

TEST(StlReader, CrcAndSizeAreThoseOfTheBytes) {
  for (const std::string& bytes : {ascii_stl(cube()), binary_stl(cube())}) {
    const TriangleSoup s = parse_stl(bytes, "crc.stl");
    EXPECT_EQ(s.crc32, zlib_crc(bytes));
    EXPECT_NE(s.crc32, 0u);
    EXPECT_EQ(s.bytes, bytes.size());
  }
}

TEST(StlReader, ReadsFilesAndNamesMissingOnes) {
  const auto dir = test::temp_dir("stl_reader");
  const std::string bytes = binary_stl(cube(), "solid but binary");
  write_file(dir / "cube.stl", bytes);
  const TriangleSoup s = read_stl((dir / "cube.stl").string());
  EXPECT_EQ(s.triangles.size(), 12u);
  EXPECT_EQ(s.bytes, bytes.size());
  EXPECT_EQ(s.crc32, zlib_crc(bytes));

  const std::string missing = (dir / "no-such-wall.stl").string();
  try {
    read_stl(missing);
    FAIL() << "a missing file was read";
  } catch (const MeshFileError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(missing + ": ", 0), 0u) << e.what();
    EXPECT_NE(std::string(e.what()).find("no such file"), std::string::npos) << e.what();
  }
  try {
    read_stl(dir.string());
    FAIL() << "a directory was read";
  } catch (const MeshFileError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(dir.string() + ": ", 0), 0u) << e.what();
  }

  // Errors found while parsing a file name the file too.
  write_file(dir / "broken.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 1 2\n");
  const std::string broken = (dir / "broken.stl").string();
  try {
    read_stl(broken);
    FAIL() << "a broken file was read";
  } catch (const MeshFileError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(broken + ": line 4: ", 0), 0u) << e.what();
  }
  std::filesystem::remove_all(dir);
}

TEST(StlReader, BinaryErrorsNameTheTriangleAndTheSizes) {
  const std::string good = binary_stl(cube()); // 12 triangles, 684 bytes

  std::string m = refusal(good.substr(0, 400), "cut.stl");
  EXPECT_EQ(m.rfind("cut.stl: ", 0), 0u) << m;
  EXPECT_NE(m.find("announces 12 triangles (684 bytes) but the file holds 400 bytes"),
            std::string::npos)
      << m;
  EXPECT_NE(m.find("triangle 7 (byte offset 384)"), std::string::npos) << m;

  std::string fewer = good;
  fewer[80] = 11;
  m = refusal(fewer, "count.stl");
  EXPECT_NE(m.find("count.stl: binary STL with a wrong triangle count: the header announces 11 "
                   "triangles (634 bytes) but the file holds 684 bytes"),
            std::string::npos)
      << m;

  // An absurd count is refused before anything is allocated for it.
  std::string absurd = good;
  for (int i = 80; i < 84; ++i) absurd[static_cast<std::size_t>(i)] = '\xff';
  m = refusal(absurd, "absurd.stl");
  EXPECT_NE(m.find("announces 4294967295 triangles"), std::string::npos) << m;
  EXPECT_NE(m.find("holds 684 bytes"), std::string::npos) << m;

  // Triangle 5 (from 1) starts at 84 + 4 * 50 = 284; its vertex 2, y at 284 + 12 + 12 + 4.
  for (const float bad :
       {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
    std::string nan = good;
    std::string f;
    put_float(f, bad);
    nan.replace(284 + 12 + 12 + 4, 4, f);
    m = refusal(nan, "nan.stl");
    EXPECT_NE(m.find("nan.stl: triangle 5 of 12 (byte offset 284): vertex 2 has a coordinate "
                     "that is not finite"),
              std::string::npos)
        << m;
  }

  m = refusal(std::string("\x01\x02garbage", 9), "tiny.stl");
  EXPECT_NE(m.find("tiny.stl: not an STL file: 9 bytes"), std::string::npos) << m;

  m = refusal(binary_stl({}), "none.stl");
  EXPECT_EQ(m, "none.stl: the mesh holds no triangles");
}

struct Broken {
  const char* what;
  std::string from, to, expected;
};
// ctest lists a case by its name and this, not by a dump of the parameter's bytes.
void PrintTo(const Broken& c, std::ostream* os) {
  *os << c.what;
}

// Two facets; the line numbers are those of the file.
const char* const two_facets = "solid two\n"            // 1
                               "  facet normal 0 0 1\n" // 2
                               "    outer loop\n"       // 3
                               "      vertex 0 0 0\n"   // 4
                               "      vertex 1 0 0\n"   // 5
                               "      vertex 0 1 0\n"   // 6
                               "    endloop\n"          // 7
                               "  endfacet\n"           // 8
                               "  facet normal 0 0 1\n" // 9
                               "    outer loop\n"       // 10
                               "      vertex 1 0 0\n"   // 11
                               "      vertex 1 1 0\n"   // 12
                               "      vertex 0 1 0\n"   // 13
                               "    endloop\n"          // 14
                               "  endfacet\n"           // 15
                               "endsolid two\n";        // 16

class BrokenAscii : public ::testing::TestWithParam<Broken> {};

TEST(StlReader, TwoFacetsAreRead) {
  const TriangleSoup s = parse_stl(two_facets, "two.stl");
  ASSERT_EQ(s.triangles.size(), 2u);
  EXPECT_EQ(s.triangles[1][1], (Vec3{1, 1, 0}));

  // A solid without facets is fine when another one holds some.
  const TriangleSoup t =
      parse_stl(std::string("solid nothing\nendsolid nothing\n") + two_facets, "three-solids.stl");
  EXPECT_EQ(t.triangles.size(), 2u);
}

TEST_P(BrokenAscii, IsRefusedWithFileAndLine) {
  std::string text = two_facets;
  const auto at = text.find(GetParam().from);
  ASSERT_NE(at, std::string::npos);
  text.replace(at, GetParam().from.size(), GetParam().to);
  const std::string m = refusal(text, "two.stl");
  ASSERT_FALSE(m.empty()) << GetParam().what << ": accepted";
  EXPECT_EQ(m.rfind("two.stl: ", 0), 0u) << m;
  EXPECT_NE(m.find(GetParam().expected), std::string::npos) << GetParam().what << ": " << m;
}

INSTANTIATE_TEST_SUITE_P(
    Stl, BrokenAscii,
    ::testing::Values(
        Broken{"misspelled outer loop", "outer loop", "outer lop",
               "two.stl: line 3: expected \"outer loop\", found \"outer lop\""},
        Broken{"missing endloop", "    endloop\n  endfacet\n  facet", "  endfacet\n  facet",
               "two.stl: line 7: expected \"vertex\" or \"endloop\", found \"endfacet\""},
        Broken{"misspelled vertex", "vertex 1 1 0", "vertx 1 1 0",
               "two.stl: line 12: expected \"vertex\" or \"endloop\", found \"vertx 1 1 0\""},
        Broken{"misspelled endfacet", "  endfacet\n", "  endfacit\n",
               "two.stl: line 8: expected \"endfacet\", found \"endfacit\""},
        Broken{"misspelled facet", "  facet normal 0 0 1\n    outer loop\n      vertex 1 0 0",
               "  fac normal 0 0 1\n    outer loop\n      vertex 1 0 0",
               "two.stl: line 9: expected \"facet normal\" or \"endsolid\", found \"fac normal 0 0 "
               "1\""},
        Broken{"facet without normal", "  facet normal 0 0 1\n    outer loop\n      vertex 1 0 0",
               "  facet\n    outer loop\n      vertex 1 0 0",
               "two.stl: line 9: expected \"facet normal\""},
        Broken{"vertex with two numbers", "vertex 1 1 0", "vertex 1 1",
               "two.stl: line 12: a vertex has 3 numbers (x y z), this one 2"},
        Broken{"vertex with four numbers", "vertex 1 1 0", "vertex 1 1 0 4",
               "two.stl: line 12: a vertex has 3 numbers (x y z), this one 4"},
        Broken{"non-numeric coordinate", "vertex 1 1 0", "vertex 1 one 0",
               "two.stl: line 12: vertex coordinate \"one\" is not a number"},
        Broken{"number with trailing text", "vertex 1 1 0", "vertex 1 1 0.5x",
               "two.stl: line 12: vertex coordinate \"0.5x\" is not a number"},
        Broken{"comma decimal", "vertex 1 1 0", "vertex 1 1,5 0",
               "two.stl: line 12: vertex coordinate \"1,5\" is not a number"},
        Broken{"NaN coordinate", "vertex 1 1 0", "vertex 1 nan 0",
               "two.stl: line 12: vertex coordinate \"nan\" is not finite"},
        Broken{"infinite coordinate", "vertex 1 1 0", "vertex -inf 1 0",
               "two.stl: line 12: vertex coordinate \"-inf\" is not finite"},
        Broken{"overflowing coordinate", "vertex 1 1 0", "vertex 1 1 1e999",
               "two.stl: line 12: vertex coordinate \"1e999\" is out of the range"},
        Broken{"facet with two vertices", "      vertex 1 1 0\n", "",
               "two.stl: line 13: the facet begun on line 9 has 2 vertices"},
        Broken{"facet with four vertices", "      vertex 1 1 0\n",
               "      vertex 1 1 0\n      vertex 2 2 0\n",
               "two.stl: line 14: the facet begun on line 9 has more than 3 vertices"},
        Broken{"missing endsolid", "endsolid two\n", "",
               "two.stl: line 15: the file ends inside the solid begun on line 1 (no "
               "\"endsolid\")"},
        Broken{"ends inside a facet", "    endloop\n  endfacet\nendsolid two\n", "",
               "two.stl: line 13: the file ends inside the facet begun on line 9"},
        Broken{"text after endsolid", "endsolid two\n", "endsolid two\nthe end\n",
               "two.stl: line 17: expected another \"solid\""},
        Broken{"without solid (read as binary)", "solid two\n", "", "two.stl: binary STL"}),
    [](const ::testing::TestParamInfo<Broken>& p) {
      std::string n = p.param.what;
      for (auto& ch : n)
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
      return n;
    });

TEST(StlReader, EmptyAsciiMeshIsRefused) {
  EXPECT_EQ(refusal("solid empty\nendsolid empty\n", "empty.stl"),
            "empty.stl: the mesh holds no triangles");
  EXPECT_EQ(refusal("", "zero.stl").rfind("zero.stl: not an STL file: 0 bytes", 0), 0u);
}

} // namespace
} // namespace yuxi
