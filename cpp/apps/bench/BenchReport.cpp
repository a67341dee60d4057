#include "BenchReport.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <sstream>
#include <thread>

#include <weft/Error.h>

#include <nlohmann/json.hpp>

namespace weft::bench {
namespace {

std::string num(double v, int digits = 3) {
    if (!(v >= 0)) return "null"; // unmeasured (negative) or NaN
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", digits, v);
    return buf;
}

std::string cell(double v, int digits = 2) { return v >= 0 ? num(v, digits) : "-"; }

double fps(double ms) { return ms > 0 ? 1000.0 / ms : -1.0; }

std::string firstLine(const std::string& path, const std::string& key) {
    std::ifstream in(path);
    std::string line;
    while (std::getline(in, line))
        if (key.empty() || line.rfind(key, 0) == 0) {
            const size_t colon = line.find(':');
            return key.empty() || colon == std::string::npos ? line : line.substr(colon + 2);
        }
    return "";
}

// A row's passes with indexed ones (shadow[0], dome[12], bounce[2][5]) summed under their base
// name, "dome (16)", in the order they first ran: per-view passes would swamp a table.
std::vector<std::pair<std::string, double>> groupedPasses(const BenchRow& r) {
    std::vector<std::pair<std::string, double>> out;
    std::vector<int> counts;
    for (const std::string& name : r.passOrder) {
        const std::string base = name.substr(0, name.find('['));
        size_t i = 0;
        while (i < out.size() && out[i].first != base) ++i;
        if (i == out.size()) {
            out.push_back({base, 0.0});
            counts.push_back(0);
        }
        out[i].second += r.passGpuMs.at(name);
        ++counts[i];
    }
    for (size_t i = 0; i < out.size(); ++i)
        if (counts[i] > 1) out[i].first += " (" + std::to_string(counts[i]) + ")";
    return out;
}

// The heaviest (grouped) passes of a row, "name ms", largest first (at most `count`).
std::string topPasses(const BenchRow& r, size_t count) {
    std::vector<std::pair<double, std::string>> p;
    for (const auto& [name, ms] : groupedPasses(r)) p.push_back({ms, name});
    std::sort(p.rbegin(), p.rend());
    std::string out;
    for (size_t i = 0; i < p.size() && i < count; ++i)
        out += (i ? ", " : "") + p[i].second + " " + num(p[i].first, 2);
    return out.empty() ? "-" : out;
}

// Every (grouped) pass of a set's rows, one column per row (GPU ms), in the order they ran.
void passTable(std::ostringstream& md, const std::vector<BenchRow>& rows, const std::string& set) {
    std::vector<std::vector<std::pair<std::string, double>>> cols;
    std::vector<std::string> heads, names;
    for (const BenchRow& r : rows) {
        if (r.set != set) continue;
        cols.push_back(groupedPasses(r));
        heads.push_back(std::to_string(r.width) + "x" + std::to_string(r.height));
        for (const auto& [name, ms] : cols.back())
            if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
    }
    if (cols.empty()) return;
    md << "\nPer pass, GPU ms (indexed passes summed, their count in brackets):\n\n| pass |";
    for (const std::string& h : heads) md << " " << h << " |";
    md << "\n|---|";
    for (size_t i = 0; i < cols.size(); ++i) md << "---|";
    md << "\n";
    for (const std::string& name : names) {
        md << "| " << name << " |";
        for (const auto& col : cols) {
            std::string v = "-";
            for (const auto& [n, ms] : col)
                if (n == name) v = num(ms, 2);
            md << " " << v << " |";
        }
        md << "\n";
    }
}

} // namespace

MachineReport machineReport() {
    MachineReport m;
    m.cpu = firstLine("/proc/cpuinfo", "model name");
    m.cores = int(std::thread::hardware_concurrency());
    m.loadAverage = firstLine("/proc/loadavg", "");
    const std::time_t now = std::time(nullptr);
    char buf[32];
    std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
    m.date = buf;
    return m;
}

// A measured value rounded to `digits`, or null where unmeasured (negative) or NaN.
nlohmann::ordered_json measured(double v, int digits = 3) {
    if (!(v >= 0)) return nullptr;
    const double scale = std::pow(10.0, digits);
    return std::round(v * scale) / scale;
}

std::string reportJson(const BenchOptions& o, const DeviceReport& d, const MachineReport& m,
                       const MachineReport& after, const std::vector<BenchRow>& rows,
                       const std::vector<std::string>& validation) {
    using Json = nlohmann::ordered_json; // fields in the order written; strings escaped
    Json j = {{"tool", "weft-bench"},
              {"weft_version", WEFT_VERSION},
              {"date", m.date},
              {"quick", o.quick},
              {"timed_frames", o.frames}};
    j["device"] = {{"name", d.name},
                   {"type", d.type},
                   {"driver", d.driver},
                   {"api_version", d.apiVersion},
                   {"others", d.others}};
    j["validation"] = {{"enabled", d.validation},
                       {"layer_available", d.validationAvailable},
                       {"messages", validation}};
    j["machine"] = {{"cpu", m.cpu},
                    {"cores", m.cores},
                    {"loadavg_before", m.loadAverage},
                    {"loadavg_after", after.loadAverage}};
    Json out = Json::array();
    for (const BenchRow& r : rows) {
        const bool seed = r.seedFps > 0;
        Json passes = Json::object();
        for (const auto& [name, ms] : r.passGpuMs) passes[name] = measured(ms);
        out.push_back(
            {{"set", r.set},
             {"workload", r.workload},
             {"config", r.config},
             {"width", r.width},
             {"height", r.height},
             {"vertices", r.vertices},
             {"frames", r.frames},
             {"wall_ms", measured(r.wallMs)},
             {"fps", measured(fps(r.wallMs))},
             {"gpu_ms", measured(r.gpuMs)},
             {"gpu_fps", measured(fps(r.gpuMs))},
             {"seed_fps", seed ? measured(r.seedFps, 0) : Json(nullptr)},
             {"ratio_wall", seed ? measured(fps(r.wallMs) / r.seedFps, 5) : Json(nullptr)},
             {"ratio_gpu",
              seed && r.gpuMs > 0 ? measured(fps(r.gpuMs) / r.seedFps, 5) : Json(nullptr)},
             {"seed_source", r.seedSource},
             {"passes_gpu_ms", passes}});
    }
    j["rows"] = out;
    // invalid UTF-8 in a device or CPU name is replaced, not thrown
    return j.dump(2, ' ', false, Json::error_handler_t::replace) + "\n";
}

std::string reportMarkdown(const BenchOptions& o, const DeviceReport& d, const MachineReport& m,
                           const MachineReport& after, const std::vector<BenchRow>& rows,
                           const std::vector<std::string>& validation) {
    std::ostringstream md;
    md << "# weft-bench" << (o.quick ? " (--quick: small sizes, not comparable)" : "") << "\n\n";
    md << "- device: **" << d.name << "** (" << d.type << ", Vulkan " << d.apiVersion
       << (d.driver.empty() ? "" : ", driver " + d.driver) << ")";
    if (!d.others.empty()) {
        md << "; not chosen:";
        for (const std::string& s : d.others) md << " " << s << ";";
    }
    md << "\n- validation layers: "
       << (d.validation            ? "on, " + std::to_string(validation.size()) + " message(s)"
           : d.validationAvailable ? "off"
                                   : "off (VK_LAYER_KHRONOS_validation not installed)")
       << "\n- machine: " << m.cpu << ", " << m.cores << " hardware threads; load average "
       << m.loadAverage << " before, " << after.loadAverage << " after\n";
    md << "- " << o.frames
       << " timed frame(s) per row after one warm-up, medians; wall = "
          "`Renderer::render` with the colour read back; GPU = the sum of the frame's pass "
          "timestamps (on lavapipe it misses work done outside them); ratio = weft fps / seed fps "
          "(target on a GPU: >= 3); the seed rows render as the seeds did: no MSAA, no bounce light, "
          "no ambient occlusion\n";
    auto table = [&](const std::string& set, const std::string& title, bool seed) {
        bool any = false;
        for (const BenchRow& r : rows) any = any || r.set == set;
        if (!any) return;
        md << "\n## " << title
           << "\n\n| workload | config | size | wall ms | fps | GPU ms | GPU fps |";
        if (seed) md << " seed fps | ratio (wall) | ratio (GPU) |";
        md << " heaviest passes, GPU ms |\n|---|---|---|---|---|---|---|";
        if (seed) md << "---|---|---|";
        md << "---|\n";
        for (const BenchRow& r : rows) {
            if (r.set != set) continue;
            md << "| " << r.workload << " | " << r.config << " | " << r.width << "x" << r.height
               << " | " << cell(r.wallMs) << " | " << cell(fps(r.wallMs)) << " | " << cell(r.gpuMs)
               << " | " << cell(fps(r.gpuMs)) << " |";
            if (seed)
                md << " " << (r.seedFps > 0 ? num(r.seedFps, 0) : "-") << " | "
                   << (r.seedFps > 0 ? num(fps(r.wallMs) / r.seedFps, 4) : "-") << " | "
                   << (r.seedFps > 0 && r.gpuMs > 0 ? num(fps(r.gpuMs) / r.seedFps, 4) : "-")
                   << " |";
            md << " " << topPasses(r, 4) << " |\n";
        }
    };
    table("demo", "seed-000 demo scene (target on a GPU: >= 120 fps at 1920x1080)", false);
    passTable(md, rows, "demo");
    table("hair", "seed 002: hair and fur, B / B+S / B+S+T (SPEC 5.5, GTX 980)", true);
    table("dome", "seed 001: dome shadow lights (SPEC 4.7, GeForce of 2006)", true);
    if (!validation.empty()) {
        md << "\n## validation messages\n\n";
        for (const std::string& v : validation) md << "- " << v << "\n";
    }
    return md.str();
}

} // namespace weft::bench
