// Bad input never crashes, hangs or lies (CONTRACT.md, "Exit status"). Every file of the corpus
// under tests/data/bad/, every line of tests/data/bad/set_values.txt and a few inputs written
// here at run time (binary bytes, huge files) is one test case:
//  - scenario files and --set values run through the floornav executable and must give exit
//    status 2, exactly one line "floornav: error: ..." naming the file (or the --set), with the
//    message tests/data/bad/expected.tsv gives, and no output folder;
//  - map files go to their loader, which must throw floornav::InputError with that message.
// Hangs are caught by ctest's per-test TIMEOUT: tests never time themselves.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <string_view>
#include <typeinfo>
#include <vector>

#include "floornav/core/input_error.hpp"
#include "floornav/io/barn.hpp"
#include "floornav/io/course_world.hpp"
#include "floornav/io/movingai_map.hpp"
#include "floornav/io/ros_map.hpp"
#include "floornav/io/sdf_world.hpp"

namespace {

namespace fs = std::filesystem;

const fs::path kBadDir = fs::path(FLOORNAV_TEST_DATA_DIR) / "bad";
// The format folders; fixtures/ holds valid files the bad scenarios refer to.
const std::array<const char*, 5> kFormatDirs = {"scenario", "ros_map", "movingai", "sdf",
                                                "course_xml"};

enum class Via { Cli, Loader };

struct BadCase {
  std::string name;      ///< the test's name
  std::string id;        ///< "scenario/dt_zero.yaml", "--set sim.dt=-1" or "generated/..."
  Via via{Via::Cli};     ///< through the executable or a loader function
  fs::path file;         ///< the input file (empty for generated cases until written)
  std::string set;       ///< the --set value, if this case is one
  std::string expected;  ///< a substring of the message
  /// For generated cases: writes the input into the folder and returns its path.
  std::function<fs::path(const fs::path&)> make;
};

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

fs::path write_file(const fs::path& p, const std::string& bytes) {
  std::ofstream(p, std::ios::binary) << bytes;
  return p;
}

/// A test name from any text: letters and digits kept, everything else '_'.
std::string test_name(const std::string& text) {
  std::string out;
  for (const char c : text) out += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return out;
}

/// case id -> expected message substring, from expected.tsv.
std::map<std::string, std::string> read_expected() {
  std::map<std::string, std::string> out;
  std::istringstream in(read_text(kBadDir / "expected.tsv"));
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    const auto tab = line.find('\t');
    if (tab == std::string::npos) continue;
    out[line.substr(0, tab)] = line.substr(tab + 1);
  }
  return out;
}

std::vector<std::string> read_set_values() {
  std::vector<std::string> out;
  std::istringstream in(read_text(kBadDir / "set_values.txt"));
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    out.push_back(line);
  }
  return out;
}

/// `n` bytes from a fixed-seed generator: the same "random" file on every run.
std::string random_bytes(std::size_t n, unsigned seed, bool allow_nul) {
  std::mt19937 rng(seed);
  std::string out(n, '\0');
  for (char& c : out) {
    unsigned v = rng() & 0xffu;
    if (!allow_nul && v == 0) v = 0x80;
    c = static_cast<char>(v);
  }
  return out;
}

/// The CRC-32 of PNG chunks (ISO 3309, as zlib's crc32).
std::uint32_t crc32(const std::string& bytes) {
  std::uint32_t crc = 0xffffffffu;
  for (const char ch : bytes) {
    crc ^= static_cast<unsigned char>(ch);
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  return crc ^ 0xffffffffu;
}

std::string be32(std::uint32_t v) {
  std::string b;
  for (int s = 24; s >= 0; s -= 8) b += static_cast<char>((v >> s) & 0xffu);
  return b;
}

/// A PNG chunk with its length and CRC.
std::string png_chunk(const std::string& type, const std::string& data) {
  const std::string body = type + data;
  return be32(static_cast<std::uint32_t>(data.size())) + body + be32(crc32(body));
}

/// A PNG signature and a valid IHDR chunk of `width` x `height` 8-bit gray, then `tail`.
std::string png_header(std::uint32_t width, std::uint32_t height, const std::string& tail) {
  // bit depth 8, gray, deflate, adaptive filtering, not interlaced
  const std::string ihdr = be32(width) + be32(height) + std::string("\x08\0\0\0\0", 5);
  return "\x89PNG\r\n\x1a\n" + png_chunk("IHDR", ihdr) + tail;
}

/// Inputs that are binary or too big to keep in the repository, written at run time.
std::vector<BadCase> generated_cases() {
  std::vector<BadCase> out;
  auto add = [&](const std::string& rel, Via via, const std::string& expected,
                 std::function<std::string()> bytes) {
    BadCase c;
    c.id = "generated/" + rel;
    c.name = test_name(c.id);
    c.via = via;
    c.expected = expected;
    c.make = [rel, bytes](const fs::path& dir) {
      const fs::path p = dir / rel;
      fs::create_directories(p.parent_path());
      return write_file(p, bytes());
    };
    out.push_back(std::move(c));
  };
  const std::string ok_scenario =
      "world: {bounds: [-1, -1, 5, 3]}\nrobot: {start: [0, 0, 0]}\ngoal: [4, 1]\n";
  add("scenario/binary_with_nul.yaml", Via::Cli, "binary data, not a YAML scenario",
      [] { return random_bytes(4096, 1, true); });
  add("scenario/binary_without_nul.yaml", Via::Cli, "is not UTF-8",
      [] { return random_bytes(4096, 2, false); });
  add("scenario/nul_after_valid_text.yaml", Via::Cli, "binary data",
      [ok_scenario] { return ok_scenario + std::string(1, '\0') + "sim: {dt: 0.5}\n"; });
  add("scenario/deep_nesting_100000_brackets.yaml", Via::Cli, "nests too deeply",
      [] { return "world: " + std::string(100000, '[') + "\n"; });
  add("scenario/deep_nesting_100000_braces.yaml", Via::Cli, "nests too deeply", [] {
    std::string s = "world: ";
    for (int i = 0; i < 100000; ++i) s += "{a: ";
    return s + "\n";
  });
  add("scenario/deep_nesting_3000_indents.yaml", Via::Cli, "nests too deeply", [] {
    std::string s;
    for (int i = 0; i < 3000; ++i) s += std::string(static_cast<std::size_t>(i), ' ') + "a:\n";
    return s;
  });
  add("scenario/polygon_of_1001_points.yaml", Via::Cli, "a polygon has at most 1000 points", [] {
    std::string s = "world:\n  bounds: [-1, -1, 5, 3]\n  obstacles:\n    - polygon: [";
    for (int i = 0; i < 1000; ++i) s += "[0, 0], ";
    return s + "[0, 0]]\nrobot: {start: [0, 0, 0]}\ngoal: [4, 1]\n";
  });
  // YAML aliases repeat one node without repeating its text: a 1000-point polygon 200 times,
  // 10001 goals, 100001 sensors, in files of a few hundred kilobytes.
  auto aliases = [](const std::string& anchor, const std::string& value, int copies) {
    std::string s = "[&" + anchor + " " + value;
    for (int i = 0; i < copies; ++i) s += ", *" + anchor;
    return s + "]";
  };
  add("scenario/alias_amplified_polygons.yaml", Via::Cli, "the polygons are too large in all",
      [aliases] {
        std::string ring = "{polygon: [";
        for (int i = 0; i < 1000; ++i) {
          const double a = 2.0 * 3.14159265358979 * i / 1000.0;
          ring += (i ? ", [" : "[") + std::to_string(3.0 + 0.3 * std::cos(a)) + ", " +
                  std::to_string(1.5 + 0.3 * std::sin(a)) + "]";
        }
        ring += "]}";
        return "world:\n  bounds: [-1, -1, 5, 3]\n  obstacles: " + aliases("p", ring, 200) +
               "\nrobot: {start: [0, 0, 0]}\ngoal: [4, 1]\n";
      });
  add("scenario/alias_amplified_goals.yaml", Via::Cli, "at most 10000 goals", [aliases] {
    return "world: {bounds: [-1, -1, 5, 3]}\nrobot: {start: [0, 0, 0]}\ngoals: " +
           aliases("g", "[4, 1]", 10000) + "\n";
  });
  add("scenario/alias_amplified_sensors.yaml", Via::Cli, "at most 4096 sensors", [aliases] {
    return "world: {bounds: [-1, -1, 5, 3]}\nrobot:\n  start: [0, 0, 0]\n  sensors: {mounts: " +
           aliases("m", "[0, 0, 0]", 100000) + "}\ngoal: [4, 1]\n";
  });
  add("scenario/larger_than_16_mib.yaml", Via::Cli,
      "more than the 16777216 a scenario file may have",
      [ok_scenario] { return ok_scenario + "# " + std::string(17u << 20, 'x') + "\n"; });
  add("ros_map/binary.yaml", Via::Loader, "is not UTF-8",
      [] { return random_bytes(2048, 3, true); });
  add("ros_map/binary.pgm", Via::Loader, "unsupported image format",
      [] { return random_bytes(2048, 4, true); });
  add("ros_map/p5_binary_truncated.pgm", Via::Loader, "truncated image data",
      [] { return "P5\n64 64\n255\n" + random_bytes(100, 5, true); });
  add("ros_map/truncated.png", Via::Loader, "bad PNG header",
      [] { return png_header(10, 10, ""); });
  add("ros_map/garbage_after_header.png", Via::Loader, "bad PNG header",
      [] { return png_header(10, 10, random_bytes(512, 6, true)); });
  add("ros_map/huge_header.png", Via::Loader, "too large",
      [] { return png_header(100000, 100000, ""); });
  add("ros_map/header_promises_16384_squared.png", Via::Loader, "too large (limit 2^26",
      [] { return png_header(16384, 16384, png_chunk("IDAT", "x\x9c")); });
  add("ros_map/header_promises_8192_squared.png", Via::Loader, "bytes cannot hold",
      [] { return png_header(8192, 8192, png_chunk("IDAT", "x\x9c")); });
  add("ros_map/signature_only.png", Via::Loader, "no IHDR chunk",
      [] { return std::string("\x89PNG\r\n\x1a\n"); });
  add("movingai/binary.map", Via::Loader, "expected 'type octile'",
      [] { return random_bytes(2048, 7, true); });
  add("movingai/binary.scen", Via::Loader, "expected 'version 1'",
      [] { return random_bytes(2048, 8, true); });
  add("sdf/binary.sdf", Via::Loader, "is not UTF-8", [] { return random_bytes(2048, 9, true); });
  add("sdf/deep_nesting_100000.sdf", Via::Loader, "malformed XML", [] {
    std::string s = "<sdf version='1.6'><world name='w'>";
    for (int i = 0; i < 100000; ++i) s += "<model>";
    return s;
  });
  add("course_xml/binary.xml", Via::Loader, "is not UTF-8",
      [] { return random_bytes(2048, 10, true); });
  add("course_xml/obstacle_of_1001_points.xml", Via::Loader, "at most 1000 <point>s", [] {
    std::string s = "<simulation><obstacle><pose x='0' y='0' theta='0'/><geometry>";
    for (int i = 0; i < 1001; ++i) s += "<point x='" + std::to_string(i) + "' y='0'/>";
    return s + "</geometry></obstacle></simulation>";
  });
  // BARN reference paths (.npy): the header is read strictly and the cells must be BARN's.
  auto npy = [](const std::string& header, const std::vector<std::int64_t>& values) {
    std::string h = header;
    while ((10 + h.size() + 1) % 64 != 0) h += ' ';
    h += '\n';
    std::string out = std::string("\x93NUMPY\x01\x00", 8);
    out += static_cast<char>(h.size() & 0xff);
    out += static_cast<char>(h.size() >> 8);
    out += h;
    for (const std::int64_t v : values)
      for (int b = 0; b < 8; ++b)
        out += static_cast<char>((static_cast<std::uint64_t>(v) >> (8 * b)) & 0xff);
    return out;
  };
  add("barn/three_dimensional.npy", Via::Loader, "got a 3-dimensional array", [npy] {
    return npy("{'descr': '<i8', 'fortran_order': False, 'shape': (1, 2, 2), }", {1, 2, 3, 4});
  });
  add("barn/decoy_descr.npy", Via::Loader, "unknown key 'note'", [npy] {
    return npy(
        "{'descr': '<f8', 'fortran_order': False, 'shape': (1, 2), 'note': \"'descr': "
        "'<i8'\"}",
        {1, 2});
  });
  add("barn/float_dtype.npy", Via::Loader, "expected dtype '<i8'", [npy] {
    return npy("{'descr': '<f8', 'fortran_order': False, 'shape': (1, 2), }", {1, 2});
  });
  add("barn/extreme_values.npy", Via::Loader, "is outside BARN's 30 x 30 grid", [npy] {
    return npy("{'descr': '<i8', 'fortran_order': False, 'shape': (2, 2), }",
               {3, 4, std::int64_t{1} << 62, -5});
  });
  add("barn/data_too_short.npy", Via::Loader, "but shape (3, 2) needs 48", [npy] {
    return npy("{'descr': '<i8', 'fortran_order': False, 'shape': (3, 2), }", {1, 2, 3, 4});
  });
  add("barn/empty_path.npy", Via::Loader, "an empty path",
      [npy] { return npy("{'descr': '<i8', 'fortran_order': False, 'shape': (0, 2), }", {}); });
  add("barn/fortran_order.npy", Via::Loader, "expected C order", [npy] {
    return npy("{'descr': '<i8', 'fortran_order': True, 'shape': (1, 2), }", {1, 2});
  });
  add("barn/text_after_header.npy", Via::Loader, "text after the header's closing brace", [npy] {
    return npy("{'descr': '<i8', 'fortran_order': False, 'shape': (1, 2), } x", {1, 2});
  });
  return out;
}

std::vector<BadCase> all_cases() {
  const auto expected = read_expected();
  auto expect = [&](const std::string& id) {
    const auto it = expected.find(id);
    return it == expected.end() ? std::string("<no line in expected.tsv>") : it->second;
  };
  std::vector<BadCase> out;
  for (const char* dir : kFormatDirs) {
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(kBadDir / dir))
      if (e.is_regular_file()) files.push_back(e.path());
    std::sort(files.begin(), files.end());
    for (const fs::path& f : files) {
      BadCase c;
      c.id = std::string(dir) + "/" + f.filename().string();
      c.name = test_name(c.id);
      c.via = std::string(dir) == "scenario" ? Via::Cli : Via::Loader;
      c.file = f;
      c.expected = expect(c.id);
      out.push_back(std::move(c));
    }
  }
  const auto sets = read_set_values();
  for (std::size_t i = 0; i < sets.size(); ++i) {
    BadCase c;
    c.id = "--set " + sets[i];
    c.name = "set_" + std::to_string(i) + "_" + test_name(sets[i]);
    c.via = Via::Cli;
    c.file = fs::path(FLOORNAV_SCENARIO_DIR) / "rectangle.yaml";
    c.set = sets[i];
    c.expected = expect(c.id);
    out.push_back(std::move(c));
  }
  // A --set value cannot hold a newline in set_values.txt; the message must stay one line.
  BadCase nl;
  nl.id = "generated/--set sim.dt=0.01\\nx";
  nl.name = "generated_set_value_with_a_newline";
  nl.file = fs::path(FLOORNAV_SCENARIO_DIR) / "rectangle.yaml";
  nl.set = "sim.dt=0.01\nx";
  nl.expected = "expected a number";
  out.push_back(std::move(nl));
  for (BadCase& c : generated_cases()) out.push_back(std::move(c));
  return out;
}

// Test names, not bytes, in gtest's messages.
void PrintTo(const BadCase& c, std::ostream* os) {
  *os << c.id;
}

std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (const char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

struct Output {
  int status{-1};
  std::string text;  // stdout and stderr
};

Output run_floornav(const std::string& args) {
  const std::string cmd = std::string(FLOORNAV_BINARY) + " " + args + " 2>&1";
  Output out;
  FILE* p = popen(cmd.c_str(), "r");
  if (p == nullptr) return out;
  std::array<char, 4096> buf{};
  std::size_t n = 0;
  while ((n = std::fread(buf.data(), 1, buf.size(), p)) > 0) out.text.append(buf.data(), n);
  const int raw = pclose(p);
  out.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + (WIFSIGNALED(raw) ? WTERMSIG(raw) : 0);
  return out;
}

/// The names a message may use for `file`: its own, or the file it points at (a scenario's
/// `map:`, a map yaml's `image:`), since the error is reported where it is.
std::vector<std::string> names_for(const fs::path& file) {
  std::vector<std::string> names{file.filename().string()};
  std::error_code ec;
  if (fs::file_size(file, ec) > (1u << 20) || ec) return names;
  std::istringstream in(read_text(file));
  for (std::string line; std::getline(in, line);) {
    const auto first = line.find_first_not_of(" \t");
    if (first == std::string::npos) continue;
    for (const std::string_view key : {"map:", "image:", "people_file:"}) {
      if (line.compare(first, key.size(), key) != 0) continue;
      std::istringstream words(line.substr(first + key.size()));
      std::string target;
      if (words >> target) names.push_back(fs::path(target).filename().string());
    }
  }
  return names;
}

bool contains_any(const std::string& text, const std::vector<std::string>& names) {
  return std::any_of(names.begin(), names.end(),
                     [&](const std::string& n) { return text.find(n) != std::string::npos; });
}

/// The loader for a map file, by its folder and extension; throws what the loader throws.
void load_map(const fs::path& file) {
  const std::string dir = file.parent_path().filename().string();
  const std::string ext = file.extension().string();
  if (dir == "ros_map") {
    if (ext == ".yaml")
      (void)floornav::load_ros_map(file);
    else
      (void)floornav::load_ros_image_map(file, 0.05);
  } else if (dir == "movingai") {
    if (ext == ".scen")
      (void)floornav::load_movingai_scen(file);
    else
      (void)floornav::load_movingai_map(file, 1.0);
  } else if (dir == "sdf") {
    (void)floornav::load_sdf_world(file);
  } else if (dir == "course_xml") {
    (void)floornav::load_course_world(file);
  } else if (dir == "barn") {
    (void)floornav::load_barn_path(file);
  } else {
    FAIL() << "no loader for " << file;
  }
}

class BadInput : public ::testing::TestWithParam<BadCase> {
 protected:
  void SetUp() override {
    work_ = fs::temp_directory_path() /
            ("floornav_bad_input_" + std::to_string(::getpid()) + "_" + GetParam().name);
    fs::remove_all(work_);
    fs::create_directories(work_);
  }
  void TearDown() override { fs::remove_all(work_); }

  fs::path work_;
};

TEST_P(BadInput, IsRefusedWithOneClearMessage) {
  const BadCase& c = GetParam();
  const fs::path file = c.make ? c.make(work_) : c.file;
  if (c.via == Via::Loader) {
    try {
      load_map(file);
      ADD_FAILURE() << c.id << ": loaded without an error";
    } catch (const floornav::InputError& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
      EXPECT_TRUE(contains_any(what, names_for(file))) << "does not name the file: " << what;
      EXPECT_NE(what.find(c.expected), std::string::npos)
          << "expected '" << c.expected << "' in: " << what;
    } catch (const std::exception& e) {
      ADD_FAILURE() << c.id << ": not an InputError but " << typeid(e).name() << ": " << e.what();
    }
    return;
  }

  const fs::path out = work_ / "out";
  std::string args = "run " + shell_quote(file.string()) + " --out " + shell_quote(out.string());
  if (!c.set.empty()) args += " --set " + shell_quote(c.set);
  const Output o = run_floornav(args);
  EXPECT_EQ(o.status, 2) << o.text;
  ASSERT_FALSE(o.text.empty());
  EXPECT_EQ(std::count(o.text.begin(), o.text.end(), '\n'), 1) << o.text;
  EXPECT_EQ(o.text.back(), '\n') << o.text;
  EXPECT_EQ(o.text.rfind("floornav: error: ", 0), 0u) << o.text;
  if (c.set.empty())
    EXPECT_TRUE(contains_any(o.text, names_for(file))) << "does not name the file: " << o.text;
  else
    EXPECT_NE(o.text.find("--set"), std::string::npos) << o.text;
  EXPECT_NE(o.text.find(c.expected), std::string::npos)
      << "expected '" << c.expected << "' in: " << o.text;
  EXPECT_FALSE(fs::exists(out)) << "the output folder was created: " << out;
}

INSTANTIATE_TEST_SUITE_P(Corpus, BadInput, ::testing::ValuesIn(all_cases()),
                         [](const ::testing::TestParamInfo<BadCase>& info) {
                           return info.param.name;
                         });

// The corpus and expected.tsv agree both ways, every format has cases, and the total is printed.
TEST(BadInputCorpus, EveryCaseHasAnExpectedMessageAndTheTotalIsPrinted) {
  const auto expected = read_expected();
  std::set<std::string> ids;
  std::map<std::string, int> per_kind;
  for (const BadCase& c : all_cases()) {
    if (c.id.rfind("generated/", 0) != 0) {
      EXPECT_TRUE(expected.count(c.id)) << c.id << " has no line in expected.tsv";
      ids.insert(c.id);
    }
    const std::string kind = c.id.rfind("--set", 0) == 0 ? "--set" : c.id.substr(0, c.id.find('/'));
    ++per_kind[kind];
  }
  for (const auto& [id, substring] : expected) {
    EXPECT_TRUE(ids.count(id)) << "expected.tsv names " << id << ", which is not in the corpus";
    EXPECT_FALSE(substring.empty()) << id;
  }
  int files = 0;
  for (const char* dir : kFormatDirs) {
    int n = 0;
    for (const auto& e : fs::directory_iterator(kBadDir / dir)) n += e.is_regular_file() ? 1 : 0;
    EXPECT_GT(n, 0) << dir;
    files += n;
  }
  EXPECT_GE(files, 60);
  std::cout << "bad-input corpus: " << files << " files, " << per_kind["--set"] << " --set values, "
            << per_kind["generated"] << " generated inputs; "
            << files + per_kind["--set"] + per_kind["generated"] << " cases in all\n";
}

}  // namespace
