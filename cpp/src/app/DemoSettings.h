#pragma once
// The demo's named settings: what weft-demo's panel shows and edits, and what a --script line
// "<frame> set <name> <value>" changes. One table serves both, so a script drives exactly the
// state the panel's widgets are bound to. Each applies to the scene (DemoScene) or to the
// renderer's settings (DemoControls::render). Parsing (DemoSettings.cpp) needs no scene, so the
// --script parser links without the renderer (its libFuzzer target, tests/fuzz/cpp); applying
// is DemoSettingsApply.cpp.
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

/// The settings, in the panel's order (the same as demoSettings()).
enum class DemoSettingId {
    Exposure,
    ToneMap,
    Msaa,
    Ao,
    Bounce,
    Hour,
    DayNight,
    LightAzimuth,
    Shadows,
    Pcf,
    HairTransparency,
    HairShadows,
    Fur,
    Wind,
    WindDirection,
    Paused,
    NormalMap,
    Btf,
    Holes,
    Reflective,
    Panel
};

/// A setting's value as parsed: `number` for numbers (exposure, ao, hour, angles, wind),
/// `index` for choices (tone map, MSAA 1/2/4/8 -> 0..3, PCF radius, fur model), `on` for on|off.
struct DemoSettingValue {
    DemoSettingId id = DemoSettingId::Exposure;
    float number = 0.0f;
    int index = 0;
    bool on = false;
};

/// Parses `value` for setting `name`; throws InvalidArgument unless `name` is a setting and
/// `value` one of its values.
DemoSettingValue parseDemoSetting(const std::string& name, const std::string& value);

/// Throws InvalidArgument unless `name` is a setting and `value` one of its values.
void checkDemoSetting(const std::string& name, const std::string& value);

/// Sets `name` to `value` (checked as above); returns a one-line description of the change.
std::string applyDemoSetting(DemoScene& demo, DemoControls& controls, const std::string& name,
                             const std::string& value);

/// The settings' names of the fur models (index = DemoScene::furModel()) and tone maps.
extern const char* const kFurModelNames[3];
extern const char* const kToneMapNames[4];

} // namespace weft::app
