// Tracing a layout along the members' tracks (see chain_tracing.hpp).
#include "propagation/chain_tracing.hpp"

#include "core/egg/member_trace.hpp"
#include "core/egg/patch_maps.hpp"
#include "core/errors.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <map>
#include <tuple>

namespace egg::propagation {
namespace {

using Clock = std::chrono::steady_clock;
int familyIndex(Family f) { return f == Family::U ? 0 : 1; }
const std::vector<GridMember>& familyMembers(const EggGrid& grid, Family f) {
  return f == Family::U ? grid.u : grid.v;
}

// One member of one patch's family that a joint names.
struct Instance {
  int patch = -1;
  Family family = Family::U;
  int member = -1;
  bool boundary = false;  // a patch side: fixed at x = 0 or 1, not traced
  double x1 = 0.0, x2 = 0.0;
  struct Link {
    int other = -1;  // instance
    bool otherAtEnd = false;
    double offset = 0.0, scale = 1.0;  // x_this = offset + scale * x_other
  };
  std::vector<Link> atStart, atEnd;
};

// A run: instances linked end to start (the next one's x1 is the previous one's traced x2).
struct Run {
  std::vector<int> members;
  std::vector<Instance::Link> steps;  // steps[k]: member k+1's x1 from member k's x2
  bool freeStart = false;             // the first start lies on no joint: it may move
  std::optional<double>
      fixedTarget;   // x2 the last member must reach (a fixed boundary member there)
  int headOn = -1;   // the run whose last end this one's last end meets
  int waitFor = -1;  // matches that run's traced end
};

double linkValue(const Instance::Link& link, double otherValue) {
  return link.offset + link.scale * otherValue;
}
Instance::Link reversedLink(int other, bool otherAtEnd, const MemberJoint& j, bool thisIsA) {
  // x_b = offset + scale x_a; seen from a: x_a = (x_b - offset) / scale.
  if (thisIsA) return {other, otherAtEnd, -j.offset / j.scale, 1.0 / j.scale};
  return {other, otherAtEnd, j.offset, j.scale};
}

using PatchStarts =
    std::vector<std::array<std::vector<double>, 2>>;  // per patch and family: the members' x1

bool usable(const std::vector<const PatchDesign*>& designs, int p) {
  return designs[p] && designs[p]->feasible;
}

// Instances of the members the joints name.
std::vector<Instance> instancesOf(const std::vector<const PatchDesign*>& designs,
                                  const LayoutPropagation& propagation, const PatchStarts& x1) {
  std::vector<Instance> inst;
  std::map<std::tuple<int, int, int>, int> instanceOf;
  const auto instance = [&](const MemberEnd& e) {
    const auto key = std::tuple{e.patch, familyIndex(e.family), e.member};
    if (auto it = instanceOf.find(key); it != instanceOf.end()) return it->second;
    const auto& given = x1[e.patch][familyIndex(e.family)];
    Instance i;
    i.patch = e.patch, i.family = e.family, i.member = e.member;
    i.boundary = e.member == 0 || e.member + 1 == static_cast<int>(given.size());
    i.x1 = i.x2 = given[e.member];
    inst.push_back(i);
    return instanceOf[key] = static_cast<int>(inst.size()) - 1;
  };
  for (const auto& j : propagation.joints) {
    if (!usable(designs, j.a.patch) || !usable(designs, j.b.patch)) continue;
    if (x1[j.a.patch][familyIndex(j.a.family)].empty() ||
        x1[j.b.patch][familyIndex(j.b.family)].empty())
      continue;
    const int a = instance(j.a), b = instance(j.b);
    (j.a.atEnd ? inst[a].atEnd : inst[a].atStart).push_back(reversedLink(b, j.b.atEnd, j, true));
    (j.b.atEnd ? inst[b].atEnd : inst[b].atStart).push_back(reversedLink(a, j.a.atEnd, j, false));
  }
  return inst;
}

// Runs: from every inner instance whose start continues no inner member's end.
std::vector<Run> runsOf(const std::vector<Instance>& inst, std::vector<int>& runOfLast) {
  const auto nextOf = [&](int i) -> const Instance::Link* {
    for (const auto& l : inst[i].atEnd)
      if (!inst[l.other].boundary && !l.otherAtEnd) return &l;
    return nullptr;
  };
  const auto hasPrevious = [&](int i) {
    return std::any_of(inst[i].atStart.begin(), inst[i].atStart.end(),
                       [&](const auto& l) { return !inst[l.other].boundary && l.otherAtEnd; });
  };
  std::vector<Run> runs;
  runOfLast.assign(inst.size(), -1);
  std::vector<char> inRun(inst.size(), 0);
  for (size_t i = 0; i < inst.size(); ++i) {
    if (inst[i].boundary || hasPrevious(static_cast<int>(i))) continue;
    Run run;
    run.freeStart = inst[i].atStart.empty();
    for (int m = static_cast<int>(i); m >= 0 && !inRun[m];) {
      inRun[m] = 1;
      run.members.push_back(m);
      const Instance::Link* next = nextOf(m);
      if (!next) break;
      // The next member's x1 from this one's x2: next->other's link back to m.
      for (const auto& l : inst[next->other].atStart)
        if (l.other == m) run.steps.push_back(l);
      m = next->other;
    }
    const int last = run.members.back();
    for (const auto& l : inst[last].atEnd)
      if (inst[l.other].boundary) run.fixedTarget = linkValue(l, inst[l.other].x1);
    runOfLast[last] = static_cast<int>(runs.size());
    runs.push_back(std::move(run));
  }
  return runs;
}

// Head-on pairs: the run whose start may move matches the other's traced end.
void pairHeadOnRuns(std::vector<Run>& runs, const std::vector<Instance>& inst,
                    const std::vector<int>& runOfLast) {
  for (size_t r = 0; r < runs.size(); ++r) {
    if (runs[r].fixedTarget) continue;
    for (const auto& l : inst[runs[r].members.back()].atEnd)
      if (!inst[l.other].boundary && l.otherAtEnd && runOfLast[l.other] >= 0)
        runs[r].headOn = runOfLast[l.other];
  }
  for (size_t r = 0; r < runs.size(); ++r) {
    Run& run = runs[r];
    if (run.headOn < 0 || run.waitFor >= 0 || runs[run.headOn].waitFor == static_cast<int>(r))
      continue;
    Run& other = runs[run.headOn];
    // Both free: the later one moves. Neither: both are held.
    if (run.freeStart && (!other.freeStart || static_cast<int>(r) > run.headOn))
      run.waitFor = run.headOn;
    else if (other.freeStart)
      other.waitFor = static_cast<int>(r);
  }
}

// Tracing the runs along their tracks: the instances' x1 and x2 as traced, which runs met their
// fixed end and which were held.
struct RunTracer {
  const std::vector<const PatchDesign*>& designs;
  std::vector<Instance>& inst;
  std::vector<Run>& runs;
  std::atomic<int> traces{0};
  std::vector<char> matched, held;

  RunTracer(const std::vector<const PatchDesign*>& designs_, std::vector<Instance>& inst_,
            std::vector<Run>& runs_)
      : designs(designs_),
        inst(inst_),
        runs(runs_),
        matched(runs_.size(), 0),
        held(runs_.size(), 0) {}

  // One member traced alone, exactly as buildGrid traces it (same guess, same options).
  void traceOne(Instance& m) {
    const PatchDesign& design = *designs[m.patch];
    GridMember g;
    g.family = m.family;
    g.index = m.member;
    g.x1 = m.x1;
    g.x2 = membersAt(design, m.family, {0.0, m.x1, 1.0}).x2[1];
    std::atomic<int> propagations{0};
    traceInnerMember(design.patch, *design.solver, design.alphaBar.quad, g, design.options.grid,
                     propagations);
    ++traces;
    m.x2 = g.x2;
  }
  double traceRun(Run& run, double start) {
    inst[run.members.front()].x1 = start;
    for (size_t k = 0; k < run.members.size(); ++k) {
      traceOne(inst[run.members[k]]);
      if (k + 1 < run.members.size())
        inst[run.members[k + 1]].x1 = linkValue(run.steps[k], inst[run.members[k]].x2);
    }
    return inst[run.members.back()].x2;
  }
  // The end parameter's rate of change with the start: the cladding slopes and joint scales.
  double runSlope(const Run& run) const {
    double slope = 1.0;
    for (size_t k = 0; k < run.members.size(); ++k) {
      const Instance& m = inst[run.members[k]];
      slope *= claddingSlope(*designs[m.patch], m.family, m.x1);
      if (k + 1 < run.members.size()) slope *= run.steps[k].scale;
    }
    return slope;
  }
  void solveRun(size_t r) {
    Run& run = runs[r];
    const double s0 = inst[run.members.front()].x1;
    try {
      double end = traceRun(run, s0);
      std::optional<double> target = run.fixedTarget;
      if (run.waitFor >= 0) {
        const Instance& e = inst[runs[run.waitFor].members.back()];
        for (const auto& l : inst[run.members.back()].atEnd)
          if (l.other == runs[run.waitFor].members.back()) target = linkValue(l, e.x2);
      }
      if (!target) return;
      const Instance& last = inst[run.members.back()];
      const double length =
          designs[last.patch]->patch.sideLengths[familySide(last.family, true).first];
      const double tolerance = 1e-10;  // metres along the end side
      double f = end - *target;
      if (!run.freeStart) {
        held[r] = std::abs(f) * length > tolerance;
        return;
      }
      // Secant on the start, from a first step along the cladding functions' slope.
      double sPrev = s0, fPrev = f;
      double s = std::clamp(s0 - f / runSlope(run), 1e-9, 1.0 - 1e-9);
      for (int it = 0; it < 12 && std::abs(f) * length > tolerance; ++it) {
        f = traceRun(run, s) - *target;
        if (std::abs(f) * length <= tolerance || f == fPrev) break;
        const double next = s - f * (s - sPrev) / (f - fPrev);
        sPrev = s, fPrev = f;
        s = std::clamp(next, 1e-9, 1.0 - 1e-9);
      }
      (std::abs(f) * length <= tolerance ? matched : held)[r] = 1;
    } catch (const Error&) {
      traceRun(run, s0);  // back to the propagated start; may throw again (caught below)
    }
  }
  // Rounds: runs that wait for another's end go after it. Returns the number of rounds.
  int solveInRounds() {
    int rounds = 0;
    std::vector<char> done(runs.size(), 0);
    size_t remaining = runs.size();
    while (remaining > 0) {
      std::vector<size_t> ready;
      for (size_t r = 0; r < runs.size(); ++r)
        if (!done[r] && (runs[r].waitFor < 0 || done[runs[r].waitFor])) ready.push_back(r);
      tbb::parallel_for(size_t(0), ready.size(), [&](size_t i) {
        try {
          solveRun(ready[i]);
        } catch (const Error&) {
          // Left at the propagated starts; the patch's own trace reports the failure.
        }
      });
      for (size_t r : ready) done[r] = 1;
      remaining -= ready.size();
      ++rounds;
    }
    return rounds;
  }
};

// One patch's grid, from the starts the tracks settled (`given`: per family, empty = placed by
// the design's member options).
void tracePatch(const PatchDesign& design, const std::array<std::vector<double>, 2>& given,
                TracedPatch& traced) {
  try {
    auto t = Clock::now();
    const auto members = [&](Family f) {
      const auto& x1 = given[familyIndex(f)];
      return x1.empty() ? placeDesignMembers(design, f, design.options.members)
                        : membersAt(design, f, x1);
    };
    traced.u = members(Family::U);
    traced.v = members(Family::V);
    traced.membersSeconds = std::chrono::duration<double>(Clock::now() - t).count();
    t = Clock::now();
    traced.grid = traceDesignGrid(design, *traced.u, *traced.v, design.options.grid);
    traced.tracingSeconds = std::chrono::duration<double>(Clock::now() - t).count();
  } catch (const InfeasiblePatch& e) {
    traced.failure = std::string("infeasible: ") + e.what();
  } catch (const SolverFailure& e) {
    traced.failure = std::string("solver failure: ") + e.what();
  } catch (const InvalidInput& e) {
    traced.failure = std::string("invalid members: ") + e.what();
  }
}

// The traced end of a member, or null when its patch has no grid or no such member.
const Eigen::Vector3d* endPoint(const std::vector<TracedPatch>& patches, const MemberEnd& e) {
  const auto& grid = patches[e.patch].grid;
  if (!grid) return nullptr;
  const auto& members = familyMembers(*grid, e.family);
  if (e.member < 0 || e.member >= static_cast<int>(members.size())) return nullptr;
  return e.atEnd ? &members[e.member].spatial.back() : &members[e.member].spatial.front();
}

// The gap between the traced member ends of the two patches on one piece.
SideGap gapOf(const SharedPiece& piece, const LayoutPropagation& propagation,
              const std::vector<TracedPatch>& patches) {
  SideGap gap;
  gap.boundary = piece.boundary;
  gap.patchA = piece.patchA, gap.patchB = piece.patchB;
  gap.piece = piece.kind;
  gap.membersA = piece.membersA, gap.membersB = piece.membersB;
  if (!patches[piece.patchA].grid || !patches[piece.patchB].grid) {
    gap.kind = GapKind::NotTraced;
  } else if (piece.kind == PieceKind::RingCut) {
    gap.kind = GapKind::RingCut;
    // Members need not close round a ring (3.7.1): the chain's member j on both sides of the cut.
    const PropagatedChain& chain = propagation.chains[piece.chain];
    const int n = static_cast<int>(chain.nodes.size()),
              m = static_cast<int>(chain.solution.start.size());
    for (int j = 1; j + 1 < m; ++j) {
      const PropagatedNode &last = chain.nodes[n - 1], &first = chain.nodes[0];
      const Eigen::Vector3d* a =
          endPoint(patches, {last.patch, last.family, chain.memberIndex(n - 1, j), last.forward});
      const Eigen::Vector3d* b =
          endPoint(patches, {first.patch, first.family, chain.memberIndex(0, j), !first.forward});
      if (a && b) gap.maxGapM = std::max(gap.maxGapM, (*a - *b).norm());
    }
  } else if (piece.membersA != piece.membersB) {
    gap.kind = GapKind::CountMismatch;
  } else {
    bool closed = false, bothStart = false, headOn = false;
    for (int j : piece.joints) {
      const MemberJoint& joint = propagation.joints[j];
      const Eigen::Vector3d *a = endPoint(patches, joint.a), *b = endPoint(patches, joint.b);
      if (a && b) gap.maxGapM = std::max(gap.maxGapM, (*a - *b).norm());
      closed = closed || joint.a.atEnd != joint.b.atEnd;
      bothStart = bothStart || (!joint.a.atEnd && !joint.b.atEnd);
      headOn = headOn || (joint.a.atEnd && joint.b.atEnd);
    }
    gap.kind = headOn ? GapKind::HeadOn : bothStart ? GapKind::BothStart : GapKind::Closed;
  }
  return gap;
}

}  // namespace

const char* toString(GapKind kind) {
  switch (kind) {
    case GapKind::Closed: return "closed";
    case GapKind::BothStart: return "both start";
    case GapKind::HeadOn: return "head-on";
    case GapKind::RingCut: return "ring cut";
    case GapKind::CountMismatch: return "count mismatch";
    case GapKind::NotTraced: return "not traced";
  }
  return "unknown";
}

LayoutTracing traceLayout(const std::vector<const PatchDesign*>& designs,
                          const LayoutPropagation& propagation) {
  const auto started = Clock::now();
  const size_t count = designs.size();
  if (propagation.x1.size() != count)
    throw InvalidInput("traceLayout: the propagation covers another number of patches");
  LayoutTracing out;
  out.patches.resize(count);
  PatchStarts x1 = propagation.x1;

  std::vector<Instance> inst = instancesOf(designs, propagation, x1);
  std::vector<int> runOfLast;
  std::vector<Run> runs = runsOf(inst, runOfLast);
  pairHeadOnRuns(runs, inst, runOfLast);

  RunTracer tracer(designs, inst, runs);
  out.rounds += tracer.solveInRounds();
  for (size_t r = 0; r < runs.size(); ++r) {
    // Head-on with neither start free: both held.
    const bool stuck = runs[r].headOn >= 0 && runs[r].waitFor < 0 &&
                       runs[runs[r].headOn].waitFor != static_cast<int>(r);
    out.matchedRuns += tracer.matched[r], out.heldRuns += tracer.held[r] || stuck;
  }
  out.memberTraces = tracer.traces;
  for (const auto& m : inst)
    if (!m.boundary) x1[m.patch][familyIndex(m.family)][m.member] = m.x1;

  // Every patch's grid, from the starts the tracks settled.
  tbb::parallel_for(size_t(0), count, [&](size_t p) {
    TracedPatch& traced = out.patches[p];
    if (!usable(designs, static_cast<int>(p))) {
      traced.failure = designs[p] ? designs[p]->failure.message : "not designed";
      return;
    }
    tracePatch(*designs[p], x1[p], traced);
  });
  ++out.rounds;

  // C0 on every piece, measured on the traced member ends.
  for (const auto& piece : propagation.pieces) {
    SideGap gap = gapOf(piece, propagation, out.patches);
    if (gap.kind != GapKind::RingCut) out.c0MaxGapM = std::max(out.c0MaxGapM, gap.maxGapM);
    out.gaps.push_back(gap);
  }
  out.seconds = std::chrono::duration<double>(Clock::now() - started).count();
  return out;
}

}  // namespace egg::propagation
