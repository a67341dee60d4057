#include "BenchReport.h"

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <sstream>
#include <thread>

#include <weft/Error.h>

namespace weft::bench {
namespace {

std::string quoted(const std::string& s) {
    std::string out = "\"";
    for (char c : s) {
        if (c == '"' || c == '\\') out += '\\';
        if (static_cast<unsigned char>(c) >= 0x20) out += c;
    }
    return out + "\"";
}

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

std::string reportJson(const BenchOptions& o, const DeviceReport& d, const MachineReport& m,
                       const MachineReport& after, const std::vector<BenchRow>& rows,
                       const std::vector<std::string>& validation) {
    std::ostringstream j;
    j << "{\n  \"tool\": \"weft-bench\", \"weft_version\": " << quoted(WEFT_VERSION)
      << ", \"date\": " << quoted(m.date) << ", \"quick\": " << (o.quick ? "true" : "false")
      << ", \"timed_frames\": " << o.frames << ",\n";
    j << "  \"device\": {\"name\": " << quoted(d.name) << ", \"type\": " << quoted(d.type)
      << ", \"driver\": " << quoted(d.driver) << ", \"api_version\": " << quoted(d.apiVersion)
      << ", \"others\": [";
    for (size_t i = 0; i < d.others.size(); ++i) j << (i ? ", " : "") << quoted(d.others[i]);
    j << "]},\n  \"validation\": {\"enabled\": " << (d.validation ? "true" : "false")
      << ", \"layer_available\": " << (d.validationAvailable ? "true" : "false")
      << ", \"messages\": [";
    for (size_t i = 0; i < validation.size(); ++i) j << (i ? ", " : "") << quoted(validation[i]);
    j << "]},\n  \"machine\": {\"cpu\": " << quoted(m.cpu) << ", \"cores\": " << m.cores
      << ", \"loadavg_before\": " << quoted(m.loadAverage)
      << ", \"loadavg_after\": " << quoted(after.loadAverage) << "},\n  \"rows\": [";
    for (size_t i = 0; i < rows.size(); ++i) {
        const BenchRow& r = rows[i];
        j << (i ? ",\n" : "\n") << "    {\"set\": " << quoted(r.set) << ", \"workload\": "
          << quoted(r.workload) << ", \"config\": " << quoted(r.config) << ", \"width\": "
          << r.width << ", \"height\": " << r.height << ", \"vertices\": " << r.vertices
          << ", \"frames\": " << r.frames << ", \"wall_ms\": " << num(r.wallMs)
          << ", \"fps\": " << num(fps(r.wallMs)) << ", \"gpu_ms\": " << num(r.gpuMs)
          << ", \"gpu_fps\": " << num(fps(r.gpuMs)) << ", \"seed_fps\": "
          << (r.seedFps > 0 ? num(r.seedFps, 0) : "null") << ", \"ratio_wall\": "
          << (r.seedFps > 0 ? num(fps(r.wallMs) / r.seedFps, 5) : "null")
          << ", \"ratio_gpu\": "
          << (r.seedFps > 0 && r.gpuMs > 0 ? num(fps(r.gpuMs) / r.seedFps, 5) : "null")
          << ", \"seed_source\": " << quoted(r.seedSource) << ", \"passes_gpu_ms\": {";
        bool first = true;
        for (const auto& [name, ms] : r.passGpuMs) {
            j << (first ? "" : ", ") << quoted(name) << ": " << num(ms);
            first = false;
        }
        j << "}}";
    }
    j << "\n  ]\n}\n";
    return j.str();
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
       << (d.validation ? "on, " + std::to_string(validation.size()) + " message(s)"
                        : d.validationAvailable ? "off" : "off (VK_LAYER_KHRONOS_validation not installed)")
       << "\n- machine: " << m.cpu << ", " << m.cores << " hardware threads; load average "
       << m.loadAverage << " before, " << after.loadAverage << " after\n";
    md << "- " << o.frames << " timed frame(s) per row after one warm-up, medians; wall = "
          "`Renderer::render` with the colour read back; GPU = the sum of the frame's pass "
          "timestamps (on lavapipe it misses work done outside them); ratio = weft fps / seed fps "
          "(target on a GPU: >= 3); the seed rows render as the seeds did: no MSAA, no bounce light, "
          "no ambient occlusion\n";
    auto table = [&](const std::string& set, const std::string& title, bool seed) {
        bool any = false;
        for (const BenchRow& r : rows) any = any || r.set == set;
        if (!any) return;
        md << "\n## " << title << "\n\n| workload | config | size | wall ms | fps | GPU ms | GPU fps |";
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
                   << (r.seedFps > 0 && r.gpuMs > 0 ? num(fps(r.gpuMs) / r.seedFps, 4) : "-") << " |";
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
