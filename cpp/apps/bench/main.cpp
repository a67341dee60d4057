// weft-bench: the GPU benchmark set (issue 19) as a native executable, so that it runs from the
// relocatable bundle on a machine without Python: the seed-000 demo scene with per-pass GPU ms,
// seed 002's hair / fur table and seed 001's dome table, each beside the seed's published fps.
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

#include <CLI/CLI.hpp>
#include <vulkan/vulkan.h>

#include <weft/Device.h>
#include <weft/Error.h>

#include "BenchReport.h"
#include "BenchSets.h"
#include "CliHelp.h"

namespace {

const char* kDescription =
    R"(Renders the benchmark set on one Vulkan device and writes bench.json and bench.md:
  demo  the seed-000 demo scene at 1280x720 and 1920x1080 (weft-demo's settings), per-pass GPU ms
  hair  seed 002: hair of 160,000 / 687,532 / 1,031,268 vertices and fur of 2,088,900 (and
        22,977,900 with --fur-23m) vertices at 800x800: B, B+S, B+S+T
  dome  seed 001: a ~40 k-vertex scene under an environment with 0 / 16 / 64 dome shadow lights
        at 640x480 and 1280x1024, dome maps reused and re-rendered every frame
Each seed row shows the seed's published fps and weft's fps as a ratio.
)";

const char* kFooter =
    "WEFT_VALIDATION=1 turns the Vulkan validation layers on; any message fails the run (exit 3).\n";

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
    std::string out = "out/bench/gpu", deviceName;
    bool images = false, listOnly = false, requireGpu = false, furOn = false, furOff = false;
    CLI::App app(kDescription, "weft-bench");
    weft::apps::useHelpLayout(app, kFooter);
    app.add_flag("--quick", o.quick,
                 "small sizes, one timed frame: proves the set runs (seconds on lavapipe)");
    CLI::Option* frames =
        app.add_option("--frames", o.frames,
                       "timed frames per row after one warm-up frame (default 3; --quick: 1)")
            ->option_text("N")
            ->check(CLI::Range(1, 1000));
    app.add_option("--sets", o.sets, "comma-separated subset of demo,hair,dome (default all)")
        ->option_text("LIST")
        ->delimiter(',')
        ->check(CLI::IsMember({"demo", "hair", "dome"}));
    app.add_option("--out", out,
                   "output folder for bench.json and bench.md (default out/bench/gpu)")
        ->option_text("DIR");
    app.add_flag("--images", images,
                 "also save the last frame of every row as OUT/images/NN_<row>.png");
    app.add_option("--device", deviceName,
                   "the Vulkan device: an index or a name substring (sets WEFT_DEVICE);\n"
                   "default: discrete, then integrated, then virtual, then CPU (lavapipe)")
        ->option_text("X")
        ->check(CLI::Validator(
            [](std::string& v) -> std::string {
                return v.empty() ? "needs an index or a name" : "";
            },
            ""));
    app.add_flag("--list-devices", listOnly,
                 "print the devices (tab-separated: device, index, type, name, Vulkan\n"
                 "version, driver, \"chosen\" or \"-\"), then \"validation\" and whether the\n"
                 "Khronos validation layer is installed, and exit");
    app.add_flag("--require-gpu", requireGpu,
                 "fail (exit 4) when the chosen device is a CPU rasteriser");
    app.add_flag("--fur-23m", furOn,
                 "also the 22,977,900-vertex fur (default on a GPU; ~1.3 GB of buffers)");
    app.add_flag("--no-fur-23m", furOff, "leave it out");
    weft::apps::addHelp(app);
    try {
        app.parse(argc, argv);
        if (furOn && furOff)
            throw CLI::ValidationError("--fur-23m and --no-fur-23m exclude each other");
    } catch (const CLI::CallForHelp&) {
        std::cout << app.help();
        return 0;
    } catch (const CLI::ParseError& e) {
        std::cerr << "weft-bench: error: " << e.what() << " (see --help)" << std::endl;
        return 2;
    }
    if (o.quick && frames->count() == 0) o.frames = 1;
    if (images) o.imageDir = (std::filesystem::path(out) / "images").string();
    if (!deviceName.empty()) setenv("WEFT_DEVICE", deviceName.c_str(), 1); // read by Vulkan
    const int fur23m = furOn ? 1 : furOff ? 0 : -1; // -1: on for a GPU, off for a CPU rasteriser
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
                         "rasteriser ("
                      << device.name << ")" << std::endl;
            return 4;
        }
        o.fur23m = fur23m < 0 ? (device.type != "cpu" && !o.quick) : fur23m == 1;
        const weft::bench::MachineReport before = weft::bench::machineReport();
        const std::vector<weft::bench::BenchRow> rows = weft::bench::runSets(o);
        const weft::bench::MachineReport after = weft::bench::machineReport();
        const std::vector<std::string> messages = weft::validationMessages();
        std::filesystem::create_directories(out);
        const std::filesystem::path dir(out);
        writeFile(dir / "bench.json",
                  weft::bench::reportJson(o, device, before, after, rows, messages));
        writeFile(dir / "bench.md",
                  weft::bench::reportMarkdown(o, device, before, after, rows, messages));
        std::cout << "weft-bench: " << rows.size() << " rows on " << device.name << " written to "
                  << std::filesystem::absolute(dir / "bench.md").string() << std::endl;
        for (const std::string& m : messages) std::cerr << "weft-bench: validation " << m << "\n";
        return messages.empty() ? 0 : 3;
    } catch (const std::exception& e) {
        std::cerr << "weft-bench: error: " << e.what() << std::endl;
        return 1;
    }
}
