// The MCAP container byte by byte: the magic at both ends, the header, the records a reader
// seeks by (footer -> summary offsets -> groups, chunk index -> chunk -> message indexes ->
// messages), the CRCs (zlib's crc32 here, as a reader computes it), and the zstd chunk
// decompressed back. The reference readers check the whole files (tests/mcap/read_bag_test.mjs).
#include "floornav/io/mcap_writer.hpp"

#include <gtest/gtest.h>
#include <zlib.h>
#include <zstd.h>

#include <cstdint>
#include <stdexcept>
#include <string>

namespace floornav {
namespace {

std::uint64_t le(const std::string& s, std::size_t at, int bytes) {
  std::uint64_t v = 0;
  for (int i = bytes - 1; i >= 0; --i) v = (v << 8) | static_cast<unsigned char>(s[at + i]);
  return v;
}

std::uint32_t crc(std::string_view s) {
  return static_cast<std::uint32_t>(
      crc32(0, reinterpret_cast<const Bytef*>(s.data()), static_cast<uInt>(s.size())));
}

const std::string kMagic("\x89MCAP0\r\n", 8);

/// Where the summary group of records with `opcode` starts (from the summary offsets).
std::size_t group_start(const std::string& f, char opcode) {
  const std::size_t footer = f.size() - 8 - 29;
  for (std::size_t at = le(f, footer + 17, 8); at < footer; at += 9 + le(f, at + 1, 8))
    if (f[at + 9] == opcode) return le(f, at + 10, 8);
  return std::string::npos;
}

/// A file with one schema, two channels and three messages.
std::string small_file(std::size_t chunk_size = 1u << 20) {
  std::string file;
  McapWriter w([&](std::string_view piece) { file.append(piece); },
               McapOptions{.library = "test", .chunk_size = chunk_size});
  const auto schema = w.add_schema("std_msgs/msg/String", "ros2msg", "string data\n");
  EXPECT_EQ(schema, 1);
  const auto a = w.add_channel(schema, "/a", "cdr", {{"offered_qos_profiles", ""}});
  const auto b = w.add_channel(schema, "/b", "cdr", {});
  EXPECT_EQ(a, 0);
  EXPECT_EQ(b, 1);
  w.write(a, 10, 10, "one");
  w.write(b, 20, 20, "two");
  w.write(a, 20, 20, "three");
  w.finish();
  return file;
}

TEST(McapWriter, MagicHeaderAndFooterAtTheirPlaces) {
  const std::string f = small_file();
  ASSERT_GT(f.size(), 2 * kMagic.size());
  EXPECT_EQ(f.substr(0, 8), kMagic);
  EXPECT_EQ(f.substr(f.size() - 8), kMagic);
  // Header: opcode 1, length, profile "ros2", library "test".
  EXPECT_EQ(f[8], '\x01');
  EXPECT_EQ(le(f, 9, 8), 4u + 4u + 4u + 4u);
  EXPECT_EQ(f.substr(17, 8), std::string("\x04\0\0\0ros2", 8));
  // Footer: opcode 2, length 20, then the summary start, the summary offsets' start, the CRC.
  const std::size_t footer = f.size() - 8 - 29;
  EXPECT_EQ(f[footer], '\x02');
  EXPECT_EQ(le(f, footer + 1, 8), 20u);
  const std::uint64_t summary = le(f, footer + 9, 8), offsets = le(f, footer + 17, 8);
  EXPECT_EQ(f[summary], '\x03');  // the summary starts with the schemas
  EXPECT_EQ(f[offsets], '\x0e');  // a summary offset record
  // The summary CRC covers the summary, the offsets and the footer up to the CRC field.
  EXPECT_EQ(le(f, footer + 25, 4), crc(std::string_view(f).substr(summary, footer + 25 - summary)));
  // The data end record just before the summary: the CRC of everything before it.
  const std::size_t data_end = summary - 13;
  EXPECT_EQ(f[data_end], '\x0f');
  EXPECT_EQ(le(f, data_end + 9, 4), crc(std::string_view(f).substr(0, data_end)));
}

TEST(McapWriter, SummaryOffsetsPointAtTheirGroups) {
  const std::string f = small_file();
  const std::size_t footer = f.size() - 8 - 29;
  std::size_t at = le(f, footer + 17, 8);
  std::string opcodes;
  while (at < footer) {
    ASSERT_EQ(f[at], '\x0e');
    const char group = f[at + 9];
    const std::uint64_t start = le(f, at + 10, 8), length = le(f, at + 18, 8);
    EXPECT_EQ(f[start], group);  // the group's first record has the group's opcode
    EXPECT_GT(length, 0u);
    opcodes += group;
    at += 9 + le(f, at + 1, 8);
  }
  EXPECT_EQ(opcodes, std::string("\x03\x04\x0b\x08"));  // schemas, channels, statistics, chunks
}

TEST(McapWriter, ChunksDecompressToTheMessagesTheirIndexesName) {
  const std::string f = small_file();
  // The only chunk index, in the summary.
  const std::size_t index = group_start(f, '\x08');
  ASSERT_NE(index, std::string::npos);
  ASSERT_EQ(f[index], '\x08');
  const std::uint64_t start_time = le(f, index + 9, 8), end_time = le(f, index + 17, 8);
  EXPECT_EQ(start_time, 10u);
  EXPECT_EQ(end_time, 20u);
  const std::uint64_t chunk = le(f, index + 25, 8), chunk_length = le(f, index + 33, 8);
  ASSERT_EQ(f[chunk], '\x06');
  EXPECT_EQ(9 + le(f, chunk + 1, 8), chunk_length);
  // Chunk: start, end, uncompressed size, CRC, "zstd", the compressed records.
  const std::uint64_t size = le(f, chunk + 25, 8);
  const std::uint32_t chunk_crc = static_cast<std::uint32_t>(le(f, chunk + 33, 4));
  EXPECT_EQ(f.substr(chunk + 37, 8), std::string("\x04\0\0\0zstd", 8));
  const std::uint64_t compressed = le(f, chunk + 45, 8);
  std::string records(size, '\0');
  ASSERT_EQ(ZSTD_decompress(records.data(), size, f.data() + chunk + 53, compressed), size);
  EXPECT_EQ(crc(records), chunk_crc);
  // Three message records: channel, sequence (per channel), log and publish time, data.
  std::size_t at = 0;
  std::vector<std::string> data;
  std::vector<std::uint64_t> offsets;
  while (at < records.size()) {
    ASSERT_EQ(records[at], '\x05');
    offsets.push_back(at);
    const std::uint64_t len = le(records, at + 1, 8);
    data.push_back(records.substr(at + 9 + 22, len - 22));
    at += 9 + len;
  }
  EXPECT_EQ(data, (std::vector<std::string>{"one", "two", "three"}));
  EXPECT_EQ(le(records, offsets[2] + 11, 4), 1u);  // channel 0's second message: sequence 1
  // The message index of channel 0 follows the chunk: (10, offset 0), (20, offset of "three").
  const std::size_t mi = chunk + chunk_length;
  ASSERT_EQ(f[mi], '\x07');
  EXPECT_EQ(le(f, mi + 9, 2), 0u);
  EXPECT_EQ(le(f, mi + 11, 4), 32u);
  EXPECT_EQ(le(f, mi + 15, 8), 10u);
  EXPECT_EQ(le(f, mi + 23, 8), offsets[0]);
  EXPECT_EQ(le(f, mi + 31, 8), 20u);
  EXPECT_EQ(le(f, mi + 39, 8), offsets[2]);
}

TEST(McapWriter, ASmallChunkSizeMakesAChunkPerMessage) {
  const std::string f = small_file(1);
  std::size_t chunks = 0;
  for (std::size_t at = group_start(f, '\x08'); f[at] == '\x08'; at += 9 + le(f, at + 1, 8)) {
    EXPECT_EQ(f[le(f, at + 25, 8)], '\x06');  // each points at a chunk
    ++chunks;
  }
  EXPECT_EQ(chunks, 3u);
}

TEST(McapWriter, RefusesMessagesOutOfTimeOrderOrOnUnknownChannels) {
  std::string file;
  McapWriter w([&](std::string_view piece) { file.append(piece); });
  const auto c = w.add_channel(w.add_schema("s", "ros2msg", ""), "/c", "cdr", {});
  w.write(c, 5, 5, "x");
  EXPECT_THROW(w.write(c, 4, 4, "y"), std::invalid_argument);
  EXPECT_THROW(w.write(7, 6, 6, "y"), std::invalid_argument);
}

}  // namespace
}  // namespace floornav
