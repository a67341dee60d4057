#pragma once
// A pass module a Renderer's user adds after tone mapping, drawn into what present() shows
// (weft-demo's ImGui panel, apps/demo/PanelPass.cpp). It lives outside the renderer so that the
// renderer, the headless path and the Python module never link a UI toolkit.
#include <weft/Renderer.h>

namespace weft::render {

class FrameGraph;
struct FramePassContext;

class FrameOverlay {
public:
    virtual ~FrameOverlay() = default;
    /// Adds passes that draw over f.ldr (registered as f.rLdr, already tone mapped, sRGB) and
    /// run before it is read back or presented. Called only for present() frames.
    virtual void addPasses(FrameGraph& g, FramePassContext& f) = 0;
};

/// Draws `overlay` over every later present() of `renderer` (null: none). The overlay must
/// outlive its use by the renderer; attach null before destroying it.
void setFrameOverlay(Renderer& renderer, FrameOverlay* overlay);

} // namespace weft::render
