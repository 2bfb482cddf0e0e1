// A test file's own temporary folder, one per process (parallel test runs do not collide), removed after
// the last test of the binary; and files written into it.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

#include <unistd.h>

#include <gtest/gtest.h>

namespace mcval::test {

/// temp/<prefix><pid>, not created: what a TempFolderCleanup is given at static initialisation (a run that only
/// lists the tests then leaves no folder behind).
inline std::filesystem::path tempFolderPath(const std::string &prefix) {
    return std::filesystem::temp_directory_path() / (prefix + std::to_string(::getpid()));
}

/// temp/<prefix><pid>, created if missing.
inline std::filesystem::path tempFolder(const std::string &prefix) {
    const std::filesystem::path dir = tempFolderPath(prefix);
    std::filesystem::create_directories(dir);
    return dir;
}

/// Removes one folder when the test binary ends (register it with AddGlobalTestEnvironment).
class TempFolderCleanup : public ::testing::Environment {
public:
    explicit TempFolderCleanup(std::filesystem::path dir) : m_dir(std::move(dir)) {}
    void TearDown() override {
        std::error_code ec;
        std::filesystem::remove_all(m_dir, ec);
    }

private:
    std::filesystem::path m_dir;
};

/// `bytes` written to dir/name (binary); the file's path.
inline std::string writeFileIn(const std::filesystem::path &dir, const std::string &name, const std::string &bytes) {
    const std::filesystem::path path = dir / name;
    std::ofstream(path, std::ios::binary) << bytes;
    return path.string();
}

}  // namespace mcval::test
