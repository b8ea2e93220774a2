#include "io/checkpoint/GrainColumns.hpp"

#include "core/Error.hpp"
#include "particles/storage/GrainFields.hpp"

#include <fmt/format.h>

namespace regolith::io::detail {

namespace {

using particles::GrainLayoutOf;
using particles::kGrainQuantity;

template <std::size_t K>
constexpr bool kInCheckpoint = particles::grainWrittenTo<K>(particles::kCheckpoint);

constexpr ColumnType columnType(particles::GrainElement e) {
    switch (e) {
    case particles::GrainElement::F64:
        return ColumnType::F64;
    case particles::GrainElement::U64:
        return ColumnType::U64;
    case particles::GrainElement::U32:
        return ColumnType::U32;
    case particles::GrainElement::U8:
        break;
    }
    return ColumnType::U8;
}

} // namespace

void GrainColumns::resize(std::size_t rows, std::size_t entries) {
    grains = rows;
    particles::forEachGrainQuantity([&](auto k) {
        if constexpr (kInCheckpoint<k.value>)
            std::get<k.value>(quantities).resize(kGrainQuantity<k.value>.components * rows);
    });
    historyOffset.resize(rows);
    historyCount.resize(rows);
    auto const declared = particles::grainFields();
    fields.resize(declared.size());
    for (std::size_t f = 0; f < declared.size(); ++f)
        fields[f].resize(static_cast<std::size_t>(declared[f].components) * rows);
    partner.resize(entries);
    spring.resize(3 * entries);
    stamp.resize(entries);
}

std::vector<ColumnView> columnViews(GrainColumns& c) {
    constexpr bool grain = false, history = true;
    std::vector<ColumnView> views;
    particles::forEachGrainQuantity([&](auto k) {
        constexpr auto const& q = kGrainQuantity<k.value>;
        if constexpr (kInCheckpoint<k.value>)
            views.push_back({q.name.data(), columnType(q.element), q.components,
                             std::get<k.value>(c.quantities).data(), grain, q.unit.data(),
                             q.description.data()});
    });
    views.insert(views.end(),
                 {
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
                 });
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
        std::size_t const width = column.size() / c.grains;
        for (std::size_t j = 0; j < width; ++j, ++k)
            column[width * row + j] = k < values.size() ? values[k] : 0.0;
    }
}

std::vector<double> getFields(GrainColumns const& c, std::size_t row) {
    std::vector<double> values;
    for (std::vector<double> const& column : c.fields) {
        std::size_t const width = column.size() / c.grains;
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
        particles::forEachGrainQuantity([&](auto k) {
            constexpr auto const& q = kGrainQuantity<k.value>;
            if constexpr (kInCheckpoint<k.value>)
                GrainLayoutOf<k.value>::put(g.*q.row, std::get<k.value>(c.quantities).data() +
                                                          q.components * i);
        });
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
    std::vector<GrainState> out(c.grains);
    for (std::size_t i = 0; i < out.size(); ++i) {
        GrainState& g = out[i];
        particles::forEachGrainQuantity([&](auto k) {
            constexpr auto const& q = kGrainQuantity<k.value>;
            if constexpr (kInCheckpoint<k.value>)
                g.*q.row = GrainLayoutOf<k.value>::get(std::get<k.value>(c.quantities).data() +
                                                       q.components * i);
        });
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
