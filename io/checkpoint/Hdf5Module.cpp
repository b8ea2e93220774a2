// The HDF5 side of the checkpoints (Hdf5Module.hpp), built as the shared module
// libregolith_hdf5.so.
#include "io/checkpoint/Hdf5Module.hpp"

#include "core/Error.hpp"
#include "io/checkpoint/Hdf5Attributes.hpp"
#include "io/checkpoint/Hdf5Handle.hpp"

#include <fmt/format.h>

#include <array>
#include <cerrno>
#include <cstdlib>

namespace regolith::io::detail {

namespace {

/// One dataset, written collectively: every rank its rows (none is fine).
void writeColumn(hid_t file, hid_t dxpl, ColumnView const& col, Slab const& slab,
                 std::string const& context) {
    int const rank = col.width > 1 ? 2 : 1;
    std::array<hsize_t, 2> const dims{slab.global, col.width};
    std::array<hsize_t, 2> const start{slab.offset, 0};
    std::array<hsize_t, 2> const count{slab.local, col.width};
    H5Handle const fileSpace =
        h5own(H5Screate_simple(rank, dims.data(), nullptr), H5Sclose, context, "H5Screate");
    H5Handle const set = h5own(H5Dcreate2(file, col.name, fileType(col.type), fileSpace.get(),
                                          H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                               H5Dclose, context, col.name);
    writeTextAttribute(set.get(), "units", col.units, context);
    writeTextAttribute(set.get(), "description", col.description, context);
    if (slab.global == 0)
        return; // nothing to write anywhere: every rank skips alike
    H5Handle const memSpace =
        h5own(H5Screate_simple(rank, count.data(), nullptr), H5Sclose, context, "H5Screate");
    if (slab.local > 0) {
        h5check(H5Sselect_hyperslab(fileSpace.get(), H5S_SELECT_SET, start.data(), nullptr,
                                    count.data(), nullptr),
                context, "H5Sselect_hyperslab");
    } else {
        h5check(H5Sselect_none(fileSpace.get()), context, "H5Sselect_none");
        h5check(H5Sselect_none(memSpace.get()), context, "H5Sselect_none");
    }
    // A rank without rows still joins the collective write; HDF5 wants a buffer anyway.
    static double const kNothing = 0.0;
    void const* data = col.data != nullptr ? col.data : &kNothing;
    h5check(H5Dwrite(set.get(), memoryType(col.type), memSpace.get(), fileSpace.get(), dxpl, data),
            context, col.name);
}

/// core::Comm::allTrue on a raw communicator: the module links no static Regolith library.
bool allTrue(MPI_Comm comm, bool mine) {
    int local = mine ? 1 : 0;
    int all = 0;
    if (MPI_Allreduce(&local, &all, 1, MPI_INT, MPI_LAND, comm) != MPI_SUCCESS)
        throw core::Error("MPI_Allreduce failed");
    return all != 0;
}

/// The message of the lowest rank whose `mine` is not empty, on every rank ("" if none).
/// COLLECTIVE.
std::string agreeOnFailure(MPI_Comm comm, std::string const& mine) {
    int rank = 0, size = 0;
    MPI_Comm_rank(comm, &rank);
    MPI_Comm_size(comm, &size);
    int first = mine.empty() ? size : rank;
    if (MPI_Allreduce(MPI_IN_PLACE, &first, 1, MPI_INT, MPI_MIN, comm) != MPI_SUCCESS)
        throw core::Error("MPI_Allreduce failed");
    if (first == size)
        return {};
    std::string message = rank == first ? mine : std::string();
    unsigned long length = message.size();
    MPI_Bcast(&length, 1, MPI_UNSIGNED_LONG, first, comm);
    message.resize(length);
    MPI_Bcast(message.data(), static_cast<int>(length), MPI_CHAR, first, comm);
    return message;
}

class Hdf5File final : public CheckpointFile {
public:
    Hdf5File(H5Handle file, std::string context)
        : m_file(std::move(file))
        , m_context(std::move(context)) {}

    // errno cleared before HDF5 calls whose failure reports it (Hdf5Handle.cpp's fail()).
    std::int64_t formatVersion() override {
        errno = 0;
        return readFormatVersion(m_file.get(), m_context);
    }

    CheckpointInfo info(std::uint64_t& checksum) override {
        errno = 0;
        return readInfoAttributes(m_file.get(), checksum, m_context);
    }

    void readColumn(ColumnView const& col, std::uint64_t globalRows, std::uint64_t first,
                    std::uint64_t rows) override {
        errno = 0;
        std::string const what = std::string("dataset '") + col.name + "'";
        hid_t const file = m_file.get();
        if (H5Lexists(file, col.name, H5P_DEFAULT) <= 0)
            throw core::InputError(m_context + ": " + what + " is missing");
        H5Handle const set =
            h5own(H5Dopen2(file, col.name, H5P_DEFAULT), H5Dclose, m_context, what.c_str());
        H5Handle const fileSpace =
            h5own(H5Dget_space(set.get()), H5Sclose, m_context, what.c_str());
        int const rank = col.width > 1 ? 2 : 1;
        std::array<hsize_t, 2> dims{0, 0};
        if (H5Sget_simple_extent_ndims(fileSpace.get()) != rank ||
            H5Sget_simple_extent_dims(fileSpace.get(), dims.data(), nullptr) != rank ||
            dims[0] != globalRows || (rank == 2 && dims[1] != col.width))
            throw core::InputError(fmt::format("{}: {} has the wrong shape (expected {} x {})",
                                               m_context, what, globalRows, col.width));
        if (rows == 0)
            return;
        std::array<hsize_t, 2> const start{first, 0};
        std::array<hsize_t, 2> const count{rows, col.width};
        h5check(H5Sselect_hyperslab(fileSpace.get(), H5S_SELECT_SET, start.data(), nullptr,
                                    count.data(), nullptr),
                m_context, "H5Sselect_hyperslab");
        H5Handle const memSpace =
            h5own(H5Screate_simple(rank, count.data(), nullptr), H5Sclose, m_context, "H5Screate");
        h5check(H5Dread(set.get(), memoryType(col.type), memSpace.get(), fileSpace.get(),
                        H5P_DEFAULT, col.data),
                m_context, what.c_str());
    }

private:
    H5Handle m_file;
    std::string m_context;
};

class Hdf5ModuleImpl final : public Hdf5Module {
public:
    void write(MPI_Comm comm, std::string const& path, CheckpointContent const& content,
               std::string const& context, CheckpointFaults faults) override {
        H5Handle const fapl = h5own(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, context, "H5Pcreate");
        h5check(H5Pset_fapl_mpio(fapl.get(), comm, MPI_INFO_NULL), context, "H5Pset_fapl_mpio");
        // The root's attributes in dense storage (file format 1.8 on): the scene text is one,
        // and an attribute in the object header cannot exceed 64 KiB (a scene listing a few
        // thousand grains does).
        h5check(H5Pset_libver_bounds(fapl.get(), H5F_LIBVER_V18, H5F_LIBVER_LATEST), context,
                "H5Pset_libver_bounds");
        H5Handle const fcpl = h5own(H5Pcreate(H5P_FILE_CREATE), H5Pclose, context, "H5Pcreate");
        h5check(H5Pset_attr_phase_change(fcpl.get(), 0, 0), context, "H5Pset_attr_phase_change");
        hid_t const created = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, fcpl.get(), fapl.get());
        if (!allTrue(comm, created >= 0)) {
            if (created >= 0)
                H5Fclose(created);
            throw core::InputError(
                fmt::format("{}: cannot create '{}' (does the directory exist and is it writable?)",
                            context, path));
        }
        H5Handle file(created, H5Fclose);
        int rank = 0;
        MPI_Comm_rank(comm, &rank);
        // Each step may fail on some ranks only (an I/O error, a full disk): the ranks agree
        // after it, so that none goes on into the next collective call alone.
        auto agreed = [&](auto&& step) {
            std::string failure;
            errno = 0; // fail() (Hdf5Handle.cpp) reports it
            try {
                step();
            } catch (core::Error const& e) {
                failure = e.what();
            }
            failure = agreeOnFailure(comm, failure);
            if (failure.empty())
                return;
            (void)file.reset(); // collective, on every rank alike
            throw core::InputError(failure);
        };
        H5Handle dxpl;
        agreed([&] {
            dxpl = h5own(H5Pcreate(H5P_DATASET_XFER), H5Pclose, context, "H5Pcreate");
            h5check(H5Pset_dxpl_mpio(dxpl.get(), H5FD_MPIO_COLLECTIVE), context,
                    "H5Pset_dxpl_mpio");
        });
        std::vector<ColumnView> const& views = *content.columns;
        for (std::size_t k = 0; k < views.size(); ++k) {
            agreed([&] {
                writeColumn(file.get(), dxpl.get(), views[k],
                            views[k].history ? content.entries : content.grains, context);
                if (k == views.size() / 2 && rank == faults.failingRank)
                    throw core::Error(
                        fmt::format("{}: {} failed (REGOLITH_TEST_FAIL_IN_CHECKPOINT)", context,
                                    views[k].name));
            });
            if (k == views.size() / 2 && faults.abortMidway) {
                H5Fflush(file.get(), H5F_SCOPE_GLOBAL);
                std::_Exit(86);
            }
        }
        agreed([&] {
            writeInfoAttributes(file.get(), *content.info, content.checksum, context);
            h5check(H5Fflush(file.get(), H5F_SCOPE_GLOBAL), context, "H5Fflush");
        });
        bool const closed = file.reset();
        std::string const failure =
            agreeOnFailure(comm, closed ? "" : context + ": closing '" + path + "' failed");
        if (!failure.empty())
            throw core::InputError(failure);
    }

    std::unique_ptr<CheckpointFile> open(std::string const& path,
                                         std::string const& context) override {
        errno = 0;
        if (H5Fis_hdf5(path.c_str()) <= 0)
            throw core::InputError(context + ": not an HDF5 file (truncated or damaged?)");
        hid_t const opened = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
        if (opened < 0)
            throw core::InputError(context + ": HDF5 cannot open it (truncated or damaged file)");
        return std::make_unique<Hdf5File>(H5Handle(opened, H5Fclose), context);
    }
};

} // namespace

} // namespace regolith::io::detail

extern "C" regolith::io::detail::Hdf5Module* regolith_hdf5_module() {
    // HDF5 would print its error stack on every failing rank; Regolith reports once.
    regolith::io::detail::silenceHdf5Errors();
    static regolith::io::detail::Hdf5ModuleImpl instance;
    return &instance;
}
