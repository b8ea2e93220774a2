#include "io/checkpoint/Hdf5Handle.hpp"

#include "core/Error.hpp"

#include <cerrno>
#include <cstring>

namespace regolith::io::detail {

void silenceHdf5Errors() {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

namespace {

/// The description of the innermost error on HDF5's default error stack (where the operating
/// system's or MPI-IO's reason ends up, e.g. "... errno = 28, error message = 'No space left
/// on device'"), or "".
std::string innermostError() {
    std::string out;
    auto const keepFirst = [](unsigned n, H5E_error2_t const* e, void* into) -> herr_t {
        if (n == 0 && e->desc != nullptr)
            *static_cast<std::string*>(into) = e->desc;
        return 0;
    };
    H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, keepFirst, &out);
    constexpr std::size_t kLongest = 300;
    if (out.size() > kLongest)
        out = out.substr(0, kLongest) + "...";
    return out;
}

[[noreturn]] void fail(std::string const& context, char const* what) {
    // The operating system's reason, which HDF5's stack does not carry (the callers clear
    // errno before their HDF5 calls, so that it is not a stale one).
    int const error = errno;
    std::string why = innermostError();
    if (error != 0)
        why += (why.empty() ? "" : ": ") + std::string(std::strerror(error));
    throw core::InputError(context + ": " + what + " failed" +
                           (why.empty() ? "" : " (" + why + ")"));
}

} // namespace

void h5check(herr_t status, std::string const& context, char const* what) {
    if (status < 0)
        fail(context, what);
}

H5Handle h5own(hid_t id, H5Handle::Closer closer, std::string const& context, char const* what) {
    if (id < 0)
        fail(context, what);
    return H5Handle(id, closer);
}

} // namespace regolith::io::detail
