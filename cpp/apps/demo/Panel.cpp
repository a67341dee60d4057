#include "Panel.h"

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <vector>

#include <GLFW/glfw3.h>
#include <imgui.h>

#include <weft/FrameStats.h>

#include "app/DemoSettings.h"
#include <weft/DemoScene.h>

namespace weft::demo {
namespace {

constexpr size_t kPlotFrames = 120;

// A panel edit goes through the settings table, exactly as a script's "set" line, and is
// logged as a key press is.
void set(app::DemoScene& demo, app::DemoControls& controls, const char* name,
         const std::string& value) {
    std::cout << "weft-demo: " << app::applyDemoSetting(demo, controls, name, value) << std::endl;
}

std::string number(float x) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", double(x));
    return text;
}

void checkbox(app::DemoScene& demo, app::DemoControls& controls, const char* label,
              const char* name, bool value) {
    if (ImGui::Checkbox(label, &value)) set(demo, controls, name, value ? "on" : "off");
}

// A combo over `names`, the setting's values (shown as `labels` when given).
void combo(app::DemoScene& demo, app::DemoControls& controls, const char* label, const char* name,
           const std::vector<const char*>& names, int current,
           const std::vector<const char*>& labels = {}) {
    const std::vector<const char*>& shown = labels.empty() ? names : labels;
    if (ImGui::Combo(label, &current, shown.data(), int(shown.size())))
        set(demo, controls, name, names[size_t(current)]);
}

// The passes summed by kind: "bounce0[1][4]" (capture 0, round 1, face 4) counts as "bounce",
// so a frame's dozens of capture faces take one row.
struct PassGroup {
    std::string name;
    int count = 0;
    double ms = 0.0;
};

std::vector<PassGroup> groupPasses(const std::vector<PassStats>& passes, bool gpu) {
    std::vector<PassGroup> groups;
    for (const PassStats& p : passes) {
        std::string kind = p.name.substr(0, p.name.find('['));
        while (kind.size() > 1 && kind.back() >= '0' && kind.back() <= '9') kind.pop_back();
        auto it = std::find_if(groups.begin(), groups.end(),
                               [&](const PassGroup& g) { return g.name == kind; });
        if (it == groups.end()) it = groups.insert(groups.end(), PassGroup{kind});
        ++it->count;
        it->ms += std::max(gpu ? p.gpuMs : p.cpuMs, 0.0);
    }
    return groups;
}

int indexOf(const std::vector<const char*>& names, const std::string& value) {
    for (size_t i = 0; i < names.size(); ++i)
        if (value == names[i]) return int(i);
    return 0;
}

} // namespace

void Panel::attach(Window& window, Renderer& renderer) {
    mLayer = std::make_unique<ImGuiLayer>(window, renderer);
}

bool Panel::wantsMouse() const { return mLayer && ImGui::GetIO().WantCaptureMouse; }
bool Panel::wantsKeyboard() const { return mLayer && ImGui::GetIO().WantCaptureKeyboard; }

void Panel::timings(const FrameStats& last, const app::DemoRates& rates) {
    ImGui::Text("%.1f fps, %.1f simulation steps/s", rates.fps, rates.simStepsPerSecond);
    // A frame's timings arrive when its slot comes round again, two frames later.
    if (last.passes.empty()) {
        ImGui::TextUnformatted("(the first frames' timings are on their way)");
        return;
    }
    const bool gpu = last.gpuMs >= 0.0;
    const double frameMs = gpu ? last.gpuMs : last.cpuMs;
    mFrameMs.push_back(float(frameMs));
    if (mFrameMs.size() > kPlotFrames) mFrameMs.pop_front();
    if (gpu)
        ImGui::Text("frame %.1f ms GPU, %.1f ms CPU", frameMs, last.cpuMs);
    else
        ImGui::Text("frame %.1f ms CPU (no GPU timer)", frameMs);
    const std::vector<float> plot(mFrameMs.begin(), mFrameMs.end());
    const float top = plot.empty() ? 1.0f : *std::max_element(plot.begin(), plot.end());
    ImGui::PlotLines("##frame", plot.data(), int(plot.size()), 0, "frame ms", 0.0f, top * 1.1f,
                     ImVec2(-1.0f, 40.0f));
    if (!ImGui::BeginTable("passes", 3, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingFixedFit))
        return;
    ImGui::TableSetupColumn("pass");
    ImGui::TableSetupColumn(gpu ? "GPU ms" : "CPU ms");
    ImGui::TableSetupColumn("share");
    ImGui::TableHeadersRow();
    double sum = 0.0;
    const std::vector<PassGroup> groups = groupPasses(last.passes, gpu);
    for (const PassGroup& g : groups) sum += g.ms;
    for (const PassGroup& g : groups) {
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        if (g.count > 1)
            ImGui::Text("%s (%d)", g.name.c_str(), g.count);
        else
            ImGui::TextUnformatted(g.name.c_str());
        ImGui::TableNextColumn();
        ImGui::Text("%.2f", g.ms);
        ImGui::TableNextColumn();
        ImGui::Text("%.0f%%", sum > 0.0 ? 100.0 * g.ms / sum : 0.0);
    }
    ImGui::EndTable();
    if (!last.reused.empty()) {
        std::string reused;
        for (const std::string& r : last.reused) reused += (reused.empty() ? "" : ", ") + r;
        ImGui::TextWrapped("reused: %s", reused.c_str());
    }
}

void Panel::update(app::DemoScene& demo, app::DemoControls& controls, const FrameStats& last,
                   const app::DemoRates& rates) {
    if (!mLayer) return;
    mLayer->beginFrame();
    if (controls.panel) {
        // As tall as the window allows, scrolling beyond; the user may move and resize it.
        const float height = std::min(ImGui::GetIO().DisplaySize.y - 16.0f, 720.0f);
        ImGui::SetNextWindowPos(ImVec2(8.0f, 8.0f), ImGuiCond_FirstUseEver);
        ImGui::SetNextWindowSize(ImVec2(330.0f, std::max(height, 100.0f)), ImGuiCond_FirstUseEver);
        ImGui::Begin("weft demo (F1 hides)");
        ImGui::PushItemWidth(140.0f);
        RenderSettings& r = controls.render;
        if (ImGui::CollapsingHeader("frame time per pass", ImGuiTreeNodeFlags_DefaultOpen))
            timings(last, rates);
        if (ImGui::CollapsingHeader("image", ImGuiTreeNodeFlags_DefaultOpen)) {
            float ev = r.exposure;
            if (ImGui::SliderFloat("exposure (EV)", &ev, -10.0f, 10.0f, "%+.1f"))
                set(demo, controls, "exposure", number(ev));
            const std::vector<const char*> tones(app::kToneMapNames, app::kToneMapNames + 4);
            combo(demo, controls, "tone map", "tone-map", tones, int(r.toneMap));
            const std::vector<const char*> msaa = {"1", "2", "4", "8"};
            combo(demo, controls, "anti-aliasing", "msaa", msaa,
                  indexOf(msaa, std::to_string(r.msaa)), {"off", "2x MSAA", "4x MSAA", "8x MSAA"});
            const std::vector<const char*> ao = {"0", "8", "16", "32", "64"};
            combo(demo, controls, "ambient occlusion", "ao", ao,
                  indexOf(ao, std::to_string(r.ambientOcclusion)),
                  {"off", "8 lights", "16 lights", "32 lights", "64 lights"});
            checkbox(demo, controls, "bounce light", "bounce", r.bounce);
        }
        if (ImGui::CollapsingHeader("sky and light")) {
            if (demo.environmentLit()) {
                ImGui::TextWrapped("lit by %s", mEnvironment.c_str());
            } else {
                float hour = demo.hour();
                if (ImGui::SliderFloat("time of day (h)", &hour, 0.0f, 24.0f, "%.1f"))
                    set(demo, controls, "hour", number(hour));
                checkbox(demo, controls, "day-night cycle", "day-night", demo.dayNight());
                float azimuth = demo.lightAzimuth();
                if (ImGui::SliderFloat("light azimuth", &azimuth, 0.0f, 359.0f, "%.0f deg"))
                    set(demo, controls, "light-azimuth", number(azimuth));
            }
            checkbox(demo, controls, "shadows", "shadows", demo.shadows());
            const std::vector<const char*> pcf = {"0", "1", "2", "3"};
            combo(demo, controls, "PCF kernel", "pcf", pcf, demo.pcf(),
                  {"1x1", "3x3", "5x5", "7x7"});
        }
        if (ImGui::CollapsingHeader("cloth")) {
            float wind = demo.windStrength();
            if (ImGui::SliderFloat("wind", &wind, 0.0f, 30.0f, "%.1f"))
                set(demo, controls, "wind", number(wind));
            float direction = demo.windDirection();
            if (ImGui::SliderFloat("wind direction", &direction, 0.0f, 359.0f, "%.0f deg"))
                set(demo, controls, "wind-direction", number(direction));
            checkbox(demo, controls, "normal map", "normal-map", demo.normalMap());
            checkbox(demo, controls, "fitted BTF material", "btf", demo.btf());
            checkbox(demo, controls, "holes", "holes", demo.holes());
            checkbox(demo, controls, "paused", "paused", demo.paused());
            if (ImGui::Button("reset the cloth"))
                std::cout << "weft-demo: " << demo.key(GLFW_KEY_C) << std::endl;
        }
        if (ImGui::CollapsingHeader("hair and sphere")) {
            const std::vector<const char*> fur(app::kFurModelNames, app::kFurModelNames + 3);
            combo(demo, controls, "fur shading", "fur", fur, demo.furModel(),
                  {"Kajiya-Kay", "Marschner", "Sadeghi"});
            checkbox(demo, controls, "hair transparency", "hair-transparency", r.hairTransparency);
            checkbox(demo, controls, "hair self-shadowing", "hair-shadows", r.hairDeepOpacity);
            checkbox(demo, controls, "reflective sphere", "reflective", demo.reflections());
        }
        ImGui::PopItemWidth();
        ImGui::TextWrapped("%s", demo.status().c_str());
        ImGui::End();
    }
    mLayer->endFrame(controls.panel);
}

} // namespace weft::demo
