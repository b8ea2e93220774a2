#include "gravity/update/GrainRecordExchange.hpp"

#include "gravity/common/UidHash.hpp"

#include <vector>

namespace regolith::gravity {

namespace {

/// A record on the wire (trivially copyable, unlike std::pair: packed as bytes).
struct UidRecord {
    std::uint64_t uid;
    GrainRecord record;
};

} // namespace

int directoryRank(std::uint64_t uid, int ranks) {
    return static_cast<int>(uidHash(uid + 0x9E3779B97F4A7C15ULL) %
                            static_cast<std::uint64_t>(ranks));
}

std::size_t fetchMigratedRecords(core::SparseExchange& exchange, int ranks,
                                 std::unordered_map<std::uint64_t, UpdatePolicy::Entry>& records,
                                 std::span<std::uint64_t const> missing, std::uint64_t call) {
    // Round 1 to the directories: per message the records given away, then the requests.
    std::vector<std::vector<UidRecord>> offers(static_cast<std::size_t>(ranks));
    std::vector<std::vector<std::uint64_t>> requests(static_cast<std::size_t>(ranks));
    for (auto it = records.begin(); it != records.end();) {
        if (it->second.seen != call) {
            offers[static_cast<std::size_t>(directoryRank(it->first, ranks))].push_back(
                {it->first, it->second.record});
            it = records.erase(it);
        } else {
            ++it;
        }
    }
    for (std::uint64_t const uid : missing)
        requests[static_cast<std::size_t>(directoryRank(uid, ranks))].push_back(uid);
    for (int r = 0; r < ranks; ++r) {
        auto const k = static_cast<std::size_t>(r);
        if (!offers[k].empty() || !requests[k].empty())
            exchange.sendBuffer(r) << offers[k] << requests[k];
    }
    exchange.start();
    std::unordered_map<std::uint64_t, GrainRecord> held; // this rank as a directory
    std::vector<std::pair<int, std::vector<std::uint64_t>>> asked;
    exchange.wait([&](int from, core::RecvBuffer& in) {
        std::vector<UidRecord> given;
        std::vector<std::uint64_t> wanted;
        in >> given >> wanted;
        for (auto const& [uid, record] : given)
            held.emplace(uid, record);
        if (!wanted.empty())
            asked.emplace_back(from, std::move(wanted));
    });
    // Round 2, the answers: the records the directory holds, in the order asked.
    for (auto const& [from, wanted] : asked) {
        std::vector<UidRecord> answer;
        for (std::uint64_t const uid : wanted)
            if (auto const it = held.find(uid); it != held.end())
                answer.push_back({uid, it->second});
        exchange.sendBuffer(from) << answer;
    }
    exchange.start();
    std::size_t found = 0;
    exchange.wait([&](int /*from*/, core::RecvBuffer& in) {
        std::vector<UidRecord> answer;
        in >> answer;
        for (auto const& [uid, record] : answer) {
            records[uid] = UpdatePolicy::Entry{record, call};
            ++found;
        }
    });
    return found;
}

} // namespace regolith::gravity
