#pragma once
// The race's choice of its leader (race.hpp), after each round of turns. A candidate's
// projected total work is its work over the share of the search tree it has resolved. The
// lead passes from its holder only to a challenger projected kLeadMargin times cheaper and at
// least as far along the tree as the holder was after the same work; of several, to the one
// furthest ahead. While neither has resolved kMinLeadShare of the tree, it stays: there a
// depth-first search's share is a few of its first, smallest subtrees, and any projection
// from it is noise.
#include <cstddef>
#include <utility>
#include <vector>

namespace linkbox::solve {

// The projection flatters the LP candidate early on (its first LPs remove whole slabs of the
// box) and any candidate while the part of the tree left is the hard part, so a projection's
// noise must not hand the lead back and forth (each change wastes the turns before).
constexpr double kLeadMargin = 2;
constexpr double kMinLeadShare = 0.01;

// A candidate's work so far and the share of the search tree it has resolved.
struct Standing {
  double work = 0;
  double tree = 0;
};
// A candidate's (work, share of the tree) at each choice so far, oldest first.
using Progress = std::vector<std::pair<double, double>>;

double projected(const Standing& s);
// How much further along the tree the challenger is than the holder was after the same work
// (interpolated between the holder's points; < 0: behind).
double ahead_of(const Progress& holder, const Standing& challenger);
bool cheaper(const Standing& holder, const Standing& challenger);
// The candidate that holds the lead after this choice; `held_progress` ends with now.
size_t choose_lead(size_t held, const std::vector<Standing>& now, const Progress& held_progress);

}  // namespace linkbox::solve
