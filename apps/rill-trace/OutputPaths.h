// The files a command will write, checked before it renders: each option's format against the
// extension of the name given (never a PNG behind a .jpg name), no two outputs that are one
// file by any spelling, and no output that is one of the command's inputs (the scene file, a
// mesh, an MTL file or a texture the scene loaded, the render to resume).
#pragma once

#include <string>
#include <vector>

namespace trace_cli {

// A file the command line names, and the option (or what it is, for an input) that names it.
struct NamedFile {
  std::string what;  // "--out", "the scene file", ...
  std::string path;
};

// Throws rt::SceneError when the extension of `path` names another format than the one
// `option` writes (--out x.jpg), with the formats each option writes. An extension no format
// is known by (or none: /dev/null, a FIFO) is taken as the user's choice.
void check_output_format(const std::string& option, const std::string& path);

// Which file a name is, to compare names however they are spelled (relative or absolute,
// "..", a symbolic link, a hard link): its device and inode where it exists, else its path
// with the links followed and made absolute. Empty for a character device (/dev/null,
// /dev/stdout on a terminal), which any number of outputs may name without clobbering it.
std::string file_identity(const std::string& path);

// Throws rt::SceneError naming both when two outputs are one file, or when an output is one
// of the inputs.
void check_output_files(const std::vector<NamedFile>& outputs,
                        const std::vector<NamedFile>& inputs);

}  // namespace trace_cli
