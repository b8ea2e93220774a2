#pragma once
/// Contact laws of one's own, chosen at run time: a program derives a law from ContactLaw and
/// gives it to the time step as a CustomContact, one of the contact models DemStep takes
/// (AnyContactModel). The law sees what the built-in models see (ContactState: normal,
/// overlap, relative velocities, effective mass and radius, the two material types) and keeps
/// its tangential and rolling springs in the contact history the same way. One virtual call
/// per contact and step: a model type of one's own (AnyContactModel.hpp, registered by name
/// through ContactModelRegistry.hpp) is called directly, as the built-in ones are.
#include "particles/kernels/ContactState.hpp"

#include <cstdint>
#include <memory>

namespace regolith::particles {

class ContactLaw {
public:
    virtual ~ContactLaw() = default;

    /// The force and couple on j of one contact (i receives the opposite), as a ContactModel's
    /// call operator: `spring` and `rolling` are the contact's history entries, kept from
    /// step to step while the grains touch (zero when the contact starts).
    [[nodiscard]] virtual ContactResponse operator()(ContactState const& s, core::Vec3& spring,
                                                     core::Vec3& rolling, double dt) const = 0;
    /// Whether the law uses `rolling` at all (then every contact keeps a rolling entry).
    [[nodiscard]] virtual bool hasRollingSpring() const { return false; }
    /// The time scale a step must resolve for a contact of material types a and b with
    /// effective mass `effectiveMass` (for a linear spring pi sqrt(m / k)); the step is
    /// refused above a tenth of the shortest (TimeStepGuard) [time].
    [[nodiscard]] virtual double contactTime(std::uint32_t a, std::uint32_t b,
                                             double effectiveMass) const = 0;
};

/// A ContactLaw as a contact model (satisfies ContactModel). Copies share the law.
class CustomContact {
public:
    /// Throws core::Error if `law` is null.
    explicit CustomContact(std::shared_ptr<ContactLaw const> law);

    ContactResponse operator()(ContactState const& s, core::Vec3& spring, core::Vec3& rolling,
                               double dt) const {
        return (*m_law)(s, spring, rolling, dt);
    }
    [[nodiscard]] bool hasRollingSpring() const { return m_law->hasRollingSpring(); }
    [[nodiscard]] ContactLaw const& law() const { return *m_law; }

private:
    std::shared_ptr<ContactLaw const> m_law;
};

static_assert(ContactModel<CustomContact>);

} // namespace regolith::particles
