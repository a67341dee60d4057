// weft-bench: the GPU benchmark set (issue 19) as a native executable, so that it runs from the
// relocatable bundle on a machine without Python: the seed-000 demo scene with per-pass GPU ms,
// seed 002's hair / fur table and seed 001's dome table, each beside the seed's published fps.
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

#include <vulkan/vulkan.h>

#include <weft/Device.h>
#include <weft/Error.h>

#include "BenchReport.h"
#include "BenchSets.h"

namespace {

const char* kUsage = R"(usage: weft-bench [options]

Renders the benchmark set on one Vulkan device and writes bench.json and bench.md:
  demo  the seed-000 demo scene at 1280x720 and 1920x1080 (weft-demo's settings), per-pass GPU ms
  hair  seed 002: hair of 160,000 / 687,532 / 1,031,268 vertices and fur of 2,088,900 (and
        22,977,900 with --fur-23m) vertices at 800x800: B, B+S, B+S+T
  dome  seed 001: a ~40 k-vertex scene under an environment with 0 / 16 / 64 dome shadow lights
        at 640x480 and 1280x1024, dome maps reused and re-rendered every frame
Each seed row shows the seed's published fps and weft's fps as a ratio.

options:
  --quick            small sizes, one timed frame: proves the set runs (seconds on lavapipe)
  --frames N         timed frames per row after one warm-up frame (default 3; --quick: 1)
  --sets LIST        comma-separated subset of demo,hair,dome (default all)
  --out DIR          output folder for bench.json and bench.md (default out/bench/gpu)
  --images           also save the last frame of every row as OUT/images/NN_<row>.png
  --device X         the Vulkan device: an index or a name substring (sets WEFT_DEVICE);
                     default: discrete, then integrated, then virtual, then CPU (lavapipe)
  --list-devices     print the devices (tab-separated: device, index, type, name, Vulkan
                     version, driver, "chosen" or "-"), then "validation" and whether the
                     Khronos validation layer is installed, and exit
  --require-gpu      fail (exit 4) when the chosen device is a CPU rasteriser
  --fur-23m          also the 22,977,900-vertex fur (default on a GPU; ~1.3 GB of buffers)
  --no-fur-23m       leave it out
  -h, --help         show this help

WEFT_VALIDATION=1 turns the Vulkan validation layers on; any message fails the run (exit 3).
)";

int parseInt(const std::string& flag, const char* value) {
    char* end = nullptr;
    const long v = std::strtol(value, &end, 10);
    if (!*value || *end || v < 1 || v > 1000)
        throw weft::InvalidArgument(flag + " needs an integer in [1, 1000], got '" + value + "'");
    return int(v);
}

std::vector<std::string> splitSets(const std::string& list) {
    std::vector<std::string> out;
    std::string item;
    for (size_t i = 0; i <= list.size(); ++i) {
        if (i == list.size() || list[i] == ',') {
            if (item != "demo" && item != "hair" && item != "dome")
                throw weft::InvalidArgument("--sets: unknown set '" + item + "' (demo, hair, dome)");
            out.push_back(item);
            item.clear();
        } else {
            item += list[i];
        }
    }
    return out;
}

bool validationLayerAvailable() {
    uint32_t n = 0;
    if (vkEnumerateInstanceLayerProperties(&n, nullptr) != VK_SUCCESS) return false;
    std::vector<VkLayerProperties> layers(n);
    vkEnumerateInstanceLayerProperties(&n, layers.data());
    for (const VkLayerProperties& l : layers)
        if (std::strcmp(l.layerName, "VK_LAYER_KHRONOS_validation") == 0) return true;
    return false;
}

weft::bench::DeviceReport deviceReport() {
    weft::bench::DeviceReport d;
    for (const weft::DeviceInfo& info : weft::listDevices()) {
        if (info.selected) {
            d.name = info.name;
            d.type = info.type;
            d.driver = info.driver;
            d.apiVersion = info.apiVersion;
        } else {
            d.others.push_back(info.name + " (" + info.type + ")");
        }
    }
    if (d.name.empty()) throw weft::Error("no usable Vulkan device was selected");
    d.validation = weft::validationEnabled();
    d.validationAvailable = validationLayerAvailable();
    return d;
}

void writeFile(const std::filesystem::path& path, const std::string& text) {
    std::ofstream out(path);
    if (!(out << text)) throw weft::IoError("cannot write " + path.string());
}

} // namespace

int main(int argc, char** argv) {
    weft::bench::BenchOptions o;
    std::string out = "out/bench/gpu";
    bool listOnly = false, requireGpu = false, framesGiven = false;
    int fur23m = -1; // -1: on for a GPU, off for a CPU rasteriser
    try {
        for (int i = 1; i < argc; ++i) {
            const std::string a = argv[i];
            auto next = [&]() -> const char* {
                if (i + 1 >= argc) throw weft::InvalidArgument(a + " needs a value");
                return argv[++i];
            };
            if (a == "-h" || a == "--help") {
                std::cout << kUsage;
                return 0;
            } else if (a == "--quick") o.quick = true;
            else if (a == "--frames") { o.frames = parseInt(a, next()); framesGiven = true; }
            else if (a == "--sets") o.sets = splitSets(next());
            else if (a == "--out") out = next();
            else if (a == "--images") o.imageDir = "images";
            else if (a == "--device") {
                const char* v = next();
                if (!*v) throw weft::InvalidArgument("--device needs an index or a name");
                setenv("WEFT_DEVICE", v, 1); // read by the first Vulkan use below
            }
            else if (a == "--list-devices") listOnly = true;
            else if (a == "--require-gpu") requireGpu = true;
            else if (a == "--fur-23m") fur23m = 1;
            else if (a == "--no-fur-23m") fur23m = 0;
            else throw weft::InvalidArgument("unknown option '" + a + "' (see --help)");
        }
        if (o.quick && !framesGiven) o.frames = 1;
        if (!o.imageDir.empty()) o.imageDir = (std::filesystem::path(out) / "images").string();
    } catch (const std::exception& e) {
        std::cerr << "weft-bench: error: " << e.what() << std::endl;
        return 2;
    }
    try {
        const weft::bench::DeviceReport device = deviceReport();
        if (listOnly) {
            // Tab-separated for scripts (gpu-check.sh): device, index, type, name, Vulkan
            // version, driver, chosen; then whether the validation layer can be loaded.
            for (const weft::DeviceInfo& info : weft::listDevices())
                std::cout << "device\t" << info.index << "\t" << info.type << "\t" << info.name
                          << "\t" << info.apiVersion << "\t" << info.driver << "\t"
                          << (info.selected ? "chosen" : "-") << "\n";
            std::cout << "validation\t"
                      << (device.validationAvailable ? "installed" : "not installed") << "\n";
            return 0;
        }
        std::cerr << "weft-bench: device " << device.name << " (" << device.type << ")"
                  << (device.validation ? ", validation on" : "") << std::endl;
        if (requireGpu && device.type == "cpu") {
            std::cerr << "weft-bench: error: --require-gpu but the chosen device is a CPU "
                         "rasteriser (" << device.name << ")" << std::endl;
            return 4;
        }
        o.fur23m = fur23m < 0 ? (device.type != "cpu" && !o.quick) : fur23m == 1;
        const weft::bench::MachineReport before = weft::bench::machineReport();
        const std::vector<weft::bench::BenchRow> rows = weft::bench::runSets(o);
        const weft::bench::MachineReport after = weft::bench::machineReport();
        const std::vector<std::string> messages = weft::validationMessages();
        std::filesystem::create_directories(out);
        const std::filesystem::path dir(out);
        writeFile(dir / "bench.json", weft::bench::reportJson(o, device, before, after, rows, messages));
        writeFile(dir / "bench.md", weft::bench::reportMarkdown(o, device, before, after, rows, messages));
        std::cout << "weft-bench: " << rows.size() << " rows on " << device.name << " written to "
                  << std::filesystem::absolute(dir / "bench.md").string() << std::endl;
        for (const std::string& m : messages) std::cerr << "weft-bench: validation " << m << "\n";
        return messages.empty() ? 0 : 3;
    } catch (const std::exception& e) {
        std::cerr << "weft-bench: error: " << e.what() << std::endl;
        return 1;
    }
}
