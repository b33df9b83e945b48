// identify_table.h -- `rtb identify --dynstiff TABLE`: the five parameters
// (and, with --free, extensions) from a dynamic-stiffness table
// (freq/table_fit.h), with the same JSON and C header as a fit to records.
#ifndef RTB_OFFLINE_CLI_IDENTIFY_TABLE_H
#define RTB_OFFLINE_CLI_IDENTIFY_TABLE_H

#include "cli/cli.h"

namespace rtb {
namespace cli {

int identify_from_table(const Args &a);

}  // namespace cli
}  // namespace rtb

#endif
