#pragma once
// A fresh folder per test process for the files a test writes, removed when
// the process ends. Names under /tmp made from the process id alone are
// reused when an id comes round again, and a batch would then "resume" from
// another run's leftovers; a folder made by mkdtemp cannot be.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace demcal::test {

inline const std::string& scratch_dir() {
  static const std::string dir = [] {
    std::string pattern = ::testing::TempDir() + "demcal_test_XXXXXX";
    if (!::mkdtemp(pattern.data())) throw std::runtime_error("cannot make a scratch folder under " + ::testing::TempDir());
    static const std::string made = pattern;
    std::atexit([] {
      std::error_code ignored;
      std::filesystem::remove_all(made, ignored);
    });
    return pattern + "/";
  }();
  return dir;
}

// `name` inside this process's scratch folder.
inline std::string scratch_path(const std::string& name) { return scratch_dir() + name; }

}  // namespace demcal::test
