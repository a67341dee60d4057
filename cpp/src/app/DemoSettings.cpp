#include "app/DemoSettings.h"

#include <cmath>
#include <functional>
#include <iomanip>
#include <sstream>

#include <GLFW/glfw3.h>

#include <weft/Error.h>

#include <weft/DemoScene.h>

namespace weft::app {

const char* const kFurModelNames[3] = {"kajiya-kay", "marschner", "sadeghi"};
const char* const kToneMapNames[4] = {"clamp", "aces", "agx", "neutral"};

namespace {

[[noreturn]] void refuse(const std::string& name, const std::string& value, const char* form) {
    throw InvalidArgument("setting " + name + " needs " + form + ", got '" + value + "'");
}

bool onOff(const std::string& name, const std::string& v) {
    if (v == "on") return true;
    if (v == "off") return false;
    refuse(name, v, "on or off");
}

float number(const std::string& name, const std::string& v, float lo, float hi) {
    std::istringstream in(v);
    float x = 0.0f;
    // NaN fails both comparisons and is refused with the rest.
    if (!(in >> x) || !in.eof() || !(x >= lo && x <= hi)) {
        std::ostringstream form;
        form << "a number in [" << lo << ", " << hi << "]";
        refuse(name, v, form.str().c_str());
    }
    return x;
}

int choice(const std::string& name, const std::string& v, const char* const* names, int n,
           const char* form) {
    for (int i = 0; i < n; ++i)
        if (v == names[i]) return i;
    refuse(name, v, form);
}

// A key press toggles these in the scene: press it when the state differs from the wish.
std::string toggle(DemoScene& demo, bool want, bool now, int key, const char* name) {
    if (want != now) return demo.key(key);
    return std::string(name) + " already " + (want ? "on" : "off");
}

// Parses `v` and, with a scene, applies it; without one only checks.
using Apply = std::function<std::string(DemoScene*, DemoControls&, const std::string& name,
                                        const std::string& v)>;

struct Entry {
    DemoSetting setting;
    Apply apply;
};

std::string renderChange(DemoControls& c, const std::string& what) {
    c.renderChanged = true;
    return what;
}

std::string onOffText(bool on) { return on ? "on" : "off"; }

const std::vector<Entry>& entries() {
    static const std::vector<Entry> table = {
        {{"exposure", "EV in [-10, 10]"}, [](DemoScene* d, DemoControls& c, auto& n, auto& v) {
             const float ev = number(n, v, -10.0f, 10.0f);
             if (!d) return std::string();
             c.render.exposure = ev;
             std::ostringstream s;
             s << "exposure " << std::showpos << ev << " EV";
             return renderChange(c, s.str());
         }},
        {{"tone-map", "clamp|aces|agx|neutral"}, [](DemoScene* d, DemoControls& c, auto& n, auto& v) {
             const int i = choice(n, v, kToneMapNames, 4, "clamp, aces, agx or neutral");
             if (!d) return std::string();
             c.render.toneMap = ToneMap(i);
             return renderChange(c, std::string("tone map ") + kToneMapNames[i]);
         }},
        {{"msaa", "1|2|4|8"}, [](DemoScene* d, DemoControls& c, auto& n, auto& v) {
             static const char* const counts[] = {"1", "2", "4", "8"};
             const int i = choice(n, v, counts, 4, "1, 2, 4 or 8");
             if (!d) return std::string();
             c.render.msaa = 1u << i;
             return renderChange(c, "MSAA " + v + "x");
         }},
        {{"ao", "0|8|16|...|64 dome lights"}, [](DemoScene* d, DemoControls& c, auto& n, auto& v) {
             const float lights = number(n, v, 0.0f, 64.0f);
             if (lights != std::floor(lights) || int(lights) % 8 != 0)
                 refuse(n, v, "0 or a multiple of 8 up to 64");
             if (!d) return std::string();
             c.render.ambientOcclusion = uint32_t(lights);
             return renderChange(c, "ambient occlusion " + (lights > 0 ? v + " dome lights" : "off"));
         }},
        {{"bounce", "on|off"}, [](DemoScene* d, DemoControls& c, auto& n, auto& v) {
             const bool on = onOff(n, v);
             if (!d) return std::string();
             c.render.bounce = on;
             return renderChange(c, "bounce light " + onOffText(on));
         }},
        {{"hour", "hours in [0, 24]"}, [](DemoScene* d, DemoControls&, auto& n, auto& v) {
             const float h = number(n, v, 0.0f, 24.0f);
             if (!d) return std::string();
             d->setHour(h);
             return "time of day " + v + "h" + (d->environmentLit() ? " (no effect: lit by a captured environment)" : "");
         }},
        {{"day-night", "on|off"}, [](DemoScene* d, DemoControls&, auto& n, auto& v) {
             const bool on = onOff(n, v);
             return d ? toggle(*d, on, d->dayNight(), GLFW_KEY_T, "day-night cycle") : "";
         }},
        {{"light-azimuth", "degrees"}, [](DemoScene* d, DemoControls&, auto& n, auto& v) {
             const float deg = number(n, v, -360.0f, 360.0f);
             if (!d) return std::string();
             d->setLightAzimuth(deg);
             return "light azimuth " + v + " deg";
         }},
        {{"shadows", "on|off"}, [](DemoScene* d, DemoControls&, auto& n, auto& v) {
             const bool on = onOff(n, v);
             return d ? toggle(*d, on, d->shadows(), GLFW_KEY_S, "shadows") : "";
         }},
        {{"pcf", "radius 0..3"}, [](DemoScene* d, DemoControls&, auto& n, auto& v) {
             static const char* const radii[] = {"0", "1", "2", "3"};
             const int r = choice(n, v, radii, 4, "0, 1, 2 or 3");
             if (!d) return std::string();
             std::string what;
             while (d->pcf() != r) what = d->key(GLFW_KEY_P); // P cycles 0..3
             return what.empty() ? "PCF unchanged" : what;
         }},
        {{"hair-transparency", "on|off"}, [](DemoScene* d, DemoControls& c, auto& n, auto& v) {
             const bool on = onOff(n, v);
             if (!d) return std::string();
             c.render.hairTransparency = on;
             return renderChange(c, "hair transparency (OIT) " + onOffText(on));
         }},
        {{"hair-shadows", "on|off"}, [](DemoScene* d, DemoControls& c, auto& n, auto& v) {
             const bool on = onOff(n, v);
             if (!d) return std::string();
             c.render.hairDeepOpacity = on;
             return renderChange(c, "hair deep opacity maps " + onOffText(on));
         }},
        {{"fur", "kajiya-kay|marschner|sadeghi"}, [](DemoScene* d, DemoControls&, auto& n, auto& v) {
             const int m = choice(n, v, kFurModelNames, 3, "kajiya-kay, marschner or sadeghi");
             if (!d) return std::string();
             std::string what = "fur shading unchanged";
             while (d->furModel() != m) what = d->key(GLFW_KEY_K); // K cycles the three
             return what;
         }},
        {{"wind", "strength in [0, 30]"}, [](DemoScene* d, DemoControls&, auto& n, auto& v) {
             const float s = number(n, v, 0.0f, 30.0f);
             if (!d) return std::string();
             d->setWind(s, d->windDirection());
             return "wind strength " + v;
         }},
        {{"wind-direction", "degrees"}, [](DemoScene* d, DemoControls&, auto& n, auto& v) {
             const float deg = number(n, v, -360.0f, 360.0f);
             if (!d) return std::string();
             d->setWind(d->windStrength(), deg);
             return "wind direction " + v + " deg";
         }},
        {{"paused", "on|off"}, [](DemoScene* d, DemoControls&, auto& n, auto& v) {
             const bool on = onOff(n, v);
             return d ? toggle(*d, on, d->paused(), GLFW_KEY_SPACE, "pause") : "";
         }},
        {{"normal-map", "on|off"}, [](DemoScene* d, DemoControls&, auto& n, auto& v) {
             const bool on = onOff(n, v);
             return d ? toggle(*d, on, d->normalMap(), GLFW_KEY_N, "normal mapping") : "";
         }},
        {{"btf", "on|off"}, [](DemoScene* d, DemoControls&, auto& n, auto& v) {
             const bool on = onOff(n, v);
             return d ? toggle(*d, on, d->btf(), GLFW_KEY_B, "BTF material") : "";
         }},
        {{"holes", "on|off"}, [](DemoScene* d, DemoControls&, auto& n, auto& v) {
             const bool on = onOff(n, v);
             return d ? toggle(*d, on, d->holes(), GLFW_KEY_H, "holes") : "";
         }},
        {{"reflective", "on|off"}, [](DemoScene* d, DemoControls&, auto& n, auto& v) {
             const bool on = onOff(n, v);
             return d ? toggle(*d, on, d->reflections(), GLFW_KEY_E, "reflective sphere") : "";
         }},
        {{"panel", "on|off"}, [](DemoScene* d, DemoControls& c, auto& n, auto& v) {
             const bool on = onOff(n, v);
             if (!d) return std::string();
             c.panel = on;
             return "panel " + onOffText(on);
         }},
    };
    return table;
}

const Entry& find(const std::string& name) {
    for (const Entry& e : entries())
        if (name == e.setting.name) return e;
    std::string known;
    for (const Entry& e : entries()) known += std::string(known.empty() ? "" : ", ") + e.setting.name;
    throw InvalidArgument("unknown setting '" + name + "' (" + known + ")");
}

} // namespace

const std::vector<DemoSetting>& demoSettings() {
    static const std::vector<DemoSetting> list = [] {
        std::vector<DemoSetting> out;
        for (const Entry& e : entries()) out.push_back(e.setting);
        return out;
    }();
    return list;
}

void checkDemoSetting(const std::string& name, const std::string& value) {
    DemoControls scratch;
    find(name).apply(nullptr, scratch, name, value);
}

std::string applyDemoSetting(DemoScene& demo, DemoControls& controls, const std::string& name,
                             const std::string& value) {
    return find(name).apply(&demo, controls, name, value);
}

} // namespace weft::app
