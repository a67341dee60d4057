// Applying a parsed demo setting (DemoSettings.cpp parses) to the scene or to the renderer
// settings the controls hold; every setting is a case of the switch (-Wswitch warns of one
// missing).
#include "app/DemoSettings.h"

#include <sstream>

#include <GLFW/glfw3.h>

#include <weft/DemoScene.h>
#include <weft/Error.h>

namespace weft::app {

namespace {

std::string renderChange(DemoControls& c, const std::string& what) {
    c.renderChanged = true;
    return what;
}

std::string onOffText(bool on) { return on ? "on" : "off"; }

// A key press toggles these in the scene: press it when the state differs from the wish.
std::string toggle(DemoScene& demo, bool want, bool now, int key, const char* name) {
    if (want != now) return demo.key(key);
    return std::string(name) + " already " + (want ? "on" : "off");
}

} // namespace

std::string applyDemoSetting(DemoScene& d, DemoControls& c, const std::string& name,
                             const std::string& v) {
    const DemoSettingValue p = parseDemoSetting(name, v);
    switch (p.id) {
    case DemoSettingId::Exposure: {
        c.render.exposure = p.number;
        std::ostringstream s;
        s << "exposure " << std::showpos << p.number << " EV";
        return renderChange(c, s.str());
    }
    case DemoSettingId::ToneMap:
        c.render.toneMap = ToneMap(p.index);
        return renderChange(c, std::string("tone map ") + kToneMapNames[p.index]);
    case DemoSettingId::Msaa:
        c.render.msaa = 1u << p.index;
        return renderChange(c, "MSAA " + v + "x");
    case DemoSettingId::Ao:
        c.render.ambientOcclusion = uint32_t(p.number);
        return renderChange(c, "ambient occlusion " +
                                   (p.number > 0 ? v + " dome lights" : std::string("off")));
    case DemoSettingId::Bounce:
        c.render.bounce = p.on;
        return renderChange(c, "bounce light " + onOffText(p.on));
    case DemoSettingId::Hour:
        d.setHour(p.number);
        return "time of day " + v + "h" +
               (d.environmentLit() ? " (no effect: lit by a captured environment)" : "");
    case DemoSettingId::DayNight:
        return toggle(d, p.on, d.dayNight(), GLFW_KEY_T, "day-night cycle");
    case DemoSettingId::LightAzimuth:
        d.setLightAzimuth(p.number);
        return "light azimuth " + v + " deg";
    case DemoSettingId::Shadows: return toggle(d, p.on, d.shadows(), GLFW_KEY_S, "shadows");
    case DemoSettingId::Pcf: {
        std::string what;
        while (d.pcf() != p.index) what = d.key(GLFW_KEY_P); // P cycles 0..3
        return what.empty() ? "PCF unchanged" : what;
    }
    case DemoSettingId::HairTransparency:
        c.render.hairTransparency = p.on;
        return renderChange(c, "hair transparency (OIT) " + onOffText(p.on));
    case DemoSettingId::HairShadows:
        c.render.hairDeepOpacity = p.on;
        return renderChange(c, "hair deep opacity maps " + onOffText(p.on));
    case DemoSettingId::Fur: {
        std::string what = "fur shading unchanged";
        while (d.furModel() != p.index) what = d.key(GLFW_KEY_K); // K cycles the three
        return what;
    }
    case DemoSettingId::Wind: d.setWind(p.number, d.windDirection()); return "wind strength " + v;
    case DemoSettingId::WindDirection:
        d.setWind(d.windStrength(), p.number);
        return "wind direction " + v + " deg";
    case DemoSettingId::Paused: return toggle(d, p.on, d.paused(), GLFW_KEY_SPACE, "pause");
    case DemoSettingId::NormalMap:
        return toggle(d, p.on, d.normalMap(), GLFW_KEY_N, "normal mapping");
    case DemoSettingId::Btf: return toggle(d, p.on, d.btf(), GLFW_KEY_B, "BTF material");
    case DemoSettingId::Holes: return toggle(d, p.on, d.holes(), GLFW_KEY_H, "holes");
    case DemoSettingId::Reflective:
        return toggle(d, p.on, d.reflections(), GLFW_KEY_E, "reflective sphere");
    case DemoSettingId::Panel: c.panel = p.on; return "panel " + onOffText(p.on);
    }
    throw Error("demo setting '" + name + "' has no way to be applied");
}

} // namespace weft::app
