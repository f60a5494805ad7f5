// feint/io/file_identity.hpp - "is this output one of my inputs?", by filesystem identity.
//
// Input files are sacred: no command writes over one of its inputs. Two names denote the same file
// when they resolve to the same device and inode, so a symbolic link, a hard link, `./x` and an
// absolute path are all caught; a name that does not exist yet is compared by its canonical path.
#pragma once

#include <string>
#include <vector>

namespace feint::io {

/// True when `a` and `b` name the same file (same device and inode, or, when one does not exist
/// yet, the same canonical path). `-` (standard input/output) is never the same as anything.
bool same_file(const std::string& a, const std::string& b);

/// Throws UsageError (exit 64) naming the first output that is also an input:
/// "the output 'x.csv' is also an input ('x.csv'): feint never overwrites its inputs".
/// Empty names and `-` are ignored.
void refuse_overwriting_inputs(const std::vector<std::string>& inputs,
                               const std::vector<std::string>& outputs);

}  // namespace feint::io
