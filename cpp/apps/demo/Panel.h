#pragma once
// weft-demo's panel: the controls that are keys today, the renderer's settings and the frame's
// time per pass, as Dear ImGui widgets over the window. Every widget changes its value through
// DemoSettings.h, the table a --script "set" line uses, so scripts test what the panel does.
#include <deque>
#include <memory>
#include <string>

#include "ImGuiLayer.h"
#include "app/DemoPanel.h"

namespace weft::demo {

class Panel : public app::DemoPanel {
public:
    /// `environment`: the --environment file the scene is lit with ("" for the analytic sky).
    explicit Panel(std::string environment) : mEnvironment(std::move(environment)) {}

    void attach(Window& window, Renderer& renderer) override;
    void update(app::DemoScene& demo, app::DemoControls& controls, const FrameStats& last,
                const app::DemoRates& rates) override;
    bool wantsMouse() const override;
    bool wantsKeyboard() const override;
    void detach() override { mLayer.reset(); }

private:
    void timings(const FrameStats& last, const app::DemoRates& rates);

    std::string mEnvironment;
    std::unique_ptr<ImGuiLayer> mLayer;
    std::deque<float> mFrameMs; // the last frames' GPU (or CPU) time, for the plot
};

} // namespace weft::demo
