// The order patches are assembled in (assembly_drawings.hpp): Section 3.6 deploys and combines
// multi-patch grids one after another.
#include "fabrication/assembly_drawings.hpp"

#include <fmt/format.h>

#include <deque>
#include <map>
#include <set>

namespace egg::fabrication {

std::vector<int> assemblyOrder(const std::vector<AssemblyPatch>& patches,
                               const std::vector<Support>& supports,
                               const std::vector<SharedBoundary>& shared,
                               std::vector<std::string>* reasons) {
  std::map<int, int> supportCount;
  for (const auto& s : supports) ++supportCount[s.patchId];
  std::map<int, std::set<int>> neighbours;
  for (const auto& s : shared) {
    neighbours[s.patchA].insert(s.patchB);
    neighbours[s.patchB].insert(s.patchA);
  }
  std::vector<int> order;
  std::set<int> placed;
  // A generalised patch bolts to the boundary lamellas of the patches round it: after all others.
  std::vector<const AssemblyPatch*> later;
  for (const auto& p : patches)
    if (!p.boltedTo.empty()) placed.insert(p.patchId), later.push_back(&p);
  while (order.size() + later.size() < patches.size()) {
    // A new start (the first, or a part of the structure not joined to what stands): the patch
    // with the most supports, ties the lower id.
    int start = -1;
    for (const auto& p : patches) {
      if (placed.count(p.patchId)) continue;
      if (start < 0 || supportCount[p.patchId] > supportCount[start]) start = p.patchId;
    }
    std::deque<int> queue{start};
    placed.insert(start);
    if (reasons) {
      reasons->push_back("P" + std::to_string(start) + " first: it stands on the most supports (" +
                         std::to_string(supportCount[start]) +
                         ") and needs no other patch to hold it");
    }
    while (!queue.empty()) {
      const int p = queue.front();
      queue.pop_front();
      order.push_back(p);
      for (int q : neighbours[p]) {
        if (placed.count(q)) continue;
        placed.insert(q);
        queue.push_back(q);
        if (reasons) {
          reasons->push_back(
              fmt::format("P{} after P{}: it shares a side with P{}, whose lamella "
                          "on that side is already standing to bolt to",
                          q, p, p));
        }
      }
    }
  }
  for (const AssemblyPatch* p : later) {
    order.push_back(p->patchId);
    if (!reasons) continue;
    std::string to;
    for (int q : p->boltedTo) to += (to.empty() ? "P" : ", P") + std::to_string(q);
    reasons->push_back(fmt::format(
        "P{} after {}: its member ends bolt to their boundary lamellas, which stand already",
        p->patchId, to));
  }
  return order;
}

}  // namespace egg::fabrication
