#pragma once
// The demo's named settings: what weft-demo's panel shows and edits, and what a --script line
// "<frame> set <name> <value>" changes. One table serves both, so a script drives exactly the
// state the panel's widgets are bound to. Each applies to the scene (DemoScene) or to the
// renderer's settings (DemoControls::render).
#include <string>
#include <vector>

#include <weft/Renderer.h>

namespace weft::app {

class DemoScene;

/// What the demo keeps besides its scene: the renderer settings the controls edit.
struct DemoControls {
    RenderSettings render;
    bool renderChanged = false; ///< render was edited and is not yet the renderer's
    bool panel = true;          ///< weft-demo's panel is shown (a window with a panel only)
};

struct DemoSetting {
    const char* name;
    const char* values; ///< the form of its values, for messages and help: "on|off", "EV", ...
};

/// Every setting, in the panel's order.
const std::vector<DemoSetting>& demoSettings();

/// Throws InvalidArgument unless `name` is a setting and `value` one of its values.
void checkDemoSetting(const std::string& name, const std::string& value);

/// Sets `name` to `value` (checked as above); returns a one-line description of the change.
std::string applyDemoSetting(DemoScene& demo, DemoControls& controls, const std::string& name,
                             const std::string& value);

/// The settings' names of the fur models (index = DemoScene::furModel()) and tone maps.
extern const char* const kFurModelNames[3];
extern const char* const kToneMapNames[4];

} // namespace weft::app
