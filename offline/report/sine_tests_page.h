// sine_tests_page.h -- `rtb report` page for the friction damper's sine
// characterization tests in the frequency domain (issue #13): measured
// dynamic stiffness |K*| and loss angle of every sine record, next to
//  * the RT model identified from time records (the friction-damper study's
//    three fit records, same preprocessing), and
//  * the RT model identified from the measured 36 lb table itself
//    (`rtb identify --dynstiff`), the route a user with a data sheet takes.
#ifndef RTB_OFFLINE_REPORT_SINE_TESTS_PAGE_H
#define RTB_OFFLINE_REPORT_SINE_TESTS_PAGE_H

#include <string>

namespace rtb {

// Writes out_dir/friction_damper_sine.md and its PNGs (byte-reproducible)
// and out_dir/friction_damper_sine_timings.md. Throws InputError on missing data.
void write_sine_tests_page(const std::string &data_dir, const std::string &out_dir, bool quiet);

}  // namespace rtb

#endif
