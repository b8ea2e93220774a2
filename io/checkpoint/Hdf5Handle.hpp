#pragma once
/// Internal to the HDF5 module (Hdf5Module.hpp): RAII ownership of HDF5 identifiers and the
/// checks of HDF5 return codes. Only the module's sources include hdf5.h.
#include <hdf5.h>

#include <string>
#include <utility>

namespace regolith::io::detail {

/// Owns one HDF5 identifier and closes it with the matching H5?close on destruction.
class H5Handle {
public:
    using Closer = herr_t (*)(hid_t);
    H5Handle() = default;
    H5Handle(hid_t id, Closer closer)
        : m_id(id)
        , m_closer(closer) {}
    ~H5Handle() { reset(); }
    H5Handle(H5Handle&& o) noexcept
        : m_id(std::exchange(o.m_id, H5I_INVALID_HID))
        , m_closer(o.m_closer) {}
    H5Handle& operator=(H5Handle&& o) noexcept {
        if (this != &o) {
            reset();
            m_id = std::exchange(o.m_id, H5I_INVALID_HID);
            m_closer = o.m_closer;
        }
        return *this;
    }
    H5Handle(H5Handle const&) = delete;
    H5Handle& operator=(H5Handle const&) = delete;

    [[nodiscard]] hid_t get() const { return m_id; }
    /// Closes now; returns false if HDF5 reported a failure (e.g. the final flush of a file).
    bool reset() {
        herr_t status = 0;
        if (m_id >= 0 && m_closer != nullptr)
            status = m_closer(m_id);
        m_id = H5I_INVALID_HID;
        return status >= 0;
    }

private:
    hid_t m_id = H5I_INVALID_HID;
    Closer m_closer = nullptr;
};

/// Turns off HDF5's printing of its error stack: Regolith reports errors itself, once.
void silenceHdf5Errors();

/// Throws core::InputError("<context>: <what> failed (<HDF5's innermost reason>[: strerror
/// (errno)])") if `status` < 0; clear errno before the HDF5 call that `status` comes from.
void h5check(herr_t status, std::string const& context, char const* what);
/// As h5check for a returned identifier; returns it wrapped in a handle closed by `closer`.
H5Handle h5own(hid_t id, H5Handle::Closer closer, std::string const& context, char const* what);

} // namespace regolith::io::detail
