#pragma once
// Shared by the libFuzzer targets in this folder. Each target hands the fuzzer's bytes to one of
// weft's loaders or parsers; an input must give a result that keeps the loader's promises or a
// weft::Error. Any other exception is a finding: it is printed and the process aborts, so
// libFuzzer reports it and saves the input (crashes, hangs, leaks and UB are caught by libFuzzer,
// AddressSanitizer and UndefinedBehaviorSanitizer themselves).
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>
#include <typeinfo>

#include <weft/Error.h>

namespace weft::fuzz {

/// Prints `what` as a finding and aborts (libFuzzer saves the input as a crash).
[[noreturn]] inline void finding(const std::string& what) {
    std::fprintf(stderr, "\n==weft-fuzz== FINDING: %s\n", what.c_str());
    std::fflush(stderr);
    std::abort();
}

/// Runs `load`; a weft::Error is an accepted answer, any other exception a finding. With
/// WEFT_FUZZ_VERBOSE set in the environment, each answer is printed (to check seeds).
template <class F> void expectResultOrWeftError(F&& load) {
    static const bool verbose = std::getenv("WEFT_FUZZ_VERBOSE") != nullptr;
    try {
        load();
        if (verbose) std::fprintf(stderr, "weft-fuzz: loaded\n");
    } catch (const weft::Error& e) {
        // bad input, refused with weft's error: what a loader must do
        if (verbose) std::fprintf(stderr, "weft-fuzz: weft::Error: %s\n", e.what());
    } catch (const std::exception& e) {
        finding(std::string("exception other than weft::Error: ") + typeid(e).name() + ": " +
                e.what());
    } catch (...) { finding("exception that is not a std::exception"); }
}

/// A folder of this process for the files a target writes: on tmpfs (/dev/shm) when there is
/// one, else in the system's temporary folder. Created on first use, removed at exit.
inline const std::filesystem::path& scratchDir() {
    static const std::filesystem::path dir = [] {
        namespace fs = std::filesystem;
        std::error_code ec;
        fs::path base =
            fs::is_directory("/dev/shm", ec) ? fs::path("/dev/shm") : fs::temp_directory_path();
        fs::path d = base / ("weft-fuzz-" + std::to_string(::getpid()));
        fs::remove_all(d, ec);
        fs::create_directories(d);
        std::atexit([] {
            std::error_code ignore;
            fs::remove_all(scratchDir(), ignore);
        });
        return d;
    }();
    return dir;
}

/// Writes `size` bytes to `path` (replacing it); aborts when the file cannot be written, as the
/// target could not test anything then.
inline void writeFile(const std::filesystem::path& path, const uint8_t* data, size_t size) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
    out.close();
    if (!out) finding("harness: cannot write " + path.string());
}

/// Writes the bytes to scratchDir()/name and returns the path as a string.
inline std::string scratchFile(const std::string& name, const uint8_t* data, size_t size) {
    const std::filesystem::path path = scratchDir() / name;
    writeFile(path, data, size);
    return path.string();
}

/// Aborts with a finding unless every one of `count` floats is finite (and >= 0 when asked).
inline void requireFiniteValues(const float* values, size_t count, const char* what,
                                bool nonNegative = false) {
    for (size_t i = 0; i < count; ++i)
        if (!std::isfinite(values[i]) || (nonNegative && values[i] < 0.0f))
            finding(std::string(what) + ": value " + std::to_string(values[i]) + " at index " +
                    std::to_string(i));
}

} // namespace weft::fuzz
