#pragma once
/// One block's contact pass -- detection and evaluation in one loop over its Verlet list --
/// instantiated for one contact model type behind a small interface: the time step makes one
/// virtual call per block (BlockContactLoop::evaluate), the loop inside calls the model directly
/// per contact, or in batches where the model has a batch kernel (BatchKernel).
#include "core/math/AABB.hpp"
#include "particles/detection/Contact.hpp"
#include "particles/detection/ContactDetector.hpp"
#include "particles/detection/PeriodicFrame.hpp"
#include "particles/kernels/ContactEvaluation.hpp"
#include "particles/kernels/ContactState.hpp"
#include "particles/kernels/ForceRecord.hpp"
#include "particles/kernels/SpringDashpotBatch.hpp"
#include "particles/storage/ParticleStorage.hpp"
#include "particles/storage/WallList.hpp"

#include <cstdint>
#include <memory>
#include <type_traits>
#include <vector>

namespace regolith::particles {

/// A contact model with a batch kernel: BatchKernel<M> names its reusable workspace and the
/// pair callback that evaluates the pairs the Verlet loop finds a batch at a time (the
/// spring-dashpot's: SpringDashpotBatch.hpp). A model of one's own gets one by specialising
/// BatchKernel beside it.
template <class M>
concept BatchedContactModel = ContactModel<M> && requires {
    typename BatchKernel<M>::Workspace;
};
/// One whose batch kernel also names a workspace for the wall contacts, `Walls`, with
/// `evaluate(ps, walls, list, model, dt, stamp, sink)` as evaluateWallsWith (the others'
/// wall contacts are evaluated one by one).
template <class M>
concept BatchedWallModel = BatchedContactModel<M> && requires {
    typename BatchKernel<M>::Walls;
};

/// The batch kernel's lanes of a batched model, made on first use and reused from block to
/// block and step to step; nothing for the others.
template <class M, bool = BatchedContactModel<M>, bool = BatchedWallModel<M>>
struct BatchLanes {
    std::unique_ptr<typename BatchKernel<M>::Workspace> lanes;
    std::unique_ptr<typename BatchKernel<M>::Walls> walls;
};
template <class M>
struct BatchLanes<M, true, false> {
    std::unique_ptr<typename BatchKernel<M>::Workspace> lanes;
};
template <class M>
struct BatchLanes<M, false, false> {};

/// What one block's pass works on.
struct BlockPass {
    ParticleStorage& particles;
    ContactDetector& detector;
    WallList& walls;
    core::AABB const& region; ///< the block's box: the contacts it owns
    PeriodicFrame const& frame;
    ContactList& contacts; ///< out: the contacts evaluated (pairs only with keepPairs)
    double dt;
    std::uint32_t stamp;
    bool keepPairs;
    /// Reproducible mode: one ForceRecord per participant, summed later in partner-uid order;
    /// nullptr: forces and torques added in place.
    std::vector<ForceRecord>* records;
};

/// The contact pass of one model type over a block (see the file comment).
class BlockContactLoop {
public:
    virtual ~BlockContactLoop() = default;
    /// Detects and evaluates the contacts of `pass` (pairs the block owns, its masters' wall
    /// contacts) and hands every participant's share to the records or the storage's forces.
    /// Not collective.
    virtual void evaluate(BlockPass const& pass) = 0;
};

/// BlockContactLoop for model type M; the model must outlive the loop.
template <ContactModel M>
class BlockContactLoopOf final : public BlockContactLoop {
public:
    explicit BlockContactLoopOf(M const& model)
        : m_model(model) {}

    void evaluate(BlockPass const& pass) override {
        if (pass.records != nullptr) {
            std::vector<ForceRecord>& out = *pass.records;
            run(pass,
                [&out](std::size_t k, Uid partner, core::Vec3 const& f, core::Vec3 const& tq) {
                    out.push_back(ForceRecord{k, partner, f, tq});
                });
            return;
        }
        // The arrays' addresses, not the storage's: stable while the block is evaluated, and
        // not reloaded after every store.
        ParticleStorage& ps = pass.particles;
        core::Vec3* const force = ps.empty() ? nullptr : &ps.force(0);
        core::Vec3* const torque = ps.empty() ? nullptr : &ps.torque(0);
        run(pass, [force, torque](std::size_t k, Uid, core::Vec3 const& f, core::Vec3 const& tq) {
            force[k] += f;
            torque[k] += tq;
        });
    }

private:
    // Detection and evaluation in one loop over the Verlet list: each contact is evaluated as
    // soon as the loop finds it (in batches with a batch kernel), its history slot hint kept
    // beside the pair. Same contacts, same order, same arithmetic as detecting first: same bits.
    template <class Sink>
    void run(BlockPass const& p, Sink&& sink) {
        ParticleStorage& ps = p.particles;
        if constexpr (BatchedContactModel<M>) {
            auto& lanes = m_batch.lanes;
            if (!lanes)
                lanes = std::make_unique<typename BatchKernel<M>::Workspace>();
            typename BatchKernel<M>::template Pairs<std::remove_reference_t<Sink>> pairs(
                ps, m_model, p.dt, p.stamp, *lanes, sink);
            p.detector.detect(ps, p.walls, p.region, p.frame, p.contacts, pairs, p.keepPairs);
            pairs.finish();
            if constexpr (BatchedWallModel<M>) {
                if (!p.contacts.walls.empty()) {
                    auto& walls = m_batch.walls;
                    if (!walls)
                        walls = std::make_unique<typename BatchKernel<M>::Walls>();
                    walls->evaluate(ps, p.walls, p.contacts.walls, m_model, p.dt, p.stamp, sink);
                }
            } else {
                evaluateWallsWith(ps, p.walls, p.contacts.walls, m_model, p.dt, p.stamp, sink);
            }
        } else {
            auto onePair = [&](Contact const& c, std::uint8_t& hint) {
                evaluatePair(ps, c, m_model, p.dt, p.stamp, hint, sink);
            };
            p.detector.detect(ps, p.walls, p.region, p.frame, p.contacts, onePair, p.keepPairs);
            evaluateWallsWith(ps, p.walls, p.contacts.walls, m_model, p.dt, p.stamp, sink);
        }
    }

    M const& m_model;
    [[no_unique_address]] BatchLanes<M> m_batch;
};

} // namespace regolith::particles
