#pragma once
// The bracket update of regula falsi with the Illinois modification, shared by the root finders
// of the planar angle (alpha_bar.cpp, Problem 2.3's constraint boundaries) and of the member
// end points (member_trace.cpp, Section 2.4.4). Each caller keeps its own step safeguard and
// stopping rule (they differ for good reasons: a jump of the cladding curve versus a smooth
// length mismatch); what they share is how the bracket shrinks.
//
// Plain regula falsi can keep one end for ever when the function is convex on the bracket; the
// Illinois rule halves the stored value at an end that has been kept twice in a row, which makes
// the convergence superlinear while the root stays bracketed.
namespace egg {

struct IllinoisBracket {
  double a = 0.0, b = 0.0;    // the bracket (either order)
  double ga = 0.0, gb = 0.0;  // the function at a and b (opposite signs)
  int kept = 0;               // -1: a was kept by the last update, +1: b was kept, 0: neither yet

  // Where the secant through (a, ga) and (b, gb) crosses zero (undefined when ga == gb).
  double falsePosition() const { return b - gb * (b - a) / (gb - ga); }

  // Replaces the end on the same side of the root as x: b if `sameSideAsB`, else a.
  void replace(double x, double g, bool sameSideAsB) {
    if (sameSideAsB) {
      b = x, gb = g;
      if (kept == -1) ga *= 0.5;
      kept = -1;
    } else {
      a = x, ga = g;
      if (kept == 1) gb *= 0.5;
      kept = 1;
    }
  }
};

}  // namespace egg
