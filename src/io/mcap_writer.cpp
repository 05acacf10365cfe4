#include "floornav/io/mcap_writer.hpp"

#include <libdeflate.h>
#include <zstd.h>

#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#endif

#include <bit>
#include <stdexcept>
#include <utility>

namespace floornav {

namespace {

constexpr std::string_view kMagic{"\x89MCAP0\r\n", 8};
// Record opcodes (the spec's table).
enum Opcode : std::uint8_t {
  kHeader = 0x01,
  kFooter = 0x02,
  kSchema = 0x03,
  kChannel = 0x04,
  kMessage = 0x05,
  kChunk = 0x06,
  kMessageIndex = 0x07,
  kChunkIndex = 0x08,
  kStatistics = 0x0B,
  kSummaryOffset = 0x0E,
  kDataEnd = 0x0F,
};
/// Bytes collected before they go to the sink: the buffer is touched whole, and a fresh page
/// costs a page fault (about 10 us on a virtual machine), so it is kept small and never grows.
constexpr std::size_t kOutputPiece = 1u << 16;

// Little-endian fields appended to a byte string (the spec's integer, string and map forms).
template <class T>
void le(std::string& out, T v) {
  if constexpr (std::endian::native == std::endian::little) {
    out.append(reinterpret_cast<const char*>(&v), sizeof(T));
  } else {
    for (std::size_t i = 0; i < sizeof(T); ++i)
      out.push_back(static_cast<char>((static_cast<std::uint64_t>(v) >> (8 * i)) & 0xFF));
  }
}
void u16(std::string& out, std::uint16_t v) {
  le(out, v);
}
void u32(std::string& out, std::uint32_t v) {
  le(out, v);
}
void u64(std::string& out, std::uint64_t v) {
  le(out, v);
}
void str(std::string& out, std::string_view s) {
  u32(out, static_cast<std::uint32_t>(s.size()));
  out.append(s);
}

/// Appends a record: opcode, content length, content.
void record(std::string& out, Opcode op, std::string_view content) {
  out.push_back(static_cast<char>(op));
  u64(out, content.size());
  out.append(content);
}

std::uint32_t crc_update(std::uint32_t crc, std::string_view bytes) {
  return libdeflate_crc32(crc, bytes.data(), bytes.size());
}

/// Maps the pages of a buffer that is about to be written whole, in one call (Linux 5.14+), rather
/// than one page fault per page on first touch: about 10 us each on a virtual machine, a tenth
/// of a small run's bag. Elsewhere, or when it fails, the pages fault in as they are touched.
void prefault([[maybe_unused]] const char* data, [[maybe_unused]] std::size_t size) {
#if defined(__linux__) && defined(MADV_POPULATE_WRITE)
  const auto page = static_cast<std::uintptr_t>(::sysconf(_SC_PAGESIZE));
  const auto at = reinterpret_cast<std::uintptr_t>(data);
  const std::uintptr_t begin = (at + page - 1) & ~(page - 1), end = (at + size) & ~(page - 1);
  if (end > begin) ::madvise(reinterpret_cast<void*>(begin), end - begin, MADV_POPULATE_WRITE);
#endif
}

}  // namespace

struct McapWriter::ZstdContext {
  ZSTD_CCtx* cctx{ZSTD_createCCtx()};
  ~ZstdContext() { ZSTD_freeCCtx(cctx); }
};

McapWriter::McapWriter(Sink sink, McapOptions options)
    : sink_(std::move(sink)), options_(std::move(options)), zstd_(new ZstdContext) {
  if (zstd_->cctx == nullptr) throw std::bad_alloc();
  for (const auto& [parameter, value] : {std::pair{ZSTD_c_compressionLevel, options_.zstd_level},
                                         std::pair{ZSTD_c_hashLog, options_.zstd_hash_log}}) {
    const std::size_t status = ZSTD_CCtx_setParameter(zstd_->cctx, parameter, value);
    if (ZSTD_isError(status))
      throw std::invalid_argument(std::string("zstd: ") + ZSTD_getErrorName(status));
  }
  // Grown once, not message by message: a chunk's records (a chunk closes after the message that
  // passes chunk_size; a bigger one grows it) and a piece of output.
  chunk_.reserve(options_.chunk_size + (1u << 12));
  out_.reserve(kOutputPiece);
  prefault(chunk_.data(), chunk_.capacity());
  prefault(out_.data(), out_.capacity());
  emit(kMagic, true);
  std::string header;
  str(header, options_.profile);
  str(header, options_.library);
  std::string rec;
  record(rec, kHeader, header);
  emit(rec, true);
}

McapWriter::~McapWriter() = default;

void McapWriter::emit(std::string_view bytes, bool data_section) {
  if (data_section) data_crc_ = crc_update(data_crc_, bytes);
  position_ += bytes.size();
  if (out_.size() + bytes.size() > kOutputPiece) {
    flush_output();
    if (bytes.size() >= kOutputPiece) {  // too big for the buffer: straight to the sink
      sink_(bytes);
      return;
    }
  }
  out_.append(bytes);
}

void McapWriter::flush_output() {
  if (!out_.empty()) sink_(out_);
  out_.clear();
}

std::uint16_t McapWriter::add_schema(std::string_view name, std::string_view encoding,
                                     std::string_view data) {
  const auto id = static_cast<std::uint16_t>(++schemas_);
  std::string content;
  u16(content, id);
  str(content, name);
  str(content, encoding);
  str(content, data);  // bytes with a uint32 length: the same form as a string
  std::string rec;
  record(rec, kSchema, content);
  emit(rec, true);
  schema_records_ += rec;
  return id;
}

std::uint16_t McapWriter::add_channel(
    std::uint16_t schema_id, std::string_view topic, std::string_view message_encoding,
    const std::vector<std::pair<std::string, std::string>>& metadata) {
  const auto id = channels_++;
  std::string content;
  u16(content, id);
  u16(content, schema_id);
  str(content, topic);
  str(content, message_encoding);
  std::string map;
  for (const auto& [k, v] : metadata) {
    str(map, k);
    str(map, v);
  }
  str(content, map);  // a map: its byte length, then the pairs
  std::string rec;
  record(rec, kChannel, content);
  emit(rec, true);
  channel_records_ += rec;
  channel_counts_.push_back(0);
  chunk_index_.emplace_back();
  return id;
}

void McapWriter::write(std::uint16_t channel_id, std::uint64_t log_time, std::uint64_t publish_time,
                       std::string_view data) {
  if (channel_id >= channels_) throw std::invalid_argument("MCAP: message on an unknown channel");
  if (message_count_ > 0 && log_time < last_time_)
    throw std::invalid_argument("MCAP: messages must be written in log-time order");
  if (chunk_.empty()) chunk_start_ = log_time;
  chunk_end_ = log_time;
  chunk_index_[channel_id].push_back({log_time, chunk_.size()});
  const std::uint32_t sequence = static_cast<std::uint32_t>(channel_counts_[channel_id]++);
  // The record's 31 bytes before its data, assembled apart and appended with the data: two
  // appends a message, not seven.
  std::string& head = message_head_;
  head.clear();
  head.push_back(static_cast<char>(kMessage));
  u64(head, 2 + 4 + 8 + 8 + data.size());
  u16(head, channel_id);
  u32(head, sequence);
  u64(head, log_time);
  u64(head, publish_time);
  chunk_.append(head);
  chunk_.append(data);
  if (message_count_ == 0) first_time_ = log_time;
  last_time_ = log_time;
  ++message_count_;
  if (chunk_.size() >= options_.chunk_size) close_chunk();
}

void McapWriter::close_chunk() {
  if (chunk_.empty()) return;
  // Not a std::string: resizing one would zero megabytes that zstd then overwrites.
  const std::size_t bound = ZSTD_compressBound(chunk_.size());
  if (bound > compressed_capacity_) {
    compressed_.reset(new char[bound]);
    compressed_capacity_ = bound;
  }
  const std::size_t n =
      ZSTD_compress2(zstd_->cctx, compressed_.get(), bound, chunk_.data(), chunk_.size());
  if (ZSTD_isError(n)) throw std::runtime_error(std::string("zstd: ") + ZSTD_getErrorName(n));

  ChunkIndex index{};
  index.start_time = chunk_start_;
  index.end_time = chunk_end_;
  index.offset = position_;
  index.compressed_size = n;
  index.uncompressed_size = chunk_.size();
  std::string head;  // the chunk record up to its compressed records
  head.push_back(static_cast<char>(kChunk));
  const std::uint64_t content = 8 + 8 + 8 + 4 + (4 + 4) + 8 + n;
  u64(head, content);
  u64(head, chunk_start_);
  u64(head, chunk_end_);
  u64(head, chunk_.size());
  u32(head, crc_update(0, chunk_));
  str(head, "zstd");
  u64(head, n);
  emit(head, true);
  emit(std::string_view(compressed_.get(), n), true);
  index.length = 1 + 8 + content;

  // The message indexes, all assembled in one buffer (kept from chunk to chunk), emitted at once.
  const std::uint64_t indexes_start = position_;
  std::string& records = index_records_;
  records.clear();
  for (std::uint16_t channel = 0; channel < channels_; ++channel) {
    std::vector<IndexEntry>& entries = chunk_index_[channel];
    if (entries.empty()) continue;
    index.message_index_offsets[channel] = indexes_start + records.size();
    const std::size_t bytes = entries.size() * 16;
    records.push_back(static_cast<char>(kMessageIndex));
    u64(records, 2 + 4 + bytes);
    u16(records, channel);
    u32(records, static_cast<std::uint32_t>(bytes));
    if constexpr (std::endian::native == std::endian::little && sizeof(IndexEntry) == 16) {
      records.append(reinterpret_cast<const char*>(entries.data()), bytes);
    } else {
      for (const IndexEntry& e : entries) {
        u64(records, e.time);
        u64(records, e.offset);
      }
    }
    entries.clear();
  }
  emit(records, true);
  index.message_index_length = position_ - indexes_start;
  chunk_indexes_.push_back(std::move(index));
  chunk_.clear();
}

void McapWriter::finish() {
  if (finished_) return;
  finished_ = true;
  close_chunk();
  std::string data_end;
  u32(data_end, data_crc_);
  std::string rec;
  record(rec, kDataEnd, data_end);
  emit(rec, true);

  // The summary: each group's records, and where each group starts.
  const std::uint64_t summary_start = position_;
  std::uint32_t summary_crc = 0;
  std::string offsets;
  const auto group = [&](Opcode op, std::string_view records) {
    if (records.empty()) return;
    std::string c;
    c.push_back(static_cast<char>(op));
    u64(c, position_);
    u64(c, records.size());
    record(offsets, kSummaryOffset, c);
    summary_crc = crc_update(summary_crc, records);
    emit(records, false);
  };
  group(kSchema, schema_records_);
  group(kChannel, channel_records_);
  std::string stats;
  u64(stats, message_count_);
  u16(stats, schemas_);
  u32(stats, channels_);
  u32(stats, 0);  // attachments
  u32(stats, 0);  // metadata
  u32(stats, static_cast<std::uint32_t>(chunk_indexes_.size()));
  u64(stats, first_time_);
  u64(stats, last_time_);
  std::string counts;
  for (std::uint16_t channel = 0; channel < channels_; ++channel) {
    u16(counts, channel);
    u64(counts, channel_counts_[channel]);
  }
  str(stats, counts);
  std::string stats_record;
  record(stats_record, kStatistics, stats);
  group(kStatistics, stats_record);
  std::string chunk_index_records;
  for (const ChunkIndex& i : chunk_indexes_) {
    std::string c;
    u64(c, i.start_time);
    u64(c, i.end_time);
    u64(c, i.offset);
    u64(c, i.length);
    u32(c, static_cast<std::uint32_t>(i.message_index_offsets.size() * 10));
    for (const auto& [channel, offset] : i.message_index_offsets) {
      u16(c, channel);
      u64(c, offset);
    }
    u64(c, i.message_index_length);
    str(c, "zstd");
    u64(c, i.compressed_size);
    u64(c, i.uncompressed_size);
    record(chunk_index_records, kChunkIndex, c);
  }
  group(kChunkIndex, chunk_index_records);

  const std::uint64_t summary_offset_start = position_;
  summary_crc = crc_update(summary_crc, offsets);
  emit(offsets, false);
  std::string footer;
  footer.push_back(static_cast<char>(kFooter));
  u64(footer, 8 + 8 + 4);
  u64(footer, summary_start);
  u64(footer, summary_offset_start);
  summary_crc = crc_update(summary_crc, footer);
  u32(footer, summary_crc);
  emit(footer, false);
  emit(kMagic, false);
  flush_output();
}

}  // namespace floornav
