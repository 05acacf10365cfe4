#pragma once
/// @file
/// An MCAP file (mcap.dev/spec, version 0, the container of ROS 2 bags, Foxglove and Lichtblick),
/// written front to back into a sink: the magic, the header, the schemas and channels, the
/// messages in zstd-compressed chunks (zstd from Debian's libzstd, CRC-32 from libdeflate), each
/// chunk followed by one message index per channel, the data end record with the data section's
/// CRC, then the summary (schemas, channels, statistics, chunk indexes), the summary offsets,
/// the footer and the closing magic. Written here rather than taken from a library: Debian 12
/// packages no MCAP library, and the format is small.
///
/// Messages must be written in log-time order (each message index then lists its chunk's
/// messages in order). A chunk is closed once it holds `chunk_size` bytes of records.

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace floornav {

struct McapOptions {
  std::string profile{"ros2"};
  std::string library{"floornav"};   ///< the header's library field
  std::size_t chunk_size{1u << 18};  ///< bytes of uncompressed records per chunk
  /// -3: zstd's fast strategy without Huffman-coded literals, skipping faster over bytes that
  /// match nothing: on a run's chunks (they compress about 3-16 times) a sixth faster than -1 and
  /// a quarter faster than level 1, for chunks about a tenth bigger (files 3-7 %)
  int zstd_level{-3};
  /// log2 of the entries of zstd's match table: a message of a run mostly repeats the one before
  /// on its channel, which a small table finds as well as a big one, faster (it stays in cache).
  int zstd_hash_log{10};
};

class McapWriter {
 public:
  using Sink = std::function<void(std::string_view)>;

  /// Writes the magic and the header to `sink`.
  McapWriter(Sink sink, McapOptions options = {});
  ~McapWriter();
  McapWriter(const McapWriter&) = delete;
  McapWriter& operator=(const McapWriter&) = delete;

  /// A schema (e.g. "nav_msgs/msg/Odometry", "ros2msg", its definition); ids count from 1.
  std::uint16_t add_schema(std::string_view name, std::string_view encoding, std::string_view data);
  /// A channel of `schema_id` on `topic`; ids count from 0. Both records go to the data section
  /// at once (before any message of the channel) and again into the summary.
  std::uint16_t add_channel(std::uint16_t schema_id, std::string_view topic,
                            std::string_view message_encoding,
                            const std::vector<std::pair<std::string, std::string>>& metadata);
  /// One message; `log_time` (ns) must not decrease from one call to the next.
  void write(std::uint16_t channel_id, std::uint64_t log_time, std::uint64_t publish_time,
             std::string_view data);
  /// Closes the last chunk and writes the summary, the footer and the closing magic.
  void finish();

 private:
  struct IndexEntry {
    std::uint64_t time;
    std::uint64_t offset;  ///< in the chunk's uncompressed records
  };
  struct ChunkIndex {
    std::uint64_t start_time, end_time, offset, length;
    std::map<std::uint16_t, std::uint64_t> message_index_offsets;
    std::uint64_t message_index_length, compressed_size, uncompressed_size;
  };

  void emit(std::string_view bytes, bool data_section);
  void close_chunk();
  void flush_output();

  Sink sink_;
  McapOptions options_;
  std::string out_;              ///< bytes not yet handed to the sink
  std::uint64_t position_{0};    ///< bytes emitted so far (the file offset of out_'s end)
  std::uint32_t data_crc_{0};    ///< running CRC-32 of the data section
  std::string schema_records_;   ///< each schema record, for the summary
  std::string channel_records_;  ///< each channel record, for the summary
  std::uint16_t schemas_{0};
  std::uint16_t channels_{0};

  std::string chunk_;  ///< the open chunk's records, uncompressed
  std::uint64_t chunk_start_{0}, chunk_end_{0};
  std::vector<std::vector<IndexEntry>> chunk_index_;  ///< per channel id: the open chunk's
  std::unique_ptr<char[]> compressed_;                ///< scratch for a chunk's compressed records
  std::size_t compressed_capacity_{0};
  std::vector<ChunkIndex> chunk_indexes_;
  std::string message_head_;   ///< scratch: a message record's fields before its data
  std::string index_records_;  ///< scratch: a chunk's message index records

  std::uint64_t message_count_{0};
  std::uint64_t first_time_{0}, last_time_{0};
  std::vector<std::uint64_t> channel_counts_;  ///< per channel id
  struct ZstdContext;
  std::unique_ptr<ZstdContext> zstd_;
  bool finished_{false};
};

}  // namespace floornav
