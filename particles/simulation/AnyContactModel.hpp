#pragma once
/// Any contact model, held by value behind one small interface: what the time step and the
/// time-step guard need of it (its per-block contact loop, its interaction range, its contact
/// time), so that a new model is a type of its own -- no list of the models anywhere. The
/// scene chooses one by name through the registry (ContactModelRegistry.hpp).
#include "particles/integration/TimeStepGuard.hpp"
#include "particles/kernels/ContactState.hpp"
#include "particles/simulation/BlockContactLoop.hpp"
#include "particles/storage/ParticleStorage.hpp"

#include <concepts>
#include <memory>
#include <type_traits>
#include <utility>

namespace regolith::particles {

/// A model whose force acts beyond touching (cohesion): `interactionRange()` is the largest
/// surface gap at which two grains still interact [length]. Detection, the Verlet lists and
/// the synchronisation's shadows reach that much farther than the radii; the model sees such
/// pairs with a negative ContactState::penetration (minus the gap).
template <class M>
concept ActsBeyondContact = requires(M const& m) {
    { m.interactionRange() } -> std::convertible_to<double>;
};

/// A contact model (ContactModel) of any type, copied in; copies share it.
///
/// What it asks of the type besides the ContactModel concept, each optional:
/// - `interactionRange()` (ActsBeyondContact): 0 without;
/// - a batch kernel (BatchKernel, BlockContactLoop.hpp): per contact without;
/// - the contact time for the dt guard, a free function found by argument-dependent lookup:
///   `estimateContactTime(ps, model)`, or `estimateContactTime(ps, model, impactVelocity)` for a
///   model whose contact time depends on the impact speed (TimeStepGuard.hpp); unguarded
///   without.
class AnyContactModel {
public:
    template <ContactModel M>
    requires(!std::same_as<std::remove_cvref_t<M>, AnyContactModel>)
        AnyContactModel(M model) // NOLINT(google-explicit-constructor): any model converts
        : m_self(std::make_shared<Held<M> const>(std::move(model))) {}

    [[nodiscard]] bool hasRollingSpring() const { return m_self->hasRollingSpring(); }
    /// The largest surface gap at which the model acts (0: only while grains overlap) [length].
    [[nodiscard]] double interactionRange() const { return m_self->interactionRange(); }
    /// Whether the contact loop evaluates its pairs in batches (BatchedContactModel).
    [[nodiscard]] bool batched() const { return m_self->batched(); }
    /// The shortest contact time among the movable grains of `ps` (estimateContactTime), at
    /// relative impact speed `impactVelocity` for a model that needs one; an infinite estimate
    /// (unguarded) for a model without one, or that needs an impact speed when
    /// `impactVelocity` is 0. Not collective.
    [[nodiscard]] ContactTimeEstimate contactTime(ParticleStorage const& ps,
                                                  double impactVelocity) const {
        return m_self->contactTime(ps, impactVelocity);
    }
    /// The per-block contact loop of this model; it refers to the model, which this object
    /// (or a copy of it) must keep alive.
    [[nodiscard]] std::unique_ptr<BlockContactLoop> blockLoop() const {
        return m_self->blockLoop();
    }
    /// The model if it is an M, else nullptr.
    template <class M>
    [[nodiscard]] M const* get() const {
        auto const* held = dynamic_cast<Held<M> const*>(m_self.get());
        return held != nullptr ? &held->model : nullptr;
    }

private:
    struct Interface {
        virtual ~Interface() = default;
        [[nodiscard]] virtual bool hasRollingSpring() const = 0;
        [[nodiscard]] virtual double interactionRange() const = 0;
        [[nodiscard]] virtual bool batched() const = 0;
        [[nodiscard]] virtual ContactTimeEstimate contactTime(ParticleStorage const& ps,
                                                              double impactVelocity) const = 0;
        [[nodiscard]] virtual std::unique_ptr<BlockContactLoop> blockLoop() const = 0;
    };

    template <class M>
    struct Held final : Interface {
        explicit Held(M m)
            : model(std::move(m)) {}
        [[nodiscard]] bool hasRollingSpring() const override { return model.hasRollingSpring(); }
        [[nodiscard]] double interactionRange() const override {
            if constexpr (ActsBeyondContact<M>)
                return model.interactionRange();
            else
                return 0.0;
        }
        [[nodiscard]] bool batched() const override { return BatchedContactModel<M>; }
        [[nodiscard]] ContactTimeEstimate contactTime(ParticleStorage const& ps,
                                                      double impactVelocity) const override {
            if constexpr (requires { estimateContactTime(ps, model, impactVelocity); }) {
                if (impactVelocity > 0.0)
                    return estimateContactTime(ps, model, impactVelocity);
                return {};
            } else if constexpr (requires { estimateContactTime(ps, model); }) {
                return estimateContactTime(ps, model);
            } else {
                return {};
            }
        }
        [[nodiscard]] std::unique_ptr<BlockContactLoop> blockLoop() const override {
            return std::make_unique<BlockContactLoopOf<M>>(model);
        }
        M model;
    };

    std::shared_ptr<Interface const> m_self;
};

} // namespace regolith::particles
