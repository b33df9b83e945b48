// atomic_file.h -- helpers around write_file_atomic (declared in rtb_offline.h).
#ifndef RTB_OFFLINE_IO_ATOMIC_FILE_H
#define RTB_OFFLINE_IO_ATOMIC_FILE_H

#include <string>

namespace rtb {

// The directory part of a path ("." for a bare name) and the file name.
std::string dir_of(const std::string &path);
std::string base_of(const std::string &path);

// Reads a whole file into memory. Throws InputError("PATH: cannot open: ...").
std::string read_file_bytes(const std::string &path);

// Test hook: make the next write_file_atomic fail at the given stage as if
// the system call had failed (EIO). 0 = off (default), 1 = after creating the
// temporary file, 2 = during write, 3 = at fsync, 4 = at rename. Not
// thread-safe; for tests only.
void set_atomic_write_fault_for_testing(int stage);

}  // namespace rtb

#endif
