// Reader of the Bonn BTF layout from a folder or a zip (shared/formats/bonn-btf.md).
#include <weft/BtfIo.h>
#include <weft/Error.h>
#include <weft/Image.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <mutex>

#include <unistd.h>

#include "btf/BtfImageCodec.h"
#include "btf/BtfParallel.h"
#include "btf/ZipArchive.h"

namespace fs = std::filesystem;

namespace weft {

namespace {

std::string lower(std::string s) {
    for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

bool isImageName(const std::string& name) {
    const std::string ext = lower(fs::path(name).extension().string());
    return ext == ".jpg" || ext == ".jpeg" || ext == ".png" || ext == ".exr";
}

struct Entry {
    std::string name; // path shown in errors
    BtfAngles angles;
    size_t source = 0; // zip entry index, or unused for folders
};

bool near(float a, float b) { return std::fabs(a - b) < 0.5f; }
bool nearAzimuth(float a, float b) {
    const float d = std::fmod(std::fabs(a - b), 360.0f);
    return std::min(d, 360.0f - d) < 0.5f;
}
bool sameDirection(float t0, float p0, float t1, float p1) {
    return near(t0, t1) && (t0 < 0.5f || nearAzimuth(p0, p1));
}

std::string angleText(float t, float p) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "(θ %g°, φ %g°)", double(t), double(p));
    return buf;
}

bool isExr(const std::string& name) { return lower(fs::path(name).extension().string()) == ".exr"; }

// OpenEXR reads files; a zip entry goes through a private temporary file.
ImageF loadExrBytes(const std::vector<uint8_t>& bytes, const std::string& name) {
    static std::atomic<unsigned> counter{0};
    const fs::path tmp = fs::temp_directory_path() /
                         ("weft-btf-" + std::to_string(::getpid()) + "-" +
                          std::to_string(counter++) + ".exr");
    {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
        if (!out) throw IoError("cannot extract EXR '" + name + "' to " + tmp.string());
    }
    try {
        ImageF img = loadExr(tmp.string());
        fs::remove(tmp);
        return img;
    } catch (const IoError& e) {
        fs::remove(tmp);
        throw IoError("cannot read EXR '" + name + "': " + e.what());
    }
}

std::vector<uint8_t> readFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw IoError("cannot open BTF image '" + path + "'");
    std::vector<uint8_t> data((std::istreambuf_iterator<char>(in)),
                              std::istreambuf_iterator<char>());
    if (in.bad()) throw IoError("cannot read BTF image '" + path + "'");
    return data;
}

} // namespace

bool parseBtfFileName(const std::string& name, BtfAngles& out) {
    const std::string base = lower(fs::path(name).filename().string());
    float values[4];
    bool found[4] = {false, false, false, false};
    static const char* keys[4] = {"tl", "pl", "tv", "pv"};
    for (size_t i = 0; i + 2 < base.size(); ++i) {
        if (i > 0 && base[i - 1] != ' ' && base[i - 1] != '_') continue;
        for (int k = 0; k < 4; ++k) {
            if (base.compare(i, 2, keys[k]) != 0) continue;
            size_t j = i + 2;
            if (j >= base.size() || !std::isdigit(static_cast<unsigned char>(base[j]))) continue;
            float v = 0;
            int digits = 0;
            while (j < base.size() && std::isdigit(static_cast<unsigned char>(base[j])) &&
                   digits < 6) {
                v = v * 10 + float(base[j] - '0');
                ++j;
                ++digits;
            }
            if (j < base.size() && base[j] != ' ' && base[j] != '_' && base[j] != '.') continue;
            if (found[k]) return false; // a key twice: ambiguous
            values[k] = v;
            found[k] = true;
        }
    }
    for (bool f : found)
        if (!f) return false;
    out.thetaLight = values[0];
    out.phiLight = values[1];
    out.thetaView = values[2];
    out.phiView = values[3];
    return true;
}

BtfSamples loadBtf(const std::string& path, const BtfLoadOptions& options) {
    for (const glm::vec2& v : options.views)
        if (!std::isfinite(v.x) || !std::isfinite(v.y) || v.x < 0 || v.x >= 90)
            throw InvalidArgument("view angles must be finite with θ_v in [0, 90) degrees");
    if (options.threads < 0) throw InvalidArgument("threads must be >= 0");

    std::unique_ptr<ZipReader> zip;
    std::vector<Entry> entries;
    std::error_code ec;
    if (fs::is_directory(path, ec)) {
        for (fs::recursive_directory_iterator it(path, ec), end; !ec && it != end;
             it.increment(ec)) {
            if (!it->is_regular_file(ec) || !isImageName(it->path().string())) continue;
            Entry e;
            e.name = it->path().string();
            if (parseBtfFileName(e.name, e.angles)) entries.push_back(e);
        }
        if (ec) throw IoError("cannot list BTF folder '" + path + "': " + ec.message());
    } else if (fs::is_regular_file(path, ec)) {
        zip = std::make_unique<ZipReader>(path);
        for (size_t i = 0; i < zip->names().size(); ++i) {
            Entry e;
            e.name = zip->names()[i];
            e.source = i;
            if (isImageName(e.name) && parseBtfFileName(e.name, e.angles)) entries.push_back(e);
        }
    } else {
        throw IoError("BTF path '" + path + "' is neither a folder nor a zip file");
    }
    if (entries.empty())
        throw IoError("no BTF images (names with tl/pl/tv/pv angles) found in '" + path + "'");

    // Views to load, in the order asked (or sorted when all are asked for).
    std::vector<glm::vec2> views = options.views;
    if (views.empty()) {
        for (const Entry& e : entries) {
            bool known = false;
            for (const glm::vec2& v : views)
                known = known || sameDirection(v.x, v.y, e.angles.thetaView, e.angles.phiView);
            if (!known) views.emplace_back(e.angles.thetaView, e.angles.phiView);
        }
        std::sort(views.begin(), views.end(), [](glm::vec2 a, glm::vec2 b) {
            return a.x != b.x ? a.x < b.x : a.y < b.y;
        });
    }
    const auto& lights = btfStandardDirections();
    std::vector<const Entry*> chosen(views.size() * lights.size(), nullptr);
    for (const Entry& e : entries) {
        size_t v = 0;
        while (v < views.size() &&
               !sameDirection(views[v].x, views[v].y, e.angles.thetaView, e.angles.phiView))
            ++v;
        if (v == views.size()) continue;
        size_t l = 0;
        while (l < lights.size() &&
               !sameDirection(lights[l].x, lights[l].y, e.angles.thetaLight, e.angles.phiLight))
            ++l;
        if (l == lights.size())
            throw IoError("BTF image '" + e.name + "' has light direction " +
                          angleText(e.angles.thetaLight, e.angles.phiLight) +
                          ", which is not one of the 81 standard directions");
        const Entry*& slot = chosen[v * lights.size() + l];
        if (slot)
            throw IoError("duplicate BTF images for light " +
                          angleText(e.angles.thetaLight, e.angles.phiLight) + ", view " +
                          angleText(e.angles.thetaView, e.angles.phiView) + ": '" + slot->name +
                          "' and '" + e.name + "'");
        slot = &e;
    }
    for (size_t i = 0; i < chosen.size(); ++i) {
        if (chosen[i]) continue;
        const glm::vec2 v = views[i / lights.size()], l = lights[i % lights.size()];
        char expected[96];
        std::snprintf(expected, sizeof expected, "NNNNN tl%03d pl%03d tv%03d pv%03d.jpg", int(l.x),
                      int(l.y), int(v.x), int(v.y));
        throw IoError("BTF in '" + path + "' misses the image for light " + angleText(l.x, l.y) +
                      ", view " + angleText(v.x, v.y) + " (expected a file like '" + expected +
                      "')");
    }

    // Compressed bytes first (zip access is sequential), then parallel decoding.
    std::vector<std::vector<uint8_t>> bytes(chosen.size());
    if (zip) {
        for (size_t i = 0; i < chosen.size(); ++i) bytes[i] = zip->read(chosen[i]->source);
    }
    std::vector<DecodedImage> images(chosen.size());
    std::vector<ImageF> floats(chosen.size()); // EXR samples (linear, used as they are)
    std::mutex errorMutex;
    std::exception_ptr firstError;
    btfParallelFor(int(chosen.size()), options.threads, [&](int b, int e) {
        for (int i = b; i < e; ++i) {
            try {
                const std::string& name = chosen[size_t(i)]->name;
                if (isExr(name)) {
                    floats[size_t(i)] = zip ? loadExrBytes(bytes[size_t(i)], name) : loadExr(name);
                    try {
                        floats[size_t(i)].requireFinite("EXR '" + name + "'");
                    } catch (const InvalidArgument& e) {
                        throw IoError(e.what());
                    }
                    images[size_t(i)].width = floats[size_t(i)].width;
                    images[size_t(i)].height = floats[size_t(i)].height;
                    images[size_t(i)].channels = floats[size_t(i)].channels;
                    continue;
                }
                if (!zip) bytes[size_t(i)] = readFile(name);
                images[size_t(i)] = decodeBtfImage(bytes[size_t(i)], name);
                std::vector<uint8_t>().swap(bytes[size_t(i)]);
            } catch (...) {
                std::lock_guard<std::mutex> lock(errorMutex);
                if (!firstError) firstError = std::current_exception();
            }
        }
    });
    if (firstError) std::rethrow_exception(firstError);

    const int width = images[0].width, height = images[0].height;
    std::vector<BtfAngles> angles;
    for (size_t i = 0; i < chosen.size(); ++i) {
        const DecodedImage& img = images[i];
        if (img.width != width || img.height != height)
            throw IoError("BTF image '" + chosen[i]->name + "' is " + std::to_string(img.width) +
                          "x" + std::to_string(img.height) + ", but '" + chosen[0]->name +
                          "' is " + std::to_string(width) + "x" + std::to_string(height));
        const glm::vec2 v = views[i / lights.size()], l = lights[i % lights.size()];
        angles.push_back({l.x, l.y, v.x, v.y});
    }
    float lut[256];
    for (int k = 0; k < 256; ++k)
        lut[k] = options.gamma == BtfGamma::Raw ? float(k) / 255.0f
                                                : float(std::pow(k / 255.0, 2.2));
    BtfSamples samples(width, height, std::move(angles));
    const size_t texels = samples.texels();
    btfParallelFor(samples.count(), options.threads, [&](int b, int e) {
        for (int s = b; s < e; ++s) {
            const DecodedImage& img = images[size_t(s)];
            const ImageF& exr = floats[size_t(s)];
            for (int c = 0; c < 3; ++c) {
                if (!exr.pixels.empty()) {
                    float* dst = samples.plane(s, c);
                    const int src = exr.channels < 3 ? 0 : c;
                    for (size_t t = 0; t < texels; ++t)
                        dst[t] = exr.pixels[t * size_t(exr.channels) + size_t(src)];
                    continue;
                }
                float* dst = samples.plane(s, c);
                const int src = img.channels == 1 ? 0 : c;
                for (size_t t = 0; t < texels; ++t)
                    dst[t] = lut[img.pixels[t * size_t(img.channels) + size_t(src)]];
            }
        }
    });
    return samples;
}

} // namespace weft
