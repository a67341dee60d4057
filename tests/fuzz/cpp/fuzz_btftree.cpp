// libFuzzer target: a BTF folder or zip built from the input by FuzzedDataProvider, then read by
// weft::loadBtf. The input chooses: whether to start from a complete frontal set (81 images of
// one valid kind), then up to 40 entries -- a Bonn name (one of the 81, with a suffix, with
// random angles, or random bytes), a prefix (none, `__MACOSX/`, `._`, sub folders), an extension
// (.jpg .png .exr .JPEG .txt or none) and the content (a valid tiny JPEG / 8-bit PNG / 16-bit
// PNG / EXR, or bytes from the input) -- each added or replacing an entry of the set; and
// folder or zip, stored or deflated. Loaded samples must be finite and >= 0.
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>

#include <fuzzer/FuzzedDataProvider.h>

#include <weft/BtfIo.h>
#include <weft/BtfSamples.h>

#include "FuzzCommon.h"
#include "btf/ZipArchive.h"

namespace fs = std::filesystem;

namespace {

std::vector<std::string> gNames;           // the 81 frontal Bonn names, no extension
std::vector<std::vector<uint8_t>> gImages; // valid tiny images: JPEG, PNG, 16-bit PNG, EXR
const char* const kImageExtension[4] = {".jpg", ".png", ".png", ".exr"};
const char* const kPrefixes[] = {
    "", "", "", "__MACOSX/", "sub/", "a/b/c/", "._", "__MACOSX/._", "sub/._"};
const char* const kExtensions[] = {".jpg", ".jpg", ".png", ".exr", ".JPEG", ".txt", ""};

std::vector<uint8_t> readAll(const fs::path& path) {
    std::vector<uint8_t> out(fs::file_size(path));
    FILE* f = std::fopen(path.c_str(), "rb");
    if (!f || std::fread(out.data(), 1, out.size(), f) != out.size())
        weft::fuzz::finding("harness: cannot read " + path.string());
    std::fclose(f);
    return out;
}

// A path inside `root` for a fuzzed name: empty, "." and ".." parts dropped, NUL replaced.
fs::path insideFolder(const fs::path& root, const std::string& name) {
    fs::path out = root;
    size_t start = 0;
    bool any = false;
    while (start <= name.size()) {
        size_t end = name.find('/', start);
        if (end == std::string::npos) end = name.size();
        std::string part = name.substr(start, std::min<size_t>(end - start, 100));
        for (char& c : part)
            if (c == '\0') c = '_';
        if (!part.empty() && part != "." && part != "..") {
            out /= part;
            any = true;
        }
        start = end + 1;
    }
    return any ? out : fs::path();
}

// The folder of the previous input, as on disk: files with their bytes, and folders.
std::map<fs::path, std::vector<uint8_t>> gFolderFiles;
std::set<fs::path> gFolderDirs;

// Makes scratchDir()/tree hold `entries` written in order into an empty folder -- a later entry
// replaces an earlier one of the same name; an entry below a name that is a file, or named like
// a folder, is left out (the file system says no) -- changing only what differs from the
// previous input's folder (most inputs share the 81 images of a complete set). With
// WEFT_FUZZ_VERIFY_TREE set, the folder is compared with the entries after every change.
fs::path syncFolder(const std::vector<std::pair<std::string, std::vector<uint8_t>>>& entries) {
    const fs::path root = weft::fuzz::scratchDir() / "tree";
    std::map<fs::path, std::vector<uint8_t>> files;
    std::set<fs::path> dirs;
    for (const auto& [name, content] : entries) {
        const fs::path p = insideFolder(root, name);
        if (p.empty() || dirs.count(p)) continue;
        std::vector<fs::path> parents;
        for (fs::path a = p.parent_path(); a != root; a = a.parent_path()) parents.push_back(a);
        bool blocked = false;
        for (const fs::path& a : parents) blocked = blocked || files.count(a) > 0;
        if (blocked) continue;
        dirs.insert(parents.begin(), parents.end());
        files[p] = content;
    }
    std::error_code ec;
    fs::create_directories(root, ec);
    for (const auto& [p, bytes] : gFolderFiles)
        if (!files.count(p)) fs::remove(p, ec);
    for (auto it = gFolderDirs.rbegin(); it != gFolderDirs.rend(); ++it) // deepest first
        if (!dirs.count(*it)) fs::remove_all(*it, ec);
    for (const fs::path& d : dirs) fs::create_directories(d, ec);
    for (const auto& [p, bytes] : files) {
        const auto old = gFolderFiles.find(p);
        if (old == gFolderFiles.end() || old->second != bytes)
            weft::fuzz::writeFile(p, bytes.data(), bytes.size());
    }
    gFolderFiles = std::move(files);
    gFolderDirs = std::move(dirs);
    static const bool verify = std::getenv("WEFT_FUZZ_VERIFY_TREE") != nullptr;
    if (verify) { // the folder on disk must be exactly what the entries say
        size_t seenFiles = 0, seenDirs = 0;
        for (fs::recursive_directory_iterator it(root), end; it != end; ++it) {
            if (it->is_directory()) {
                ++seenDirs;
                if (!gFolderDirs.count(it->path())) weft::fuzz::finding("harness: extra folder");
            } else {
                ++seenFiles;
                const auto f = gFolderFiles.find(it->path());
                if (f == gFolderFiles.end() || readAll(it->path()) != f->second)
                    weft::fuzz::finding("harness: extra or stale file " + it->path().string());
            }
        }
        if (seenFiles != gFolderFiles.size() || seenDirs != gFolderDirs.size())
            weft::fuzz::finding("harness: missing files or folders");
    }
    return root;
}

} // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    char name[64];
    for (const glm::vec2& d : weft::btfStandardDirections()) {
        std::snprintf(name, sizeof name, "00000 tl%03d pl%03d tv000 pv000", int(d.x), int(d.y));
        gNames.push_back(name);
    }
    // the seed corpus's tiny images (WEFT_FUZZ_CORPUS: tests/fuzz/corpus, set by CMake)
    for (const char* file : {"jpeg/rgb.jpg", "jpeg/grey.png", "jpeg/rgb16.png", "exr/ramp.exr"})
        gImages.push_back(readAll(fs::path(WEFT_FUZZ_CORPUS) / file));
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    FuzzedDataProvider in(data, size);
    std::vector<std::pair<std::string, std::vector<uint8_t>>> entries;
    if (in.ConsumeBool()) { // a complete set to mutate, so that loads can get far
        const size_t kind = in.ConsumeIntegralInRange<size_t>(0, gImages.size() - 1);
        for (const std::string& n : gNames)
            entries.emplace_back(n + kImageExtension[kind], gImages[kind]);
    }
    const int extra = in.ConsumeIntegralInRange(0, 40);
    for (int i = 0; i < extra; ++i) {
        std::string stem;
        switch (in.ConsumeIntegralInRange(0, 3)) {
        case 0: stem = gNames[in.ConsumeIntegralInRange<size_t>(0, gNames.size() - 1)]; break;
        case 1: stem = in.ConsumeRandomLengthString(40); break;
        case 2: {
            char buf[80];
            int angles[4];
            for (int& a : angles) a = in.ConsumeIntegralInRange(0, 999);
            std::snprintf(buf, sizeof buf, "x tl%d pl%d tv%d pv%d", angles[0], angles[1], angles[2],
                          angles[3]);
            stem = buf;
            break;
        }
        default:
            stem = gNames[in.ConsumeIntegralInRange<size_t>(0, gNames.size() - 1)] +
                   in.ConsumeRandomLengthString(8);
        }
        std::string name = std::string(kPrefixes[in.ConsumeIntegralInRange<size_t>(0, 8)]) + stem +
                           kExtensions[in.ConsumeIntegralInRange<size_t>(0, 6)];
        const size_t pick = in.ConsumeIntegralInRange<size_t>(0, gImages.size());
        std::vector<uint8_t> content =
            pick < gImages.size() ? gImages[pick]
                                  : in.ConsumeBytes<uint8_t>(in.ConsumeIntegralInRange(0, 2048));
        if (!entries.empty() && in.ConsumeBool())
            entries[in.ConsumeIntegralInRange<size_t>(0, entries.size() - 1)] = {name, content};
        else
            entries.emplace_back(std::move(name), std::move(content));
    }
    const bool asZip = in.ConsumeBool(), deflate = in.ConsumeBool();

    std::string path;
    if (asZip) {
        path = (weft::fuzz::scratchDir() / "tree.zip").string();
        try {
            weft::ZipWriter zip(path);
            for (const auto& [name, content] : entries) zip.add(name, content, deflate);
            zip.close();
        } catch (const weft::Error&) {
            return 0; // libzip cannot write these names (duplicates, empty): nothing to read
        }
    } else {
        path = syncFolder(entries).string();
    }
    weft::BtfLoadOptions options;
    options.threads = 1;
    weft::fuzz::expectResultOrWeftError([&] {
        const weft::BtfSamples s = weft::loadBtf(path, options);
        weft::fuzz::requireFiniteValues(s.values().data(), s.values().size(), "BTF sample", true);
    });
    return 0;
}
