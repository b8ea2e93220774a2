#pragma once
/// The built-in per-grain quantities, listed once (kGrainQuantities). The list drives the
/// particle storage's state arrays (ParticleStorage), the synchronisation's full-state record
/// (creation, promotion, migration), the checkpoint's grain columns (written, read, hashed and
/// sent to their owners on restart), the VTK point arrays and the `--dump` columns, and it
/// reserves its names against grain fields of one's own (GrainFields.hpp). A new built-in
/// quantity is one line of the list plus its member in GrainRow; a field a program needs for
/// itself is declared at run time instead (declareGrainField).
///
/// Kept out of the list on purpose (docs/notes/grain-quantities.md):
/// - the synchronisation's structure, not state: owner block, periodic image, shadow holders
///   and the contact history (its own columns history_*), and the derived inverse mass and
///   inertia (ParticleStorage keeps them beside the list's arrays);
/// - the per-step update record (position, velocity, angular velocity, orientation, flags,
///   owner, history and grain fields: particles/sync/SyncMessages.cpp, UpdateList.cpp), which
///   sends the orientation only when the storage keeps any;
/// - the VTK arrays owner_rank and shadow, which describe a copy, not the grain
///   (kStructureColumns).
#include "core/math/Vec3.hpp"
#include "particles/storage/ParticleFlags.hpp"
#include "particles/storage/Uid.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

namespace regolith::particles {

/// One grain's built-in state as a row: the member of each kGrainQuantities entry the particle
/// storage keeps (what ParticleInit creates a grain from).
struct GrainRow {
    Uid uid = kInvalidUid;
    core::Vec3 position = core::Vec3::Zero();        ///< [length]
    core::Vec3 velocity = core::Vec3::Zero();        ///< [length/time]
    core::Vec3 angularVelocity = core::Vec3::Zero(); ///< world frame [rad/time]
    core::Quat orientation = core::Quat::Identity();
    core::Vec3 force = core::Vec3::Zero();  ///< of the last force computation [force]
    core::Vec3 torque = core::Vec3::Zero(); ///< of the last force computation [force length]
    double radius = 0.0;                    ///< [length]
    double mass = 0.0;                      ///< [mass]
    std::uint32_t type = 0; ///< material index into the contact model's MaterialTable
    Flags flags{};
};

/// The self-gravity's records of a grain (update_threshold > 0 or update_every): its position at
/// the last field update, the acceleration it got then, and the rate it is extrapolated at. NaN
/// if it has none. Kept by the self-gravity forces per uid, not by ParticleStorage; a checkpoint
/// carries them (io::GrainState).
struct GrainGravityRecord {
    core::Vec3 gravityReference = core::Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
    core::Vec3 gravityField = core::Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
    core::Vec3 gravitySlope = core::Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
};

/// The element type of a quantity's columns.
enum class GrainElement : std::uint8_t { F64, U64, U32, U8 };

/// How a value type is laid out as column elements (components per grain): a number as itself.
template <class T>
struct GrainValueLayout {
    static_assert(std::is_arithmetic_v<T>);
    using Element = T;
    static constexpr std::size_t components = 1;
    static void put(T v, Element* out) { out[0] = v; }
    static T get(Element const* in) { return in[0]; }
};
template <>
struct GrainValueLayout<Flags> {
    using Element = std::uint8_t;
    static constexpr std::size_t components = 1;
    static void put(Flags v, Element* out) { out[0] = v.bits(); }
    static Flags get(Element const* in) { return Flags::fromBits(in[0]); }
};
template <>
struct GrainValueLayout<core::Vec3> {
    using Element = double;
    static constexpr std::size_t components = 3;
    static void put(core::Vec3 const& v, Element* out) {
        out[0] = v.x();
        out[1] = v.y();
        out[2] = v.z();
    }
    static core::Vec3 get(Element const* in) { return {in[0], in[1], in[2]}; }
};
template <>
struct GrainValueLayout<core::Quat> { ///< (w, x, y, z)
    using Element = double;
    static constexpr std::size_t components = 4;
    static void put(core::Quat const& q, Element* out) {
        out[0] = q.w();
        out[1] = q.x();
        out[2] = q.y();
        out[3] = q.z();
    }
    static core::Quat get(Element const* in) { return {in[0], in[1], in[2], in[3]}; }
};

template <class E>
constexpr GrainElement grainElementOf() {
    if constexpr (std::is_same_v<E, double>)
        return GrainElement::F64;
    else if constexpr (std::is_same_v<E, std::uint64_t>)
        return GrainElement::U64;
    else if constexpr (std::is_same_v<E, std::uint32_t>)
        return GrainElement::U32;
    else
        return GrainElement::U8;
}

/// Where a quantity is written (bits of GrainQuantity::outputs).
enum GrainOutput : unsigned {
    kCheckpoint = 1U, ///< a checkpoint column (and restored from it)
    kVtk = 2U,        ///< a VTK point array (position is the points themselves)
    kDump = 4U,       ///< `--dump` columns (GrainQuantity::dumpColumns)
};

/// How ParticleStorage keeps a quantity.
enum class GrainStorage : std::uint8_t {
    PerCopy,    ///< one array element per copy
    WhenNeeded, ///< an array only once some copy needs it (the orientation: not the identity)
    Elsewhere,  ///< not in ParticleStorage (e.g. the self-gravity records, kept per uid)
};

/// One entry of kGrainQuantities: a quantity of type T, the member of Row holding it (GrainRow
/// for what the storage keeps, GrainGravityRecord for the self-gravity's records).
template <class T, class Row = GrainRow>
struct GrainQuantity {
    using Value = T;
    using Layout = GrainValueLayout<T>;
    std::string_view name;        ///< checkpoint dataset, VTK array, reserved grain-field name
    std::string_view unit;        ///< the checkpoint column's `units`
    std::string_view description; ///< the checkpoint column's `description`
    T Row::*row;
    GrainStorage storage = GrainStorage::PerCopy;
    unsigned outputs = kCheckpoint;
    std::string_view dumpColumns = {}; ///< the dump's column names, comma-separated

    static constexpr std::size_t components = Layout::components;
    static constexpr GrainElement element = grainElementOf<typename Layout::Element>();
};

/// The table. Order is the checkpoint's (its checksum hashes the columns in this order) and the
/// dump's; one line per quantity.
inline constexpr std::tuple kGrainQuantities{
    GrainQuantity<Uid>{"uid", "1", "unique grain id", &GrainRow::uid, GrainStorage::PerCopy,
                       kCheckpoint | kVtk | kDump, "uid"},
    GrainQuantity<core::Vec3>{
        "position", "length", "centre (x, y, z), wrapped into the domain on periodic axes",
        &GrainRow::position, GrainStorage::PerCopy, kCheckpoint | kDump, "x,y,z"},
    GrainQuantity<core::Vec3>{"velocity", "length/time", "velocity", &GrainRow::velocity,
                              GrainStorage::PerCopy, kCheckpoint | kVtk | kDump, "vx,vy,vz"},
    GrainQuantity<core::Vec3>{"angular_velocity", "rad/time", "angular velocity, world frame",
                              &GrainRow::angularVelocity, GrainStorage::PerCopy,
                              kCheckpoint | kVtk | kDump, "wx,wy,wz"},
    GrainQuantity<core::Quat>{"orientation", "1",
                              "orientation quaternion (w, x, y, z), body to world",
                              &GrainRow::orientation, GrainStorage::WhenNeeded},
    GrainQuantity<core::Vec3>{"force", "mass length/time^2",
                              "total force of the last force computation (contacts, walls, "
                              "self-gravity; not gravity.external)",
                              &GrainRow::force, GrainStorage::PerCopy, kCheckpoint | kVtk},
    GrainQuantity<core::Vec3>{"torque", "mass length^2/time^2",
                              "total torque of the last force computation", &GrainRow::torque},
    GrainQuantity<double>{"radius", "length", "radius", &GrainRow::radius, GrainStorage::PerCopy,
                          kCheckpoint | kVtk | kDump, "radius"},
    GrainQuantity<double>{"mass", "mass", "mass", &GrainRow::mass, GrainStorage::PerCopy,
                          kCheckpoint | kVtk | kDump, "mass"},
    GrainQuantity<std::uint32_t>{"type", "1", "material type ([[materials]] index)",
                                 &GrainRow::type},
    GrainQuantity<Flags>{"flags", "1", "state bits (particles::Flag: 2 = fixed)", &GrainRow::flags},
    GrainQuantity<core::Vec3, GrainGravityRecord>{
        "gravity_reference", "length",
        "position at the last self-gravity update (update_threshold > 0)",
        &GrainGravityRecord::gravityReference, GrainStorage::Elsewhere},
    GrainQuantity<core::Vec3, GrainGravityRecord>{"gravity_field", "length/time^2",
                                                  "self-gravity acceleration at the last update "
                                                  "(update_threshold > 0)",
                                                  &GrainGravityRecord::gravityField,
                                                  GrainStorage::Elsewhere},
    GrainQuantity<core::Vec3, GrainGravityRecord>{"gravity_slope", "length/time^3",
                                                  "rate the self-gravity field is extrapolated at "
                                                  "until the next update (gravity.update_every)",
                                                  &GrainGravityRecord::gravitySlope,
                                                  GrainStorage::Elsewhere},
};

inline constexpr std::size_t kGrainQuantityCount = std::tuple_size_v<decltype(kGrainQuantities)>;

/// Calls `f(std::integral_constant<std::size_t, K>{})` for every entry K of the table, in order
/// (a fold: no run-time loop; `kGrainQuantity<K>` is a constant expression in f).
template <class F>
constexpr void forEachGrainQuantity(F&& f) {
    [&]<std::size_t... K>(std::index_sequence<K...>) {
        (f(std::integral_constant<std::size_t, K>{}), ...);
    }
    (std::make_index_sequence<kGrainQuantityCount>{});
}

/// Entry K of the table, its value layout, and whether it is written to `output`.
template <std::size_t K>
inline constexpr auto const& kGrainQuantity = std::get<K>(kGrainQuantities);
template <std::size_t K>
using GrainLayoutOf = typename std::remove_cvref_t<decltype(kGrainQuantity<K>)>::Layout;
template <std::size_t K>
constexpr bool grainWrittenTo(GrainOutput output) {
    return (kGrainQuantity<K>.outputs & output) != 0;
}

/// One std::vector per entry of the table, of the entry's column element type (the columns of
/// many grains, component after component; entries an output skips stay empty).
template <class Table>
struct GrainColumnsOf;
template <class... Q>
struct GrainColumnsOf<std::tuple<Q...>> {
    using type = std::tuple<std::vector<typename Q::Layout::Element>...>;
};
using GrainElementColumns = GrainColumnsOf<std::remove_cv_t<decltype(kGrainQuantities)>>::type;

/// The place of the entry named `name` in the table (a compile error if there is none).
consteval std::size_t grainQuantityIndex(std::string_view name) {
    std::size_t found = kGrainQuantityCount;
    forEachGrainQuantity([&](auto k) {
        if (kGrainQuantity<k.value>.name == name)
            found = k.value;
    });
    if (found == kGrainQuantityCount)
        throw "no grain quantity of that name";
    return found;
}

/// The columns beside the table's that describe the structure, not the state: the contact
/// history's (checkpoint) and a copy's owner and role (VTK). Reserved names too.
inline constexpr std::array<std::string_view, 7> kStructureColumns{
    "history_offset", "history_count", "history_partner", "history_spring",
    "history_stamp",  "owner_rank",    "shadow"};

/// Is `name` a built-in column (the table's or kStructureColumns)?
[[nodiscard]] constexpr bool isBuiltInColumn(std::string_view name) {
    bool found = false;
    forEachGrainQuantity([&](auto k) { found = found || kGrainQuantity<k.value>.name == name; });
    for (std::string_view s : kStructureColumns)
        found = found || s == name;
    return found;
}

} // namespace regolith::particles
