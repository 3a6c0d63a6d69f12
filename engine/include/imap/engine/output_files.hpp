// Checks made before any work, so that a run never fails at its end: output
// files and folders can be written, input images agree in size, the frame
// fits the parameters. Errors are engine::Error (exit 2) naming the flag.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "imap/golden/params.hpp"

namespace imap::engine {

// Checks, before the work, that `path` (given with `flag`) can be written
// later: its folder exists, files can be created in it (permissions,
// read-only file system), and it is not a folder; with `image`, OpenCV can
// write its extension. Error (exit 2) otherwise; nothing when empty.
void check_output_file(const std::string& flag, const std::string& path, bool image);

// The same for an output folder (`--out-dir`): it is a folder or can be
// created in an existing folder (the rule of every output flag: it creates
// the one thing it names, a file or this folder, in a folder that exists),
// and files can be created in it.
void check_output_dir(const std::string& flag, const std::string& dir);
// Creates an output folder (and its missing parents); Error naming `flag`
// if it is a file or cannot be created.
void create_output_dir(const std::string& flag, const std::string& dir);

// Two output flags naming one file would overwrite each other: Error naming
// both; (flag, path) pairs, empty paths ignored.
void check_distinct_outputs(const std::vector<std::pair<std::string, std::string>>& outs);

// A stereo pair's two images must have one size: Error naming both files
// and their sizes otherwise.
void check_same_size(const std::string& left, int lw, int lh, const std::string& right, int rw,
                     int rh);

// golden::validate with its ParamError as an Error (exit 2).
void validate_frame(const golden::Params& p, const golden::Roi& roi, int w, int h);

// The extension of `path` in lower case, with its dot (".avi"); "" if none.
std::string lower_extension(const std::string& path);

// The folder a file named `path` goes to: its parent, or "." for a bare
// file name ("n1.avi"), so that it can be made absolute or compared.
std::string folder_of(const std::string& path);
// True when the file `path` lies directly in folder `dir` (both taken
// relative to the current folder; "n1.json" is in ".", "out/x" in "out/").
bool file_in_folder(const std::string& path, const std::string& dir);

}  // namespace imap::engine
