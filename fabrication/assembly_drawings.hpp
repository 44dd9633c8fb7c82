#pragma once
// Assembly drawings (cut/assembly.pdf, issue 38): what a crew needs on site, on ISO pages
// (fabrication.paper_size, A3 by default), each with a title band and a scale bar:
//  - the assembly order: patches one after another over the patch graph, each next patch sharing
//    a side with one already standing (Section 3.6: multi-patch grids are deployed and combined
//    sequentially), and within a patch the u lamellas laid first, the v lamellas on top, bolted;
//  - per patch: the planar grid as it is laid out and bolted on the ground, every lamella and
//    connection labelled, notch (slide) directions drawn as arrows; the deployed patch in an
//    axonometric view with the same labels;
//  - the support plan (plan view, every support with its id and site coordinates, a table);
//  - the joins between patches: which lamella of which patch meets which, at which connections.
// Page text is real PDF text (pdftotext reads every id).
#include "fabrication/fabricate.hpp"

#include <string>
#include <vector>

namespace egg::fabrication {

// Patch order: the patch with the most supports first, then breadth first over shared sides
// (ties: the lower id). `reasons` gets one line per patch.
std::vector<int> assemblyOrder(const std::vector<AssemblyPatch>& patches,
                               const std::vector<Support>& supports,
                               const std::vector<SharedBoundary>& shared,
                               std::vector<std::string>* reasons = nullptr);

// The PDF. Throws WriteError when cairo fails.
std::string assemblyPdf(const FabricationResult& result);

}  // namespace egg::fabrication
