// The thread governor: how many threads a machine whose other processes keep cores busy allows.
#define BOOST_TEST_MODULE common_thread_governor
#include <boost/test/unit_test.hpp>

#include "ddafrac/common/thread_governor.hpp"

using ddafrac::common::busy_cores_of_others;
using ddafrac::common::CpuTimes;
using ddafrac::common::threads_for;

BOOST_AUTO_TEST_CASE(an_idle_machine_gets_every_thread_asked_for) {
  BOOST_TEST(threads_for(0.0, 2, 2, 2) == 2);
  BOOST_TEST(threads_for(0.0, 8, 4, 1) == 4);  // never more than asked for
  BOOST_TEST(threads_for(0.0, 2, 1, 1) == 1);
}

BOOST_AUTO_TEST_CASE(one_busy_process_on_two_cores_leaves_one_thread) {
  BOOST_TEST(threads_for(1.0, 2, 2, 2) == 1);
  // Two threads of ours beside one busy process share 2 cores 2:1; the other holds ~0.67.
  BOOST_TEST(threads_for(2.0 / 3.0, 2, 2, 2) == 1);
  BOOST_TEST(threads_for(3.0, 4, 4, 4) == 1);
  BOOST_TEST(threads_for(2.0, 8, 8, 8) == 6);
}

BOOST_AUTO_TEST_CASE(a_fully_busy_machine_still_runs_one_thread) { BOOST_TEST(threads_for(2.0, 2, 2, 2) == 1); }

BOOST_AUTO_TEST_CASE(noise_below_the_hysteresis_does_not_flip_the_count) {
  // 0.2 busy cores of others (a shell, the hypervisor): still 2 threads.
  BOOST_TEST(threads_for(0.2, 2, 2, 2) == 2);
  // Back up from 1 only once the other core is clearly free.
  BOOST_TEST(threads_for(0.5, 2, 2, 1) == 1);
  BOOST_TEST(threads_for(0.1, 2, 2, 1) == 2);
}

BOOST_AUTO_TEST_CASE(busy_cores_of_others_subtract_this_process) {
  // 2 CPUs over 100 ticks each (200 in all): 150 busy ticks of which 100 are ours -> 0.5 cores.
  const CpuTimes before{1000.0, 5000.0, 300.0};
  const CpuTimes after{1150.0, 5200.0, 400.0};
  BOOST_TEST(busy_cores_of_others(before, after, 2) == 0.5, boost::test_tools::tolerance(1e-12));
  // No time passed: nothing measured.
  BOOST_TEST(busy_cores_of_others(before, before, 2) == 0.0);
  // Clock-tick rounding can make ours exceed the machine's: never below 0.
  BOOST_TEST(busy_cores_of_others(before, CpuTimes{1100.0, 5200.0, 420.0}, 2) == 0.0);
}

BOOST_AUTO_TEST_CASE(this_machine_counters_are_readable) {
  const auto t = ddafrac::common::read_cpu_times();
  BOOST_REQUIRE(t.has_value());
  BOOST_TEST(t->machine_total > t->machine_busy);
  BOOST_TEST(t->own >= 0.0);
}
