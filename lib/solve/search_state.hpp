#pragma once
// A search's state and result as plain data: what a checkpoint stores (solve/checkpoint.hpp),
// what one process hands another (solve/share.hpp), and what a finished search returns.
#include "interval/box.hpp"
#include "prune/sequence.hpp"
#include "solve/result.hpp"

#include <string>
#include <vector>

namespace linkbox::solve {

// A search's whole state between two boxes.
struct SearchState {
  struct Node {  // a box and its place in the search tree: '0' = lower half, '1' = upper half
    Box box;
    std::string path;
    prune::Sequence::Backoff backoff;  // inherited from the parent (see Sequence)
  };
  struct Found {
    std::string path;
    Box box;
    bool certified = false;
  };
  // One box as the search committed it, for another search to replay: a lent subtree's boxes
  // come back to the lender as these (solve/lending.hpp).
  struct Record {
    std::string path;
    char outcome = 'e';  // 'e' empty, 's' solution, 'c' certified solution, 'x' split
    double work = 0, volume = 0;
    Stats stats;
    Box box;       // a solution's box; a split's box before bisection
    int dim = -1;  // split: the side bisected (the halves follow, as one process makes them)
    prune::Sequence::Backoff backoff;  // split: the box's, its halves take its child()
  };
  std::vector<Node> pending;  // in list order (the back is taken first depth-first)
  std::vector<Found> solutions;
  std::vector<Record> records;  // when recording (Search::record_boxes), in commit order
  Stats stats;
  double work = 0;
  double volume_done = 0;
};

struct Result {
  std::vector<Box> solutions;
  std::vector<char> certified;  // per solution: the certifier proved exactly one root in it
  Stats stats;
  bool complete = true;  // false when a limit stopped the search: unexplored boxes remain
  std::vector<Box> pending;  // the unexplored boxes when incomplete
  double volume_left = 0;    // their share of the start box's volume (split dimensions)
};

}  // namespace linkbox::solve
