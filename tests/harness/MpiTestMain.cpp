// GoogleTest main for every Regolith test executable: initialises MPI (and PETSc where the
// executable links the gravity module), runs the tests on every rank, and makes every rank
// exit with the same code: a test that failed on any rank fails everywhere. Rank 0 prints
// gtest's report and then one line per rank that failed, with its failed tests.
#include "core/mpi/Comm.hpp"
#include "tests/harness/TestEnvironment.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <sstream>
#include <string>

namespace {

/// Records the failed assertions of this rank so rank 0 can report them.
class FailureRecorder : public testing::EmptyTestEventListener {
public:
    // gtest holds its lock while calling OnTestPartResult, so the test name is recorded here
    // rather than asked for there (current_test_info() would deadlock).
    void OnTestStart(testing::TestInfo const& info) override {
        m_current = std::string(info.test_suite_name()) + "." + info.name();
    }
    void OnTestEnd(testing::TestInfo const& /*info*/) override { m_current = "(global)"; }
    void OnTestPartResult(testing::TestPartResult const& r) override {
        if (!r.failed())
            return;
        m_report << "  " << m_current << " at " << (r.file_name() ? r.file_name() : "?") << ":"
                 << r.line_number() << "\n    " << r.summary() << "\n";
    }
    [[nodiscard]] std::string report() const { return m_report.str(); }

private:
    std::ostringstream m_report;
    std::string m_current = "(global)";
};

} // namespace

int main(int argc, char** argv) {
    regolith::core::MpiEnvironment mpi(argc, argv);
    testing::InitGoogleTest(&argc, argv);
    int result = 1;
    {
        regolith::testing::ExtraEnvironment extra(argc, argv);
        regolith::core::Comm world;

        auto& listeners = testing::UnitTest::GetInstance()->listeners();
        auto* recorder = new FailureRecorder; // owned by gtest
        listeners.Append(recorder);
        if (world.rank() != 0)
            delete listeners.Release(listeners.default_result_printer());

        int const local = RUN_ALL_TESTS();
        int const failedRanks = world.allReduce(local != 0 ? 1 : 0, regolith::core::ReduceOp::Sum);
        auto const reports = world.gatherStrings(recorder->report(), 0);
        if (world.rank() == 0 && failedRanks > 0) {
            std::printf("\n[ MPI ] %d of %d ranks failed:\n", failedRanks, world.size());
            for (std::size_t r = 0; r < reports.size(); ++r)
                if (!reports[r].empty())
                    std::printf("[ rank %zu ]\n%s", r, reports[r].c_str());
            std::fflush(stdout);
        }
        result = failedRanks == 0 ? 0 : 1;
    }
    return result;
}
