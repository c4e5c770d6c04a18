// Test helper: a fresh folder under the system's temporary directory, removed afterwards.
#pragma once

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

namespace relight::test {

class TempDir {
  public:
    /// A folder no other test has: named by the process and a counter, and made only if it
    /// did not exist. (A clock's stamp alone is not enough: ctest starts test processes side
    /// by side, each with its counter at 0, and two of them once got the same stamp and
    /// folder, one reading the edit the other wrote.)
    explicit TempDir(const std::string& prefix = "relight_test") {
        static std::atomic<int> counter{0};
        const auto base = std::filesystem::temp_directory_path();
        std::filesystem::create_directories(base);
        for (;;) {
            const auto stamp = std::chrono::steady_clock::now().time_since_epoch().count();
            path_ = base / (prefix + "_" + std::to_string(::getpid()) + "_" +
                            std::to_string(stamp) + "_" + std::to_string(counter++));
            if (std::filesystem::create_directory(path_)) break;  // false: it existed
        }
    }
    ~TempDir() {
        std::error_code ec;
        std::filesystem::remove_all(path_, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;

    const std::filesystem::path& path() const { return path_; }
    /// Writes `text` to path()/name (binary, as given) and returns the file's path.
    std::filesystem::path write(const std::string& name, const std::string& text) const {
        std::ofstream out(path_ / name, std::ios::binary);
        out << text;
        return path_ / name;
    }

  private:
    std::filesystem::path path_;
};

}  // namespace relight::test
