#pragma once
/// Contact parameters per pair of particle types (materials), symmetric in the pair.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace regolith::particles {

/// Throws core::InputError: material type `type` is not below `numTypes`.
[[noreturn]] void throwBadMaterialType(std::uint32_t type, std::size_t numTypes);

/// Range checks shared by the contact models, for the pair of types (a, b). Each throws
/// core::InputError "contact.<key> = <value> for material types (a, b): expected ..." when the
/// value is out of range.
struct MaterialCheck {
    std::uint32_t a;
    std::uint32_t b;
    void positive(char const* key, double value) const;    ///< finite and > 0
    void nonNegative(char const* key, double value) const; ///< finite and >= 0
    void restitution(double value) const;                  ///< in (0, 1]
    /// Model C's rolling spring: stiffness and damping ratio finite and >= 0, the stiffness at
    /// most `normalStiffness` if that is > 0 (a linear model's k_n): stiffer, the rolling
    /// oscillation (inertia 1 / (R_eff^2 ΣI⁻¹), at least 0.4 m_eff) would outrun the normal
    /// one, whose period sets the time step; up to k_n it is at most 1.6 times faster.
    void rollingSpring(double stiffness, double dampingRatio, double normalStiffness) const;
};

/// A symmetric `numTypes x numTypes` table of contact parameters `P`. Type indices are the
/// `type` of particles and walls.
template <class P>
class MaterialTable {
public:
    /// A table for `numTypes` types, every pair set to `initial`.
    explicit MaterialTable(std::size_t numTypes = 1, P const& initial = P{})
        : m_numTypes(numTypes)
        , m_params(numTypes * numTypes, initial) {}

    /// Sets the parameters of the pair (a, b) and (b, a). Throws core::InputError for a type
    /// index >= numTypes().
    void set(std::uint32_t a, std::uint32_t b, P const& p) {
        if (a >= m_numTypes || b >= m_numTypes)
            throwBadMaterialType(a >= m_numTypes ? a : b, m_numTypes);
        m_params[a * m_numTypes + b] = p;
        m_params[b * m_numTypes + a] = p;
    }
    /// Sets every pair.
    void setAll(P const& p) { m_params.assign(m_params.size(), p); }
    /// The parameters of the pair (a, b). Precondition: a, b < numTypes() (unchecked: hot).
    [[nodiscard]] P const& operator()(std::uint32_t a, std::uint32_t b) const {
        return m_params[a * m_numTypes + b];
    }
    [[nodiscard]] std::size_t numTypes() const { return m_numTypes; }
    /// Calls f(a, b, params) once per unordered pair a <= b.
    template <class F>
    void forEachPair(F&& f) const {
        for (std::uint32_t a = 0; a < m_numTypes; ++a)
            for (std::uint32_t b = a; b < m_numTypes; ++b)
                f(a, b, (*this)(a, b));
    }

private:
    std::size_t m_numTypes;
    std::vector<P> m_params;
};

} // namespace regolith::particles
