#pragma once
// One PDF of several drawings, a page per drawing at true size (1 mm = 72/25.4 pt), through cairo:
// for checking the sheets on screen or on paper before cutting.
#include "fabrication/drawing.hpp"

#include <string>
#include <vector>

namespace egg::fabrication {

// The PDF bytes. Throws WriteError when cairo fails.
std::string toPdf(const std::vector<Drawing>& pages);

}  // namespace egg::fabrication
