#pragma once
// A linear pre-scan of JSON text before it is parsed into a document: bounded nesting
// (a document 70,000 levels deep crashed the recursive code that walked it), numbers that fit a
// double (nlohmann refuses 1e400 with an out_of_range error that named no field), and where in
// the document the first problem is ("patching.slope_bounds[1]"). It builds nothing, so a huge
// input costs one pass and no memory; nlohmann's callback parser is quadratic on long arrays.
#include <string>

namespace egg {

struct JsonCheck {
  bool ok = true;
  std::string path;     // where the problem is: "a.b[2].c" (empty: at the top)
  std::string problem;  // "nested deeper than 64 levels", "number out of range (1e400)", "not valid
                        // JSON: ..."
};

JsonCheck checkJsonText(const std::string& text, int maxDepth);

}  // namespace egg
