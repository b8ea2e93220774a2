#include "io/checkpoint/Hdf5Attributes.hpp"

#include "core/Error.hpp"
#include "io/checkpoint/Hdf5Handle.hpp"

#include <array>
#include <vector>

namespace regolith::io::detail {

hid_t fileType(ColumnType t) {
    switch (t) {
    case ColumnType::U64:
        return H5T_STD_U64LE;
    case ColumnType::U32:
        return H5T_STD_U32LE;
    case ColumnType::U8:
        return H5T_STD_U8LE;
    case ColumnType::F64:
        return H5T_IEEE_F64LE;
    }
    return H5I_INVALID_HID;
}

hid_t memoryType(ColumnType t) {
    switch (t) {
    case ColumnType::U64:
        return H5T_NATIVE_UINT64;
    case ColumnType::U32:
        return H5T_NATIVE_UINT32;
    case ColumnType::U8:
        return H5T_NATIVE_UINT8;
    case ColumnType::F64:
        return H5T_NATIVE_DOUBLE;
    }
    return H5I_INVALID_HID;
}

namespace {

void writeAttr(hid_t file, char const* name, hid_t fileT, hid_t memT, hsize_t n, void const* data,
               std::string const& context) {
    H5Handle const space =
        h5own(H5Screate_simple(1, &n, nullptr), H5Sclose, context, "H5Screate_simple");
    H5Handle const attr =
        h5own(H5Acreate2(file, name, fileT, space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
              context, name);
    h5check(H5Awrite(attr.get(), memT, data), context, name);
}

void writeText(hid_t file, char const* name, std::string const& text, std::string const& context) {
    // A fixed-size string of the text's length plus its terminating NUL (HDF5 refuses size 0).
    H5Handle const type = h5own(H5Tcopy(H5T_C_S1), H5Tclose, context, "H5Tcopy");
    h5check(H5Tset_size(type.get(), text.size() + 1), context, "H5Tset_size");
    H5Handle const space = h5own(H5Screate(H5S_SCALAR), H5Sclose, context, "H5Screate");
    H5Handle const attr =
        h5own(H5Acreate2(file, name, type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
              context, name);
    h5check(H5Awrite(attr.get(), type.get(), text.c_str()), context, name);
}

} // namespace

void writeTextAttribute(hid_t object, char const* name, std::string const& text,
                        std::string const& context) {
    writeText(object, name, text, context);
}

namespace {

/// Why a required attribute may be absent: the file is an HDF5 file, but another program's,
/// or its metadata is damaged (one flipped byte there hides attributes).
constexpr char const* kNotACheckpoint = " (not a Regolith checkpoint, or a damaged one)";

/// Reads `n` values of attribute `name`, which must hold exactly `n`.
void readAttr(hid_t file, char const* name, hid_t memT, hsize_t n, void* data,
              std::string const& context) {
    std::string const what = std::string("attribute '") + name + "'";
    if (H5Aexists(file, name) <= 0)
        throw core::InputError(context + ": " + what + " is missing" + kNotACheckpoint);
    H5Handle const attr = h5own(H5Aopen(file, name, H5P_DEFAULT), H5Aclose, context, what.c_str());
    H5Handle const space = h5own(H5Aget_space(attr.get()), H5Sclose, context, what.c_str());
    if (H5Sget_simple_extent_npoints(space.get()) != static_cast<hssize_t>(n))
        throw core::InputError(context + ": " + what + " has the wrong size");
    h5check(H5Aread(attr.get(), memT, data), context, what.c_str());
}

std::string readText(hid_t file, char const* name, std::string const& context) {
    std::string const what = std::string("attribute '") + name + "'";
    if (H5Aexists(file, name) <= 0)
        throw core::InputError(context + ": " + what + " is missing" + kNotACheckpoint);
    H5Handle const attr = h5own(H5Aopen(file, name, H5P_DEFAULT), H5Aclose, context, what.c_str());
    H5Handle const type = h5own(H5Aget_type(attr.get()), H5Tclose, context, what.c_str());
    if (H5Tget_class(type.get()) != H5T_STRING || H5Tis_variable_str(type.get()) != 0)
        throw core::InputError(context + ": " + what + " is not a fixed-size string");
    std::size_t const size = H5Tget_size(type.get());
    std::vector<char> buffer(size + 1, '\0');
    h5check(H5Aread(attr.get(), type.get(), buffer.data()), context, what.c_str());
    return std::string(buffer.data());
}

} // namespace

void writeInfoAttributes(hid_t file, CheckpointInfo const& info, std::uint64_t checksum,
                         std::string const& context) {
    auto const i64 = [&](char const* name, std::int64_t v) {
        writeAttr(file, name, H5T_STD_I64LE, H5T_NATIVE_INT64, 1, &v, context);
    };
    auto const u64 = [&](char const* name, std::uint64_t v) {
        writeAttr(file, name, H5T_STD_U64LE, H5T_NATIVE_UINT64, 1, &v, context);
    };
    auto const f64 = [&](char const* name, double const* v, hsize_t n) {
        writeAttr(file, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, n, v, context);
    };
    i64("format_version", info.formatVersion);
    i64("step", info.step);
    f64("time", &info.time, 1);
    f64("dt", &info.dt, 1);
    f64("domain_min", info.domain.min.data(), 3);
    f64("domain_max", info.domain.max.data(), 3);
    std::array<std::uint8_t, 3> const periodic{info.periodic[0], info.periodic[1],
                                               info.periodic[2]};
    writeAttr(file, "periodic", H5T_STD_U8LE, H5T_NATIVE_UINT8, 3, periodic.data(), context);
    writeText(file, "scene", info.scene, context);
    writeText(file, "state_checksum", info.stateChecksum, context);
    u64("grain_count", info.grainCount);
    u64("history_count", info.historyCount);
    i64("gravity_updates", info.gravityUpdates);
    f64("gravity_potential_energy", &info.gravityPotentialEnergy, 1);
    i64("gravity_since_update", info.gravitySinceUpdate);
    i64("gravity_interval", info.gravityInterval);
    u64("checksum", checksum);
}

std::int64_t readFormatVersion(hid_t file, std::string const& context) {
    std::int64_t v = 0;
    readAttr(file, "format_version", H5T_NATIVE_INT64, 1, &v, context);
    return v;
}

CheckpointInfo readInfoAttributes(hid_t file, std::uint64_t& checksum, std::string const& context) {
    CheckpointInfo info;
    readAttr(file, "format_version", H5T_NATIVE_INT64, 1, &info.formatVersion, context);
    readAttr(file, "step", H5T_NATIVE_INT64, 1, &info.step, context);
    readAttr(file, "time", H5T_NATIVE_DOUBLE, 1, &info.time, context);
    readAttr(file, "dt", H5T_NATIVE_DOUBLE, 1, &info.dt, context);
    readAttr(file, "domain_min", H5T_NATIVE_DOUBLE, 3, info.domain.min.data(), context);
    readAttr(file, "domain_max", H5T_NATIVE_DOUBLE, 3, info.domain.max.data(), context);
    std::array<std::uint8_t, 3> periodic{};
    readAttr(file, "periodic", H5T_NATIVE_UINT8, 3, periodic.data(), context);
    for (std::size_t k = 0; k < 3; ++k)
        info.periodic[k] = periodic[k] != 0;
    info.scene = readText(file, "scene", context);
    info.stateChecksum = readText(file, "state_checksum", context);
    readAttr(file, "grain_count", H5T_NATIVE_UINT64, 1, &info.grainCount, context);
    readAttr(file, "history_count", H5T_NATIVE_UINT64, 1, &info.historyCount, context);
    readAttr(file, "gravity_updates", H5T_NATIVE_INT64, 1, &info.gravityUpdates, context);
    readAttr(file, "gravity_potential_energy", H5T_NATIVE_DOUBLE, 1, &info.gravityPotentialEnergy,
             context);
    readAttr(file, "gravity_since_update", H5T_NATIVE_INT64, 1, &info.gravitySinceUpdate, context);
    readAttr(file, "gravity_interval", H5T_NATIVE_INT64, 1, &info.gravityInterval, context);
    readAttr(file, "checksum", H5T_NATIVE_UINT64, 1, &checksum, context);
    return info;
}

} // namespace regolith::io::detail
