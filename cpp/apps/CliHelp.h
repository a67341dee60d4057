#pragma once
// The --help layout weft-demo and weft-bench share over CLI11: the usage line first, then what
// the program does, its options (as "-h, --help"), and a footer.
#include <sstream>
#include <string>

#include <CLI/CLI.hpp>

namespace weft::apps {

class HelpFormatter : public CLI::Formatter {
public:
    std::string make_help(const CLI::App* app, std::string name,
                          CLI::AppFormatMode mode) const override {
        std::ostringstream out;
        // make_groups starts each group with a blank line.
        out << "usage: " << name << " [options]\n\n"
            << app->get_description() << make_groups(app, mode) << "\n"
            << app->get_footer();
        return out.str();
    }
    std::string make_option_name(const CLI::Option* opt, bool positional) const override {
        std::string name = CLI::Formatter::make_option_name(opt, positional);
        for (size_t at = name.find(','); at != std::string::npos; at = name.find(',', at + 2))
            name.insert(at + 1, " "); // "-h, --help"
        return name;
    }
};

/// Sets `app` up with the shared layout: options in one "options" group, descriptions from
/// column 21, `footer` after them. Add the options, then call addHelp(app) last, so that
/// -h, --help is listed last, as the hand-written help always did.
inline void useHelpLayout(CLI::App& app, const std::string& footer) {
    auto formatter = std::make_shared<HelpFormatter>();
    formatter->column_width(21);
    formatter->label("OPTIONS", "options");
    app.formatter(formatter);
    app.footer(footer);
    app.set_help_flag();
    app.option_defaults()->group("options");
}

inline void addHelp(CLI::App& app) { app.set_help_flag("-h,--help", "show this help"); }

} // namespace weft::apps
