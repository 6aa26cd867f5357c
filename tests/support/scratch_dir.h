#pragma once
// For tests of scene_io's readers and writers: a fresh temporary directory for each test, and the
// check that an action fails with a FileError naming the file at fault.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <functional>
#include <string>

#include "scene_io/file_error.h"

namespace trs_test {

/// Expects `action` to fail with a FileError naming `file` and saying `problem`.
inline void expect_error(const std::function<void()>& action, const std::filesystem::path& file,
                         const std::string& problem) {
  try {
    action();
    ADD_FAILURE() << "no error; expected one naming " << file;
  } catch (const trs::FileError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(file.string() + ": "), std::string::npos) << message;
    EXPECT_NE(message.find(problem), std::string::npos) << message;
  }
}

/// A test with a fresh temporary directory, removed afterwards.
class ScratchDirTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() /
           (std::string(test->test_suite_name()) + "-" + std::to_string(::getpid()) + "-" +
            test->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::filesystem::path file(const std::string& name) const { return dir_ / name; }

  std::filesystem::path dir_;
};

}  // namespace trs_test
