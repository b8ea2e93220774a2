#include "core/timing/TimerTree.hpp"

#include "core/Error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <limits>
#include <span>

namespace regolith::core {

namespace {

constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();

void checkName(std::string_view name) {
    if (name.empty() || name.find_first_of("/\n") != std::string_view::npos)
        throw Error(fmt::format("TimerTree: invalid phase name '{}' (empty, or contains '/' or "
                                "a newline)",
                                name));
}

std::vector<std::string_view> split(std::string_view s, char sep) {
    std::vector<std::string_view> out;
    if (s.empty())
        return out;
    std::size_t begin = 0;
    for (;;) {
        std::size_t const end = s.find(sep, begin);
        out.push_back(s.substr(begin, end == std::string_view::npos ? end : end - begin));
        if (end == std::string_view::npos)
            return out;
        begin = end + 1;
    }
}

std::string join(std::vector<std::string> const& parts, char sep) {
    std::string out;
    for (std::size_t i = 0; i < parts.size(); ++i) {
        if (i > 0)
            out += sep;
        out += parts[i];
    }
    return out;
}

} // namespace

// ---- Scope -------------------------------------------------------------------------------

TimerTree::Scope::~Scope() {
    // Cannot be out of order: scopes neither move nor outlive their block, and a stop() out of
    // order throws instead of closing.
    if (m_open)
        m_tree->close(m_node, m_start);
}

void TimerTree::Scope::stop() {
    if (!m_open)
        return;
    if (m_tree->m_open.empty() || m_tree->m_open.back() != m_node)
        throw Error(fmt::format("TimerTree: stop() of '{}' while an inner scope is open",
                                m_tree->pathOf(m_node)));
    m_open = false;
    m_tree->close(m_node, m_start);
}

// ---- TimerTree ---------------------------------------------------------------------------

TimerTree::TimerTree()
    : TimerTree([] {
        return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
            .count();
    }) {}

TimerTree::TimerTree(Clock clock)
    : m_clock(std::move(clock))
    , m_nodes(1) {}

TimerTree::Scope TimerTree::scope(std::string_view name) {
    checkName(name);
    std::size_t const parent = m_open.empty() ? kRoot : m_open.back();
    std::size_t const node = child(parent, name);
    m_open.push_back(node);
    return Scope(*this, node, m_clock());
}

void TimerTree::close(std::size_t node, double start) {
    double const elapsed = m_clock() - start;
    m_nodes[node].seconds += std::max(elapsed, 0.0);
    m_nodes[node].calls += 1;
    m_open.pop_back();
}

void TimerTree::addTime(std::string_view path, double seconds, std::uint64_t calls) {
    if (!(seconds >= 0.0))
        throw Error(
            fmt::format("TimerTree::addTime: negative or NaN duration {} for '{}'", seconds, path));
    std::size_t const node = findOrCreate(path);
    m_nodes[node].seconds += seconds;
    m_nodes[node].calls += calls;
}

std::size_t TimerTree::child(std::size_t parent, std::string_view name) {
    for (std::size_t const c : m_nodes[parent].children)
        if (m_nodes[c].name == name)
            return c;
    std::size_t const index = m_nodes.size();
    m_nodes.push_back(Node{std::string(name), parent, {}, 0.0, 0});
    m_nodes[parent].children.push_back(index);
    return index;
}

std::size_t TimerTree::findOrCreate(std::string_view path) {
    auto const parts = split(path, '/');
    if (parts.empty())
        throw Error("TimerTree: empty path");
    std::size_t node = kRoot;
    for (auto const part : parts) {
        checkName(part);
        node = child(node, part);
    }
    return node;
}

std::size_t TimerTree::find(std::string_view path) const {
    std::size_t node = kRoot;
    for (auto const part : split(path, '/')) {
        auto const& kids = m_nodes[node].children;
        auto const it = std::find_if(kids.begin(), kids.end(),
                                     [&](std::size_t c) { return m_nodes[c].name == part; });
        if (it == kids.end())
            return kNone;
        node = *it;
    }
    return node == kRoot ? kNone : node;
}

double TimerTree::seconds(std::string_view path) const {
    std::size_t const n = find(path);
    return n == kNone ? 0.0 : m_nodes[n].seconds;
}

std::uint64_t TimerTree::calls(std::string_view path) const {
    std::size_t const n = find(path);
    return n == kNone ? 0 : m_nodes[n].calls;
}

bool TimerTree::contains(std::string_view path) const {
    return find(path) != kNone;
}

std::string TimerTree::pathOf(std::size_t node) const {
    std::string path;
    while (node != kRoot) {
        path = path.empty() ? m_nodes[node].name : m_nodes[node].name + "/" + path;
        node = m_nodes[node].parent;
    }
    return path;
}

void TimerTree::preorder(std::size_t node, std::vector<std::size_t>& out) const {
    if (node != kRoot)
        out.push_back(node);
    for (std::size_t const c : m_nodes[node].children)
        preorder(c, out);
}

std::vector<std::string> TimerTree::paths() const {
    std::vector<std::size_t> order;
    preorder(kRoot, order);
    std::vector<std::string> out;
    out.reserve(order.size());
    for (std::size_t const n : order)
        out.push_back(pathOf(n));
    return out;
}

std::string TimerTree::currentPath() const {
    return m_open.empty() ? std::string() : pathOf(m_open.back());
}

void TimerTree::reset() {
    if (!m_open.empty())
        throw Error(fmt::format("TimerTree::reset while scope '{}' is open", currentPath()));
    m_nodes.assign(1, Node{});
}

TimerReport TimerTree::reduce(Comm const& comm) const {
    // 1. The union of all ranks' paths, merged on rank 0 in tree order and broadcast.
    auto const gathered = comm.gatherStrings(join(paths(), '\n'), 0);
    std::string unionPaths;
    if (comm.rank() == 0) {
        TimerTree merged([] { return 0.0; });
        for (auto const& rankPaths : gathered)
            for (auto const p : split(rankPaths, '\n'))
                merged.findOrCreate(p);
        unionPaths = join(merged.paths(), '\n');
    }
    comm.broadcast(unionPaths, 0);
    auto const all = split(unionPaths, '\n');

    // 2. This rank's values on the union (0 where it lacks a phase), reduced element-wise.
    std::size_t const n = all.size();
    std::vector<double> tMin(n), tMax(n), tSum(n);
    std::vector<std::uint64_t> cMin(n), cMax(n), cSum(n);
    for (std::size_t i = 0; i < n; ++i) {
        std::size_t const node = find(all[i]);
        tMin[i] = tMax[i] = tSum[i] = node == kNone ? 0.0 : m_nodes[node].seconds;
        cMin[i] = cMax[i] = cSum[i] = node == kNone ? 0 : m_nodes[node].calls;
    }
    comm.allReduceInPlace(std::span<double>(tMin), ReduceOp::Min);
    comm.allReduceInPlace(std::span<double>(tMax), ReduceOp::Max);
    comm.allReduceInPlace(std::span<double>(tSum), ReduceOp::Sum);
    comm.allReduceInPlace(std::span<std::uint64_t>(cMin), ReduceOp::Min);
    comm.allReduceInPlace(std::span<std::uint64_t>(cMax), ReduceOp::Max);
    comm.allReduceInPlace(std::span<std::uint64_t>(cSum), ReduceOp::Sum);

    std::vector<TimerStats> rows;
    rows.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
        std::string_view const path = all[i];
        std::size_t const slash = path.rfind('/');
        TimerStats s;
        s.path = std::string(path);
        s.name = std::string(slash == std::string_view::npos ? path : path.substr(slash + 1));
        s.depth = static_cast<int>(std::count(path.begin(), path.end(), '/'));
        s.min = tMin[i];
        s.avg = tSum[i] / comm.size();
        s.max = tMax[i];
        s.callsMin = cMin[i];
        s.callsMax = cMax[i];
        s.callsSum = cSum[i];
        rows.push_back(std::move(s));
    }
    return TimerReport(comm.size(), std::move(rows));
}

} // namespace regolith::core
