// gravity.self = "direct": the exact pairwise sum over all ranks (gravity/direct).
#include "coupling/gravity/GravityMethod.hpp"
#include "gravity/direct/DirectSum.hpp"

namespace regolith::coupling {

namespace {

class DirectSumMethod final : public GravityMethod {
public:
    explicit DirectSumMethod(GravityMethodInput const& in)
        : m_sum(in.comm, gravity::direct::DirectOptions{in.config.G, in.config.softening,
                                                        in.config.reproducible}) {}
    double evaluate(gravity::PointMasses const& grains, gravity::FieldOut out) override {
        return m_sum.evaluate(grains, out);
    }

private:
    gravity::direct::DirectSum m_sum;
};

} // namespace

GravityMethodEntry directSumMethod() {
    GravityMethodEntry e;
    e.name = "direct";
    e.softens = true;
    e.make = makeGravityMethod<DirectSumMethod>;
    return e;
}

} // namespace regolith::coupling
