#include "io/detail/AgreeOnError.hpp"

#include "core/Error.hpp"

#include <string>

namespace regolith::io::detail {

void agreeOnError(core::Comm const& comm, std::function<void()> const& action) {
    std::string message;
    bool failed = false;
    try {
        action();
    } catch (core::InputError const& e) {
        failed = true;
        message = e.what();
    }
    int const firstFailing =
        comm.allReduce(failed ? comm.rank() : comm.size(), core::ReduceOp::Min);
    if (firstFailing == comm.size())
        return;
    comm.broadcast(message, firstFailing);
    throw core::InputError(message.empty() ? std::string("unknown input error") : message);
}

} // namespace regolith::io::detail
