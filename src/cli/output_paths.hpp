// Output paths of the command line, checked before any long work: a render or
// benchmark that would fail to write its result refuses at once (a usage
// error, exit status 2) instead of after minutes of work.
#pragma once

#include <string>
#include <string_view>

namespace tessera::cli {

// The folders `path` lies in, created where missing (-o into a new folder works).
// Throws UsageError "PATH: cannot create the folder ...".
void create_parent_folders(const std::string& path, std::string_view what);

// Throws UsageError "PATH: cannot write WHAT: REASON" unless a file can be
// written at `path`: it is not a folder, its folder exists and takes a new file
// (outputs are written to a temporary name there and renamed) and, with
// `append`, an existing file is writable.
void check_writable_file(const std::string& path, std::string_view what, bool append = false);

// Only the first test of check_writable_file: `path` is not a folder.
void check_not_folder(const std::string& path, std::string_view what);

// Creates `folder` where missing and checks that it takes a new file.
void check_writable_folder(const std::string& folder, std::string_view what);

}  // namespace tessera::cli
