#include "particles/generators/GrainCsv.hpp"

#include "core/Error.hpp"
#include "core/file/Files.hpp"
#include "core/log/Printable.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <istream>
#include <limits>
#include <string_view>

namespace regolith::particles {

namespace {

enum class Column { X, Y, Z, Radius, Vx, Vy, Vz, Wx, Wy, Wz, Density, Mass, Uid, Type, Count };

constexpr std::array<std::string_view, static_cast<std::size_t>(Column::Count)> kColumnNames{
    "x", "y", "z", "radius", "vx", "vy", "vz", "wx", "wy", "wz", "density", "mass", "uid", "type"};

/// At most this many bytes of a field are quoted in a message: the file may be anything
/// (path = "/etc/shadow"), and its content is not the message's to print.
constexpr std::size_t kQuotedBytes = 24;

std::string quoted(std::string_view field) {
    return core::printable(field, kQuotedBytes);
}

std::string_view trim(std::string_view s) {
    auto const first = s.find_first_not_of(" \t\r");
    if (first == std::string_view::npos)
        return {};
    auto const last = s.find_last_not_of(" \t\r");
    return s.substr(first, last - first + 1);
}

std::vector<std::string_view> splitFields(std::string_view line) {
    std::vector<std::string_view> fields;
    std::size_t start = 0;
    while (true) {
        auto const comma = line.find(',', start);
        fields.push_back(trim(line.substr(
            start, comma == std::string_view::npos ? std::string_view::npos : comma - start)));
        if (comma == std::string_view::npos)
            return fields;
        start = comma + 1;
    }
}

/// Where a message points: "particles[3].path: 'init.csv' line 7".
struct Place {
    std::string const& key;
    std::string const& file;
    int line;
    [[nodiscard]] std::string str() const {
        return fmt::format("{}: '{}' line {}", key, file, line);
    }
};

double parseReal(std::string_view field, Place const& at, std::size_t column,
                 std::string_view name) {
    if (field.size() > 1 && field.front() == '+' && field[1] != '-')
        field.remove_prefix(1); // from_chars rejects an explicit plus sign
    double value = 0.0;
    auto const* end = field.data() + field.size();
    auto const [ptr, ec] = std::from_chars(field.data(), end, value);
    if (field.empty() || ec != std::errc{} || ptr != end || !std::isfinite(value))
        throw core::InputError(fmt::format("{}, column {} ({}): expected a finite number, got '{}'",
                                           at.str(), column + 1, name, quoted(field)));
    return value;
}

std::uint64_t parseCount(std::string_view field, Place const& at, std::size_t column,
                         std::string_view name) {
    std::uint64_t value = 0;
    auto const* end = field.data() + field.size();
    auto const [ptr, ec] = std::from_chars(field.data(), end, value);
    if (field.empty() || ec != std::errc{} || ptr != end)
        throw core::InputError(
            fmt::format("{}, column {} ({}): expected a non-negative integer, got '{}'", at.str(),
                        column + 1, name, quoted(field)));
    return value;
}

bool skipLine(std::string_view line) {
    auto const t = trim(line);
    return t.empty() || t.front() == '#';
}

} // namespace

std::vector<std::string> const& grainCsvColumns() {
    static std::vector<std::string> const names(kColumnNames.begin(), kColumnNames.end());
    return names;
}

CsvGrainTable parseGrainCsv(std::istream& in, std::string const& fileName, std::string const& key) {
    std::string text;
    int lineNo = 0;
    // Header: the first line that is not blank or a comment.
    bool haveHeader = false;
    while (std::getline(in, text)) {
        ++lineNo;
        if (!skipLine(text)) {
            haveHeader = true;
            break;
        }
    }
    if (!haveHeader)
        throw core::InputError(fmt::format("{}: '{}' has no header line (expected column names "
                                           "such as x,y,z,radius)",
                                           key, fileName));
    Place const headerAt{key, fileName, lineNo};
    auto const header = splitFields(text);
    // A first line without one column name is not a grain table's header: say so without
    // quoting it (it may be anything).
    if (std::none_of(header.begin(), header.end(), [](std::string_view h) {
            return std::find(kColumnNames.begin(), kColumnNames.end(), h) != kColumnNames.end();
        }))
        throw core::InputError(fmt::format("{}: not a header of grain columns (expected column "
                                           "names such as x,y,z,radius; known: {})",
                                           headerAt.str(), fmt::join(kColumnNames, ",")));
    std::vector<Column> columnOf(header.size(), Column::Count);
    std::array<bool, static_cast<std::size_t>(Column::Count)> present{};
    for (std::size_t c = 0; c < header.size(); ++c) {
        std::size_t found = kColumnNames.size();
        for (std::size_t n = 0; n < kColumnNames.size(); ++n)
            if (header[c] == kColumnNames[n])
                found = n;
        if (found == kColumnNames.size())
            throw core::InputError(fmt::format("{}, column {}: unknown column '{}' (known: {})",
                                               headerAt.str(), c + 1, quoted(header[c]),
                                               fmt::join(kColumnNames, ",")));
        if (present[found])
            throw core::InputError(fmt::format("{}, column {}: duplicate column '{}'",
                                               headerAt.str(), c + 1, quoted(header[c])));
        present[found] = true;
        columnOf[c] = static_cast<Column>(found);
    }
    for (auto const required : {Column::X, Column::Y, Column::Z, Column::Radius})
        if (!present[static_cast<std::size_t>(required)])
            throw core::InputError(
                fmt::format("{}: missing required column '{}' (required: x,y,z,radius)",
                            headerAt.str(), kColumnNames[static_cast<std::size_t>(required)]));
    CsvGrainTable table;
    table.hasDensity = present[static_cast<std::size_t>(Column::Density)];
    table.hasMass = present[static_cast<std::size_t>(Column::Mass)];
    table.hasUid = present[static_cast<std::size_t>(Column::Uid)];
    table.hasType = present[static_cast<std::size_t>(Column::Type)];
    for (auto const w : {Column::Wx, Column::Wy, Column::Wz})
        table.hasAngularVelocity = table.hasAngularVelocity || present[static_cast<std::size_t>(w)];
    if (table.hasDensity && table.hasMass)
        throw core::InputError(
            fmt::format("{}: both a density and a mass column; give one of them", headerAt.str()));

    while (std::getline(in, text)) {
        ++lineNo;
        if (skipLine(text))
            continue;
        Place const at{key, fileName, lineNo};
        auto const fields = splitFields(text);
        if (fields.size() != header.size())
            throw core::InputError(fmt::format("{}: expected {} comma-separated fields (as in the "
                                               "header), got {}",
                                               at.str(), header.size(), fields.size()));
        CsvGrain g;
        g.line = lineNo;
        for (std::size_t c = 0; c < fields.size(); ++c) {
            auto const col = columnOf[c];
            auto const name = kColumnNames[static_cast<std::size_t>(col)];
            if (col == Column::Uid) {
                g.uid = parseCount(fields[c], at, c, name);
                continue;
            }
            if (col == Column::Type) {
                auto const t = parseCount(fields[c], at, c, name);
                if (t > std::numeric_limits<std::uint32_t>::max())
                    throw core::InputError(
                        fmt::format("{}, column {} (type): {} is too large", at.str(), c + 1, t));
                g.type = static_cast<std::uint32_t>(t);
                continue;
            }
            double const v = parseReal(fields[c], at, c, name);
            switch (col) {
            case Column::X:
                g.position.x() = v;
                break;
            case Column::Y:
                g.position.y() = v;
                break;
            case Column::Z:
                g.position.z() = v;
                break;
            case Column::Radius:
                g.radius = v;
                break;
            case Column::Vx:
                g.velocity.x() = v;
                break;
            case Column::Vy:
                g.velocity.y() = v;
                break;
            case Column::Vz:
                g.velocity.z() = v;
                break;
            case Column::Wx:
                g.angularVelocity.x() = v;
                break;
            case Column::Wy:
                g.angularVelocity.y() = v;
                break;
            case Column::Wz:
                g.angularVelocity.z() = v;
                break;
            case Column::Density:
                g.density = v;
                break;
            case Column::Mass:
                g.mass = v;
                break;
            case Column::Uid:
            case Column::Type:
            case Column::Count:
                break;
            }
        }
        table.grains.push_back(g);
    }
    if (in.bad())
        throw core::InputError(
            fmt::format("{}: reading '{}' failed after line {}", key, fileName, lineNo));
    return table;
}

CsvGrainTable readGrainCsv(std::string const& path, std::string const& key,
                           std::string const& resolvedFrom) {
    // Where a relative path was looked for: the scene file's folder, not the working directory.
    std::string const from =
        resolvedFrom.empty()
            ? std::string()
            : fmt::format(" (a relative path is taken from the scene file's folder '{}')",
                          resolvedFrom);
    std::string const why = core::whyNotRegularFile(path);
    if (why == "no such file")
        throw core::InputError(
            fmt::format("{}: cannot open '{}': no such file{}", key, path, from));
    if (!why.empty())
        throw core::InputError(
            fmt::format("{}: '{}' is {}, not a regular file (a CSV file)", key, path, why));
    std::ifstream in(path);
    if (!in)
        throw core::InputError(fmt::format("{}: cannot open '{}'{}", key, path, from));
    return parseGrainCsv(in, path, key);
}

} // namespace regolith::particles
