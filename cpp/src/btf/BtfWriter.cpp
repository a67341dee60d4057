// Writer of the Bonn BTF layout (folder or zip), used by the synthetic generator.
#include <weft/BtfIo.h>
#include <weft/Error.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "btf/BtfImageCodec.h"
#include "btf/BtfParallel.h"
#include "btf/ZipArchive.h"

namespace fs = std::filesystem;

namespace weft {

namespace {

int wholeDegrees(float v, const char* what) {
    const float r = std::round(v);
    if (std::fabs(v - r) > 1e-3f || r < 0 || r > 359)
        throw InvalidArgument(std::string("writeBtf needs whole-degree angles in [0, 360); ") +
                              what + " is " + std::to_string(v));
    return int(r);
}

int standardIndex(int theta, int phi) {
    const auto& dirs = btfStandardDirections();
    for (size_t i = 0; i < dirs.size(); ++i)
        if (int(dirs[i].x) == theta && (theta == 0 || int(dirs[i].y) == phi)) return int(i);
    return -1;
}

} // namespace

void writeBtf(const std::string& path, const BtfSamples& samples, const BtfWriteOptions& options) {
    samples.requireFinite();
    if (options.jpegQuality < 1 || options.jpegQuality > 100)
        throw InvalidArgument("JPEG quality must be 1..100");
    for (char c : options.prefix)
        if (c == '/' || c == '\\' || c == ' ')
            throw InvalidArgument("file name prefix must not contain separators or spaces");
    const int count = samples.count();
    std::vector<std::string> names(static_cast<size_t>(count));
    for (int s = 0; s < count; ++s) {
        const BtfAngles& a = samples.angles()[size_t(s)];
        const int tl = wholeDegrees(a.thetaLight, "θ_l"), pl = wholeDegrees(a.phiLight, "φ_l");
        const int tv = wholeDegrees(a.thetaView, "θ_v"), pv = wholeDegrees(a.phiView, "φ_v");
        const int li = standardIndex(tl, pl), vi = standardIndex(tv, pv);
        const int index = li >= 0 && vi >= 0 ? li * 81 + vi : s;
        const char* ext = options.format == BtfImageFormat::Jpeg ? "jpg" : "png";
        char file[160];
        if (options.prefix.empty())
            std::snprintf(file, sizeof file, "tv%03d_pv%03d/%05d tl%03d pl%03d tv%03d pv%03d.%s",
                          tv, pv, index, tl, pl, tv, pv, ext);
        else
            std::snprintf(file, sizeof file, "tv%03d_pv%03d/%s_%05d_tl%03d_pl%03d_tv%03d_pv%03d.%s",
                          tv, pv, options.prefix.c_str(), index, tl, pl, tv, pv, ext);
        names[size_t(s)] = std::string("UBO2003/MANYFILES/") + file;
    }
    const size_t texels = samples.texels();
    std::vector<std::vector<uint8_t>> encoded(names.size());
    btfParallelFor(count, 0, [&](int b, int e) {
        std::vector<uint8_t> rgb(texels * 3);
        for (int s = b; s < e; ++s) {
            for (int c = 0; c < 3; ++c) {
                const float* p = samples.plane(s, c);
                for (size_t t = 0; t < texels; ++t) {
                    float v = std::min(std::max(p[t], 0.0f), 1.0f);
                    if (options.gamma == BtfGamma::Linear) v = std::pow(v, 1.0f / 2.2f);
                    rgb[t * 3 + size_t(c)] = uint8_t(std::lround(v * 255.0f));
                }
            }
            encoded[size_t(s)] =
                options.format == BtfImageFormat::Jpeg
                    ? encodeJpeg(rgb.data(), samples.width(), samples.height(), options.jpegQuality)
                    : encodePng(rgb.data(), samples.width(), samples.height());
        }
    });
    if (options.zip) {
        ZipWriter zip(path);
        for (int s = 0; s < count; ++s) zip.add(names[size_t(s)], encoded[size_t(s)], false);
        zip.close();
        return;
    }
    for (int s = 0; s < count; ++s) {
        const fs::path file = fs::path(path) / names[size_t(s)];
        std::error_code ec;
        fs::create_directories(file.parent_path(), ec);
        if (ec)
            throw IoError("cannot create folder '" + file.parent_path().string() +
                          "': " + ec.message());
        std::ofstream out(file, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(encoded[size_t(s)].data()),
                  std::streamsize(encoded[size_t(s)].size()));
        if (!out) throw IoError("cannot write BTF image '" + file.string() + "'");
    }
}

} // namespace weft
