#pragma once
// A UI drawn over the demo's window: weft-demo's Dear ImGui panel (apps/demo/). The library only
// calls this interface, so the library, the headless path and the Python module link no UI
// toolkit, and a run without a display never touches one.
namespace weft {
class Renderer;
class Window;
struct FrameStats;
} // namespace weft

namespace weft::app {

class DemoScene;
struct DemoControls;

/// What the window loop measures, for the panel to show.
struct DemoRates {
    double fps = 0.0;
    double simStepsPerSecond = 0.0;
};

class DemoPanel {
public:
    virtual ~DemoPanel() = default;
    /// The run's window and renderer exist: called once, before the first frame.
    virtual void attach(Window& window, Renderer& renderer) = 0;
    /// Before each frame is drawn: lays the widgets out and applies what the user changed to
    /// `demo` and `controls` (through DemoSettings.h, as a --script "set" line would);
    /// `last` is the renderer's last frame. Nothing is drawn while controls.panel is off.
    virtual void update(DemoScene& demo, DemoControls& controls, const FrameStats& last,
                        const DemoRates& rates) = 0;
    /// The panel has the mouse / the keyboard now: the demo leaves those events to it.
    virtual bool wantsMouse() const = 0;
    virtual bool wantsKeyboard() const = 0;
    /// Before the window and the renderer go.
    virtual void detach() = 0;
};

} // namespace weft::app
