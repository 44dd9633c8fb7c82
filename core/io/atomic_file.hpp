#pragma once
// Every file eggshell writes goes through here: the text is written to a temporary file in the
// target's folder and renamed into place, so a crash, a full disk or a reader racing the writer
// never sees a half-written file (DEVELOPERS.md: nothing lost or half-written).
#include <filesystem>
#include <string>

namespace egg {

// Writes `text` to `path` atomically. Throws IoError naming the path.
void writeFileAtomically(const std::filesystem::path& path, const std::string& text);

// A random suffix for temporary names (8 characters of [0-9a-z]).
std::string temporarySuffix();

}  // namespace egg
