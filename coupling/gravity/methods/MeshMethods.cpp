// gravity.self = "pm" and "p3m": the particle-mesh method on the blocks' grid (deposit, Poisson
// solve, interpolate; gravity/GridGravity), alone or with P3M's short-range pair correction
// (P3mGravity.hpp).
#include "coupling/gravity/GravityMethod.hpp"
#include "coupling/gravity/P3mGravity.hpp"
#include "gravity/GridGravity.hpp"
#include "gravity/MeshPotentialTable.hpp"
#include "gravity/petsc/PetscSession.hpp"

#include <vector>

namespace regolith::coupling {

namespace {

/// The particle-mesh method with the PETSc session it needs (nested: an app that opened one
/// keeps it). Its energy leaves out each grain's mesh self-energy, as P3M's does (measured
/// with the same table, out to P3M's default cut-off of 4 cells for the regular part).
class ParticleMeshMethod final : public GravityMethod {
public:
    explicit ParticleMeshMethod(GravityMethodInput const& in)
        : m_session(m_argc, m_argv)
        , m_comm(in.comm.duplicate())
        , m_grid(in.comm, in.forest, in.config.cellsPerBlock, gridGravityOptions(in.config))
        , m_self(in.comm, m_grid, 4.0 * m_grid.layout().spacing().minCoeff()) {}

    double evaluate(gravity::PointMasses const& grains, gravity::FieldOut out) override {
        m_position.resize(grains.size());
        for (std::size_t k = 0; k < grains.size(); ++k)
            m_position[k] = core::Vec3(grains.x[k], grains.y[k], grains.z[k]);
        gravity::Grains const g{m_position, grains.r, grains.m};
        m_grid.update(g);
        m_acceleration.resize(grains.size());
        m_grid.accelerations(g, m_acceleration);
        for (std::size_t k = 0; k < grains.size(); ++k) {
            out.ax[k] = m_acceleration[k].x();
            out.ay[k] = m_acceleration[k].y();
            out.az[k] = m_acceleration[k].z();
        }
        double self = 0.0;
        for (std::size_t k = 0; k < grains.size(); ++k)
            self += 0.5 * grains.m[k] * grains.m[k] *
                    (grains.r.empty() ? m_self.selfPotential(m_position[k])
                                      : m_self.selfPotential(m_position[k], grains.r[k]));
        return m_grid.potentialEnergy(g) - m_comm.allReduce(self, core::ReduceOp::Sum);
    }

    [[nodiscard]] std::optional<gravity::GridFieldsView> gridFields() const override {
        return m_grid.fields();
    }
    void resetInitialGuess() override { m_grid.resetInitialGuess(); }

private:
    int m_argc = 0;
    char** m_argv = nullptr;
    gravity::PetscSession m_session;
    core::Comm m_comm;
    gravity::GridGravity m_grid;
    gravity::MeshPotentialTable m_self;
    std::vector<core::Vec3> m_position, m_acceleration;
};

class P3mMethod final : public GravityMethod {
public:
    explicit P3mMethod(GravityMethodInput const& in)
        : m_p3m(in.comm, in.forest, in.config) {}
    double evaluate(gravity::PointMasses const& grains, gravity::FieldOut out) override {
        return m_p3m.evaluate(grains, out);
    }
    /// The mesh part (the grains deposited as points).
    [[nodiscard]] std::optional<gravity::GridFieldsView> gridFields() const override {
        return m_p3m.grid().fields();
    }
    void resetInitialGuess() override { m_p3m.resetInitialGuess(); }

private:
    P3mGravity m_p3m;
};

} // namespace

GravityMethodEntry particleMeshMethod() {
    GravityMethodEntry e;
    e.name = "pm";
    e.usesGrid = true;
    e.periodic = true;
    e.make = makeGravityMethod<ParticleMeshMethod>;
    return e;
}

GravityMethodEntry p3mMethod() {
    GravityMethodEntry e;
    e.name = "p3m";
    e.usesGrid = true;
    e.periodic = true;
    e.softens = true; // its near pairs
    e.make = makeGravityMethod<P3mMethod>;
    return e;
}

} // namespace regolith::coupling
