// The distributed engine gives the answers of the serial one (tests/mpi/, run with mpirun -np
// 1, 2 and 4 by ctest): exchanges in pieces, shared files, checkpoints read in
// shares, cut planes kept on loading, snapshots.
#include "mpi_support.hpp"

#include <gtest/gtest.h>

namespace yuxi {
namespace {

using namespace mpi_test;

// A message of `bytes` from rank `from`, different at every byte and for every sender.
std::string message_of(int from, std::size_t bytes) {
  std::string m(bytes, '\0');
  for (std::size_t k = 0; k < bytes; ++k) m[k] = static_cast<char>((k * 131 + 7 * from) % 251);
  return m;
}

// A started exchange travels in pieces (comm.hpp), blocking ones in one message: messages of
// no byte, of one piece, of many, and of more than max_exchange_pieces arrive whole either way.
TEST(Mpi, ExchangesInPiecesArriveWhole) {
  const Comm comm = Comm::world();
  const int to = (comm.rank() + 1) % comm.size();
  const int from = (comm.rank() + comm.size() - 1) % comm.size();
  const std::size_t sizes[] = {0,
                               1,
                               Comm::exchange_piece_bytes - 1,
                               Comm::exchange_piece_bytes,
                               Comm::exchange_piece_bytes + 1,
                               100000,
                               Comm::exchange_piece_bytes * Comm::max_exchange_pieces * 3 + 5};
  int tag = 900;
  for (const std::size_t bytes : sizes) {
    for (const bool started : {false, true}) {
      const std::string out = message_of(comm.rank(), bytes);
      std::string in = "stale";
      if (started) {
        Comm::Exchange e = comm.start_send_receive(to, out, from, in, bytes, tag);
        comm.wait_receive(e);
        comm.wait_send(e);
      } else {
        comm.send_receive(to, out, from, in, bytes, tag);
      }
      EXPECT_EQ(in, message_of(from, bytes)) << bytes << " bytes";
      tag += 2;
    }
  }
}

TEST(Mpi, SharedFileHoldsEveryRanksBytesInRankOrder) {
  const Comm comm = Comm::world();
  const auto dir = shared_temp_dir("shared_file");
  const auto path = dir / "f.bin";
  const std::string mine =
      message_of(comm.rank(), 1000 + 3000 * static_cast<std::size_t>(comm.rank()));
  std::uint64_t end = 0;
  {
    SharedFile f(comm, path, SharedFile::Mode::truncate);
    EXPECT_EQ(f.size_at_open(), 0u);
    if (comm.root()) f.write_at(0, "head");
    end = f.write_in_rank_order(4, mine);
    f.close(true);
  }
  { // appended after what the file holds
    SharedFile f(comm, path, SharedFile::Mode::append);
    EXPECT_EQ(f.size_at_open(), end);
    f.write_in_rank_order(f.size_at_open(), mine);
    f.close(false);
  }
  if (comm.root()) {
    std::string expected;
    for (int r = 0; r < comm.size(); ++r)
      expected += message_of(r, 1000 + 3000 * static_cast<std::size_t>(r));
    EXPECT_EQ(end, 4 + expected.size());
    EXPECT_EQ(slurp(path), "head" + expected + expected);
    std::filesystem::remove_all(dir);
  }
}

TEST(Mpi, SharedFileReportsAFailureOnEveryRank) {
  const Comm comm = Comm::world();
  const auto dir = shared_temp_dir("shared_file_missing");
  const auto path = dir / "no_such_folder" / "f.bin";
  bool thrown = false;
  try {
    SharedFile f(comm, path, SharedFile::Mode::truncate);
    f.write_in_rank_order(0, "x");
    f.close(false);
  } catch (const std::runtime_error& e) {
    thrown = true;
    EXPECT_NE(std::string(e.what()).find("no_such_folder"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(thrown);
  if (comm.root()) std::filesystem::remove_all(dir);
}

// A checkpoint that every rank wrote is read back in shares: each rank reads and holds its own
// section alone, loads it into a new simulation to the same state, and a damaged byte in any
// rank's section is refused on every rank (the file's CRC, combined from the ranks' parts).
TEST(Mpi, CheckpointIsReadBackInSharesAndVerifiedWhole) {
  const Comm comm = Comm::world();
  Simulation sim = dense(comm);
  sim.run(31); // (a checkpoint may follow any step)
  const auto dir = shared_temp_dir("checkpoint_shares");
  const auto path = dir / "c.yxc";
  write_checkpoint(path, "scene text", sim);
  ArchiveWriter mine;
  sim.save_state(mine);

  const CheckpointData d = read_checkpoint(path, comm);
  EXPECT_EQ(d.scene_text, "scene text");
  EXPECT_EQ(d.step, 31);
  EXPECT_EQ(d.n_sections, static_cast<std::uint64_t>(comm.size()));
  EXPECT_EQ(d.first_section, static_cast<std::uint64_t>(comm.rank()));
  ASSERT_EQ(d.sections.size(), 1u);
  EXPECT_TRUE(d.sections[0] == mine.data()) << "this rank's own section";
  Simulation loaded = dense(comm); // continues as the original, bit for bit
  apply_checkpoint(d, loaded);
  sim.run(20);
  loaded.run(20);
  expect_same(snapshot(sim), snapshot(loaded), 0.0, 0.0);

  if (comm.root()) { // a group of one reads every section
    const CheckpointData all = read_checkpoint(path, Comm::self());
    EXPECT_EQ(all.sections.size(), static_cast<std::size_t>(comm.size()));
    EXPECT_TRUE(all.sections[0] == mine.data());
  }
  comm.barrier();
  if (comm.rank() == comm.size() - 1) { // a byte of the last rank's section
    std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(static_cast<std::streamoff>(std::filesystem::file_size(path) - 4 - 100));
    f.put('\x5a');
  }
  comm.barrier();
  bool refused = false;
  try {
    read_checkpoint(path, comm);
  } catch (const CheckpointError& e) {
    refused = true;
    EXPECT_NE(std::string(e.what()).find("c.yxc: checksum mismatch"), std::string::npos)
        << e.what();
  }
  EXPECT_TRUE(refused);
  comm.barrier();
  if (comm.root()) std::filesystem::remove_all(dir);
}

// A run resumed on as many ranks keeps the saved cut planes, even where the saved run was due
// to move them at its next list build (here the first, list_builds() == 1): the loaded run
// balances at that build too, not while loading, with no list to weigh the particles by.
TEST(Mpi, ALoadedRunKeepsItsCutPlanesUntilItsNextBalancing) {
  const Comm comm = Comm::world();
  Simulation sim = dense(comm);
  ASSERT_EQ(sim.list_builds(), 1);
  const auto dir = shared_temp_dir("checkpoint_cuts");
  write_checkpoint(dir / "c.yxc", "", sim);
  Simulation loaded = dense(comm);
  apply_checkpoint(read_checkpoint(dir / "c.yxc", comm), loaded);
  for (int a = 0; a < 3; ++a)
    EXPECT_EQ(loaded.decomposition().cuts(a), sim.decomposition().cuts(a)) << "axis " << a;
  sim.request_list_build();
  loaded.request_list_build();
  sim.step();
  loaded.step();
  for (int a = 0; a < 3; ++a)
    EXPECT_EQ(loaded.decomposition().cuts(a), sim.decomposition().cuts(a)) << "axis " << a;
  comm.barrier();
  if (comm.root()) std::filesystem::remove_all(dir);
}

// Every rank writes its own particles into the one VTK file and the one LAMMPS dump frame; each
// particle is in them once, with its values, whatever the number of ranks.
TEST(Mpi, SnapshotsHoldEveryParticleOnceFromEveryRank) {
  const Comm comm = Comm::world();
  Simulation sim = dense(comm);
  sim.run(50);
  const auto dir = shared_temp_dir("snapshots");
  write_vtu(dir / "p.vtu", sim.particles(), comm);
  const Box box{{-6, -6, -6}, {6, 6, 6}, {Boundary::periodic, Boundary::periodic, Boundary::wall}};
  {
    LammpsDumpWriter dump(dir / "p.lammpstrj", box, std::nullopt, comm);
    dump.write(sim.particles(), 50);
  }
  const ParticleStore all = sim.gather_particles();
  if (!comm.root()) return;
  std::map<GlobalId, std::size_t> index; // gathered particle of each id
  for (std::size_t i = 0; i < all.n_owned(); ++i) index[all.gid[i]] = i;
  ASSERT_EQ(index.size(), 1440u);

  // The dump: its header counts them all, and each line is one particle, once.
  std::istringstream dump(slurp(dir / "p.lammpstrj"));
  std::vector<std::string> lines;
  for (std::string l; std::getline(dump, l);) lines.push_back(l);
  ASSERT_EQ(lines.size(), 9 + index.size());
  EXPECT_EQ(lines[3], "1440");
  std::set<GlobalId> seen;
  for (std::size_t k = 9; k < lines.size(); ++k) {
    std::istringstream row(lines[k]);
    GlobalId id = 0;
    int type = 0;
    double radius = 0, mass = 0, x = 0;
    row >> id >> type >> radius >> mass >> x;
    ASSERT_TRUE(index.count(id)) << lines[k];
    EXPECT_TRUE(seen.insert(id).second) << "particle " << id << " twice";
    EXPECT_NEAR(radius, all.radius[index[id]], 1e-7); // (8 significant digits)
    EXPECT_NEAR(x, all.x[index[id]].x, 1e-8);
  }

  // The VTK file: the ids and points arrays hold every particle once, ids with their points.
  const std::string vtu = slurp(dir / "p.vtu");
  EXPECT_NE(vtu.find("NumberOfPoints=\"1440\""), std::string::npos);
  const std::size_t data = vtu.find('_', vtu.find("<AppendedData")) + 1;
  const auto array_at = [&](const std::string& name) {
    const std::size_t decl = vtu.find("Name=\"" + name + "\"");
    const std::size_t off = vtu.find("offset=\"", decl) + 8;
    const std::size_t at = data + std::stoull(vtu.substr(off, vtu.find('"', off) - off));
    std::uint64_t size = 0;
    std::memcpy(&size, vtu.data() + at, sizeof size);
    return std::make_pair(at + sizeof size, size);
  };
  const auto [ids, id_bytes] = array_at("id");
  const auto [points, point_bytes] = array_at("Points");
  ASSERT_EQ(id_bytes, 1440u * 8);
  ASSERT_EQ(point_bytes, 1440u * 24);
  seen.clear();
  for (std::size_t k = 0; k < 1440; ++k) {
    std::int64_t id = 0;
    double p[3];
    std::memcpy(&id, vtu.data() + ids + 8 * k, 8);
    std::memcpy(p, vtu.data() + points + 24 * k, 24);
    ASSERT_TRUE(index.count(id)) << "id " << id;
    EXPECT_TRUE(seen.insert(id).second) << "particle " << id << " twice";
    const Vec3& x = all.x[index[id]];
    EXPECT_EQ(p[0], x.x);
    EXPECT_EQ(p[1], x.y);
    EXPECT_EQ(p[2], x.z);
  }
  // The last cell's offset is the number of points: the ranks' cells follow each other.
  const auto [offsets, offset_bytes] = array_at("offsets");
  std::int64_t last = 0;
  std::memcpy(&last, vtu.data() + offsets + offset_bytes - 8, 8);
  EXPECT_EQ(last, 1440);
  EXPECT_NE(vtu.rfind("</VTKFile>"), std::string::npos);
  std::filesystem::remove_all(dir);
}

} // namespace
} // namespace yuxi
