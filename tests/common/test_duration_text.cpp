// Durations as the progress line and `study --status` print them.
#define BOOST_TEST_MODULE common_duration_text
#include <boost/test/unit_test.hpp>

#include <limits>

#include "ddafrac/common/stopwatch.hpp"

using ddafrac::common::duration_text;

BOOST_AUTO_TEST_CASE(seconds_minutes_and_hours_each_in_their_own_form) {
  BOOST_TEST(duration_text(0.0) == "0s");
  BOOST_TEST(duration_text(59.9) == "59s");
  BOOST_TEST(duration_text(60.0) == "1m00s");
  BOOST_TEST(duration_text(425.0) == "7m05s");
  BOOST_TEST(duration_text(3599.0) == "59m59s");
  BOOST_TEST(duration_text(3600.0) == "1h00m");
  BOOST_TEST(duration_text(4740.0) == "1h19m");
}

BOOST_AUTO_TEST_CASE(an_unknown_time_says_so) {
  BOOST_TEST(duration_text(-1.0) == "--");
  BOOST_TEST(duration_text(std::numeric_limits<double>::quiet_NaN()) == "--");
  BOOST_TEST(duration_text(std::numeric_limits<double>::infinity()) == "--");
  BOOST_TEST(duration_text(2e7) == "--");  // a run that has barely started
}
