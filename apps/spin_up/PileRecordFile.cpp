#include "apps/spin_up/PileRecordFile.hpp"

#include "core/Error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <fstream>
#include <map>
#include <sstream>

namespace regolith::apps {

namespace {

std::vector<std::string> split(std::string const& line, char by) {
    std::vector<std::string> out;
    std::stringstream in(line);
    std::string item;
    while (std::getline(in, item, by))
        if (!item.empty())
            out.push_back(item);
    return out;
}

/// The number in `text`, or throws `bad`.
double number(std::string const& text, core::InputError const& bad) {
    double v = 0.0;
    auto const [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (ec != std::errc() || end != text.data() + text.size())
        throw bad;
    return v;
}

} // namespace

std::string readPileRecord(std::string const& path) {
    std::ifstream in(path);
    if (!in)
        return {};
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

ResumedRecord resumeRecord(std::string_view text, double until, std::string const& path) {
    core::InputError const bad(fmt::format(
        "pile.file = \"{}\": expected the record of the run being restarted (its first line "
        "'# mass=… omega_c=…', then its columns), to continue it",
        path));
    std::stringstream in{std::string(text)};
    std::string header, columns;
    if (!std::getline(in, header) || !header.starts_with("#") || !std::getline(in, columns))
        throw bad;
    std::map<std::string, double> ref;
    for (std::string const& kv : split(header.substr(1), ' ')) {
        auto const eq = kv.find('=');
        if (eq == std::string::npos)
            throw bad;
        ref[kv.substr(0, eq)] = number(kv.substr(eq + 1), bad);
    }
    auto const value = [&](char const* key) {
        auto const it = ref.find(key);
        if (it == ref.end())
            throw bad;
        return it->second;
    };
    ResumedRecord out;
    PileReference& r = out.reference;
    r.mass = value("mass");
    r.bulkRadius = value("bulk_radius");
    r.omegaC = value("omega_c");
    r.spin = value("spin");
    r.centre = core::Vec3(value("centre_x"), value("centre_y"), value("centre_z"));
    r.meanGrainRadius = value("mean_grain_radius");
    out.centre = r.centre;
    std::vector<std::string> const names = split(columns, ',');
    auto const column = [&](char const* name) {
        auto const it = std::find(names.begin(), names.end(), name);
        if (it == names.end())
            throw bad;
        return static_cast<std::size_t>(it - names.begin());
    };
    std::size_t const time = column("time"), spin = column("spin_over_omega_c");
    std::size_t const shed = column("shed_fraction");
    std::size_t const cx = column("centre_x"), cy = column("centre_y"), cz = column("centre_z");
    out.kept = header + "\n" + columns + "\n";
    double const last = until * (1.0 + 1e-8) + 1e-12; // the rows' times have 9 digits
    std::string line;
    while (std::getline(in, line)) {
        std::vector<std::string> const cells = split(line, ',');
        if (cells.size() != names.size())
            throw bad;
        if (number(cells[time], bad) > last)
            break;
        out.spins.push_back(number(cells[spin], bad));
        if (!out.onset && number(cells[shed], bad) > 0.0)
            out.onset = out.spins.back();
        out.centre =
            core::Vec3(number(cells[cx], bad), number(cells[cy], bad), number(cells[cz], bad));
        out.kept += line + "\n";
    }
    return out;
}

} // namespace regolith::apps
