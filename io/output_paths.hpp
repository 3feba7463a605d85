// Checks on where a command writes, made before it runs anything (a long run must not end in a
// refused write) and again by the atomic writers: an output never replaces anything but a
// regular file (a device such as /dev/null, a directory, a pipe), never one of the command's
// inputs, and a name taken from an input (a scene's name as `<out-dir>/<name>.h5`) is a plain
// file name that stays inside its directory. Violations are input errors (exit 2) naming the
// option or field, its value and what is allowed.
#pragma once
#include <string>
#include <vector>

namespace lsi {

// `option PATH`: PATH may be new, or an existing regular file (or a link to one) that is none of
// `inputs` (compared as files: another spelling of the same file counts). Throws InputError.
void check_output_file(const std::string& option, const std::string& path,
                       const std::vector<std::string>& inputs = {});

// `option DIR`: DIR may be new or an existing directory. Throws InputError.
void check_output_directory(const std::string& option, const std::string& dir);

// A name used as a file name inside a directory (`<dir>/<name><suffix>`): not empty, at most 200
// bytes, no '/' or '\', no NUL or other control character, not "." or "..". `what` names it in the
// message (e.g. "scenes/a.json: name"). Throws InputError.
void check_file_name(const std::string& what, const std::string& name);

// The same test without throwing (for the writers' last check): "" when `path` may be replaced
// by a regular file, else why not.
std::string unsafe_output_reason(const std::string& path);

}  // namespace lsi
