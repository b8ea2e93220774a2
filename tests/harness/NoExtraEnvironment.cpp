#include "tests/harness/TestEnvironment.hpp"

namespace regolith::testing {

ExtraEnvironment::ExtraEnvironment(int& /*argc*/, char**& /*argv*/) {}
ExtraEnvironment::~ExtraEnvironment() = default;

} // namespace regolith::testing
