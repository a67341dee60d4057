#pragma once
// A fresh directory under the system temp dir for one test, removed with its contents after.
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include <gtest/gtest.h>

class TempDir {
public:
    TempDir() {
        const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
        std::random_device random;
        do {
            mPath = std::filesystem::temp_directory_path() /
                    ("weft-" + std::string(test->name()) + "-" + std::to_string(random()));
        } while (!std::filesystem::create_directory(mPath));
    }
    ~TempDir() {
        std::error_code ignored;
        std::filesystem::remove_all(mPath, ignored);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;

    std::string file(const std::string& name) const { return (mPath / name).string(); }
    // Writes `text` byte for byte (no newline translation) and returns the file's path.
    std::string write(const std::string& name, const std::string& text) const {
        const std::string path = file(name);
        std::ofstream out(path, std::ios::binary);
        out << text;
        EXPECT_TRUE(out.good()) << path;
        return path;
    }

private:
    std::filesystem::path mPath;
};
