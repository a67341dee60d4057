// The demo's settings: names, the form of their values and parsing. Applying a parsed value to
// the scene or the renderer settings is DemoSettingsApply.cpp.
#include "app/DemoSettings.h"

#include <cmath>
#include <sstream>

#include <weft/Error.h>

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

// Parses a value of one setting into `out` (number, index or on); throws InvalidArgument.
using Parse = void (*)(const std::string& name, const std::string& v, DemoSettingValue& out);

struct Entry {
    DemoSettingId id;
    DemoSetting setting;
    Parse parse;
};

void parseOnOff(const std::string& n, const std::string& v, DemoSettingValue& out) {
    out.on = onOff(n, v);
}

void parseAngle(const std::string& n, const std::string& v, DemoSettingValue& out) {
    out.number = number(n, v, -360.0f, 360.0f);
}

const std::vector<Entry>& entries() {
    using Id = DemoSettingId;
    static const std::vector<Entry> table = {
        {Id::Exposure,
         {"exposure", "EV in [-10, 10]"},
         [](auto& n, auto& v, DemoSettingValue& out) { out.number = number(n, v, -10.0f, 10.0f); }},
        {Id::ToneMap,
         {"tone-map", "clamp|aces|agx|neutral"},
         [](auto& n, auto& v, DemoSettingValue& out) {
             out.index = choice(n, v, kToneMapNames, 4, "clamp, aces, agx or neutral");
         }},
        {Id::Msaa,
         {"msaa", "1|2|4|8"},
         [](auto& n, auto& v, DemoSettingValue& out) {
             static const char* const counts[] = {"1", "2", "4", "8"};
             out.index = choice(n, v, counts, 4, "1, 2, 4 or 8");
         }},
        {Id::Ao,
         {"ao", "0|8|16|...|64 dome lights"},
         [](auto& n, auto& v, DemoSettingValue& out) {
             const float lights = number(n, v, 0.0f, 64.0f);
             if (lights != std::floor(lights) || int(lights) % 8 != 0)
                 refuse(n, v, "0 or a multiple of 8 up to 64");
             out.number = lights;
         }},
        {Id::Bounce, {"bounce", "on|off"}, parseOnOff},
        {Id::Hour,
         {"hour", "hours in [0, 24]"},
         [](auto& n, auto& v, DemoSettingValue& out) { out.number = number(n, v, 0.0f, 24.0f); }},
        {Id::DayNight, {"day-night", "on|off"}, parseOnOff},
        {Id::LightAzimuth, {"light-azimuth", "degrees"}, parseAngle},
        {Id::Shadows, {"shadows", "on|off"}, parseOnOff},
        {Id::Pcf,
         {"pcf", "radius 0..3"},
         [](auto& n, auto& v, DemoSettingValue& out) {
             static const char* const radii[] = {"0", "1", "2", "3"};
             out.index = choice(n, v, radii, 4, "0, 1, 2 or 3");
         }},
        {Id::HairTransparency, {"hair-transparency", "on|off"}, parseOnOff},
        {Id::HairShadows, {"hair-shadows", "on|off"}, parseOnOff},
        {Id::Fur,
         {"fur", "kajiya-kay|marschner|sadeghi"},
         [](auto& n, auto& v, DemoSettingValue& out) {
             out.index = choice(n, v, kFurModelNames, 3, "kajiya-kay, marschner or sadeghi");
         }},
        {Id::Wind,
         {"wind", "strength in [0, 30]"},
         [](auto& n, auto& v, DemoSettingValue& out) { out.number = number(n, v, 0.0f, 30.0f); }},
        {Id::WindDirection, {"wind-direction", "degrees"}, parseAngle},
        {Id::Paused, {"paused", "on|off"}, parseOnOff},
        {Id::NormalMap, {"normal-map", "on|off"}, parseOnOff},
        {Id::Btf, {"btf", "on|off"}, parseOnOff},
        {Id::Holes, {"holes", "on|off"}, parseOnOff},
        {Id::Reflective, {"reflective", "on|off"}, parseOnOff},
        {Id::Panel, {"panel", "on|off"}, parseOnOff},
    };
    return table;
}

const Entry& find(const std::string& name) {
    for (const Entry& e : entries())
        if (name == e.setting.name) return e;
    std::string known;
    for (const Entry& e : entries())
        known += std::string(known.empty() ? "" : ", ") + e.setting.name;
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

DemoSettingValue parseDemoSetting(const std::string& name, const std::string& value) {
    const Entry& e = find(name);
    DemoSettingValue out;
    out.id = e.id;
    e.parse(name, value, out);
    return out;
}

void checkDemoSetting(const std::string& name, const std::string& value) {
    parseDemoSetting(name, value);
}

} // namespace weft::app
