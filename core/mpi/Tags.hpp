#pragma once
/// Every MPI tag Regolith uses, in one place. Subsystems also duplicate their communicator,
/// so a tag only has to be unique within one subsystem's traffic.
namespace regolith::core {

enum class Tag : int {
    ExchangeSizes = 101,     ///< NeighbourExchange: byte counts per peer
    ExchangeData = 102,      ///< NeighbourExchange: payload
    ExchangePeerCheck = 103, ///< NeighbourExchange: peer-list census (empty messages)
    SparseExchange = 201,    ///< SparseExchange (NBX): payload, receivers do not know senders
    SparseExchangeAlt = 202, ///< SparseExchange: payload of odd-numbered calls (see there)
    DirectGravityRing = 301, ///< gravity::DirectSum: blocks of grains passed round the ring
    TestTraffic = 901,       ///< tests only
};

constexpr int toInt(Tag t) {
    return static_cast<int>(t);
}

} // namespace regolith::core
