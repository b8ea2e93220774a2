#include "io/vtk/VtkPieces.hpp"

#include "core/Error.hpp"
#include "particles/storage/GrainFields.hpp"
#include "particles/storage/GrainQuantities.hpp"

#include <fmt/format.h>

#include <cstdint>

namespace regolith::io::detail {

namespace {

using particles::GrainLayoutOf;
using particles::kGrainQuantity;

template <std::size_t K>
constexpr bool kInVtk = particles::grainWrittenTo<K>(particles::kVtk);

constexpr char const* vtkType(particles::GrainElement e) {
    switch (e) {
    case particles::GrainElement::F64:
        return "Float64";
    case particles::GrainElement::U64:
        return "UInt64";
    case particles::GrainElement::U32:
        return "UInt32";
    case particles::GrainElement::U8:
        break;
    }
    return "UInt8";
}

} // namespace

std::vector<ArraySpec> particleArrays(bool shadows) {
    std::vector<ArraySpec> a;
    particles::forEachGrainQuantity([&](auto k) {
        constexpr auto const& q = kGrainQuantity<k.value>;
        if constexpr (kInVtk<k.value>)
            a.push_back({std::string(q.name), vtkType(q.element), static_cast<int>(q.components)});
    });
    a.push_back({"owner_rank", "Int32", 1});
    if (shadows)
        a.push_back({"shadow", "UInt8", 1});
    for (particles::GrainField const& f : particles::grainFields()) // of one's own
        a.push_back({f.name, "Float64", f.components});
    return a;
}

std::vector<ArraySpec> blockArrays() {
    return {{"block_id", "UInt64", 1},
            {"owner_rank", "Int32", 1},
            {"level", "Int32", 1},
            {"grains", "Int64", 1}};
}

namespace {

void append(std::vector<double>& to, core::Vec3 const& v) {
    to.insert(to.end(), {v.x(), v.y(), v.z()});
}

void check(bool written, std::string const& path) {
    if (!written)
        throw core::Error(fmt::format("cannot write VTK file '{}'", path));
}

} // namespace

void writeParticlePiece(std::string const& path, particles::LocalParticles const& local,
                        bool shadows) {
    std::size_t n = 0;
    for (particles::BlockParticles const& bp : local.blocks())
        n += shadows ? bp.particles.size() : bp.particles.countMasters();
    // Columns in particleArrays() order: the table's, owner_rank, shadow, the grain fields.
    std::vector<double> xyz;
    particles::GrainElementColumns quantities; // the entries written to VTK
    std::vector<std::int32_t> owner;
    std::vector<std::uint8_t> shadow;
    auto const fields = particles::grainFields();
    std::vector<std::vector<double>> fieldValues(fields.size());
    xyz.reserve(3 * n);
    particles::forEachGrainQuantity([&](auto k) {
        if constexpr (kInVtk<k.value>)
            std::get<k.value>(quantities).reserve(kGrainQuantity<k.value>.components * n);
    });
    owner.reserve(n);
    shadow.reserve(n);
    for (particles::BlockParticles const& bp : local.blocks()) {
        particles::ParticleStorage const& ps = bp.particles;
        ps.forEach([&](std::size_t i) {
            bool const isShadow = ps.flags(i).isShadow();
            if (isShadow && !shadows)
                return;
            append(xyz, ps.position(i));
            particles::forEachGrainQuantity([&](auto k) {
                if constexpr (kInVtk<k.value>) {
                    auto& column = std::get<k.value>(quantities);
                    column.resize(column.size() + kGrainQuantity<k.value>.components);
                    GrainLayoutOf<k.value>::put(ps.value<k.value>(i),
                                                column.data() + column.size() -
                                                    kGrainQuantity<k.value>.components);
                }
            });
            owner.push_back(ps.owner(i).rank);
            shadow.push_back(isShadow ? 1 : 0);
            for (std::size_t f = 0; f < fields.size(); ++f) {
                particles::GrainFieldId const id = particles::grainFieldId(f);
                for (std::size_t c = 0; c < id.components; ++c)
                    fieldValues[f].push_back(
                        ps.fieldComponents() > id.offset + c ? ps.field(id, i, c) : 0.0);
            }
        });
    }
    std::vector<ArraySpec> const specs = particleArrays(shadows);
    std::vector<void const*> values;
    particles::forEachGrainQuantity([&](auto k) {
        if constexpr (kInVtk<k.value>)
            values.push_back(std::get<k.value>(quantities).data());
    });
    values.push_back(owner.data());
    if (shadows)
        values.push_back(shadow.data());
    for (std::vector<double> const& f : fieldValues)
        values.push_back(f.data());
    std::vector<vtkxml::Column> columns;
    for (std::size_t k = 0; k < specs.size(); ++k)
        columns.push_back({specs[k], values[k]});
    check(vtkxml::module().writeVertices(path, owner.size(), xyz.data(), columns), path);
}

void writeBlockPiece(std::string const& path, particles::LocalParticles const& local) {
    std::vector<double> bounds;
    std::vector<std::uint64_t> id;
    std::vector<std::int32_t> owner, level;
    std::vector<std::int64_t> grains;
    auto const blocks = local.blocks();
    for (std::size_t b = 0; b < blocks.size(); ++b) {
        // The forest's blocks, also where the particles' subdomains merge several.
        auto const load = local.loadPerLeaf(b);
        auto const& leaves = blocks[b].block->leaves;
        for (std::size_t l = 0; l < leaves.size(); ++l) {
            append(bounds, leaves[l].aabb.min);
            append(bounds, leaves[l].aabb.max);
            id.push_back(leaves[l].id.raw());
            owner.push_back(blocks[b].block->owner);
            level.push_back(leaves[l].id.level());
            grains.push_back(static_cast<std::int64_t>(load[l].grains));
        }
    }
    std::vector<ArraySpec> const specs = blockArrays();
    std::vector<vtkxml::Column> const columns{{specs[0], id.data()},
                                              {specs[1], owner.data()},
                                              {specs[2], level.data()},
                                              {specs[3], grains.data()}};
    check(vtkxml::module().writeBoxes(path, id.size(), bounds.data(), columns), path);
}

namespace {

std::string declare(std::vector<ArraySpec> const& arrays) {
    std::string out;
    for (ArraySpec const& a : arrays)
        out +=
            fmt::format("      <PDataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\"/>\n",
                        a.type, a.name, a.components);
    return out;
}

} // namespace

std::string pvtuText(std::vector<ArraySpec> const& pointArrays,
                     std::vector<ArraySpec> const& cellArrays,
                     std::vector<std::string> const& pieces) {
    std::string out = "<?xml version=\"1.0\"?>\n"
                      "<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\" "
                      "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
                      "  <PUnstructuredGrid GhostLevel=\"0\">\n";
    out += "    <PPointData>\n" + declare(pointArrays) + "    </PPointData>\n";
    out += "    <PCellData>\n" + declare(cellArrays) + "    </PCellData>\n";
    out += "    <PPoints>\n      <PDataArray type=\"Float64\" NumberOfComponents=\"3\"/>\n"
           "    </PPoints>\n";
    for (std::string const& p : pieces)
        out += fmt::format("    <Piece Source=\"{}\"/>\n", p);
    out += "  </PUnstructuredGrid>\n</VTKFile>\n";
    return out;
}

} // namespace regolith::io::detail
