#include "io/checkpoint/Hdf5Handle.hpp"

#include "core/Error.hpp"

namespace regolith::io::detail {

void silenceHdf5Errors() {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

void h5check(herr_t status, std::string const& context, char const* what) {
    if (status < 0)
        throw core::InputError(context + ": " + what + " failed");
}

H5Handle h5own(hid_t id, H5Handle::Closer closer, std::string const& context, char const* what) {
    if (id < 0)
        throw core::InputError(context + ": " + what + " failed");
    return H5Handle(id, closer);
}

} // namespace regolith::io::detail
