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
#include "core/FileRead.h"

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
    const fs::path tmp = fs::temp_directory_path() / ("weft-btf-" + std::to_string(::getpid()) +
                                                      "-" + std::to_string(counter++) + ".exr");
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
    return readInputFile(path, "BTF image", kMaxBtfImageBytes);
}

// macOS adds `__MACOSX/` folders and `._name` AppleDouble files (resource forks) when it zips
// or copies to foreign file systems; they carry the image names but are not images.
bool isMacMetadata(const std::string& name) {
    const fs::path p(name);
    if (p.filename().string().rfind("._", 0) == 0) return true;
    for (const fs::path& part : p)
        if (part == "__MACOSX") return true;
    return false;
}

// One decoded image: 8/16-bit values (JPEG, PNG) or floats (EXR).
struct Decoded {
    DecodedImage image;
    ImageF exr;
    bool isExr = false;
    int width() const { return isExr ? exr.width : image.width; }
    int height() const { return isExr ? exr.height : image.height; }
};

Decoded decodeEntry(const Entry& e, const ZipReader* zip, std::mutex& zipMutex, bool jpegCells) {
    Decoded d;
    d.isExr = isExr(e.name);
    if (d.isExr && !zip) {
        d.exr = loadExr(e.name);
    } else {
        std::vector<uint8_t> bytes;
        if (zip) {
            std::lock_guard<std::mutex> lock(zipMutex); // one libzip handle: sequential access
            bytes = zip->read(e.source, kMaxBtfImageBytes);
        } else {
            bytes = readFile(e.name);
        }
        if (d.isExr)
            d.exr = loadExrBytes(bytes, e.name);
        else
            d.image = decodeBtfImage(bytes, e.name, jpegCells);
    }
    if (d.isExr) {
        try {
            d.exr.requireFinite("EXR '" + e.name + "'");
        } catch (const InvalidArgument& err) { throw IoError(err.what()); }
    }
    return d;
}

BtfSamples allocateSamples(int width, int height, std::vector<BtfAngles> angles,
                           const std::string& path) {
    const double bytes = double(width) * height * 3.0 * 4.0 * double(angles.size());
    const double memory = double(::sysconf(_SC_PHYS_PAGES)) * double(::sysconf(_SC_PAGESIZE));
    if (memory > 0 && bytes > memory)
        throw IoError("the BTF in '" + path + "' (" + std::to_string(angles.size()) +
                      " images of " + std::to_string(width) + "x" + std::to_string(height) +
                      ") needs " + std::to_string(int64_t(bytes / (1 << 20))) +
                      " MiB of float samples, more than this machine's memory");
    try {
        return BtfSamples(width, height, std::move(angles));
    } catch (const std::bad_alloc&) {
        throw IoError("out of memory allocating the samples of the BTF in '" + path + "'");
    }
}

// Converts decoded values into sample planes. 8- and 16-bit values follow the same rule:
// Raw = value / max, Linear = (value / max)^2.2; EXR floats are used as stored.
class SampleStore {
public:
    explicit SampleStore(BtfGamma gamma) : mGamma(gamma) {
        for (int k = 0; k < 256; ++k) mLut8[k] = convert(k, 255);
    }

    void put(const Decoded& d, const Entry& entry, const Entry& first, BtfSamples& samples, int s) {
        if (d.width() != samples.width() || d.height() != samples.height())
            throw IoError("BTF image '" + entry.name + "' is " + std::to_string(d.width()) + "x" +
                          std::to_string(d.height()) + ", but '" + first.name + "' is " +
                          std::to_string(samples.width()) + "x" + std::to_string(samples.height()));
        const size_t texels = samples.texels();
        if (d.isExr) {
            for (int c = 0; c < 3; ++c)
                copyPlane(d.exr.pixels.data(), d.exr.channels, d.exr.channels < 3 ? 0 : c, texels,
                          samples.plane(s, c), [](float v) { return v; });
            return;
        }
        const DecodedImage& img = d.image;
        const int src = img.channels == 1 ? 0 : 1; // channel step: grey repeats channel 0
        if (!img.pixels16.empty()) {
            const float* lut = lut16();
            for (int c = 0; c < 3; ++c)
                copyPlane(img.pixels16.data(), img.channels, c * src, texels, samples.plane(s, c),
                          [lut](uint16_t v) { return lut[v]; });
            return;
        }
        for (int c = 0; c < 3; ++c)
            copyPlane(img.pixels.data(), img.channels, c * src, texels, samples.plane(s, c),
                      [this](uint8_t v) { return mLut8[v]; });
    }

private:
    float convert(int value, int max) const {
        return mGamma == BtfGamma::Raw ? float(value) / float(max)
                                       : float(std::pow(double(value) / max, 2.2));
    }
    const float* lut16() {
        std::call_once(mLut16Once, [this] {
            mLut16.resize(65536);
            for (int k = 0; k < 65536; ++k) mLut16[size_t(k)] = convert(k, 65535);
        });
        return mLut16.data();
    }
    template <typename T, typename F>
    static void copyPlane(const T* pixels, int channels, int channel, size_t texels, float* dst,
                          F value) {
        for (size_t t = 0; t < texels; ++t)
            dst[t] = value(pixels[t * size_t(channels) + size_t(channel)]);
    }

    BtfGamma mGamma;
    float mLut8[256];
    std::once_flag mLut16Once;
    std::vector<float> mLut16;
};
// Gathers the JPEG cells of every sample; gives up (no cells) as soon as one image is not a
// JPEG with the first one's layout. put() runs concurrently for different samples.
class CellStore {
public:
    CellStore(const JpegCoefficientImage& first, int count) {
        if (first.components.empty()) return;
        auto cells = std::make_shared<BtfJpegCells>();
        cells->ycbcr = first.ycbcr;
        size_t offset = 0;
        for (const auto& c : first.components) {
            BtfJpegCells::Component comp;
            comp.blocksWide = c.blocksWide;
            comp.blocksHigh = c.blocksHigh;
            comp.hSampling = c.hSampling;
            comp.vSampling = c.vSampling;
            comp.offset = offset;
            offset += size_t(c.blocksWide) * size_t(c.blocksHigh) * 64;
            cells->components.push_back(comp);
        }
        cells->coefficientsPerSample = offset;
        try {
            cells->coefficients.resize(offset * size_t(count));
            cells->quant.resize(first.components.size() * 64 * size_t(count));
        } catch (const std::bad_alloc&) {
            return; // the cells are optional: the samples load without them
        }
        mCells = std::move(cells);
        mValid = true;
    }

    void put(const JpegCoefficientImage& img, int s) {
        if (!mValid.load()) return;
        BtfJpegCells& cells = *mCells;
        bool same = img.ycbcr == cells.ycbcr && img.components.size() == cells.components.size() &&
                    img.coefficients.size() == cells.coefficientsPerSample;
        for (size_t c = 0; same && c < img.components.size(); ++c) {
            const auto& a = img.components[c];
            const auto& b = cells.components[c];
            same = a.blocksWide == b.blocksWide && a.blocksHigh == b.blocksHigh &&
                   a.hSampling == b.hSampling && a.vSampling == b.vSampling;
        }
        if (!same) {
            mValid = false;
            return;
        }
        std::copy(img.coefficients.begin(), img.coefficients.end(),
                  cells.coefficients.begin() +
                      std::ptrdiff_t(size_t(s) * cells.coefficientsPerSample));
        const size_t nq = cells.components.size() * 64;
        for (size_t c = 0; c < img.components.size(); ++c)
            std::copy(img.components[c].quant, img.components[c].quant + 64,
                      cells.quant.begin() + std::ptrdiff_t(size_t(s) * nq + c * 64));
    }

    std::shared_ptr<const BtfJpegCells> result() const { return mValid.load() ? mCells : nullptr; }

private:
    std::shared_ptr<BtfJpegCells> mCells;
    std::atomic<bool> mValid{false};
};

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
    checkThreads(options.threads);

    std::unique_ptr<ZipReader> zip;
    std::vector<Entry> entries;
    std::error_code ec;
    if (fs::is_directory(path, ec)) {
        for (fs::recursive_directory_iterator it(path, ec), end; !ec && it != end;
             it.increment(ec)) {
            if (!it->is_regular_file(ec) || !isImageName(it->path().string()) ||
                isMacMetadata(it->path().string()))
                continue;
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
            if (isImageName(e.name) && !isMacMetadata(e.name) && parseBtfFileName(e.name, e.angles))
                entries.push_back(e);
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
        std::sort(views.begin(), views.end(),
                  [](glm::vec2 a, glm::vec2 b) { return a.x != b.x ? a.x < b.x : a.y < b.y; });
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

    if (zip) {
        // Every chosen entry's declared size is checked (and summed) before any is inflated.
        uint64_t total = 0;
        for (const Entry* e : chosen) total += zip->checkedSize(e->source, kMaxBtfImageBytes);
        if (total > kMaxBtfZipTotalBytes)
            throw IoError("the BTF images in zip '" + path + "' declare " + std::to_string(total) +
                          " bytes uncompressed, more than the " +
                          std::to_string(kMaxBtfZipTotalBytes) + " a BTF zip may have");
    }

    // Angles are known from the names; the image size from the first image.
    std::vector<BtfAngles> angles;
    for (size_t i = 0; i < chosen.size(); ++i) {
        const glm::vec2 v = views[i / lights.size()], l = lights[i % lights.size()];
        angles.push_back({l.x, l.y, v.x, v.y});
    }
    SampleStore store(options.gamma);
    std::mutex zipMutex;
    const bool wantCells = options.jpegCells && options.gamma == BtfGamma::Raw;
    auto decode = [&](size_t i) { return decodeEntry(*chosen[i], zip.get(), zipMutex, wantCells); };
    BtfSamples samples;
    std::unique_ptr<CellStore> cells;
    {
        const Decoded first = decode(0);
        samples = allocateSamples(first.width(), first.height(), std::move(angles), path);
        store.put(first, *chosen[0], *chosen[0], samples, 0);
        if (wantCells && !first.isExr) {
            cells = std::make_unique<CellStore>(first.image.coefficients, int(chosen.size()));
            cells->put(first.image.coefficients, 0);
        }
    }
    // Every other image is read, decoded and converted by one thread, then freed: memory holds
    // the samples plus one image per thread, never the whole archive.
    std::mutex errorMutex;
    std::exception_ptr firstError;
    std::atomic<bool> failed{false};
    btfParallelForDynamic(int(chosen.size()) - 1, options.threads, 1, [&](int b, int e) {
        for (int k = b; k < e && !failed.load(); ++k) {
            const size_t i = size_t(k) + 1;
            try {
                Decoded d = decode(i);
                store.put(d, *chosen[i], *chosen[0], samples, int(i));
                if (cells) {
                    if (d.isExr)
                        cells->put(JpegCoefficientImage{}, int(i));
                    else
                        cells->put(d.image.coefficients, int(i));
                }
            } catch (...) {
                std::lock_guard<std::mutex> lock(errorMutex);
                if (!firstError) firstError = std::current_exception();
                failed = true;
            }
        }
    });
    if (firstError) std::rethrow_exception(firstError);
    if (cells) samples.setJpegCells(cells->result());
    return samples;
}

} // namespace weft
