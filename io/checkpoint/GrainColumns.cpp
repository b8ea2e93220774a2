#include "io/checkpoint/GrainColumns.hpp"

#include "core/Error.hpp"
#include "particles/storage/GrainFields.hpp"

#include <fmt/format.h>

namespace regolith::io::detail {

void GrainColumns::resize(std::size_t grains, std::size_t entries) {
    uid.resize(grains);
    for (auto* v : {&position, &velocity, &angularVelocity, &force, &torque, &gravityReference,
                    &gravityField, &gravitySlope})
        v->resize(3 * grains);
    orientation.resize(4 * grains);
    radius.resize(grains);
    mass.resize(grains);
    type.resize(grains);
    flags.resize(grains);
    historyOffset.resize(grains);
    historyCount.resize(grains);
    auto const declared = particles::grainFields();
    fields.resize(declared.size());
    for (std::size_t f = 0; f < declared.size(); ++f)
        fields[f].resize(static_cast<std::size_t>(declared[f].components) * grains);
    partner.resize(entries);
    spring.resize(3 * entries);
    stamp.resize(entries);
}

std::vector<ColumnView> columnViews(GrainColumns& c) {
    constexpr bool grain = false, history = true;
    constexpr char const* velocity = "length/time";
    std::vector<ColumnView> views{
        {"uid", ColumnType::U64, 1, c.uid.data(), grain, "1", "unique grain id"},
        {"position", ColumnType::F64, 3, c.position.data(), grain, "length",
         "centre (x, y, z), wrapped into the domain on periodic axes"},
        {"velocity", ColumnType::F64, 3, c.velocity.data(), grain, velocity, "velocity"},
        {"angular_velocity", ColumnType::F64, 3, c.angularVelocity.data(), grain, "rad/time",
         "angular velocity, world frame"},
        {"orientation", ColumnType::F64, 4, c.orientation.data(), grain, "1",
         "orientation quaternion (w, x, y, z), body to world"},
        {"force", ColumnType::F64, 3, c.force.data(), grain, "mass length/time^2",
         "total force of the last force computation (contacts, walls, self-gravity; not "
         "gravity.external)"},
        {"torque", ColumnType::F64, 3, c.torque.data(), grain, "mass length^2/time^2",
         "total torque of the last force computation"},
        {"radius", ColumnType::F64, 1, c.radius.data(), grain, "length", "radius"},
        {"mass", ColumnType::F64, 1, c.mass.data(), grain, "mass", "mass"},
        {"type", ColumnType::U32, 1, c.type.data(), grain, "1",
         "material type ([[materials]] index)"},
        {"flags", ColumnType::U8, 1, c.flags.data(), grain, "1",
         "state bits (particles::Flag: 2 = fixed)"},
        {"gravity_reference", ColumnType::F64, 3, c.gravityReference.data(), grain, "length",
         "position at the last self-gravity update (update_threshold > 0)"},
        {"gravity_field", ColumnType::F64, 3, c.gravityField.data(), grain, "length/time^2",
         "self-gravity acceleration at the last update (update_threshold > 0)"},
        {"gravity_slope", ColumnType::F64, 3, c.gravitySlope.data(), grain, "length/time^3",
         "rate the self-gravity field is extrapolated at until the next update "
         "(gravity.update_every)"},
        {"history_offset", ColumnType::U64, 1, c.historyOffset.data(), grain, "1",
         "first row of the grain's contact-history entries"},
        {"history_count", ColumnType::U32, 1, c.historyCount.data(), grain, "1",
         "number of the grain's contact-history entries"},
        {"history_partner", ColumnType::U64, 1, c.partner.data(), history, "1",
         "uid of the contact partner (a wall's: particles::wallUid)"},
        {"history_spring", ColumnType::F64, 3, c.spring.data(), history, "length",
         "tangential spring elongation"},
        {"history_stamp", ColumnType::U32, 1, c.stamp.data(), history, "1",
         "step the entry was last touched"},
    };
    // The grain fields of one's own, after the built-in columns, named as declared.
    auto const declared = particles::grainFields();
    for (std::size_t f = 0; f < declared.size() && f < c.fields.size(); ++f)
        views.push_back({declared[f].name.c_str(), ColumnType::F64,
                         static_cast<std::size_t>(declared[f].components), c.fields[f].data(),
                         grain, declared[f].unit.c_str(), declared[f].description.c_str()});
    return views;
}

namespace {

void put3(std::vector<double>& v, std::size_t row, core::Vec3 const& x) {
    for (std::size_t k = 0; k < 3; ++k)
        v[3 * row + k] = x[static_cast<Eigen::Index>(k)];
}

core::Vec3 get3(std::vector<double> const& v, std::size_t row) {
    return {v[3 * row], v[3 * row + 1], v[3 * row + 2]};
}

/// Row `row` of every grain-field column from `values` (declaration order; missing: 0).
void putFields(GrainColumns& c, std::size_t row, std::vector<double> const& values) {
    std::size_t k = 0;
    for (std::vector<double>& column : c.fields) {
        std::size_t const width = column.size() / c.uid.size();
        for (std::size_t j = 0; j < width; ++j, ++k)
            column[width * row + j] = k < values.size() ? values[k] : 0.0;
    }
}

std::vector<double> getFields(GrainColumns const& c, std::size_t row) {
    std::vector<double> values;
    for (std::vector<double> const& column : c.fields) {
        std::size_t const width = column.size() / c.uid.size();
        for (std::size_t j = 0; j < width; ++j)
            values.push_back(column[width * row + j]);
    }
    return values;
}

} // namespace

GrainColumns toColumns(std::span<GrainState const> grains, std::uint64_t historyBase) {
    std::size_t entries = 0;
    for (GrainState const& g : grains)
        entries += g.history.size();
    GrainColumns c;
    c.resize(grains.size(), entries);
    std::size_t e = 0;
    for (std::size_t i = 0; i < grains.size(); ++i) {
        GrainState const& g = grains[i];
        c.uid[i] = g.uid;
        put3(c.position, i, g.position);
        put3(c.velocity, i, g.velocity);
        put3(c.angularVelocity, i, g.angularVelocity);
        c.orientation[4 * i] = g.orientation.w();
        c.orientation[4 * i + 1] = g.orientation.x();
        c.orientation[4 * i + 2] = g.orientation.y();
        c.orientation[4 * i + 3] = g.orientation.z();
        put3(c.force, i, g.force);
        put3(c.torque, i, g.torque);
        c.radius[i] = g.radius;
        c.mass[i] = g.mass;
        c.type[i] = g.type;
        c.flags[i] = g.flags;
        put3(c.gravityReference, i, g.gravityReference);
        put3(c.gravityField, i, g.gravityField);
        put3(c.gravitySlope, i, g.gravitySlope);
        putFields(c, i, g.fields);
        c.historyOffset[i] = historyBase + e;
        c.historyCount[i] = static_cast<std::uint32_t>(g.history.size());
        for (particles::HistoryEntry const& h : g.history) {
            c.partner[e] = h.partner;
            put3(c.spring, e, h.spring);
            c.stamp[e] = h.stamp;
            ++e;
        }
    }
    return c;
}

std::vector<GrainState> fromColumns(GrainColumns const& c, std::uint64_t historyBase,
                                    std::string const& context) {
    std::vector<GrainState> out(c.uid.size());
    for (std::size_t i = 0; i < out.size(); ++i) {
        GrainState& g = out[i];
        g.uid = c.uid[i];
        g.position = get3(c.position, i);
        g.velocity = get3(c.velocity, i);
        g.angularVelocity = get3(c.angularVelocity, i);
        g.orientation = core::Quat(c.orientation[4 * i], c.orientation[4 * i + 1],
                                   c.orientation[4 * i + 2], c.orientation[4 * i + 3]);
        g.force = get3(c.force, i);
        g.torque = get3(c.torque, i);
        g.radius = c.radius[i];
        g.mass = c.mass[i];
        g.type = c.type[i];
        g.flags = c.flags[i];
        g.gravityReference = get3(c.gravityReference, i);
        g.gravityField = get3(c.gravityField, i);
        g.gravitySlope = get3(c.gravitySlope, i);
        g.fields = getFields(c, i);
        std::uint64_t const first = c.historyOffset[i];
        std::uint64_t const count = c.historyCount[i];
        if (first < historyBase || first - historyBase + count > c.partner.size())
            throw core::InputError(fmt::format(
                "{}: grain uid {} names history entries [{}, {}) outside the stored ones", context,
                g.uid, first, first + count));
        g.history.resize(count);
        for (std::uint64_t k = 0; k < count; ++k) {
            std::size_t const e = first - historyBase + k;
            g.history[k] = {c.partner[e], get3(c.spring, e), c.stamp[e]};
        }
    }
    return out;
}

} // namespace regolith::io::detail
