#pragma once
// The local search's construction and candidate lists (local.cpp): the nearest-neighbour
// tour and, per visit, the cheapest moves into and out of it.
#include <vector>

#include "stitchsim/planner/sequence/solver.h"
#include "tour.h"

namespace stitchsim::planner::detail {

/// Course's precedence group (0 without groups).
inline int GroupOf(const SequenceProblem& p, int course) {
  return p.group.empty() ? 0 : p.group[course];
}

/// From p.start, repeatedly the cheapest move to an unvisited visit (each course forwards,
/// and backwards when bidirectional; with groups, only courses of the earliest group not yet
/// finished); ties by course, then forwards first.
std::vector<Visit> NearestNeighbourTour(const SequenceProblem& p);

/// For every visit node (2 course + reversed), the k nodes of other courses of the same or a
/// neighbouring group with the cheapest move into it (in) and out of it (out), ties by node;
/// forward nodes only if unidirectional.
struct Candidate {
  int node = 0;       ///< the other visit's node
  double cost = 0.0;  ///< the move between them (into or out of the list's node)
};
struct NodeLists {
  std::vector<std::vector<Candidate>> in, out;
};
/// The lists, O(n^2) moves priced through `tour` (its table when there is one).
NodeLists BuildNodeLists(const Tour& tour, const SequenceProblem& p, int k);

/// The greedy construction (one set, no groups): the moves of the lists, cheapest first
/// (ties by node), each kept if it joins the end of one chain of courses to the start of
/// another, each course laid one way (bidirectional: a chain may be turned round, every course
/// flipped, to make the join); then, from p.start, repeatedly the chain whose first visit (or,
/// bidirectional, whose turned first visit) is the cheapest move away, laid whole.
std::vector<Visit> GreedyTour(const SequenceProblem& p, const NodeLists& lists);

}  // namespace stitchsim::planner::detail
