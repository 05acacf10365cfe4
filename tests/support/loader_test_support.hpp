#pragma once
// Shared by the map-loader tests: a fresh folder per test for hand-made files, and the check that
// a loader refuses bad input with an InputError saying what is wrong.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "floornav/core/input_error.hpp"

namespace floornav::test {

/// A fresh directory for one test's files (named after the test and the process), removed after.
class TempDirTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() /
           ("floornav_" + std::string(info->test_suite_name()) + "_" + info->name() + "_" +
            std::to_string(::getpid()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  /// Writes `bytes` to `name` in the test's folder and returns its path.
  std::filesystem::path write(const std::string& name, const std::string& bytes) {
    const std::filesystem::path p = dir_ / name;
    std::ofstream(p, std::ios::binary) << bytes;
    return p;
  }

  std::filesystem::path dir_;
};

/// Expects `load()` to throw an InputError whose message contains `needle`.
template <class F>
void expect_input_error(F load, const std::string& needle) {
  try {
    load();
    ADD_FAILURE() << "no InputError; expected one containing '" << needle << "'";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos)
        << "message: " << e.what() << "\nexpected to contain: " << needle;
  }
}

}  // namespace floornav::test
