#include "particles/kernels/ContactLaw.hpp"

#include "core/Error.hpp"

#include <utility>

namespace regolith::particles {

CustomContact::CustomContact(std::shared_ptr<ContactLaw const> law)
    : m_law(std::move(law)) {
    if (!m_law)
        throw core::Error("CustomContact: no contact law");
}

} // namespace regolith::particles
