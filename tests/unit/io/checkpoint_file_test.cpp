// The restart file's envelope written in pieces (CheckpointFileWriter, as a distributed run
// streams its state into it) against the whole-payload writer, the readers' refusals of a
// damaged file, and the mapped reader against the whole-file reader.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <string>

#include "blockdem/io/atomic_file.hpp"
#include "blockdem/io/checkpoint_file.hpp"
#include "support/temp_path.hpp"

namespace blockdem {
namespace {

namespace fs = std::filesystem;

fs::path fresh(const std::string& name) {
  const fs::path dir = test::temp_path("checkpoint_file_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// A payload larger than the writer's buffer (1 MiB), so that pieces, the patch and the
// read-back checksum cross its bounds.
std::string payload() {
  std::string p;
  for (std::int64_t k = 0; p.size() < (std::size_t{3} << 20); ++k)
    p += std::to_string(k * 7919) + ';';
  return p;
}

// In pieces, with a length patched in after the fact (already on disk), the file is the bytes
// write_checkpoint_file writes for the whole payload, and it reads back to the payload. The
// previous checkpoint becomes NAME.prev alike. Tolerance: none (bytes).
TEST(CheckpointFileWriter, PiecesWithAPatchGiveTheWholeWritersBytes) {
  const fs::path dir = fresh("pieces");
  const std::string p = payload();
  write_checkpoint_file(dir / "whole.bdck", 42, "old");
  write_checkpoint_file(dir / "whole.bdck", 42, p);
  write_checkpoint_file(dir / "pieces.bdck", 42, "old");
  {
    CheckpointFileWriter w(dir / "pieces.bdck", 42);
    w.append(p.substr(0, 10));
    w.append(std::string(8, '\0'));  // patched below, once written to the file
    for (std::size_t at = 18; at < p.size(); at += 100'003) w.append(p.substr(at, 100'003));
    EXPECT_EQ(w.size(), p.size());
    w.patch(10, p.substr(10, 8));
    w.finish();
  }
  EXPECT_EQ(read_file_bytes(dir / "pieces.bdck"), read_file_bytes(dir / "whole.bdck"));
  EXPECT_EQ(read_checkpoint_file(dir / "pieces.bdck", 42), p);
  EXPECT_EQ(read_file_bytes(dir / "pieces.bdck.prev"), read_file_bytes(dir / "whole.bdck.prev"));
  EXPECT_FALSE(fs::exists(dir / ".pieces.bdck.tmp"));
}

// Pieces larger than the buffer go to the file without it, between small buffered ones; a
// patch into such a piece (on disk) and one into the buffered tail both land. Oracle: the
// whole-payload writer's bytes. Tolerance: none (bytes).
TEST(CheckpointFileWriter, PiecesLargerThanTheBufferGiveTheWholeWritersBytes) {
  const fs::path dir = fresh("large");
  const std::string p = payload();
  write_checkpoint_file(dir / "whole.bdck", 7, p);
  {
    CheckpointFileWriter w(dir / "pieces.bdck", 7);
    const std::size_t cut1 = 1000, cut2 = cut1 + (std::size_t{5} << 19), cut3 = cut2 + 3;
    const std::size_t hole = cut1 + 123'457;  // 16 bytes left to patch inside the large piece
    std::string large = p.substr(cut1, cut2 - cut1);
    large.replace(hole - cut1, 16, 16, '#');
    w.append(p.substr(0, cut1));    // buffered
    w.append(large);                // 2.5 MiB: past the buffer
    w.append(std::string(3, '#'));  // buffered again
    w.append(p.substr(cut3));       // the rest (buffered)
    EXPECT_EQ(w.size(), p.size());
    w.patch(hole, p.substr(hole, 16));         // inside the large piece, on disk
    w.patch(cut2 - 2, p.substr(cut2 - 2, 5));  // across from it into the small piece
    w.finish();
  }
  EXPECT_EQ(read_file_bytes(dir / "pieces.bdck"), read_file_bytes(dir / "whole.bdck"));
  EXPECT_EQ(read_checkpoint_file(dir / "pieces.bdck", 7), p);
}

// A writer destroyed before finish() (an error while the state was merged) leaves the last
// checkpoint as it was and no temporary file.
TEST(CheckpointFileWriter, UnfinishedLeavesTheLastCheckpoint) {
  const fs::path dir = fresh("unfinished");
  write_checkpoint_file(dir / "c.bdck", 7, "last");
  const std::string before = read_file_bytes(dir / "c.bdck");
  {
    CheckpointFileWriter w(dir / "c.bdck", 7);
    w.append(payload());
  }
  EXPECT_EQ(read_file_bytes(dir / "c.bdck"), before);
  EXPECT_FALSE(fs::exists(dir / "c.bdck.prev"));
  EXPECT_FALSE(fs::exists(dir / ".c.bdck.tmp"));
}

// Bad input: a file written in pieces, then truncated by one byte or with one payload byte
// changed, is refused with the file's name and the reason.
TEST(CheckpointFileWriter, DamagedFileIsRefusedWithItsReason) {
  const fs::path dir = fresh("damaged");
  {
    CheckpointFileWriter w(dir / "c.bdck", 7);
    w.append(payload());
    w.finish();
  }
  const std::string good = read_file_bytes(dir / "c.bdck");
  const auto refusal = [&](const std::string& bytes) {
    write_file_atomically(dir / "c.bdck", bytes);
    try {
      read_checkpoint_file(dir / "c.bdck", 7);
    } catch (const CheckpointError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  const std::string truncated = refusal(good.substr(0, good.size() - 1));
  EXPECT_NE(truncated.find((dir / "c.bdck").string() + ": truncated"), std::string::npos)
      << truncated;
  std::string flipped = good;
  flipped[1000] ^= 1;
  EXPECT_NE(refusal(flipped).find("corrupt (checksum mismatch)"), std::string::npos);
}

// The mapped reader gives the payload read_checkpoint_file gives, byte for byte, also after
// pages were given back behind a reader (they are read from the file again) and across the
// checksum's 16 MiB chunks. Tolerance: none (bytes).
TEST(MappedCheckpoint, PayloadIsTheReadersAlsoAfterPagesAreGivenBack) {
  const fs::path dir = fresh("mapped");
  std::string p;
  for (std::int64_t k = 0; p.size() < (std::size_t{40} << 20); ++k)
    p += std::to_string(k * 104729) + ',';
  write_checkpoint_file(dir / "c.bdck", 11, p);
  const MappedCheckpoint empty_one = [&] {
    write_checkpoint_file(dir / "e.bdck", 11, "");
    return MappedCheckpoint(dir / "e.bdck", 11);
  }();
  EXPECT_TRUE(empty_one.payload().empty());
  MappedCheckpoint m(dir / "c.bdck", 11);
  ASSERT_EQ(m.payload().size(), p.size());
  EXPECT_TRUE(m.payload() == p);
  m.release_before(p.size() / 2);
  EXPECT_TRUE(m.payload() == p);
  m.release_before(p.size() + 4096);  // past the end: clamped
  EXPECT_TRUE(m.payload() == p);
  EXPECT_TRUE(m.payload() == read_checkpoint_file(dir / "c.bdck", 11));
}

// Bad input: the mapped reader refuses what read_checkpoint_file refuses, with the same message
// (file name and reason): a missing file, an empty one, a damaged magic, a truncated one, one
// byte changed, another scenario.
TEST(MappedCheckpoint, RefusesWhatTheReaderRefusesWithTheSameMessage) {
  const fs::path dir = fresh("mapped_bad");
  write_checkpoint_file(dir / "c.bdck", 7, payload());
  const std::string good = read_file_bytes(dir / "c.bdck");
  const auto message = [](const auto& read) {
    try {
      read();
    } catch (const CheckpointError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  const auto both = [&](const std::string& bytes, std::uint64_t hash, const char* reason) {
    write_file_atomically(dir / "c.bdck", bytes);
    const std::string read = message([&] { read_checkpoint_file(dir / "c.bdck", hash); });
    const std::string mapped = message([&] { MappedCheckpoint(dir / "c.bdck", hash); });
    EXPECT_EQ(mapped, read);
    EXPECT_NE(read.find((dir / "c.bdck").string() + ": " + reason), std::string::npos) << read;
  };
  both("", 7, "not a blockdem checkpoint");
  std::string magic = good;
  magic[1] = 'X';
  both(magic, 7, "not a blockdem checkpoint");
  both(good.substr(0, 20), 7, "truncated (shorter than a header)");
  both(good.substr(0, good.size() - 1), 7, "truncated or padded");
  std::string flipped = good;
  flipped[good.size() / 2] ^= 1;
  both(flipped, 7, "corrupt (checksum mismatch)");
  both(good, 8, "written for another scenario or other run options");
  fs::remove(dir / "c.bdck");
  EXPECT_EQ(message([&] { MappedCheckpoint(dir / "c.bdck", 7); }),
            (dir / "c.bdck").string() + ": cannot be read");
  EXPECT_EQ(message([&] { read_checkpoint_file(dir / "c.bdck", 7); }),
            (dir / "c.bdck").string() + ": cannot be read");
}

}  // namespace
}  // namespace blockdem
